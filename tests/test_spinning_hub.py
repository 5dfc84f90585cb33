"""Spinning beams (issue 36 point 7): Bathe's composite integrator
(`dynamic.integrator = "bathe"`, runtime/analysis/dyn_bathe.c) and the
equations of motion in the hub's rotating frame (`dynamic.frame`,
runtime/analysis/dyn_frame.c).

References that are not our own earlier output: central differences of the
dynamic residual (the iteration matrix's consistency at a spinning state, in
the inertial and in the rotating frame); the rigid rotation of the hub applied
to the undeformed tip plus the closed-form centrifugal stretch of a spinning
bar, u(L) = rho A w^2 L^3 / (3 EA); the closed-form steady stretch of a point
mass on an elastic bar turning at a constant rate; the closed form of a linear
oscillator (x = v/w sin(w t), for the order of accuracy and the energy
behaviour).  The inertial and the rotating-frame runs of the hub are compared
with each other only as a convergence check (their difference falls as h^2),
each being held to the closed forms on its own."""
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


def _dyn_check_exe():
    from gen.solver_build import VARIANTS, build_solver, compile_object, runtime_headers, runtime_objects
    _, index = all_pair_symbols()
    obj = BUILD / "release" / "dyn_check.o"
    compile_object(ROOT / "tests" / "dyn_check.c", obj, VARIANTS["release"], runtime_headers())
    objs = [o for o in runtime_objects("release") if o.name != "main.o"] + [obj]
    return build_solver(["gef_resultant_full"], BUILD / "release" / "dyn_check", index, "release", main_objs=objs)


def test_iteration_matrix_matches_central_differences_at_a_spinning_state():
    """The generalized-alpha iteration matrix (K_t + gp C + bp M, the gef beam's
    rotary inertia with its gyroscopic terms, the prescribed rotation's rows)
    against central differences of the dynamic residual with q' and q'' moved
    by gp and bp times the step, at the hub's beam turned by 1 rad and spinning
    at 6 rad/s (dt = 0.01 and 0.05): no entry off by more than 1e-4 of its size
    (measured: 2e-6 at worst, the differences' own error).  The tangent is
    consistent: the Newton trouble of the spinning beam under generalized-alpha
    is not an inconsistent Jacobian."""
    exe = _dyn_check_exe()
    out = _out()
    run_scene(HUB, ["dynamic.t_end=0.02", "dynamic.frame=none"], out=out / "o")
    import subprocess
    for dt in ("0.01", "0.05"):
        r = subprocess.run([str(exe), str(out / "o" / "model.dat"), "20", "1.0", "6", dt], capture_output=True,
                           text=True)
        assert r.returncode == 0, r.stderr
        err, big, _, _, nbad = r.stdout.split()
        assert float(big) > 1e6 and int(nbad) == 0, r.stdout
        assert float(err) < 1e-9 * float(big), r.stdout


# the hub's beam made soft and thick: the frame's inertia terms (rotary ones too)
# as large as the stiffness in the iteration matrix, so that an error in any of
# them shows (EA 2.8e3 N, GA 1e3 N, EI = GJ 1.4 N m^2; 1 x 1 m at 1 kg/m^3)
SOFT = [f"material.beam.{k}={v}" for k, v in (("EA", 2.8e3), ("GA1", 1e3), ("GA2", 1e3), ("GJ", 1.4), ("EI1", 1.4),
                                               ("EI2", 1.4), ("rho", 1.0))] + ["section.sq.b=1.0", "section.sq.h=1.0"]


