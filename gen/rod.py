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

Derivation: strains as functions of z = (r_0, r_1, r_2, p_c, psi_0, psi_2); the
psi_i as functions of (p_c, p_i); chain rule with sympy derivatives at both
levels, CSE over everything.
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


def strains_at(xi, r, pc, psi0, psi2, l):
    """(Gamma, K) at xi from node positions r[3], the middle quaternion pc and the
    relative rotation vectors of the end nodes."""
    N = lagrange(xi)
    dN = lagrange_d(xi)
    psi = N[0] * psi0 + N[2] * psi2
    dpsi = (dN[0] * psi0 + dN[2] * psi2) / l
    u = psi.dot(psi)
    du = 2 * psi.dot(dpsi)
    e = (Ch(u), Sh(u) * psi)
    de = (-Sh(u) / 4 * du, Sh1(u) * du * psi + Sh(u) * dpsi)
    kv = qmul(qconj(e), de)[1]
    K = 2 * kv
    R = rotation(*pc) * rotation(*e, unit=True)
    dr = sum((dN[n] * r[n] for n in range(3)), sp.zeros(3, 1)) / l
    G = R.T * dr
    return list(G), list(K), R


def frame_at(xi, r, pc, psi0, psi2):
    N = lagrange(xi)
    psi = N[0] * psi0 + N[2] * psi2
    u = psi.dot(psi)
    R = rotation(*pc) * rotation(Ch(u), Sh(u) * psi, unit=True)
    pos = sum((N[n] * r[n] for n in range(3)), sp.zeros(3, 1))
    return pos, R


def relative_rotation_vectors(prog, prefix):
    """Program definitions of psi_0, psi_2 from the nodal quaternions; returns their
    symbols and, for each, the expressions in the nodal quaternion symbols."""
    nodes = [node_syms(prefix, n) for n in range(3)]
    pc = (nodes[1][1], nodes[1][2])
    psis, exprs = [], []
    for i in (0, 2):
        s, v = qmul(qconj(pc), (nodes[i][1], nodes[i][2]))
        e = log_vector(s, v)
        exprs.append(e)
        psis.append(sp.Matrix([prog.define(f"psi{i}_{k}", e[k]) for k in range(3)]))
    return nodes, pc, psis, exprs


def tab_layout():
    """tab = [l, then per Gauss point Gamma0 (3), K0 (3)]."""
    return 1 + 6 * len(GAUSS)


def tabulate_program(elem):
    prog = Program()
    l = sp.Symbol("geom[0]", positive=True)
    prog.output("tab[0]", l, op="=")
    nodes, pc, psis, _ = relative_rotation_vectors(prog, "q0")
    r = [n[0] for n in nodes]
    for g, (xg, _) in enumerate(GAUSS):
        G, K, _ = strains_at(xg, r, pc, psis[0], psis[1], l)
        for k in range(3):
            prog.output(f"tab[{1 + 6 * g + k}]", G[k], op="=")
            prog.output(f"tab[{4 + 6 * g + k}]", K[k], op="=")
    return prog


