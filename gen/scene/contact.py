"""[[contact]] tables: rigid primitives the beams may touch (issue 34, first
part): half-spaces, spheres, capsules and boxes, fixed, moved (translated and
turned) by an amplitude, or parts of a rigid body; barrier
contact of the beams' centrelines swept by their sections
(runtime/assembly/contact_force.c; the model file's contact records).

Keys: shape (half_space, sphere, capsule, box); normal and point (half_space: the
solid is where (x - point) . normal < 0); center, radius (sphere); a, b,
radius (capsule); center, size (edge lengths), axes ([x axis, y axis]; box);
turn (a rotation vector, rad, times the amplitude's factor) about pivot
(default the primitive's centre); body (the name of a [[body]] it belongs to); beams (names; default every beam); distance (the barrier's
reach, m; default 1e-3 of the model length); stiffness (the barrier's, N/m per
metre of beam; default 1000 times the heaviest contacting beam's weight per
metre over the reach); samples (points per element, ends included, default
4);
contact_radius (m; default the section's: a circle's radius, a rectangle's
half-height h/2); friction (the Coulomb coefficient mu, default 0; or static_friction and
kinetic_friction apart) and slip (the slip per step below which friction
sticks, m; default 1e-7 of the model length) or, in dynamics, slip_velocity
(m/s: slip = slip_velocity x dynamic.dt); motion (m: a prescribed translation, times the load factor in statics
or the factor of `amplitude`, which dynamics requires)."""
import math

from gen.scene.interactions import Interaction
from gen.scene.values import _dot, _norm, _scale, _sub, check_keys, get_array_of_tables, get_int, get_number, get_str, \
    get_vec3

SHAPES = {"half_space": ("normal", "point"), "sphere": ("center", "radius"), "capsule": ("a", "b", "radius"),
          "box": ("center", "size", "axes")}
KEYS = ("name", "shape", "normal", "point", "center", "radius", "a", "b", "beams", "distance", "stiffness",
        "samples", "contact_radius", "friction", "slip", "motion", "amplitude", "static_friction",
        "kinetic_friction", "size", "axes", "turn", "pivot", "body", "slip_velocity")
# The reference of the keys (docs/reference/interactions.md): (keys, unit, default, meaning).
DOC = (
    (('shape',), '', 'required',
     '`half_space`, `sphere`, `capsule` (a segment swept by a sphere) or `box`: a rigid primitive that the beams may touch ([docs/explanation/contact.md](docs/explanation/contact.md))'),
    (('name',), '', '',
     'a label'),
    (('normal', 'point'), 'm', 'point [0, 0, 0]',
     '`half_space`: its outward normal and a point of its surface (the solid is where (x − point)·normal < 0)'),
    (('center', 'radius'), 'm', 'required',
     '`sphere`: centre and radius; `capsule`: `.radius` of the swept sphere'),
    (('a', 'b'), 'm', 'required',
     '`capsule`: the ends of its segment (distinct)'),
    (('size', 'axes'), 'm,', 'required, the global axes',
     '`box` (with `.center`): its three edge lengths, and the directions of its first two edges `[[x axis], [y axis]]` (the third is their cross product)'),
    (('turn', 'pivot'), 'rad, m', "0, the primitive's centre",
     'a prescribed rotation (rotation vector) of the primitive about `.pivot`, times the load factor or the factor of `.amplitude`, after which `.motion` translates it'),
    (('body',), '', 'none',
     'the name of a `[[body]]` the primitive belongs to (given where it is in the reference configuration; it moves with the body, and its contact forces act on the body; no `.motion` or `.turn`)'),
    (('beams',), '', 'every beam',
     'names of the beams that may touch it'),
    (('distance',), 'm', '1e-3 × the model length',
     'reach ŝ of the barrier −(s − ŝ)² ln(s/ŝ): the distance s between a section and the primitive at which it starts to push'),
    (('stiffness',), 'N/m per m', "1000 × the heaviest beam's weight per metre / reach",
     'barrier stiffness κ (the energy of a stretch of beam of length w is κ w b(s))'),
    (('samples',), '', '4',
     'points per element at which contact is sought (the ends and the points between at equal steps); contact between them is not resolved'),
    (('contact_radius',), 'm', "the section's",
     "the swept section's radius: a circle's radius, a rectangle's half-height h/2 by default"),
    (('friction',), '', '0',
     'Coulomb coefficient μ (one for sticking and sliding)'),
    (('static_friction', 'kinetic_friction'), '', '`friction`',
     'μs and μk apart (0 ≤ μk ≤ μs; not with `friction`): μ passes from μs to μk between a slip of ε and 2ε since the anchor'),
    (('motion',), 'm', '[0, 0, 0]',
     'a prescribed translation of the primitive: times the load factor in statics, or the factor of `.amplitude`'),
    (('amplitude',), '', 'the load factor',
     'the history of `.motion` and `.turn` (required in dynamics when either is given): an `[amplitude.NAME]` or inline table'),
    (('slip',), 'm', '1e-7 × the model length',
     'slip tolerance ε: below it a point sticks (a spring of stiffness 2μN/ε about where it stuck, which stays put while it sticks), beyond it slides with μN'),
    (('slip_velocity',), 'm/s', 'none',
     'dynamics: the slip velocity v_s of the stick–slip transition instead of `.slip`: ε = v_s × `dynamic.dt` (a point slipping slower than v_s over a step of `dynamic.dt` sticks; not with `.slip`)'),
)
CODE = {"half_space": 0, "sphere": 1, "capsule": 2, "box": 3}
GRAVITY = 9.81


