"""Compressible Neo-Hookean: W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2.

Small-strain limit: Hooke's law with the Lame constants lambda, mu.
"""
from sympy import log

from gen.materials import lame

NAME = "neo_hookean"
TITLE = "compressible Neo-Hookean"
PARAMS = ("lambda", "mu")
INPUTS = ((("E", "nu"), lame), (("lambda", "mu"), lambda lam, mu: (lam, mu)))
# Each scene key's range (lo < value < hi, None: unbounded) and unit, checked by the scene reader.
RANGES = {"E": (0, None, "Pa"), "nu": (-1, 0.5, ""), "lambda": (None, None, "Pa"), "mu": (0, None, "Pa")}


def energy(I1, I2, J, p):
    return p["mu"] / 2 * (I1 - 3) - p["mu"] * log(J) + p["lambda"] / 2 * log(J)**2


def small_strain(lam, mu):
    return mu * (3 * lam + 2 * mu) / (lam + mu), lam / (2 * (lam + mu))
