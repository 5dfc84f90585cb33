"""A rigid body's primitive resting on a fixed primitive ([[body_contact]]:
gen/scene/body_contact.py, runtime/assembly/body_contact.c; issue 34, a body
on a table), against closed forms: a box resting on a table passes its
weight M g to it (to 1e-6); pushed below mu_s M g it stays (within a few slip
tolerances, no creep), above it slides with the kinetic energy
t^2 (F - mu_k M g)^2 / (2 M) (within 2 %); a ball dropped onto the ground at
dt = 1e-2, 1e-3, 1e-4 never passes into it, and at dt = 1e-4 keeps its
energy (1 %).  The Jacobian on the body against central differences
(tests/contact_roll_check.c) for a box (corners) and a ball (its friction on
the surface point that turns with it) across stick, transition and slip; bad
input is one line."""
import csv
import json

from test_contact_rolling import _build_check
from test_contact_scenes import out_dir, run_scene_expect_error
from util import ROOT, run_cli, run_scene

M, G = 2.0, 9.81


def _box(push=None, ramp=None, extra=()):
    text = (ROOT / "models" / "contact_box_table.toml").read_text()
    if push is not None:
        amp = f'\namplitude = {{type = "ramp", t0 = 0.0, t1 = {ramp!r}}}' if ramp else ""
        text = text.replace("value = [0.0, 0.0, 0.0]", f"value = [{push!r}, 0.0, 0.0]{amp}")
    for a, b in extra:
        assert a in text, a
        text = text.replace(a, b)
    p = out_dir() / "box.toml"
    p.write_text(text)
    out = out_dir()
    s, _ = run_scene(p, out=out)
    return s, out


def test_a_box_resting_on_a_table_passes_its_weight():
    s, out = _box()
    bc = s["body_contact"]
    assert bc["max_penetration"] == 0 and 0 < bc["min_distance"] < 1e-3, bc
    assert abs(bc["sets"][0]["normal_force"] / (M * G) - 1) < 1e-6, bc
    assert abs(bc["sets"][0]["force"][2] / (M * G) - 1) < 1e-6 and bc["sets"][0]["active_points"] == 4, bc
    with open(out / "body_contacts.csv", newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["step"] == "100"]
    assert len(rows) == 4 and abs(sum(float(r["fz"]) for r in rows) / (M * G) - 1) < 1e-6, rows


def _ux(out):
    with open(out / "sensors.csv", newline="") as fh:
        return [(float(r["time"]), float(r["ux"])) for r in csv.DictReader(fh)]


def test_a_pushed_box_sticks_below_static_friction_and_slides_with_the_closed_form_energy_above():
    """mu_s = 0.4, mu_k = 0.3: mu_k M g = 5.886 N, mu_s M g = 7.848 N.  Pushed
    by 5 N and by 7 N (between the two; ramped over 50 ms) it stays within
    3 slip tolerances (1e-7 m each; measured 7.8e-8, 1.1e-7 m) and does not
    creep once the push is constant; pushed by 10 N at once it slides:
    kinetic energy t^2 (F - mu_k M g)^2 / (2 M) within 2 % (+1.4 %: the first
    step has no friction yet)."""
    for push in (5.0, 7.0):
        _, out = _box(push, ramp=0.05)
        ux = _ux(out)
        assert max(abs(u) for _, u in ux) < 3e-7, (push, ux[-1])
        late = [u for t, u in ux if t >= 0.06]
        assert max(late) - min(late) < 1e-8, (push, late)
    _, out = _box(10.0)
    with open(out / "energy.csv", newline="") as fh:
        last = list(csv.DictReader(fh))[-1]
    t, kinetic = float(last["time"]), float(last["kinetic"])
    ref = t * t * (10.0 - 0.3 * M * G) ** 2 / (2 * M)
    assert abs(kinetic / ref - 1) < 0.02, (kinetic, ref)
    with open(out / "body_contacts.csv", newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["step"] == "50"]
    assert rows and all(r["state"] == "slip" for r in rows), rows
    fx = sum(float(r["fx"]) for r in rows)
    fn = sum(float(r["normal_force"]) for r in rows)
    assert abs(-fx / (0.3 * fn) - 1) < 1e-3, (fx, fn)       # Coulomb: mu_k N against the motion


BALL = """[scene]
analysis = "dynamic"
[[body]]
name = "ball"
mass = 1.0
center = [0.0, 0.0, 0.1]
inertia = [1e-3, 1e-3, 1e-3]
[[load]]
type = "gravity"
value = [0.0, 0.0, -9.81]
[[body_contact]]
body = "ball"
shape = "sphere"
center = [0.0, 0.0, 0.1]
radius = 0.05
against = {shape = "half_space", normal = [0.0, 0.0, 1.0]}
distance = 1e-3
friction = 0.3
[dynamic]
t_end = 0.3
dt = 1e-3
rho_inf = 1.0
[[sensor]]
name = "ball"
at = "ball"
"""


