"""Geometrically exact beams (seed 002, chapter 5): Timoshenko (Simo-Reissner),
Euler-Bernoulli and Kirchhoff, as one three-node element family.

Nodes at xi = 0, 1/2, 1 carry a position r (3) and a quaternion p (4, not
necessarily unit: the rotation is that of p/|p|).  Rotations are interpolated
relative to the middle node c (Jelenic and Crisfield): the end nodes' rotations
relative to it, psi_i = log(R_c^T R_i), are interpolated with the quadratic
Lagrange functions, R(xi) = R_c exp(psi(xi)).  The strains (Eqs. 5.29-5.30,
material components) are

    Gamma = R^T r' - Gamma0,        K = axial(R^T R') - K0,

at the two Gauss points (reduced integration: no shear locking), with r
interpolated quadratically and Gamma0, K0 the same measures of the reference
configuration (tabulated from it, so curved beams start stress free).  Rigid
motions leave Gamma and K unchanged (objectivity), the formulation is total
(no rotation increments, so no path dependence), and a constant curvature is
represented exactly: a roll-up under an end moment has the exact end rotation
for any number of elements.

The energy is the material's quadratic potential (Eq. 5.33) per unit length.
Euler-Bernoulli and Kirchhoff drop the shear (and axial) terms and enforce
Gamma_2 = Gamma_3 = 0 (and Gamma_1 = 0) at the Gauss points with Lagrange
multipliers, element-internal unknowns scaled by EA (Sections 5.4-5.5: perfect
bilateral constraints).  A penalty c (|p|^2 - 1)^2 / 4 per node (c = (GJ + EI1 +
EI2)/l) fixes the free scale of the quaternions; it does no work on the motion.

Derivation through the strain measures, in layers that are each differentiated
on their own (gen/chain.py):

    q  (21 nodal coordinates)
    z  = (r_0, r_1, r_2, p_c, psi_0, psi_2)   19   psi_i = log(conj(p_c) p_i)
    v  = (r', p_c, psi, psi')                 13   at a Gauss point, linear in z
    w  = (R_c^T r', e, e')                    11   e = exp(psi) as a quaternion
    s  = (Gamma - Gamma0, K - K0)              6

Everything up to s is the same for the three elements and every material: it
is emitted once, as the functions of out/kernels/rod_strain.c (strains, their
Jacobian B = ds/dv, the geometric term sum_k sigma_k d2 s_k / dv2, the
pull-back v -> z) and rod_common.c (psi and its derivatives, the pull-back
z -> q), with the rotary inertia in rod_inertia.c.  An element x material kernel only adds the energy as
a function of s (material law, multipliers): sigma = dL/ds, B^T D B with
D = d2L/ds2, and calls the shared kinematics in a loop over the Gauss points.
"""
from dataclasses import dataclass
from functools import lru_cache

import sympy as sp

from gen.program import Program
from gen.rodmath import At, Ch, Sh, Sh1

XI_NODES = (sp.Integer(0), sp.Rational(1, 2), sp.Integer(1))
GAUSS = ((sp.Rational(1, 2) - sp.sqrt(3) / 6, sp.Rational(1, 2)), (sp.Rational(1, 2) + sp.sqrt(3) / 6, sp.Rational(1, 2)))
NODE_DOF = 7                      # r (3) + p (4)
STRAIN_NAMES = ("g1", "g2", "g3", "k1", "k2", "k3")


@dataclass(frozen=True)
class RodElement:
    name: str
    title: str
    source: str
    constrained: tuple            # strain components held at zero by multipliers, e.g. ("g2", "g3")
    kind: str = "rod"
    material_kind: str = "resultant"
    rule_names: tuple = ("full",)
    default_rule: str = "full"

    @property
    def nnode(self):
        return 3

    @property
    def ninternal(self):
        return len(GAUSS) * len(self.constrained)

    @property
    def ndof(self):
        return 3 * NODE_DOF + self.ninternal

    def fields(self):
        out = []
        for n in range(3):
            out += [("r", NODE_DOF * n, 3), ("p", NODE_DOF * n + 3, 4)]
        out += [("lambda", 3 * NODE_DOF + i, 1) for i in range(self.ninternal)]
        return out


def lagrange(xi):
    return (2 * (xi - sp.Rational(1, 2)) * (xi - 1), -4 * xi * (xi - 1), 2 * xi * (xi - sp.Rational(1, 2)))