def _primitive(ctx, ct, where, shape):
    """(code, prm[7]) of the primitive, checked."""
    for k in sum(SHAPES.values(), ()):
        if k in ct and k not in SHAPES[shape]:
            ctx.fail(f"{where}.{k}", f"not a key of a {shape} (expected {', '.join(SHAPES[shape])})")
    if shape == "half_space":
        n = get_vec3(ctx, ct, "normal", where, nonzero=True)
        n = _scale(n, 1.0 / _norm(n))
        p = get_vec3(ctx, ct, "point", where, default=[0.0, 0.0, 0.0])
        return CODE[shape], n + [_dot(n, p), 0.0, 0.0, 0.0]
    if shape == "sphere":
        c = get_vec3(ctx, ct, "center", where)
        return CODE[shape], c + [get_number(ctx, ct, "radius", where, positive=True), 0.0, 0.0, 0.0]
    if shape == "box":
        c = get_vec3(ctx, ct, "center", where)
        size = get_vec3(ctx, ct, "size", where)
        if not all(s > 0.0 for s in size):
            ctx.fail(f"{where}.size", f"expected three positive edge lengths (got {size!r})")
        return CODE[shape], c + [s / 2.0 for s in size] + sum(_axes(ctx, ct, where), [])
    a, b = get_vec3(ctx, ct, "a", where), get_vec3(ctx, ct, "b", where)
    if not _norm(_sub(b, a)) > 0.0:
        ctx.fail(f"{where}.b", f"expected an end other than a = {a!r} (a capsule of zero length)")
    return CODE[shape], a + b + [get_number(ctx, ct, "radius", where, positive=True)]


