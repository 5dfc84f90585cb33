"""[[load]] tables: point forces and moments on beams, gravity."""
import gen.scene_keys as K
from gen.scene.mesh import locate, locate_node, parse_point
from gen.scene.values import _dot, _norm, check_keys, get_array_of_tables, get_str, get_vec3


def loads(ctx, doc, beams):
    """(forces, moments, gravity) of the scene."""
    forces = []
    moments = []
    gravity = None
    for li, lt in enumerate(get_array_of_tables(ctx, doc, "load")):
        where = f"load[{li}]"
        ltype = get_str(ctx, lt, "type", where, choices=tuple(K.LOAD))
        if ltype in ("force", "moment"):
            check_keys(ctx, lt, set(K.LOAD[ltype]), where)
            if "at" not in lt:
                ctx.fail(f"{where}.at", "missing; expected a point like 'arm:end'")
            beam, s = parse_point(ctx, lt["at"], f"{where}.at", beams)
            val = get_vec3(ctx, lt, "value", where)
            e, xi = locate(beam, s)
            if ltype == "force":
                dist = get_str(ctx, lt, "distribution", where, default="point", choices=("point", "section"))
                forces.append((e, xi, 0.0, 0.0, 1 if dist == "section" else 0, val))
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
                moments.append((e, xi, val))
        else:
            check_keys(ctx, lt, set(K.LOAD["gravity"]), where)
            g = get_vec3(ctx, lt, "value", where)
            if gravity is not None:
                ctx.fail(f"{where}.type", "gravity given twice")
            gravity = g

    return forces, moments, gravity
