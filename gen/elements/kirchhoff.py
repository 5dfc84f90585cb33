"""kirchhoff: the shear-rigid and inextensible beam of seed 002, Section 5.5: the gef
kinematics with Gamma = 0 at both Gauss points by Lagrange multipliers (6 per element)."""
from gen.rod import RodElement

ELEMENT = RodElement(
    name="kirchhoff",
    title="nonlinear Kirchhoff beam (shear-rigid, inextensible), 3 nodes x (r, p) + 6 multipliers",
    source="seed 002_d9cca145703809b0.txt, Section 5.5 (constraints by Lagrange multipliers at Gauss points)",
    constrained=("g1", "g2", "g3"),
)
