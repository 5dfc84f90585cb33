"""Dynamics: generalized-alpha with constraints against the rigid pendulum, energy
balance, constraint residuals, convergence order, Euler-Bernoulli frequencies
(modal and free vibration), Rayleigh decay, joints and prescribed motion."""
import csv
import math
import tempfile

import numpy as np

from references.pencil import matrix_pencil
from references.rigid_pendulum import rigid_pendulum as rigid_pendulum_lists
from util import BUILD, ensure_dir, load_run, run_scene

G, L = 9.81, 1.0


def rigid_pendulum(t_end, n=40000, g=G):
    """The rigid rod pendulum (references/rigid_pendulum.py) as arrays (times, tip x, tip z)."""
    return tuple(np.array(v) for v in rigid_pendulum_lists(t_end, n=n, g=g, L=L))


def agm_K(k):
    """Complete elliptic integral of the first kind by the arithmetic-geometric mean."""
    a, b = 1.0, math.sqrt(1 - k * k)
    for _ in range(40):
        a, b = (a + b) / 2, math.sqrt(a * b)
    return math.pi / (2 * a)


def tip_series(rows, name):
    r = [x for x in rows if x["sensor"] == name]
    return (np.array([float(x["time"]) for x in r]), np.array([[float(x[k]) for k in ("x", "y", "z")] for x in r]))


def energies(out):
    with open(f"{out}/energy.csv", newline="") as fh:
        return list(csv.DictReader(fh))


def run(scene, sets):
    out = tempfile.mkdtemp(prefix="bk-dyn-", dir=ensure_dir(BUILD / "runs"))
    s, rows = run_scene(scene, sets, out=out)
    return s, rows, out


def test_stiff_pendulum_is_the_rigid_pendulum():
    """E = 7e11: the tip path of ancf3243 and gef follows the rigid rod pendulum to 1e-3 L
    over 1 s (dt = 1e-3), the two elements agree to 1e-3 L, the constraint holds to
    1e-10 m at every step, and the time to swing to the opposite horizontal is half the
    closed-form period 4 sqrt(2L/(3g)) K(sin 45 deg)."""
    t_ref, x_ref, z_ref = rigid_pendulum(1.2)
    paths = {}
    for scene in ("pendulum_stiff_ancf", "pendulum_stiff_gef"):
        s, rows, out = run(scene, ["dynamic.t_end=1.1", "dynamic.dt=1e-3"])
        t, p = tip_series(rows, "B")
        paths[scene] = p
        xr, zr = np.interp(t, t_ref, x_ref), np.interp(t, t_ref, z_ref)
        m = t <= 1.0 + 1e-9
        err = np.max(np.hypot(p[m, 0] - xr[m], p[m, 2] - zr[m]))
        assert err <= 1e-3 * L, f"{scene}: tip path {err:.2e} m from the rigid pendulum"
        assert s["max_constraint_residual"] <= 1e-10, s["max_constraint_residual"]
        assert max(float(e["constraint_residual"]) for e in energies(out)) <= 1e-10
        # time of the upward zero crossing of z after the lowest point: half a period
        i = next(k for k in range(1, len(t)) if p[k - 1, 2] < 0 <= p[k, 2] and t[k] > 0.5)
        t_half = t[i - 1] + (t[i] - t[i - 1]) * (-p[i - 1, 2]) / (p[i, 2] - p[i - 1, 2])
        T = 4 * math.sqrt(2 * L / (3 * G)) * agm_K(math.sin(math.pi / 4))
        assert abs(t_half - T / 2) <= 2e-3 * T / 2, (scene, t_half, T / 2)
    a, b = paths.values()
    n = min(len(a), len(b))
    assert np.max(np.linalg.norm(a[:n] - b[:n], axis=1)) <= 1e-3 * L


def test_energy_is_conserved_without_dissipation():
    """Soft pendulum, rho_inf = 1, dt = 5e-4: total energy drift <= 1e-4 of the
    gravity potential range over 2 s."""
    s, rows, out = run("pendulum_soft_ancf", ["dynamic.rho_inf=1.0", "dynamic.dt=5e-4"])
    e = energies(out)
    scale = max(abs(float(x["gravity"])) for x in e)
    drift = max(abs(float(x["total"])) for x in e) / scale
    assert drift <= 1e-4, drift


