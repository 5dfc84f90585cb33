"""Dynamics that are honest about energy and steps (issue 36): the energy balance of
energy.csv / summary.json against closed forms (a damped rigid translation, a ramped
load's work, a beam spun up by a driven hub), and the step controller's memory
(its policy, by the C harness tests/step_control_check.c)."""
import csv
import math
import subprocess
from functools import lru_cache

from util import BUILD, build_runtime_program, ensure_dir, run_scene

FREE_BEAM = """
[scene]
analysis = "dynamic"
[material.m]
law = "resultant"
E = 1.0e7
nu = 0.3
rho = 1000.0
[section.c]
shape = "circle"
radius = 0.01
[[beam]]
name = "b"
element = "gef"
material = "m"
section = "c"
start = [0.0, 0.0, 0.0]
end = [2.0, 0.0, 0.0]
up = [0.0, 0.0, 1.0]
elements = 4
[[sensor]]
name = "tip"
at = "b:end"
"""
MASS = 1000.0 * math.pi * 0.01 ** 2 * 2.0          # rho A L (kg)


def _energy(out):
    with open(out / "energy.csv", newline="") as fh:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(fh)]


def _run(text, name, sets=()):
    d = ensure_dir(BUILD / "robust_dynamics")
    p = d / f"{name}.toml"
    p.write_text(text)
    out = d / f"{name}_out"
    s, rows = run_scene(p, list(sets), out=out)
    return s, _energy(out)


def test_damping_dissipation_of_a_damped_rigid_translation():
    """A free beam translating at 1 m/s along its axis with Rayleigh alpha = 2 /s:
    v = e^(-alpha t), so the energy dissipated by damping is T0 (1 - e^(-2 alpha t))
    (closed form): within 1e-4 T0 at every row, the integrator's dissipation within
    1e-4 T0 (rho_inf = 1, dt = 1 ms), and the balance closes (work of loads 0)."""
    text = FREE_BEAM + "[dynamic]\nt_end = 0.5\ndt = 1e-3\nrho_inf = 1.0\nrayleigh_alpha = 2.0\n" \
        "[[initial_velocity]]\nvelocity = [1.0, 0.0, 0.0]\n"
    s, e = _run(text, "damped_translation")
    T0 = 0.5 * MASS
    assert abs(e[0]["kinetic"] - T0) <= 1e-12 * T0
    for r in e:
        exact = T0 * (1.0 - math.exp(-4.0 * r["time"]))
        assert abs(r["dissipated_damping"] - exact) <= 1e-4 * T0, (r["time"], r["dissipated_damping"], exact)
        assert abs(r["dissipated_integrator"]) <= 1e-4 * T0, r
        assert abs(r["work_loads"]) <= 1e-12 * T0
    assert abs(e[-1]["kinetic"] - T0 * math.exp(-2.0)) <= 1e-4 * T0
    en = s["energy"]
    assert abs(en["dissipated_damping"] - e[-1]["dissipated_damping"]) <= 1e-12 * T0
    assert en["created_max"] <= 1e-4


def test_work_of_a_ramped_distributed_load_on_a_free_beam():
    """A free beam pushed by a uniform load q a(t) along y, a ramping 0 -> 1 over
    0.1 s (no potential the integrator could use): the beam translates rigidly with
    v = (q/rho A) int a dt, and the work of the load is 1/2 M v^2 (closed form): the
    kinetic energy within 1e-6 of it at the end; the work (a trapezoidal rule over
    the steps of the power q a(t) v(t), cubic in t on the ramp) within 1e-4, and the
    integrator's dissipation within 1e-4 of it."""
    q = 2.0
    text = FREE_BEAM + "[dynamic]\nt_end = 0.2\ndt = 1e-3\nrho_inf = 0.9\n" \
        f'[[load]]\ntype = "distributed"\nbeam = "b"\nvalue = [0.0, {q!r}, 0.0]\n' \
        'amplitude = {type = "ramp", t0 = 0.0, t1 = 0.1}\n'
    s, e = _run(text, "ramped_push")
    v = q * 2.0 / MASS * (0.05 + 0.1)
    W = 0.5 * MASS * v * v
    assert abs(e[-1]["kinetic"] - W) <= 1e-6 * W, (e[-1]["kinetic"], W)
    assert abs(e[-1]["work_loads"] - W) <= 1e-4 * W, (e[-1]["work_loads"], W)
    assert abs(e[-1]["dissipated_integrator"]) <= 1e-4 * W
    assert abs(s["energy"]["work_loads"] - e[-1]["work_loads"]) <= 1e-12 * W


