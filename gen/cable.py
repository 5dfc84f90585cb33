"""The ANCF gradient-deficient beam ("cable"): 2 nodes x (r, r_x), 12 DOF, the
cubic Hermite interpolation of seed 001 Eqs. (4)-(6), stress free in its
reference configuration, straight or curved.

Energy per unit reference arc length, at Gauss points along the axis
(x in [0, l] the element's parameter, a = r', b = r'', c = a x b):
    W = 1/2 EA eps^2 + 1/2 EI (kappa - kappa0)^2,
    eps = |a| / |a0| - 1,    kappa = |c| / |a|^3,
and dS = |a0| dx, with a0, kappa0 those of the Hermite interpolation of the
reference coordinates q0 at that point (tabulated from q0: an interpolated arc
is not parametrised by arc length exactly, and its curvature is not exactly
1/R).  Expanded, (kappa - kappa0)^2 = |c|^2/|a|^6 - 2 kappa0 |c|/|a|^3 +
kappa0^2; the middle term, not differentiable at c = 0, uses
sqrt(|c|^2 + eta), eta = (1e-8 |c0|)^2 (an error of 5e-17 relative in the
reference's stationarity).  A straight reference (kappa0 l below 1e-10 plus
the turn round-off in r1 - r0 can fake, 2.2e-13 (|r0| + |r1|)/l) has
kappa0 = 0, the exact energy 1/2 EA eps^2 + 1/2 EI kappa^2 (kappa^2 is a smooth
function of q, so the element is well defined for straight configurations).
Only the curvature's magnitude is compared: the cable has no section frame, and
|a|, a.b, |b| are the only invariants of (a, b) under rotation, so an objective
energy of (a, b) sees no bending plane: the element is a rod free to twist
(GJ = 0), one bending stiffness (EI1 = EI2 is required), and no torsion.
Forces and tangents are derived analytically: W as a function of (r', r''),
chained through the constant shape-function derivatives.
"""
from dataclasses import dataclass
from functools import lru_cache

import sympy as sp

from gen.element import ContinuumElement, Node, XI, L, geom_symbol, shape_functions
from gen.program import Program
from gen.quadrature import gauss_unit

NGAUSS = 4


@dataclass(frozen=True)
class CableElement:
    name: str
    title: str
    source: str
    kind: str = "cable"
    material_kind: str = "resultant"
    rule_names: tuple = ("full",)
    default_rule: str = "full"

    @property
    def nnode(self):
        return 2

    @property
    def ndof(self):
        return 12

    @property
    def ninternal(self):
        return 0

    def fields(self):
        return [("r", 0, 3), ("r_x", 3, 3), ("r", 6, 3), ("r_x", 9, 3)]


HERMITE = ContinuumElement(name="hermite", title="", source="",
                           basis=((0, 0, 0), (1, 0, 0), (2, 0, 0), (3, 0, 0)),
                           nodes=(Node(sp.Integer(0), ("r", "r_x")), Node(sp.Integer(1), ("r", "r_x"))))


@lru_cache(maxsize=None)
def hermite():
    """(N, dN/dx, d2N/dx2) as expressions in xi and l."""
    N = shape_functions(HERMITE)
    d1 = tuple(sp.diff(n, XI) / L for n in N)
    d2 = tuple(sp.diff(n, XI, 2) / L**2 for n in N)
    return N, d1, d2


# Per Gauss point: w l |a0|, N'_a (4), N''_a (4), 1/|a0|, kappa0, eta, |a0|', kappa0'
STRIDE = 14
BETA = 1e-8             # sqrt(eta) = BETA |c0|
STRAIGHT = 1e-10        # kappa0 l below it (plus round-off's): a straight reference, kappa0 = 0
ROUNDOFF_TURN = 1000 * 2.0**-52     # times (|r0| + |r1|)/l: the turn round-off can fake


class CurvedFlag(sp.Function):
    """1 where the reference turns by at least STRAIGHT over the element
    (argument kappa0 l less the turn round-off can fake), else 0: the C helper
    curved_flag() of the element file."""
    nargs = 1
    c_name = "curved_flag"


def tab_layout():
    return NGAUSS * STRIDE


def hermite3():
    """d3N/dx3 as expressions in l (constants of the cubic)."""
    N, _, _ = hermite()
    return tuple(sp.diff(n, XI, 3) / L**3 for n in N)


