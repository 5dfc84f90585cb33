"""A rod's frame as programs: the centreline position and section frame at xi
(bk_rod_frame), the orthonormal section frame with its Jacobian
(bk_rod_section_frame) and a moment fixed in space on a node's quaternion."""
import sympy as sp

from gen.program import Program
from gen.rod import NQ, NODE_DOF, NX, PSI_Q, _named, _syms, lagrange, rotation
from gen.rodmath import Ch, Sh


# ----------------------------------------------------------------------------
# Element-level programs: frame, nodal moment, rotary inertia of a node

def frame_program():
    """pos[3], d[9] = (d1, d2, d3) at xi from q and psi[6]."""
    prog = Program()
    q, psi = _syms("q", NQ), _syms("psi", 6)
    xi = sp.Symbol("xi", real=True)
    N = lagrange(xi)
    ps = N[0] * sp.Matrix(psi[0:3]) + N[2] * sp.Matrix(psi[3:6])
    u = ps.dot(ps)
    R = rotation(q[10], sp.Matrix(q[11:14])) * rotation(Ch(u), Sh(u) * ps, unit=True)
    for i in range(3):
        prog.output(f"pos[{i}]", sum(N[n] * q[NODE_DOF * n + i] for n in range(3)), op="=")
    for k, col in enumerate((1, 2, 0)):        # d1, d2 (section axes), d3 (axis)
        for i in range(3):
            prog.output(f"d[{3 * k + i}]", R[i, col], op="=")
    return prog


def section_frame_program(jacobian):
    """R[9] = (e1, e2, e3) = (d1, d2, d3) of frame_program at xi, the rod's own
    rotation (orthonormal: no Gram-Schmidt), from q (p_c) and psi[6]; jacobian:
    also dR[nd*k + j] = dR_k/dq_j for the quaternion DOFs j (the others are
    zero, written by the caller), the total derivative through psi with its
    Jacobian J[48] (bk_rod_psi_j): dR/dp_c directly and through both psi_a,
    dR/dp_0 and dR/dp_2 through psi_0 and psi_2."""
    prog = Program()
    q, psi, J = _syms("q", NQ), _syms("psi", 6), _syms("J", 6 * NX)
    xi = sp.Symbol("xi", real=True)
    N = lagrange(xi)
    ps = N[0] * sp.Matrix(psi[0:3]) + N[2] * sp.Matrix(psi[3:6])
    u = ps.dot(ps)
    e_expr = [Ch(u)] + list(Sh(u) * ps)
    e = [prog.define(f"fe{c}", x) for c, x in enumerate(e_expr)]
    Rm = rotation(q[10], sp.Matrix(q[11:14])) * rotation(e[0], sp.Matrix(e[1:]), unit=True)
    R = [Rm[i, col] for col in (1, 2, 0) for i in range(3)]      # rows e1 = d1, e2 = d2, e3 = d3 (axis)
    for k in range(9):
        prog.output(f"R[{k}]", R[k], op="=")
    if not jacobian:
        return prog
    de = [[_named(prog, f"fde{c}_{m}", sp.diff(e_expr[c], psi[m])) for m in range(6)] for c in range(4)]
    for k in range(9):
        dRe = [_named(prog, f"fre{k}_{c}", sp.diff(R[k], e[c])) for c in range(4)]
        dpsi = [_named(prog, f"frp{k}_{m}", sum(dRe[c] * de[c][m] for c in range(4))) for m in range(6)]
        for j in sorted(set(PSI_Q[0]) | set(PSI_Q[1])):
            d = sp.diff(R[k], q[j]) if 10 <= j < 14 else 0
            for a in range(2):
                if j in PSI_Q[a]:
                    b = PSI_Q[a].index(j)
                    d += sum(dpsi[3 * a + kk] * J[(3 * a + kk) * NX + b] for kk in range(3))
            prog.output(f"dR[nd*{k} + {j}]", d, op="=")
    return prog


def moment_node_program():
    """Q[4], dQ[16] (row-major 4 x 4) of a moment M[3] fixed in space on the
    quaternion p[4] of a node."""
    from gen.loads import quaternion_moment
    prog = Program()
    p = _syms("p", 4)
    M = sp.Matrix(_syms("M", 3))
    Q = quaternion_moment(p[0], sp.Matrix(p[1:]), M)
    for i in range(4):
        prog.output(f"Q[{i}]", Q[i], op="=")
        for j in range(4):
            prog.output(f"dQ[{4 * i + j}]", sp.diff(Q[i], p[j]), op="=")
    return prog
