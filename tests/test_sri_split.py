"""The SRI split of gen/uniaxial.py: its uniaxial-stress energy U(c) and
derivatives against a direct numerical minimisation over the lateral stretch
(scipy, a second implementation), for every material and for a Yeoh law written
here (a new material gets the split with no code of its own); for St.
Venant-Kirchhoff the split is exactly the one the law used before,
E/2 E11^2 + 2 mu (E12^2 + E13^2)."""
import types

import numpy as np
import sympy as sp
from scipy.optimize import minimize_scalar

from gen.materials import all_materials
from gen.program import Program
from gen.uniaxial import U0, U1, U2, define_uniaxial, full_order_energy, shear_modulus

YEOH = types.SimpleNamespace(
    NAME="yeoh", PARAMS=("c1", "c2", "c3", "kappa"),
    energy=lambda I1, I2, J, p: (p["c1"] * (J**sp.Rational(-2, 3) * I1 - 3) + p["c2"] * (J**sp.Rational(-2, 3) * I1 - 3)**2
                                 + p["c3"] * (J**sp.Rational(-2, 3) * I1 - 3)**3 + p["kappa"] / 2 * (J - 1)**2))

VALUES = {"svk": {"lambda": 1.2, "mu": 0.8}, "neo_hookean": {"lambda": 3.0, "mu": 1.0},
          "mooney_rivlin": {"c10": 0.3, "c01": 0.1, "kappa": 80.0},
          "arruda_boyce": {"mu": 0.3, "lambda_m": 3.0, "kappa": 300.0},
          "yeoh": {"c1": 0.2, "c2": -0.01, "c3": 0.005, "kappa": 200.0}}


def materials():
    out = {n: m for n, (m, _) in all_materials().items() if n in VALUES}
    out["yeoh"] = YEOH
    return out


def generated_uniaxial(mat, vals, c):
    """U, U', U'' as the generated program computes them, evaluated numerically."""
    params = {k: sp.Symbol(k, positive=True) for k in mat.PARAMS}
    prog = Program()
    csym = sp.Symbol("C00", positive=True)
    repl = define_uniaxial(prog, mat, params, csym)
    env = {csym: c, **{params[k]: v for k, v in vals.items()}}
    for s, e in prog.defs:
        env[s] = float(e.xreplace(env))
    return [env[repl[f(csym)]] for f in (U0, U1, U2)]


def numeric_uniaxial(mat, vals, c):
    params = {k: sp.Float(v) for k, v in vals.items()}
    cc, dd = sp.symbols("cc dd", positive=True)
    w = sp.lambdify((cc, dd), mat.energy(cc + 2 * dd, 2 * cc * dd + dd**2, sp.sqrt(cc) * dd, params))

    def U(x):
        r = minimize_scalar(lambda d: w(x, d), bounds=(0.05, 5.0), method="bounded",
                            options={"xatol": 1e-13, "maxiter": 500})
        return r.fun
    h = 1e-4
    return U(c), (U(c + h) - U(c - h)) / (2 * h), (U(c + h) - 2 * U(c) + U(c - h)) / h**2


def test_uniaxial_energy_matches_numerical_minimisation():
    for name, mat in materials().items():
        for c in (0.7, 0.95, 1.0, 1.1, 1.6):
            g = generated_uniaxial(mat, VALUES[name], c)
            n = numeric_uniaxial(mat, VALUES[name], c)
            scale = max(1.0, abs(n[2]))
            assert abs(g[0] - n[0]) <= 1e-9 * scale, (name, c, g[0], n[0])
            assert abs(g[1] - n[1]) <= 1e-6 * scale, (name, c, g[1], n[1])
            assert abs(g[2] - n[2]) <= 1e-3 * scale, (name, c, g[2], n[2])


