"""ancf3243: the ANCF fully parameterized two-node beam (24 DOF).

Nodal vectors r, r_x, r_y, r_z at both ends; cubic along the axis, linear
across (seed 001_7d39798056ad1df0.txt, Eq. 3).  Default quadrature 3 x 2 x 2
Gauss points, as in the seed's comparison.

integration = "sri" (selective reduced integration against Poisson and volumetric
locking): the material's sri_split() gives the part of the energy integrated at
full order (3 x 2 x 2) and the part integrated at the centreline points of the
cross-section (3 x 1 x 1, y = z = 0).
"""
from sympy import Integer

from gen.element import ContinuumElement, Node, RulePart

VECTORS = ("r", "r_x", "r_y", "r_z")

ELEMENT = ContinuumElement(
    name="ancf3243",
    title="ANCF fully parameterized beam, 2 nodes x (r, r_x, r_y, r_z), 24 DOF",
    source="seed 001_7d39798056ad1df0.txt, Eq. (1)-(3)",
    basis=((0, 0, 0), (1, 0, 0), (2, 0, 0), (3, 0, 0),
           (0, 1, 0), (1, 1, 0), (0, 0, 1), (1, 0, 1)),
    nodes=(Node(Integer(0), VECTORS), Node(Integer(1), VECTORS)),
    rules=(("full", (RulePart("all", (3, 2, 2)),)),
           ("sri", (RulePart("full_order", (3, 2, 2)), RulePart("centreline", (3, 1, 1))))),
)
