"""ancf3273: two-node ANCF beam with a cubic centreline (as ancf3243) and
quadratic transverse terms: nodal r, r_x, r_y, r_z, r_yy, r_yz, r_zz (42 DOF).

Basis {1, x, x^2, x^3} + {1, x} x {y, z, y^2, yz, z^2}.

Integrations: "reduced" (default), 3 x 2 x 2 Gauss points; "full", 3 x 3 x 3
(identical results in the seed's bending cases; see ancf3363 for why the 2 x 2
section rule is the default).
"""
from sympy import Integer

from gen.element import ContinuumElement, Node, RulePart

VECTORS = ("r", "r_x", "r_y", "r_z", "r_yy", "r_yz", "r_zz")

ELEMENT = ContinuumElement(
    name="ancf3273",
    title="ANCF two-node beam with quadratic transverse terms, 2 nodes x (r, r_x, r_y, r_z, r_yy, r_yz, r_zz), 42 DOF",
    source="two-node variant of the seed 000 higher-order element (cubic axis as in 001 Eq. 3)",
    basis=((0, 0, 0), (1, 0, 0), (2, 0, 0), (3, 0, 0)) +
          tuple((i, j, k) for i in range(2) for (j, k) in ((1, 0), (0, 1), (2, 0), (1, 1), (0, 2))),
    nodes=(Node(Integer(0), VECTORS), Node(Integer(1), VECTORS)),
    rules=(("full", (RulePart("all", (3, 3, 3)),)),
           ("reduced", (RulePart("all", (3, 2, 2)),))),
    default_rule="reduced",
)
