"""A clamped rod twisted under slight tension forms a plectoneme with
self-contact (issue 35 point 5; models/plectoneme.toml: gef rod, the end
turned by a prescribed_rotation relative to a slider pulled by a dead tension T).

Against closed forms:
- the straight rod's torque is C theta / L (C = G J, the torsional stiffness);
- it turns unstable at the critical moments of the Greenhill problem for a rod
  clamped at both ends under tension (linearized, complex lateral deflection
  w: B w'''' - i M w''' - T w'' = 0, w = w' = 0 at both ends).  With
  k1,2 = (M +- sqrt(M^2 - 4 B T)) / 2B the determinant of the four end
  conditions on {1, s, e^(i k1 s), e^(i k2 s)} vanishes where
      2 (k1 - k2) sin(k1 L/2) sin(k2 L/2) = k1 k2 L sin((k1 - k2) L/2);
  its roots above 2 sqrt(B T) (the infinitely long rod's) are found here by
  bisection, independent of the solver.  The static run of the same rod
  without contact or imperfection (stability check, 100 fixed steps) reports
  where the count of negative tangent eigenvalues changes;
- dynamics with contact: past the instability the rod writhes (the end jumps
  towards the clamp, the middle leaves the axis by many radii), the strands
  touch, and at every output step the rod's parts more than 5 cm apart along
  it stay at least 2 r - 0.5 mm apart (the polyline through the nodes and the
  integration points of sections.csv, a search independent of the runtime's
  closest points; 0.5 mm the bound for that polyline's chords against the
  curved element)."""
import csv
import math
import tempfile
from pathlib import Path

import pytest

from util import BUILD, ROOT, ensure_dir, run_scene

SCENE = ROOT / "models" / "plectoneme.toml"
E, NU, R, L = 5.0e6, 0.3, 0.004, 1.0
B = E * math.pi * R ** 4 / 4                       # bending stiffness E I
C = B / (1 + NU)                                   # G J, J = 2 I
T = 100 * B / L ** 2                               # the scene's tension
ANGLE = 40.0                                       # rad at the amplitude 1


def out_dir():
    return Path(tempfile.mkdtemp(prefix="bk-plect-", dir=ensure_dir(BUILD / "runs")))


def _greenhill(n):
    """The first n critical moments of the clamped rod under tension T."""
    def f(M):
        d = math.sqrt(M * M - 4 * B * T)
        k1, k2 = (M + d) / (2 * B), (M - d) / (2 * B)
        return 2 * (k1 - k2) * math.sin(k1 * L / 2) * math.sin(k2 * L / 2) - k1 * k2 * L * math.sin((k1 - k2) * L / 2)
    m0, roots = 2 * math.sqrt(B * T), []
    grid = [m0 * (1 + 1e-9 + 2.0 * i / 20000) for i in range(20001)]
    for a, b in zip(grid, grid[1:]):
        if f(a) * f(b) < 0:
            for _ in range(100):
                c = 0.5 * (a + b)
                a, b = (c, b) if f(a) * f(c) > 0 else (a, c)
            roots.append(0.5 * (a + b))
            if len(roots) == n:
                return roots
    raise AssertionError(roots)


def _static_scene():
    """The scene without contact and imperfection, static, 0.4 rad a step
    (the drive fixes the angle modulo 2 pi: a step must stay below pi)."""
    s = SCENE.read_text()
    s = s[:s.index("[[beam_contact]]")] + s[s.index("[dynamic]"):]
    s = s[:s.index("[dynamic]")] + "[static]\nload_steps = 100\nstep_control = \"fixed\"\n\n" + s[s.index("[[sensor]]"):]
    s = s.replace('analysis = "dynamic"', 'analysis = "static"').replace('angle_amplitude = "twist"\n', "")
    s = s.replace('amplitude = "pull"', 'amplitude = {type = "table", points = [[0.0, 1.0], [1.0, 1.0]]}')
    s = s.replace("value = [0.0, 1e-4, 0.0]", "value = [0.0, 0.0, 0.0]")
    assert "beam_contact" not in s and 'analysis = "static"' in s
    p = out_dir() / "static.toml"
    p.write_text(s)
    return p