def test_rotating_frame_iteration_matrix_matches_central_differences():
    """The iteration matrix in the hub's rotating frame (dynamic.frame: the
    translational frame forces T^T M (T'' y + 2 T' q') with their stiffness and
    Coriolis parts, the rotary inertia turned into the inertial frame and back
    with its Jacobians, the constraint held) against central differences of the
    dynamic residual, at a state turned 0.3 rad and spinning at 0.5 rad/s
    relative to the frame, during the spin-up (t = 7.5 s: w = 3 rad/s and the
    Euler term) and at the steady spin (t = 16 s, 6 rad/s), dt = 0.01 and 0.05,
    on the hub's beam made soft and thick (SOFT).  No entry off by more than
    1e-4 of its size, the largest error below 1e-9 of the largest entry
    (measured 1.2e-4 against 7.9e5, 4.3e-6 against 3.1e4: the differences' own
    error).  The test can fail: a 1 % error put into any one of the frame's
    terms (translational Coriolis or centrifugal, rotary Coriolis, rotary
    T^T Cq T' or T^T Mq T'') gave errors of 1e-2 to 2.6 (measured)."""
    exe = _dyn_check_exe()
    out = _out()
    run_scene(HUB, ["dynamic.t_end=0.02"] + SOFT, out=out / "o")
    assert 'frame=hub' in (out / "o" / "model.dat").read_text()
    import subprocess
    for t in ("7.5", "16"):
        for dt in ("0.01", "0.05"):
            r = subprocess.run([str(exe), str(out / "o" / "model.dat"), t, "0.3", "0.5", dt], capture_output=True,
                               text=True)
            assert r.returncode == 0, r.stderr
            err, big, _, _, nbad = r.stdout.split()
            assert float(big) > 1e4 and int(nbad) == 0, r.stdout
            assert float(err) < 1e-9 * float(big), (t, dt, r.stdout)
            print(f"frame t {t} dt {dt}: {r.stdout.strip()}")


def _hub_run(dt, integrator="bathe", t_end=20.0, frame="hub", extra=()):
    out = _out()
    s, _ = run_scene(HUB, [f"dynamic.dt={dt}", f"dynamic.integrator={integrator}", f"dynamic.t_end={t_end}",
                           f"dynamic.frame={frame}", *extra], out=out)
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
    """models/spinning_hub.toml in the inertial frame (dynamic.frame = "none";
    Bathe, dt = 0.01, 20 s): at most 6 Newton iterations a step (both
    sub-steps; measured 5.1), cut-backs on at most 2 % of the steps (measured
    none), and from the end of the spin-up (15 s) on the tip within 0.01 m of
    the rigid rotation (measured 3.7 mm: the residual vibration the spin-up
    leaves), the mean radial stretch the closed form
    u(L) = rho A w^2 L^3/(3 EA) = 0.514 mm within 2 %."""
    s, out = _hub_run(0.01, frame="none")
    assert s["converged"] and s["steps"] == 2000, s
    assert s["newton_iterations"] / s["steps"] <= 6.0, s["newton_iterations"]
    assert s["cutbacks"] <= 0.02 * s["steps"], s["cutbacks"]
    dev, radial, u = _deviation(out, TS)
    assert dev < 0.01, dev
    assert abs(radial / u - 1) < 0.02, (radial, u)
    print(f"hub dt 0.01: {s['newton_iterations'] / s['steps']:.2f} it/step, {s['cutbacks']} cut-backs, "
          f"deviation {dev:.4g} m, stretch {radial:.4g} m against {u:.4g} m")


@pytest.mark.parametrize("integ,dt", (("bathe", 0.05), ("generalized_alpha", 0.05), ("generalized_alpha", 0.01)))
def test_spinning_hub_in_its_rotating_frame(integ, dt):
    """Issue 36 point 7, the equations of motion in the hub's frame (the
    scene's dynamic.frame = "hub"): at dt = 0.05 (the hub turns 0.3 rad a step)
    with Bathe's scheme and with generalized-alpha at rho_inf = 0.95 (the
    issue's integrator), and the issue's own case, generalized-alpha at
    rho_inf = 0.95 and dt = 0.01: each at most 6 Newton iterations a step,
    cut-backs on at most 2 % of the steps, the tip from 15 s on within 0.01 m
    of the rigid rotation, the mean radial stretch the closed form u(L) within
    2 %.  Measured: Bathe 4.00 iterations a step, no cut-backs, 3.7 mm,
    stretch -0.002 %; generalized-alpha 3.12 iterations a step, no cut-backs,
    4.0 mm, -0.003 % (at dt = 0.01: 2.07, none, 3.7 mm, -0.001 %).  (In the inertial frame, for the record: Bathe 12.5 mm at 14.4
    iterations a step -- the 3.7 mm of vibration the spin-up leaves and a
    steady lag of 8.3 mm, the scheme's drag on the rigid rotation, falling as
    h^3; docs/explanation/robustness.md.)"""
    s, out = _hub_run(dt, integrator=integ)
    assert s["converged"] and s["steps"] == round(20.0 / dt), s
    assert s["newton_iterations"] / s["steps"] <= 6.0, s["newton_iterations"]
    assert s["cutbacks"] <= 0.02 * s["steps"], s["cutbacks"]
    dev, radial, u = _deviation(out, TS)
    assert dev < 0.01, dev
    assert abs(radial / u - 1) < 0.02, (radial, u)
    print(f"hub in its frame, {integ} dt {dt}: {s['newton_iterations'] / s['steps']:.2f} it/step, "
          f"{s['cutbacks']} cut-backs, deviation {dev:.4g} m, stretch {radial / u - 1:+.3%}")


