"""ancf3333: three-node ANCF beam with nodal r, r_y, r_z (27 DOF).

Quadratic along the axis, linear across: basis {1, x, x^2} x {1, y, z}.  The
axial slope is not a nodal unknown; it follows from the three nodal positions.
"""
from sympy import Integer, Rational

from gen.element import ContinuumElement, Node, RulePart

VECTORS = ("r", "r_y", "r_z")

ELEMENT = ContinuumElement(
    name="ancf3333",
    title="ANCF three-node beam, 3 nodes x (r, r_y, r_z), 27 DOF",
    source="quadratic-axial / linear-transverse ANCF beam (Orzechowski and Fraczek, Nonlinear Dyn 2015)",
    basis=tuple((i, j, k) for i in range(3) for (j, k) in ((0, 0), (1, 0), (0, 1))),
    nodes=(Node(Integer(0), VECTORS), Node(Rational(1, 2), VECTORS), Node(Integer(1), VECTORS)),
    rules=(("full", (RulePart("all", (3, 2, 2)),)),),
)
