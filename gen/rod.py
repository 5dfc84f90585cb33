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
# This file: the element family (RodElement), its interpolation, quaternion
# helpers and the layouts of the shared kinematics.  The programs derived from
# them: gen/rod_kinematics.py (psi, strains, pull-backs), gen/rod_energy.py
# (gauge penalty, material law, section resultants), gen/rod_frame.py (frame,
# nodal moment), gen/rod_inertia.py (nodal rotary inertia).
from dataclasses import dataclass

import sympy as sp

from gen.rodmath import At

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
