"""Joint actuators ([[actuator]]: gen/actuator.py, runtime/assembly/actuators.c), each
against a reference that is not our own element: central differences of the
generated joint-coordinate kernels and of the assembled actuator forces, the
relative rotation built from quaternions, the double integral of tau/J for a
rigid link driven by a motor torque, and the closed-form step response of a
PD-controlled joint (a damped second-order system)."""
import csv
import ctypes
import math
import re
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from util import BUILD, ROOT, build_shared_kernels, ensure_dir, run_cli, run_scene
from test_bad_input import check_error

NX = 14

LINK = """
[scene]
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

[dynamic]
t_end = 1.0
dt = 1e-3
output_every = 10
"""
J_O = 0.025 + 1.2 * 0.25**2          # the link's moment of inertia about the hinge: 0.1 kg m^2


def _rows(out, name):
    with open(Path(out) / name, newline="") as fh:
        return list(csv.DictReader(fh))


def _run(text, sets=()):
    d = Path(tempfile.mkdtemp(prefix="bk-act-", dir=ensure_dir(BUILD / "runs")))
    (d / "scene.toml").write_text(text)
    s, rows = run_scene(d / "scene.toml", sets, out=d / "out")
    return s, rows, d / "out"


def _p(a):
    return a.ctypes.data_as(ctypes.POINTER(ctypes.c_double))


def _quat(axis, angle):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    return np.concatenate([[math.cos(angle / 2)], math.sin(angle / 2) * axis])


def test_actuator_kernels_match_finite_differences_and_the_relative_angle():
    """ds/dx and d2s/dx2 of both generated coordinates against central differences
    of s (the angle atan2(Y, X) and the displacement) at random frames, axes and
    offsets (quaternions off unit length); and at a joint that holds, the angle is
    the relative rotation of two frames built from quaternions (a turned by
    phi_a, b by phi_b about the same axis: s = phi_a - phi_b) and the displacement
    the offset along the axis."""
    lib = ctypes.CDLL(str(build_shared_kernels()))
    D = ctypes.POINTER(ctypes.c_double)
    fns = {k: ctypes.CFUNCTYPE(None, D, D, D, D, D)(("bk_actuator_" + k, lib)) for k in ("rotation", "translation")}

    def ev(kind, x, prm):
        val, g, H = np.zeros(2), np.zeros(NX), np.zeros(NX * NX)
        x = np.ascontiguousarray(x)
        fns[kind](_p(x), _p(prm), _p(val), _p(g), _p(H))
        s = math.atan2(val[1], val[0]) if kind == "rotation" else val[0]
        return s, g, H.reshape(NX, NX)
    rng = np.random.default_rng(11)
    for kind in fns:
        for trial in range(3):
            x, prm = rng.normal(size=NX), rng.normal(size=24)
            s0, g0, H0 = ev(kind, x, prm)
            h = 1e-6
            gfd, Hfd = np.zeros(NX), np.zeros((NX, NX))
            for j in range(NX):
                e = np.zeros(NX)
                e[j] = h
                sp_, gp_, _ = ev(kind, x + e, prm)
                sm_, gm_, _ = ev(kind, x - e, prm)
                gfd[j] = (sp_ - sm_) / (2 * h)
                Hfd[:, j] = (gp_ - gm_) / (2 * h)
            assert np.abs(g0 - gfd).max() <= 1e-7 * max(1.0, np.abs(g0).max()), kind
            assert np.abs(H0 - Hfd).max() <= 1e-6 * max(1.0, np.abs(H0).max()), kind
            assert np.abs(H0 - H0.T).max() <= 1e-12 * max(1.0, np.abs(H0).max()), kind
    # a joint that holds: axes E (columns, the third the joint axis) in both frames' reference
    axis = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
    n1 = np.cross(axis, [1.0, 0, 0])
    n1 /= np.linalg.norm(n1)
    E = np.column_stack([n1, np.cross(axis, n1), axis])
    for pa, pb, off in ((0.7, -0.4, 0.0), (2.9, -2.9, 0.12), (-1.3, 0.2, -0.05)):
        qa, qb = 1.7 * _quat(axis, pa), 0.6 * _quat(axis, pb)      # (scaled: the rotation is p/|p|)
        ca = np.array([0.1, 0.2, -0.3])
        Ra = _rot(qa)
        rb = np.array([1.0, -2.0, 0.5])
        ra = rb - Ra @ ca + off * axis                               # o_a = o_b + off axis
        x = np.concatenate([ra, qa, rb, qb])
        prm = np.concatenate([ca, [0.0, 0.0, 0.0], E.T.ravel(), E.T.ravel()])
        s, _, _ = ev("rotation", x, prm)
        d = (pa - pb + math.pi) % (2 * math.pi) - math.pi
        assert abs(s - d) < 1e-12, (s, d)
        s, _, _ = ev("translation", x, prm)
        assert abs(s - off) < 1e-12, (s, off)


