"""Beams passing through themselves or each other with no beam contact modelled
(issue 36: the 40 N tendon finger curled past a full turn through its own body,
unflagged): runtime/output/overlap.c warns at the first output state where two
parts that were not neighbours come closer than their sections' half-heights.

References: closed forms of where the overlap begins -- the circle of a
cantilever rolled up by an end moment (its end comes within the section's
height h of its root at a roll angle 2 pi - h / R), and the deflection of a
cantilever under an end load, P a^2 (3 L - a) / (6 EI) at a, pressed onto a
beam crossing below it."""
import math

import pytest

from util import BUILD, ensure_dir, run_scene

E, R_SEC = 7.0e10, 0.005                  # Pa; the sections' half-height (m)
EI_SQ = E * (2 * R_SEC) ** 4 / 12         # the square section's (N m^2)
EI_RD = E * math.pi * R_SEC ** 4 / 4      # the round section's (N m^2)

ROLL = """[scene]
analysis = "static"
[material.alu]
law = "resultant"
E = 7.0e10
nu = 0.3
rho = 2700.0
[section.sq]
shape = "rectangle"
b = 0.01
h = 0.01
[[beam]]
name = "arm"
element = "gef"
material = "alu"
section = "sq"
start = [0.0, 0.0, 0.0]
end = [1.0, 0.0, 0.0]
up = [0.0, 0.0, 1.0]
elements = 40
[[constraint]]
type = "clamp"
a = "arm:start"
[[load]]
type = "moment"
at = "arm:end"
value = [0.0, 0.0, {M}]
[static]
load_steps = 40
"""

CROSS = """[scene]
analysis = "static"
[material.alu]
law = "resultant"
E = 7.0e10
nu = 0.3
rho = 2700.0
[section.rd]
shape = "circle"
radius = 0.005
[[beam]]
name = "below"
element = "gef"
material = "alu"
section = "rd"
start = [0.5, -0.5, 0.0]
end = [0.5, 0.5, 0.0]
up = [0.0, 0.0, 1.0]
elements = 8
[[beam]]
name = "above"
element = "gef"
material = "alu"
section = "rd"
start = [0.0, 0.0, 0.05]
end = [1.0, 0.0, 0.05]
up = [0.0, 0.0, 1.0]
elements = 16
[[constraint]]
type = "clamp"
a = "below:start"
[[constraint]]
type = "clamp"
a = "below:end"
[[constraint]]
type = "clamp"
a = "above:start"
[[load]]
type = "force"
at = "above:end"
value = [0.0, 0.0, {P}]
[static]
load_steps = 12
"""


def _run(text, name):
    d = ensure_dir(BUILD / "overlap")
    (d / f"{name}.toml").write_text(text)
    s, _ = run_scene(d / f"{name}.toml", out=d / f"{name}_out")
    return s, [w for w in s["warnings"] if "nothing keeps them apart" in w]


def _factor(w):
    return float(w.split(" apart at load factor ")[1].split(",")[0])


@pytest.mark.parametrize("elements", [40, 1000])
def test_a_rolled_up_cantilever_passing_through_itself_is_flagged(elements):
    """An end moment k 2 pi EI / L rolls a cantilever (L = 1 m, 10 x 10 mm, gef)
    into a circle of angle k lambda 2 pi at load factor lambda.  Its end comes
    within h = 10 mm of its root when 2 R sin(pi - phi / 2) < h, R = L / phi:
    phi > 2 pi - h / R, so phi (1 + h / L) > 2 pi, k lambda > 0.990 (closed form).
    k = 0.9: the gap stays 0.1 m, no warning; k = 1.1: the warning names the beam,
    points along it one turn apart, and a load factor not below the closed form's
    0.9001 and within 0.05 of it (measured 0.925: the first load step past it,
    increments of 0.025).  With 40 elements each is longer than the section;
    with 1,000 (1 mm each) the check's runs of elements hold ten, and the pairs
    of one run with the next that are neighbours along the beam are skipped
    without a comparison (output/overlap.c): the same closed form holds."""
    text = ROLL.replace("elements = 40", f"elements = {elements}")
    s, w = _run(text.format(M=0.9 * 2 * math.pi * EI_SQ), f"roll_09_{elements}")
    assert s["converged"] and not w, s["warnings"]
    s, w = _run(text.format(M=1.1 * 2 * math.pi * EI_SQ), f"roll_11_{elements}")
    assert s["converged"] and len(w) == 1, s["warnings"]
    lam_star = 1.0 / (1.0 + 2 * R_SEC / 1.0) / 1.1        # phi (1 + h / L) > 2 pi
    lam = _factor(w[0])
    assert "beam 'arm' at s = " in w[0] and "passes through itself" in w[0] and "self = true" in w[0], w
    assert lam_star <= lam <= lam_star + 0.05, (lam, lam_star)
    print(f"roll-up: flagged at load factor {lam} (closed form {lam_star:.4f}): {w[0]}")


