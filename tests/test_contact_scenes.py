"""Contact in scenes (the [[contact]] tables, gen/scene/contact.py; the runtime's
contact interaction) against closed forms: a rod resting on the ground carries
its whole weight on it; a cantilever under its own weight propped at its tip by
a rigid ball puts 3 q L / 8 on the ball, and with the ball lowered by g the
closed form with the gap, 3 q L / 8 - 3 E I g / L^3; bad input is refused with
one line naming the key."""
import math
import tempfile
from pathlib import Path

from util import BUILD, ROOT, ensure_dir, run_cli, run_scene


def out_dir():
    return Path(tempfile.mkdtemp(prefix="bk-contact-", dir=ensure_dir(BUILD / "runs")))


def run_scene_expect_error(path):
    """The one-line error of a scene the scene compiler refuses (exit 1)."""
    r = run_cli(["run", str(path), "--quiet", "--out", str(out_dir())])
    assert r.returncode == 1, (r.returncode, r.stderr[-2000:])
    lines = [ln for ln in r.stderr.splitlines() if ln.startswith("error:")]
    assert len(lines) == 1, r.stderr
    return lines[0]


def _contact(summary):
    c = summary["contact"]
    assert c["max_penetration"] == 0 and c["min_distance"] > 0, c
    return c


def test_rod_on_the_ground_carries_its_weight():
    """The ground's force on the rod is its weight to 1e-6 (summary.json and
    contact_totals.csv at the last step, where the normal force is the same:
    the ground is flat), and the totals are the sums of contacts.csv's rows."""
    import csv
    out = out_dir()
    s, _ = run_scene(ROOT / "models" / "contact_rod_ground.toml", out=out)
    c = _contact(s)
    weight = 7850.0 * math.pi * 0.005 ** 2 * 1.0 * 9.81
    fz = c["sets"][0]["force"][2]
    assert abs(fz - weight) <= 1e-6 * weight, (fz, weight)
    assert c["min_distance"] < 0.001                         # within the barrier's reach
    with open(out / "contact_totals.csv", newline="") as fh:
        last = list(csv.DictReader(fh))[-1]
    with open(out / "contacts.csv", newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["step"] == last["step"]]
    for key in ("fz", "normal_force"):
        assert abs(float(last[key]) - weight) <= 1e-6 * weight, (key, last)
        assert abs(float(last[key]) - sum(float(r[key]) for r in rows)) <= 1e-12 * weight
    assert int(last["active_points"]) == len(rows) and abs(float(last["min_distance"]) - c["min_distance"]) < 1e-15


def _propped(gap):
    text = (ROOT / "models" / "contact_propped_cantilever.toml").read_text()
    if gap:
        text = text.replace("center = [1.0, 0.0, -0.015001]", f"center = [1.0, 0.0, {-0.015001 - gap!r}]")
    d = out_dir()
    p = d / "propped.toml"
    p.write_text(text)
    return run_scene(p)[0]


def test_propped_cantilever_reaction_is_three_eighths_of_the_load():
    q, L = 2700.0 * 1e-4 * 9.81, 1.0
    fz = _contact(_propped(0.0))["sets"][0]["force"][2]
    assert abs(fz / (3 * q * L / 8) - 1) < 5e-3, fz


def test_propped_cantilever_by_arc_length_continuation():
    """The same propped cantilever followed by arc-length continuation (the
    predictor kept from crossing the ball by the contact's step limit): 3qL/8
    within 0.5 % at load factor 1."""
    text = (ROOT / "models" / "contact_propped_cantilever.toml").read_text()
    assert "load_steps = 4\n" in text
    p = out_dir() / "propped_arc.toml"
    p.write_text(text.replace("load_steps = 4\n", 'method = "arc_length"\n'))
    s = run_scene(p)[0]
    q, L = 2700.0 * 1e-4 * 9.81, 1.0
    assert s["converged"] and abs(s["load_factor"] - 1.0) < 1e-9, s["load_factor"]
    fz = _contact(s)["sets"][0]["force"][2]
    assert abs(fz / (3 * q * L / 8) - 1) < 5e-3, fz


def test_propped_cantilever_with_a_gap():
    q, L, EI, g = 2700.0 * 1e-4 * 9.81, 1.0, 7.0e10 * 0.01 ** 4 / 12, 0.002
    ref = 3 * q * L / 8 - 3 * EI * g / L ** 3
    fz = _contact(_propped(g))["sets"][0]["force"][2]
    assert abs(fz / ref - 1) < 5e-3, (fz, ref)