def _tip_energy(out):
    e = list(csv.DictReader(open(out / "energy.csv", newline="")))
    return _tip(out), float(e[-1]["kinetic"]), float(e[-1]["dissipated_integrator"])


def test_rotating_and_inertial_frames_converge_to_one_motion():
    """The hub's scene solved in the inertial frame and in the hub's frame
    (Bathe) at dt = 0.02 and 0.01: the tips' largest distance over the 20 s
    falls at least 3-fold as the step halves (measured 2.19 mm -> 0.48 mm, an
    order of 2.2; 0.11 mm at dt = 0.005) and is below 1 mm at dt = 0.01; each
    run on its own holds the closed-form stretch u(L) within 2 % after 15 s,
    and the kinetic energy both report at the end (energy.csv: the inertial
    one in both) is the rigid spin's J w^2 / 2 = rho A L^3 w^2 / 6 = 7,200 J
    within 0.5 % (the stretch and the vibration add 0.006 %; measured
    inertial 7,206.6 and 7,213.3 J, rotating 7,204.4 J at both steps).  In the
    rotating frame the balance of the hub's work, kinetic and strain energy
    closes with the integrator dissipating less than 1e-5 of the kinetic
    energy (measured -0.002 J: a steady spin costs the scheme nothing); the
    inertial runs' integrator dissipates 4.9 and 28.8 J (the drag that makes
    the lag; printed, not asserted).  The hub's reaction at 20 s, reported in
    the inertial axes by both, is the centrifugal pull rho A w^2 L^2 / 2 =
    2,160 N along the beam towards the hub within 0.2 % (measured 0.05 % in
    the rotating frame, 0.07-0.10 % in the inertial one: the vibration and the
    stretch)."""
    d, T, D = [], {}, {}
    for dt in (0.02, 0.01):
        tips = {}
        for frame in ("hub", "none"):
            s, out = _hub_run(dt, frame=frame, extra=("dynamic.output_every=1",))
            assert s["converged"] and s["cutbacks"] == 0, s
            _, radial, u = _deviation(out, TS)
            assert abs(radial / u - 1) < 0.02, (dt, frame, radial, u)
            tips[frame], T[frame, dt], D[frame, dt] = _tip_energy(out)
            assert abs(T[frame, dt] / (RHOA * L ** 3 * W ** 2 / 6) - 1) < 5e-3, (dt, frame, T[frame, dt])
            assert frame != "hub" or abs(D[frame, dt]) < 1e-5 * T[frame, dt], (dt, D)
            # the hub's reaction (summary.json, the inertial axes): the centrifugal pull
            # rho A w^2 L^2 / 2 = 2,160 N towards the hub, along the beam at theta(20 s)
            F = np.array(s["reactions"][0]["force"][:2])
            F0 = -RHOA * W ** 2 * L ** 2 / 2 * np.array([math.cos(_theta(20.0)), math.sin(_theta(20.0))])
            assert np.linalg.norm(F - F0) < 2e-3 * np.linalg.norm(F0), (dt, frame, F, F0)
        a, b = tips["hub"], tips["none"]
        assert np.allclose(a[0], b[0])
        d.append(np.hypot(a[1] - b[1], a[2] - b[2]).max())
    assert d[1] < 1e-3 and d[0] / d[1] > 3.0, d
    print(f"frame against inertial: {d} m at dt 0.02, 0.01; kinetic {T}; integrator {D}")


