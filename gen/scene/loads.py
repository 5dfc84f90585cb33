"""[[load]] tables: point forces and moments on beams (dead or follower),
distributed loads along beams, tendons, gravity; each with an amplitude
(gen/scene/amplitude.py; -1: the default, the load factor in statics and 1 in
dynamics)."""
import math

import gen.scene_keys as K
from gen.scene.mesh import locate, locate_node, parse_point
from gen.scene.values import (_dot, _norm, _typename, check_keys, get_array_of_tables, get_bool, get_name,
                              get_number, get_str, get_vec3)


def _span(ctx, lt, where, beams):
    """(beam, [(element, xi0, xi1)]) of the part of a beam a distributed load or a
    tendon covers: `beam` (all of it) or `from` and `to` (points on one beam)."""
    if "beam" in lt and ("from" in lt or "to" in lt):
        ctx.fail(f"{where}.beam", "give either `beam` (the whole beam) or `from` and `to`, not both")
    if "beam" in lt:
        bname = lt["beam"]
        if not isinstance(bname, str) or bname not in beams:
            ctx.fail(f"{where}.beam", f"no beam named {bname!r} (beams: {', '.join(beams) or 'none'})")
        beam, s0, s1 = beams[bname], 0.0, beams[bname]["length"]
    else:
        for k in ("from", "to"):
            if k not in lt:
                ctx.fail(f"{where}.{k}", "missing; expected a point like 'arm:0.2' (or `beam` for a whole beam)")
        beam, s0 = parse_point(ctx, lt["from"], f"{where}.from", beams)
        beam_b, s1 = parse_point(ctx, lt["to"], f"{where}.to", beams)
        if beam_b is not beam:
            ctx.fail(f"{where}.to", f"expected a point on beam {beam['name']!r} like `from`, found {lt['to']!r}")
        if not s1 > s0 + 1e-12 * beam["length"]:
            ctx.fail(f"{where}.to", f"expected a point beyond `from` (arc length {s0:.6g} m), found {s1:.6g} m")
    pieces = []
    for k in range(beam["nelem"]):
        a, l = beam["elem_start"][k], beam["elem_lens"][k]
        lo, hi = max(s0, a), min(s1, a + l)
        if hi > lo + 1e-12 * l:
            pieces.append((beam["first_elem"] + k, (lo - a) / l, (hi - a) / l))
    return beam, pieces


def _follower(ctx, lt, where, beam):
    fol = get_bool(ctx, lt, "follower", where, False)
    if fol and not beam["section_frame"]:
        ctx.fail(f"{where}.follower", f"element {beam['element']} has no section frame for a follower load to "
                 "turn with")
    return int(fol)


def _line_offset(ctx, lt, where, beam, what):
    """(dy, dz) of a tendon's or chamber's line in the sections of its beam: the
    beam a continuum ANCF beam or a rod (an element with a section_line()), the
    point inside the smallest section along the beam."""
    if beam["kind"] != "continuum" and not beam.get("section_line"):
        ctx.fail(f"{where}.beam", f"{what} act on continuum ANCF beams (ancf3243, ancf3333, ancf3273, ancf3363) "
                 f"and rods (gef, euler_bernoulli, kirchhoff) only, beam {beam['name']!r} is {beam['element']}")
    off = lt.get("offset")
    if (not isinstance(off, list) or len(off) != 2
            or any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in off)):
        ctx.fail(f"{where}.offset", f"expected [dy, dz] (m, along the section axes d1, d2), found "
                 f"{_typename(off) if not isinstance(off, list) else off}")
    dy, dz = float(off[0]), float(off[1])
    b = min(sec[1] for sec in beam["sections"])       # the smallest section along the beam
    h = min(sec[2] for sec in beam["sections"])
    if beam["sections"][0][0] == "circle":
        if dy * dy + dz * dz >= 0.25 * b * b:
            ctx.fail(f"{where}.offset", f"the {what[:-1]} at [{dy:g}, {dz:g}] m lies outside the section of beam "
                     f"{beam['name']!r} (a circle of diameter {b:g} m: sqrt(dy^2 + dz^2) < {0.5 * b:g})")
    elif abs(dy) >= 0.5 * b or abs(dz) >= 0.5 * h:
        ctx.fail(f"{where}.offset", f"the {what[:-1]} at [{dy:g}, {dz:g}] m lies outside the section of "
                 f"beam {beam['name']!r} ({b:g} x {h:g} m: |dy| < {0.5 * b:g}, |dz| < {0.5 * h:g})")
    return dy, dz


