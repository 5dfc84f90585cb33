"""Natural bending frequencies of a clamped-free Timoshenko beam: shear
compliance (Cowper's coefficient of the section) and rotary inertia, by
shooting on the beam's two differential equations (a reference computed apart
from any finite element: the modal tests and the bench's sparse modes compare
beamkit's beams with it).

With w the deflection, psi the section's rotation, gamma = w' - psi the shear
strain and kappa = psi' the curvature, a free vibration at circular frequency
omega solves

    w' = psi + gamma              k G A gamma' = -rho A omega^2 w
    psi' = kappa                  E I kappa'   = -k G A gamma - rho I omega^2 psi

with w = psi = 0 at the clamp and E I kappa = k G A gamma = 0 at the free end.
The two solutions from the clamp (gamma(0) = 1 or kappa(0) = 1) give the free
end's moment and shear force; omega is a natural frequency where their 2 x 2
determinant vanishes.  Each root is bracketed next to the Euler-Bernoulli
frequency (the Timoshenko beam is a little softer and heavier in rotation:
its frequencies lie just below)."""
import math

# beta_n L of the clamped-free Euler-Bernoulli beam
BETA_L = (1.8751040687, 4.6940911330, 7.8547574382, 10.9955407349)


def cowper_rectangle(nu):
    """Cowper's shear coefficient of a rectangle."""
    return 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu)


def euler_bernoulli_hz(E, rho, A, I, L, mode):
    """Clamped-free Euler-Bernoulli frequency (Hz) of mode 1, 2, ..."""
    return BETA_L[mode - 1] ** 2 / (2.0 * math.pi * L * L) * math.sqrt(E * I / (rho * A))


def _end_determinant(omega, EI, kGA, rhoA, rhoI, L):
    from scipy.integrate import solve_ivp

    def rhs(_x, y):
        w, psi, gamma, kappa = y
        return [psi + gamma, kappa, -rhoA * omega**2 * w / kGA, (-kGA * gamma - rhoI * omega**2 * psi) / EI]

    ends = []
    for y0 in ([0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]):
        s = solve_ivp(rhs, (0.0, L), y0, method="DOP853", rtol=1e-12, atol=1e-15)
        _, _, gamma, kappa = s.y[:, -1]
        ends.append((EI * kappa, kGA * gamma))
    return ends[0][0] * ends[1][1] - ends[0][1] * ends[1][0]


def clamped_free_hz(E, nu, rho, b, h, L, mode, rotary=True):
    """Frequency (Hz) of bending mode 1, 2, ... (up to 4) of a clamped-free
    Timoshenko beam of a b x h rectangle bending about the axis along b (I =
    b h^3 / 12), Cowper's coefficient; rotary = False leaves the rotary inertia out."""
    from scipy.optimize import brentq
    A, I, G = b * h, b * h**3 / 12.0, E / (2.0 * (1.0 + nu))
    args = (E * I, cowper_rectangle(nu) * G * A, rho * A, rho * I if rotary else 0.0, L)
    w_eb = 2.0 * math.pi * euler_bernoulli_hz(E, rho, A, I, L, mode)
    w = brentq(lambda w: _end_determinant(w, *args), 0.95 * w_eb, 1.0001 * w_eb, xtol=1e-13 * w_eb, rtol=1e-15)
    return w / (2.0 * math.pi)
