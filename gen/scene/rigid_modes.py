"""Free rigid motions of a static model: the six infinitesimal rigid motions of
the whole model (translations along x, y, z and rotations about the axes
through the model's centre) that no fixed coordinate and no linear constraint
row holds.  A static analysis of such a model has no unique equilibrium (its
tangent is singular, or only round-off holds it), so the scene compiler
refuses it, naming the motion (issue 36).

A node's coordinates move with a rigid motion (translation t, rotation w
about c) as: its position r by t + w x (r - c); every other vector field (the
ANCF gradients r_x, r_y, r_z and higher) by w x v; a quaternion p by
(0, w) p / 2.  The motions that all constraint rows annihilate are the null
space of the rows applied to the six motions (an SVD of a rows x 6 matrix)."""
NAMES = ("a translation along x", "a translation along y", "a translation along z",
         "a rotation about x", "a rotation about y", "a rotation about z")


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def rigid_velocities(mesh):
    """The six rigid motions' velocities of every coordinate: [6][ndof]."""
    q0 = mesh.q0
    pos = [q0[mesh.field_dofs(g)["r"][0]:mesh.field_dofs(g)["r"][0] + 3]
           for g in range(len(mesh.nodes)) if "r" in mesh.field_dofs(g)]
    c = [sum(p[i] for p in pos) / max(1, len(pos)) for i in range(3)]
    modes = [[0.0] * len(q0) for _ in range(6)]
    for g in range(len(mesh.nodes)):
        for f, dofs in mesh.field_dofs(g).items():
            v = [q0[d] for d in dofs]
            for k in range(6):
                if f == "p":                           # (0, w) p / 2
                    if k < 3:
                        continue
                    w = [1.0 if i == k - 3 else 0.0 for i in range(3)]
                    s, u = v[0], v[1:]
                    wu = _cross(w, u)
                    dp = [-0.5 * sum(w[i] * u[i] for i in range(3))] + [0.5 * (s * w[i] + wu[i]) for i in range(3)]
                elif len(dofs) != 3:
                    continue
                elif k < 3:                            # translation: positions only
                    dp = [1.0 if i == k else 0.0 for i in range(3)] if f == "r" else [0.0] * 3
                else:
                    w = [1.0 if i == k - 3 else 0.0 for i in range(3)]
                    dp = _cross(w, [v[i] - c[i] for i in range(3)] if f == "r" else v)
                for d, x in zip(dofs, dp):
                    modes[k][d] = x
    return modes


def free_motions(mesh, fixed, lincons):
    """Descriptions of the rigid motions no constraint holds (empty: none)."""
    import numpy as np
    modes = np.array(rigid_velocities(mesh))             # 6 x ndof
    norms = np.linalg.norm(modes, axis=1)
    scale = 1.0 / np.where(norms > 0.0, norms, 1.0)      # each motion of unit size over the whole model
    rows = [modes[:, d] for d in sorted(fixed)]
    for terms, _rhs, _tf in lincons:
        rows.append(sum(c0 * modes[:, d] for d, c0, _cc, _cs in terms))
    if not rows:
        basis = np.eye(6)
    else:
        A = np.array(rows) * scale
        _u, sv, vt = np.linalg.svd(A)
        tol = 1e-9 * max(1.0, sv[0] if len(sv) else 1.0)
        rank = int(np.sum(sv > tol))
        basis = vt[rank:]
    out = []
    for b in basis:
        k = int(np.argmax(np.abs(b)))
        parts = [NAMES[i] for i in range(6) if abs(b[i]) > 0.2 * abs(b[k])]
        out.append(" with ".join(parts))
    return out


def check_static(ctx, mesh, rows, analysis, has_contact, stat):
    """Refuse a static analysis whose model can move as a rigid body (unless
    [static] free_rigid_motion = true, contact may hold it, or joints
    nonlinear in q take part: those are not checked here)."""
    if analysis != "static" or has_contact or rows.nlcons or stat.get("free_rigid_motion"):
        return
    free = free_motions(mesh, rows.fixed, rows.lincons)
    if free:
        what = "; ".join(free[:3]) + (f" (and {len(free) - 3} more)" if len(free) > 3 else "")
        ctx.fail("constraint", f"the model is free to move as a rigid body in statics ({what}): no constraint "
                 "holds it, so it has no unique equilibrium; add a clamp or joint to the ground, run dynamics, or set "
                 "[static] free_rigid_motion = true")