def _rot(p):
    p = np.asarray(p) / np.linalg.norm(p)
    w, x, y, z = p
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


TWO_BODIES = """
[scene]
analysis = "dynamic"

[amplitude.profile]
type = "quintic"
t0 = 0.0
t1 = 0.5

[[body]]
name = "base"
mass = 2.0
center = [0.0, 0.0, 0.0]
inertia = [0.02, 0.03, 0.04]

[[body]]
name = "arm"
mass = 0.7
center = [0.3, 0.1, 0.0]
inertia = [0.002, 0.01, 0.011]

[[constraint]]
type = "prismatic"
name = "rail"
a = "base"
at = [0.0, 0.0, 0.0]
axis = [1.0, 0.2, 0.1]

[[constraint]]
type = "revolute"
name = "elbow"
a = "arm"
b = "base"
at = [0.1, 0.05, 0.0]
axis = [0.1, 0.3, 1.0]

[[actuator]]
name = "slide"
joint = "rail"
effort = 3.0
kp = 40.0
kd = 2.0
setpoint = 0.2
setpoint_amplitude = "profile"

[[actuator]]
name = "motor"
joint = "elbow"
effort = 0.4
kp = 7.0
kd = 0.6
setpoint = 1.1
setpoint_amplitude = "profile"

[dynamic]
t_end = 0.002
dt = 1e-3
"""


def test_actuator_jacobian_matches_central_differences():
    """The actuators' Jacobian as assembled (-tau H + kp g g^T + kd g (H x')^T +
    gp kd g g^T, runtime/assembly/actuators.c) against central differences of
    their assembled forces in q and q' (d/dq + gp d/dq'), at a turned state with
    velocities: a PD + feed-forward motor on a revolute joint between two bodies
    and a PD linear motor on a prismatic joint to the ground, at t = 0.3 (inside
    the set-point's quintic profile), with gp = 0 (statics) and 700 (a step)."""
    from gen.solver_build import VARIANTS, build_solver, compile_object, runtime_headers, runtime_objects
    from util import all_pair_symbols
    _, index = all_pair_symbols()
    pairs = [index["body"]["pair"]]
    obj = BUILD / "sanitize" / "actuator_check.o"
    compile_object(ROOT / "tests" / "actuator_check.c", obj, VARIANTS["sanitize"], runtime_headers())
    objs = [o for o in runtime_objects("sanitize") if o.name != "main.o"] + [obj]
    exe = build_solver(pairs, BUILD / "sanitize" / "actuator_check", index, "sanitize", main_objs=objs)
    _, _, out = _run(TWO_BODIES)
    for gp in (0.0, 700.0):
        r = subprocess.run([str(exe), str(out / "model.dat"), "0.3", str(gp)], capture_output=True, text=True)
        assert r.returncode == 0 and not r.stderr, r.stderr
        err, big = map(float, r.stdout.split())
        assert big > 1.0 and err < 1e-6 * big, (gp, err, big)