SPUN_MASS = """[scene]
analysis = "dynamic"
[material.bar]
law = "resultant"
EA = 1.0e4
GA1 = 1.0e4
GA2 = 1.0e4
GJ = 1.0e3
EI1 = 1.0e3
EI2 = 1.0e3
rho = 1.0
[section.s]
shape = "rectangle"
b = 0.01
h = 0.01
[[beam]]
name = "bar"
element = "gef"
material = "bar"
section = "s"
start = [0.0, 0.0, 0.0]
end = [1.0, 0.0, 0.0]
up = [0.0, 0.0, 1.0]
elements = 2
[[point_mass]]
at = "bar:end"
mass = 1.0
[[constraint]]
type = "prescribed_rotation"
name = "hub"
a = "bar:start"
axis = [0.0, 0.0, 1.0]
rate = 5.0
[[initial_velocity]]
beam = "bar"
angular_velocity = [0.0, 0.0, 5.0]
[dynamic]
t_end = 40.0
dt = {dt}
integrator = "{integrator}"
frame = "hub"
[[sensor]]
name = "m"
at = "bar:end"
"""


# the end mass as a rigid body (J = 0.01, 0.02, 0.03 kg m^2) welded to the bar's end: its
# rotary inertia turned by the frame, a joint between parts kept in it
SPUN_BODY = ('[[point_mass]]\nat = "bar:end"\nmass = 1.0\n',
             '[[body]]\nname = "m"\nmass = 1.0\ncenter = [1.0, 0.0, 0.0]\ninertia = [0.01, 0.02, 0.03]\n'
             '[[constraint]]\ntype = "fixed"\na = "m"\nb = "bar:end"\n')


@pytest.mark.parametrize("body", (False, True))
def test_point_mass_on_a_spinning_bar_is_exact_in_the_rotating_frame(body):
    """A point mass m = 1 kg at the end of an elastic bar (gef, L = 1 m, EA =
    1e4 N, 1e-4 kg/m) on a hub turning at a constant w = 5 rad/s, started with
    the rigid spin: in the hub's frame a steady spin is a constant state, an
    equilibrium of the centrifugal forces that the scheme keeps at any step.
    Bathe at dt = 0.2 s (the hub turns 1 rad a step): once the start's axial
    and bending vibration is gone (periods 0.06 s and less: removed by the
    scheme), the radial stretch is the closed form of the bar with its end mass,
    EA u'' + rho A w^2 (x + u) = 0, u(0) = 0, EA u'(L) = m w^2 (L + u(L)):
    u(L) = A sin(k L) - L, k^2 = rho A w^2 / EA, A = EA / (EA k cos kL - m w^2 sin kL)
    (2.5063 mm; the end mass alone m w^2 L^2 / (EA - m w^2 L) = 2.5063 mm),
    within 1e-9 from t = 20 s on (measured 0 to 1e-13), and the mass on the
    hub's radius, its angle off w t by less than 1e-9 rad (measured 1e-14: no
    lag).  The same with the mass a rigid body welded to the bar's end (the
    stretch is the same; measured 0 and 1e-14 again).  (In the inertial frame at this step, for the record: the run cuts
    its steps back 3,561 times and stops with energy created; at dt = 0.01 it
    still vibrates.)"""
    EA, m, w, Lb, rhoA = 1e4, 1.0, 5.0, 1.0, 1e-4
    k = math.sqrt(rhoA * w * w / EA)
    A = EA / (EA * k * math.cos(k * Lb) - m * w * w * math.sin(k * Lb))
    u = A * math.sin(k * Lb) - Lb
    d = _out()
    text = SPUN_MASS.format(dt=0.2, integrator="bathe")
    if body:
        text = text.replace(*SPUN_BODY).replace('beam = "bar"\nangular_velocity', "angular_velocity")
        assert "[[body]]" in text and 'beam = "bar"\nangular' not in text
    (d / "m.toml").write_text(text)
    s, _ = run_scene(d / "m.toml", out=d / "o")
    assert s["converged"] and s["cutbacks"] == 0 and not s["warnings"], s
    rows = [r for r in csv.DictReader(open(d / "o" / "sensors.csv", newline="")) if float(r["time"]) >= 20.0]
    assert len(rows) >= 100
    t = np.array([float(r["time"]) for r in rows])
    x, y = np.array([float(r["x"]) for r in rows]), np.array([float(r["y"]) for r in rows])
    stretch = np.hypot(x, y) - Lb
    phase = np.angle(np.exp(1j * (np.arctan2(y, x) - w * t)))
    assert np.abs(stretch / u - 1).max() < 1e-9, (stretch.min(), stretch.max(), u)
    assert np.abs(phase).max() < 1e-9, np.abs(phase).max()
    print(f"spun mass: stretch {stretch[-1]:.12g} m against {u:.12g} m, phase {np.abs(phase).max():.3g} rad, "
          f"{s['newton_iterations'] / s['steps']:.2f} it/step")


