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
# Each scene key's range (lo < value < hi, None: unbounded) and unit, checked by the scene reader.
RANGES = {"E": (0, None, "Pa"), "nu": (-1, 0.5, ""), "lambda": (None, None, "Pa"), "mu": (0, None, "Pa")}
# Principal Green strains the law is meant for (the runtime warns beyond): St.
# Venant-Kirchhoff is a large-rotation, moderate-strain law; in compression its
# uniaxial stress peaks at E = -1/3 (stretch 1/sqrt 3) and then softens to zero.
GREEN_STRAIN_RANGE = (-0.2, 0.5)


def energy(I1, I2, J, p):
    trE = (I1 - 3) / 2
    trE2 = (I1**2 - 2 * I2 - 2 * I1 + 3) / 4
    return p["lambda"] / 2 * trE**2 + p["mu"] * trE2


def small_strain(lam, mu):
    return mu * (3 * lam + 2 * mu) / (lam + mu), lam / (2 * (lam + mu))
