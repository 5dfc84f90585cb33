"""The closed forms the hard cases compare with: the seed cantilever's Euler
load and two-turn moment, the compressed elastica past buckling and the limit
load of the two-bar truss."""
import math

EI, L, PCR = 60.0, 1.0, math.pi ** 2 * 60.0 / 4.0
M_TWO_TURNS = 4 * math.pi * EI / L


def elastica_compressed(P, pcr=None):
    """Inextensible elastica of the cantilever under a dead axial end load P > Pcr
    (first mode; pcr: the Euler load, default the seed's square section): tip
    position (x, z) / L, from K(k) = pi/2 sqrt(P / Pcr), x = 2 E(k) / K(k) - 1,
    z = 2 k / K(k)."""
    import mpmath as mp
    kt = mp.pi / 2 * mp.sqrt(P / (pcr or PCR))
    lo, hi = mp.mpf(0), mp.mpf(1)
    for _ in range(200):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if mp.ellipk(mid) < kt else (lo, mid)
    m = lo
    return float(2 * mp.ellipe(m) / mp.ellipk(m) - 1), float(2 * mp.sqrt(m) / mp.ellipk(m))


def truss_closed_form(EA=1.0e6, b=1.0, h=0.1):
    """Limit load of the pin-ended two-bar truss half model (tests/test_continuation.py)."""
    L0 = math.hypot(b, h)
    Ls = (b * b * L0) ** (1.0 / 3.0)
    ys = math.sqrt(Ls * Ls - b * b)
    return EA * ys * (1.0 / Ls - 1.0 / L0), h - ys