def tabulate_program():
    """tab[] from geom[BK_GEOM_L] and the reference coordinates q0: the reference's
    Hermite interpolation at each Gauss point, its positions entering as the
    difference r1 - r0 (N1 + N3 = 1: round-off relative to the element, not to
    the distance from the origin)."""
    prog = Program()
    l = geom_symbol("L")
    q0 = [sp.Symbol(f"q0[{i}]", real=True) for i in range(12)]
    d = [prog.define(f"d{i}", q0[6 + i] - q0[i]) for i in range(3)]
    N, d1, d2 = hermite()

    def interp(D, sub, name):
        # sum_a D_a q0_a with D_0 = -D_2 (derivatives of the partition of unity)
        return sp.Matrix([prog.define(f"{name}{i}", (D[2] * d[i] + D[1] * q0[3 + i] + D[3] * q0[9 + i]).subs(sub))
                          for i in range(3)])

    c3 = interp(hermite3(), {L: l}, "c3_")
    # the turn that round-off in r1 - r0 can fake: elements far from the origin
    # against their length (1 mm at 1e5 m: 4e-8 rad)
    noise = prog.define("noise", ROUNDOFF_TURN * (sp.sqrt(sum(v**2 for v in q0[0:3]))
                                                  + sp.sqrt(sum(v**2 for v in q0[6:9]))) / l)
    for g, (xg, wg) in enumerate(gauss_unit(NGAUSS)):
        base = STRIDE * g
        sub = {XI: sp.Float(xg), L: l}
        a0 = interp(d1, sub, f"a{g}_")
        b0 = interp(d2, sub, f"b{g}_")
        g0 = prog.define(f"g{g}", sp.sqrt(a0.dot(a0)))
        cr = a0.cross(b0)
        nc = prog.define(f"nc{g}", sp.sqrt(cr.dot(cr)))
        flag = prog.define(f"fl{g}", CurvedFlag(nc / g0**3 * l - noise))
        dg0 = prog.define(f"dg{g}", a0.dot(b0) / g0)
        dnc = cr.dot(a0.cross(c3)) / (nc + 1 - flag)          # d|c0|/dx (where curved)
        prog.output(f"tab[{base}]", sp.Float(wg) * l * g0, op="=")
        for a in range(4):
            prog.output(f"tab[{base + 1 + a}]", d1[a].subs(sub), op="=")
            prog.output(f"tab[{base + 5 + a}]", d2[a].subs(sub), op="=")
        prog.output(f"tab[{base + 9}]", 1 / g0, op="=")
        prog.output(f"tab[{base + 10}]", flag * nc / g0**3, op="=")
        prog.output(f"tab[{base + 11}]", flag * (BETA * nc)**2 + 1 - flag, op="=")
        prog.output(f"tab[{base + 12}]", dg0, op="=")
        prog.output(f"tab[{base + 13}]", flag * (dnc / g0**3 - 3 * nc * dg0 / g0**4), op="=")
    return prog


def energy_density():
    """W per unit reference arc length as a function of a = r', b = r'' and a
    point's constants: (W, a, b, (1/|a0|, kappa0, eta), (EA, EI))."""
    a_ = sp.Matrix(sp.symbols("a0:3", real=True))       # r'
    b_ = sp.Matrix(sp.symbols("b0:3", real=True))       # r''
    ig, k0, eta = sp.symbols("ig k0 eta", real=True)
    EA, EI = sp.symbols("EA EI", real=True)
    c = a_.cross(b_)
    na2 = a_.dot(a_)
    cc = c.dot(c)
    bend = cc / na2**3 - 2 * k0 * sp.sqrt(cc + eta) / na2**sp.Rational(3, 2) + k0**2
    W = EA / 2 * (sp.sqrt(na2) * ig - 1)**2 + EI / 2 * bend
    return W, a_, b_, (ig, k0, eta), (EA, EI)


def _point(t, g):
    """Table entries of Gauss point g: (w l |a0|, N', N'', (1/|a0|, kappa0, eta), |a0|', kappa0')."""
    b = STRIDE * g
    return t[b], t[b + 1: b + 5], t[b + 5: b + 9], t[b + 9: b + 12], t[b + 12], t[b + 13]


def _density(mat):
    params = {name: sp.Symbol(f"mat[{k}]", real=True) for k, name in enumerate(mat.PARAMS)}
    W, a_, b_, consts, (EA, EI) = energy_density()
    return W.subs({EA: params["EA"], EI: params["EI1"]}), a_, b_, consts, params


