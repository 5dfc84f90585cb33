"""Rolling of round rods (issue 34): friction acts on the section's surface,
at the point x - r n, and turns the section (elements with nodal rotations:
gef; docs/explanation/contact.md, Rolling).  Against closed forms: a rod pushed sideways
on the ground rolls without slipping with a = 2F/(3m) (a solid cylinder,
I = m r^2 / 2) and its section turns by y / r; on a 30 degree slope it rolls
with a = (2/3) g sin(alpha) when mu >= tan(alpha) / 3 and slides with
a = g (sin(alpha) - mu cos(alpha)) below (its section spun by the friction's
moment mu N r / I); frictionless it slides with F/m and does not turn; an
ancf_cable rod (no rotations: it slides, not rolls) holds where the gef rod
rolls.  The friction's force and Jacobian on the rolling section against
central differences (tests/contact_roll_check.c) across stick, transition
and slip, on the ground and on a rigid body's box."""
import csv
import math
import subprocess

import numpy as np

from test_contact_scenes import out_dir
from util import BUILD, ROOT, run_cli, run_scene

R, F = 0.005, 1.0
M = 7850.0 * math.pi * R ** 2 * 1.0           # the rod's mass (1 m)
Z1 = 0.005981850356113462                     # its centreline's equilibrium height under g (the barrier's)
Z30 = 0.0059831057817507066                   # under g cos(30 deg)


def _scene(replace=(), name="roll"):
    text = (ROOT / "models" / "contact_rod_rolls.toml").read_text()
    for a, b in replace:
        assert a in text, a
        text = text.replace(a, b)
    p = out_dir() / f"{name}.toml"
    p.write_text(text)
    out = out_dir()
    s, rows = run_scene(p, out=out)
    return s, rows, out


def _mid(out):
    """(t, uy, section angle about x, unwrapped) of the sensor 'mid'."""
    with open(out / "sensors.csv", newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["sensor"] == "mid"]
    t = np.array([float(r["time"]) for r in rows])
    uy = np.array([float(r["uy"]) for r in rows])
    th = np.unwrap([math.atan2(float(r["d1z"]), float(r["d1y"])) for r in rows])
    return t, uy, th


SLOPE = (("value = [0.0, 0.0, -9.81]", "value = [0.0, 4.905, -8.495709211826]"),      # g along a 30 deg slope
         ('[[load]]\ntype = "distributed"\nbeam = "rod"\nvalue = [0.0, 1.0, 0.0]\n\n', ""),
         (repr(Z1), repr(Z30)))


def test_a_round_rod_pushed_sideways_rolls_without_slipping():
    """1 N on a 0.6165 kg gef rod, mu = 0.3 (mu m g = 1.81 N): y = a t^2 / 2 with
    a = 2F/(3m) = 1.0813 m/s^2 (measured -2.4e-5 at 0.1 s); no slip at the
    contact, the section's angle = -y / r (3.7e-5); the ground's friction on
    the rod is F/3 against the push (contacts.csv)."""
    _, _, out = _scene()
    t, uy, th = _mid(out)
    ref = 0.5 * (2 * F / (3 * M)) * t[-1] ** 2
    assert abs(uy[-1] / ref - 1) < 1e-3, (uy[-1], ref)
    assert abs(-th[-1] * R / uy[-1] - 1) < 1e-3, (th[-1], uy[-1])
    with open(out / "contacts.csv", newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["step"] == "100"]
    fy = sum(float(r["fy"]) for r in rows)
    assert abs(-fy / (F / 3) - 1) < 1e-2, fy
    assert all(r["state"] == "stick" for r in rows if float(r["normal_force"]) > 0)


def test_frictionless_the_rod_slides_with_f_over_m_and_does_not_turn():
    _, _, out = _scene([("friction = 0.3", "friction = 0.0")])
    t, uy, th = _mid(out)
    ref = 0.5 * F / M * t[-1] ** 2
    assert abs(uy[-1] / ref - 1) < 1e-3, (uy[-1], ref)
    assert abs(th[-1]) < 1e-9, th[-1]


def test_a_cable_rod_without_rotations_holds_where_the_gef_rod_rolls():
    """ancf_cable carries no section rotation: its friction acts at the
    centreline, so the 1 N push (below mu m g = 1.81 N) is held (within a few
    slip tolerances, 1e-7 m each)."""
    _, _, out = _scene([('element = "gef"', 'element = "ancf_cable"'), ("elements = 10", "elements = 20")])
    t, uy, _ = _mid(out)
    assert max(abs(uy)) < 3e-7, max(abs(uy))


