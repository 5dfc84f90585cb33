"""Beam-to-beam contact in dynamics (issue 35 part 2; [[beam_contact]] with
analysis = "dynamic", runtime/assembly/beam_contact*.c, analysis/dynamics.c).

Against closed forms: a short bar dropped across a clamped-clamped beam
settles to the beam's static sag under the bar's weight and its own
(Euler-Bernoulli) with the contact carrying the bar's weight; a bar thrown at
the beam never passes through it at dt = 1e-4 ... 1e-2 (fixed and adaptive
steps; the positions from sensors.csv, not from the contact code) and gains no
energy; two equal free bars colliding crosswise exchange their velocities (the
rigid-body limit of a conservative impact of equal masses) with the total
momentum constant to round-off; a bar pushed along a stiff rail slides with
the kinetic coefficient (kinetic energy t^2 (F - mu_k m g)^2 / (2m)) and,
pushed by less than mu_s m g but more than mu_k m g, sticks."""
import csv
import json
import tempfile
from functools import lru_cache
from pathlib import Path

import pytest

from util import BUILD, ROOT, ensure_dir, run_memcheck, run_scene

DROP = (ROOT / "models" / "contact_bar_drop.toml").read_text()
R_BEAM, R_BAR = 0.005, 0.004                       # contact radii: half-heights


def out_dir():
    return Path(tempfile.mkdtemp(prefix="bk-bcdyn-", dir=ensure_dir(BUILD / "runs")))


def _scene(text, name="scene"):
    d = out_dir()
    p = d / f"{name}.toml"
    p.write_text(text)
    return p, d / "out"


def _heights(out):
    """{time: {sensor: z}} from sensors.csv."""
    z = {}
    with open(out / "sensors.csv", newline="") as fh:
        for r in csv.DictReader(fh):
            z.setdefault(float(r["time"]), {})[r["sensor"]] = float(r["z"])
    return z


def _energy(out):
    with open(out / "energy.csv", newline="") as fh:
        return [float(r["total"]) for r in csv.DictReader(fh)]


def test_dropped_bar_settles_to_the_static_deflection():
    """models/contact_bar_drop.toml: the beam (L = 1 m, EI = 7e10 * 1e-8 / 12)
    sags P L^3 / (192 EI) + q L^4 / (384 EI) at its middle under the bar's
    weight P and its own weight q (clamped at both ends); the contact force on
    each is P, equal and opposite; the bar rests on the beam."""
    p, out = _scene(DROP)
    s, _ = run_scene(p, out=out)
    EI, L, g = 7.0e10 * 0.01 ** 4 / 12, 1.0, 9.81
    P, q = 7800.0 * 0.04 * 0.008 * 0.2 * g, 2700.0 * 0.01 * 0.01 * g
    sag = P * L ** 3 / (192 * EI) + q * L ** 4 / (384 * EI)
    mid = -s["sensors"]["mid"]["displacement"][2]
    assert abs(mid / sag - 1) < 0.01, (mid, sag)
    c = s["contact"]
    bar, beam = c["beam_sets"][0]["beams"]["bar"], c["beam_sets"][0]["beams"]["beam"]
    assert abs(bar[2] / P - 1) < 1e-3, (bar, P)
    assert all(abs(bar[i] + beam[i]) <= 1e-12 * P for i in range(3)), (bar, beam)
    assert c["max_penetration"] == 0 and 0 < c["min_distance"] < 1e-5, c
    gap = s["sensors"]["bar"]["position"][2] - s["sensors"]["mid"]["position"][2] - R_BEAM - R_BAR
    assert 0 < gap < 1e-5, gap


def _thrown(dt, extra="", contact=True, z0=0.1, t_end=0.1):
    """The bar thrown down at 2 m/s from z0, no gravity, no damping,
    rho_inf = 0: returns (summary, out)."""
    t = DROP.replace('[[load]]\ntype = "gravity"\nvalue = [0.0, 0.0, -9.81]\n',
                     '[[initial_velocity]]\nbeam = "bar"\nvelocity = [0.0, 0.0, -2.0]\n')
    t = t.replace("rayleigh_alpha = 100.0\n", "").replace("rho_inf = 0.5", "rho_inf = 0.0")
    t = t.replace("t_end = 0.4", f"t_end = {t_end}").replace("dt = 1e-3", f"dt = {dt}{extra}")
    t = t.replace("start = [0.5, -0.1, 0.011]", f"start = [0.5, -0.1, {z0}]")
    t = t.replace("end = [0.5, 0.1, 0.011]", f"end = [0.5, 0.1, {z0}]")
    if not contact:
        t = t.replace('[[beam_contact]]\nbeams = ["beam", "bar"]\ndistance = 1e-5\n', "")
    p, out = _scene(t, f"thrown_{dt}")
    s, _ = run_scene(p, out=out)
    return s, out


