"""Gauss–Legendre rules on intervals and boxes.

Points and weights are computed once with 30 significant digits by sympy and
rounded to the nearest double, so every run emits the same literals.
"""
from functools import lru_cache

from sympy.integrals.quadrature import gauss_legendre


@lru_cache(maxsize=None)
def gauss_unit(n):
    """n-point Gauss–Legendre rule on [0, 1]: tuple of (point, weight) floats."""
    if n < 1:
        raise ValueError("a Gauss rule needs at least one point")
    x, w = gauss_legendre(n, 30)
    return tuple((float((xi + 1) / 2), float(wi / 2)) for xi, wi in zip(x, w))


def box_rule(counts):
    """Tensor rule on the unit cube [0,1]^3 for counts = (nx, ny, nz).

    Returns a list of ((s_x, s_y, s_z), weight) with the x index slowest, so the
    order is fixed.  The caller maps s to element coordinates.
    """
    nx, ny, nz = counts
    rule = []
    for sx, wx in gauss_unit(nx):
        for sy, wy in gauss_unit(ny):
            for sz, wz in gauss_unit(nz):
                rule.append(((sx, sy, sz), wx * wy * wz))
    return rule
