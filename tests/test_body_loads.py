"""Loads on rigid bodies (gen/scene/body_loads.py; the rigid_body element's
generated moment(), gen/emit_body.py), against closed forms: a link on a hinge
turned by a dead moment and by a follower force at its tip (theta = T t^2 / 2 J),
a free body pushed at its centre of mass (x = F t^2 / 2 m), the static angle of a
hinged body under a moment held by a PD actuator's spring (M / kp); and the
generated moment's Jacobian against central differences."""
import csv
import ctypes
import math
import tempfile
from pathlib import Path

import numpy as np

from util import BUILD, ensure_dir, run_scene
from test_bad_input import check_error

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

[[sensor]]
name = "c"
at = "link"

[dynamic]
t_end = 0.5
dt = 1e-3
output_every = 10
"""
J_O = 0.025 + 1.2 * 0.25**2


def _run(text, sets=()):
    d = Path(tempfile.mkdtemp(prefix="bk-bload-", dir=ensure_dir(BUILD / "runs")))
    (d / "scene.toml").write_text(text)
    s, rows = run_scene(d / "scene.toml", sets, out=d / "out")
    return s, rows, d / "out"


def _angles(out):
    with open(Path(out) / "sensors.csv", newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["sensor"] == "c"]
    t = np.array([float(r["time"]) for r in rows])
    th = np.unwrap(np.array([math.atan2(float(r["d1y"]), float(r["d1x"])) for r in rows]))
    return t, th


def test_dead_moment_on_a_body_turns_the_hinged_link():
    """A moment of 0.3 N m about z on the link (at = its name): theta = M t^2 / (2 J_O)."""
    _, _, out = _run(LINK + '[[load]]\ntype = "moment"\nat = "link"\nvalue = [0.0, 0.0, 0.3]\n')
    t, th = _angles(out)
    ref = 0.3 * t**2 / (2 * J_O)
    assert np.abs(th - ref).max() < 1e-4 * ref.max(), np.abs(th - ref).max() / ref.max()


def test_follower_force_at_a_body_point_keeps_its_lever():
    """A follower force of 0.4 N along +y (reference) at the link's tip point
    [0.5, 0, 0] stays perpendicular to the link: a constant torque 0.5 x 0.4 N m,
    theta = 0.2 t^2 / (2 J_O) through 1.25 rad."""
    _, _, out = _run(LINK + '[[load]]\ntype = "force"\nat = "link"\npoint = [0.5, 0.0, 0.0]\nvalue = [0.0, 0.4, 0.0]\n'
                     'follower = true\n')
    t, th = _angles(out)
    ref = 0.2 * t**2 / (2 * J_O)
    assert ref.max() > 0.2
    assert np.abs(th - ref).max() < 1e-4 * ref.max(), np.abs(th - ref).max() / ref.max()


def test_dead_force_at_the_centre_of_a_free_body():
    """A free body pushed by F = (1, -2, 0.5) N at its centre of mass: x = F t^2 / 2 m."""
    text = """
[scene]
analysis = "dynamic"

[[body]]
name = "block"
mass = 2.0
center = [0.1, 0.2, 0.3]
inertia = [0.01, 0.02, 0.025]

[[load]]
type = "force"
at = "block"
value = [1.0, -2.0, 0.5]

[[sensor]]
name = "c"
at = "block"

[dynamic]
t_end = 0.3
dt = 1e-3
"""
    s, _, _ = _run(text)
    u = np.array(s["sensors"]["c"]["displacement"])
    ref = np.array([1.0, -2.0, 0.5]) * 0.3**2 / (2 * 2.0)
    assert np.abs(u - ref).max() < 1e-9 + 1e-6 * np.abs(ref).max(), (u, ref)


def test_static_moment_on_a_body_against_a_pd_spring():
    """Statics: the hinged link under a moment of 0.2 N m about z held by an
    actuator of stiffness kp = 5 N m/rad (set-point 0): theta = M / kp = 0.04 rad."""
    text = LINK.replace('analysis = "dynamic"', 'analysis = "static"') + """
