"""Spinning beams (issue 36 point 7) and Bathe's composite integrator
(`dynamic.integrator = "bathe"`, runtime/analysis/dyn_bathe.c).

References that are not our own earlier output: central differences of the
dynamic residual (the iteration matrix's consistency at a spinning state); the
rigid rotation of the hub applied to the undeformed tip plus the closed-form
centrifugal stretch of a spinning bar, u(L) = rho A w^2 L^3 / (3 EA); the closed
form of a linear oscillator (x = v/w sin(w t), for the order of accuracy and
the energy behaviour)."""
import csv
import math
import tempfile
from pathlib import Path

import numpy as np
import pytest

from util import BUILD, ROOT, all_pair_symbols, ensure_dir, run_scene

HUB = ROOT / "models" / "spinning_hub.toml"
L, EA, RHOA, W = 10.0, 2.8e7, 1.2, 6.0
TS = 15.0


def _theta(t):
    """The hub's angle the scene's spline was sampled from (exact from 15 s on:
    6 t - 45)."""
    if t >= TS:
        return W * (t - TS / 2)
    return W / TS * (t * t / 2 + (TS / (2 * math.pi)) ** 2 * (math.cos(2 * math.pi * t / TS) - 1))


def _out():
    return Path(tempfile.mkdtemp(prefix="bk-spin-", dir=ensure_dir(BUILD / "runs")))


def _tip(out):
    rows = [r for r in csv.DictReader(open(out / "sensors.csv", newline="")) if r["sensor"] == "tip"]
    return (np.array([float(r["time"]) for r in rows]), np.array([float(r["x"]) for r in rows]),
            np.array([float(r["y"]) for r in rows]))


def test_iteration_matrix_matches_central_differences_at_a_spinning_state():
    """The generalized-alpha iteration matrix (K_t + gp C + bp M, the gef beam's
    rotary inertia with its gyroscopic terms, the prescribed rotation's rows)
    against central differences of the dynamic residual with q' and q'' moved
    by gp and bp times the step, at the hub's beam turned by 1 rad and spinning
    at 6 rad/s (dt = 0.01 and 0.05): no entry off by more than 1e-4 of its size
    (measured: 2e-6 at worst, the differences' own error).  The tangent is
    consistent: the Newton trouble of the spinning beam under generalized-alpha
    is not an inconsistent Jacobian."""
    from gen.solver_build import VARIANTS, build_solver, compile_object, runtime_headers, runtime_objects
    _, index = all_pair_symbols()
    obj = BUILD / "release" / "dyn_check.o"
    compile_object(ROOT / "tests" / "dyn_check.c", obj, VARIANTS["release"], runtime_headers())
    objs = [o for o in runtime_objects("release") if o.name != "main.o"] + [obj]
    exe = build_solver(["gef_resultant_full"], BUILD / "release" / "dyn_check", index, "release", main_objs=objs)
    out = _out()
    run_scene(HUB, ["dynamic.t_end=0.02"], out=out / "o")
    import subprocess
    for dt in ("0.01", "0.05"):
        r = subprocess.run([str(exe), str(out / "o" / "model.dat"), "20", "1.0", "6", dt], capture_output=True,
                           text=True)
        assert r.returncode == 0, r.stderr
        err, big, _, _, nbad = r.stdout.split()
        assert float(big) > 1e6 and int(nbad) == 0, r.stdout
        assert float(err) < 1e-9 * float(big), r.stdout


def _hub_run(dt, integrator="bathe", t_end=20.0):
    out = _out()
    s, _ = run_scene(HUB, [f"dynamic.dt={dt}", f"dynamic.integrator={integrator}", f"dynamic.t_end={t_end}"],
                     out=out)
    return s, out


def _deviation(out, t_from):
    """The tip's largest distance from the rigid rotation (hub angle applied to
    the undeformed tip, stretched by the closed form u(L)) from t_from on."""
    t, x, y = _tip(out)
    u = RHOA * W ** 2 * L ** 3 / (3 * EA)
    th = np.array([_theta(v) for v in t])
    m = t >= t_from
    d = np.hypot(x - (L + u) * np.cos(th), y - (L + u) * np.sin(th))[m]
    radial = np.hypot(x, y)[m] - L
    return d.max(), radial.mean(), u


