"""Analysis options ([static], [dynamic], [modal], [output]: checked by the
options schema, gen/options_schema.py), initial velocities and sensors."""
import gen.scene_keys as K
from gen import options_schema as S
from gen.options_schema import DYNAMIC_FRAMES  # noqa: F401  (gen/scene/cost.py)
from gen.scene.mesh import locate, parse_point
from gen.scene.values import _cross, _dot, _sub, check_keys, get_array_of_tables, get_name, get_str, get_vec3

STATIC_DEFAULTS = S.defaults("static")
DYNAMIC_DEFAULTS = S.defaults("dynamic")


def options(ctx, doc, analysis):
    """(static, dynamic, modal, output) options: {key: value} by the schema
    (choices by name)."""
    v = S.validate(ctx, doc, analysis)
    return v["static"], v["dynamic"], v["modal"], v["output"]


def initial_velocities(ctx, doc, mesh):
    """Initial velocities: rigid translation + rotation, per beam or for all."""
    beams, nodes, dof_of_node, q0, ndof = mesh.beams, mesh.nodes, mesh.dof_of_node, mesh.q0, mesh.ndof
    qd0 = [0.0] * ndof
    for ii, iv in enumerate(get_array_of_tables(ctx, doc, "initial_velocity")):
        where = f"initial_velocity[{ii}]"
        check_keys(ctx, iv, set(K.INITIAL_VELOCITY), where)
        v = get_vec3(ctx, iv, "velocity", where, default=[0.0, 0.0, 0.0])
        w = get_vec3(ctx, iv, "angular_velocity", where, default=[0.0, 0.0, 0.0])
        c = get_vec3(ctx, iv, "center", where, default=[0.0, 0.0, 0.0])
        if "body" in iv:
            if "beam" in iv:
                ctx.fail(f"{where}.body", "give either beam or body, not both")
            bn = get_str(ctx, iv, "body", where)
            if bn not in mesh.bodies:
                ctx.fail(f"{where}.body", f"no body named {bn!r} (bodies: {', '.join(mesh.bodies) or 'none'})")
            gids = [mesh.bodies[bn]["gid"]]
        elif "beam" in iv:
            bn = get_str(ctx, iv, "beam", where)
            if bn not in beams:
                ctx.fail(f"{where}.beam", f"no beam named {bn!r} (beams: {', '.join(beams)})")
            gids = sorted(set(beams[bn]["node_at"].values()))
        else:
            gids = range(len(nodes))
        for gid in gids:
            X = nodes[gid][0]
            base = dof_of_node[gid]
            for f, dim in nodes[gid][4]:
                vals = [q0[base + i] for i in range(dim)]
                if f == "r":
                    out = [v[i] + x for i, x in enumerate(_cross(w, _sub(X, c)))]
                elif f == "p":                     # p' = (0, w) p / 2
                    s0, v0 = vals[0], vals[1:]
                    out = [-0.5 * _dot(w, v0)] + [0.5 * (s0 * w[i] + _cross(w, v0)[i]) for i in range(3)]
                elif dim == 3:
                    out = _cross(w, vals)
                else:
                    out = [0.0] * dim
                for i in range(dim):
                    qd0[base + i] = out[i]
                base += dim

    return qd0


def sensors(ctx, doc, beams, bodies=None):
    """[(name, element, xi, offset)] of the [[sensor]] tables (a body: its centre of mass, xi = 1/2, or
    with `point` that point of the body, offset = its place in the body axes; gen/scene/body_loads.py)."""
    sensors = []
    seen = set()
    for si, sd in enumerate(get_array_of_tables(ctx, doc, "sensor")):
        where = f"sensor[{si}]"
        check_keys(ctx, sd, set(K.SENSOR), where)
        sn = get_name(ctx, sd, "name", where)
        if sn in seen:
            ctx.fail(f"sensor.{sn}", f"duplicate sensor name {sn!r}")
        seen.add(sn)
        if "at" not in sd:
            ctx.fail(f"sensor.{sn}.at", "missing; expected a point like 'arm:end'")
        if bodies and isinstance(sd["at"], str) and sd["at"] in bodies:
            from gen.scene.body_loads import body_point
            off = body_point(ctx, sd, f"sensor.{sn}", bodies[sd["at"]])
            sensors.append((sn, bodies[sd["at"]]["elem"], 0.5, off or [0.0, 0.0, 0.0]))
            continue
        if "point" in sd:
            ctx.fail(f"sensor.{sn}.point", "a point of a rigid body: expected `at` to name a body")
        beam, s = parse_point(ctx, sd["at"], f"sensor.{sn}.at", beams)
        e, xi = locate(beam, s)
        sensors.append((sn, e, xi, [0.0, 0.0, 0.0]))

    return sensors
