"""ancf3363: the higher-order ANCF beam with quadratic transverse interpolation
(seed 000_8d1bf0ab6c94edd4.txt): 3 nodes x (r, r_y, r_z, r_yy, r_yz, r_zz), 54 DOF.

Basis {1, x, x^2} x {1, y, z, y^2, yz, z^2}: the cross-section can take the
trapezoidal shape of bending with Poisson's effect and change its volume
quadratically, which removes Poisson and volumetric locking.

Integrations: "reduced" (default), 3 x 2 x 2 Gauss points; "full", 3 x 3 x 3.
With a nearly incompressible material (bulk modulus 1000 x shear modulus) the
full rule imposes the volume constraint at 9 points of a section that has 6
in-plane vector unknowns and locks (about 10 % too stiff in
out/report/incompressible.md); the 2 x 2 section rule does not, and gives the
same results as the full rule for compressible materials.
"""
from sympy import Integer, Rational

from gen.element import ContinuumElement, Node, RulePart

VECTORS = ("r", "r_y", "r_z", "r_yy", "r_yz", "r_zz")
TRANSVERSE = ((0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2))

ELEMENT = ContinuumElement(
    name="ancf3363",
    title="ANCF higher-order beam, 3 nodes x (r, r_y, r_z, r_yy, r_yz, r_zz), 54 DOF",
    source="seed 000_8d1bf0ab6c94edd4.txt (Xu, Liu, Qu 2019)",
    basis=tuple((i, j, k) for i in range(3) for (j, k) in TRANSVERSE),
    nodes=(Node(Integer(0), VECTORS), Node(Rational(1, 2), VECTORS), Node(Integer(1), VECTORS)),
    rules=(("full", (RulePart("all", (3, 3, 3)),)),
           ("reduced", (RulePart("all", (3, 2, 2)),))),
    default_rule="reduced",
)
