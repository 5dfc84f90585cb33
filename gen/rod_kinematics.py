"""The rods' shared kinematics as programs (the functions of out/kernels/rod_strain.c
and rod_common.c): psi_a = log(conj(p_c) p_i) with its derivatives, the Gauss
point's v, strains s(v), their Jacobian B and geometric term, and the pull-backs
v -> z -> q (layouts in gen/rod.py)."""
from functools import lru_cache

import sympy as sp

from gen.program import Program
from gen.rod import (NODE_DOF, NQ, NGC, NS, NV, NX, NZ, PSI_Q, _named, _sym, _syms, _tri_sym, log_vector, qconj, qmul,
                     rotation, tri)
from gen.rodmath import Ch, Sh, Sh1


# ----------------------------------------------------------------------------
# psi_a = log(conj(p_c) p_i) and its first and second derivatives

def _psi_layers(a):
    """(x, rq symbols, {rq: expr in x}, psi_a as expressions in rq) of psi_a."""
    q = _syms("q", NQ)
    x = [q[i] for i in PSI_Q[a]]
    s_, v_ = qmul(qconj((x[0], sp.Matrix(x[1:4]))), (x[4], sp.Matrix(x[5:8])))
    rq = sp.symbols(f"rq{a}_0:4", real=True)
    return x, list(rq), dict(zip(rq, [s_] + list(v_))), log_vector(rq[0], sp.Matrix(rq[1:]))


def psi_program(order):
    """psi[6] (psi_0, psi_2) from q; order 1: also J[(3a+k)*8 + b] = d psi_a,k / d x_b
    with x = q[PSI_Q[a]] (chain rule through the relative quaternion
    rq = conj(p_c) p_i, bilinear in x)."""
    from gen.chain import pull_back
    prog = Program()
    for a in range(2):
        x, rq, rq_map, psi = _psi_layers(a)
        for sym, e in rq_map.items():
            prog.defs.append((sym, e))
        for k in range(3):
            prog.output(f"psi[{3 * a + k}]", psi[k], op="=")
            if order == 0:
                continue
            ps = sp.Symbol(f"ps{a}_{k}", real=True)
            Gr, _ = pull_back(prog, f"r{a}{k}", {ps: sp.Integer(1)}, {}, {ps: psi[k]}, rq, False)
            Gx, _ = pull_back(prog, f"x{a}{k}", Gr, {}, rq_map, x, False)
            for b in range(NX):
                prog.output(f"J[{(3 * a + k) * NX + b}]", Gx.get(x[b], 0), op="=")
    return prog


def psi_hessian_program():
    """Hc[36 a + tri8(b, c)] = sum_k Gz[13 + 3a + k] d2 psi_a,k / dx_b dx_c: the
    second derivatives of psi contracted with the gradient in z (what the
    pull-back z -> q needs), one upper triangle per end node."""
    from gen.chain import pull_back
    prog = Program()
    Gz = _syms("Gz", NZ)
    t8 = tri(NX)
    for a in range(2):
        x, rq, rq_map, psi = _psi_layers(a)
        for sym, e in rq_map.items():
            prog.defs.append((sym, e))
        ps = sp.symbols(f"ps{a}_0:3", real=True)
        Gr, Hr = pull_back(prog, f"r{a}", {ps[k]: Gz[13 + 3 * a + k] for k in range(3)}, {},
                           {ps[k]: psi[k] for k in range(3)}, rq, True)
        Hr = {(rq[i], rq[j]): v for (i, j), v in Hr.items()}
        _, Hx = pull_back(prog, f"x{a}", Gr, Hr, rq_map, x, True)
        for (b, c), i in t8.items():
            prog.output(f"Hc[{len(t8) * a + i}]", Hx.get((b, c), 0), op="=")
    return prog


# ----------------------------------------------------------------------------
# Gauss point: v from z, strains s(v), Jacobian B, geometric term

def v_program():
    """v[13] at a Gauss point from q (r, p_c), psi[6] and c[5]."""
    prog = Program()
    q, psi, c = _syms("q", NQ), _syms("psi", 6), _syms("c", NGC)
    for i in range(3):
        prog.output(f"v[{i}]", sum(c[2 + n] * q[NODE_DOF * n + i] for n in range(3)), op="=")
    for j in range(4):
        prog.output(f"v[{3 + j}]", q[10 + j], op="=")
    for k in range(3):
        prog.output(f"v[{7 + k}]", c[0] * psi[k] + c[1] * psi[3 + k], op="=")
        prog.output(f"v[{10 + k}]", c[2] * psi[k] + c[4] * psi[3 + k], op="=")
    return prog


