"""gef: geometrically exact Simo-Reissner (Timoshenko) beam, 3 nodes x (r, quaternion),
21 DOF; strains (5.29)-(5.30) and the quadratic potential (5.33) of seed 002.
See gen/rod.py for the interpolation (rotations relative to the middle node)."""
from gen.rod import RodElement

ELEMENT = RodElement(
    name="gef",
    title="geometrically exact Simo-Reissner (Timoshenko) beam, 3 nodes x (r, p), 21 DOF",
    source="seed 002_d9cca145703809b0.txt, Sections 5.1-5.3; Jelenic and Crisfield rotation interpolation",
    constrained=(),
)