def _hub_scene(t_end, rho_inf, dt):
    """The spin-up beam of Simo and Vu-Quoc (1986) as issue 36 gives it: gef, 10
    elements, EA 2.8e7, GA 1e7, EI = GJ 1.4e4, rho A 1.2, rho I 6e-4 (a circle of
    rho pi r^2 = 1.2, r^2 / 4 = 5e-4), L 10, clamped to a hub turned by
    theta = (w/T)(t^2/2 + (T/2pi)^2 (cos(2 pi t/T) - 1)) up to T = 15 s, then w (t - T/2),
    w = 6 rad/s: written as rate w t plus angle -w T/2 times a spline amplitude."""
    T, w = 15.0, 6.0
    pts = []
    for i in range(151):
        t = T * i / 150
        th = (w / T) * (t * t / 2 + (T / (2 * math.pi)) ** 2 * (math.cos(2 * math.pi * t / T) - 1))
        pts.append(f"[{t!r}, {(w * t - th) / (w * T / 2)!r}]")
    return f"""
[scene]
analysis = "dynamic"
[material.m]
law = "resultant"
EA = 2.8e7
GA1 = 1.0e7
GA2 = 1.0e7
GJ = 1.4e4
EI1 = 1.4e4
EI2 = 1.4e4
rho = {1.2 / (math.pi * 2e-3)!r}
[section.c]
shape = "circle"
radius = {math.sqrt(2e-3)!r}
[[beam]]
name = "b"
element = "gef"
material = "m"
section = "c"
start = [0.0, 0.0, 0.0]
end = [10.0, 0.0, 0.0]
up = [0.0, 0.0, 1.0]
elements = 10
[amplitude.spin]
type = "spline"
points = [{", ".join(pts)}]
[[constraint]]
type = "prescribed_rotation"
a = "b:start"
axis = [0.0, 0.0, 1.0]
rate = {w!r}
angle = {-w * T / 2!r}
angle_amplitude = "spin"
[dynamic]
t_end = {t_end!r}
dt = {dt!r}
rho_inf = {rho_inf!r}
[[sensor]]
name = "tip"
at = "b:end"
"""


def test_spin_up_beam_work_of_the_hub_and_centrifugal_stretch():
    """The spin-up beam at rho_inf = 0.8, dt = 0.01, to t = 18 s (3 s at constant
    spin): the tip's stretch along the rotating beam is rho A w^2 L^3 / (3 EA)
    = 5.143e-4 m (the closed form of a rigidly spinning bar) within 2 %; the strain
    energy is (rho A w^2)^2 L^5 / (15 EA) = 0.4443 J within 1 %; the kinetic energy
    1/2 (rho A L^3/3 + rho I_p L) w^2 = 7200.2 J within 0.2 % (the spin-up leaves a
    small vibration); the work of the driven hub closes the balance with an
    integrator dissipation >= 0 and below 0.2 % of it.  Newton: at most 6
    iterations a step on average, no cut-back."""
    s, e = _run(_hub_scene(18.0, 0.8, 0.01), "spin_up")
    w, L, rA, EA = 6.0, 10.0, 1.2, 2.8e7
    with open(BUILD / "robust_dynamics" / "spin_up_out" / "sensors.csv", newline="") as fh:
        last = list(csv.DictReader(fh))[-1]
    t = float(last["time"])
    th = w * (t - 7.5)
    x, y = float(last["x"]), float(last["y"])
    radial = x * math.cos(th) + y * math.sin(th)
    stretch = rA * w * w * L ** 3 / (3 * EA)
    assert abs((radial - L) - stretch) <= 0.02 * stretch, (radial - L, stretch)
    U = (rA * w * w) ** 2 * L ** 5 / (15 * EA)
    assert abs(e[-1]["strain"] - U) <= 0.01 * U, (e[-1]["strain"], U)
    Tk = 0.5 * (rA * L ** 3 / 3 + 1.2e-3 * L) * w * w
    assert abs(e[-1]["kinetic"] - Tk) <= 2e-3 * Tk, (e[-1]["kinetic"], Tk)
    W = e[-1]["work_loads"]
    assert 0.0 <= e[-1]["dissipated_integrator"] <= 2e-3 * W
    assert abs(W - e[-1]["kinetic"] - e[-1]["strain"] - e[-1]["dissipated_integrator"]) <= 1e-9 * W
    assert s["converged"] and s["cutbacks"] == 0
    assert s["newton_iterations"] <= 6 * s["steps"], (s["newton_iterations"], s["steps"])