def test_on_a_slope_it_rolls_with_two_thirds_g_sin_alpha_or_slides_below_tan_alpha_over_three():
    """alpha = 30 deg, tan(alpha)/3 = 0.192.  mu = 0.3: rolls, y = (2/3) g
    sin(alpha) t^2 / 2 (measured +2e-5), angle -y/r.  mu = 0.1: slides,
    y = g (sin(alpha) - mu cos(alpha)) t^2 / 2 (+0.2 %: the first step has
    no friction yet), the section spun by mu N r / I = 2 mu g cos(alpha) / r
    (-1 %)."""
    g, a = 9.81, math.radians(30.0)
    _, _, out = _scene(SLOPE, "slope")
    t, uy, th = _mid(out)
    ref = 0.5 * (2.0 / 3.0) * g * math.sin(a) * t[-1] ** 2
    assert abs(uy[-1] / ref - 1) < 2e-3, (uy[-1], ref)
    assert abs(-th[-1] * R / uy[-1] - 1) < 2e-3, (th[-1], uy[-1])
    _, _, out = _scene(SLOPE + (("friction = 0.3", "friction = 0.1"),), "slope_slides")
    t, uy, th = _mid(out)
    ref = 0.5 * g * (math.sin(a) - 0.1 * math.cos(a)) * t[-1] ** 2
    assert abs(uy[-1] / ref - 1) < 1e-2, (uy[-1], ref)
    spin = 0.5 * 2 * 0.1 * g * math.cos(a) / R * t[-1] ** 2
    assert abs(-th[-1] / spin - 1) < 3e-2, (th[-1], spin)
    assert -th[-1] * R < 0.9 * uy[-1]                       # it slips: the contact point moves


def _build_check():
    from gen.solver_build import VARIANTS, build_solver, compile_object, runtime_headers, runtime_objects
    from util import all_pair_symbols
    pairs, index = all_pair_symbols()
    pairs = [p for p in pairs if p.startswith("gef_resultant")] + ["rigid_body_rigid_full"]
    obj = BUILD / "sanitize" / "contact_roll_check.o"
    compile_object(ROOT / "tests" / "contact_roll_check.c", obj, VARIANTS["sanitize"], runtime_headers())
    objs = [o for o in runtime_objects("sanitize") if o.name != "main.o"] + [obj]
    return build_solver(pairs, BUILD / "sanitize" / "contact_roll_check", index, "sanitize", main_objs=objs)


BODY = """
[[body]]
name = "slab"
mass = 5.0
center = [0.5, 0.0, -0.05]
inertia = [0.1, 0.2, 0.3]
"""


def test_rolling_friction_jacobian_against_differences():
    """The contact interaction's Jacobian on a gef rod whose friction turns its
    sections, against central differences of its residual, with the slip
    tolerance 1e-3 m and the surface points displaced by about 2e-4 (stick),
    1.5e-3 (transition) and 6e-3 m (slip) from the accepted state; on the
    ground, and on a box that belongs to a rigid body (the body's coordinates
    in the block)."""
    exe = _build_check()
    ground = (("friction = 0.3", "friction = 0.3\nslip = 1e-3"),)
    slab = ground + (('shape = "half_space"\nnormal = [0.0, 0.0, 1.0]\npoint = [0.0, 0.0, 0.0]',
                      'shape = "box"\ncenter = [0.5, 0.0, -0.05]\nsize = [2.0, 2.0, 0.1]\nbody = "slab"'),
                     ("[dynamic]", BODY + "\n[dynamic]"))
    for case, rep in (("ground", ground), ("body", slab)):
        text = (ROOT / "models" / "contact_rod_rolls.toml").read_text()
        for a, b in rep:
            assert a in text, a
            text = text.replace(a, b)
        p = out_dir() / f"{case}.toml"
        p.write_text(text)
        out = out_dir()
        r = run_cli(["run", str(p), "--quiet", "--out", str(out), "--set", "dynamic.t_end=0.001"])
        assert (out / "model.dat").exists(), r.stderr[-2000:]
        for amp in (2e-4, 1.5e-3, 6e-3):
            c = subprocess.run([str(exe), str(out / "model.dat"), repr(amp), "contact"], capture_output=True, text=True,
                               timeout=300)
            assert c.returncode == 0, (case, amp, c.returncode, c.stderr[-2000:])
            jerr, jmax, fmax, rolling = c.stdout.split()
            assert int(rolling) > 0 and float(fmax) > 0.0, (case, amp, c.stdout)
            assert float(jerr) < 1e-6 * float(jmax), (case, amp, c.stdout)
