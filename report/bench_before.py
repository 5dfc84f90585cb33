"""Whole-solver wall times of two checkouts of beamkit, paired and interleaved:
was a restructuring of the runtime (issue 33: analyses as modules, one
interaction interface, the options schema) within noise of before?

    /usr/bin/python3 -m report.bench_before BEFORE_ROOT AFTER_ROOT [--runs 10]
        [--after-set KEY=VALUE ...]

Each root is a checkout (a git worktree) of the project.  For every scene of
SCENES each root compiles the scene and builds its solver with its own
`./build.sh run` (its own model file format; the solver's path is read from
that run's exec calls, traced with strace); then the two solvers alone (no
Python front end) run the scene RUNS times each, alternating which goes first,
with the same flags (--quiet, one OpenMP thread), into a scratch output
directory.  --after-set adds overrides to the after root's scenes only (e.g.
output.hdf5=false when the before root wrote no results.h5).  Printed: the
median wall time of each, their ratio, the median of the paired differences
with its spread (the half-distance between the quartiles of the differences),
and each run's Newton iterations (summary.json): where they differ the two
roots did not compute the same thing, and the time per iteration compares
them.  Timing only: nothing is asserted.
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

# (label, scene of models/, --set overrides)
SCENES = [
    ("seed Table 3 (10 ancf3243, static)", "cantilever_bend_100N_nu03", []),
    ("Table 3, 1,000 elements (static)", "cantilever_bend_100N_nu03", ["beam.0.elements=1000"]),
    ("silicone_fall (dynamic)", "silicone_fall", []),
    ("silicone_fall_damped (dynamic)", "silicone_fall_damped", []),
    ("soft seed pendulum (10 ancf3243, dynamic)", "pendulum_soft_ancf", []),
]
# the solver's exec: out/bin/solver_HASH (out/bin/SCENE before the solver cache)
SOLVER_RE = re.compile(r'execve\("([^"]*/out/bin/(?!run-cached")[^"]*)"')


def prepare(root, scene, sets, work):
    """Builds root's solver of the scene and writes its model file into work;
    returns (solver, model file)."""
    os.makedirs(work, exist_ok=True)
    trace = os.path.join(work, "exec.trace")
    run = os.path.join(work, "run")
    cmd = ["strace", "-f", "-qq", "-e", "trace=execve", "-o", trace, "./build.sh", "run", scene, "--quiet",
           "--out", run]
    for s in sets:
        cmd += ["--set", s]
    env = dict(os.environ, BK_NO_FAST_RUN="1")
    r = subprocess.run(cmd, cwd=root, env=env, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"error: {root}: ./build.sh run {scene} failed:\n{r.stderr[-2000:]}")
    with open(trace) as f:
        found = SOLVER_RE.findall(f.read())
    if not found:
        sys.exit(f"error: {root}: no solver run seen in the trace of ./build.sh run {scene}")
    return found[-1], os.path.join(run, "model.dat")


def wall(solver, model, out):
    env = dict(os.environ, OMP_NUM_THREADS="1")
    os.makedirs(out, exist_ok=True)          # (an older solver does not make it)
    t0 = time.perf_counter()
    r = subprocess.run([solver, model, out, "--quiet"], env=env, capture_output=True)
    t = time.perf_counter() - t0
    if r.returncode != 0:
        sys.exit(f"error: {solver} {model}: exit {r.returncode}\n{r.stderr.decode()[-2000:]}")
    return t


def iterations(out):
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f).get("newton_iterations", 0)


def quartile_spread(xs):
    q = statistics.quantiles(xs, n=4)
    return 0.5 * (q[2] - q[0])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("--runs", type=int, default=10)
    ap.add_argument("--after-set", action="append", default=[], metavar="KEY=VALUE")
    a = ap.parse_args(argv)
    scratch = tempfile.mkdtemp(prefix="bk-before-after-")
    rows = []
    for k, (label, scene, sets) in enumerate(SCENES):
        runs = {}
        for tag, root in (("before", a.before), ("after", a.after)):
            work = os.path.join(scratch, f"{k}_{tag}")
            extra = a.after_set if tag == "after" else []
            runs[tag] = prepare(os.path.abspath(root), scene, sets + extra, work) + (os.path.join(work, "timed"),)
        times = {"before": [], "after": []}
        for i in range(a.runs):
            order = ("before", "after") if i % 2 == 0 else ("after", "before")
            for tag in order:
                times[tag].append(wall(*runs[tag]))
        diff = [x - y for x, y in zip(times["after"], times["before"])]
        mb, ma = statistics.median(times["before"]), statistics.median(times["after"])
        it = {tag: iterations(runs[tag][2]) for tag in runs}
        per = (ma / max(it["after"], 1)) / (mb / max(it["before"], 1))
        rows.append((label, mb, ma, ma / mb, statistics.median(diff), quartile_spread(diff), it["before"],
                     it["after"], per))
        print(f"{label}: before {mb:.4f} s, after {ma:.4f} s", file=sys.stderr)
    print("| scene | before (s) | after (s) | after / before | median paired difference (s) ± half IQR "
          "| Newton iterations before, after | per iteration after / before |")
    print("|---|---|---|---|---|---|---|")
    for label, mb, ma, ratio, d, spread, ib, ia, per in rows:
        print(f"| {label} | {mb:.4f} | {ma:.4f} | {ratio:.3f} | {d:+.4f} ± {spread:.4f} | {ib}, {ia} | {per:.3f} |")
    print(f"\nmedians of {a.runs} runs each, interleaved; solver alone, --quiet, OMP_NUM_THREADS=1; "
          f"scratch output in {scratch}")


if __name__ == "__main__":
    main()