def test_spinning_hub_with_bathe_converges_and_follows_the_rigid_rotation():
    """models/spinning_hub.toml (Bathe, dt = 0.01, 20 s): at most 6 Newton
    iterations a step (both sub-steps; measured 5.1), cut-backs on at most 2 %
    of the steps (measured none), and from the end of the spin-up (15 s) on the
    tip within 0.01 m of the rigid rotation (measured 3.7 mm: the residual
    vibration the spin-up leaves), the mean radial stretch the closed form
    u(L) = rho A w^2 L^3/(3 EA) = 0.514 mm within 2 %."""
    s, out = _hub_run(0.01)
    assert s["converged"] and s["steps"] == 2000, s
    assert s["newton_iterations"] / s["steps"] <= 6.0, s["newton_iterations"]
    assert s["cutbacks"] <= 0.02 * s["steps"], s["cutbacks"]
    dev, radial, u = _deviation(out, TS)
    assert dev < 0.01, dev
    assert abs(radial / u - 1) < 0.02, (radial, u)
    print(f"hub dt 0.01: {s['newton_iterations'] / s['steps']:.2f} it/step, {s['cutbacks']} cut-backs, "
          f"deviation {dev:.4g} m, stretch {radial:.4g} m against {u:.4g} m")


@pytest.mark.slow
def test_spinning_hub_at_a_large_step():
    """The same at dt = 0.05 (Bathe): converged without cut-backs; the tip from
    15 s on within 0.015 m of the rigid rotation (measured 12.5 mm: the 3.7 mm
    residual vibration and a lag of 8.3 mm that falls as h^3, 1.2 mm at dt =
    0.025 -- the backward-difference sub-step's drag on a motion turning 0.3 rad
    a step; issue 36's 0.01 m is not met at this step; 8.2 mm at dt = 0.04; a
    point mass on a hub-fixed spring lags the same way, so it is the scheme on the
    translations, not the rotation update: docs/explanation/robustness.md).  Generalized-alpha
    (rho_inf = 0.95) on the same scene: for the record, 1.2 m off with tens of
    thousands of cut-backs (not asserted)."""
    s, out = _hub_run(0.05)
    assert s["converged"] and s["cutbacks"] == 0, s
    dev, _, _ = _deviation(out, TS)
    assert dev < 0.015, dev
    print(f"hub dt 0.05: {s['newton_iterations'] / s['steps']:.2f} it/step, deviation {dev:.4g} m")


OSC = """[scene]
analysis = "dynamic"
[[body]]
name = "m"
mass = 2.0
center = [0.0, 0.0, 0.0]
inertia = [1e-3, 1e-3, 1e-3]
[[spring]]
a = "m"
b = [0.0, 0.0, 0.3]
stiffness = 800.0
[[initial_velocity]]
body = "m"
velocity = [0.0, 0.0, 0.05]
[[sensor]]
name = "m"
at = "m"
[dynamic]
integrator = "bathe"
t_end = {t_end}
dt = {dt}
"""


def _osc(dt, t_end):
    d = _out()
    (d / "osc.toml").write_text(OSC.format(dt=dt, t_end=t_end))
    s, _ = run_scene(d / "osc.toml", out=d / "o")
    rows = [r for r in csv.DictReader(open(d / "o" / "sensors.csv", newline="")) if r["sensor"] == "m"]
    e = list(csv.DictReader(open(d / "o" / "energy.csv", newline="")))
    return s, np.array([float(r["time"]) for r in rows]), np.array([float(r["uz"]) for r in rows]), e


def test_bathe_is_second_order_on_a_linear_oscillator_and_removes_unresolved_energy():
    """A mass on a spring (m = 2 kg, k = 800 N/m, period 0.314 s), started with
    0.05 m/s: z(t) = v/w sin(w t), energy kinetic + k z^2/2.  Over two periods the error at the end falls
    by 4 (order 2: measured order within 1.8 .. 2.2) as the step halves from T/20
    to T/80; the total energy (kinetic + spring) never grows, and loses less than
    0.1 % over the two periods at T/80 (resolved modes keep their energy), while
    at a step of 20 periods (w h = 126, unresolved) it falls below 1 % of its
    start within 3 steps (spectral radius 0 at infinity; at w h = 12.6 the
    energy still keeps 42 % a step)."""
    k, m, v = 800.0, 2.0, 0.05
    w = math.sqrt(k / m)
    T = 2 * math.pi / w
    errs = []
    for n in (20, 40, 80):
        s, t, z, e = _osc(T / n, 2 * T)
        assert s["converged"]
        errs.append(abs(z[-1] - v / w * math.sin(w * t[-1])))
    orders = [math.log2(errs[i] / errs[i + 1]) for i in range(2)]
    assert all(1.8 < p < 2.2 for p in orders), (errs, orders)
    # the energy: kinetic (energy.csv) plus the spring's k z^2 / 2 (sensors.csv; the
    # spring is an interaction, its energy in the balance's work, not in `total`)
    tot = np.array([float(r["kinetic"]) for r in e]) + 0.5 * k * z ** 2
    e0 = 0.5 * m * v * v
    assert abs(tot[0] / e0 - 1) < 1e-12, (tot[0], e0)
    assert np.all(np.diff(tot) <= 1e-12 * e0), np.diff(tot).max()
    assert 0.0 <= 1 - tot[-1] / e0 < 1e-3, tot[-1] / e0
    _, _, z, e = _osc(20 * T, 60 * T)
    tot = np.array([float(r["kinetic"]) for r in e]) + 0.5 * k * z ** 2
    assert tot[3] < 0.01 * e0 and np.all(np.diff(tot) <= 1e-12 * e0), tot
    print("energy at w h = 126:", tot / e0)
    print(f"oscillator: errors {errs}, orders {orders}")