[[load]]
type = "moment"
at = "link"
value = [0.0, 0.0, 0.2]

[[actuator]]
name = "spring"
joint = "hinge"
kp = 5.0
"""
    _, _, out = _run(text)
    t, th = _angles(out)
    assert abs(th[-1] - 0.04) < 1e-9, th[-1]


def test_bad_body_loads():
    """One line each: a body point far outside the body, a point on a moment."""
    base = LINK + '[[load]]\ntype = "force"\nat = "link"\nvalue = [0.0, 1.0, 0.0]\n'
    check_error(base + 'follower = true\npoint = [50.0, 0.0, 0.0]\n', "load[0].point",
                "expected a point of the body")
    check_error(LINK + '[[load]]\ntype = "moment"\nat = "link"\nvalue = [0.0, 0.0, 1.0]\npoint = [0.5, 0.0, 0.0]\n',
                "load[0].point", "unknown key")


def test_rigid_body_moment_kernel_against_finite_differences():
    """The rigid body's generated moment() (a moment fixed in space on its
    quaternion) and its Jacobian against 4th-order central differences, with the
    element checks of tests/kernel_check.c (force, tangent, rigid motions)."""
    import subprocess
    from util import all_pair_symbols, build_program
    _, index = all_pair_symbols()
    exe = build_program("kernel_check.c", "kernel_check_body", "sanitize", pairs=[index["body"]["pair"]])
    r = subprocess.run([str(exe), "5", "rigid_body"], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0 and "runtime error" not in r.stderr, r.stdout + r.stderr[-3000:]
    rows = [dict(kv.split("=", 1) for kv in line.split()) for line in r.stdout.splitlines()]
    assert rows and all(float(d["fd_moment"]) <= 1e-8 for d in rows), r.stdout
    print(r.stdout)


def test_sensor_at_a_body_point_follows_the_body():
    """A sensor at the link's tip point [0.5, 0, 0] (sensor.point) while the moment
    of 0.3 N m turns it: the point is on the circle of radius 0.5 at the
    link's angle (from the centre-of-mass sensor's axes), and its displacement is
    from its own reference place."""
    _, _, out = _run(LINK + '[[load]]\ntype = "moment"\nat = "link"\nvalue = [0.0, 0.0, 0.3]\n'
                     '[[sensor]]\nname = "tip"\nat = "link"\npoint = [0.5, 0.0, 0.0]\n')
    t, th = _angles(out)
    with open(Path(out) / "sensors.csv", newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["sensor"] == "tip"]
    p = np.array([[float(r[k]) for k in ("x", "y", "z", "ux", "uy", "uz")] for r in rows])
    ref = np.column_stack([0.5 * np.cos(th), 0.5 * np.sin(th), 0 * th])
    assert th[-1] > 0.3
    assert np.abs(p[:, :3] - ref).max() < 1e-12
    assert np.abs(p[:, 3:] - (ref - [0.5, 0.0, 0.0])).max() < 1e-12


def test_dead_force_at_a_body_point_against_a_pd_spring_statics():
    """Statics: the hinged link held by an actuator spring kp = 5 N m/rad, a dead
    force F = (0, -2, 0) N at its tip point [0.5, 0, 0]: equilibrium
    kp theta = 0.5 F_y cos(theta) (root by brentq: -0.19289 rad), within 1e-9."""
    from scipy.optimize import brentq
    text = LINK.replace('analysis = "dynamic"', 'analysis = "static"') + """
[[load]]
type = "force"
at = "link"
point = [0.5, 0.0, 0.0]
value = [0.0, -2.0, 0.0]

[[actuator]]
name = "spring"
joint = "hinge"
kp = 5.0