def test_a_cantilever_pressed_through_a_crossing_beam_is_flagged():
    """A cantilever (L = 1 m, round r = 5 mm) 50 mm above a beam crossing it at
    a = 0.5 m, pressed down by an end load P: their centrelines come within
    2 r = 10 mm when P a^2 (3 L - a) / (6 EI) > 40 mm (closed form).  P for 30 mm:
    no warning; P for 60 mm: warned at the first load step past 2/3 (measured
    0.677, adaptive increments of about 1/12), naming both beams, with the gap
    it reports within 0.5 mm of the closed form's 50 mm - 60 mm lambda (measured
    9.51 mm against 9.38 mm)."""
    unit = 0.5 ** 2 * (3 * 1.0 - 0.5) / (6 * EI_RD)         # deflection at a per newton
    s, w = _run(CROSS.format(P=-0.03 / unit), "cross_30mm")
    assert s["converged"] and not w, s["warnings"]
    s, w = _run(CROSS.format(P=-0.06 / unit), "cross_60mm")
    assert s["converged"] and len(w) == 1, s["warnings"]
    assert "'above'" in w[0] and "'below'" in w[0] and "pass through each other" in w[0], w
    lam = _factor(w[0])
    assert 2.0 / 3.0 < lam <= 2.0 / 3.0 + 1.0 / 12 + 1e-9, lam
    d = float(w[0].split(" are ")[1].split(" m apart")[0])
    assert abs(d - (0.05 - 0.06 * lam)) < 5e-4, (d, lam)       # the gap the closed form gives there
    print(f"crossing: flagged at load factor {lam}: {w[0]}")


def test_the_40N_tendon_finger_curling_through_itself_is_flagged():
    """Issue 36's scene: the ancf3363 silicone finger (100 x 20 x 10 mm) under a
    step tendon tension.  At 10 N (50 ms) it bends without touching itself: no
    warning; at 40 N it curls past a full turn and the check names the finger,
    the time and [[beam_contact]] self = true (first 6 ms)."""
    s, _ = run_scene("tendon_finger_dynamic", out=ensure_dir(BUILD / "overlap") / "finger10")
    assert not [w for w in s["warnings"] if "nothing keeps them apart" in w], s["warnings"]
    s, _ = run_scene("tendon_finger_dynamic", ["load.0.tension=40", "dynamic.t_end=0.006"],
                     out=ensure_dir(BUILD / "overlap") / "finger40")
    w = [w for w in s["warnings"] if "nothing keeps them apart" in w]
    assert len(w) == 1 and "beam 'f'" in w[0] and "passes through itself" in w[0] and " at t = " in w[0], w
    print(w[0])


def test_the_check_is_off_when_an_interaction_keeps_sections_apart():
    """Regression guard (no independent reference): the check is off when an
    interaction keeps the sections apart (beam contact, interaction.h
    keeps_apart), whichever beams it covers.  The crossing of the test above
    pressed 60 mm (flagged there; beam contact needs static.stability = false,
    so both runs have it) with a third, distant beam in self contact:
    no overlap warning, and the crossing's deflection unchanged by the
    distant beam (the same tip position as without it, to 1e-12 m)."""
    unit = 0.5 ** 2 * (3 * 1.0 - 0.5) / (6 * EI_RD)
    base = CROSS.format(P=-0.06 / unit).replace("load_steps = 12\n", "load_steps = 12\nstability = false\n") + \
        '[[sensor]]\nname = "tip"\nat = "above:end"\n'
    extra = ('[[beam]]\nname = "far"\nelement = "gef"\nmaterial = "alu"\nsection = "rd"\n'
             'start = [0.0, 5.0, 0.0]\nend = [1.0, 5.0, 0.0]\nup = [0.0, 0.0, 1.0]\nelements = 8\n'
             '[[constraint]]\ntype = "clamp"\na = "far:start"\n'
             '[[beam_contact]]\nbeams = ["far"]\nself = true\n')
    s0, w0 = _run(base, "cross_60mm_sensor")
    s1, w1 = _run(base + extra, "cross_60mm_far_contact")
    assert s0["converged"] and len(w0) == 1, s0["warnings"]
    assert s1["converged"] and not w1, s1["warnings"]
    p0, p1 = s0["sensors"]["tip"]["position"], s1["sensors"]["tip"]["position"]
    assert max(abs(a - b) for a, b in zip(p0, p1)) < 1e-12, (p0, p1)