def p_matrix():
    """{v index: {z index: coefficient}} of the linear map v = P z."""
    c = _syms("c", NGC)
    P = {}
    for i in range(3):
        P[i] = {3 * n + i: c[2 + n] for n in range(3)}
    for j in range(4):
        P[3 + j] = {9 + j: sp.Integer(1)}
    for k in range(3):
        P[7 + k] = {13 + k: c[0], 16 + k: c[1]}
        P[10 + k] = {13 + k: c[2], 16 + k: c[4]}
    return P


def _strain_layers():
    """(v symbols, w symbols, {w: expr in v}, s as expressions in w)."""
    v = _syms("v", NV)
    rp, pc = sp.Matrix(v[0:3]), (v[3], sp.Matrix(v[4:7]))
    psi, dpsi = sp.Matrix(v[7:10]), sp.Matrix(v[10:13])
    u = psi.dot(psi)
    du = 2 * psi.dot(dpsi)
    y_e = rotation(*pc).T * rp
    e_e = [Ch(u)] + list(Sh(u) * psi)
    de_e = [-Sh(u) / 4 * du] + list(Sh1(u) * du * psi + Sh(u) * dpsi)
    ysym = sp.Matrix(sp.symbols("y0:3", real=True))
    esym = sp.symbols("e0:4", real=True)
    desym = sp.symbols("de0:4", real=True)
    wsyms = list(ysym) + list(esym) + list(desym)
    w_map = dict(zip(wsyms, list(y_e) + e_e + de_e))
    ev, dev = sp.Matrix(esym[1:]), sp.Matrix(desym[1:])
    Gam = rotation(esym[0], ev, unit=True).T * ysym
    Kap = 2 * (esym[0] * dev - desym[0] * ev - ev.cross(dev))
    return v, wsyms, w_map, list(Gam) + list(Kap)


@lru_cache(maxsize=None)
def strain_jacobian():
    """(Program defining the w layer and its Jacobians, {(k, a): B_ka expr}) with
    B = ds/dv = ds/dw dw/dv; only the structurally nonzero entries."""
    v, wsyms, w_map, s_w = _strain_layers()
    prog = Program()
    for x, e in w_map.items():
        prog.defs.append((x, e))
    Jwv = {}
    for i, x in enumerate(wsyms):
        for a in range(NV):
            d = sp.diff(w_map[x], v[a])
            if d != 0:
                Jwv[(i, a)] = _named(prog, f"jw{i}_{a}", d)
    B = {}
    for k in range(NS):
        for i, x in enumerate(wsyms):
            d = sp.diff(s_w[k], x)
            if d == 0:
                continue
            d = _named(prog, f"js{k}_{i}", d)
            for a in range(NV):
                if (i, a) in Jwv:
                    B[(k, a)] = B.get((k, a), 0) + d * Jwv[(i, a)]
    return prog, B


def b_pattern():
    """Sorted (k, a) of the structurally nonzero entries of B[k*13 + a]."""
    return sorted(strain_jacobian()[1])


def strain_program(order):
    """s[6] = strains - t0 from v (order 0); order 1: also B[6*13] (all entries written)."""
    v, wsyms, w_map, s_w = _strain_layers()
    t0 = _syms("t0", NS)
    if order == 0:
        prog = Program()
        for x, e in w_map.items():
            prog.defs.append((x, e))
    else:
        base, B = strain_jacobian()
        prog = Program()
        prog.defs = list(base.defs)
    for k in range(NS):
        prog.output(f"s[{k}]", s_w[k] - t0[k], op="=")
    if order >= 1:
        for k in range(NS):
            for a in range(NV):
                prog.output(f"B[{k * NV + a}]", B.get((k, a), 0), op="=")
    return prog


def strain_gradient_program():
    """Gv[13] = sum_k sg_k ds_k/dv (reverse mode through w: the force without B)."""
    from gen.chain import pull_back
    v, wsyms, w_map, s_w = _strain_layers()
    prog = Program()
    for x, e in w_map.items():
        prog.defs.append((x, e))
    sg = _syms("sg", NS)
    ssyms = sp.symbols("st0:6", real=True)
    Gw, _ = pull_back(prog, "w", dict(zip(ssyms, sg)), {}, dict(zip(ssyms, s_w)), wsyms, False)
    Gv, _ = pull_back(prog, "v", Gw, {}, w_map, v, False)
    for a in range(NV):
        prog.output(f"Gv[{a}]", Gv.get(v[a], 0), op="=")
    return prog