def lagrange_d(xi):
    return (4 * xi - 3, -8 * xi + 4, 4 * xi - 1)


def qmul(a, b):
    """Quaternion product of (s, v) pairs (v: 3x1 Matrix)."""
    s1, v1 = a
    s2, v2 = b
    return (s1 * s2 - v1.dot(v2), s1 * v2 + s2 * v1 + v1.cross(v2))


def qconj(a):
    return (a[0], -a[1])


def rotation(s, v, unit=False):
    """Rotation matrix of the quaternion (s, v) / |(s, v)| (unit: |(s, v)| = 1 known)."""
    n2 = 1 if unit else s**2 + v.dot(v)
    V = sp.Matrix([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return sp.eye(3) + 2 * (s * V + V * V) / n2


def log_vector(s, v):
    """Rotation vector of the quaternion (s, v): 2 atan2(|v|, s) v / |v|."""
    return 2 * At(v.dot(v), s) * v


def node_syms(prefix, n):
    r = sp.Matrix([sp.Symbol(f"{prefix}[{NODE_DOF * n + i}]", real=True) for i in range(3)])
    s = sp.Symbol(f"{prefix}[{NODE_DOF * n + 3}]", real=True)
    v = sp.Matrix([sp.Symbol(f"{prefix}[{NODE_DOF * n + 4 + i}]", real=True) for i in range(3)])
    return r, s, v


def tab_layout():
    """tab = [l, then per Gauss point Gamma0 (3), K0 (3)]."""
    return 1 + 6 * len(GAUSS)


# ----------------------------------------------------------------------------
# Layouts of the shared kinematics (out/kernels/rod_common.h documents them)

NZ = 19                 # z = (r_0, r_1, r_2 (9), p_c (4), psi_0 (3), psi_2 (3))
NV = 13                 # v = (r' (3), p_c (4), psi (3), psi' (3))
NW = 11                 # w = (y = R_c^T r' (3), e (4), e' (4))
NS = 6                  # s = (Gamma (3), K (3)) minus their reference values
NX = 8                  # arguments of psi_a: (p_c, p_i), i = 0 (a = 0) or 2 (a = 1)
NGC = 5                 # Gauss-point coefficients c = (N_0, N_2, N_0'/l, N_1'/l, N_2'/l)
PSI_Q = ((10, 11, 12, 13, 3, 4, 5, 6), (10, 11, 12, 13, 17, 18, 19, 20))   # q index of psi_a's arguments
NQ = 3 * NODE_DOF


def tri(n):
    """{(i, j): k} packed row-major upper triangle of an n x n matrix (i <= j)."""
    out, k = {}, 0
    for i in range(n):
        for j in range(i, n):
            out[(i, j)] = k
            k += 1
    return out


def _sym(name, i):
    return sp.Symbol(f"{name}[{i}]", real=True)


def _syms(name, n):
    return [_sym(name, i) for i in range(n)]


def _tri_sym(name, n):
    """Symmetric access (i, j) -> symbol name[packed index] of an upper triangle."""
    t = tri(n)
    return lambda i, j: _sym(name, t[(min(i, j), max(i, j))])


def gauss_table():
    """Per Gauss point (N_0, N_2, N_0', N_1', N_2', weight) at xi_g (exact)."""
    rows = []
    for xg, wg in GAUSS:
        N, dN = lagrange(xg), lagrange_d(xg)
        rows.append((N[0], N[2], dN[0], dN[1], dN[2], wg))
    return rows


def _named(prog, name, expr):
    expr = sp.sympify(expr)
    return expr if expr.is_Atom else prog.define(name, expr)


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


# ----------------------------------------------------------------------------
# Quaternion gauge penalty  sum_n w_n cg/4 (|p_n|^2 - 1)^2,  w = (1/2, 1, 1/2)

def _gauge():
    q = _syms("q", NQ)
    cg = sp.Symbol("cg", real=True)
    U = 0
    for n, wn in zip(range(3), (sp.Rational(1, 2), 1, sp.Rational(1, 2))):
        p = q[NODE_DOF * n + 3: NODE_DOF * n + 7]
        U += wn * cg / 4 * (sum(x * x for x in p) - 1)**2
    return q, U


def gauge_program(order):
    """order 0: ge = U; 1: f[i] += dU/dq_i; 2: K[nd*i + j] += d2U/dq_i dq_j (i <= j)."""
    q, U = _gauge()
    prog = Program()
    if order == 0:
        prog.output("ge", U, op="=")
    elif order == 1:
        for i in range(NQ):
            d = sp.diff(U, q[i])
            if d != 0:
                prog.output(f"f[{i}]", d, op="+=")
    else:
        for i in range(NQ):
            for j in range(i, NQ):
                d = sp.diff(U, q[i], q[j])
                if d != 0:
                    prog.output(f"K[nd*{i} + {j}]", d, op="+=")
    return prog


def gauge_coefficient(params):
    """cg of the gauge penalty from the material parameters and l = tab[0]."""
    return (params["GJ"] + params["EI1"] + params["EI2"]) / _sym("tab", 0)


# ----------------------------------------------------------------------------
# Element x material: the energy as a function of the strains

def material_programs(elem, mat):
    """Programs of one Gauss point of an element x material kernel, in the symbols
    s[6], B[...], lam[nc] (the point's multipliers), w (weight x l), mat[...]:
      "energy":  e += w (W(s) + c_l sum_j lam_j s_cj)
      "force":   sg[6] = dL/ds; Gv[13] = B^T sg (tangent path only); fl[j] = dL/dlam_j
      "tangent": Hv[tri13] += B^T D B (D = d2L/ds2); C[13 j + a] = d fl_j / dv_a
    (c_l = EA scales the multipliers), and the parameter symbols."""
    params = {name: _sym("mat", k) for k, name in enumerate(mat.PARAMS)}
    s = _syms("s", NS)
    lam = _syms("lam", len(elem.constrained))
    w = sp.Symbol("w", real=True)
    gs = dict(zip(STRAIN_NAMES, s))
    W = mat.energy([gs["g1"], gs["g2"], gs["g3"]], [gs["k1"], gs["k2"], gs["k3"]], params)
    W = W.subs({gs[c]: 0 for c in elem.constrained})
    cl = params["EA"]
    L = w * (W + cl * sum(lam[j] * gs[c] for j, c in enumerate(elem.constrained)))
    pattern = b_pattern()
    Bs = {(k, a): _sym("B", k * NV + a) for k, a in pattern}

    pe = Program()
    pe.output("e", L, op="+=")

    pf = Program()
    sg = []
    for k in range(NS):
        sg.append(_named(pf, f"sig{k}", sp.diff(L, s[k])))
        pf.output(f"sg[{k}]", sg[k], op="=")
    for a in range(NV):
        pf.output(f"Gv[{a}]", sum(sg[k] * Bs[(k, a)] for k in range(NS) if (k, a) in Bs), op="=")
    for j, c in enumerate(elem.constrained):
        pf.output(f"fl[{j}]", sp.diff(L, lam[j]), op="=")

    pk = Program()
    D = {(k, l): sp.diff(L, s[k], s[l]) for k in range(NS) for l in range(NS)}
    DB = {}
    for k in range(NS):
        for b in range(NV):
            e = sum(D[(k, l)] * Bs[(l, b)] for l in range(NS) if (l, b) in Bs and D[(k, l)] != 0)
            if e != 0:
                DB[(k, b)] = _named(pk, f"DB{k}_{b}", e)
    for (a, b), i in tri(NV).items():
        e = sum(Bs[(k, a)] * DB[(k, b)] for k in range(NS) if (k, a) in Bs and (k, b) in DB)
        if e != 0:
            pk.output(f"Hv[{i}]", e, op="+=")
    for j, c in enumerate(elem.constrained):
        k = STRAIN_NAMES.index(c)
        g = sp.diff(L, lam[j], s[k])
        for a in range(NV):
            pk.output(f"C[{NV * j + a}]", g * Bs[(k, a)] if (k, a) in Bs else 0, op="=")
    return {"energy": pe, "force": pf, "tangent": pk}, params


def section_program(elem, mat):
    """The stress resultants at a Gauss point in the material frame, rs[6] =
    (n1, n2, n3, m1, m2, m3) (components along d3, d1, d2: N, Q2, Q3, T, M2,
    M3), from s[6], lam[nc] and mat[...]: dW/ds of the law for the free strain
    components, EA lam_j (the force the multiplier of Gamma_j = 0 exerts, the
    resultant conjugate to that component in the constrained energy) for the
    components held at zero.  Returns (program, parameter symbols)."""
    params = {name: _sym("mat", k) for k, name in enumerate(mat.PARAMS)}
    s = _syms("s", NS)
    lam = _syms("lam", len(elem.constrained))
    gs = dict(zip(STRAIN_NAMES, s))
    W = mat.energy([gs["g1"], gs["g2"], gs["g3"]], [gs["k1"], gs["k2"], gs["k3"]], params)
    W = W.subs({gs[c]: 0 for c in elem.constrained})
    prog = Program()
    for k, name in enumerate(STRAIN_NAMES):
        if name in elem.constrained:
            e = params["EA"] * lam[elem.constrained.index(name)]
        else:
            e = sp.diff(W, s[k])
        prog.output(f"rs[{k}]", e, op="=")
    return prog, params


def section_source_label(elem):
    """What the rows of sections.csv from sections() hold: "law" (n = C Gamma,
    m = D K), with the components held at zero by multipliers named."""
    names = dict(zip(STRAIN_NAMES, ("N", "Q2", "Q3")))
    if not elem.constrained:
        return "law"
    return "law;multiplier:" + " ".join(names[c] for c in elem.constrained)


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


def rotary_node_program():
    """Rotary inertia of one node with inertia Jn[3] = w_n l (Ip, I1, I2) per unit
    density: T = 1/2 W^T diag(Jn) W with the body angular velocity
    W = 2 g / |p|^2, g = Im(conj(p) p'); f[4] = d/dt dT/dp' - dT/dp, Mq = df/dp'',
    Cq = df/dp', Kq = df/dp (4 x 4 row-major), T[0].

    Written in the intermediates ni = 1/|p|^2, n2' = 2 p.p', g and
    g' = Im(conj(p) p'') (conj(p')p' is real): with dg/dp' = G(p), dg/dp = -G(p'),
        dT/dp' = 2 ni G(p)^T J W,   dT/dp = 2 ni (-G(p')^T J W) - 4 ni^2 p (g . J W),
    the time derivative of the first by the product rule; the Jacobians of f by
    the chain rule through the intermediates (gen/chain.py)."""
    from gen.chain import pull_back
    prog = Program()
    Jn = _syms("Jn", 3)
    p, pd, pdd = _syms("p", 4), _syms("pd", 4), _syms("pdd", 4)

    def im(a, b):
        return list(qmul(qconj((a[0], sp.Matrix(a[1:]))), (b[0], sp.Matrix(b[1:])))[1])
    ni, n2d = sp.symbols("ni n2d", real=True)
    g = sp.symbols("g0:3", real=True)
    gd = sp.symbols("gd0:3", real=True)
    umap = {ni: 1 / sum(x * x for x in p), n2d: 2 * sum(a * b for a, b in zip(p, pd))}
    umap.update(dict(zip(g, im(p, pd))))
    umap.update(dict(zip(gd, im(p, pdd))))
    for x, e in umap.items():
        prog.defs.append((x, e))
    W = [2 * g[k] * ni for k in range(3)]
    Wd = [2 * (gd[k] * ni - g[k] * n2d * ni**2) for k in range(3)]
    gexpr = im(p, pd)
    G = [[sp.diff(gexpr[k], pd[i]) for i in range(4)] for k in range(3)]      # G(p), linear in p
    Gd = [[sp.diff(gexpr[k], p[i]) for i in range(4)] for k in range(3)]      # -G(p')
    to_pd = dict(zip(p, pd))
    JW = [Jn[k] * W[k] for k in range(3)]
    JWd = [Jn[k] * Wd[k] for k in range(3)]
    nid = -n2d * ni**2
    y = list(p) + list(pd) + list(pdd)
    for i in range(4):
        dpi = sum(2 * (nid * JW[k] * G[k][i] + ni * JWd[k] * G[k][i]
                       + ni * JW[k] * G[k][i].xreplace(to_pd)) for k in range(3))
        dTdp = sum(JW[k] * (2 * Gd[k][i] * ni - 4 * g[k] * p[i] * ni**2) for k in range(3))
        fi = dpi - dTdp
        prog.output(f"f[{i}]", fi, op="=")
        outer = sorted(fi.free_symbols & (set(y) | set(umap)), key=lambda x: x.name)
        Gy, _ = pull_back(prog, f"f{i}", {x: sp.diff(fi, x) for x in outer}, {}, umap, y, False)
        for arr, var in (("Mq", pdd), ("Cq", pd), ("Kq", p)):
            for j in range(4):
                prog.output(f"{arr}[{4 * i + j}]", Gy.get(var[j], 0), op="=")
    prog.output("T[0]", sum(Jn[k] * W[k]**2 for k in range(3)) / 2, op="=")
    return prog