def test_a_dropped_ball_never_passes_into_the_ground():
    """Dropped from 5 cm (1 m/s at the ground), rho_inf = 1: no point ever at a
    distance <= 0 (body_contacts.csv, the centre's height), it bounces; at
    dt = 1e-4 the total energy stays within 1 % of the start (-9e-4 of m g h)."""
    p = out_dir() / "ball.toml"
    p.write_text(BALL)
    for dt in (1e-2, 1e-3, 1e-4):
        out = out_dir()
        s, rows = run_scene(p, sets=[f"dynamic.dt={dt!r}"], out=out)
        assert s["body_contact"]["max_penetration"] == 0, (dt, s["body_contact"])
        with open(out / "body_contacts.csv", newline="") as fh:
            d = [float(r["distance"]) for r in csv.DictReader(fh)]
        assert d and min(d) > 0.0, dt
        z = [float(r["z"]) for r in rows]
        assert min(z) > 0.05 and z[-1] > 0.05, (dt, min(z))
        if dt == 1e-4:
            with open(out / "energy.csv", newline="") as fh:
                tot = [(float(r["time"]), float(r["total"])) for r in csv.DictReader(fh)]
            mgh = 1.0 * 9.81 * 0.05             # (the barrier's own energy is not in the total: it dips in contact)
            assert max(e for _, e in tot) < 0.01 * mgh, max(e for _, e in tot)
            apex = min(tot, key=lambda te: abs(te[0] - 0.2))[1]     # in the air again, at the top
            assert abs(apex) < 0.01 * mgh, apex


def test_body_contact_jacobian_against_differences():
    """A box (its corners) and a ball (friction on its surface point, which
    turns with it) on the ground, slip tolerance 1e-3 m, the body displaced by
    about 2e-4 (stick), 1.5e-3 (transition) and 6e-3 m (slip) and turned
    about z from an accepted state."""
    exe = _build_check()
    import subprocess
    box = (ROOT / "models" / "contact_box_table.toml").read_text().replace(
        "kinetic_friction = 0.3", "kinetic_friction = 0.3\nslip = 1e-3")
    ball = BALL.replace("friction = 0.3", "friction = 0.3\nslip = 1e-3").replace(
        "center = [0.0, 0.0, 0.1]", "center = [0.0, 0.0, 0.05099]")
    for case, text in (("box", box), ("ball", ball)):
        p = out_dir() / f"{case}.toml"
        p.write_text(text)
        out = out_dir()
        r = run_cli(["run", str(p), "--quiet", "--out", str(out), "--set", "dynamic.t_end=0.001"])
        assert (out / "model.dat").exists(), r.stderr[-2000:]
        for amp in (2e-4, 1.5e-3, 6e-3):
            c = subprocess.run([str(exe), str(out / "model.dat"), repr(amp), "body_contact"], capture_output=True,
                               text=True, timeout=300)
            assert c.returncode == 0, (case, amp, c.returncode, c.stderr[-2000:])
            jerr, jmax, fmax, rolling = c.stdout.split()
            assert int(rolling) > 0 and float(fmax) > 0.0, (case, amp, c.stdout)
            assert float(jerr) < 1e-6 * float(jmax), (case, amp, c.stdout)


def test_bad_body_contact_input_is_one_clear_line():
    text = (ROOT / "models" / "contact_box_table.toml").read_text()
    for a, b, msg in (('body = "box"', 'body = "crate"', "body_contact[0].body: expected the name of a [[body]]"),
                      ("against = {", "#", "body_contact[0].against: expected an inline table"),
                      ('shape = "box"\ncenter', 'shape = "half_space"\ncenter', "body_contact[0].shape"),
                      ("point = [0.0, 0.0, 0.0]}", "point = [0.0, 0.0, 0.002]}", "starts 0.00100"),
                      ("static_friction = 0.4", "static_friction = 0.2", "kinetic_friction: expected at most")):
        p = out_dir() / "bad.toml"
        assert a in text, a
        p.write_text(text.replace(a, b, 1))
        assert msg in run_scene_expect_error(p), (msg, run_scene_expect_error(p))


def test_slip_velocity_sets_the_stick_slip_transition_per_step():
    """slip_velocity = 1 m/s at dt = 1e-3 s: the slip tolerance is v_s dt =
    1 mm.  The box pushed by 7 N (ramped over 0.2 s, held, mass-proportional
    damping) stands on its stick spring at the closed form of the smoothed
    law, mu_s M g f1(y) = F: y = eps (1 - sqrt(1 - F / (mu_s M g))) =
    0.6713 mm (measured +1.2e-4), the same as with slip = 1e-3 given directly;
    with slip and slip_velocity both, or slip_velocity in statics, one line."""
    import math
    runs = []
    for opt in ("slip_velocity = 1.0", "slip = 1e-3"):
        _, out = _box(7.0, ramp=0.2, extra=(("kinetic_friction = 0.3", f"kinetic_friction = 0.3\n{opt}"),
                                           ("t_end = 0.1", "t_end = 0.5\nrayleigh_alpha = 50.0")))
        runs.append(_ux(out)[-1][1])
    ref = 1e-3 * (1 - math.sqrt(1 - 7.0 / (0.4 * M * G)))
    assert abs(runs[0] / ref - 1) < 2e-3, (runs, ref)
    assert runs[0] == runs[1], runs
    text = (ROOT / "models" / "contact_box_table.toml").read_text()
    p = out_dir() / "bad.toml"
    p.write_text(text.replace("kinetic_friction = 0.3", "kinetic_friction = 0.3\nslip = 1e-6\nslip_velocity = 1.0"))
    assert "body_contact[0].slip_velocity: expected either `slip`" in run_scene_expect_error(p)
    rod = (ROOT / "models" / "contact_rod_ground.toml").read_text()
    p.write_text(rod.replace("distance = 0.001", "distance = 0.001\nfriction = 0.3\nslip_velocity = 1e-3"))
    assert "contact[0].slip_velocity: is for dynamics" in run_scene_expect_error(p)