def _spun_ancf(d, frame, dt):
    """The spun mass on an ancf3243 bar (SVK, E = 1e8 Pa, nu = 0, 10 x 10 mm),
    the first 4 s with Bathe."""
    text = SPUN_MASS.format(dt=dt, integrator="bathe").replace(
        'law = "resultant"\nEA = 1.0e4\nGA1 = 1.0e4\nGA2 = 1.0e4\nGJ = 1.0e3\nEI1 = 1.0e3\nEI2 = 1.0e3',
        'law = "svk"\nE = 1.0e8\nnu = 0.0').replace('"gef"', '"ancf3243"').replace("t_end = 40.0", "t_end = 4.0")
    assert "ancf3243" in text and "svk" in text
    (d / f"a{frame}{dt}.toml").write_text(text.replace('frame = "hub"', f'frame = "{frame}"'))
    s, _ = run_scene(d / f"a{frame}{dt}.toml", out=d / f"o{frame}{dt}")
    assert s["converged"], s
    rows = list(csv.DictReader(open(d / f"o{frame}{dt}" / "sensors.csv", newline="")))
    return np.array([[float(r[k]) for k in ("time", "x", "y")] for r in rows])


def test_ancf_slopes_turn_with_the_rotating_frame():
    """The rotating frame turns ANCF nodal vectors like positions (the hub's
    prescribed rotation there is rows on the gradients): the spun mass on an
    ancf3243 bar, whose soft bending swings the mass slowly about the spin,
    solved in the hub's frame and in the inertial frame at dt = 0.005 and
    0.0025 s: the tips' largest distance over 4 s falls at least 3-fold as
    the step halves (measured 2.7e-4 -> 7.1e-5 m, an order of 1.95; 1.0e-3 m at
    dt = 0.01) -- a convergence check of the two formulations towards one
    motion, neither the reference of the other."""
    d = _out()
    dist = []
    for dt in (0.005, 0.0025):
        a, b = _spun_ancf(d, "hub", dt), _spun_ancf(d, "none", dt)
        assert np.allclose(a[:, 0], b[:, 0])
        dist.append(np.hypot(a[:, 1] - b[:, 1], a[:, 2] - b[:, 2]).max())
    assert dist[1] < 2e-4 and dist[0] / dist[1] > 3.0, dist
    print(f"ancf frame against inertial: {dist} m")


FRAME_REFUSED = [
    ('[[load]]\ntype = "gravity"\nvalue = [0.0, 0.0, -9.81]\n', "load[0]", "gravity"),
    ('[[constraint]]\ntype = "spherical"\na = "bar:0.5"\n', "constraint[1]", "to the ground"),
    ("", "dynamic.frame", "no [[constraint]] named 'spindle'"),
]


@pytest.mark.parametrize("extra,where,words", FRAME_REFUSED)
def test_rotating_frame_refuses_what_it_cannot_turn(extra, where, words):
    """Gravity (a direction fixed in space), a support to the ground (the
    ground turns in the frame), a frame naming no constraint: one line naming
    the key, a non-zero exit, no run."""
    from util import run_cli
    d = _out()
    text = SPUN_MASS.format(dt=0.2, integrator="bathe") + extra
    if not extra:
        text = text.replace('frame = "hub"', 'frame = "spindle"')
    (d / "r.toml").write_text(text)
    r = run_cli(["run", str(d / "r.toml"), "--quiet", "--out", str(d / "o")])
    assert r.returncode != 0, r.stdout
    line = [x for x in r.stderr.splitlines() if x.strip()]
    assert len(line) == 1 and where in line[0] and words in line[0], r.stderr


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
