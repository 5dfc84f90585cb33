"""Quadratic resultant potential of a beam (seed 002, Eq. 5.33):
W = 1/2 (EA g1^2 + GA1 g2^2 + GA2 g3^2) + 1/2 (GJ k1^2 + EI1 k2^2 + EI2 k3^2)
per unit reference length, with g = (axial, shear along d1, shear along d2)
strains and k = (torsion, bending about d1, bending about d2) curvatures.

From E, nu and the section (section_stiffness below): G = E / (2 (1 + nu));
shear correction (Cowper) k = 10 (1 + nu) / (12 + 11 nu) for rectangles and
6 (1 + nu) / (7 + 6 nu) for circles; torsion constant of a b x h rectangle
J = a c^3 / 3 (1 - 192 c / (pi^5 a) sum_{n odd} tanh(n pi a / (2 c)) / n^5),
a = max(b, h), c = min(b, h) (J = 0.1406 b^4 for the square), pi r^4 / 2 for a
circle.  A scene can also give the six stiffnesses directly.
"""
import math

NAME = "resultant"
TITLE = "quadratic resultant potential (EA, GA1, GA2, GJ, EI1, EI2)"
KIND = "resultant"
PARAMS = ("EA", "GA1", "GA2", "GJ", "EI1", "EI2")
INPUTS = ((PARAMS, lambda *v: v),)
# Each scene key's range (lo < value < hi, None: unbounded) and unit, checked by the scene reader
# (E and nu: with the beam's section, section_stiffness below).
RANGES = {"EA": (0, None, "N"), "GA1": (0, None, "N"), "GA2": (0, None, "N"), "GJ": (0, None, "N m^2"),
          "EI1": (0, None, "N m^2"), "EI2": (0, None, "N m^2"), "E": (0, None, "Pa"), "nu": (-1, 0.5, "")}


def energy(g, k, p):
    return (p["EA"] * g[0]**2 + p["GA1"] * g[1]**2 + p["GA2"] * g[2]**2
            + p["GJ"] * k[0]**2 + p["EI1"] * k[1]**2 + p["EI2"] * k[2]**2) / 2


def torsion_constant_rectangle(b, h, terms=50):
    a, c = max(b, h), min(b, h)
    s = sum(math.tanh(n * math.pi * a / (2 * c)) / n**5 for n in range(1, 2 * terms, 2))
    return a * c**3 / 3 * (1 - 192 * c / (math.pi**5 * a) * s)


def section_stiffness(E, nu, shape, b, h):
    """(EA, GA1, GA2, GJ, EI1, EI2) of a rectangle b x h (b along d1) or a circle (b = h = 2r)."""
    G = E / (2 * (1 + nu))
    if shape == "rectangle":
        A, I1, I2 = b * h, b * h**3 / 12, h * b**3 / 12
        J = torsion_constant_rectangle(b, h)
        k = 10 * (1 + nu) / (12 + 11 * nu)
    else:
        r = b / 2
        A, I1 = math.pi * r**2, math.pi * r**4 / 4
        I2, J = I1, math.pi * r**4 / 2
        k = 6 * (1 + nu) / (7 + 6 * nu)
    return (E * A, k * G * A, k * G * A, G * J, E * I1, E * I2)
