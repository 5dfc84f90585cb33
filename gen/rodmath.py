"""Smooth special functions of rotation kinematics, for sympy and C.

Rotations are carried by quaternions.  Two maps need functions that are smooth
at zero angle but whose textbook formulas divide by zero there:

  exp:  a rotation vector psi (angle phi = |psi|, u = phi^2) has the unit
        quaternion (Ch(u), Sh(u) psi) with Ch(u) = cos(sqrt(u)/2) and
        Sh(u) = sin(sqrt(u)/2) / sqrt(u);
  log:  a quaternion (s, v), not necessarily unit, has the rotation vector
        2 At(|v|^2, s) v with At(u, s) = atan2(sqrt(u), s) / sqrt(u).

For sympy they are Function classes whose derivatives are again such functions
(or plain expressions), so forces and tangents differentiate through them.  For
C, `rod_math.h` implements each with a power series near zero (coefficients
exact from sympy) and the closed form elsewhere; both branches agree to
round-off at the switch (tests/test_rods.py checks them against mpmath-precision
sympy evaluations).
"""
import sympy as sp

# Series lengths and switch points: Sh series in u/4 for u < 4 (terms decay
# like 1/(2k+1)!); At series in x = u/s^2 for s > 0 and x < 1/4.
SH_TERMS = 16
SH_SWITCH = 4.0
AT_TERMS = 36
AT_SWITCH = 0.25


class _CFunc(sp.Function):
    c_name = None


class Sh(_CFunc):
    """sin(sqrt(u)/2)/sqrt(u)"""
    nargs = 1
    c_name = "bk_sh"

    def fdiff(self, argindex=1):
        return Sh1(self.args[0])


class Sh1(_CFunc):
    nargs = 1
    c_name = "bk_sh1"

    def fdiff(self, argindex=1):
        return Sh2(self.args[0])


class Sh2(_CFunc):
    nargs = 1
    c_name = "bk_sh2"

    def fdiff(self, argindex=1):
        return Sh3(self.args[0])


class Sh3(_CFunc):
    nargs = 1
    c_name = "bk_sh3"

    def fdiff(self, argindex=1):
        raise NotImplementedError("fourth derivative of Sh is not provided")


class Ch(_CFunc):
    """cos(sqrt(u)/2); d/du = -Sh(u)/4"""
    nargs = 1
    c_name = "bk_ch"

    def fdiff(self, argindex=1):
        return -Sh(self.args[0]) / 4


class At(_CFunc):
    """atan2(sqrt(u), s)/sqrt(u)"""
    nargs = 2
    c_name = "bk_at"

    def fdiff(self, argindex=1):
        u, s = self.args
        if argindex == 1:
            return At_u(u, s)
        return -1 / (u + s**2)


class At_u(_CFunc):
    nargs = 2
    c_name = "bk_at_u"

    def fdiff(self, argindex=1):
        u, s = self.args
        if argindex == 1:
            return At_uu(u, s)
        return 1 / (u + s**2)**2


class At_uu(_CFunc):
    nargs = 2
    c_name = "bk_at_uu"

    def fdiff(self, argindex=1):
        raise NotImplementedError("third derivatives of At are not provided")


# ----------------------------------------------------------------------------
# closed forms (sympy, for the C branches and for the tests)

_u = sp.Symbol("u", positive=True)
_s = sp.Symbol("s", real=True)


def closed_forms():
    """name -> sympy closed form in (u) or (u, s)."""
    sh = sp.sin(sp.sqrt(_u) / 2) / sp.sqrt(_u)
    at = sp.atan2(sp.sqrt(_u), _s) / sp.sqrt(_u)
    at_u = (_s / (_u + _s**2) - at) / (2 * _u)
    at_uu = (-_s / (_u + _s**2)**2 - 3 * at_u) / (2 * _u)
    return {"bk_sh": sh, "bk_sh1": sp.diff(sh, _u), "bk_sh2": sp.diff(sh, _u, 2),
            "bk_sh3": sp.diff(sh, _u, 3), "bk_at": at, "bk_at_u": at_u, "bk_at_uu": at_uu}


def sh_series_coeffs(n):
    """Coefficients c_k of Sh^(n)(u) = sum_k c_k u^k (exact rationals)."""
    out = []
    for k in range(SH_TERMS):
        j = k + n                     # term u^j of Sh, differentiated n times
        c = sp.Rational((-1)**j, 2 * 4**j * sp.factorial(2 * j + 1)) * sp.ff(j, n)
        out.append(c)
    return out


def at_series_coeffs(n):
    """At^(n)_u(u, s) = s^-(2n+1) sum_k c_k x^k with x = u/s^2."""
    out = []
    for k in range(AT_TERMS):
        j = k + n
        out.append(sp.Rational((-1)**j, 2 * j + 1) * sp.ff(j, n))
    return out


def _horner(coeffs, x):
    s = f"{float(coeffs[-1])!r}"
    for c in reversed(coeffs[:-1]):
        s = f"({float(c)!r} + {x} * {s})"
    return s


def rod_math_header(banner, h):
    from gen.program import print_c
    cf = closed_forms()
    lines = [f"/* {banner}", " * generator: gen/rodmath.py", f" * input hash: sha256:{h}", " *"]
    lines += [" * " + l if l.strip() else " *" for l in __doc__.strip().splitlines()]
    lines += [" */", "#ifndef BK_GEN_ROD_MATH_H", "#define BK_GEN_ROD_MATH_H", "", "#include <math.h>", ""]
    lines += ["/* cos(sqrt(u)/2) */",
              "static inline double bk_ch(double u) { return cos(0.5 * sqrt(u)); }", ""]
    for n, name in enumerate(("bk_sh", "bk_sh1", "bk_sh2", "bk_sh3")):
        expr = cf[name].subs(_u, sp.Symbol("u"))
        lines += [f"/* d^{n}/du^{n} [sin(sqrt(u)/2)/sqrt(u)] */",
                  f"static inline double {name}(double u)", "{",
                  f"    if (u < {SH_SWITCH!r})",
                  f"        return {_horner(sh_series_coeffs(n), 'u')};",
                  f"    return {print_c(expr)};", "}", ""]
    for n, name in enumerate(("bk_at", "bk_at_u", "bk_at_uu")):
        expr = cf[name].subs({_u: sp.Symbol("u"), _s: sp.Symbol("s")})
        p = 2 * n + 1
        lines += [f"/* d^{n}/du^{n} [atan2(sqrt(u), s)/sqrt(u)] */",
                  f"static inline double {name}(double u, double s)", "{",
                  f"    if (s > 0.0 && u < {AT_SWITCH!r} * s * s) {{",
                  "        const double x = u / (s * s);",
                  f"        return {_horner(at_series_coeffs(n), 'x')} / ({'*'.join(['s'] * p)});",
                  "    }",
                  f"    return {print_c(expr)};", "}", ""]
    lines += ["#endif", ""]
    return "\n".join(lines)
