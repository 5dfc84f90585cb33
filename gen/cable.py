"""The ANCF gradient-deficient beam ("cable"): 2 nodes x (r, r_x), 12 DOF, the
cubic Hermite interpolation of seed 001 Eqs. (4)-(6).

Energy per unit reference length, at Gauss points along the axis:
    W = 1/2 EA eps^2 + 1/2 EI kappa^2,
    eps = |r'| - 1,    kappa^2 = |r' x r''|^2 / |r'|^6
(the exact curvature of the centreline; kappa^2 is a smooth function of q, so
the element is well defined for straight configurations).  The cross-section
has no orientation: one bending stiffness (EI1 = EI2 is required) and no
torsion.  Forces and tangents are derived analytically: W as a function of
(r', r''), chained through the constant shape-function derivatives.
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


def tab_layout():
    """Per Gauss point: w l, N'_a (4), N''_a (4)."""
    return NGAUSS * 9


def tabulate_program():
    prog = Program()
    l = geom_symbol("L")
    N, d1, d2 = hermite()
    for g, (xg, wg) in enumerate(gauss_unit(NGAUSS)):
        base = 9 * g
        prog.output(f"tab[{base}]", sp.Float(wg) * l, op="=")
        for a in range(4):
            prog.output(f"tab[{base + 1 + a}]", d1[a].subs({XI: sp.Float(xg), L: l}), op="=")
            prog.output(f"tab[{base + 5 + a}]", d2[a].subs({XI: sp.Float(xg), L: l}), op="=")
    return prog


def body_program(elem, mat, want):
    prog = Program()
    q = [sp.Symbol(f"q[{i}]", real=True) for i in range(12)]
    t = [sp.Symbol(f"tab[{i}]", real=True) for i in range(tab_layout())]
    params = {name: sp.Symbol(f"mat[{k}]", real=True) for k, name in enumerate(mat.PARAMS)}
    EA, EI = params["EA"], params["EI1"]
    a_ = sp.Matrix(sp.symbols("a0:3", real=True))       # r'
    b_ = sp.Matrix(sp.symbols("b0:3", real=True))       # r''
    c = a_.cross(b_)
    na2 = a_.dot(a_)
    W = EA / 2 * (sp.sqrt(na2) - 1)**2 + EI / 2 * c.dot(c) / na2**3
    z = list(a_) + list(b_)
    dW = [sp.diff(W, v) for v in z]
    d2W = {(i, j): sp.diff(dW[i], z[j]) for i in range(6) for j in range(i, 6)}
    U = 0
    f = [0] * 12
    K = {}
    for g in range(NGAUSS):
        w = t[9 * g]
        d1 = t[9 * g + 1: 9 * g + 5]
        d2 = t[9 * g + 5: 9 * g + 9]
        ra = [prog.define(f"a{g}_{i}", sum(d1[n] * q[3 * n + i] for n in range(4))) for i in range(3)]
        rb = [prog.define(f"b{g}_{i}", sum(d2[n] * q[3 * n + i] for n in range(4))) for i in range(3)]
        sub = dict(zip(z, ra + rb))
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
    point, n, m), global axes, of W(a, b) (a = r', b = r''): the balance laws
    of this energy, n' = -f and m' + r' x n = 0, hold with
        n = W_a - d/dx W_b = W_a - W_ba r'' - W_bb r''',    m = r' x W_b
    (the rotation invariance a x W_a + b x W_b = 0 gives the second), and a
    free end carries n = the applied force, W_b = 0.  The force n thus holds
    the derivative of the bending term along the axis (r''' of the cubic, a
    constant of the element): the cable has no shear strain, its transverse
    force is that derivative, not a law.  Returns (program, parameter symbols)."""
    prog = Program()
    q = [sp.Symbol(f"q[{i}]", real=True) for i in range(12)]
    t = [sp.Symbol(f"tab[{i}]", real=True) for i in range(tab_layout())]
    params = {name: sp.Symbol(f"mat[{k}]", real=True) for k, name in enumerate(mat.PARAMS)}
    EA, EI = params["EA"], params["EI1"]
    l = geom_symbol("L")
    a_ = sp.Matrix(sp.symbols("a0:3", real=True))
    b_ = sp.Matrix(sp.symbols("b0:3", real=True))
    cr = a_.cross(b_)
    na2 = a_.dot(a_)
    W = EA / 2 * (sp.sqrt(na2) - 1)**2 + EI / 2 * cr.dot(cr) / na2**3
    N, _, _ = hermite()
    d3 = [sp.diff(n, XI, 3) / L**3 for n in N]
    c_ = [prog.define(f"c{i}", sum(d3[n].subs({L: l}) * q[3 * n + i] for n in range(4))) for i in range(3)]
    for g, (xg, _) in enumerate(gauss_unit(NGAUSS)):
        d1 = t[9 * g + 1: 9 * g + 5]
        d2 = t[9 * g + 5: 9 * g + 9]
        ra = [prog.define(f"a{g}_{i}", sum(d1[n] * q[3 * n + i] for n in range(4))) for i in range(3)]
        rb = [prog.define(f"b{g}_{i}", sum(d2[n] * q[3 * n + i] for n in range(4))) for i in range(3)]
        sub = dict(zip(list(a_) + list(b_), ra + rb))
        Wa = [sp.diff(W, a_[i]) for i in range(3)]
        Wb = [sp.diff(W, b_[i]) for i in range(3)]
        dWb = [sum(sp.diff(Wb[i], a_[j]) * b_[j] for j in range(3)) for i in range(3)]
        Wb_s = [prog.define(f"Wb{g}_{i}", Wb[i].subs(sub)) for i in range(3)]
        for i in range(3):
            Ni = [n.subs({XI: sp.Float(xg), L: l}) for n in N]
            prog.output(f"sec[{9 * g + i}]", sum(Ni[n] * q[3 * n + i] for n in range(4)), op="=")
            nval = Wa[i].subs(sub) - dWb[i].subs(sub) - sum(sp.diff(Wb[i], b_[j]).subs(sub) * c_[j] for j in range(3))
            prog.output(f"sec[{9 * g + 3 + i}]", nval, op="=")
        m = sp.Matrix(ra).cross(sp.Matrix(Wb_s))
        for i in range(3):
            prog.output(f"sec[{9 * g + 6 + i}]", m[i], op="=")
    return prog, params


def sample_xi():
    return tuple(x for x, _ in gauss_unit(NGAUSS))