def test_motor_torque_turns_a_rigid_link_by_the_double_integral_of_tau_over_J():
    """A rigid link on a hinge (J_O = 0.1 kg m^2 about it), no gravity, driven by a
    motor torque tau = 0.5 sin(2 pi t) N m: theta(t) = tau0/(J w) (t - sin(w t)/w)
    (0.796 rad at t = 1 s) within 0.1 % of its largest value at every output step,
    and the rate and effort in actuators.csv."""
    text = LINK + """
[amplitude.wave]
type = "sine"
frequency = 1.0

[[actuator]]
name = "motor"
joint = "hinge"
effort = 0.5
effort_amplitude = "wave"
"""
    s, _, out = _run(text)
    rows = _rows(out, "actuators.csv")
    w, tau0 = 2 * math.pi, 0.5
    t = np.array([float(r["time"]) for r in rows])
    th = np.array([float(r["value"]) for r in rows])
    rate = np.array([float(r["rate"]) for r in rows])
    eff = np.array([float(r["effort"]) for r in rows])
    ref = tau0 / (J_O * w) * (t - np.sin(w * t) / w)
    ref_rate = tau0 / (J_O * w) * (1 - np.cos(w * t))
    peak = ref.max()
    assert len(rows) == 101 and abs(t[-1] - 1.0) < 1e-12
    assert np.abs(th - ref).max() < 1e-3 * peak, np.abs(th - ref).max() / peak
    assert np.abs(rate - ref_rate).max() < 1e-3 * ref_rate.max()
    assert np.abs(eff - tau0 * np.sin(w * t)).max() < 1e-12
    act = s["actuators"][0]
    assert act["name"] == "motor" and abs(act["peak_effort"] - tau0) < 1e-12 and min(abs(act["peak_time"] - 0.25),
                                                                                 abs(act["peak_time"] - 0.75)) < 1e-9
    print(f"motor link: max |theta - ref| / peak = {np.abs(th - ref).max() / peak:.2e}")


def test_pd_joint_follows_a_step_set_point_as_a_damped_second_order_system():
    """The same link under a PD law, tau = kp (theta_ref - theta) - kd theta', with a
    set-point of 0.5 rad from t = 0 on: J theta'' + kd theta' + kp theta =
    kp theta_ref, omega_n = sqrt(kp/J) = 6.32 rad/s, zeta = kd/(2 sqrt(kp J)) = 0.3,
    theta = theta_ref (1 - e^(-zeta wn t') (cos wd t' + zeta/sqrt(1 - zeta^2) sin wd t'))
    within 1e-3 of theta_ref over 2 s (overshoot 37 %); and the same in statics with
    kp alone (an unloaded link goes to the set-point)."""
    kp, J, zeta, th0, t0 = 4.0, J_O, 0.3, 0.5, 0.0
    kd = 2 * zeta * math.sqrt(kp * J)
    text = LINK.replace("t_end = 1.0", "t_end = 2.0") + f"""
[[actuator]]
name = "pd"
joint = "hinge"
kp = {kp!r}
kd = {kd!r}
setpoint = {th0!r}
"""
    _, _, out = _run(text)
    rows = _rows(out, "actuators.csv")
    t = np.array([float(r["time"]) for r in rows])
    th = np.array([float(r["value"]) for r in rows])
    wn = math.sqrt(kp / J)
    wd = wn * math.sqrt(1 - zeta**2)
    tt = np.clip(t - t0, 0.0, None)
    ref = np.where(t >= t0, th0 * (1 - np.exp(-zeta * wn * tt) * (np.cos(wd * tt) + zeta / math.sqrt(1 - zeta**2)
                                                                     * np.sin(wd * tt))), 0.0)
    err = np.abs(th - ref).max()
    assert th.max() > 1.3 * th0                    # it does overshoot (37 %)
    assert err < 1e-3 * th0, err / th0
    print(f"PD step: max |theta - ref| / theta_ref = {err / th0:.2e}")


