"""A rod's frame as programs: the centreline position and section frame at xi
(bk_rod_frame), the orthonormal section frame with its Jacobian
(bk_rod_section_frame), a moment fixed in space on a node's quaternion, and the
tangent of a material line fixed in the sections with its derivatives
(bk_rod_section_line: tendons and chambers on rods)."""
import sympy as sp

from gen.program import Program
from gen.rod import NQ, NODE_DOF, NX, PSI_Q, _named, _syms, lagrange, rotation, tri
from gen.rodmath import Ch, Sh, Sh1


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


# ----------------------------------------------------------------------------
# A material line fixed in the sections (tendons, chambers): its tangent

def _line_layers():
    """(v symbols, w symbols, {w: expr in v}, t as expressions in w) of the
    tangent t = dP/dxi of the line P = r + R (0, a1, a2) at a point with
    coefficients c (v = (r', p_c, psi, psi') of bk_rod_v): t = r' + R_c (dR_e/dxi) A,
    R_e the rotation of e = exp(psi), differentiated along the unit curve e(xi)
    (de as in the strain kinematics); r' and p_c pass through."""
    v = _syms("v", 13)
    a = _syms("a", 2)
    psi, dpsi = sp.Matrix(v[7:10]), sp.Matrix(v[10:13])
    u = psi.dot(psi)
    du = 2 * psi.dot(dpsi)
    e_e = [Ch(u)] + list(Sh(u) * psi)
    de_e = [-Sh(u) / 4 * du] + list(Sh1(u) * du * psi + Sh(u) * dpsi)
    esym = sp.symbols("le0:4", real=True)
    desym = sp.symbols("lde0:4", real=True)
    w_map = dict(zip(list(esym) + list(desym), e_e + de_e))
    Re = rotation(esym[0], sp.Matrix(esym[1:]), unit=True)
    dRe = sum((sp.diff(Re, esym[c]) * desym[c] for c in range(4)), sp.zeros(3, 3))
    A = sp.Matrix([0, a[0], a[1]])
    t = sp.Matrix(v[0:3]) + rotation(v[3], sp.Matrix(v[4:7])) * (dRe * A)
    wsyms = list(v[0:7]) + list(esym) + list(desym)
    return v, wsyms, w_map, list(t)


def line_program():
    """t[3] = dP/dxi and Dv[3*13] = dt/dv (row-major) of the line at the offset
    a[2] from v[13] (bk_rod_v with c = (N_0, N_2, N_0', N_1', N_2') at xi)."""
    from gen.chain import pull_back
    v, wsyms, w_map, t = _line_layers()
    prog = Program()
    for x, e in w_map.items():
        prog.defs.append((x, e))
    for k in range(3):
        prog.output(f"t[{k}]", t[k], op="=")
        tk = sp.Symbol(f"lt{k}", real=True)
        Gw, _ = pull_back(prog, f"lw{k}", {tk: sp.Integer(1)}, {}, {tk: t[k]}, wsyms, False)
        Gv, _ = pull_back(prog, f"lv{k}", Gw, {}, w_map, v, False)
        for b in range(13):
            prog.output(f"Dv[{13 * k + b}]", Gv.get(v[b], 0), op="=")
    return prog


def line_hessian_program(part=None):
    """Hv[tri13] = d2(u . t)/dv2 (upper triangle) of the line's tangent
    contracted with u[3]: all 91 entries, or (part 0, 1) those of rows a < 4,
    a >= 4 (two functions of a size that compiles fast)."""
    from gen.chain import pull_back
    v, wsyms, w_map, t = _line_layers()
    uu = _syms("u", 3)
    prog = Program()
    for x, e in w_map.items():
        prog.defs.append((x, e))
    phi = sp.Symbol("lphi", real=True)
    Gw, Hw = pull_back(prog, "lw", {phi: sp.Integer(1)}, {}, {phi: sum(uu[k] * t[k] for k in range(3))}, wsyms,
                       True)
    Hw = {(wsyms[i], wsyms[j]): h for (i, j), h in Hw.items()}
    _, Hv = pull_back(prog, "lv", Gw, Hw, w_map, v, True)
    for (a, b), i in tri(13).items():
        if part is None or (a < LINE_HESS_SPLIT) == (part == 0):
            prog.output(f"Hv[{i}]", Hv.get((a, b), 0), op="=")
    return prog


LINE_HESS_SPLIT = 4           # rows of Hv in line_hessian_program's part 0
