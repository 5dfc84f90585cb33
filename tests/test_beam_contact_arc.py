"""Beam-to-beam contact with arc-length continuation (issue 35; static.method
= "arc_length" with [[beam_contact]]; the predictor held to the contact's
step limit, runtime/analysis/arc_step.c).

The crossed cantilevers of models/contact_crossed_beams.toml with the upper
1 mm above touching: the arc-length path closes the gap and presses the upper
onto the lower; at the load factor 1 the contact force and the tip's
deflection against the closed form (Euler-Bernoulli cantilevers, small
deflection, the crossing a rigid link once the gap g is closed):
  R = (P a^2 (3L - a) / 6 - g EI) / ((a^3 + b^3) / 3),
  w = (P L^3 / 3 - R a^2 (3L - a) / 6) / EI."""
import tempfile
from pathlib import Path

from util import BUILD, ROOT, ensure_dir, run_scene


def test_arc_length_closes_the_gap_and_matches_the_closed_form():
    text = (ROOT / "models" / "contact_crossed_beams.toml").read_text()
    text = text.replace("0.01001]", "0.01101]").replace("load_steps = 4", 'load_steps = 4\nmethod = "arc_length"')
    d = Path(tempfile.mkdtemp(prefix="bk-bcarc-", dir=ensure_dir(BUILD / "runs")))
    (d / "arc.toml").write_text(text)
    s, rows = run_scene(d / "arc.toml", out=d / "out")
    P, L, a, b, EI, g = 2.0, 1.0, 0.91, 0.915, 7.0e10 * 0.01 ** 4 / 12, 0.001
    R = (P * a * a * (3 * L - a) / 6 - g * EI) / ((a ** 3 + b ** 3) / 3)
    w = (P * L ** 3 / 3 - R * a * a * (3 * L - a) / 6) / EI
    tip = -s["sensors"]["tip"]["displacement"][2]
    assert abs(tip / w - 1) < 0.01, (tip, w)
    c = s["contact"]
    low, up = c["beam_sets"][0]["beams"]["lower"], c["beam_sets"][0]["beams"]["upper"]
    assert abs(low[2] / -R - 1) < 0.01, (low, R)
    assert all(abs(up[i] + low[i]) <= 1e-12 * abs(up[2]) for i in range(3)), (up, low)
    assert c["max_penetration"] == 0 and 0 < c["min_distance"] < 1e-5, c


def test_arc_length_starting_in_contact_goes_forward_and_matches_load_control():
    """The crossed cantilevers as given (touching at the load factor 0: their
    sections 1e-5 m apart, the barrier's reach) by arc length.  The first
    predictor runs into the lower beam and is cut to 0.4 % by the contact's
    step limiter; that step is solved in load control at the uncut
    predictor's load factor (runtime/analysis/arc_step.c), and the path goes
    on forward: the load factor grows at every step to 1 (before: the arc's
    other root, the beams moving apart, the load factor to -3e7), and the end
    state is load control's (4 steps), the contact force the closed form
    R = P a^2 (3L - a) / 6 / ((a^3 + b^3) / 3) = 1.13892 N."""
    text = (ROOT / "models" / "contact_crossed_beams.toml").read_text()
    d = Path(tempfile.mkdtemp(prefix="bk-bcarc-", dir=ensure_dir(BUILD / "runs")))
    (d / "arc.toml").write_text(text.replace("load_steps = 4", 'load_steps = 4\nmethod = "arc_length"'))
    s, rows = run_scene(d / "arc.toml", out=d / "arc")
    ref, _ = run_scene(ROOT / "models" / "contact_crossed_beams.toml", out=d / "load")
    lams = sorted({float(r["time"]) for r in rows})
    steps = [float(r["time"]) for r in rows if r["sensor"] == "tip"]
    assert s["converged"] and s["load_factor"] == 1.0 and steps == lams, (s.get("error"), steps)
    assert all(b > a for a, b in zip(steps, steps[1:])) and len(steps) > 2, steps
    w, w0 = s["sensors"]["tip"]["displacement"], ref["sensors"]["tip"]["displacement"]
    assert all(abs(w[i] - w0[i]) <= 1e-9 * abs(w0[2]) for i in range(3)), (w, w0)
    P, L, a, b = 2.0, 1.0, 0.91, 0.915
    R = P * a * a * (3 * L - a) / 6 / ((a ** 3 + b ** 3) / 3)
    low = s["contact"]["beam_sets"][0]["beams"]["lower"]
    assert abs(low[2] / -R - 1) < 1e-3, (low, R)
    assert s["contact"]["max_penetration"] == 0 and s["contact"]["min_distance"] > 0
