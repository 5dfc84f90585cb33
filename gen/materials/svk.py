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


def sri_split(I1, I2, I4, J, p):
    """Selective reduced integration: the uniaxial part E/2 E11^2 (E11 = (I4 - 1)/2,
    the Green strain along the beam axis, E Young's modulus) at full order; the
    rest, which carries the Poisson coupling of E11 with the transverse strains,
    at the centreline.  The rest is >= 0 and vanishes in uniaxial stress, so bending
    sees E I and a bar in tension the exact uniaxial law."""
    lam, mu = p["lambda"], p["mu"]
    E = mu * (3 * lam + 2 * mu) / (lam + mu)
    W_axial = E / 2 * ((I4 - 1) / 2)**2
    return W_axial, energy(I1, I2, J, p) - W_axial


def small_strain(lam, mu):
    return mu * (3 * lam + 2 * mu) / (lam + mu), lam / (2 * (lam + mu))