def _bad(extra, replace=None):
    text = (ROOT / "models" / "contact_rod_ground.toml").read_text()
    if replace:
        text = text.replace(*replace)
    p = out_dir() / "bad.toml"
    p.write_text(text + extra)
    return run_scene_expect_error(p)


def test_bad_contact_input_is_one_clear_line():
    e = _bad("", replace=("distance = 0.001", "distance = 0.001\nfriction = 0.3\nstatic_friction = 0.3"))
    assert "contact[0].static_friction: expected either `friction`" in e
    e = _bad("", replace=("distance = 0.001", "distance = 0.001\nstatic_friction = 0.3\nkinetic_friction = 0.4"))
    assert "contact[0].kinetic_friction: expected at most static_friction = 0.3" in e
    e = _bad("", replace=("distance = 0.001", "distance = 0.001\nfriction = -0.1"))
    assert "contact[0].friction" in e and ">= 0" in e
    e = _bad("", replace=('shape = "half_space"', 'shape = "torus"'))
    assert "contact[0].shape" in e and "half_space" in e
    e = _bad("", replace=("distance = 0.001", "distance = 0.0"))
    assert "contact[0].distance" in e and "positive" in e
    e = _bad("", replace=("point = [0.0, 0.0, 0.0]", "point = [0.0, 0.0, 0.002]"))
    assert "beam 'rod' element 0 starts" in e and "into the half_space" in e


def test_dropped_rod_never_passes_through_and_gains_no_energy():
    """The rod dropped from 5 mm onto the ground (dynamics, 0.1 s): no sample
    point ever at a distance <= 0 (contacts.csv), the total energy of
    energy.csv (kinetic, strain, gravity; the barrier's own energy is not in
    it) never above its start by 1 % of the drop's m g h, for dt from 1e-4 to
    1e-2 (at 1e-2 with rho_inf = 0: with the default 0.8 the barrier, stiffer
    than such a step resolves, gains energy; docs/explanation/contact.md says so)."""
    import csv
    m_g_h = 7850.0 * math.pi * 0.005 ** 2 * 9.81 * 0.005
    text = (ROOT / "models" / "contact_rod_ground.toml").read_text()
    text = text.replace('analysis = "static"', 'analysis = "dynamic"').replace("0.0055]", "0.0105]")
    for dt, rho in ((1e-2, 0.0), (1e-3, 0.8), (1e-4, 0.8)):
        p = out_dir() / "drop.toml"
        p.write_text(text.replace("[static]", f"[dynamic]\nt_end = 0.1\ndt = {dt!r}\nrho_inf = {rho!r}\n\n[static]"))
        out = out_dir()
        s, _ = run_scene(p, out=out)
        assert s["converged"] and _contact(s)
        with open(out / "contacts.csv", newline="") as fh:
            dist = [float(r["distance"]) for r in csv.DictReader(fh)]
        assert dist and min(dist) > 0.0, dt                       # it touched, and never went through
        with open(out / "energy.csv", newline="") as fh:
            total = [float(r["total"]) for r in csv.DictReader(fh)]
        assert max(total) <= total[0] + 0.01 * m_g_h, (dt, max(total), total[0])
        assert not [w for w in s["warnings"] if "energy grew" in w], s["warnings"]
    # dt = 1e-2 with the default rho_inf = 0.8: the bounce gains energy, and the run says so
    p = out_dir() / "drop.toml"
    p.write_text(text.replace("[static]", "[dynamic]\nt_end = 0.1\ndt = 0.01\n\n[static]"))
    s, _ = run_scene(p)
    assert [w for w in s["warnings"] if "total energy grew" in w and "rho_inf = 0" in w], s["warnings"]


