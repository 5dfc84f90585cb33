"""euler_bernoulli: the shear-rigid beam of seed 002, Section 5.4: the gef kinematics
with Gamma_2 = Gamma_3 = 0 at both Gauss points by Lagrange multipliers (4 per element)."""
from gen.rod import RodElement

ELEMENT = RodElement(
    name="euler_bernoulli",
    title="nonlinear Euler-Bernoulli beam (shear-rigid), 3 nodes x (r, p) + 4 multipliers",
    source="seed 002_d9cca145703809b0.txt, Section 5.4 (constraints by Lagrange multipliers at Gauss points)",
    constrained=("g2", "g3"),
)
