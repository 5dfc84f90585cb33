"""[[body_contact]] tables: a rigid body's primitive resting on a fixed one
(issue 34: a body on a table): the body's sphere, capsule or box (given where
it is in the reference configuration) against a fixed half-space, sphere,
capsule or box (`against`, an inline table), with the barrier and the lagged
friction of the beams' contact (runtime/assembly/body_contact.c; the model
file's body_contact record; docs/explanation/contact.md, Bodies on primitives).

The body's primitive is resolved by points: a sphere by its centre (its
radius the section radius: exact), a capsule by the centres of its two end
spheres (exact against a half-space), a box by its eight corners (exact
against a half-space; against a curved or a box primitive, contact between
corners, on an edge or a face, is not resolved).

Keys: body (a [[body]]'s name); shape (sphere, capsule, box) with center,
radius / a, b, radius / center, size, axes as in [[contact]]; against =
{shape = ..., ...} (half_space: normal, point; sphere; capsule; box; fixed);
distance (the barrier's reach, m; default 1e-3 of the model length);
stiffness (N/m per point; default 1000 x the body's weight over the reach);
friction or static_friction and kinetic_friction; slip (m; default 1e-7 of
the model length) or, in dynamics, slip_velocity (m/s: slip = slip_velocity x
dynamic.dt)."""
from gen.scene import contact as C
from gen.scene.interactions import Interaction
from gen.scene.values import check_keys, get_array_of_tables, get_number, get_str

BODY_SHAPES = ("sphere", "capsule", "box")
KEYS = ("name", "body", "shape", "center", "radius", "a", "b", "size", "axes", "against", "distance", "stiffness",
        "friction", "static_friction", "kinetic_friction", "slip", "slip_velocity")
AGAINST_KEYS = ("shape", "normal", "point", "center", "radius", "a", "b", "size", "axes")
DOC = (
    (('name',), '', '', 'a label'),
    (('body',), '', 'required',
     'the `[[body]]` whose primitive this is ([docs/explanation/contact.md](docs/explanation/contact.md), Bodies on primitives)'),
    (('shape',), '', 'required',
     '`sphere` (`.center`, `.radius`), `capsule` (`.a`, `.b`, `.radius`) or `box` (`.center`, `.size`, `.axes`): the '
     "body's primitive where it is in the reference configuration; resolved by points: a sphere's centre, a "
     "capsule's two end centres, a box's eight corners"),
    (('center', 'radius', 'a', 'b', 'size', 'axes'), 'm', 'required (axes: the global axes)',
     "the body's primitive, as in `[[contact]]`"),
    (('against',), '', 'required',
     'the fixed primitive it rests on, an inline table `{shape = "half_space", normal = [...], point = [...]}` '
     '(or a `sphere`, `capsule`, `box` with their keys)'),
    (('distance',), 'm', '1e-3 × the model length',
     'reach ŝ of the barrier −(s − ŝ)² ln(s/ŝ)'),
    (('stiffness',), 'N/m', "1000 × the body's weight / reach",
     'barrier stiffness κ of each point (its energy κ b(s))'),
    (('friction',), '', '0',
     'Coulomb coefficient μ'),
    (('static_friction', 'kinetic_friction'), '', '`friction`',
     'μs and μk apart (0 ≤ μk ≤ μs; not with `friction`)'),
    (('slip',), 'm', '1e-7 × the model length',
     'slip tolerance ε: below it a point sticks, beyond it slides with μN'),
    (('slip_velocity',), 'm/s', 'none',
     'dynamics: ε = v_s × `dynamic.dt` instead of `.slip` (as in `[[contact]]`)'),
)


