"""Mooney-Rivlin with a volumetric penalty:
W = c10 (Ibar1 - 3) + c01 (Ibar2 - 3) + kappa/2 (J - 1)^2,
Ibar1 = J^-2/3 I1, Ibar2 = J^-4/3 I2.

Small-strain limit: shear modulus mu = 2 (c10 + c01), bulk modulus kappa, so
E = 9 kappa mu / (3 kappa + mu), nu = (3 kappa - 2 mu) / (2 (3 kappa + mu)).
"""
from sympy import Rational

NAME = "mooney_rivlin"
TITLE = "Mooney-Rivlin with volumetric penalty kappa/2 (J-1)^2"
PARAMS = ("c10", "c01", "kappa")
INPUTS = ((PARAMS, lambda c10, c01, kappa: (c10, c01, kappa)),)
# Each scene key's range (lo < value < hi, None: unbounded) and unit, checked by the scene reader.
RANGES = {"c10": (None, None, "Pa"), "c01": (None, None, "Pa"), "kappa": (0, None, "Pa")}


def energy(I1, I2, J, p):
    Ib1 = J**Rational(-2, 3) * I1
    Ib2 = J**Rational(-4, 3) * I2
    return p["c10"] * (Ib1 - 3) + p["c01"] * (Ib2 - 3) + p["kappa"] / 2 * (J - 1)**2


def small_strain(c10, c01, kappa):
    mu = 2 * (c10 + c01)
    return 9 * kappa * mu / (3 * kappa + mu), (3 * kappa - 2 * mu) / (2 * (3 * kappa + mu))