def geometric_program():
    """Hv[tri13] = sum_k sg_k d2 s_k / dv2 (upper triangle, all 91 entries written)."""
    from gen.chain import pull_back
    v, wsyms, w_map, s_w = _strain_layers()
    prog = Program()
    for x, e in w_map.items():
        prog.defs.append((x, e))
    sg = _syms("sg", NS)
    ssyms = sp.symbols("st0:6", real=True)
    Gw, Hw = pull_back(prog, "w", dict(zip(ssyms, sg)), {}, dict(zip(ssyms, s_w)), wsyms, True)
    Hw = {(wsyms[i], wsyms[j]): h for (i, j), h in Hw.items()}
    _, Hv = pull_back(prog, "v", Gw, Hw, w_map, v, True)
    for (a, b), i in tri(NV).items():
        prog.output(f"Hv[{i}]", Hv.get((a, b), 0), op="=")
    return prog


# ----------------------------------------------------------------------------
# Pull-backs v -> z (per Gauss point, accumulated) and z -> q

def grad_v2z_program():
    """Gz[19] += P^T Gv."""
    prog = Program()
    Gv = _syms("Gv", NV)
    acc = {}
    for a, row in p_matrix().items():
        for b, p in row.items():
            acc[b] = acc.get(b, 0) + p * Gv[a]
    for b in range(NZ):
        prog.output(f"Gz[{b}]", acc[b], op="+=")
    return prog


def hess_v2z_program():
    """Hz[tri19] += P^T Hv P (upper triangles)."""
    prog = Program()
    Hv = _tri_sym("Hv", NV)
    P = p_matrix()
    cols = {}                                     # z index -> [(v index, coefficient)]
    for a, row in P.items():
        for b, p in row.items():
            cols.setdefault(b, []).append((a, p))
    for (b, b2), i in tri(NZ).items():
        e = sum(p * p2 * Hv(a, a2) for a, p in cols[b] for a2, p2 in cols[b2])
        prog.output(f"Hz[{i}]", e, op="+=")
    return prog


def z_jacobian():
    """{z index: {q index: dz/dq}} with the psi rows as the symbols J[...]."""
    Jz = {}
    for n in range(3):
        for i in range(3):
            Jz[3 * n + i] = {NODE_DOF * n + i: sp.Integer(1)}
    for j in range(4):
        Jz[9 + j] = {10 + j: sp.Integer(1)}
    for a in range(2):
        for k in range(3):
            Jz[13 + 3 * a + k] = {PSI_Q[a][b]: _sym("J", (3 * a + k) * NX + b) for b in range(NX)}
    return Jz


def grad_z2q_program():
    """g[21] = J^T Gz."""
    prog = Program()
    Gz = _syms("Gz", NZ)
    acc = {}
    for z, row in z_jacobian().items():
        for i, d in row.items():
            acc[i] = acc.get(i, 0) + d * Gz[z]
    for i in range(NQ):
        prog.output(f"g[{i}]", acc.get(i, 0), op="=")
    return prog


def hess_z2q_program():
    """K[nd*i + j] = (J^T Hz J)_ij + Hc (psi_hessian_program), i <= j < 21,
    computed as J^T (Hz J) with only the needed entries of Hz J."""
    prog = Program()
    Hz = _tri_sym("Hz", NZ)
    Jz = z_jacobian()
    rows = {}                                     # q index -> [(z index, dz/dq)]
    for z, row in Jz.items():
        for i, d in row.items():
            rows.setdefault(i, []).append((z, d))
    T = {}

    def t(z, j):                                 # (Hz J)[z][j]
        if (z, j) not in T:
            T[(z, j)] = _named(prog, f"T{z}_{j}", sum(Hz(z, z2) * d for z2, d in rows[j]))
        return T[(z, j)]

    t8 = tri(NX)
    for i in range(NQ):
        for j in range(i, NQ):
            e = sum(d * t(z, j) for z, d in rows[i])
            for a in range(2):
                if i in PSI_Q[a] and j in PSI_Q[a]:
                    b, c = sorted((PSI_Q[a].index(i), PSI_Q[a].index(j)))
                    e += _sym("Hc", len(t8) * a + t8[(b, c)])
            prog.output(f"K[nd*{i} + {j}]", e, op="=")
    return prog