def _pulled_rod(force, friction="friction = 0.3", ramp=None):
    """The rod of contact_rod_ground.toml free on the ground (no constraint:
    friction holds it), friction 0.3, its start at its static equilibrium
    distance, pulled along its axis at its end by `force` for 0.1 s (at once,
    or ramped up over `ramp` seconds)."""
    import re
    text = (ROOT / "models" / "contact_rod_ground.toml").read_text()
    text = text.replace('analysis = "static"', 'analysis = "dynamic"').replace("0.0055]", "0.005981850356113462]")
    held = r'\[\[constraint\]\]\ntype = "point_on_line"\na = "rod:(start|end)"\naxis = \[0.0, 0.0, 1.0\]\n\n'
    text = re.sub(held, "", text)
    text = text.replace("distance = 0.001\n", f"distance = 0.001\n{friction}\n")
    text = text.replace("[static]", f'[[load]]\ntype = "force"\nat = "rod:end"\nvalue = [{force!r}, 0.0, 0.0]\n' +
                                     (f'amplitude = {{type = "ramp", t0 = 0.0, t1 = {ramp!r}}}\n' if ramp else "") +
                                     "\n[dynamic]\nt_end = 0.1\ndt = 0.001\n\n[static]")
    p = out_dir() / "pulled.toml"
    p.write_text(text)
    out = out_dir()
    run_scene(p, out=out)
    return out


def test_friction_sticks_below_the_limit_and_slides_with_the_closed_form_energy_above():
    """mu m g = 0.3 x 6.048 N = 1.814 N.  Pulled by 1 N the rod stays: its
    displacement stays within 3 slip tolerances (1e-7 m) and stops growing (no
    creep).  Pulled by 3 N it slides: the kinetic energy at t is
    t^2 (F - mu m g)^2 / (2 m) within 2 % (the first half step, before the
    lagged friction acts, adds about 1.5 % at dt = 1e-3)."""
    import csv
    m = 7850.0 * math.pi * 0.005 ** 2
    out = _pulled_rod(1.0)
    with open(out / "sensors.csv", newline="") as fh:
        ux = [(float(r["time"]), float(r["ux"])) for r in csv.DictReader(fh)]
    assert max(abs(u) for _, u in ux) < 3e-7, ux[-1]
    half = [u for t, u in ux if t >= 0.05]
    assert max(half) - min(half) < 1e-8, half                 # no creep
    out = _pulled_rod(3.0)
    with open(out / "energy.csv", newline="") as fh:
        last = list(csv.DictReader(fh))[-1]
    t, kinetic = float(last["time"]), float(last["kinetic"])
    ref = t * t * (3.0 - 0.3 * m * 9.81) ** 2 / (2 * m)
    assert abs(kinetic / ref - 1) < 0.02, (kinetic, ref)
    with open(out / "contacts.csv", newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["step"] == "50"]
    assert all(r["state"] == "slip" for r in rows)
    fx = sum(float(r["fx"]) for r in rows)
    assert abs(-fx / (0.3 * m * 9.81) - 1) < 1e-3, fx          # Coulomb: mu N against the motion


def test_static_friction_holds_where_kinetic_friction_would_slide():
    """Static 0.4, kinetic 0.3: mu_k m g = 1.814 N < 2 N < mu_s m g = 2.419 N.
    Pulled by 2 N (ramped over 10 ms) the rod stays: 2.3e-6 m in 0.1 s
    (the points near the pulled end at their limit creep by about a quarter
    of the slip tolerance a step: a known limit, docs/explanation/contact.md), where with one
    coefficient 0.3 it slides 9.8 mm; pulled by 3 N at once it slides with the
    kinetic coefficient: kinetic energy t^2 (F - mu_k m g)^2 / (2 m) within
    2 %."""
    import csv
    m = 7850.0 * math.pi * 0.005 ** 2
    two = "static_friction = 0.4\nkinetic_friction = 0.3"
    out = _pulled_rod(2.0, two, ramp=0.01)
    with open(out / "sensors.csv", newline="") as fh:
        held = float(list(csv.DictReader(fh))[-1]["ux"])
    out = _pulled_rod(2.0, ramp=0.01)                            # one coefficient 0.3: it slides
    with open(out / "sensors.csv", newline="") as fh:
        slid = float(list(csv.DictReader(fh))[-1]["ux"])
    # sliding from 10 ms on at (2 - 1.814) N / 0.617 kg: 0.3 m/s^2 x (0.09 s)^2 / 2 = 1.2 mm at least
    assert slid > 1e-3 and abs(held) < 5e-6, (held, slid)
    out = _pulled_rod(3.0, two)
    with open(out / "energy.csv", newline="") as fh:
        last = list(csv.DictReader(fh))[-1]
    t, kinetic = float(last["time"]), float(last["kinetic"])
    ref = t * t * (3.0 - 0.3 * m * 9.81) ** 2 / (2 * m)
    assert abs(kinetic / ref - 1) < 0.02, (kinetic, ref)


