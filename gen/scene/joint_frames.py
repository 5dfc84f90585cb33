"""The frames a joint couples: a body, a beam node (its position and, on rods,
its quaternion) or the ground, with its reference place, rotation and DOFs."""
import math


def quat_rotation(p):
    """The rotation matrix of the quaternion p / |p|."""
    s0, x, y, z = p
    n = s0 * s0 + x * x + y * y + z * z
    s0, x, y, z = (c / math.sqrt(n) for c in p)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - s0 * z), 2 * (x * z + s0 * y)],
            [2 * (x * y + s0 * z), 1 - 2 * (x * x + z * z), 2 * (y * z - s0 * x)],
            [2 * (x * z - s0 * y), 2 * (y * z + s0 * x), 1 - 2 * (x * x + y * y)]]


def endpoint(ctx, key, spec, mesh, ctype):
    """A frame of a joint: {what, X, R, dofs (7 or None for the ground), rot}."""
    if spec is None:
        return {"what": "the ground", "X": None, "R": None, "dofs": None, "rot": True, "id": "ground"}
    if isinstance(spec, str) and ":" not in spec and spec in mesh.bodies:
        b = mesh.bodies[spec]
        base = mesh.dof_of_node[b["gid"]]
        return {"what": f"body {spec!r}", "X": b["X"], "R": b["R"], "dofs": list(range(base, base + 7)),
                "rot": True, "id": ("node", b["gid"]), "where": (b["elem"], 0.0)}
    if isinstance(spec, str) and ":" not in spec:
        ctx.fail(key, f"expected BEAM:start, BEAM:end, BEAM:<arc length in m> or a body name, found {spec!r} "
                 f"(bodies: {', '.join(mesh.bodies) or 'none'})")
    beam, s_, gid = mesh.node_of(ctx, key, spec, f"{ctype} joint")
    from gen.scene.mesh import locate
    where = locate(beam, s_)
    fd = mesh.field_dofs(gid)
    X = mesh.nodes[gid][0]
    if "p" in fd:
        p = [mesh.q0[d] for d in fd["p"]]
        return {"what": f"beam point {spec!r}", "X": X, "R": quat_rotation(p), "dofs": fd["r"] + fd["p"],
                "rot": True, "id": ("node", gid), "where": where}
    return {"what": f"beam point {spec!r} (element {beam['element']}, no nodal rotation)", "X": X,
            "R": [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], "dofs": fd["r"] + [-1] * 4,
            "rot": False, "id": ("node", gid), "where": where}


def mtv(R, v):
    """R^T v."""
    return [sum(R[i][k] * v[i] for i in range(3)) for k in range(3)]
