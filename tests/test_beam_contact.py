"""Beam-to-beam contact (issue 35; [[beam_contact]], gen/scene/beam_contact.py;
runtime/assembly/beam_contact*.c).

The interaction on in-memory spring chains (tests/beam_contact_check.c,
AddressSanitizer + UBSan): its forces and Jacobian against central
differences of its residual, action = reaction, the broad phase against a
comparison of every pair of boxes, the Newton matrix's pattern growing when
chains that started apart come near.  Scenes against closed forms: two
crossed cantilevers (Euler-Bernoulli superposition with the crossing a rigid
link), two stacked strips (the contact carries the whole load), a roll-up on
itself, friction between the crossed beams (sliding: Coulomb's force and the
closed-form deflection; sticking below the limit); bad input refused with one
line."""
import csv
import json
import math
import subprocess
import tempfile
from functools import lru_cache
from pathlib import Path

from util import BUILD, ROOT, build_runtime_program, ensure_dir, run_cli, run_memcheck, run_scene


@lru_cache(maxsize=None)
def check():
    exe = build_runtime_program(["beam_contact_check.c", "spring_element.c"], "beam_contact_check", "sanitize")
    r = subprocess.run([str(exe)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0 and "runtime error" not in r.stderr, r.stderr[-3000:]
    out = {}
    for line in r.stdout.splitlines():
        d = dict(kv.split("=", 1) for kv in line.split())
        out[d.pop("case")] = d
    return out


def test_forces_and_jacobian_match_differences_and_balance():
    d = check()["jacobian"]
    assert int(d["active"]) > 20 and 0 < float(d["min_distance"]) < float(d["shat"]), d   # the barrier acts
    assert float(d["err"]) < 1e-6, d                                   # Jacobian against central differences
    assert float(d["force_sum"]) < 1e-12 * float(d["force_max"]), d    # action = reaction


def test_broad_phase_finds_exactly_the_overlapping_boxes():
    d = check()["broad"]
    assert int(d["brute"]) > 500 and d["pairs"] == d["brute"], d
    assert d["missing"] == "0" and d["extra"] == "0", d


def test_pattern_grows_when_chains_come_near():
    d = check()["growth"]
    assert d["couple0"] == "0" and int(d["couple1"]) > 0, d
    assert int(d["gen1"]) == int(d["gen0"]) + 1 and int(d["nnz1"]) > int(d["nnz0"]), d
    assert int(d["active"]) > 0, d


def out_dir():
    return Path(tempfile.mkdtemp(prefix="bk-bcontact-", dir=ensure_dir(BUILD / "runs")))


def _beam_contact(summary):
    c = summary["contact"]
    assert c["max_penetration"] == 0 and c["min_distance"] > 0, c
    return c


@lru_cache(maxsize=None)
def crossed():
    out = out_dir()
    s, _ = run_scene(ROOT / "models" / "contact_crossed_beams.toml", out=out)
    return s, out


def test_crossed_beams_against_the_closed_form():
    """P at the upper's tip (L = 1 m), the crossing a = 0.91 m from its clamp
    and b = 0.915 m from the lower's: the lower carries R = P a^2 (3L - a) / 6
    / ((a^3 + b^3) / 3), the tip moves w = (P L^3 / 3 - R a^2 (3L - a) / 6) / EI
    (small deflection, Euler-Bernoulli; gef's shear is 1e-4 of it)."""
    s, _ = crossed()
    c = _beam_contact(s)
    P, L, a, b, EI = 2.0, 1.0, 0.91, 0.915, 7.0e10 * 0.01 ** 4 / 12
    R = P * a * a * (3 * L - a) / 6 / ((a ** 3 + b ** 3) / 3)
    w = (P * L ** 3 / 3 - R * a * a * (3 * L - a) / 6) / EI
    k_ref, k = P / w, P / -s["sensors"]["tip"]["displacement"][2]
    assert abs(k / k_ref - 1) < 0.01, (k, k_ref)
    up, low = c["beam_sets"][0]["beams"]["upper"], c["beam_sets"][0]["beams"]["lower"]
    assert abs(low[2] / -R - 1) < 0.01, (low, R)
    assert all(abs(up[i] + low[i]) <= 1e-12 * abs(up[2]) for i in range(3)), (up, low)   # action = reaction
    assert c["min_distance"] < 1e-5                                   # within the barrier's reach


def test_crossed_beams_contact_rows_name_both_beams():
    """contacts.csv's beam-to-beam rows: primitive -1, the first element the
    upper's (elements 0-19), the second beam and element the lower's; no
    friction; the forces on the upper sum to the summary's."""
    s, out = crossed()
    with open(out / "contacts.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert list(rows[0])[:16] == ["step", "time", "set", "primitive", "element", "point", "x", "y", "z", "distance",
                                  "normal_force", "tangential_force", "state", "fx", "fy", "fz"]   # part 1's order
    last = [r for r in rows if int(r["step"]) == s["steps"]]
    assert last and all(r["primitive"] == "-1" and int(r["element"]) < 20 and r["beam_b"] == "lower" and
                        int(r["element_b"]) >= 20 and r["state"] == "none" for r in last), last
    assert all(float(r["tangential_force"]) == 0 for r in last)
    bs = s["contact"]["beam_sets"]
    assert abs(sum(float(r["normal_force"]) for r in last) / bs[0]["normal_force"] - 1) < 1e-9
    assert all(float(r["distance"]) > 0 for r in rows)
    assert abs(sum(float(r["fz"]) for r in last) - bs[0]["beams"]["upper"][2]) < 1e-9


BALL = """
[[contact]]
shape = "sphere"
center = [0.91, 0.085, -0.075]
radius = 0.05
"""


def test_rigid_and_beam_contact_share_the_summary_entry():
    """summary.json "contact" holds both interactions: min_distance the
    smaller of the two, max_penetration the larger, the rigid sets under
    "sets", the beam pairs under "beam_sets".  The crossed beams (sections
    < 1e-5 apart) with a ball 20 mm below the lower's tip (out of the barrier's
    reach: the same solution): the beams' distance; the upper beam lifted
    0.2 m and unloaded (no beam pair near: beam_min_distance null): the
    ball's 20 mm; the second under valgrind."""
    text = (ROOT / "models" / "contact_crossed_beams.toml").read_text() + BALL
    d = out_dir()
    (d / "ball.toml").write_text(text)
    s, _ = run_scene(d / "ball.toml", out=d / "out")
    c, ref = s["contact"], crossed()[0]["contact"]
    assert c["sets"][0]["active_points"] == 0 and c["max_penetration"] == 0, c
    assert c["min_distance"] == c["beam_min_distance"] < 1e-5, c
    assert abs(c["beam_sets"][0]["normal_force"] / ref["beam_sets"][0]["normal_force"] - 1) < 1e-12, (c, ref)
    far = text.replace("0.01001]", "0.21001]").replace("value = [0.0, 0.0, -2.0]", "value = [0.0, 0.0, 0.0]")
    (d / "far.toml").write_text(far)
    s, _ = run_scene(d / "far.toml", out=d / "far")
    c = s["contact"]
    assert c["beam_min_distance"] is None and c["beam_sets"][0]["active_pairs"] == 0, c
    assert abs(c["min_distance"] - 0.02) < 1e-4 and c["max_penetration"] == 0, c
    r, vg = run_memcheck(d / "far.toml")                  # the merge under valgrind (exit 99 on an error)
    assert r.returncode == 0, r.stderr[-3000:]
    v = json.loads((vg / "summary.json").read_text())["contact"]
    assert abs(v.pop("min_distance") - c.pop("min_distance")) < 1e-12 and v == c, (v, c)


def test_stacked_strips_carry_the_load_on_the_contact():
    s, _ = run_scene(ROOT / "models" / "contact_stacked_strips.toml", out=out_dir())
    c = _beam_contact(s)
    up, low = c["beam_sets"][0]["beams"]["upper"], c["beam_sets"][0]["beams"]["lower"]
    assert abs(up[2] / 20.0 - 1) < 1e-9, up                          # the distributed load: 20 N/m over 1 m
    assert all(abs(up[i] + low[i]) <= 1e-12 * 20.0 for i in range(3)), (up, low)
    assert c["beam_sets"][0]["active_pairs"] > 10


def test_crossed_beams_under_valgrind():
    """valgrind memcheck on the solver (exit 99 on an error or a leak)."""
    r, out = run_memcheck("contact_crossed_beams")
    assert r.returncode == 0, r.stderr[-3000:]
    assert (out / "summary.json").exists()


def _error(text):
    d = out_dir()
    p = d / "bad.toml"
    p.write_text(text)
    r = run_cli(["run", str(p), "--quiet", "--out", str(d / "out")])
    assert r.returncode == 1, (r.returncode, r.stderr[-2000:])
    lines = [ln for ln in r.stderr.splitlines() if ln.startswith("error:")]
    assert len(lines) == 1, r.stderr
    assert not (d / "out" / "summary.json").exists()
    return lines[0]




def test_bad_beam_contact_input_is_refused_with_one_line():
    base = (ROOT / "models" / "contact_crossed_beams.toml").read_text()
    cases = [
        (base.replace('distance = 1e-5', 'distance = 1e-5\nstatic_friction = 0.3\nkinetic_friction = 0.4'),
         "beam_contact[0].kinetic_friction"),
        (base.replace('distance = 1e-5', 'distance = 1e-5\nfriction = 0.3\nstatic_friction = 0.4'),
         "beam_contact[0].static_friction"),
        (base.replace('distance = 1e-5', 'distance = 1e-5\nfriction = -0.3'), "beam_contact[0].friction"),
        (base.replace('stability = false\n', ''), "stability = false"),
        (base.replace('beams = ["upper", "lower"]', 'beams = ["upper", "nosuch"]'), "no beam named 'nosuch'"),
        (base.replace('beams = ["upper", "lower"]', 'beams = ["upper"]'), "two beams or more"),
        (base.replace('start = [0.0, 0.0, 0.01001]', 'start = [0.0, 0.0, 0.009]')
             .replace('end = [1.0, 0.0, 0.01001]', 'end = [1.0, 0.0, 0.009]'), "start 0.001 m into each other"),
        (base.replace('samples = ', 'x = ').replace('distance = 1e-5', 'distance = 1e-5\nsamples = 1'),
         "beam_contact[0].samples"),
    ]
    for text, expect in cases:
        line = _error(text)
        assert expect in line and "beam_contact" in line, (expect, line)


def _min_far_distance(sections_csv, gap):
    """Per output step, the smallest distance between the chords of nodal
    points (sections.csv) more than `gap` apart along the beam, by a search over
    41 x 41 points of each pair of chords (independent of the runtime's
    closest-point formulas)."""
    import numpy as np
    with open(sections_csv, newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["source"] == "nodal"]
    out = {}
    for step in sorted({int(r["step"]) for r in rows}):
        pts = {float(r["s"]): (float(r["x"]), float(r["y"]), float(r["z"])) for r in rows if int(r["step"]) == step}
        s = sorted(pts)
        X = np.array([pts[k] for k in s])
        t = np.linspace(0.0, 1.0, 41)[:, None]
        best = math.inf
        for i in range(len(s) - 1):
            P = X[i] + t * (X[i + 1] - X[i])
            for j in range(i + 1, len(s) - 1):
                if s[j] - s[i + 1] <= gap:
                    continue
                Q = X[j] + t * (X[j + 1] - X[j])
                best = min(best, float(np.min(np.linalg.norm(P[:, None, :] - Q[None, :, :], axis=2))))
        out[step] = best
    return out


def test_self_contact_rollup_lies_on_itself_and_never_passes_through():
    """The roll-up past one turn (models/self_contact_rollup.toml): at every
    output step the beam's parts more than 5 cm apart along it stay a section
    (10 mm) apart, less the chords' sag between the nodes (1 mm); the same
    scene without contact runs its second turn through the first.  The contact
    acts between the first turn and the second."""
    out = out_dir()
    s, _ = run_scene(ROOT / "models" / "self_contact_rollup.toml", out=out)
    c = _beam_contact(s)
    assert c["beam_sets"][0]["normal_force"] > 10.0 and c["beam_sets"][0]["active_pairs"] > 0, c
    far = _min_far_distance(out / "sections.csv", 0.05)
    assert len(far) > 10 and min(far.values()) > 0.009, far
    with open(out / "contacts.csv", newline="") as fh:
        last = [r for r in csv.DictReader(fh) if int(r["step"]) == s["steps"]]
    assert any(min(int(r["element"]), int(r["element_b"])) < 10 and max(int(r["element"]),
               int(r["element_b"])) > 28 and r["beam_b"] == "arm" for r in last), last
    text = (ROOT / "models" / "self_contact_rollup.toml").read_text()
    free = out_dir() / "free.toml"
    free.write_text(text.replace("[[beam_contact]]\nbeams = [\"arm\"]\nself = true\n", ""))
    out2 = out_dir()
    run_scene(free, out=out2)
    assert min(_min_far_distance(out2 / "sections.csv", 0.05).values()) < 0.001


def test_friction_jacobian_matches_differences():
    """The lagged friction between beams (sticking and sliding pairs) with the
    barrier: the Jacobian against central differences, action = reaction."""
    d = check()["friction"]
    assert float(d["err"]) < 1e-6, d
    assert float(d["force_sum"]) < 1e-12 * float(d["force_max"]), d


def _crossed_with_friction(pull, friction="friction = 0.3"):
    """The crossed cantilevers with friction 0.3 (or the keys `friction`):
    pressed by P over the first half of the load path, then the upper's tip
    pulled sideways (along the lower, y) by `pull` over the second.  Returns
    (summary, out)."""
    text = (ROOT / "models" / "contact_crossed_beams.toml").read_text()
    text = text.replace("distance = 1e-5", "distance = 1e-5\n" + friction)
    text = text.replace('value = [0.0, 0.0, -2.0]\n', 'value = [0.0, 0.0, -2.0]\namplitude = {type = "ramp", t0 = 0.0, '
                        't1 = 0.5}\n\n[[load]]\ntype = "force"\nat = "upper:end"\nvalue = [0.0, ' + repr(pull) +
                        ', 0.0]\namplitude = {type = "ramp", t0 = 0.5, t1 = 1.0}\n')
    text = text.replace("load_steps = 4", "load_steps = 8")
    d = out_dir()
    (d / "friction.toml").write_text(text)
    s, _ = run_scene(d / "friction.toml", out=d / "out")
    return s, d / "out"


def _sensor_y(out):
    with open(out / "sensors.csv", newline="") as fh:
        return [(float(r["time"]), r["sensor"], float(r["uy"])) for r in csv.DictReader(fh)]


def _crossing_slip(out):
    """The upper's crossing point relative to the lower's along y, at the last
    state of the pressing half (load factor <= 0.5) and at the end."""
    rows = _sensor_y(out)
    def rel(t):
        u = {n: y for tt, n, y in rows if tt == t}
        return u["crossing"] - u["lower_crossing"]
    t_press = max(t for t, _, _ in rows if t <= 0.5)
    return rel(t_press), rel(1.0)


def test_crossed_beams_slide_with_coulomb_friction():
    """Pulled by 1 N (beyond the friction limit mu R = 0.342 N: a prop at the
    crossing would need 1.15 N): the upper slides along the lower, the friction
    on it is mu times the lagged normal force, and its tip moves
    (T L^3 / 3 - mu R a^2 (3L - a) / 6) / EI sideways."""
    s, out = _crossed_with_friction(1.0)
    P, L, a, b, EI, mu, T = 2.0, 1.0, 0.91, 0.915, 7.0e10 * 0.01 ** 4 / 12, 0.3, 1.0
    R = P * a * a * (3 * L - a) / 6 / ((a ** 3 + b ** 3) / 3)
    ref = (T * L ** 3 / 3 - mu * R * a * a * (3 * L - a) / 6) / EI
    tip = s["sensors"]["tip"]["displacement"][1]
    assert abs(tip / ref - 1) < 0.02, (tip, ref)
    with open(out / "contacts.csv", newline="") as fh:
        last = [r for r in csv.DictReader(fh) if int(r["step"]) == s["steps"]]
    fy = sum(float(r["fy"]) for r in last)                   # on the upper: against its slip (+y)
    assert abs(fy / (-mu * R) - 1) < 0.05, (fy, mu * R)
    assert all(r["state"] == "slip" for r in last if float(r["tangential_force"]) > 0), last   # (the rubbing rows)
    assert abs(sum(float(r["tangential_force"]) for r in last) / (mu * R) - 1) < 0.05
    before, after = _crossing_slip(out)
    assert after - before > 1e-3, (before, after)            # it slid (millimetres)
    assert _beam_contact(s)["beam_sets"][0]["active_pairs"] > 0


def test_crossed_beams_stick_below_the_friction_limit():
    """Pulled by -0.2 N, within the limit whatever the friction the pressing
    left (at most mu R = 0.342 N against the 0.23 N the prop takes): the
    crossing sticks, moving less than ten slip tolerances (1e-7 m) relative to
    the lower while the tip is pulled."""
    s, out = _crossed_with_friction(-0.2)
    before, after = _crossing_slip(out)
    assert abs(after - before) < 1e-6, (before, after)
    assert s["sensors"]["tip"]["displacement"][1] < 0


def test_crossed_beams_slide_with_the_kinetic_coefficient():
    """static_friction = 0.4, kinetic_friction = 0.3, pulled by 1 N: the upper
    slides (2 slip tolerances and more a step), so the friction is the kinetic
    mu_k R and the tip moves (T L^3 / 3 - mu_k R a^2 (3L - a) / 6) / EI (the
    closed form of the sliding test with mu = 0.3; mu_s = 0.4 would give a
    tip 6 % nearer)."""
    s, out = _crossed_with_friction(1.0, "static_friction = 0.4\nkinetic_friction = 0.3")
    P, L, a, b, EI, mu_k, T = 2.0, 1.0, 0.91, 0.915, 7.0e10 * 0.01 ** 4 / 12, 0.3, 1.0
    R = P * a * a * (3 * L - a) / 6 / ((a ** 3 + b ** 3) / 3)
    ref = (T * L ** 3 / 3 - mu_k * R * a * a * (3 * L - a) / 6) / EI
    tip = s["sensors"]["tip"]["displacement"][1]
    assert abs(tip / ref - 1) < 0.02, (tip, ref)
    with open(out / "contacts.csv", newline="") as fh:
        last = [r for r in csv.DictReader(fh) if int(r["step"]) == s["steps"]]
    fy = sum(float(r["fy"]) for r in last)
    assert abs(fy / (-mu_k * R) - 1) < 0.05, (fy, mu_k * R)


def test_crossed_beams_stick_with_the_static_coefficient_only():
    """Pulled by -0.2 N: the prop at the crossing needs 0.23 N, more than
    mu_k R = 0.117 N (mu_k = 0.1) and less than mu_s R = 0.467 N (mu_s = 0.4):
    it sticks (relative motion below ten slip tolerances) with the two
    coefficients, and slides with mu = 0.1 alone (millimetres)."""
    _, out = _crossed_with_friction(-0.2, "static_friction = 0.4\nkinetic_friction = 0.1")
    before, after = _crossing_slip(out)
    assert abs(after - before) < 1e-6, (before, after)
    _, out = _crossed_with_friction(-0.2, "friction = 0.1")
    before, after = _crossing_slip(out)
    assert abs(after - before) > 1e-4, (before, after)


def test_gripper_fingers_closed_on_nothing_touch_at_their_tips():
    """models/contact_fingers_closed.toml (issue 35 point 6, with dead loads for
    the fingers' drive): two parallel cantilevers 2 mm apart, their tips pushed
    together by F = 300 N.  Each tip closes g/2 = 1 mm (to the barrier's gap);
    the contact force is F less what the finger's tip stiffness takes,
    R = F - (g/2) / (L^3 / 3EI + L / (kappa G A)), kappa = 5/6 (gef is a
    shear-flexible beam: 126.35 N; Euler-Bernoulli alone gives 125 N).  The
    tips' sections stay apart (sensors), action = reaction."""
    s, _ = run_scene(ROOT / "models" / "contact_fingers_closed.toml", out=out_dir())
    E, nu, A, I, L, F = 7.0e10, 0.3, 1e-4, 1e-8 / 12, 0.1, 300.0
    R = F - 0.001 / (L ** 3 / (3 * E * I) + L / (5 / 6 * E / (2 * (1 + nu)) * A))
    c = _beam_contact(s)
    left, right = c["beam_sets"][0]["beams"]["left"], c["beam_sets"][0]["beams"]["right"]
    assert abs(right[1] / R - 1) < 0.005, (right, R)
    assert all(abs(left[i] + right[i]) <= 1e-12 * R for i in range(3)), (left, right)
    gap = s["sensors"]["right_tip"]["position"][1] - s["sensors"]["left_tip"]["position"][1] - 0.01
    assert 0 < gap < 1e-5, gap


def test_crossed_beams_paraview_frames_show_both_beams_forces():
    """beam_contacts_NNNNNN.vtp with every frame of results.pvd, listed in
    beam_contacts.pvd: at the last, two vertices per row of contacts.csv (the
    closest point on each beam) whose forces are equal and opposite and sum,
    on the upper's, to the summary's force on it."""
    import re
    s, out = crossed()
    frames = re.findall(r'file="(beam_contacts_\d+\.vtp)"', (out / "beam_contacts.pvd").read_text())
    assert len(frames) == len(re.findall(r"<DataSet", (out / "results.pvd").read_text())), frames
    text = (out / frames[-1]).read_text()
    n = int(re.search(r'NumberOfPoints="(\d+)"', text).group(1))
    with open(out / "contacts.csv", newline="") as fh:
        last = [r for r in csv.DictReader(fh) if int(r["step"]) == s["steps"]]
    assert n == 2 * len(last) > 0, (n, len(last))
    block = text.split('Name="force" NumberOfComponents="3" format="ascii">')[1].split("</DataArray>")[0]
    f = [[float(x) for x in line.split()] for line in block.strip().splitlines()]
    assert all(abs(sum(v[i] for v in f)) <= 1e-6 * max(abs(v[2]) for v in f) for i in range(3)), f
    up = s["contact"]["beam_sets"][0]["beams"]["upper"]
    assert abs(sum(v[2] for v in f[0::2]) / up[2] - 1) < 1e-6, (f, up)
