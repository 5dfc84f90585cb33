"""Loads on rigid bodies: a [[load]] force or moment whose `at` is a body's name,
as the records of the loads on beams (gen/scene/loads.py).

The value is given in global components in the reference configuration; a
follower load turns with the body from there (its components along the body
axes e1, e2, e3, the section frame of the rigid_body element).  A force acts at
the centre of mass, or with `point` (global coordinates of a point of the body
in the reference configuration) at that body point: a follower force f at the
point c (body axes) is the follower force f at the centre of mass and the
follower moment c x f, exactly.  A dead force F at a point c off the centre
of mass (its moment (R c) x F neither dead nor following the body) is a record
of its own: the interaction whose model record "body_force" (body_point_forces)
runtime/assembly/body_forces.c reads, the work F . (r + R c) with its exact
Jacobian.
"""
from gen.scene.interactions import Interaction
from gen.scene.values import _cross, _norm, _sub, get_array_of_tables, get_bool, get_str, get_vec3

SIZE_FACTOR = 10.0          # a body point within this many times the body's size of its centre


def _mtv(R, v):
    return [sum(R[i][k] * v[i] for i in range(3)) for k in range(3)]


def body_point(ctx, lt, where, body):
    """The offset c (body axes) of lt['point'] from the body's centre of mass, or None."""
    if "point" not in lt:
        return None
    X = get_vec3(ctx, lt, "point", where, bound=1e9)
    off = _sub(X, body["X"])
    size = max(body["geom_edge"], 1e-9)
    if _norm(off) > SIZE_FACTOR * size:
        ctx.fail(f"{where}.point", f"{_norm(off):.6g} m from the centre of mass of body {body['name']!r} (its "
                 f"size about {size:.3g} m): expected a point of the body, within {SIZE_FACTOR:g} times its size")
    return _mtv(body["R"], off)


def body_load(ctx, lt, where, ltype, body, amps):
    """([force records], [moment records]) of a force or moment on a body."""
    val = get_vec3(ctx, lt, "value", where)
    fol = get_bool(ctx, lt, "follower", where, False)
    amp = amps.ref(lt, "amplitude", where)
    e = body["elem"]
    if ltype == "moment":
        return [], [(e, 0.5, _mtv(body["R"], val) if fol else val, amp, int(fol))]
    if "distribution" in lt and get_str(ctx, lt, "distribution", where) != "point":
        ctx.fail(f"{where}.distribution", "a force on a rigid body acts at a point: omit `distribution`")
    c = body_point(ctx, lt, where, body)
    if c is not None and _norm(c) > 1e-12 * max(1.0, body["geom_edge"]) and not fol:
        return [], []                    # a dead force off the centre: body_point_forces
    if not fol:
        return [(e, 0.5, 0.0, 0.0, 0, val, amp, 0)], []
    f = _mtv(body["R"], val)
    forces = [(e, 0.5, 0.0, 0.0, 0, f, amp, 1)]
    moments = [(e, 0.5, _cross(c, f), amp, 1)] if c is not None and _norm(c) > 0.0 else []
    return forces, moments


def body_point_forces(ctx, doc, bodies, amps):
    """[(element, c (body axes), F, amplitude)] of the dead forces at body points off
    the centre of mass (the loads body_load leaves out; checked there)."""
    out = []
    for li, lt in enumerate(get_array_of_tables(ctx, doc, "load")):
        if not (isinstance(lt, dict) and lt.get("type") == "force" and isinstance(lt.get("at"), str)
                and lt["at"] in bodies and "point" in lt and lt.get("follower") is not True):
            continue
        where = f"load[{li}]"
        body = bodies[lt["at"]]
        c = body_point(ctx, lt, where, body)
        if _norm(c) > 1e-12 * max(1.0, body["geom_edge"]):
            out.append((body["elem"], c, get_vec3(ctx, lt, "value", where), amps.ref(lt, "amplitude", where)))
    return out


def _build(ctx, doc, scene):
    return body_point_forces(ctx, doc, scene.bodies, scene.amps)


def body_force_records(pfs, fmt):
    """The lines of the record: 'body_forces N', then per force 'body_force
    ELEMENT CX CY CZ FX FY FZ AMP' (C in the body axes, F global)."""
    out = [f"body_forces {len(pfs)}"]
    out += [f"body_force {e} " + " ".join(fmt(x) for x in list(c) + list(F)) + f" {amp}" for e, c, F, amp in pfs]
    return out


# (part of the [[load]] table, whose keys gen/scene/loads.py checks and docs/reference/scene.md lists)
INTERACTION = Interaction(table="load", keys=(), record="body_force", build=_build, lines=body_force_records,
                          holds=False, order=70)