MOTOR_LINK = """[scene]
analysis = "dynamic"
[[body]]
name = "link"
mass = 1.2
center = [0.25, 0.0, 0.0]
inertia = [1e-4, 0.025, 0.025]
[[constraint]]
type = "revolute"
name = "hinge"
a = "link"
at = [0.0, 0.0, 0.0]
axis = [0.0, 0.0, 1.0]
[[actuator]]
name = "motor"
joint = "hinge"
effort = 0.5
[dynamic]
t_end = 1.0
dt = 1e-3
output_every = 100
"""

MOTOR_ARM = """[scene]
analysis = "dynamic"
[material.alu]
law = "resultant"
E = 7.0e10
nu = 0.3
rho = 2700.0
[section.bar]
shape = "rectangle"
b = 0.02
h = 0.005
[[beam]]
name = "arm"
element = "gef"
material = "alu"
section = "bar"
start = [0.0, 0.0, 0.0]
end = [0.5, 0.0, 0.0]
up = [0.0, 1.0, 0.0]
elements = 8
[[constraint]]
type = "revolute"
name = "hinge"
a = "arm:start"
at = [0.0, 0.0, 0.0]
axis = [0.0, 0.0, 1.0]
[amplitude.ramp]
type = "cycloidal"
t0 = 0.0
t1 = 0.2
[[actuator]]
name = "motor"
joint = "hinge"
effort = 0.2
effort_amplitude = "ramp"
[dynamic]
t_end = 0.5
dt = 1e-3
rho_inf = 0.9
output_every = 50
"""


def test_motor_work_closes_the_energy_balance():
    """The motors' work in energy.csv's work_loads (the actuators are an
    interaction: their power tau s' enters with the other interactions', by
    the balance's trapezoidal rule).  A rigid link (J = 0.1 kg m^2 about its
    hinge) under a constant motor torque of 0.5 N m for 1 s: the work tau theta
    = tau^2 t^2/(2J) = 1.25 J within 1e-5 (measured 4.8e-6), the kinetic energy
    J w^2/2 gained within 3e-5 (9.4e-6), the integrator's share (rho_inf 0.8)
    within 1e-5 of it; a flexible gef
    arm spun up by a motor (a cycloidal torque ramp): the balance closes to a
    drift below 1e-3 of the work (measured 1.9e-5)."""
    J, tau = 0.025 + 1.2 * 0.25 ** 2, 0.5
    for text, rigid in ((MOTOR_LINK, True), (MOTOR_ARM, False)):
        d = _out()
        (d / "m.toml").write_text(text)
        s, _ = run_scene(d / "m.toml", out=d / "o")
        e = list(csv.DictReader(open(d / "o" / "energy.csv", newline="")))
        W, T, U = float(e[-1]["work_loads"]), float(e[-1]["kinetic"]), float(e[-1]["strain"])
        Dn = float(e[-1]["dissipated_integrator"])
        assert s["converged"] and W > 0.0, s
        if rigid:
            ref = tau ** 2 * 1.0 ** 2 / (2 * J)
            assert abs(W / ref - 1) < 1e-5 and abs(T / ref - 1) < 3e-5, (W, T, ref)
            assert abs(Dn) < 1e-5 * ref, Dn
        else:
            assert T > 0.5 * W and abs(W - T - U - Dn) < 1e-12 * W and abs(Dn) < 1e-3 * W, (W, T, U, Dn)
        print(f"motor: work {W:.9g} J, kinetic {T:.9g} J, strain {U:.3g} J, integrator {Dn:.3g} J")