INDENTATION = """
[scene]
analysis = "static"
[material.alu]
law = "resultant"
E = 7.0e10
nu = 0.3
rho = 2700.0
[section.square]
shape = "rectangle"
b = 0.01
h = 0.01
[[beam]]
name = "arm"
element = "gef"
material = "alu"
section = "square"
start = [0.0, 0.0, 0.0]
end = [1.0, 0.0, 0.0]
up = [0.0, 0.0, 1.0]
elements = 20
[[constraint]]
type = "clamp"
a = "arm:start"
[[contact]]
shape = "capsule"
a = [1.0, -0.05, 0.0151]
b = [1.0, 0.05, 0.0151]
radius = 0.01
distance = 1e-4
stiffness = 1e9
motion = [0.0, 0.0, -0.0005]
[static]
load_steps = 100
[[sensor]]
name = "tip"
at = "arm:end"
"""


def test_indentation_by_a_moving_cylinder_is_resisted_with_three_ei_over_l_cubed():
    """A rigid cylinder (a capsule across the beam) moving down by 0.5 mm onto
    a cantilever's tip, its surface starting at the barrier's reach: the force
    on the cylinder against the tip's deflection is the cantilever's stiffness
    3 E I / L^3 = 175 N/m within 1 % at every step (gef's shear flexibility
    makes it 7.6e-5 less), and its slope against the cylinder's own motion
    (the indentation) within 1 % from the first contact on: 0.5 % at the first
    step, 0.07 % at 0.3 mm (the barrier's compliance is in series: with the
    stiffness 1e7 instead of 1e9 it was 5 % at first)."""
    import collections
    import csv
    p = out_dir() / "indent.toml"
    p.write_text(INDENTATION)
    out = out_dir()
    s, _ = run_scene(p, out=out)
    assert s["converged"] and _contact(s)
    force = collections.defaultdict(float)
    with open(out / "contacts.csv", newline="") as fh:
        for r in csv.DictReader(fh):
            force[int(r["step"])] -= float(r["fz"])
    with open(out / "sensors.csv", newline="") as fh:
        rows = {int(r["step"]): (float(r["time"]), -float(r["uz"])) for r in csv.DictReader(fh)}
    k = 3 * 7.0e10 * (0.01 ** 4 / 12) / 1.0 ** 3
    pts = [(rows[st][0] * 0.0005, rows[st][1], force[st]) for st in sorted(rows) if force[st] > 0]
    assert len(pts) >= 5
    for _, tip, f in pts:
        assert abs(f / tip / k - 1) < 1e-2, (f, tip)
    for (i1, _, f1), (i2, _, f2) in zip(pts, pts[1:]):
        assert abs((f2 - f1) / (i2 - i1) / k - 1) < 1e-2, (i1, (f2 - f1) / (i2 - i1) / k)


def test_capstan_reaction_is_ten_e_to_the_mu_theta():
    """models/contact_capstan.toml: a steel wire (r = 0.25 mm) half round a fixed
    cylinder (theta = pi, mu = 0.3), its lead pulled by 10 N, its tail drawn
    2 mm so that it slides.  The capstan's 10 e^(mu theta) = 25.663 N within
    1 %; and the closed form of this rope: its friction acts on its surface,
    on the drum (radius R = 50 mm), its tension at its centreline (radius Rc
    = 50.33 mm; docs/explanation/contact.md, Rolling): the moments about the
    drum's axis of a piece of the wrap, dT Rc = mu (p R) R dtheta with p R = T,
    give 10 e^(mu pi R / Rc) = 25.506 N, within 1 % (measured 25.659 N: -0.02 %
    and +0.6 %, the wire's bending stiffness, sqrt(EI/T) = 8 mm)."""
    s, _ = run_scene(ROOT / "models" / "contact_capstan.toml")
    assert s["converged"] and _contact(s)
    r = next(x for x in s["reactions"] if x["type"] == "prescribed_motion")
    assert abs(r["force"][0] / (10.0 * math.exp(0.3 * math.pi)) - 1) < 1e-2, r["force"]
    ref = 10.0 * math.exp(0.3 * math.pi * 0.05 / 0.05033)
    assert abs(r["force"][0] / ref - 1) < 1e-2, (r["force"], ref)