def body_program(elem, mat, want):
    """Energy (want="energy"), force ("force") or force + tangent ("tangent") of one
    element, through the layers  q -> z = (r_n, p_c, psi_0, psi_2)  ->  w = (R_c^T r',
    e, e') per Gauss point  ->  strains  ->  energy (gen/chain.py)."""
    from gen.chain import pull_back
    prog = Program()
    nd, n21 = elem.ndof, 3 * NODE_DOF
    second = want == "tangent"
    q = [sp.Symbol(f"q[{i}]", real=True) for i in range(nd)]
    t = [sp.Symbol(f"tab[{i}]", real=True) for i in range(tab_layout())]
    params = {name: sp.Symbol(f"mat[{k}]", real=True) for k, name in enumerate(mat.PARAMS)}
    l = t[0]
    nodes = [node_syms("q", n) for n in range(3)]
    r = [n[0] for n in nodes]
    pc = (nodes[1][1], nodes[1][2])
    psi0 = sp.Matrix(sp.symbols("psi0_0:3", real=True))
    psi2 = sp.Matrix(sp.symbols("psi2_0:3", real=True))
    zs = list(r[0]) + list(r[1]) + list(r[2]) + [pc[0]] + list(pc[1]) + list(psi0) + list(psi2)
    lam = [q[n21 + i] for i in range(elem.ninternal)]
    c_lambda = params["EA"]

    U = 0
    Gz, Hz = {}, {}
    Gl, Hlz = {}, {}                     # multiplier gradient, d2U/dlambda dz
    for g, (xg, wg) in enumerate(GAUSS):
        N = lagrange(xg)
        dN = lagrange_d(xg)
        psi = N[0] * psi0 + N[2] * psi2
        dpsi = (dN[0] * psi0 + dN[2] * psi2) / l
        u = psi.dot(psi)
        du = 2 * psi.dot(dpsi)
        dr = sum((dN[n] * r[n] for n in range(3)), sp.zeros(3, 1)) / l
        y_e = rotation(*pc).T * dr
        e_e = [Ch(u)] + list(Sh(u) * psi)
        de_e = [-Sh(u) / 4 * du] + list(Sh1(u) * du * psi + Sh(u) * dpsi)
        ysym = sp.Matrix(sp.symbols(f"y{g}_0:3", real=True))
        esym = sp.symbols(f"e{g}_0:4", real=True)
        desym = sp.symbols(f"de{g}_0:4", real=True)
        wsyms = list(ysym) + list(esym) + list(desym)
        w_map = dict(zip(wsyms, list(y_e) + e_e + de_e))
        for x, v in w_map.items():          # values of the w layer
            prog.defs.append((x, v))
        ev = sp.Matrix(esym[1:])
        dev = sp.Matrix(desym[1:])
        Gam = rotation(esym[0], ev, unit=True).T * ysym
        Kap = 2 * (esym[0] * dev - desym[0] * ev - ev.cross(dev))
        strains = [Gam[k] - t[1 + 6 * g + k] for k in range(3)] + [Kap[k] - t[4 + 6 * g + k] for k in range(3)]
        ssyms = sp.symbols(f"s{g}_0:6", real=True)
        for x, v in zip(ssyms, strains):
            prog.defs.append((x, v))
        gs = dict(zip(STRAIN_NAMES, ssyms))
        W = mat.energy([gs["g1"], gs["g2"], gs["g3"]], [gs["k1"], gs["k2"], gs["k3"]], params)
        W = W.subs({gs[c]: 0 for c in elem.constrained})
        w = wg * l
        mult = {c: lam[len(elem.constrained) * g + j] for j, c in enumerate(elem.constrained)}
        L = w * (W + c_lambda * sum(mult[c] * gs[c] for c in elem.constrained))
        U += L
        if want == "energy":
            continue
        Gs = {x: sp.diff(L, x) for x in ssyms}
        Hs = {}
        if second:
            for a in range(6):
                for b in range(a, 6):
                    v = sp.diff(L, ssyms[a], ssyms[b])
                    if v != 0:
                        Hs[(ssyms[a], ssyms[b])] = v
        Gw, Hw = pull_back(prog, f"w{g}", Gs, Hs, dict(zip(ssyms, strains)), wsyms, second)
        Hw = {(wsyms[i], wsyms[j]): v for (i, j), v in Hw.items()}
        Gzg, Hzg = pull_back(prog, f"z{g}", Gw, Hw, w_map, zs, second)
        for b, v in Gzg.items():
            Gz[b] = Gz.get(b, 0) + v
        for k, v in Hzg.items():
            Hz[k] = Hz.get(k, 0) + v
        for c in elem.constrained:
            i = lam.index(mult[c])
            Gl[i] = w * c_lambda * gs[c]
            if second:
                Jw, _ = pull_back(prog, f"c{g}{c}w", {gs[c]: sp.Integer(1)}, {}, dict(zip(ssyms, strains)), wsyms, False)
                Jz, _ = pull_back(prog, f"c{g}{c}z", Jw, {}, w_map, zs, False)
                Hlz[i] = {b: w * c_lambda * v for b, v in Jz.items()}

    # quaternion gauge penalty
    cg = (params["GJ"] + params["EI1"] + params["EI2"]) / l
    gauge = 0
    for n, wn in zip(range(3), (sp.Rational(1, 2), 1, sp.Rational(1, 2))):
        s_, v_ = nodes[n][1], nodes[n][2]
        gauge += wn * cg / 4 * (s_**2 + v_.dot(v_) - 1)**2
    psi_map = {}
    for i, psym in ((0, psi0), (2, psi2)):
        s_, v_ = qmul(qconj(pc), (nodes[i][1], nodes[i][2]))
        e = log_vector(s_, v_)
        for k in range(3):
            psi_map[psym[k]] = e[k]
    for x, v in psi_map.items():           # values of the z layer
        prog.defs.insert(0, (x, v))
    if want == "energy":
        prog.output("e", U + gauge, op="=")
        return prog, params

    qn = q[:n21]
    Hz_sym = {(zs[i], zs[j]): v for (i, j), v in Hz.items()}
    Gq, Hq = pull_back(prog, "q", Gz, Hz_sym, psi_map, qn, second)
    f = [Gq.get(qn[i], 0) for i in range(n21)] + [Gl.get(i, 0) for i in range(elem.ninternal)]
    for i in range(n21):
        f[i] += sp.diff(gauge, q[i])
    for i in range(nd):
        if f[i] != 0:
            prog.output(f"f[{i}]", f[i], op="=")
    if not second:
        return prog, params
    K = dict(Hq)
    for i in range(n21):
        for j in range(i, n21):
            v = sp.diff(gauge, q[i], q[j])
            if v != 0:
                K[(i, j)] = K.get((i, j), 0) + v
    for i, Jz in Hlz.items():
        Jq, _ = pull_back(prog, f"lq{i}", Jz, {}, psi_map, qn, False)
        for b, v in Jq.items():
            K[(qn.index(b), n21 + i)] = v
    for (i, j), v in sorted(K.items()):
        prog.output(f"K[{i * nd + j}]", v, op="=")
    return prog, params