[static]
load_steps = 4
"""
    _, _, out = _run(text)
    t, th = _angles(out)
    ref = brentq(lambda x: 5.0 * x + 1.0 * math.cos(x), -1.0, 0.0, xtol=1e-14)
    assert abs(th[-1] - ref) < 1e-9, (th[-1], ref)


def test_dead_force_at_a_body_point_jacobian_against_central_differences():
    """The interactions' Jacobian (dead forces at points of two bodies, with the PD
    motors of tests/test_actuators.py) against central differences of their forces
    (tests/actuator_check.c), at a turned state with velocities."""
    import subprocess
    from gen.solver_build import VARIANTS, build_solver, compile_object, runtime_headers, runtime_objects
    from test_actuators import TWO_BODIES
    from util import ROOT, all_pair_symbols
    _, index = all_pair_symbols()
    obj = BUILD / "sanitize" / "actuator_check.o"
    compile_object(ROOT / "tests" / "actuator_check.c", obj, VARIANTS["sanitize"], runtime_headers())
    objs = [o for o in runtime_objects("sanitize") if o.name != "main.o"] + [obj]
    exe = build_solver([index["body"]["pair"]], BUILD / "sanitize" / "actuator_check", index, "sanitize",
                       main_objs=objs)
    text = TWO_BODIES + """
[[load]]
type = "force"
at = "arm"
point = [0.5, 0.2, 0.05]
value = [3.0, -2.0, 1.0]

[[load]]
type = "force"
at = "base"
point = [0.1, -0.1, 0.2]
value = [-1.0, 0.5, 2.0]
amplitude = {type = "sine", frequency = 2.0}
"""
    _, _, out = _run(text)
    for gp in (0.0, 700.0):
        r = subprocess.run([str(exe), str(out / "model.dat"), "0.3", str(gp)], capture_output=True, text=True)
        assert r.returncode == 0 and not r.stderr, r.stderr
        err, big = map(float, r.stdout.split())
        assert big > 1.0 and err < 1e-6 * big, (gp, err, big)


def test_damaged_interaction_records_are_refused_naming_the_record():
    """The actuators and the forces at body points are interactions reading their
    own model records ("actuator", "body_force"; runtime/assembly/actuators.c,
    body_forces.c): a record naming a joint or an element out of range, a force on
    an element that is not a body, or a token too many is refused with one line
    naming the model file and the record."""
    import subprocess
    from util import ROOT
    text = LINK + """
[[load]]
type = "force"
at = "link"
point = [0.5, 0.0, 0.0]
value = [0.0, -2.0, 0.0]

[[actuator]]
name = "spring"
joint = "hinge"
kp = 5.0
"""
    d = Path(tempfile.mkdtemp(prefix="bk-bload-", dir=ensure_dir(BUILD / "runs")))
    (d / "bload_records.toml").write_text(text)
    run_scene(d / "bload_records.toml", out=d / "out")
    model = (d / "out" / "model.dat").read_text()
    act = next(line for line in model.splitlines() if line.startswith("actuator spring "))
    bf = next(line for line in model.splitlines() if line.startswith("body_force "))
    assert "\nrecord actuator\nactuators 1\n" in model and "\nrecord body_force\nbody_forces 1\n" in model
    f = act.split()
    cases = [(model.replace(act, " ".join(f[:3] + ["7"] + f[4:])), "record actuator: actuator joint: expected an "
              "integer in [0, 0], found '7'"),
             (model.replace(act, act + " 1"), "record actuator: unexpected '1' after the record's data"),
             (model.replace(bf, "body_force 9 " + bf.split(" ", 2)[2]), "record body_force: body force element: "
              "expected an integer in [0, 0], found '9'"),
             (model.replace("record body_force", "record body_forcez"), "record body_forcez: no interaction module "
              "of this solver reads it")]
    for k, (edited, msg) in enumerate(cases):
        (d / f"edited{k}.dat").write_text(edited)
        (d / f"w{k}").mkdir()
        r = subprocess.run([str(ROOT / "out" / "bin" / "bload_records"), str(d / f"edited{k}.dat"), str(d / f"w{k}"),
                            "--quiet"], capture_output=True, text=True)
        assert r.returncode == 1 and len(r.stderr.strip().splitlines()) == 1, (k, r.returncode, r.stderr)
        assert f"{d / f'edited{k}.dat'}, {msg}" in r.stderr, (k, r.stderr)
