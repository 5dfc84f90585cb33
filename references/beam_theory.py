"""Linear beam theory references: Timoshenko cantilevers and the small-strain
moduli of the hyperelastic laws."""


def cowper_rectangle(nu):
    """Cowper's shear correction factor of a rectangular section."""
    return 10 * (1 + nu) / (12 + 11 * nu)


def cantilever_uniform_load_tip(E, nu, L, b, h, q):
    """Tip deflection of a Timoshenko cantilever (rectangle b x h) under a uniform
    load q (N/m): q L^4 / (8 E I) + q L^2 / (2 k G A)."""
    A, I = b * h, b * h**3 / 12
    G = E / (2 * (1 + nu))
    return q * L**4 / (8 * E * I) + q * L**2 / (2 * cowper_rectangle(nu) * G * A)


def cantilever_tip_load_tip(E, nu, L, b, h, P):
    """Tip deflection under a tip force P: P L^3 / (3 E I) + P L / (k G A)."""
    A, I = b * h, b * h**3 / 12
    G = E / (2 * (1 + nu))
    return P * L**3 / (3 * E * I) + P * L / (cowper_rectangle(nu) * G * A)


def ab_moduli(mu, lm, kappa):
    """Small-strain (E, nu) of the five-term Arruda-Boyce law with bulk modulus kappa."""
    mu0 = mu * (1 + 3 / (5 * lm**2) + 99 / (175 * lm**4) + 513 / (875 * lm**6) + 42039 / (67375 * lm**8))
    return 9 * kappa * mu0 / (3 * kappa + mu0), (3 * kappa - 2 * mu0) / (2 * (3 * kappa + mu0))