@lru_cache(maxsize=None)
def _controller():
    return build_runtime_program(["step_control_check.c"], "step_control_check", "sanitize")


def _steps(script, ratio=0.0):
    r = subprocess.run([str(_controller()), script, repr(ratio)], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and "runtime error" not in r.stderr, r.stderr
    lines = r.stdout.split("\n")
    hs = [float(l.split()[1]) for l in lines if l and l[0] in "fsS"]
    hold, fails = [int(x) for x in lines[len(hs)].split()[1::2]]
    return hs, hold, fails


def test_step_controller_remembers_failures():
    """The controller's policy (a specification guard, dt = 1): a failure halves the
    step, which then stays at 1/2 for 15 accepted steps (no regrowth for 8, and not
    back to the size that failed before 16); a second failure soon after the regrowth
    doubles the hold (32 steps at 1/2); cuts in one step keep it; a slow Newton (20
    iterations) forbids growth; with an error estimate (tol > 0) growth is at most
    to 0.9 of the size that failed while it is remembered."""
    hs, hold, fails = _steps("f" + "s" * 20)
    assert hs[:16] == [0.5] * 16 and hs[16:] == [1.0] * 5 and hold == 8 and fails == 1
    hs, hold, _ = _steps("f" + "s" * 20 + "f" + "s" * 40)
    assert hs[21:21 + 32] == [0.5] * 32 and hs[21 + 32] == 1.0 and hold == 16
    hs, hold, fails = _steps("ff" + "s" * 40)
    assert hs[:2] == [0.5, 0.25] and hold == 8 and fails == 2
    assert 0.25 in hs[2:11] and max(hs[2:18]) <= 0.5 and hs[-1] == 1.0
    hs, _, _ = _steps("f" + "S" * 30)
    assert hs == [0.5] * 31
    hs, _, _ = _steps("f" + "s" * 12, ratio=1e-3)
    assert max(hs) <= 0.9 and hs[-1] == 0.9 and hs[:8] == [0.5] * 8


def _bent_cantilever(replace_constraint, name):
    from util import ROOT
    text = (ROOT / "models" / "cantilever_bend_10N.toml").read_text()
    text = replace_constraint(text).replace("[static]", "[static]\nfree_rigid_motion = true")
    d = ensure_dir(BUILD / "robust_dynamics")
    p = d / f"{name}.toml"
    p.write_text(text)
    from util import run_cli
    return run_cli(["run", str(p), "--out", str(d / f"{name}_out")])


def test_singular_tangent_names_the_free_motion():
    """Statics of a model left free on purpose (free_rigid_motion = true) meets a
    singular tangent; the message names the motion from the matrix's null vector:
    the cantilever of cantilever_bend_10N pinned at its start (a spherical joint)
    turns about an axis normal to the beam (its tip, at s = 1 m, moves normal to the
    beam: no x component), and without any constraint every node translates."""
    r = _bent_cantilever(lambda t: t.replace('type = "clamp"', 'type = "spherical"'), "pinned")
    assert r.returncode == 2, r.stderr
    line = [l for l in r.stderr.splitlines() if l.startswith("error")][0]
    import re
    m = re.search(r"the largest translation at beam 'arm' at s = 1 m, along \(([-0-9.]+), ([-0-9.]+), "
                  r"([-0-9.]+)\); the section turning most at .* about \(([-0-9.]+), ", line)
    assert m, line
    assert abs(float(m.group(1))) <= 0.01 and abs(float(m.group(4))) <= 0.01, line
    r = _bent_cantilever(lambda t: t.split("[[constraint]]")[0] + "[[load]]" + t.split("[[load]]")[1], "floating")
    assert r.returncode == 2, r.stderr
    assert "free motion (null vector of the matrix):" in r.stderr and "translation at beam 'arm'" in r.stderr, \
        r.stderr
