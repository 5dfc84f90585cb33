"""[[body]] tables: rigid bodies as one-node elements (rigid_body, gen/body.py)
with the centre of mass r and a quaternion p (the body axes e1, e2, e3 are the
principal axes of the inertia tensor), numbered after the beams' DOFs."""
import math

import gen.scene_keys as K
from gen.scene.geometry import frame_quaternion
from gen.scene.values import _cross, _dot, _norm, _scale, _typename, check_keys, get_array_of_tables, get_name, \
    get_number, get_vec3


def _axes(ctx, bt, where):
    """Rows of `axes` (the body's reference frame, right-handed, orthonormal), default global."""
    if "axes" not in bt:
        return [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    v = bt["axes"]
    if not isinstance(v, list) or len(v) != 3 or not all(
            isinstance(r, list) and len(r) == 3 and all(isinstance(x, (int, float)) and not isinstance(x, bool)
                                                        for x in r) for r in v):
        ctx.fail(f"{where}.axes", f"expected 3 rows of 3 numbers (the body axes), found {_typename(v)}")
    rows = [[float(x) for x in r] for r in v]
    for i in range(3):
        for j in range(3):
            if abs(_dot(rows[i], rows[j]) - (i == j)) > 1e-9:
                ctx.fail(f"{where}.axes", f"the rows must be orthonormal, found {rows!r}")
    if _dot(_cross(rows[0], rows[1]), rows[2]) < 0:
        ctx.fail(f"{where}.axes", "the axes must be right-handed (axes[0] x axes[1] = axes[2])")
    return rows


def _inertia(ctx, bt, where):
    """The inertia tensor (kg m^2) about the centre of mass in the body axes, from
    [Jxx, Jyy, Jzz] or [Jxx, Jyy, Jzz, Jxy, Jxz, Jyz] (tensor entries)."""
    key = f"{where}.inertia"
    if "inertia" not in bt:
        ctx.fail(key, "missing; expected [Jxx, Jyy, Jzz] or [Jxx, Jyy, Jzz, Jxy, Jxz, Jyz] in kg m^2")
    v = bt["inertia"]
    if not isinstance(v, list) or len(v) not in (3, 6) or any(
            isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x) for x in v):
        ctx.fail(key, f"expected [Jxx, Jyy, Jzz] or [Jxx, Jyy, Jzz, Jxy, Jxz, Jyz] (numbers), found "
                 f"{_typename(v) if not isinstance(v, list) else repr(v)}")
    v = [float(x) for x in v] + [0.0] * (6 - len(v))
    J = [[v[0], v[3], v[4]], [v[3], v[1], v[5]], [v[4], v[5], v[2]]]
    if v[3] == v[4] == v[5] == 0.0:
        lam, vecs = v[:3], [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    else:
        import numpy as np
        w, U = np.linalg.eigh(np.array(J))
        if np.linalg.det(U) < 0:
            U[:, 2] = -U[:, 2]
        lam, vecs = [float(x) for x in w], [[float(U[i, k]) for i in range(3)] for k in range(3)]
    tol = 1e-12 * max(abs(x) for x in lam) if any(lam) else 0.0
    if min(lam) <= tol:
        ctx.fail(key, f"the inertia tensor must be positive definite; its principal moments are "
                 f"{', '.join(f'{x:.6g}' for x in lam)}")
    for i in range(3):
        a, b, c = lam[i], lam[(i + 1) % 3], lam[(i + 2) % 3]
        if a > b + c + 1e-9 * (a + b + c):
            ctx.fail(key, f"the principal moments {', '.join(f'{x:.6g}' for x in lam)} violate the triangle "
                     f"inequality ({a:.6g} > {b:.6g} + {c:.6g}): no mass distribution has them")
    return lam, vecs


def mesh_bodies(ctx, doc, mesh, index):
    """Every [[body]]: a node (r, p) and a rigid_body element.  mesh.bodies[name] =
    {name, gid, elem, X, R (columns e1, e2, e3)}."""
    info = index.get("body")
    tables = get_array_of_tables(ctx, doc, "body")
    if tables and not info:
        ctx.fail("body", "the generated kernels have no rigid body: run ./build.sh gen")
    for bi, bt in enumerate(tables):
        where = f"body[{bi}]"
        check_keys(ctx, bt, set(K.BODY), where)
        name = get_name(ctx, bt, "name", where)
        where = f"body.{name}"
        if name in mesh.bodies or name in mesh.beams:
            ctx.fail(f"{where}.name", f"duplicate name {name!r} (bodies and beams share names)")
        M = get_number(ctx, bt, "mass", where, positive=True)
        X = get_vec3(ctx, bt, "center", where, bound=1e9)
        rows = _axes(ctx, bt, where)
        lam, vecs = _inertia(ctx, bt, where)
        # principal axes in global coordinates: e_k = sum_i vecs[k][i] rows[i]
        E = [[sum(vecs[k][i] * rows[i][j] for i in range(3)) for j in range(3)] for k in range(3)]
        pair = info["pair"]
        if pair not in mesh.pairs:
            mesh.pairs.append(pair)
        pidx = mesh.pairs.index(pair)
        cg = 4e4 * max(lam)
        mkey = ((cg,), 1.0, (), tuple(info["params"]))
        if mkey not in mesh.mats_used:
            mesh.mats_used.append(mkey)
        midx = mesh.mats_used.index(mkey)
        edge = math.sqrt(6.0 * sum(lam) / 3.0 / M)
        gid = len(mesh.nodes)
        fields = tuple((f, d) for f, d in info["nodes"][0]["fields"])
        mesh.nodes.append((X, E[0], E[1], E[2], fields))
        base = mesh.ndof
        mesh.dof_of_node.append(base)
        mesh.q0.extend(list(X) + frame_quaternion(E[0], E[1], E[2]))
        mesh.ndof += 7
        from gen import contract
        geom = [edge, edge, edge, M, lam[0], lam[1], lam[2], 1.0]
        geom += [0.0] * (contract.ngeom() - len(geom))       # (the slots of beams' layers: unused)
        mesh.geoms.append((pidx, len(mesh.elements), geom))
        mesh.elements.append((pidx, len(mesh.geoms) - 1, midx, list(range(base, base + 7))))
        R = [[E[k][i] for k in range(3)] for i in range(3)]
        mesh.bodies[name] = {"name": name, "gid": gid, "elem": len(mesh.elements) - 1, "X": X, "R": R,
                             "mass": M, "geom_edge": edge}
    return mesh