def _chamber(ctx, lt, where, beams, amps):
    """A pneumatic chamber along (part of) a beam: cross-section area A, centroid
    at the offset (dy, dz), pressure p (times the amplitude).  Its loads are those
    of the potential -p A l(q), l the length of the material line through the
    chamber's centroid (the tendon's line, with tension -p A): at each end cap the
    force p A outward along that line (an axial force p A and a moment p A e that
    turn with the section), along a curved chamber the walls' pressure."""
    beam, pieces = _span(ctx, lt, where, beams)
    dy, dz = _line_offset(ctx, lt, where, beam, "chambers")
    area = get_number(ctx, lt, "area", where, positive=True)
    p = get_number(ctx, lt, "pressure", where)
    secs = beam["sections"]
    full = min(sec[1] * sec[2] * (0.25 * math.pi if sec[0] == "circle" else 1.0) for sec in secs)
    if area >= full:
        ctx.fail(f"{where}.area", f"a chamber of {area:g} m^2 does not fit in the section of beam "
                 f"{beam['name']!r} (its smallest section has {full:g} m^2)")
    amp = amps.ref(lt, "amplitude", where)
    return (amp, -p * area, [(e, x0, x1, dy, dz) for e, x0, x1 in pieces])


def loads(ctx, doc, beams, amps, bodies=None):
    """(forces, moments, gravity, distributed, tendons) of the scene (a force or
    moment on a body: gen/scene/body_loads.py)."""
    forces = []
    moments = []
    dloads = []
    tendons = []
    gravity = None
    names = {}
    for li, lt in enumerate(get_array_of_tables(ctx, doc, "load")):
        where = f"load[{li}]"
        if "name" in lt:                # a label: --set load.NAME.KEY=..., unique among the loads
            nm = get_name(ctx, lt, "name", where)
            if nm in names:
                ctx.fail(f"{where}.name", f"the name {nm!r} is used twice (load[{names[nm]}] has it); "
                         "expected a unique name per load")
            names[nm] = li
        ltype = get_str(ctx, lt, "type", where, choices=tuple(K.LOAD))
        if ltype == "distributed":
            check_keys(ctx, lt, set(K.LOAD[ltype]), where)
            beam, pieces = _span(ctx, lt, where, beams)
            val = get_vec3(ctx, lt, "value", where)
            fol, amp = _follower(ctx, lt, where, beam), amps.ref(lt, "amplitude", where)
            dloads += [(e, x0, x1, fol, amp, val) for e, x0, x1 in pieces]
        elif ltype == "tendon":
            check_keys(ctx, lt, set(K.LOAD[ltype]), where)
            beam, pieces = _span(ctx, lt, where, beams)
            dy, dz = _line_offset(ctx, lt, where, beam, "tendons")
            T = get_number(ctx, lt, "tension", where, nonneg=True)
            amp = amps.ref(lt, "amplitude", where)
            tendons.append((amp, T, [(e, x0, x1, dy, dz) for e, x0, x1 in pieces]))
        elif ltype == "chamber":
            check_keys(ctx, lt, set(K.LOAD[ltype]), where)
            tendons.append(_chamber(ctx, lt, where, beams, amps))
        elif ltype in ("force", "moment"):
            check_keys(ctx, lt, set(K.LOAD[ltype]), where)
            if "at" not in lt:
                ctx.fail(f"{where}.at", "missing; expected a point like 'arm:end'")
            if bodies and isinstance(lt["at"], str) and lt["at"] in bodies:
                from gen.scene.body_loads import body_load
                fs, ms = body_load(ctx, lt, where, ltype, bodies[lt["at"]], amps)
                forces += fs
                moments += ms
                continue
            if "point" in lt:
                ctx.fail(f"{where}.point", "a point of a rigid body: expected `at` to name a body")
            beam, s = parse_point(ctx, lt["at"], f"{where}.at", beams)
            val = get_vec3(ctx, lt, "value", where)
            e, xi = locate(beam, s)
            fol, amp = _follower(ctx, lt, where, beam), amps.ref(lt, "amplitude", where)
            if ltype == "force":
                dist = get_str(ctx, lt, "distribution", where, default="point", choices=("point", "section"))
                forces.append((e, xi, 0.0, 0.0, 1 if dist == "section" else 0, val, amp, fol))
            else:
                if beam["moments"] == "nodes":
                    frac = s / beam["length"]
                    nodes_here = [x for x in beam["node_at"] if abs(x - frac) < 1e-9]
                    if not nodes_here:
                        near = min(beam["node_at"], key=lambda x: abs(x - frac)) * beam["length"]
                        ctx.fail(f"{where}.at", f"element {beam['element']} takes moments at nodes only "
                                 f"(nearest node of {beam['name']!r} at {near:.6g} m), found {s:.6g}")
                    e, xi = locate_node(beam, nodes_here[0])
                elif beam["moments"] == "no_torsion":
                    _, t, _, _ = beam["geo"].at(s)
                    mt = abs(_dot(val, t))
                    if mt > 1e-9 * max(_norm(val), 1e-300):
                        ctx.fail(f"{where}.value", f"element {beam['element']} cannot carry a torque about its "
                                 f"axis (moment component {mt:.6g} N m along the beam at {lt['at']!r})")
                moments.append((e, xi, val, amp, fol))
        else:
            check_keys(ctx, lt, set(K.LOAD["gravity"]), where)
            g = get_vec3(ctx, lt, "value", where)
            if gravity is not None:
                ctx.fail(f"{where}.type", "gravity given twice")
            gravity = (g, amps.ref(lt, "amplitude", where))

    return forces, moments, gravity, dloads, tendons
