"""Running a hard case's scene (out/report/runs/hard/) and reading what it
wrote: the element variants the cases loop over, their --set overrides, the
summary and the Newton history with its observed convergence rate."""
import csv
import json
import math
import time
from pathlib import Path

from gen.cli import execute
from gen.scene import ROOT

OUT = ROOT / "out" / "report"
RUNS = OUT / "runs" / "hard"
CONTINUUM = [("ancf3243", "full"), ("ancf3243", "sri"), ("ancf3333", "full"), ("ancf3273", "full"),
             ("ancf3363", "full"), ("ancf3363", "reduced")]
RODS = ["gef", "euler_bernoulli", "kirchhoff", "ancf_cable"]


def label(element, integ):
    return element if integ in ("full", None) else f"{element} ({integ})"


def run(scene, sets, tag):
    out = RUNS / tag
    t0 = time.time()
    rc, out = execute(scene, sets, out)
    s = json.loads((Path(out) / "summary.json").read_text())
    s["_wall"] = time.time() - t0
    s["_rc"] = rc
    s["_out"] = Path(out)
    return s


def element_sets(beam, element, integ, material="alu"):
    sets = [f"beam.{beam}.element={element}"]
    if element in RODS:
        sets.append(f"material.{material}.law=resultant")
    elif integ:
        sets.append(f"beam.{beam}.integration={integ}")
    return sets


def newton_rows(out):
    with open(Path(out) / "newton.csv", newline="") as fh:
        return list(csv.DictReader(fh))


def convergence_rate(out):
    """Observed local order at the last iteration, median over the converged
    solves: log e_k / log e_(k-1) with e the residual relative to the force
    scale (2 for quadratic convergence from e_(k-1) well below 1)."""
    by = {}
    for r in newton_rows(out):
        by.setdefault(r["attempt"], []).append(float(r["residual"]) / max(float(r["reference"]), 1e-300))
    ps = []
    for e in by.values():
        # the last iteration usually sits at the round-off floor: use the two before
        if len(e) >= 4 and 0 < e[-2] < e[-3] < 1e-2:
            ps.append(math.log(e[-2]) / math.log(e[-3]))
    ps.sort()
    return ps[len(ps) // 2] if ps else float("nan")