def test_bad_actuators():
    """One clear line each: an actuator on a joint without an axis, on a driven
    joint, on a constraint that does not exist, a set-point without a gain, a
    name not of 1 to 63 letters, digits, '_', '.' or '-'."""
    sph = LINK.replace('type = "revolute"', 'type = "spherical"').replace('axis = [0.0, 0.0, 1.0]\n', "")
    check_error(sph + '[[actuator]]\njoint = "hinge"\neffort = 1.0\n', "actuator[0].joint",
                "spherical joint: an actuator needs a joint with an axis")
    check_error(LINK + '[[actuator]]\njoint = "knee"\neffort = 1.0\n', "actuator[0].joint",
                "no constraint named 'knee'")
    check_error(LINK + '[[actuator]]\njoint = "hinge"\nsetpoint = 1.0\n', "actuator[0].kp", "needs a gain")
    check_error(LINK + '[[actuator]]\njoint = "hinge"\nkp = -1.0\n', "actuator[0].kp", "")
    # names: 1 to 63 of letters, digits, '_', '.', '-' (a space, 64 letters, an empty one, a non-ASCII letter)
    for bad in ("the motor", "m" * 64, "", "moteur\u00e9"):
        check_error(LINK + f'[[actuator]]\nname = "{bad}"\njoint = "hinge"\neffort = 1.0\n', "actuator[0].name",
                    "expected 1 to 63 letters, digits")


BEAM_JOINT = """[scene]
analysis = "dynamic"
[material.m]
law = "LAW"
E = 7.0e10
nu = 0.33
rho = 2700.0
[section.bar]
shape = "rectangle"
b = 0.02
h = 0.02
[[beam]]
name = "arm"
element = "ELEMENT"
material = "m"
section = "bar"
start = [0.0, 0.0, 0.0]
end = [0.5, 0.0, 0.0]
elements = 4
[dynamic]
t_end = 0.002
dt = 1e-3
[[constraint]]
name = "j"
"""
# every constraint type: the table's other keys, and the last words of the refusal
# of an actuator on it (None: it takes one)
JOINT_KINDS = {
    "revolute": ('a = "arm:start"\naxis = [0.0, 0.0, 1.0]', None),
    "prismatic": ('a = "arm:start"\naxis = [1.0, 0.0, 0.0]', None),
    "clamp": ('a = "arm:start"', "it has no axis"),
    "spherical": ('a = "arm:start"', "it has no axis"),
    "fixed": ('a = "arm:start"', "it has no axis"),
    "universal": ('a = "arm:start"\naxis = [0.0, 0.0, 1.0]\naxis_b = [0.0, 1.0, 0.0]', "two axes"),
    "point_on_line": ('a = "arm:end"\naxis = [1.0, 0.0, 0.0]', "a force along it is a `force` load"),
    "prescribed_motion": ('a = "arm:end"\nmotion = [0.0, 0.01, 0.0]\namplitude = {type = "ramp", t0 = 0.0, t1 = 0.01}',
                          "its force is in reactions.csv"),
    "prescribed_rotation": ('a = "arm:start"\naxis = [0.0, 0.0, 1.0]\nrate = 1.0', "its effort is in joints.csv"),
    "prescribed_translation": ('a = "arm:start"\naxis = [1.0, 0.0, 0.0]\nrate = 1.0', "its effort is in joints.csv"),
}