def body_program(elem, mat, want):
    prog = Program()
    q = [sp.Symbol(f"q[{i}]", real=True) for i in range(12)]
    t = [sp.Symbol(f"tab[{i}]", real=True) for i in range(tab_layout())]
    W, a_, b_, consts, params = _density(mat)
    z = list(a_) + list(b_)
    dW = [sp.diff(W, v) for v in z]
    d2W = {(i, j): sp.diff(dW[i], z[j]) for i in range(6) for j in range(i, 6)}
    U = 0
    f = [0] * 12
    K = {}
    for g in range(NGAUSS):
        w, d1, d2, cg, _, _ = _point(t, g)
        ra = [prog.define(f"a{g}_{i}", sum(d1[n] * q[3 * n + i] for n in range(4))) for i in range(3)]
        rb = [prog.define(f"b{g}_{i}", sum(d2[n] * q[3 * n + i] for n in range(4))) for i in range(3)]
        sub = dict(zip(z + list(consts), ra + rb + list(cg)))
        if want == "energy":
            U += w * W.subs(sub)
            continue
        Wz = [prog.define(f"W{g}_{i}", w * dW[i].subs(sub)) for i in range(6)]
        # z_i = sum_n D_n q[3n + comp(i)] with D = N' for i < 3, N'' for i >= 3
        D = lambda i, n: d1[n] if i < 3 else d2[n]
        for n in range(4):
            for k in range(3):
                f[3 * n + k] += Wz[k] * D(0, n) + Wz[3 + k] * D(3, n)
        if want != "tangent":
            continue
        Wzz = {}
        for (i, j), e in d2W.items():
            e = e.subs(sub)
            if e != 0:
                Wzz[(i, j)] = Wzz[(j, i)] = prog.define(f"H{g}_{i}_{j}", w * e)
        for n in range(4):
            for m in range(4):
                for k in range(3):
                    for kk in range(3):
                        r, cidx = 3 * n + k, 3 * m + kk
                        if r > cidx:
                            continue
                        v = 0
                        for (i, j) in ((k, kk), (k, 3 + kk), (3 + k, kk), (3 + k, 3 + kk)):
                            if (i, j) in Wzz:
                                v += D(i, n) * D(j, m) * Wzz[(i, j)]
                        if v != 0:
                            K[(r, cidx)] = K.get((r, cidx), 0) + v
    if want == "energy":
        prog.output("e", U, op="=")
        return prog, params
    for i in range(12):
        prog.output(f"f[{i}]", f[i], op="=")
    if want == "tangent":
        for (i, j), v in sorted(K.items()):
            prog.output(f"K[{12 * i + j}]", v, op="=")
    return prog, params


def section_program(elem, mat):
    """Section resultants at the Gauss points, sec[9 g + 0..8] = (centreline
    point, n, m), global axes, of the energy per unit parameter x, G W(a, b, x)
    (a = r', b = r'', G = |a0|; W depends on x through the reference's kappa0
    and 1/|a0|): the balance laws of this energy, n' = -f and m' + r' x n = 0,
    hold with
        n = G W_a - (G W_b)' = G W_a - G' W_b - G (W_ba b + W_bb r''' + W_bk kappa0'),
        m = r' x G W_b
    (the rotation invariance a x W_a + b x W_b = 0 gives the second), and a
    free end carries n = the applied force, W_b = 0.  The force n thus holds
    the derivative of the bending term along the axis (r''' of the cubic, a
    constant of the element): the cable has no shear strain, its transverse
    force is that derivative, not a law.  W_b does not depend on 1/|a0|; eta's
    change along x (a term of relative size 1e-16) is left out.  Returns
    (program, parameter symbols)."""
    prog = Program()
    q = [sp.Symbol(f"q[{i}]", real=True) for i in range(12)]
    t = [sp.Symbol(f"tab[{i}]", real=True) for i in range(tab_layout())]
    W, a_, b_, consts, params = _density(mat)
    k0 = consts[1]
    l = geom_symbol("L")
    N, _, _ = hermite()
    c_ = [prog.define(f"c{i}", sum(d3.subs({L: l}) * q[3 * n + i] for n, d3 in enumerate(hermite3())))
          for i in range(3)]
    Wa = [sp.diff(W, a_[i]) for i in range(3)]
    Wb = [sp.diff(W, b_[i]) for i in range(3)]
    dWb = [sum(sp.diff(Wb[i], a_[j]) * b_[j] + sp.diff(Wb[i], b_[j]) * sp.Symbol(f"c{j}", real=True)
               for j in range(3)) for i in range(3)]
    for g, (xg, wg) in enumerate(gauss_unit(NGAUSS)):
        w, d1, d2, cg, dG, dk0 = _point(t, g)
        G = prog.define(f"G{g}", w / (sp.Float(wg) * l))
        ra = [prog.define(f"a{g}_{i}", sum(d1[n] * q[3 * n + i] for n in range(4))) for i in range(3)]
        rb = [prog.define(f"b{g}_{i}", sum(d2[n] * q[3 * n + i] for n in range(4))) for i in range(3)]
        sub = dict(zip(list(a_) + list(b_) + list(consts), ra + rb + list(cg)))
        Wb_s = [prog.define(f"Wb{g}_{i}", Wb[i].subs(sub)) for i in range(3)]
        Ni = [n.subs({XI: sp.Float(xg), L: l}) for n in N]
        for i in range(3):
            prog.output(f"sec[{9 * g + i}]", sum(Ni[n] * q[3 * n + i] for n in range(4)), op="=")
            inner = dWb[i].subs(sub) + sp.diff(Wb[i], k0).subs(sub) * dk0
            prog.output(f"sec[{9 * g + 3 + i}]", G * Wa[i].subs(sub) - dG * Wb_s[i] - G * inner, op="=")
        m = sp.Matrix(ra).cross(sp.Matrix(Wb_s))
        for i in range(3):
            prog.output(f"sec[{9 * g + 6 + i}]", G * m[i], op="=")
    assert all(s.name == f"c{i}" for i, s in enumerate(c_))
    return prog, params


def sample_xi():
    return tuple(x for x, _ in gauss_unit(NGAUSS))
