"""Materials: the small-strain limit is Hooke's law with the documented (E, nu),
and one element in homogeneous uniaxial stretch follows the closed-form
stress-stretch curve of each law."""
import math

import numpy as np
import sympy as sp

from gen.materials import all_materials as _all
from util import Kernel, rel, run_scene, ROOT, BUILD, ensure_dir

def all_materials():
    """The continuum (hyperelastic) laws; the resultant potential of beams is tested in test_rods."""
    return {k: v for k, v in _all().items() if getattr(v[0], "KIND", "continuum") == "continuum"}


# Parameter values used to exercise each law (kernel order, SI units).
PARAMS = {
    "svk": (1.3e6, 0.7e6),
    "neo_hookean": (2.1e6, 0.45e6),
    "mooney_rivlin": (0.3e6, 0.05e6, 5.0e7),
    "arruda_boyce": (0.3e6, 3.0, 1.0e8),
}


def hooke(E, nu):
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    d = lambda a, b: 1.0 if a == b else 0.0
    return np.array([[[[lam * d(i, J) * d(k, L) + mu * (d(i, k) * d(J, L) + d(i, L) * d(J, k))
                        for L in range(3)] for k in range(3)] for J in range(3)] for i in range(3)])


def test_every_material_is_covered():
    assert sorted(all_materials()) == sorted(PARAMS), "add the new material to PARAMS in this test"


def test_small_strain_limit_is_hooke():
    """d2W/dF dF at F = I equals the isotropic elasticity tensor for the (E, nu) of each
    material's small_strain() mapping, and the reference state is stress free."""
    Fs = sp.Matrix(3, 3, sp.symbols("f0:9", real=True))
    C = Fs.T * Fs
    I1 = C.trace()
    I2 = (I1**2 - (C * C).trace()) / 2
    J = Fs.det()
    at_I = {Fs[i, j]: (1 if i == j else 0) for i in range(3) for j in range(3)}
    for name, (mod, _) in all_materials().items():
        vals = PARAMS[name]
        p = {k: sp.nsimplify(v) for k, v in zip(mod.PARAMS, vals)}
        W = mod.energy(I1, I2, J, p)
        E, nu = (float(x) for x in mod.small_strain(*[p[k] for k in mod.PARAMS]))
        ref = hooke(E, nu)
        for i in range(3):
            for Jj in range(3):
                P = float(sp.diff(W, Fs[i, Jj]).subs(at_I))
                assert abs(P) <= 1e-9 * E, (name, "stress at F = I", i, Jj, P)
                for k in range(3):
                    for L in range(3):
                        A = float(sp.diff(W, Fs[i, Jj], Fs[k, L]).subs(at_I))
                        assert abs(A - ref[i, Jj, k, L]) <= 1e-10 * E, (name, i, Jj, k, L, A, ref[i, Jj, k, L])


def test_element_tangent_at_reference_is_linear_elastic():
    """The generated tangent of every pair at the reference state equals the St. Venant-Kirchhoff
    (linear elastic) tangent with the same small-strain (E, nu)."""
    mats = all_materials()
    geom = [0.2, 0.03, 0.02]
    for elem in ("ancf3243", "ancf3333", "ancf3273", "ancf3363"):
        ref_k = Kernel(elem, "svk")
        tab = ref_k.tabulate(geom)
        q0 = reference_coordinates(elem, geom)
        for name, (mod, _) in mats.items():
            E, nu = (float(x) for x in mod.small_strain(*PARAMS[name]))
            lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
            _, f0, K0 = ref_k.eval(q0, tab, [lam, mu])
            _, f, K = Kernel(elem, name).eval(q0, tab, list(PARAMS[name]))
            err = np.abs(K - K0).max() / np.abs(K0).max()
            assert err <= 1e-9, f"{elem} x {name}: tangent differs from linear elasticity by {err:.2e}"
            assert np.abs(f).max() <= 1e-9 * np.abs(K0).max() * geom[0], (elem, name, np.abs(f).max())


def reference_coordinates(elem, geom):
    import json
    idx = json.loads((ROOT / "out" / "kernels" / "index.json").read_text())
    q = []
    for nd in idx["elements"][elem]["nodes"]:
        a, b = (int(x) for x in nd["xi"].split("/")) if "/" in nd["xi"] else (int(nd["xi"]), 1)
        for v, _ in nd["fields"]:
            q += {"r": [geom[0] * a / b, 0, 0], "r_x": [1, 0, 0], "r_y": [0, 1, 0],
                  "r_z": [0, 0, 1]}.get(v, [0, 0, 0])
    return np.array(q, dtype=float)


