"""ancf_cable: the ANCF gradient-deficient beam, 2 nodes x (r, r_x), 12 DOF (seed 001,
Eqs. 4-6), axial strain and curvature energy; see gen/cable.py."""
from gen.cable import CableElement

ELEMENT = CableElement(
    name="ancf_cable",
    title="ANCF gradient-deficient beam (cable), 2 nodes x (r, r_x), 12 DOF",
    source="seed 001_7d39798056ad1df0.txt, Eqs. (4)-(6)",
)