def _capstan_held(hold):
    """models/contact_capstan.toml made a nylon rope of 0.25 mm radius (its
    bending stiffness negligible; a 1 mm rope's, sqrt(EI/T) = 9-14 mm at the wrap's
    ends, adds enough friction there to hold 10/3.8) with the tail held by a
    dead force `hold` along it instead of the prescribed motion; the lead is
    pulled by 10 N, both ramped together over the first fifth of the load."""
    text = (ROOT / "models" / "contact_capstan.toml").read_text()
    drawn = '[[constraint]]\ntype = "prescribed_motion"\na = "tail:end"\nmotion = [0.002, 0.0, 0.0]\n'
    lead = '[[load]]\ntype = "force"\nat = "lead:start"'
    assert drawn in text and lead in text and "radius = 0.00025\n" in text and "0.05033" in text
    text = text.replace(drawn, "").replace("E = 2.0e11\n", "E = 1.0e9\n").replace("rho = 7850.0\n", "rho = 1150.0\n")
    text = text.replace(lead, f'[[load]]\ntype = "force"\nat = "tail:end"\nvalue = [{hold!r}, 0.0, 0.0]\n'
                              f'amplitude = "pull"\n\n' + lead)
    p = out_dir() / "capstan_held.toml"
    p.write_text(text)
    return p


def test_capstan_holds_above_ten_e_to_the_minus_mu_theta_and_slides_below():
    """The sticking side of the capstan: the lead pulled by 10 N, the tail
    held by H.  10 e^(-mu pi) = 3.897 N: held by 4.0 N (ratio 2.50, 2.6 % below
    e^(mu pi) = 2.566) the rope is in equilibrium and, once the loads stop
    growing, does not move (the lead's end within 1e-6 m over 80 % of the
    load steps); held by 3.8 N (ratio 2.63, 2.5 % above) there is no
    equilibrium: the rope slides and the static solve fails (exit 2)."""
    import csv
    out = out_dir()
    s, _ = run_scene(_capstan_held(4.0), out=out)
    assert s["converged"] and _contact(s)
    with open(out / "sensors.csv", newline="") as fh:
        ux = [(float(r["time"]), float(r["ux"])) for r in csv.DictReader(fh)]
    after = [u for t, u in ux if t >= 0.2 + 1e-9]
    assert len(after) > 10 and max(after) - min(after) < 1e-6, (min(after), max(after))
    r = run_cli(["run", str(_capstan_held(3.8)), "--quiet", "--out", str(out_dir())])
    assert r.returncode == 2 and "static solve failed" in r.stderr, (r.returncode, r.stderr[-500:])


def test_reactions_contact_forces_and_loads_balance():
    """The propped cantilever at the last load step: the clamp's reaction, the
    ball's contact forces (contacts.csv, each at its point) and the beam's weight
    (rho A g over the length, its moment about the clamp w L^2 / 2) sum to zero,
    force and moment about the clamp, to round-off of the converged state."""
    import csv
    out = out_dir()
    s, _ = run_scene(ROOT / "models" / "contact_propped_cantilever.toml", out=out)
    w = 2700.0 * 0.01 * 0.01 * 9.81                       # N/m, the scene's rho A g
    (rc,) = s["reactions"]
    rows = list(csv.DictReader(open(out / "contacts.csv", newline="")))
    last = [r for r in rows if r["step"] == rows[-1]["step"]]
    fc = [sum(float(r[k]) for r in last) for k in ("fx", "fy", "fz")]
    mc = [0.0, 0.0, 0.0]
    for r in last:
        x = [float(r[k]) for k in ("x", "y", "z")]
        f = [float(r[k]) for k in ("fx", "fy", "fz")]
        mc = [mc[0] + x[1] * f[2] - x[2] * f[1], mc[1] + x[2] * f[0] - x[0] * f[2], mc[2] + x[0] * f[1] - x[1] * f[0]]
    for k in range(3):
        assert abs(fc[k] - s["contact"]["sets"][0]["force"][k]) < 1e-12 * w
    force = [rc["force"][k] + fc[k] + (-w if k == 2 else 0.0) for k in range(3)]
    # the weight's moment about the clamp from the straight beam: the deflection shortens the
    # lever arms by a fraction of order (deflection / L)^2 (measured 1.2e-7)
    moment = [rc["moment"][k] + mc[k] + (w / 2 if k == 1 else 0.0) for k in range(3)]
    assert max(abs(v) for v in force) < 1e-8 * w, force
    assert max(abs(v) for v in moment) < 1e-6 * w / 2, moment
    assert fc[2] > 0.3 * w                                # the ball carries a share (3/8 of the load)
