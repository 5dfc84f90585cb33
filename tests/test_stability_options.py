"""The static stability check's two levels: by default the inertia of the
constrained tangent alone (the negative-eigenvalue count and its events), with
static.eigenvalues = true also the eigenvalue estimates.  The count is checked
against the Euler load of the seed cantilever (one negative pair past P_cr =
pi^2 EI / (4 L^2) for the square section, two equal modes); the estimates
themselves against dense eigenvalues in tests/test_spring.py."""
import csv
import math
import tempfile
from pathlib import Path

from util import BUILD, ensure_dir, run_cli, run_scene

EI = 7.2e10 * 0.01 ** 4 / 12
P_CR = math.pi ** 2 * EI / 4.0          # clamped-free column, L = 1 m


def fresh():
    return Path(tempfile.mkdtemp(prefix="bk-stab-", dir=ensure_dir(BUILD / "runs")))


def rows(out):
    with open(out / "stability.csv", newline="") as fh:
        return list(csv.DictReader(fh))


def test_inertia_alone_by_default_and_eigenvalues_on_request():
    # compression past the Euler load, straight (no imperfection): the count goes 0 -> 2
    sets = ["load.0.value.0=%r" % (-1.5 * P_CR), "load.0.value.2=0.0", "static.load_steps=3",
            "static.step_control=fixed"]
    out = fresh()
    s, _ = run_scene("cantilever_bend_10N", sets, out)
    r = rows(out)
    assert [int(x["negative_eigenvalues"]) for x in r][-1] == 2, r
    assert all(x["eig_min"] == "nan" and x["eig_max"] == "nan" for x in r), r[:2]
    ev = s["stability"]["events"]
    assert ev and abs(ev[0]["critical_load_factor"] * 1.5 - 1.0) < 0.02, ev
    out2 = fresh()
    run_scene("cantilever_bend_10N", sets + ["static.eigenvalues=true"], out2)
    r2 = rows(out2)
    assert [x["negative_eigenvalues"] for x in r2] == [x["negative_eigenvalues"] for x in r]
    lo = [float(x["eig_min"]) for x in r2]
    hi = [float(x["eig_max"]) for x in r2]
    assert all(math.isfinite(a) and math.isfinite(b) and abs(a) <= b for a, b in zip(lo, hi)), r2
    assert lo[0] > 0 and lo[-1] < 0, lo     # the smallest eigenvalue changes sign past the Euler load


def test_eigenvalues_key_must_be_a_boolean():
    r = run_cli(["run", "cantilever_bend_10N", "--quiet", "--set", "static.eigenvalues=2"])
    assert r.returncode != 0
    assert "static.eigenvalues" in r.stderr and "true or false" in r.stderr, r.stderr
