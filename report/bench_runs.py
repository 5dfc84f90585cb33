"""Running one bench configuration and measuring it: the element / integration
variants as --set overrides, the run into out/report/bench/runs/, a sensor's
track and its positions at given times, and the work-precision point of a run."""
import csv
import json
import math

from gen.cli import execute
from gen.scene import ROOT, SceneError

OUT = ROOT / "out" / "report"
WORK = OUT / "bench"

FREE = ["constraint.0.cross_section=free"]


def beam_variants(beam, law_key):
    """(label, --set overrides) of every element / integration variant."""
    res = [f"material.{law_key}.law=resultant"]
    b = f"beam.{beam}"
    return [
        ("ancf3243 full", [f"{b}.element=ancf3243", f"{b}.integration=full"]),
        ("ancf3243 sri", [f"{b}.element=ancf3243", f"{b}.integration=sri"]),
        ("ancf3333 full", [f"{b}.element=ancf3333", f"{b}.integration=full"]),
        ("ancf3273 reduced", [f"{b}.element=ancf3273", f"{b}.integration=reduced"]),
        ("ancf3273 full", [f"{b}.element=ancf3273", f"{b}.integration=full"]),
        ("ancf3363 reduced", [f"{b}.element=ancf3363", f"{b}.integration=reduced"]),
        ("ancf3363 full", [f"{b}.element=ancf3363", f"{b}.integration=full"]),
        ("ancf_cable", [f"{b}.element=ancf_cable"] + res),
        ("gef", [f"{b}.element=gef"] + res),
        ("euler_bernoulli", [f"{b}.element=euler_bernoulli"] + res),
        ("kirchhoff", [f"{b}.element=kirchhoff"] + res),
    ]


def pick(variants, labels):
    return [v for v in variants if v[0] in labels]


# ---------------------------------------------------------------- running

def run(scene, sets, tag):
    """Run a scene; returns dict(summary, rows) or None with the error text."""
    out = WORK / "runs" / tag
    try:
        rc, out = execute(scene, sets, out)
    except SceneError as e:
        return None, str(e).strip()
    sp = out / "summary.json"
    if not sp.exists():
        return None, f"no summary (exit status {rc})"
    s = json.loads(sp.read_text())
    rows = []
    with open(out / "sensors.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    s["_rows"] = rows
    s["_rc"] = rc
    return s, None


def tip_xyz(s, sensor):
    p = s["sensors"][sensor]["position"]
    return [float(v) for v in p]


def track(rows, sensor):
    """{time: (x, y, z)} of one sensor."""
    out = {}
    for r in rows:
        if r["sensor"] == sensor:
            out[float(r["time"])] = (float(r["x"]), float(r["y"]), float(r["z"]))
    return out


def at_times(tr, times):
    """Positions at the given times: the stored time within 1e-7 s, else linear
    interpolation between the bracketing stored times (steps that a cut-back
    moved off the grid); None when a time is outside the run."""
    import bisect
    keys = sorted(tr)
    res = []
    for t in times:
        i = bisect.bisect_left(keys, t - 1e-7)
        if i < len(keys) and abs(keys[i] - t) <= 1e-7:
            res.append(tr[keys[i]])
            continue
        if i == 0 or i >= len(keys):
            return None
        t0, t1 = keys[i - 1], keys[i]
        a = (t - t0) / (t1 - t0)
        res.append(tuple((1 - a) * x0 + a * x1 for x0, x1 in zip(tr[t0], tr[t1])))
    return res


def dist(a, b):
    return math.sqrt(sum((x - y)**2 for x, y in zip(a, b)))


def point(problem, label, n, dt, s, err, errfun):
    p = {"problem": problem, "variant": label, "elements": n, "dt": dt, "converged": False,
         "wall_s": math.nan, "newton_iterations": None, "steps": None, "error": math.nan, "failure": err or ""}
    if s is not None:
        p["converged"] = bool(s["converged"]) and s["_rc"] == 0
        p["wall_s"] = float(s["wall_s"])
        p["newton_iterations"] = s.get("newton_iterations")
        p["steps"] = s.get("steps")
        if p["converged"]:
            try:
                p["error"] = errfun(s)
            except (KeyError, TypeError, ValueError) as e:
                p["failure"] = f"no error: {e}"
        else:
            p["failure"] = (s.get("error") or f"exit status {s['_rc']}").splitlines()[0][:120]
    return p