def test_twisted_rod_turns_unstable_at_the_clamped_greenhill_moments():
    s, _ = run_scene(_static_scene(), out=out_dir() / "out")
    crit = [e["critical_load_factor"] for e in s["stability"]["events"]]
    ref = [M * L / C / ANGLE for M in _greenhill(3)]       # 0.68196, 0.76880, 0.90373
    assert len(crit) == 3, s["stability"]
    for c, r in zip(crit, ref):
        assert abs(c / r - 1) < 2e-3, (crit, ref)
    assert all(e["negative_after"] - e["negative_before"] == 2 for e in s["stability"]["events"])


def _far_distance(sections_csv, gap, n=11):
    """{step: smallest distance between points of the polyline through the
    nodal and integration points more than `gap` apart along the rod}."""
    import numpy as np
    with open(sections_csv, newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["source"] in ("nodal", "law")]
    out = {}
    for step in sorted({int(r["step"]) for r in rows}):
        pts = {float(r["s"]): (float(r["x"]), float(r["y"]), float(r["z"])) for r in rows if int(r["step"]) == step}
        s = np.array(sorted(pts))
        X = np.array([pts[k] for k in s])
        t = np.linspace(0.0, 1.0, n)[:-1, None]
        P = np.concatenate([X[i] + t * (X[i + 1] - X[i]) for i in range(len(s) - 1)] + [X[-1:]])
        a = np.concatenate([s[i] + t[:, 0] * (s[i + 1] - s[i]) for i in range(len(s) - 1)] + [s[-1:]])
        best = math.inf
        for i in range(0, len(P), 256):
            d = np.linalg.norm(P[i:i + 256, None, :] - P[None, :, :], axis=2)
            far = np.abs(a[i:i + 256, None] - a[None, :]) > gap
            best = min(best, float(np.min(np.where(far, d, np.inf))))
        out[step] = best
    return out


@pytest.mark.slow
def test_plectoneme_forms_with_self_contact_and_no_penetration():
    out = out_dir()
    s, _ = run_scene(SCENE, out=out)
    theta_c = _greenhill(1)[0] * L / C
    with open(out / "joints.csv", newline="") as fh:
        twist = {int(r["step"]): (float(r["value"]), float(r["effort"])) for r in csv.DictReader(fh)
                 if r["name"] == "twist"}
    with open(out / "sensors.csv", newline="") as fh:
        pos = {}
        for r in csv.DictReader(fh):
            pos.setdefault(int(r["step"]), {})[r["sensor"]] = (float(r["x"]), float(r["y"]), float(r["z"]))
    straight = [k for k in twist if twist[k][0] < 0.98 * theta_c]
    for k in straight:                        # straight: torque C theta / L, the middle on the axis
        th, M = twist[k]
        assert abs(M - C * th / L) <= 2e-3 * C * theta_c / L, (th, M)
        assert math.hypot(*pos[k]["middle"][1:]) < R / 4, (th, pos[k])
    last = max(pos)
    off = max(math.hypot(*p["middle"][1:]) for p in pos.values())
    assert pos[last]["end"][0] < 0.5 * L and off > 10 * R, (pos[last], off)   # writhed: end jumped in
    peak = max(M for _, M in twist.values())
    assert peak > 2 * math.sqrt(B * T) and twist[max(twist)][1] < 0.5 * peak, (peak, twist[max(twist)])
    c = s["contact"]
    assert c["max_penetration"] == 0 and c["beam_sets"][0]["active_pairs"] > 10, c
    far = _far_distance(out / "sections.csv", 0.05)
    assert len(far) > 30 and min(far.values()) > 2 * R - 0.0005, sorted(far.values())[:3]