def _check_thrown(s, out):
    z = _heights(out)
    gaps = [v["bar"] - v["mid"] - R_BEAM - R_BAR for v in z.values()]
    assert min(gaps) > 0, min(gaps)                          # above the beam at every output step
    assert z[max(z)]["bar"] > z[max(z)]["mid"] + 0.01        # and bounced off it
    e = _energy(out)                                         # 0.5 m v^2 at the start
    assert abs(e[0] / (0.5 * 7800 * 0.04 * 0.008 * 0.2 * 4.0) - 1) < 1e-12, e[0]
    assert max(e) <= e[0] * (1 + 1e-6), (max(e), e[0])       # no energy gained (rho_inf = 0 dissipates)
    c = s["contact"]
    assert c["max_penetration"] == 0 and c["element_pairs"] > 0, c


def test_thrown_bar_never_passes_through_fixed_steps():
    """dt = 1e-2 moves the bar 20 mm a step, more than the two sections
    together (18 mm): the predictor and every Newton correction are held to
    the contact's step limit.  The broad phase finds the pair during the fall
    (the pattern grows in dynamics)."""
    for dt in ("1e-2", "1e-3", "1e-4"):
        s, out = _thrown(dt)
        _check_thrown(s, out)


def test_thrown_bar_never_passes_through_adaptive_steps():
    s, out = _thrown("1e-3", extra="\ntol = 1e-5")
    _check_thrown(s, out)
    assert s["steps"] > 100, s["steps"]                      # the step adapted below dt


def test_without_contact_the_thrown_bar_passes_through():
    """The same scene without [[beam_contact]]: the bar ends below the beam
    (so the checks above can fail)."""
    _, out = _thrown("1e-3", contact=False)
    z = _heights(out)
    assert z[max(z)]["bar"] < z[max(z)]["mid"] - 0.05


def test_thrown_bar_with_pattern_growth_under_valgrind():
    """valgrind memcheck on the solver while the pattern grows in dynamics
    (the mass matrix and the Newton matrix follow it)."""
    t = DROP.replace('[[load]]\ntype = "gravity"\nvalue = [0.0, 0.0, -9.81]\n',
                     '[[initial_velocity]]\nbeam = "bar"\nvelocity = [0.0, 0.0, -2.0]\n')
    t = t.replace("rayleigh_alpha = 100.0\n", "").replace("t_end = 0.4", "t_end = 0.06").replace("dt = 1e-3",
                                                                                                 "dt = 5e-3")
    t = t.replace("0.011]", "0.05]")
    p, _ = _scene(t, "vg")
    r, out = run_memcheck(p)
    assert r.returncode == 0, r.stderr[-3000:]
    assert json.loads((out / "summary.json").read_text())["contact"]["element_pairs"] > 0


COLLIDE = """
[scene]
analysis = "dynamic"

[material.steel]
law = "resultant"
E = 2.1e11
nu = 0.3
rho = 7800.0

[section.bar]
shape = "rectangle"
b = 0.01
h = 0.01

[[beam]]
name = "a"
element = "gef"
material = "steel"
section = "bar"
start = [0.0, -0.05, 0.013]
end = [0.0, 0.05, 0.013]
up = [0.0, 0.0, 1.0]
elements = 4

[[beam]]
name = "b"
element = "gef"
material = "steel"
section = "bar"
start = [-0.05, 0.0, 0.0]
end = [0.05, 0.0, 0.0]
up = [0.0, 0.0, 1.0]
elements = 4

[[initial_velocity]]
beam = "a"
velocity = [0.0, 0.0, -1.0]

[[beam_contact]]
beams = ["a", "b"]
distance = 2e-3
stiffness = 1e5

[dynamic]
t_end = 0.008
dt = 1e-5
rho_inf = 1.0

[[sensor]]
name = "a"
at = "a:0.05"

[[sensor]]
name = "b"
at = "b:0.05"
"""


@lru_cache(maxsize=None)
def collision():
    p, out = _scene(COLLIDE, "collide")
    run_scene(p, out=out)
    return _heights(out)


def test_equal_bars_exchange_their_velocities():
    """Bar a (0.1 m, steel, 10 x 10 mm) at 1 m/s onto the equal bar b at rest,
    crosswise, centre on centre: a soft barrier (2 mm reach) makes the impact
    last ~3 ms against the bars' 0.2 ms bending period, so they move as rigid
    bodies: a stops, b leaves at 1 m/s (equal masses, conservative impact).
    Velocities from the positions over the last 1 ms (after the impact)."""
    z = collision()
    ts = sorted(z)
    t1, t2 = ts[-101], ts[-1]
    va = (z[t2]["a"] - z[t1]["a"]) / (t2 - t1)
    vb = (z[t2]["b"] - z[t1]["b"]) / (t2 - t1)
    assert abs(va) < 1e-3 and abs(vb + 1.0) < 1e-3, (va, vb)
    assert min(v["a"] - v["b"] for v in z.values()) > 0.01     # never within the sections (10 mm)


