"""dynamic.jacobian = "reuse" (modified Newton across steps, the default) against
full Newton (`every_iteration`): both stop at the same tolerances, so the sensor
histories agree to the Newton tolerance (a consistency check of one code in two
modes, not a verification: the dynamic tests against rigid-pendulum, Euler-
Bernoulli and CalculiX references run with the default), while the reuse needs far
fewer factorizations; a stiff case and one with Rayleigh damping (whose force uses
the tangent even when the factors are kept) included."""
import csv
import json
import tempfile
from pathlib import Path

import pytest

from util import BUILD, ensure_dir, run_cli


def run(scene, sets):
    out = Path(tempfile.mkdtemp(prefix="bk-reuse-", dir=ensure_dir(BUILD / "runs")))
    r = run_cli(["run", scene, "--quiet", "--out", str(out), "--set", "output.vtk_every=0"]
                + [a for s in sets for a in ("--set", s)])
    assert r.returncode == 0, r.stderr[-2000:]
    with open(out / "sensors.csv", newline="") as f:
        rows = {(x["sensor"], round(float(x["time"]), 9)): (float(x["ux"]), float(x["uy"]), float(x["uz"]))
                for x in csv.DictReader(f)}
    return json.loads((out / "summary.json").read_text()), rows


@pytest.mark.parametrize("scene,sets,tol,max_ratio", [
    ("pendulum_soft_ancf", ["dynamic.t_end=1", "dynamic.dt=1e-3"], 1e-6, 0.5),
    ("pendulum_stiff_ancf", ["dynamic.t_end=1", "dynamic.dt=1e-3"], 1e-6, 0.6),
    ("pendulum_soft_ancf", ["dynamic.t_end=1", "dynamic.dt=1e-3", "dynamic.rayleigh_beta=1e-3"], 1e-6, 0.6),
])
def test_reuse_matches_full_newton_with_fewer_factorizations(scene, sets, tol, max_ratio):
    sr, rr = run(scene, sets)
    sf, rf = run(scene, sets + ["dynamic.jacobian=every_iteration"])
    assert sr["converged"] and sf["converged"]
    common = set(rr) & set(rf)            # a step halved in one mode adds an output time
    assert len(common) >= 0.98 * len(rf) > 100
    scale = max(max(abs(c) for c in row) for row in rf.values())
    diff = max(max(abs(a - b) for a, b in zip(rr[k], rf[k])) for k in common)
    assert diff <= tol * scale, (diff, scale)
    assert sr["factorizations"] <= max_ratio * sf["factorizations"], (sr["factorizations"], sf["factorizations"])


def test_unknown_jacobian_mode_is_refused():
    r = run_cli(["run", "pendulum_soft_ancf", "--quiet", "--set", "dynamic.jacobian=sometimes"])
    assert r.returncode != 0
    assert "dynamic.jacobian" in r.stderr and "reuse" in r.stderr and "every_iteration" in r.stderr, r.stderr
