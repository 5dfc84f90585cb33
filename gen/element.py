"""Continuum (ANCF) beam elements as data, and the shape functions they imply.

An element is declared by
  * a polynomial basis: monomials x^i y^j z^k (x along the axis, y and z across),
  * a node layout: for each node its position along the axis (xi in [0, 1]) and
    the nodal vectors it carries, named by the derivative they interpolate:
    "r" (position), "r_x", "r_y", "r_z", "r_yy", "r_yz", "r_zz", ...,
  * a reference geometry: the straight box x in [0, l], y in [-b/2, b/2],
    z in [-h/2, h/2] (physical coordinates, so the reference slopes are unit
    vectors), and
  * quadrature rules, one per integration variant.

`shape_functions` solves the interpolation conditions (one per nodal vector
component) for the shape functions N_a, so that r(x, y, z) = sum_a N_a q_a with
q_a the a-th nodal vector: the shape-function matrix is S = N (x) I_3.
"""
from dataclasses import dataclass
from functools import lru_cache

import sympy as sp

# The element's symbolic reference coordinates and geometry.
XI, Y, Z = sp.symbols("xi y z", real=True)           # xi = x / l in [0, 1]
L, B, H = sp.symbols("l b h", positive=True)          # length, width, height
GEOMETRY = (L, B, H)                                  # geom[BK_GEOM_L], [BK_GEOM_B], [BK_GEOM_H] in C
LO, HI = sp.symbols("band_lo band_hi", nonnegative=True)   # fractions of h left out below / above a layer's band
AX = sp.Symbol("band_axis", real=True)                     # a layered section's neutral axis, z / h


def geom_symbol(slot):
    """The C geometry entry geom[BK_GEOM_<slot>] (runtime/bk_kernel.h) as a symbol."""
    from gen import contract
    contract.geom_slot(slot)                          # raises if the header has no such slot
    return sp.Symbol(f"geom[BK_GEOM_{slot}]", positive=True)


def geom_subs():
    """{l, b, h} -> their geom[] entries."""
    return {L: geom_symbol("L"), B: geom_symbol("B"), H: geom_symbol("H")}


def band_subs():
    """{band_lo, band_hi} -> geom[BK_GEOM_BAND_LO], [BK_GEOM_BAND_HI] (a layer's band)."""
    return {LO: sp.Symbol("geom[BK_GEOM_BAND_LO]", real=True), HI: sp.Symbol("geom[BK_GEOM_BAND_HI]", real=True),
            AX: sp.Symbol("geom[BK_GEOM_BAND_AXIS]", real=True)}


def vector_order(name):
    """Derivative multi-index (n_x, n_y, n_z) interpolated by a nodal vector name."""
    if name == "r":
        return (0, 0, 0)
    if not name.startswith("r_") or not set(name[2:]) <= set("xyz") or len(name) < 3:
        raise ValueError(f"nodal vector name {name!r}: expected r, r_x, r_y, r_yz, ...")
    letters = name[2:]
    return (letters.count("x"), letters.count("y"), letters.count("z"))


@dataclass(frozen=True)
class Node:
    xi: sp.Rational                 # position along the axis, 0 <= xi <= 1
    vectors: tuple                  # names of the nodal vectors, in DOF order


@dataclass(frozen=True)
class RulePart:
    """One integration pass: which part of the energy, and the Gauss point counts
    (n_x, n_y, n_z) over the element box."""
    energy: str                     # "all", or a part name a material provides
    points: tuple


@dataclass(frozen=True)
class ContinuumElement:
    name: str
    title: str
    source: str
    basis: tuple                    # monomial exponents (i, j, k) of x^i y^j z^k
    nodes: tuple
    rules: tuple = ()               # ((integration name, (RulePart, ...)), ...)
    default_rule: str = "full"
    kind: str = "continuum"
    material_kind: str = "continuum"
    ninternal: int = 0

    @property
    def nnode(self):
        return len(self.nodes)

    def fields(self):
        return [(v, 3 * a, 3) for a, (_, v) in enumerate(self.shape_labels())]

    def rule(self, name):
        for n, parts in self.rules:
            if n == name:
                return parts
        raise KeyError(name)

    @property
    def rule_names(self):
        return tuple(n for n, _ in self.rules)

    @property
    def nshape(self):
        return sum(len(n.vectors) for n in self.nodes)

    @property
    def ndof(self):
        return 3 * self.nshape

    def shape_labels(self):
        """(node index, vector name) for each shape function, in DOF order."""
        return [(i, v) for i, n in enumerate(self.nodes) for v in n.vectors]

    def describe_layout(self):
        parts = []
        for i, n in enumerate(self.nodes):
            parts.append(f"node {i} (xi={n.xi}): " + ", ".join(n.vectors))
        return "; ".join(parts)


def _monomial(e):
    i, j, k = e
    return (L * XI) ** i * Y ** j * Z ** k


def _d(expr, order):
    """Physical derivative d^(nx+ny+nz)/dx^nx dy^ny dz^nz of an expression in (xi, y, z)."""
    nx, ny, nz = order
    for _ in range(nx):
        expr = sp.diff(expr, XI) / L
    if ny:
        expr = sp.diff(expr, Y, ny)
    if nz:
        expr = sp.diff(expr, Z, nz)
    return expr


@lru_cache(maxsize=None)
def shape_functions(elem):
    """Shape functions N_a(xi, y, z; l) of the element, as a tuple of sympy expressions.

    Solves A c = delta with A[(node, vector), k] = D^vector m_k(node) for the
    monomials m_k of the basis; raises if the conditions are not unisolvent.
    """
    mons = [_monomial(e) for e in elem.basis]
    labels = elem.shape_labels()
    if len(mons) != len(labels):
        raise ValueError(f"{elem.name}: {len(mons)} basis monomials but {len(labels)} nodal vectors")
    rows = []
    for node_index, vec in labels:
        node = elem.nodes[node_index]
        order = vector_order(vec)
        rows.append([_d(m, order).subs({XI: node.xi, Y: 0, Z: 0}) for m in mons])
    A = sp.Matrix(rows)
    if A.det() == 0:
        raise ValueError(f"{elem.name}: interpolation conditions are singular")
    coeff = A.inv()                      # column a: coefficients of N_a
    out = []
    for a in range(len(labels)):
        expr = sum(coeff[k, a] * mons[k] for k in range(len(mons)))
        out.append(sp.expand(sp.simplify(expr)))
    return tuple(out)


@lru_cache(maxsize=None)
def shape_gradients(elem):
    """Tuple over shape functions of (dN/dx, dN/dy, dN/dz) in physical coordinates."""
    return tuple(tuple(sp.expand(_d(N, o)) for o in ((1, 0, 0), (0, 1, 0), (0, 0, 1)))
                 for N in shape_functions(elem))


def reference_vector(vec, t, d1, d2, x0):
    """Reference value of a nodal vector for the straight box X = x0 + x t + y d1 + z d2."""
    order = vector_order(vec)
    if order == (0, 0, 0):
        return list(x0)
    if order == (1, 0, 0):
        return list(t)
    if order == (0, 1, 0):
        return list(d1)
    if order == (0, 0, 1):
        return list(d2)
    return [0.0, 0.0, 0.0]
