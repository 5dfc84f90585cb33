"""Mechanisms with driven joints between frames (issue 40, verifications 2, 4 and 5):
the slider-crank driven through a relative joint between the crank and a frame
body against the ground-driven one (models/slider_crank.toml), and the flexible
two-link arm (models/flexible_arm.toml): its residual vibration after the
motion against the modal analysis about the final configuration."""
import csv
import tempfile
from pathlib import Path

import numpy as np

from util import BUILD, ROOT, ensure_dir, run_scene

GROUND_DRIVE = '''[[constraint]]
type = "prescribed_rotation"
a = "crank:start"
axis = [0.0, 0.0, 1.0]
rate = 12.566370614359172
'''
RELATIVE_DRIVE = '''[[body]]
name = "frame"
mass = 2.0
center = [0.0, 0.0, 0.0]
inertia = [0.01, 0.01, 0.01]

[[constraint]]
type = "fixed"
name = "base"
a = "frame"
at = [0.0, 0.0, 0.0]

[[constraint]]
type = "prescribed_rotation"
name = "motor"
a = "crank:start"
b = "frame"
axis = [0.0, 0.0, 1.0]
rate = 12.566370614359172
'''


def _sensors(out):
    with open(Path(out) / "sensors.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    return [(r["sensor"], float(r["time"])) for r in rows], np.array([[float(r[k]) for k in "xyz"] for r in rows])


def _reactions(out):
    """{(type, at): array of (Fx, Fy, Fz, Mx, My, Mz) per output step} of reactions.csv."""
    with open(Path(out) / "reactions.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    out = {}
    for r in rows:
        out.setdefault((r["type"], r["at"]), []).append([float(r[k]) for k in ("Fx", "Fy", "Fz", "Mx", "My", "Mz")])
    return {k: np.array(v) for k, v in out.items()}


def test_slider_crank_driven_relative_to_a_frame_body_equals_the_ground_driven_one():
    """Issue 40 verification 4: models/slider_crank.toml (flexible rod, Rayleigh
    damping beta = 1.5 ms) with the crank driven relative to a frame body welded to
    the ground (prescribed_rotation with b = "frame") against the ground-driven one,
    over half a turn.
    * Against the same drive to the ground as a joint with frames (`at` given):
      every reaction, the drive's included, equal to the Newton tolerance (bound
      1e-6 of each joint's peak; measured 1.5e-8), the motion to 1e-9 m.
    * Against the shipped scene, whose drive of a beam node to the ground is
      compiled to linear rows (the node's position eliminated, its quaternion
      prescribed component by component): the slider, crank pin and rod midpoint
      to 1e-9 m (measured 2.6e-11 m), the other joints' reactions to 1e-6 of
      their peaks (measured 4e-7); the drive's own reaction differs by 1.1e-3 of
      its peak (8.6e-3 at dt = 1 ms, 1.5e-4 at 0.25 ms: the two forms are two time
      discretizations of one drive, whose difference falls as dt^3; the
      quaternion's velocity of generalized-alpha differs between them (its gauge
      prescribed by the rows, projected out in the joint), and the stiff crank's
      Rayleigh force beta K q' turns that into force: 1.2e-5 without the damping).
      Asserted: below 2e-3 at dt = 0.5 ms and at least 4 times smaller at 0.25 ms."""
    src = (ROOT / "models" / "slider_crank.toml").read_text()
    assert GROUND_DRIVE in src
    d = Path(tempfile.mkdtemp(prefix="bk-mech-", dir=ensure_dir(BUILD / "runs")))
    (d / "relative.toml").write_text(src.replace(GROUND_DRIVE, RELATIVE_DRIVE))
    (d / "joint.toml").write_text(src.replace(GROUND_DRIVE, GROUND_DRIVE.replace('a = "crank:start"\n',
                                                                                 'a = "crank:start"\nat = [0.0, 0.0, 0.0]\n')))
    sets = ["dynamic.t_end=0.25"]
    run_scene(ROOT / "models" / "slider_crank.toml", sets, out=d / "ground")
    for name in ("relative", "joint"):
        run_scene(d / f"{name}.toml", sets, out=d / name)
    keys_g, xg = _sensors(d / "ground")
    assert len(keys_g) == 753 and np.abs(xg[:, 0]).max() > 0.3          # it did turn: the slider moved
    for name in ("relative", "joint"):
        keys, x = _sensors(d / name)
        assert keys == keys_g
        err = np.abs(xg - x).max()
        assert err < 1e-9, (name, err)
    rg, rr, rj = (_reactions(d / n) for n in ("ground", "relative", "joint"))
    assert set(rg) == set(rj) == set(rr) - {("fixed", "frame")} and len(rg) == 4
    drive = ("prescribed_rotation", "crank:start")
    for k in rg:
        peak = np.abs(rg[k]).max()
        same_form = np.abs(rr[k] - rj[k]).max() / peak
        assert same_form < 1e-6, (k, same_form)
        rows_form = np.abs(rr[k] - rg[k]).max() / peak
        assert rows_form < (2e-3 if k == drive else 1e-6), (k, rows_form)
        print(f"slider-crank {k[0]} at {k[1]}: relative vs ground as a joint {same_form:.1e}, "
              f"vs ground as rows {rows_form:.1e} of the peak {peak:.3g}")
    # the drive's difference between the two forms is the time discretization's
    half = ["dynamic.t_end=0.25", "dynamic.dt=2.5e-4", "dynamic.output_every=4"]
    run_scene(ROOT / "models" / "slider_crank.toml", half, out=d / "ground_half")
    run_scene(d / "joint.toml", half, out=d / "joint_half")
    full = np.abs(rj[drive] - rg[drive]).max()
    halved = np.abs(_reactions(d / "joint_half")[drive] - _reactions(d / "ground_half")[drive]).max()
    assert halved < full / 4, (full, halved)
    print(f"slider-crank drive, rows vs joint: {full:.2e} N at dt = 0.5 ms, {halved:.2e} N at 0.25 ms")


def test_flexible_arm_residual_vibration_at_the_first_modal_frequency():
    """models/flexible_arm.toml: after the cycloidal motion stops (t = 1 s) the
    payload vibrates about the final configuration (14 mm); the frequency of that
    motion from its zero crossings over 1 - 3 s (along its principal direction,
    about its mean) against the first frequency of the modal analysis about the
    final configuration (the same scene, modal about the static state at load
    factor 1, where the drives are at their final angles): within 2 % (measured
    2.26886 Hz against 2.26892 Hz, 2e-5).  The modal analysis' static state is the
    final configuration: the payload where the rigid kinematics put it."""
    import math
    d = Path(tempfile.mkdtemp(prefix="bk-arm-", dir=ensure_dir(BUILD / "runs")))
    scene = ROOT / "models" / "flexible_arm.toml"
    run_scene(scene, out=d / "dyn")
    s_m, _ = run_scene(scene, ["scene.analysis=modal", "modal.about=static"], out=d / "modal")
    f1 = s_m["frequencies_hz"][0]
    p = np.array(s_m["sensors"]["payload"]["position"])
    th1, th2 = 1.2, 1.2 - 0.9
    rigid = np.array([0.5 * math.cos(th1) + 0.4 * math.cos(th2), 0.5 * math.sin(th1) + 0.4 * math.sin(th2), 0.0])
    assert np.abs(p - rigid).max() < 1e-9, (p, rigid)
    with open(d / "dyn" / "sensors.csv", newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["sensor"] == "payload"]
    t = np.array([float(r["time"]) for r in rows])
    x = np.array([[float(r["x"]), float(r["y"])] for r in rows])[t >= 1.0] - p[:2]
    t = t[t >= 1.0]
    y = x @ np.linalg.svd(x - x.mean(0), full_matrices=False)[2][0]
    y -= y.mean()
    assert 5e-3 < np.abs(y).max() < 5e-2                         # a residual vibration of about 14 mm
    k = np.where(np.diff(np.sign(y)) != 0)[0]
    tz = t[k] - y[k] * (t[k + 1] - t[k]) / (y[k + 1] - y[k])
    f = (len(tz) - 1) / (2 * (tz[-1] - tz[0]))
    assert len(tz) >= 8
    assert abs(f / f1 - 1) < 0.02, (f, f1)
    print(f"flexible arm: residual vibration {f:.6f} Hz, modal {f1:.6f} Hz, {abs(f / f1 - 1):.1e}")


def test_bad_mechanism_input_one_line_each():
    """Issue 40 verification 5 on models/flexible_arm.toml: a driven joint whose axis
    is zero, an actuator on a joint without an axis (the payload's weld), a body point
    far outside the body (a sensor 5 m from a 0.3 kg payload), a joint at an arc
    length beyond the beam and one 1e-8 m from a node (a node is added at a joint
    between nodes, but not that close to another): one line each naming the key,
    exit 1."""
    from test_bad_input import check_error
    base = (ROOT / "models" / "flexible_arm.toml").read_text()
    elbow = 'b = "upper:end"\naxis = [0.0, 0.0, 1.0]'
    assert elbow in base
    check_error(base.replace(elbow, 'b = "upper:end"\naxis = [0.0, 0.0, 0.0]'), "constraint[1].axis", "zero")
    check_error(base + '[[actuator]]\njoint = "grip"\neffort = 1.0\n', "actuator[0].joint",
                "fixed joint: an actuator needs a joint with an axis")
    check_error(base + '[[sensor]]\nname = "far"\nat = "payload"\npoint = [5.9, 0.0, 0.0]\n', "sensor.far.point",
                "expected a point of the body")
    check_error(base.replace(elbow, 'b = "upper:0.7"\naxis = [0.0, 0.0, 1.0]'), "constraint[1].b",
                "outside beam 'upper'")
    check_error(base.replace(elbow, 'b = "upper:0.31250001"\naxis = [0.0, 0.0, 1.0]'), "beam.upper.elements",
                "within 1e-08 m of a node")


ALL_PARTS = """[scene]
analysis = "dynamic"

[amplitude.profile]
type = "quintic"
t0 = 0.0
t1 = 0.05

[material.alu]
law = "resultant"
E = 7.0e10
nu = 0.33
rho = 2700.0

[section.bar]
shape = "rectangle"
b = 0.005
h = 0.02

[[beam]]
name = "arm"
element = "gef"
material = "alu"
section = "bar"
start = [0.0, 0.0, 0.0]
end = [0.5, 0.0, 0.0]
elements = 4

[[body]]
name = "base"
mass = 2.0
center = [0.0, 0.0, 0.0]
inertia = [0.02, 0.03, 0.04]

[[body]]
name = "tip"
mass = 0.3
center = [0.5, 0.0, 0.0]
inertia = [2e-4, 2e-4, 2e-4]

[[constraint]]
type = "prismatic"
name = "rail"
a = "base"
at = [0.0, 0.0, 0.0]
axis = [1.0, 0.0, 0.0]

[[constraint]]
type = "revolute"
name = "shoulder"
a = "arm:start"
b = "base"
axis = [0.0, 0.0, 1.0]

[[constraint]]
type = "fixed"
a = "tip"
b = "arm:end"

[[point_mass]]
at = "arm:0.3"
mass = 0.1

[[load]]
type = "gravity"
value = [0.0, -9.81, 0.0]

[[load]]
type = "force"
at = "tip"
point = [0.52, 0.0, 0.0]
value = [0.0, 0.1, 0.0]
follower = true

[[load]]
type = "moment"
at = "tip"
value = [0.0, 0.0, 0.05]

[[load]]
type = "force"
at = "base"
point = [0.05, 0.02, 0.0]
value = [0.2, -0.1, 0.0]

[[actuator]]
name = "slide"
joint = "rail"
kp = 40.0
kd = 2.0
setpoint = 0.05
setpoint_amplitude = "profile"

[[actuator]]
name = "motor"
joint = "shoulder"
effort = 0.4
effort_amplitude = {type = "ramp", t0 = 0.0, t1 = 0.02}
kp = 7.0
kd = 0.6
setpoint = 0.5
setpoint_amplitude = "profile"

[[sensor]]
name = "tp"
at = "tip"
point = [0.52, 0.0, 0.0]

[dynamic]
t_end = 0.05
dt = 1e-3
"""


def test_every_mechanism_part_is_clean_under_sanitizers_and_valgrind():
    """A scene with every part of this page at once (a PD linear motor on a body's
    prismatic joint, a PD + ramped motor on a revolute joint between a beam node and
    the body, a point mass between nodes, a follower and a dead force at body
    points, a moment on a body, a sensor at a body point, gravity): with AddressSanitizer and
    UBSan exit 0 and no report, under valgrind's memcheck exit 0 (not 99)."""
    from util import run_cli, run_memcheck
    d = Path(tempfile.mkdtemp(prefix="bk-mech-", dir=ensure_dir(BUILD / "runs")))
    (d / "all.toml").write_text(ALL_PARTS)
    r = run_cli(["run", str(d / "all.toml"), "--sanitize", "--quiet", "--out", str(d / "asan")])
    assert r.returncode == 0 and "runtime error" not in r.stderr and "Sanitizer" not in r.stderr, r.stderr[-2000:]
    r, _ = run_memcheck(d / "all.toml", out=d / "vg")
    assert r.returncode == 0, (r.returncode, r.stderr[-2000:])


PIVOTED_BAR = """
[scene]
analysis = "modal"

[material.steel]
law = "resultant"
E = 2.1e11
nu = 0.3
rho = 7850.0

[section.sq]
shape = "rectangle"
b = 0.01
h = 0.01

[[beam]]
name = "bar"
element = "gef"
material = "steel"
section = "sq"
start = [0.0, 0.0, 0.3]
end = [0.0, 0.0, -0.7]
up = [1.0, 0.0, 0.0]
elements = 4

[[constraint]]
type = "revolute"
name = "pivot"
a = "bar:0.3"
axis = [0.0, 1.0, 0.0]

[[load]]
type = "gravity"
value = [0.0, 0.0, -9.81]

[modal]
modes = 1
about = "static"
"""


def test_joint_between_nodes_gets_a_node():
    """A 1 m steel bar (4 elements: nodes every 0.25 m) hung from a revolute joint at
    0.3 m from its top end, between two nodes: a node is added there (5 elements, said
    in the warnings) and the bar swings as a compound pendulum pivoted 0.2 m above its
    centre of mass, f = sqrt(g d / ((L^2 + b^2)/12 + d^2)) / 2 pi = 0.634768 Hz (modal
    about the hanging state; measured 0.634731 Hz, 5.8e-5: the bar's elasticity,
    (f / f_bending)^2 ~ 1.4e-4)."""
    import math
    d = Path(tempfile.mkdtemp(prefix="bk-mech-", dir=ensure_dir(BUILD / "runs")))
    (d / "bar.toml").write_text(PIVOTED_BAR)
    s, _ = run_scene(d / "bar.toml", out=d / "o")
    ref = math.sqrt(9.81 * 0.2 / ((1 + 0.01**2) / 12 + 0.2**2)) / (2 * math.pi)
    assert abs(s["frequencies_hz"][0] / ref - 1) < 1e-4, (s["frequencies_hz"], ref)
    assert any("node(s) added at arc length 0.3 m" in w and "5 elements" in w for w in s["warnings"]), s["warnings"]
    print(f"bar pivoted between nodes: {s['frequencies_hz'][0]:.6f} Hz against {ref:.6f} Hz")