def test_which_joints_take_an_actuator():
    """Issue 40, verification 5 and the actuators' scope: of every constraint type
    (gen/scene_keys.py CONSTRAINT, all listed here) an actuator acts on `revolute`
    and `prismatic` joints (a gef beam's end to the ground: the run ends with exit 0
    and actuators.csv); on each other type it is refused with one line naming
    actuator[0].joint and why; on an ANCF point (no nodal rotation) a revolute
    joint, fine without a motor, is refused with one line saying the motor needs a
    rotation there."""
    import gen.scene_keys as K
    assert set(JOINT_KINDS) == set(K.CONSTRAINT)
    gef = BEAM_JOINT.replace("LAW", "resultant").replace("ELEMENT", "gef")
    motor = '[[actuator]]\njoint = "j"\neffort = 0.1\n'
    for kind, (keys, why) in JOINT_KINDS.items():
        text = gef + f'type = "{kind}"\n{keys}\n' + motor
        if why is None:
            s, _, out = _run(text)
            assert s["converged"] and len(_rows(out, "actuators.csv")) == 3, kind
        else:
            check_error(text, "actuator[0].joint", f"is a {kind} joint: an actuator needs a joint with an axis, "
                        f"revolute or prismatic \\(.*{re.escape(why)}")
    ancf = BEAM_JOINT.replace("LAW", "svk").replace("ELEMENT", "ancf3243") + 'type = "revolute"\n' + \
        JOINT_KINDS["revolute"][0] + "\n"
    s, _, _ = _run(ancf)                           # without a motor: the linear rows of an ANCF hinge
    assert s["converged"]
    check_error(ancf + motor, "constraint[0].a", "a revolute joint with an actuator needs a rotation on both sides")


def test_sweep_window_outputs_of_the_motor_link():
    """beamkit/windows.py on the motor-driven link's results (effort 0.5 sin(2 pi t)
    sampled every 0.01 s from 0 to 1 s): peak 0.5 and amplitude 0.5 over the run,
    rms 0.5 sqrt(50/101) (the 101 samples' sin^2 sum to 50), over [0.2, 0.3] s the
    max 0.5 (t = 0.25) and min 0.5 sin(0.4 pi); the joint's angle at the end equals
    the closed form (through the joint's name in joints.csv); bad outputs refused."""
    from beamkit import windows
    text = LINK + """
[amplitude.wave]
type = "sine"
frequency = 1.0

[[actuator]]
name = "motor"
joint = "hinge"
effort = 0.5
effort_amplitude = "wave"
"""
    _, _, out = _run(text)
    v = lambda o: windows.value(out, o)
    assert abs(v("motor.effort:peak") - 0.5) < 1e-12 and abs(v("motor.effort:amplitude") - 0.5) < 1e-12
    assert abs(v("motor.effort:rms") - 0.5 * math.sqrt(50 / 101)) < 1e-12
    assert abs(v("motor.effort:max@0.2:0.3") - 0.5) < 1e-12
    assert abs(v("motor.effort:min@0.2:0.3") - 0.5 * math.sin(0.4 * math.pi)) < 1e-12
    mean = 0.5 * sum(math.sin(2 * math.pi * k / 100) for k in range(50, 101)) / 51
    assert abs(v("motor.effort:mean@0.5:1.0") - mean) < 1e-12
    assert abs(v("hinge.value:max") - 0.5 / (J_O * 2 * math.pi)) < 1e-3 * 0.8
    assert v("motor.effort:peak@2:3") is None
    import tomllib
    doc = tomllib.loads(text)
    assert windows.check(doc, "s", "motor.effort:peak@1:3") is None
    assert "no joint or actuator 'elbow'" in windows.check(doc, "s", "elbow.effort:peak")
    assert "unknown statistic 'median'" in windows.check(doc, "s", "motor.effort:median")
    assert "T1 > T0" in windows.check(doc, "s", "motor.effort:rms@3:1")
    assert "no sensor 'tip'" in windows.check(doc, "s", "tip.uy:peak")