def test_colliding_bars_keep_their_momentum():
    """No external force: the mean height of the two equal bars' centres
    moves at v0 / 2 throughout (action = reaction), to round-off."""
    z = collision()
    dev = max(abs((v["a"] + v["b"]) / 2 - (0.0065 - 0.5 * t)) for t, v in z.items())
    assert dev < 1e-12, dev


SLIDE = """[scene]
analysis = "dynamic"

[material.steel]
law = "resultant"
E = 2.1e11
nu = 0.3
rho = 7800.0

[section.rail]
shape = "rectangle"
b = 0.04
h = 0.04

[section.bar]
shape = "rectangle"
b = 0.01
h = 0.01

[[beam]]
name = "rail"
element = "gef"
material = "steel"
section = "rail"
start = [-0.25, 0.0, 0.0]
end = [0.35, 0.0, 0.0]
up = [0.0, 0.0, 1.0]
elements = 12

[[beam]]
name = "bar"
element = "gef"
material = "steel"
section = "bar"
start = [-0.05, 0.0, 0.02501001]
end = [0.05, 0.0, 0.02501001]
up = [0.0, 0.0, 1.0]
elements = 4

[[constraint]]
type = "clamp"
a = "rail:start"

[[constraint]]
type = "clamp"
a = "rail:end"

[[load]]
type = "gravity"
value = [0.0, 0.0, -9.81]

[[load]]
type = "force"
at = "bar:end"
value = [1.0, 0.0, 0.0]
amplitude = {type = "ramp", t0 = 0.05, t1 = 0.0501}

[[beam_contact]]
beams = ["rail", "bar"]
distance = 1e-5
static_friction = 0.4
kinetic_friction = 0.3
slip = 1e-7

[dynamic]
t_end = 0.1
dt = 1e-4
rho_inf = 0.0

[[sensor]]
name = "bar"
at = "bar:0.05"
"""


def _slide(force, ramp_end, friction="static_friction = 0.4\nkinetic_friction = 0.3"):
    """A steel bar (0.1 m, 10 x 10 mm, m = 0.078 kg) lying on a clamped-clamped
    40 x 40 mm rail, along it, settled under gravity for 0.05 s, then pushed
    along it at its end by `force` (N) ramped in until `ramp_end`."""
    t = SLIDE.replace("value = [1.0, 0.0, 0.0]", f"value = [{force}, 0.0, 0.0]").replace("t1 = 0.0501",
                                                                                       f"t1 = {ramp_end}")
    t = t.replace("static_friction = 0.4\nkinetic_friction = 0.3", friction)
    p, out = _scene(t, "slide")
    s, _ = run_scene(p, out=out)
    return s, out


def test_bar_slides_along_a_rail_with_the_kinetic_coefficient():
    """F = 1 N > mu_s m g = 0.306 N, applied at t0 = 0.05 s: the bar's
    kinetic energy follows (t - t0)^2 (F - mu_k m g)^2 / (2m) (mu_k = 0.3)."""
    s, out = _slide(1.0, 0.0501)
    m, g, F, mu_k = 7800 * 1e-4 * 0.1, 9.81, 1.0, 0.3
    with open(out / "energy.csv", newline="") as fh:
        T = {float(r["time"]): float(r["kinetic"]) for r in csv.DictReader(fh)}
    t = max(T)
    ref = (t - 0.05) ** 2 * (F - mu_k * m * g) ** 2 / (2 * m)
    assert abs(T[t] / ref - 1) < 0.01, (T[t], ref)
    assert s["contact"]["max_penetration"] == 0


def test_bar_on_a_rail_sticks_between_the_coefficients():
    """F = 0.27 N, between mu_k m g = 0.230 N and mu_s m g = 0.306 N (ramped
    over 10 ms): it holds within a slip tolerance or so (1e-7 m); with
    mu = 0.3 alone it slides (tenths of a millimetre)."""
    s, _ = _slide(0.27, 0.06)
    assert abs(s["sensors"]["bar"]["displacement"][0]) < 3e-7, s["sensors"]["bar"]
    s, _ = _slide(0.27, 0.06, friction="friction = 0.3")
    assert s["sensors"]["bar"]["displacement"][0] > 1e-4, s["sensors"]["bar"]


def _tip_gaps(out):
    """{time: right tip's x - left tip's x} (sensors.csv; centrelines)."""
    g = {}
    with open(out / "sensors.csv", newline="") as fh:
        for r in csv.DictReader(fh):
            g.setdefault(float(r["time"]), {})[r["sensor"]] = float(r["x"])
    return {t: v["right_tip"] - v["left_tip"] for t, v in g.items()}


