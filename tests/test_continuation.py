"""Arc-length continuation (static.method = "arc_length", runtime/newton.c) on
benchmarks with independent references: the von Mises two-bar truss (closed
form derived below), the clamped-hinged deep circular arch (DaDeppo and
Schmidt 1975), the Euler bifurcation of the seed cantilever (closed form), and
the bad-input and budget behaviour."""
import json
import math
import tempfile
from pathlib import Path

from scipy.optimize import brentq

from test_bad_input import check_error
from util import BUILD, ROOT, ensure_dir, load_run, rel, run_cli, run_scene

# --- the two-bar truss (models/truss_snap_through.toml) -----------------------
# Half model: one pin-ended bar from (0, 0) to the apex (b, h) on the symmetry
# line, EA, half load F downwards.  A straight pin-ended bar carries only its
# axial force N = EA (L / L0 - 1) (tension positive), L = sqrt(b^2 + y^2) at
# apex height y.  Vertical equilibrium of the apex: F = -N y / L, i.e.
#     F(y) = EA y (1 / L - 1 / L0).
# dF/dy = EA (1/L - 1/L0 - y^2/L^3) = EA (b^2 / L^3 - 1 / L0) = 0 at
#     L* = (b^2 L0)^(1/3),  y* = sqrt(L*^2 - b^2),  F_max = EA y* (1/L* - 1/L0)
# and by the oddness of F(y) the mirrored minimum -F_max at -y*.
EA, B, H, F_REF = 1.0e6, 1.0, 0.1, 400.0
L0 = math.hypot(B, H)


def truss_force(y):
    return EA * y * (1.0 / math.hypot(B, y) - 1.0 / L0)


def truss_limit():
    Ls = (B * B * L0) ** (1.0 / 3.0)
    ys = math.sqrt(Ls * Ls - B * B)
    return ys, EA * ys * (1.0 / Ls - 1.0 / L0)


def test_truss_snap_through_limit_loads_and_path_match_the_closed_form():
    s, rows = run_scene("truss_snap_through")
    assert s["converged"], s["error"]
    ys, fmax = truss_limit()
    crit = s["critical_points"]
    assert [c["type"] for c in crit] == ["limit_point", "limit_point"], crit
    # the snap: up to +F_max at height y*, down through zero to -F_max at -y*
    assert rel(crit[0]["load_factor"] * F_REF, fmax) < 1e-4, (crit[0], fmax)
    assert rel(crit[1]["load_factor"] * F_REF, -fmax) < 1e-4, (crit[1], fmax)
    assert abs(crit[0]["displacement"]["apex"][2] - (ys - H)) < 1e-3 * H
    assert abs(crit[1]["displacement"]["apex"][2] - (-ys - H)) < 1e-3 * H
    # every equilibrium of the path is on the closed-form curve, the load factor
    # rises, falls below zero and ends on the target on the inverted branch
    lams = [float(r["time"]) for r in rows]
    for r in rows:
        y = H + float(r["uz"])
        assert abs(float(r["time"]) * F_REF - truss_force(y)) < 1e-5 * fmax, r
    k = lams.index(min(lams))
    assert max(lams[:k]) < fmax / F_REF * (1 + 1e-9) and lams[k] < 0.0 and lams[-1] == 1.0
    y_end = brentq(lambda y: truss_force(y) - F_REF, -10 * H, -ys)
    assert abs(H + float(rows[-1]["uz"]) - y_end) < 1e-6 * H
    # the stability count follows: unstable between the limit points
    ev = s["stability"]["events"]
    assert [(e["negative_before"], e["negative_after"]) for e in ev] == [(0, 1), (1, 0)]


def test_truss_step_budget_keeps_the_path_and_says_where():
    out = Path(tempfile.mkdtemp(prefix="bk-arc-", dir=ensure_dir(BUILD / "runs")))
    r = run_cli(["run", "truss_snap_through", "--quiet", "--out", str(out), "--set", "static.max_steps=3"])
    assert r.returncode != 0
    assert "not reached within static.max_steps = 3 steps" in r.stderr and "load factor" in r.stderr, r.stderr
    s, rows = load_run(out)
    assert not s["converged"] and s["steps"] == 3 and len(rows) == 4


def test_deep_arch_limit_load_within_one_percent_of_dadeppo_schmidt():
    # DaDeppo and Schmidt (J. Appl. Mech. 42 (1975) 894-896), clamped-hinged
    # 215-degree arch, crown point load: P_cr R^2 / EI = 8.97 (897 for
    # R = 100, EI = 1e6, the value quoted by e.g. Ibrahimbegovic 1995).
    s, rows = run_scene("deep_arch_215")
    assert s["converged"], s["error"]
    lim = [c for c in s["critical_points"] if c["type"] == "limit_point"]
    assert lim, s["critical_points"]
    p_cr = lim[0]["load_factor"] * 1000.0
    assert rel(p_cr * 100.0**2 / 1.0e6, 8.97) < 0.01, p_cr
    # past the limit the load factor falls (snap-through)
    lams = [float(r["time"]) for r in rows]
    assert lams[-1] < lim[0]["load_factor"] - 0.05


def test_euler_bifurcation_without_imperfection_on_the_arc_length_path():
    s, _ = run_scene("cantilever_euler_arc")
    assert s["converged"], s["error"]
    bif = [c for c in s["critical_points"] if c["type"] == "bifurcation"]
    assert len(bif) == 1, s["critical_points"]
    EI = 7.2e10 * 0.01**4 / 12.0
    p_e = math.pi**2 * EI / 4.0
    assert rel(bif[0]["load_factor"] * 200.0, p_e) < 2e-3, (bif, p_e)


TRUSS = (ROOT / "models" / "truss_snap_through.toml").read_text()


def test_arc_length_options_are_checked():
    check_error(TRUSS.replace('method = "arc_length"', 'method = "arc"'), "static.method",
                "expected one of|expected")
    check_error(TRUSS.replace("target_load_factor = 1.0", "target_load_factor = -1.0"),
                "static.target_load_factor", "positive")
    check_error(TRUSS.replace("target_load_factor = 1.0", "target_load_factor = 1.0\narc_iterations = 40"),
                "static.arc_iterations", "expected")
    check_error(TRUSS.replace("target_load_factor = 1.0", "target_load_factor = 1.0\ncycles = 1"),
                "static.cycles", "arc_length")
    check_error(TRUSS.replace('method = "arc_length"\n', ""), "static.target_load_factor", "arc_length")
    check_error(TRUSS.replace("target_load_factor = 1.0", "target_load_factor = 1.0\narc_constraint = \"ball\""),
                "static.arc_constraint", "cylindrical")
