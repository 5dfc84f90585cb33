"""Arruda-Boyce (eight-chain) with a volumetric penalty:
W = mu sum_{i=1..5} C_i / lambda_m^(2i-2) (Ibar1^i - 3^i) + kappa/2 (J - 1)^2,
C = (1/2, 1/20, 11/1050, 19/7000, 519/673750), Ibar1 = J^-2/3 I1.

mu is the series' shear parameter and lambda_m the locking stretch.  The
initial shear modulus is mu0 = mu (1 + 3/(5 lm^2) + 99/(175 lm^4) + 513/(875 lm^6)
+ 42039/(67375 lm^8)), the bulk modulus kappa; E = 9 kappa mu0/(3 kappa + mu0),
nu = (3 kappa - 2 mu0)/(2 (3 kappa + mu0)).

The penalty kappa/2 (J - 1)^2 has U'(1) = 0 and U''(1) = kappa.  For nearly
incompressible use (kappa >> mu, e.g. 1000 mu for silicone) it keeps J close to
1, and elements whose interpolation cannot represent isochoric bending lock:
see the issue notes and out/report/seed_tables.md.
"""
from sympy import Rational

NAME = "arruda_boyce"
TITLE = "Arruda-Boyce (5 terms) with volumetric penalty kappa/2 (J-1)^2"
PARAMS = ("mu", "lambda_m", "kappa")
INPUTS = ((PARAMS, lambda mu, lm, kappa: (mu, lm, kappa)),)
# Each scene key's range (lo < value < hi, None: unbounded) and unit, checked by the scene reader.
RANGES = {"mu": (0, None, "Pa"), "lambda_m": (1, 1e6, ""), "kappa": (0, None, "Pa")}
COEFFS = (Rational(1, 2), Rational(1, 20), Rational(11, 1050), Rational(19, 7000), Rational(519, 673750))


def energy(I1, I2, J, p):
    Ib1 = J**Rational(-2, 3) * I1
    W = sum(c / p["lambda_m"]**(2 * i) * (Ib1**(i + 1) - 3**(i + 1)) for i, c in enumerate(COEFFS))
    return p["mu"] * W + p["kappa"] / 2 * (J - 1)**2


def small_strain(mu, lm, kappa):
    mu0 = mu * (1 + Rational(3, 5) / lm**2 + Rational(99, 175) / lm**4 + Rational(513, 875) / lm**6
                + Rational(42039, 67375) / lm**8)
    return 9 * kappa * mu0 / (3 * kappa + mu0), (3 * kappa - 2 * mu0) / (2 * (3 * kappa + mu0))
