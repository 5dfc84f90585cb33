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


def rigid_velocities(mesh):
    """The six rigid motions' velocities of every coordinate: an array 6 x ndof."""
    import numpy as np
    q0 = np.asarray(mesh.q0, dtype=float)
    modes = np.zeros((6, len(q0)))
    groups = {"r": [], "p": [], "v": []}               # first DOFs of positions, quaternions, other vectors
    for g in range(len(mesh.nodes)):
        for f, dofs in mesh.field_dofs(g).items():
            if f == "p":
                groups["p"].append(dofs[0])
            elif len(dofs) == 3:
                groups["r" if f == "r" else "v"].append(dofs[0])
    r = np.array(groups["r"], dtype=int)
    c = q0[r[:, None] + np.arange(3)].mean(axis=0) if len(r) else np.zeros(3)
    for k in range(3):
        modes[k, r + k] = 1.0                          # translations move the positions
    for k in range(3):
        w = np.eye(3)[k]
        for key, rel in (("r", True), ("v", False)):
            d = np.array(groups[key], dtype=int)
            if not len(d):
                continue
            v = q0[d[:, None] + np.arange(3)] - (c if rel else 0.0)
            modes[3 + k][d[:, None] + np.arange(3)] = np.cross(w, v)
        d = np.array(groups["p"], dtype=int)
        if len(d):                                     # (0, w) p / 2
            s, u = q0[d], q0[d[:, None] + 1 + np.arange(3)]
            modes[3 + k, d] = -0.5 * u @ w
            modes[3 + k][d[:, None] + 1 + np.arange(3)] = 0.5 * (s[:, None] * w + np.cross(w, u))
    return modes


def _coordinates(mesh):
    """({DOF: (field kind "r", "v" or "p", the field's first DOF)} of the
    coordinates a rigid motion moves, the centre of the positions), as
    rigid_velocities groups them."""
    q0 = mesh.q0
    where, pos = {}, []
    for g in range(len(mesh.nodes)):
        for f, dofs in mesh.field_dofs(g).items():
            if f == "p":
                for d in dofs:
                    where[d] = ("p", dofs[0])
            elif len(dofs) == 3:
                for d in dofs:
                    where[d] = ("r" if f == "r" else "v", dofs[0])
                if f == "r":
                    pos.append(dofs[0])
    c = [sum(q0[d + k] for d in pos) / len(pos) if pos else 0.0 for k in range(3)]
    return where, c


def _velocity_row(q0, where, c, d):
    """Coordinate d's velocity under the six rigid motions (column d of
    rigid_velocities), in plain Python."""
    row = [0.0] * 6
    kind, d0 = where.get(d, (None, d))
    j = d - d0
    if kind in ("r", "v"):
        v = [q0[d0 + k] - (c[k] if kind == "r" else 0.0) for k in range(3)]
        if kind == "r":
            row[j] = 1.0                             # translation j moves component j
        for k in range(3):                           # rotation k: (e_k x v)[j]
            row[3 + k] = -v[(k + 2) % 3] if j == (k + 1) % 3 else v[(k + 1) % 3] if j == (k + 2) % 3 else 0.0
    elif kind == "p":                                # quaternion (s, u): (0, w) p / 2
        s, u = q0[d0], [q0[d0 + 1 + k] for k in range(3)]
        for k in range(3):
            if j == 0:
                row[3 + k] = -0.5 * u[k]
            else:
                i = j - 1
                cross = -u[(k + 2) % 3] if i == (k + 1) % 3 else u[(k + 1) % 3] if i == (k + 2) % 3 else 0.0
                row[3 + k] = 0.5 * ((s if i == k else 0.0) + cross)
    return row


def fixed_hold_all(mesh, fixed, rel=1e-3):
    """True when the fixed coordinates alone clearly hold all six rigid motions:
    their rows of the rigid velocities span the six motions, each new direction
    with at least `rel` of its row's length left after the earlier ones are
    taken out (Gram-Schmidt).  A clamp does (its position rows hold the
    translations, its gradient rows the rotations), so a clamped scene needs no
    numpy (about 100 ms of a run that changes only numbers); anything less
    clear-cut is left to free_motions' SVDs, which decide as before."""
    if len(fixed) < 6:
        return False
    where, c = _coordinates(mesh)
    basis = []
    for d in fixed:
        row = _velocity_row(mesh.q0, where, c, d)
        n0 = sum(x * x for x in row) ** 0.5
        if n0 == 0.0:
            continue
        for b in basis:
            dot = sum(x * y for x, y in zip(row, b))
            row = [x - dot * y for x, y in zip(row, b)]
        n = sum(x * x for x in row) ** 0.5
        if n > rel * n0:
            basis.append([x / n for x in row])
            if len(basis) == 6:
                return True
    return False


def free_motions(mesh, fixed, lincons):
    """Descriptions of the rigid motions no constraint holds (empty: none).
    Only motions that move some coordinate count (a straight cable turning
    about its own axis moves none)."""
    if fixed_hold_all(mesh, fixed):
        return []
    import numpy as np
    modes = rigid_velocities(mesh)                       # 6 x ndof
    _u, s, vt = np.linalg.svd(modes.T, full_matrices=False)
    keep = s > 1e-12 * max(s[0], 1e-300)
    V = vt[keep].T / s[keep]                             # 6 x r: combinations of unit velocity field
    rows = [modes[:, d] for d in sorted(fixed)]
    for terms, _rhs, _tf in lincons:
        rows.append(sum(c0 * modes[:, d] for d, c0, _cc, _cs in terms))
    if not rows:                                         # nothing holds it: every motion that moves something
        return [NAMES[i] for i in range(6) if np.linalg.norm(modes[i]) > 1e-12 * max(s[0], 1e-300)]
    A = np.array(rows) @ V
    _u2, sv, vt2 = np.linalg.svd(A)
    rank = int(np.sum(sv > 1e-9 * max(1.0, sv[0] if len(sv) else 1.0)))
    basis = vt2[rank:]
    out = []
    for b in basis:
        m = V @ b                                          # the motion's six components
        m = m / np.linalg.norm(m)
        k = int(np.argmax(np.abs(m)))
        parts = [NAMES[i] for i in range(6) if abs(m[i]) > 0.2 * abs(m[k])]
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
