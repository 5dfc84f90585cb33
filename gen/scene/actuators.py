"""Actuators: [[actuator]] tables, each a motor acting equally and oppositely on
the two frames of a named joint with an axis: the interaction whose model
record "actuator" runtime/assembly/actuators.c reads.

  effort = tau0 a_e(x) + kp (s_ref a_s(x) - s) + kd (s_ref a_s'(x) - s')
s the joint coordinate (the angle of frame a relative to b about the axis, rad,
or the displacement along it, m; 0 in the reference configuration), a_e the
`effort_amplitude` (default: the load factor in statics, 1 in dynamics), a_s
the `setpoint_amplitude` (default: 1).  The effort is a torque (N m) on frame a
about the axis and its opposite on b, or a force (N) along the axis.
"""

import gen.scene_keys as K
from gen.scene.interactions import Interaction
from gen.scene.values import check_keys, get_array_of_tables, get_number, get_str, plain_name

# joint types an actuator may act on: the coordinate it drives
AXIS_KIND = {"revolute": "rotation", "prismatic": "translation"}
# why the other joint types take none (the error's last words)
NO_ACTUATOR = {"universal": "a universal joint has two axes; a motor turns about one",
               "point_on_line": "a point_on_line axis carries no motor; a force along it is a `force` load at "
                                "the point",
               "prescribed_rotation": "a driven joint prescribes the motion; its effort is in joints.csv",
               "prescribed_translation": "a driven joint prescribes the motion; its effort is in joints.csv",
               "prescribed_motion": "a prescribed motion prescribes the point's path; its force is in "
                                    "reactions.csv"}


def actuated_joints(doc):
    """The names of the constraints some [[actuator]] acts on (they are made
    joints nonlinear in q, whose frames the actuator needs)."""
    acts = doc.get("actuator", [])
    if not isinstance(acts, list):
        return set()
    return {a.get("joint") for a in acts if isinstance(a, dict) and isinstance(a.get("joint"), str)}


def actuators(ctx, doc, rows, amps):
    """Records (name, kind, nlcon, tau0, effort amplitude, kp, kd, setpoint,
    setpoint amplitude) of every [[actuator]]."""
    joints = {r[9]: r for r in rows.reactions}
    out, names = [], set()
    for i, at in enumerate(get_array_of_tables(ctx, doc, "actuator")):
        where = f"actuator[{i}]"
        check_keys(ctx, at, set(K.ACTUATOR), where)
        name = get_str(ctx, at, "name", where, default=f"actuator{i}")
        if not plain_name(name):
            ctx.fail(f"{where}.name", f"expected 1 to 63 letters, digits, '_', '.' or '-', found {name!r}")
        if name in names:
            ctx.fail(f"{where}.name", f"the name {name!r} is given to two actuators")
        names.add(name)
        if "joint" not in at:
            ctx.fail(f"{where}.joint", "missing; expected the name of a revolute or prismatic [[constraint]]")
        jname = get_str(ctx, at, "joint", where)
        if jname not in joints:
            ctx.fail(f"{where}.joint", f"no constraint named {jname!r} (constraints: "
                     f"{', '.join(sorted(joints)) or 'none'})")
        ctype, nlcon = joints[jname][1], joints[jname][8]
        if ctype not in AXIS_KIND:
            ctx.fail(f"{where}.joint", f"constraint {jname!r} is a {ctype} joint: an actuator needs a joint with "
                     f"an axis, revolute or prismatic ({NO_ACTUATOR.get(ctype, 'it has no axis')})")
        if nlcon < 0:       # (actuated joints are made nonlinear: gen/scene/joints.py)
            ctx.fail(f"{where}.joint", f"constraint {jname!r} has no frames to act on")
        tau0 = get_number(ctx, at, "effort", where, default=0.0)
        kp = get_number(ctx, at, "kp", where, default=0.0, nonneg=True)
        kd = get_number(ctx, at, "kd", where, default=0.0, nonneg=True)
        sref = get_number(ctx, at, "setpoint", where, default=0.0)
        eamp = amps.ref(at, "effort_amplitude", where)
        samp = amps.ref(at, "setpoint_amplitude", where)
        if eamp >= 0 and "effort" not in at:
            ctx.fail(f"{where}.effort", "missing; `effort_amplitude` scales the effort `effort`")
        if samp >= 0 and "setpoint" not in at:
            ctx.fail(f"{where}.setpoint", "missing; `setpoint_amplitude` scales the set-point `setpoint`")
        if ("setpoint" in at) and kp == 0.0 and kd == 0.0:
            ctx.fail(f"{where}.kp", "a set-point needs a gain: kp > 0 (and kd >= 0)")
        if "effort" not in at and kp == 0.0 and kd == 0.0:
            ctx.fail(where, "expected an `effort` (N m or N) or a feedback law (`kp`, `kd`, `setpoint`)")
        out.append((name, AXIS_KIND[ctype], nlcon, tau0, eamp, kp, kd, sref, samp))
    return out


def _build(ctx, doc, scene):
    return actuators(ctx, doc, scene.joints, scene.amps)


def actuator_records(acts, fmt):
    """The lines of the record: 'actuators N', then per actuator 'actuator NAME
    KIND JOINT EFFORT EAMP KP KD SETPOINT SAMP'."""
    out = [f"actuators {len(acts)}"]
    for name, kind, nlcon, tau0, eamp, kp, kd, sref, samp in acts:
        out.append(f"actuator {name} {kind} {nlcon} {fmt(tau0)} {eamp} {fmt(kp)} {fmt(kd)} {fmt(sref)} {samp}")
    return out


# (its keys are documented with the scene's, docs/reference/scene.md: gen/scene_keys.py ACTUATOR)
INTERACTION = Interaction(table="actuator", keys=K.ACTUATOR, record="actuator", build=_build, lines=actuator_records,
                          holds=False, order=60)
