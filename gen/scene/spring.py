"""[[spring]] tables: linear springs between two points of the model, or
between a point and a fixed point in space (runtime/assembly/spring.c).  The
energy of a spring is k/2 (l - l0)^2, l the distance between its ends: it
pulls when longer than its rest length l0 and pushes when shorter.

Keys: a (a point: 'beam:start', 'beam:end', 'beam:<arc length in m>', or a
body's name: its centre of mass); b (another such point, or a fixed point
[x, y, z] in m); stiffness (N/m); rest_length (m; default the distance of the
ends in the reference configuration); name (a label for the outputs)."""
import math

from gen.scene.interactions import Interaction
from gen.scene.mesh import locate, parse_point
from gen.scene.values import check_keys, get_array_of_tables, get_name, get_number, get_vec3

KEYS = ("name", "a", "b", "stiffness", "rest_length")
DOC = (
    (("name",), "", "spring[i]", "a label (the outputs' `spring` column)"),
    (("a",), "", "required", "one end: a beam point (`beam:start`, `beam:end`, `beam:<arc length in m>`) or a body's "
                             "name (its centre of mass)"),
    (("b",), "", "required", "the other end: a point as `.a`, or a fixed point `[x, y, z]` in m"),
    (("stiffness",), "N/m", "required", "k of the energy k/2 (l − l0)², l the distance between the ends (> 0)"),
    (("rest_length",), "m", "the ends' distance in the reference", "l0 (≥ 0; 0: a zero-length spring, "
                                                                     "force k × the ends' separation)"),
)


def _point(ctx, spec, key, scene):
    """(element, xi, reference position) of a point given as a string."""
    if isinstance(spec, str) and spec in scene.bodies:
        b = scene.bodies[spec]
        return b["elem"], 0.5, list(b["X"])
    beam, s = parse_point(ctx, spec, key, scene.beams)
    e, xi = locate(beam, s)
    return e, xi, list(beam["geo"].at(s)[0])


def _build(ctx, doc, scene):
    """[(name, ea, xia, eb, xib, fixed point or None, k, l0)] of the [[spring]] tables."""
    out, names = [], set()
    for i, sp in enumerate(get_array_of_tables(ctx, doc, "spring")):
        where = f"spring[{i}]"
        check_keys(ctx, sp, set(KEYS), where)
        name = get_name(ctx, sp, "name", where) if "name" in sp else f"spring{i}"
        if name in names:
            ctx.fail(f"{where}.name", f"duplicate spring name {name!r}")
        names.add(name)
        for k in ("a", "b", "stiffness"):
            if k not in sp:
                ctx.fail(f"{where}.{k}", "missing" + ("; expected a point like 'arm:end'" if k != "stiffness"
                                                      else "; expected the stiffness in N/m"))
        ea, xia, pa = _point(ctx, sp["a"], f"{where}.a", scene)
        if isinstance(sp["b"], str):
            eb, xib, pb = _point(ctx, sp["b"], f"{where}.b", scene)
            fixed = None
        else:
            pb = get_vec3(ctx, sp, "b", where)
            eb, xib, fixed = -1, 0.0, pb
        k = get_number(ctx, sp, "stiffness", where, positive=True)
        l0 = get_number(ctx, sp, "rest_length", where, default=math.dist(pa, pb), nonneg=True)
        if fixed is None and ea == eb and xia == xib:
            ctx.fail(f"{where}.b", "the same point as .a: a spring needs two ends")
        out.append((name, ea, xia, eb, xib, fixed, k, l0))
    return out


def _lines(springs, fmt):
    """'springs N', then per spring 'spring NAME EA XIA EB XIB X Y Z K L0' (EB = -1:
    the fixed point X Y Z; else X Y Z are 0)."""
    out = [f"springs {len(springs)}"]
    for name, ea, xia, eb, xib, fixed, k, l0 in springs:
        x = fixed or [0.0, 0.0, 0.0]
        out.append(f"spring {name} {ea} {fmt(xia)} {eb} {fmt(xib)} " + " ".join(fmt(v) for v in x) +
                   f" {fmt(k)} {fmt(l0)}")
    return out


INTERACTION = Interaction(table="spring", keys=KEYS, record="spring", build=_build, lines=_lines, holds=True,
                          order=50, doc=DOC, title="linear springs between points, or to a fixed point")