def _points(code, prm):
    """The body primitive's contact points in the reference configuration and
    their radii: a sphere's centre, a capsule's end centres, a box's corners."""
    if code == C.CODE["sphere"]:
        return [(prm[:3], prm[3])]
    if code == C.CODE["capsule"]:
        return [(prm[:3], prm[6]), (prm[3:6], prm[6])]
    c, h, A = prm[:3], prm[3:6], [prm[6:9], prm[9:12], prm[12:15]]
    out = []
    for sx in (-1, 1):
        for sy in (-1, 1):
            for sz in (-1, 1):
                out.append(([c[i] + sx * h[0] * A[0][i] + sy * h[1] * A[1][i] + sz * h[2] * A[2][i]
                             for i in range(3)], 0.0))
    return out


def body_contacts(ctx, doc, bodies, length_scale, analysis="static"):
    """[(body element, X, R0 rows, body code, body prm, against code, against
    prm, reach, stiffness, (mu_s, mu_k), slip)] of the [[body_contact]] tables."""
    out = []
    for i, bt in enumerate(get_array_of_tables(ctx, doc, "body_contact")):
        where = f"body_contact[{i}]"
        check_keys(ctx, bt, set(KEYS), where)
        name = bt.get("body")
        if not isinstance(name, str) or name not in bodies:
            ctx.fail(f"{where}.body", f"expected the name of a [[body]] (bodies: {', '.join(bodies) or 'none'})")
        shape = get_str(ctx, bt, "shape", where, choices=BODY_SHAPES)
        code, prm = C._primitive(ctx, bt, where, shape)
        ag = bt.get("against")
        if not isinstance(ag, dict):
            ctx.fail(f"{where}.against", 'expected an inline table {shape = "half_space", normal = [...], '
                                         'point = [...]} (the fixed primitive the body rests on)')
        aw = f"{where}.against"
        check_keys(ctx, ag, set(AGAINST_KEYS), aw)
        ashape = get_str(ctx, ag, "shape", aw, choices=tuple(C.SHAPES))
        acode, aprm = C._primitive(ctx, ag, aw, ashape)
        mu_s, mu_k = C._friction(ctx, bt, where)
        reach = get_number(ctx, bt, "distance", where, default=1e-3 * length_scale, positive=True)
        slip = C.slip_tolerance(ctx, bt, where, length_scale, analysis, doc)
        b = bodies[name]
        weight = b["mass"] * C.GRAVITY
        kappa = get_number(ctx, bt, "stiffness", where, default=max(1e3 * weight / reach, 1e-12), positive=True)
        for k, (z, r) in enumerate(_points(code, prm)):
            depth = r - C._distance(acode, aprm, z)
            if depth >= 0.0:
                ctx.fail(where, f"body {name!r}'s {shape} (point {k}) starts {depth:.6g} m into the {ashape} "
                                f"(it must start clear of it)")
        out.append((b["elem"], list(b["X"]), [v for row in b["R"] for v in row], code, prm, acode, aprm, reach,
                    kappa, (mu_s, mu_k), slip))
    return out


def _build(ctx, doc, scene):
    data = body_contacts(ctx, doc, scene.bodies or {}, scene.length_scale, scene.analysis)
    return data or None


def _lines(data, fmt):
    """'bcontacts N', then per table 'bc BODY X(3) R0(9) SHAPE prm(15) ASHAPE aprm(15) REACH STIFFNESS MU_S
    MU_K SLIP'."""
    out = [f"bcontacts {len(data)}"]
    for elem, X, R0, code, prm, acode, aprm, reach, kappa, (mu_s, mu_k), slip in data:
        nums = X + R0 + [code] + prm + [0.0] * (15 - len(prm)) + [acode] + aprm + [0.0] * (15 - len(aprm))
        out.append(f"bc {elem} " + " ".join(str(v) if isinstance(v, int) else fmt(v) for v in nums) + " " +
                   " ".join(fmt(v) for v in (reach, kappa, mu_s, mu_k, slip)))
    return out


INTERACTION = Interaction(table="body_contact", keys=KEYS, record="body_contact", build=_build, lines=_lines,
                          holds=True, order=31, doc=DOC,
                          title="a rigid body's primitive resting on a fixed primitive (docs/explanation/contact.md)")