def test_energy_does_not_grow_with_dissipation():
    """With physical damping (Rayleigh, Kelvin-Voigt) the total energy decreases at every
    step (to round-off); with numerical dissipation alone (rho_inf = 0.8) it never rises
    above its initial value by more than 1e-4 and ends below it."""
    s, rows, out = run("pendulum_soft_ancf", ["dynamic.rho_inf=1.0", "dynamic.dt=1e-3",
                                              "dynamic.rayleigh_alpha=0.5", "dynamic.rayleigh_beta=1e-4"])
    tot = [float(x["total"]) for x in energies(out)]
    scale = max(abs(float(x["gravity"])) for x in energies(out))
    assert max(tot[i + 1] - tot[i] for i in range(len(tot) - 1)) <= 1e-12 * scale
    s, rows, out = run("silicone_fall_damped", ["dynamic.t_end=0.1"])
    tot = [float(x["total"]) for x in energies(out)]
    scale = max(abs(float(x["gravity"])) for x in energies(out))
    assert max(tot[i + 1] - tot[i] for i in range(len(tot) - 1)) <= 1e-12 * scale
    assert tot[-1] < -1e-3 * scale
    s, rows, out = run("pendulum_soft_ancf", ["dynamic.rho_inf=0.8", "dynamic.dt=1e-3"])
    tot = [float(x["total"]) for x in energies(out)]
    scale = max(abs(float(x["gravity"])) for x in energies(out))
    assert max(tot) <= 1e-4 * scale and tot[-1] < 0, (max(tot) / scale, tot[-1] / scale)


def test_double_pendulum_joint_and_constraint_residual():
    """Double pendulum (spherical joint to ground, spherical joint between the rods): the
    joint points coincide and every constraint row holds to 1e-10 at every step."""
    for scene in ("double_pendulum_soft_ancf", "double_pendulum_soft_gef"):
        s, rows, out = run(scene, ["dynamic.t_end=0.05", "dynamic.output_every=1"])
        assert s["max_constraint_residual"] <= 1e-10, (scene, s["max_constraint_residual"])
        assert max(float(e["constraint_residual"]) for e in energies(out)) <= 1e-10


def test_second_order_convergence():
    """Soft pendulum (ancf3243), tip position at t = 0.5 s for dt = 4e-4 ... 5e-5 against
    dt = 1e-5: fitted order 2 +- 0.2."""
    def tip(dt):
        s, rows, out = run("pendulum_soft_ancf", ["dynamic.t_end=0.5", f"dynamic.dt={dt}",
                                                  "dynamic.output_every=100000000"])
        t, p = tip_series(rows, "B")
        assert abs(t[-1] - 0.5) < 1e-12
        return p[-1]
    ref = tip(1e-5)
    dts = [4e-4, 2e-4, 1e-4, 5e-5]
    errs = [np.linalg.norm(tip(dt) - ref) for dt in dts]
    slope = np.polyfit(np.log(dts), np.log(errs), 1)[0]
    assert abs(slope - 2.0) <= 0.2, (errs, slope)


def eb_frequencies(E=2.1e11, rho=7850.0, b=0.01, h=0.01, Lb=1.0):
    c = math.sqrt(E * b * h**3 / 12 / (rho * b * h))
    return [bl * bl / (2 * math.pi * Lb * Lb) * c for bl in (1.8751, 4.6941, 7.8548)]


def test_modal_frequencies_match_euler_bernoulli():
    """First three bending frequencies of a slender cantilever (each twice: square
    section) within 0.5 % of beta L = 1.8751, 4.6941, 7.8548, for gef, ancf3243 with
    selective reduced integration (full integration locks at nu = 0.3: 16 % high) and
    ancf3363."""
    exact = eb_frequencies()
    ancf = ["material.steel.law=svk", "constraint.0.cross_section=free"]
    for sets in ([], ["beam.arm.element=ancf3243", "beam.arm.integration=sri"] + ancf,
                 ["beam.arm.element=ancf3363", "beam.arm.elements=40"] + ancf):
        if "beam.arm.integration=sri" in sets:
            sets = sets + ["beam.arm.elements=40"]          # 3243 converges at second order
        s, rows, out = run("cantilever_modal", sets)
        f = s["frequencies_hz"]
        got = [f[0], f[2], f[4]]
        for g, x in zip(got, exact):
            assert abs(g - x) <= 5e-3 * x, (sets, got, exact)
        assert abs(f[1] - f[0]) <= 1e-6 * f[0]


def free_vibration(sets):
    s, rows, out = run("cantilever_modal", ["scene.analysis=dynamic"] + sets)
    t, p = tip_series(rows, "tip")
    return t, p[:, 2]