def _axes(ctx, ct, where):
    """A box's axes (rows): `axes` = [x axis, y axis] (orthogonalized, the
    third their cross product), default the global axes."""
    if "axes" not in ct:
        return [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    ax = ct["axes"]
    if not (isinstance(ax, list) and len(ax) == 2):
        ctx.fail(f"{where}.axes", "expected two vectors [[x axis], [y axis]] (the box's edges' directions)")
    e1 = get_vec3(ctx, {"x": ax[0]}, "x", f"{where}.axes[0]", nonzero=True)
    e2 = get_vec3(ctx, {"y": ax[1]}, "y", f"{where}.axes[1]", nonzero=True)
    e1 = _scale(e1, 1.0 / _norm(e1))
    e2 = _sub(e2, _scale(e1, _dot(e1, e2)))
    if not _norm(e2) > 1e-9:
        ctx.fail(f"{where}.axes", "expected two axes that are not parallel")
    e2 = _scale(e2, 1.0 / _norm(e2))
    e3 = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
    return [e1, e2, e3]


def _distance(code, prm, x):
    """The primitive's gap at x (as out/kernels/contact.c computes it)."""
    if code == 0:
        return _dot(prm[:3], x) - prm[3]
    if code == 1:
        return _norm(_sub(x, prm[:3])) - prm[3]
    if code == 3:
        c, h, A = prm[:3], prm[3:6], [prm[6:9], prm[9:12], prm[12:15]]
        w = [_dot(A[k], _sub(x, c)) for k in range(3)]
        out = [max(abs(w[k]) - h[k], 0.0) for k in range(3)]
        if any(out):
            return _norm(out)
        return -min(h[k] - abs(w[k]) for k in range(3))
    a, b = prm[:3], prm[3:6]
    e = _sub(b, a)
    t = min(max(_dot(_sub(x, a), e) / _dot(e, e), 0.0), 1.0)
    return _norm(_sub(x, [a[i] + t * e[i] for i in range(3)])) - prm[6]


def slip_tolerance(ctx, ct, where, length_scale, analysis, doc):
    """The slip tolerance eps (m): `slip`, or in dynamics `slip_velocity` times
    the nominal step dynamic.dt (the transition in slip velocity), default
    1e-7 of the model length."""
    if "slip_velocity" not in ct:
        return get_number(ctx, ct, "slip", where, default=1e-7 * length_scale, positive=True)
    if "slip" in ct:
        ctx.fail(f"{where}.slip_velocity", "expected either `slip` (m per step) or `slip_velocity` (m/s), not both")
    if analysis != "dynamic":
        ctx.fail(f"{where}.slip_velocity", f"is for dynamics (the analysis is {analysis!r}: give `slip`, the slip "
                                           f"per load step, m)")
    vs = get_number(ctx, ct, "slip_velocity", where, positive=True)
    dt = (doc.get("dynamic") or {}).get("dt")
    if isinstance(dt, bool) or not isinstance(dt, (int, float)) or not dt > 0.0:
        ctx.fail(f"{where}.slip_velocity", "needs dynamic.dt (a positive time step): eps = slip_velocity x dt")
    return vs * float(dt)


def _friction(ctx, ct, where):
    """(mu_s, mu_k): `friction` gives both; `static_friction` and
    `kinetic_friction` give them apart (mu_k <= mu_s)."""
    both = "friction" in ct
    for k in ("static_friction", "kinetic_friction"):
        if both and k in ct:
            ctx.fail(f"{where}.{k}", "expected either `friction` (one coefficient) or `static_friction` and "
                                     "`kinetic_friction`, not both")
    mu = get_number(ctx, ct, "friction", where, default=0.0, nonneg=True, hi=100.0)
    mu_s = get_number(ctx, ct, "static_friction", where, default=mu, nonneg=True, hi=100.0)
    mu_k = get_number(ctx, ct, "kinetic_friction", where, default=mu_s, nonneg=True, hi=100.0)
    if mu_k > mu_s:
        ctx.fail(f"{where}.kinetic_friction", f"expected at most static_friction = {mu_s!r} (got {mu_k!r})")
    return mu_s, mu_k


def beam_names(ctx, ct, where, beams):
    """The table's `beams` (default every beam), each an existing beam."""
    names = ct.get("beams", list(beams))
    if not isinstance(names, list) or not names or not all(isinstance(n, str) for n in names):
        ctx.fail(f"{where}.beams", "expected a non-empty list of beam names")
    for n in names:
        if n not in beams:
            ctx.fail(f"{where}.beams", f"no beam named {n!r} (beams: {', '.join(beams) or 'none'})")
    return names


def weight_per_length(doc, name, sec):
    """rho A g of beam `name` (its material's density, its section's area)."""
    bt = next(b for b in doc.get("beam", []) if b.get("name") == name)
    rho = float(doc["material"][bt["material"]].get("rho", 0.0))
    area = sec[1] * sec[2] if sec[0] == "rectangle" else math.pi * sec[2] ** 2 / 4.0
    return rho * area * GRAVITY


def _pivot(code, prm):
    """The point a primitive turns about by default: its centre (a capsule's
    middle, a half-space's point nearest the origin)."""
    if code == 0:
        return _scale(prm[:3], prm[3])
    if code == 2:
        return [(prm[i] + prm[3 + i]) / 2.0 for i in range(3)]
    return prm[:3]


def _placement(ctx, ct, where, code, prm, amps, analysis, bodies):
    """(motion, turn, pivot, amplitude, body element, body reference [X, R0 row-major]) of a primitive."""
    motion = get_vec3(ctx, ct, "motion", where, default=[0.0, 0.0, 0.0])
    turn = get_vec3(ctx, ct, "turn", where, default=[0.0, 0.0, 0.0])
    pivot = get_vec3(ctx, ct, "pivot", where, default=_pivot(code, prm))
    amp = amps.ref(ct, "amplitude", where) if amps is not None else -1
    moves = any(motion) or any(turn)
    if "amplitude" in ct and not moves:
        ctx.fail(f"{where}.amplitude", "expected with `motion` or `turn` (the amplitude scales the primitive's motion)")
    if moves and analysis == "dynamic" and amp < 0:
        ctx.fail(f"{where}.amplitude", "missing; a moving primitive in dynamics needs an amplitude (a ramp, ...) "
                                       "of its motion")
    if "body" not in ct:
        return motion, turn, pivot, amp, -1, []
    name = ct["body"]
    if not isinstance(name, str) or name not in bodies:
        ctx.fail(f"{where}.body", f"expected the name of a [[body]] (bodies: {', '.join(bodies) or 'none'})")
    for k in ("motion", "turn", "amplitude"):
        if k in ct:
            ctx.fail(f"{where}.{k}", "a primitive of a body moves with the body (drive the body instead)")
    b = bodies[name]
    return motion, turn, pivot, amp, b["elem"], list(b["X"]) + [b["R"][i][j] for i in range(3) for j in range(3)]


def contacts(ctx, doc, beams, length_scale, amps=None, analysis="static", bodies=None):
    """(prims, sets) of the model file's contact records: prims [(code, prm,
    (motion, turn, pivot, amplitude, body, body reference))],
    sets [(prim, reach, stiffness, friction, slip, samples, [(element, radius)])]."""
    prims, sets = [], []
    for i, ct in enumerate(get_array_of_tables(ctx, doc, "contact")):
        where = f"contact[{i}]"
        check_keys(ctx, ct, set(KEYS), where)
        mu_s, mu_k = _friction(ctx, ct, where)
        shape = get_str(ctx, ct, "shape", where, choices=tuple(SHAPES))
        code, prm = _primitive(ctx, ct, where, shape)
        place = _placement(ctx, ct, where, code, prm, amps, analysis, bodies or {})
        names = beam_names(ctx, ct, where, beams)
        reach = get_number(ctx, ct, "distance", where, default=1e-3 * length_scale, positive=True)
        samples = get_int(ctx, ct, "samples", where, default=4, lo=1, hi=64)
        slip = slip_tolerance(ctx, ct, where, length_scale, analysis, doc)
        weight = max(weight_per_length(doc, n, beams[n]["section"]) for n in names)
        kappa = get_number(ctx, ct, "stiffness", where, default=max(1e3 * weight / reach, 1e-12), positive=True)
        members = []
        for n in names:
            beam = beams[n]
            sec = beam["section"]
            r = get_number(ctx, ct, "contact_radius", where, default=sec[2] / 2.0, nonneg=True)
            for k in range(beam["nelem"]):
                s0, l = beam["elem_start"][k], beam["elem_lens"][k]
                for j in range(samples):
                    xi = 0.5 if samples == 1 else j / (samples - 1)      # as runtime/assembly/contact_force.c
                    x = beam["geo"].at(s0 + xi * l)[0]
                    depth = r - _distance(code, prm, x)
                    if depth >= 0.0:
                        ctx.fail(where, f"beam {n!r} element {k} starts {depth:.6g} m into the {shape} "
                                        f"(its sections must start clear of it: move the beam or the {shape})")
                members.append((beam["first_elem"] + k, r))
        prims.append((code, prm, place))
        sets.append((len(prims) - 1, reach, kappa, (mu_s, mu_k), slip, samples, members))
    return prims, sets


def contact_records(prims, sets, fmt):
    """The model file's lines: 'contacts NPRIM NSET', a 'prim CODE p0..p6' per
    primitive (its motion and amplitude after the parameters), a 'cset PRIM
    REACH STIFFNESS MU_S MU_K SLIP SAMPLES N e r ...' per set."""
    out = [f"contacts {len(prims)} {len(sets)}"]
    for code, prm, (motion, turn, pivot, amp, body, ref) in prims:
        out.append("prim " + str(code) + " " + " ".join(fmt(v) for v in prm + [0.0] * (15 - len(prm)) + motion + turn +
                                                         pivot) + f" {amp} {body}" + "".join(" " + fmt(v) for v in ref))
    for p, reach, kappa, (mu_s, mu_k), slip, samples, members in sets:
        out.append(f"cset {p} {fmt(reach)} {fmt(kappa)} {fmt(mu_s)} {fmt(mu_k)} {fmt(slip)} {samples} {len(members)} " +
                   " ".join(f"{e} {fmt(r)}" for e, r in members))
    return out



def _build(ctx, doc, scene):
    prims, sets = contacts(ctx, doc, scene.beams, scene.length_scale, scene.amps, scene.analysis, scene.bodies)
    return (prims, sets) if sets else None


def _lines(data, fmt):
    return contact_records(data[0], data[1], fmt)


INTERACTION = Interaction(table="contact", keys=KEYS, record="contact", build=_build, lines=_lines, holds=True,
                          order=30, doc=DOC,
                          title="rigid primitives the beams may touch (docs/explanation/contact.md)")
