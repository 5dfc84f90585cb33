"""St. Venant–Kirchhoff: W = lambda/2 (tr E)^2 + mu tr(E^2), E = (C - I)/2.

In invariants: tr E = (I1 - 3)/2 and tr(E^2) = (I1^2 - 2 I2 - 2 I1 + 3)/4.
Small-strain limit: Hooke's law with E = mu (3 lambda + 2 mu)/(lambda + mu),
nu = lambda / (2 (lambda + mu)).
"""
from gen.materials import lame

NAME = "svk"
TITLE = "St. Venant-Kirchhoff"
PARAMS = ("lambda", "mu")
INPUTS = ((("E", "nu"), lame), (("lambda", "mu"), lambda lam, mu: (lam, mu)))


def energy(I1, I2, J, p):
    trE = (I1 - 3) / 2
    trE2 = (I1**2 - 2 * I2 - 2 * I1 + 3) / 4
    return p["lambda"] / 2 * trE**2 + p["mu"] * trE2


def sri_split(I1, I2, J, C, p):
    """Selective reduced integration: at full order the uniaxial part E/2 E11^2
    (E Young's modulus) and the transverse shears 2 mu (E12^2 + E13^2); at the
    centreline the rest, which holds the Poisson coupling of E11 with the
    transverse normal strains.  The rest is >= 0 and vanishes in uniaxial stress,
    so bending sees E I, a bar in tension the exact uniaxial law, and torsion and
    shear keep their full-order stiffness."""
    lam, mu = p["lambda"], p["mu"]
    E = mu * (3 * lam + 2 * mu) / (lam + mu)
    E11, E12, E13 = (C[0, 0] - 1) / 2, C[0, 1] / 2, C[0, 2] / 2
    W_full = E / 2 * E11**2 + 2 * mu * (E12**2 + E13**2)
    return W_full, energy(I1, I2, J, p) - W_full


def small_strain(lam, mu):
    return mu * (3 * lam + 2 * mu) / (lam + mu), lam / (2 * (lam + mu))
