"""ancf3273: two-node ANCF beam with a cubic centreline (as ancf3243) and
quadratic transverse terms: nodal r, r_x, r_y, r_z, r_yy, r_yz, r_zz (42 DOF).

Basis {1, x, x^2, x^3} + {1, x} x {y, z, y^2, yz, z^2}.

Integrations: "sri" (default): the full-order part of the energy (the
material's uniaxial-stress energy of the axial stretch and the transverse
shears, gen/uniaxial.py) at 3 x 3 x 3 points, the rest (lateral and volumetric
response) at 1 x 2 x 2 points, one section rule at mid-element; "reduced",
3 x 2 x 2 and "full", 3 x 3 x 3 Gauss points for the whole energy.

Why "reduced" and "full" lock with nearly incompressible materials: the
transverse fields (r_y, r_z, r_yy, r_yz, r_zz) are linear along the element,
while the cubic centreline carries a curvature that varies linearly.  At
constant curvature (an end moment) the section can contract as J = 1 demands
and the element is exact (0.998 of beam theory at kappa = 1000 mu, 10
elements); under a distributed load the curvature varies within the element,
the lateral fields cannot follow it at every point, and the volumetric penalty
stiffens the beam (0.76 of beam theory, self-weight, 10 elements, free clamp).
Integrating the lateral part at one point along the axis asks J = 1 only where
the linear lateral fields can meet it: 0.995 at 10 elements, no spurious
modes (the first 12 natural frequencies of a cantilever: bending pairs at 8.373,
53.07, 151.4, ... Hz against Euler-Bernoulli 8.355, 52.36, 146.6 Hz).
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
           ("reduced", (RulePart("all", (3, 2, 2)),)),
           ("sri", (RulePart("full_order", (3, 3, 3)), RulePart("centreline", (1, 2, 2))))),
    default_rule="sri",
)