def test_gripper_closed_on_nothing_fingers_touch_and_stay_apart():
    """models/gripper_closed_empty.toml (issue 35 point 6): the tendons alone
    would bend each fingertip 32 mm (T e L^2 / 2EI) across the 25 mm between
    the fingers; with beam contact the tips' centrelines stay more than the
    two half-thicknesses (10 mm) apart at every output step and press on each
    other at the end (equal and opposite); the same scene without
    [[beam_contact]] runs the tips through each other."""
    text = (ROOT / "models" / "gripper_closed_empty.toml").read_text()
    p, out = _scene(text, "grip")
    s, _ = run_scene(p, out=out)
    gaps = _tip_gaps(out)
    assert min(gaps.values()) > 0.01, min(gaps.values())
    assert gaps[max(gaps)] < 0.0105, gaps[max(gaps)]               # closed: within half a millimetre
    c = s["contact"]
    left, right = c["beam_sets"][0]["beams"]["left"], c["beam_sets"][0]["beams"]["right"]
    assert right[0] > 0.05 and all(abs(left[i] + right[i]) <= 1e-12 * right[0] for i in range(3)), c
    free = text.replace('[[beam_contact]]\nbeams = ["left", "right"]\ndistance = 3e-4\nfriction = 0.8\nslip = 1e-5\n', "")
    assert free != text
    p, out = _scene(free, "grip_free")
    run_scene(p, out=out)
    assert _tip_gaps(out)[max(gaps)] < 0.0, "without contact the fingertips cross"


@pytest.mark.slow
def test_overhand_knot_tightens_without_passing_through_itself():
    """models/knot.toml (issue 35 point 4): an overhand knot in a 4 mm rubber
    rope, its ends pulled 0.22 m apart each over 2 s.  At every output step
    the rope's parts more than 12 mm apart along it stay at least the two
    radii (4 mm) apart less 0.5 mm (the stated bound: the sag of the nodal
    chords, ~h^2/8R for 6 mm elements bent to R ~ 10 mm, and the barrier
    keeping a gap), from the nodal chords of sections.csv (an independent
    search); the knot closes to a finite size (its extent across the pull,
    y, from 101 mm to less than half) with pairs in contact, and the pull
    (reactions.csv) grows as it tightens."""
    from test_beam_contact import _min_far_distance
    out = out_dir()
    s, _ = run_scene(ROOT / "models" / "knot.toml", out=out)
    far = _min_far_distance(out / "sections.csv", 0.012)
    assert len(far) > 30 and min(far.values()) > 0.004 - 0.0005, min(far.values())
    ext = {}
    with open(out / "sections.csv", newline="") as fh:
        for r in csv.DictReader(fh):
            if r["source"] == "nodal":
                ext.setdefault(int(r["step"]), []).append(float(r["y"]))
    first, last = ext[min(ext)], ext[max(ext)]
    assert max(first) - min(first) > 0.1 and 0.01 < max(last) - min(last) < 0.05, (first, last)
    c = s["contact"]
    assert c["beam_sets"][0]["active_pairs"] > 10 and c["max_penetration"] == 0, c
    with open(out / "reactions.csv", newline="") as fh:
        pull = [(float(r["time"]), float(r["Fx"])) for r in csv.DictReader(fh) if r["at"] == "rope:end"]
    mid = dict(pull)[min(t for t, _ in pull if t >= 1.0)]
    assert pull[-1][1] > 0.1 and pull[-1][1] > 2 * mid, pull
    from report.plot import figures                          # the pull against the end's displacement
    assert "pull.png" in figures(out)


def test_pull_plot_draws_the_prescribed_motions_reaction_against_displacement():
    """./build.sh plot's pull.png (report/plot.py fig_pull, drawn for the
    knot's pull): on models/contact_capstan.toml, whose rope end is drawn
    2 mm by a prescribed_motion, the curve is the reaction along the motion
    against its length, read back from reactions.csv here."""
    from report.plot import figures
    out = out_dir()
    run_scene(ROOT / "models" / "contact_capstan.toml", out=out)
    fig = figures(out)["pull.png"]
    line = fig.axes[0].get_lines()[0]
    with open(out / "reactions.csv", newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["type"] == "prescribed_motion"]
    x0 = float(rows[0]["x"])
    ref = [(1e3 * abs(float(r["x"]) - x0), float(r["Fx"])) for r in rows]   # the motion is along +x
    assert len(line.get_xdata()) == len(ref)
    assert all(abs(a - b) < 1e-9 and abs(c - d) < 1e-9 * max(1.0, abs(d))
               for a, c, (b, d) in zip(line.get_xdata(), line.get_ydata(), ref)), (list(line.get_ydata()), ref)
    assert max(line.get_xdata()) > 1.9                          # the 2 mm drawn