def principal_stresses(mod, params, lam1, lamt):
    """Nominal stresses (P1, P2) of W(l1, l2, l3) at (lam1, lamt, lamt): an evaluation of
    the law written in principal stretches, independent of the element machinery."""
    l1, l2, l3 = sp.symbols("l1 l2 l3", positive=True)
    I1 = l1**2 + l2**2 + l3**2
    I2 = l1**2 * l2**2 + l2**2 * l3**2 + l1**2 * l3**2
    J = l1 * l2 * l3
    p = {k: sp.Float(v, 30) for k, v in zip(mod.PARAMS, params)}
    W = mod.energy(I1, I2, J, p)
    at = {l1: sp.Float(lam1, 30), l2: sp.Float(lamt, 30), l3: sp.Float(lamt, 30)}
    return float(sp.diff(W, l1).subs(at).evalf(30)), float(sp.diff(W, l2).subs(at).evalf(30))


SCENE = """[scene]
analysis = "static"
[material.m]
law = "{law}"
rho = 1000.0
{params}
[section.s]
shape = "rectangle"
b = 0.01
h = 0.012
[[beam]]
name = "bar"
element = "{elem}"
integration = "{integ}"
material = "m"
section = "s"
start = [0.0, 0.0, 0.0]
end = [0.1, 0.0, 0.0]
elements = 1
[[constraint]]
type = "clamp"
a = "bar:start"
cross_section = "free"
[[load]]
type = "force"
at = "bar:end"
value = [{force!r}, 0.0, 0.0]
distribution = "section"
[static]
load_steps = 4
rtol = 1e-13
utol = 1e-13
[[sensor]]
name = "tip"
at = "bar:end"
[[sensor]]
name = "mid"
at = "bar:0.05"
"""


def test_uniaxial_stretch_follows_closed_form():
    """One element, root section free to contract, end traction F: the axial and lateral
    stretches satisfy P1(l, lt) A0 = F and P2(l, lt) = 0 of the closed-form law to 1e-8."""
    d = ensure_dir(BUILD / "uniaxial")
    A0 = 0.01 * 0.012
    worst = []
    for name, (mod, _) in all_materials().items():
        vals = PARAMS[name]
        E, nu = (float(x) for x in mod.small_strain(*vals))
        target = 1.25 if name != "svk" else 1.1
        # lateral stretch for the target from P2 = 0 (bisection on the closed form)
        lo, hi = 0.5, 1.0
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            if principal_stresses(mod, vals, target, mid)[1] > 0:
                hi = mid
            else:
                lo = mid
        force = principal_stresses(mod, vals, target, 0.5 * (lo + hi))[0] * A0
        params = "\n".join(f"{k} = {v!r}" for k, v in zip(mod.PARAMS, vals))
        for elem, integ in (("ancf3243", "full"), ("ancf3243", "sri"), ("ancf3333", "full"),
                            ("ancf3273", "full"), ("ancf3363", "full")):
            path = d / f"{name}_{elem}_{integ}.toml"
            path.write_text(SCENE.format(law=name, params=params, elem=elem, integ=integ, force=force))
            s, rows = run_scene(path)
            tip, mid = s["sensors"]["tip"], s["sensors"]["mid"]
            lam = 1 + tip["displacement"][0] / 0.1
            lamt = math.sqrt(sum(x * x for x in tip["d1"]))
            P1, P2 = principal_stresses(mod, vals, lam, lamt)
            e1 = abs(P1 * A0 - force) / force
            e2 = abs(P2) / abs(P1)
            e3 = abs(mid["displacement"][0] - tip["displacement"][0] / 2) / abs(tip["displacement"][0])
            if max(e1, e2, e3) > 1e-8:
                worst.append(f"{name} {elem} {integ}: stretch {lam:.6f}, lateral {lamt:.6f}: "
                             f"|P1 A0 - F|/F = {e1:.1e}, |P2|/P1 = {e2:.1e}, homogeneity {e3:.1e}")
    assert not worst, "\n".join(worst)