def test_free_vibration_frequencies_match_euler_bernoulli():
    """Free vibration (rho_inf = 1, dt = 1e-4, started by a small rigid-rotation velocity):
    the first three frequencies of the tip signal (matrix pencil) within 0.5 %."""
    t, z = free_vibration([])
    f, d = matrix_pencil(z - z.mean() * 0, t[1] - t[0], 6)
    exact = eb_frequencies()
    assert len(f) >= 3, f
    for g, x in zip(f[:3], exact):
        assert abs(g - x) <= 5e-3 * x, (f, exact)


def test_rayleigh_damping_decay_rate():
    """Rayleigh damping C = alpha M + beta K: the first mode decays at
    (alpha + beta omega_1^2) / 2 within 1 %."""
    alpha, beta = 2.0, 1e-5
    t, z = free_vibration([f"dynamic.rayleigh_alpha={alpha}", f"dynamic.rayleigh_beta={beta}"])
    f, d = matrix_pencil(z, t[1] - t[0], 6)
    w1 = 2 * math.pi * f[0]
    exact = (alpha + beta * w1 * w1) / 2
    assert abs(d[0] - exact) <= 1e-2 * exact, (f[0], d[0], exact)


REVOLUTE = """[scene]
analysis = "dynamic"
[material.rod]
law = "{law}"
E = 7.0e11
nu = 0.3
rho = 2700.0
[section.square]
shape = "rectangle"
b = 0.01
h = 0.01
[[beam]]
name = "rod"
element = "{elem}"
material = "rod"
section = "square"
start = [0.0, 0.0, 0.0]
end = [1.0, 0.0, 0.0]
elements = 6
[[constraint]]
type = "{ctype}"
a = "rod:start"
axis = {axis}
{extra}
[[load]]
type = "gravity"
value = [0.0, 0.0, -9.81]
[dynamic]
t_end = 0.5
dt = 2e-3
[[sensor]]
name = "tip"
at = "rod:end"
"""


def test_revolute_pendulum_about_a_tilted_axis():
    """A stiff pendulum on a revolute joint whose axis (0, 0.6, 0.8) is tilted from the
    vertical swings like the rigid pendulum under the gravity component normal to the
    axis (g 0.6): tip path within 1e-3 L over 0.5 s (the axial component bends the rod
    out of the plane by its elastic deflection only), for ancf3243 and gef."""
    axis = np.array([0.0, 0.6, 0.8])
    g_perp = np.array([0.0, 0.0, -G]) - np.dot([0.0, 0.0, -G], axis) * axis
    e2 = g_perp / np.linalg.norm(g_perp)
    geff = np.linalg.norm(g_perp)
    d = ensure_dir(BUILD / "joints")
    for elem, law in (("ancf3243", "svk"), ("gef", "resultant")):
        p = d / f"revolute_{elem}.toml"
        p.write_text(REVOLUTE.format(law=law, elem=elem, ctype="revolute", axis="[0.0, 0.6, 0.8]", extra=""))
        s, rows = run_scene(p)
        t, pos = tip_series(rows, "tip")
        tr, xr, zr = rigid_pendulum(0.6, g=geff)
        xi, zi = np.interp(t, tr, xr), np.interp(t, tr, zr)
        exact = np.outer(xi, [1.0, 0.0, 0.0]) - np.outer(zi, e2)
        err = np.max(np.linalg.norm(pos - exact, axis=1))
        assert err <= 1e-3 * L, (elem, err)
        assert np.max(pos @ e2) > 0.3                     # it did swing down the tilted plane
        assert s["max_constraint_residual"] <= 1e-10


def test_prescribed_rotation_turns_a_stiff_beam_rigidly():
    """A stiff beam whose root follows a prescribed rotation (1 rad/s about z, no gravity,
    started with the matching rigid-rotation velocity): the tip follows the rigid
    rotation to 1e-6 m after 0.5 s, for ancf3243 and gef."""
    d = ensure_dir(BUILD / "joints")
    for elem, law in (("ancf3243", "svk"), ("gef", "resultant")):
        p = d / f"spin_{elem}.toml"
        txt = REVOLUTE.format(law=law, elem=elem, ctype="prescribed_rotation", axis="[0.0, 0.0, 1.0]",
                              extra="rate = 1.0")
        txt = txt.replace("value = [0.0, 0.0, -9.81]", "value = [0.0, 0.0, 0.0]")
        txt += "[[initial_velocity]]\nangular_velocity = [0.0, 0.0, 1.0]\n"
        p.write_text(txt)
        s, rows = run_scene(p, ["dynamic.dt=1e-3"])
        t, pos = tip_series(rows, "tip")
        exact = np.array([np.cos(t[-1]), np.sin(t[-1]), 0.0])
        assert np.linalg.norm(pos[-1] - exact) <= 1e-6, (elem, pos[-1], exact)