def test_sweep_reports_window_outputs():
    """A sweep of the motor link over two effort levels (one local worker) with
    window outputs: the peak effort is the effort level, the largest angle over
    0 - 1 s the closed form tau0 / (J w) (0.1 % as above)."""
    from beamkit.sweep import sweep
    text = LINK + """
[amplitude.wave]
type = "sine"
frequency = 1.0

[[actuator]]
name = "motor"
joint = "hinge"
effort = 0.5
effort_amplitude = "wave"
"""
    d = Path(tempfile.mkdtemp(prefix="bk-actsw-", dir=ensure_dir(BUILD / "runs")))
    (d / "link.toml").write_text(text)
    res = sweep(str(d / "link.toml"), grid={"actuator.0.effort": [0.5, 1.0]}, out=d / "sweep", workers=1,
                progress=False, outputs=["motor.effort:peak", "hinge.value:max@0:1"])
    assert not res.failed
    peak, th = res.column("motor.effort:peak"), res.column("hinge.value:max@0:1")
    assert np.allclose(peak, [0.5, 1.0], rtol=1e-12, atol=0)
    ref = np.array([0.5, 1.0]) / (J_O * 2 * math.pi)
    assert np.abs(th / ref - 1).max() < 1e-3, th / ref


def test_plot_draws_joints_actuators_and_reactions():
    """./build.sh plot's joints.png (the hinge's angle, rate and effort and the
    motor's, from joints.csv and actuators.csv) and reactions.png: the lines drawn
    are the tables' columns."""
    from report.plot import figures
    text = LINK + '[[actuator]]\nname = "motor"\njoint = "hinge"\neffort = 0.2\n'
    _, _, out = _run(text)
    figs = figures(out)
    assert "joints.png" in figs and "reactions.png" in figs
    acts = _rows(out, "actuators.csv")
    ax = figs["joints.png"].axes
    lines = {ln.get_label(): ln for ln in ax[2].get_lines()}
    eff = lines["actuator motor (rad, N m)"].get_ydata()
    assert np.allclose(eff, [float(r["effort"]) for r in acts]) and abs(eff[-1] - 0.2) < 1e-12
    ang = {ln.get_label(): ln for ln in ax[0].get_lines()}["joint hinge (rad, N m)"].get_ydata()
    assert np.allclose(ang[-1], 0.2 / (2 * J_O), rtol=1e-3)          # theta = tau t^2 / (2 J) at t = 1
    rx = {ln.get_label() for ln in figs["reactions.png"].axes[0].get_lines()}
    assert "hinge Fx" in rx
    import matplotlib.pyplot as plt
    for f in figs.values():
        plt.close(f)


def test_modal_analysis_includes_the_actuators_spring():
    """The hinged link held by an actuator with kp = 4 N m/rad (no other stiffness):
    the modal analysis' one frequency is sqrt(kp / J_O) / 2 pi = 1.00658 Hz (the
    actuator's stiffness kp g g^T in the modal stiffness), about the reference and
    about the static state under a dead moment about the hinge (0.2 N m: turned by
    M / kp = 0.05 rad, the same spring: the moment's own load stiffness in the
    quaternion coordinates, which the modal analysis takes (symmetrized, with a
    warning), cancels the actuator's -tau d2s/dq2; it was 2.5e-6 off when modal
    left the load stiffness out).  The sparse solver takes the same stiffness."""
    text = LINK.replace('analysis = "dynamic"', 'analysis = "modal"') + """
[modal]
modes = 1

[[actuator]]
name = "spring"
joint = "hinge"
kp = 4.0
"""
    ref = math.sqrt(4.0 / J_O) / (2 * math.pi)
    s, _, _ = _run(text)
    assert abs(s["frequencies_hz"][0] / ref - 1) < 1e-9, (s["frequencies_hz"], ref)
    s, _, _ = _run(text + '[[load]]\ntype = "moment"\nat = "link"\nvalue = [0.0, 0.0, 0.2]\n',
                   ["modal.about=static"])
    assert abs(s["frequencies_hz"][0] / ref - 1) < 1e-9, (s["frequencies_hz"], ref)
    assert any("load stiffness of moments" in w and "symmetrized" in w for w in s["warnings"]), s["warnings"]
    s, _, _ = _run(text, ["modal.solver=sparse"])
    assert abs(s["frequencies_hz"][0] / ref - 1) < 1e-9, (s["frequencies_hz"], ref)
