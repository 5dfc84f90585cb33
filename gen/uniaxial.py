"""The uniaxial-stress part of an isotropic strain energy, for selective
reduced integration (gen/continuum.py, sri_split).

For W(I1, I2, J) and an axial stretch with C11 = c, the lateral stretches that
make the lateral stresses vanish (C22 = C33 = d, no shear) minimise
    w(c, d) = W(c + 2 d, 2 c d + d^2, sqrt(c) d)
over d: dw/dd = 0 at d = d*(c).  The uniaxial energy is U(c) = w(c, d*(c)); by
the envelope theorem U'(c) = w_c and U''(c) = w_cc - w_cd^2 / w_dd at d*.  The
generated kernels solve dw/dd = 0 at each point by HALLEY_STEPS steps of
Halley's method, d <- d - 2 f f' / (2 f'^2 - f f'') with f = dw/dd, from
d0 = c^(-nu_log), nu_log = w_cd / w_dd at c = d = 1 (the small-strain Poisson
ratio in logarithmic strain); St. Venant-Kirchhoff (w quadratic in d, f'' = 0)
takes one, which is exact.  Halley converges cubically: three steps reach
round-off wherever five Newton steps did (c from 0.1 to 10, neo-Hookean
nu <= 0.4999, Mooney-Rivlin and Arruda-Boyce kappa/mu >= 10; tests/test_sri_split.py
checks the root), with the same transcendental (the logarithm or power of J)
once a step for f, f' and f'': each step is a link of a dependency chain that
no other work overlaps, so fewer steps are what the kernel's time follows.
The step is one fraction where that takes no more operations (a vector
division costs as much as 20-30 multiplications).

U0, U1, U2 are sympy functions standing for U, U', U'' in an energy expression;
define_uniaxial() puts their values into a program.
"""
import sympy as sp

from gen.program import count_ops

HALLEY_STEPS = 3


class U2(sp.Function):
    """U''(c) of the uniaxial energy."""
    nargs = 1

    def fdiff(self, argindex=1):
        raise NotImplementedError("third derivative of the uniaxial energy is not needed")


class U1(sp.Function):
    """U'(c)."""
    nargs = 1

    def fdiff(self, argindex=1):
        return U2(self.args[0])


class U0(sp.Function):
    """U(c): energy of uniaxial stress at C11 = c."""
    nargs = 1

    def fdiff(self, argindex=1):
        return U1(self.args[0])


_c, _d = sp.symbols("c_ax d_lat", positive=True)


def lateral_energy(mat, params):
    """w(c, d) of the material with the symbols (c, d)."""
    return mat.energy(_c + 2 * _d, 2 * _c * _d + _d**2, sp.sqrt(_c) * _d, params)


def shear_modulus(mat, params):
    """Small-strain shear modulus mu0 = d2W/dgamma2 at gamma = 0 for
    C = I + gamma (e1 e2^T + e2 e1^T) (E12 = gamma/2, W = 2 mu0 E12^2 + O(gamma^4))."""
    g = sp.Symbol("gamma_s", real=True)
    W = mat.energy(sp.Integer(3), 3 - g**2, sp.sqrt(1 - g**2), params)
    return sp.simplify(sp.diff(W, g, 2).subs(g, 0))


def nu_log(mat, params):
    w = lateral_energy(mat, params)
    at1 = {_c: 1, _d: 1}
    return sp.simplify(sp.diff(w, _c, _d).subs(at1) / sp.diff(w, _d, 2).subs(at1))


def uniaxial_exact(mat, params):
    """True when d*(c) is found in closed form by one Newton step (w quadratic in d)."""
    w = lateral_energy(mat, params)
    return sp.diff(w, _d, 3) == 0


def define_uniaxial(prog, mat, params, c):
    """Defines in prog the lateral stretch d* at C11 = c (a program symbol) and the
    values of U, U', U''; returns {U0(c): ..., U1(c): ..., U2(c): ...} to substitute."""
    w = lateral_energy(mat, params)
    wd, wdd = sp.diff(w, _d), sp.diff(w, _d, 2)
    exact = uniaxial_exact(mat, params)
    steps = 1 if exact else HALLEY_STEPS
    d = prog.define("ulat0", c**(-nu_log(mat, params)) if steps > 1 else sp.Integer(1))
    step = wd / wdd if exact else 2 * wd * wdd / (2 * wdd**2 - wd * sp.diff(w, _d, 3))
    one = sp.together(step)              # one fraction: a single division per step,
    if count_ops(one).total() <= count_ops(step).total():
        step = one                       # where that is no more operations
    for k in range(steps):
        d = prog.define(f"ulat{k + 1}", d - step.subs({_c: c, _d: d}))
    at = {_c: c, _d: d}
    wc = sp.diff(w, _c)
    u0 = prog.define("Uax0", w.subs(at))
    u1 = prog.define("Uax1", wc.subs(at))
    u2 = prog.define("Uax2", (sp.diff(w, _c, 2) - sp.diff(w, _c, _d)**2 / wdd).subs(at))
    return {U0(c): u0, U1(c): u1, U2(c): u2}


def full_order_energy(mat, params, C):
    """The full-order part of the SRI split: uniaxial-stress energy of the axial
    stretch plus the transverse shears with the small-strain shear modulus,
    U(C11) + mu0/2 (C12^2 + C13^2) (element frame, x along the axis)."""
    mu0 = shear_modulus(mat, params)
    return U0(C[0, 0]) + mu0 / 2 * (C[0, 1]**2 + C[0, 2]**2)