def test_svk_split_is_the_former_one():
    mat = all_materials()["svk"][0]
    lam, mu = sp.symbols("lambda mu", positive=True)
    p = {"lambda": lam, "mu": mu}
    C = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"C{min(i, j)}{max(i, j)}", real=True))
    prog = Program()
    repl = define_uniaxial(prog, mat, p, C[0, 0])
    W = full_order_energy(mat, p, C).xreplace(repl)
    for s, e in reversed(prog.defs):
        W = W.subs(s, e)
    E = mu * (3 * lam + 2 * mu) / (lam + mu)
    former = E / 2 * ((C[0, 0] - 1) / 2)**2 + 2 * mu * ((C[0, 1] / 2)**2 + (C[0, 2] / 2)**2)
    assert sp.simplify(W - former) == 0


def test_shear_modulus_is_the_small_strain_one():
    for name, mat in materials().items():
        p = {k: sp.Float(v) for k, v in VALUES[name].items()}
        g = sp.Symbol("g")
        # independent: energy of a small simple shear, W = mu0 g^2 / 2 + O(g^4) with C = I + g(e1e2 + e2e1)
        # (numerical second difference)
        f = sp.lambdify(g, mat.energy(sp.Integer(3), 3 - g**2, sp.sqrt(1 - g**2), p))
        h = 1e-4
        num = (f(h) - 2 * f(0.0) + f(-h)) / h**2
        assert abs(float(shear_modulus(mat, p)) - num) <= 1e-5 * abs(num), (name, num)


def test_lateral_stretch_is_the_root_to_round_off():
    """The generated iteration (gen/uniaxial.py: HALLEY_STEPS steps from
    c^-nu_log) ends on the root of dw/dd = 0 to round-off over axial stretches
    from 0.32 to 3.2 (c from 0.1 to 10) and nearly incompressible to
    compressible parameters; the root by bisection in 60-digit arithmetic
    (mpmath), from a bracket checked by sign, not by the kernel's iteration."""
    import mpmath as mp
    from gen.uniaxial import _c, _d, lateral_energy
    mp.mp.dps = 60
    cases = {"neo_hookean": [{"lambda": nu / ((1 + nu) * (1 - 2 * nu)), "mu": 1 / (2 * (1 + nu))}
                             for nu in (0.3, 0.45, 0.49, 0.4999)],
             "mooney_rivlin": [{"c10": 0.5 * a, "c01": 0.5 * (1 - a), "kappa": k}
                               for a in (1.0, 0.2) for k in (10.0, 1000.0, 1e4)],
             "arruda_boyce": [{"mu": 1.0, "lambda_m": lm, "kappa": k} for lm in (1.5, 7.0) for k in (10.0, 1e4)],
             "yeoh": [dict(VALUES["yeoh"], kappa=k) for k in (20.0, 2000.0)]}
    mats = materials()
    for name, grid in cases.items():
        mat = mats[name]
        params = {k: sp.Symbol(k, positive=True) for k in mat.PARAMS}
        csym = sp.Symbol("C00", positive=True)
        prog = Program()
        define_uniaxial(prog, mat, params, csym)
        dstar = [s for s, _ in prog.defs if str(s).startswith("ulat")][-1]
        wd = sp.diff(lateral_energy(mat, params), _d)
        for vals in grid:
            f = sp.lambdify((_c, _d), wd.subs({params[k]: v for k, v in vals.items()}), "mpmath")
            for c in np.geomspace(0.1, 10.0, 9):
                env = {csym: float(c), **{params[k]: v for k, v in vals.items()}}
                for s, e in prog.defs:
                    env[s] = float(e.xreplace(env))
                lo, hi = mp.mpf("1e-6"), mp.mpf(20)
                assert f(c, lo) < 0 < f(c, hi), (name, vals, c)
                for _ in range(200):
                    mid = (lo + hi) / 2
                    lo, hi = (mid, hi) if f(c, mid) < 0 else (lo, mid)
                root = float(lo)
                assert abs(env[dstar] - root) <= 4e-15 * root, (name, vals, c, env[dstar], root)
