"""Contact in the bench: the cost of a Newton iteration of a rod of 1,000
ancf_cable elements lying on the ground (every element in contact, with
friction) against the same rod without contact (bench/newton_iter.c: the
assembly with the interactions, the contact's own share and its broad phase's,
the factorization; CPU time, paired interleaved passes), self-contact checking
from 1,000 to 100,000 elements and its growth exponent,
the same 1,000 elements as two rods of 500 lying one on the other
(beam-to-beam contact, [[beam_contact]] with self-contact checked on both),
and the wall time of models/gripper_lift.toml per simulated second.
Run alone: /usr/bin/python3 -m report.bench_contact [--quick] [--no-gripper]; --cost the iteration
costs alone, --self the self-contact growth alone."""
import json
import os
import subprocess
import sys
import time

from gen.scene import ROOT
from report.bench_runs import WORK

ROD = """[scene]
analysis = "static"
[material.steel]
law = "resultant"
E = 2.1e11
nu = 0.3
rho = 7850.0
[section.round]
shape = "circle"
radius = 0.005
[[beam]]
name = "rod"
element = "ancf_cable"
material = "steel"
section = "round"
start = [0.0, 0.0, 0.0055]
end = [{length}, 0.0, 0.0055]
up = [0.0, 0.0, 1.0]
elements = {n}
[[constraint]]
type = "clamp"
a = "rod:start"
[[load]]
type = "gravity"
value = [0.0, 0.0, -9.81]
{contact}"""

# two rods of n/2 elements, the upper 1 mm above touching (within the 2 mm
# reach: every element pair along them in contact), both clamped at x = 0
STACKED = """[scene]
analysis = "static"
[material.steel]
law = "resultant"
E = 2.1e11
nu = 0.3
rho = 7850.0
[section.round]
shape = "circle"
radius = 0.005
[[beam]]
name = "lower"
element = "ancf_cable"
material = "steel"
section = "round"
start = [0.0, 0.0, 0.0]
end = [{length}, 0.0, 0.0]
up = [0.0, 0.0, 1.0]
elements = {n}
[[beam]]
name = "upper"
element = "ancf_cable"
material = "steel"
section = "round"
start = [0.0, 0.0, 0.011]
end = [{length}, 0.0, 0.011]
up = [0.0, 0.0, 1.0]
elements = {n}
[[constraint]]
type = "clamp"
a = "lower:start"
[[constraint]]
type = "clamp"
a = "upper:start"
[[load]]
type = "gravity"
value = [0.0, 0.0, -9.81]
[[beam_contact]]
beams = ["lower", "upper"]
self = true
distance = 0.002
friction = 0.3
[static]
stability = false
"""

# the rod checked against itself ([[beam_contact]] self = true): straight,
# nothing within reach, the cost of the checking alone
SELF = """[[beam_contact]]
beams = ["rod"]
self = true
distance = 0.001
friction = 0.3
[static]
stability = false
"""

GROUND = """[[contact]]
shape = "half_space"
normal = [0.0, 0.0, 1.0]
distance = 0.001
friction = 0.3
"""


def _newton_exe():
    """The bench_newton solver of ancf_cable (bench/newton_iter.c)."""
    from gen.scene import load_index
    from gen.solver_build import BUILD, VARIANTS, build_solver, compile_object, runtime_headers, runtime_objects
    obj = BUILD / "release" / "bench" / "newton_iter.o"
    compile_object(ROOT / "bench" / "newton_iter.c", obj, VARIANTS["release"], runtime_headers())
    robjs = [o for o in runtime_objects("release") if o.stem != "main"]
    return build_solver(["ancf_cable_resultant_full"], BUILD / "release" / "bench" / "bench_newton_cable", load_index(),
                        "release", main_objs=[obj] + robjs)


KEYS = ("iteration", "assembly", "interactions", "factor", "prepare", "limit", "contact_broad", "beam_broad")


def _model(text, name):
    """The model file of the scene text (in WORK)."""
    from gen.scene import build, write_model
    WORK.mkdir(parents=True, exist_ok=True)
    scene, mpath = WORK / f"{name}.toml", WORK / f"{name}.dat"
    scene.write_text(text)
    write_model(build(scene, []), mpath)
    return mpath


def _run(exe, mpath, iterations):
    """bench_newton's medians over the iterations, from the thread's CPU clock (one thread; on a machine
    shared with other jobs CPU time is the steadier): {key: seconds} for KEYS."""
    r = subprocess.run([str(exe), str(mpath), str(iterations)], capture_output=True, text=True,
                       env=dict(os.environ, OMP_NUM_THREADS="1"))
    if r.returncode != 0:
        raise RuntimeError(f"bench_newton ({mpath.name}) failed: {r.stderr[-500:]}")
    d = dict(line.split("=", 1) for line in r.stdout.split())
    return {k: float(d[f"{k}_cpu_s"]) for k in KEYS}


def _paired(exe, models, iterations, passes):
    """{label: [per pass {key: s}]}: every model run once per pass, the passes interleaved."""
    out = {k: [] for k in models}
    for _ in range(passes):
        for label, mpath in models.items():
            out[label].append(_run(exe, mpath, iterations))
    return out


def _median(xs):
    import statistics
    return statistics.median(xs)


def self_contact_growth(quick, log):
    """The straight rod checked against itself (SELF, nothing within reach) at
    1,000, 10,000 and 100,000 elements (quick: 1,000 and 10,000), each run
    paired with the rod without contact (interleaved passes, CPU time, medians
    of 5 iterations; the medians of the passes): rows {elements,
    iteration_s, free_iteration_s, eval_s (its interactions: the candidates'
    pairs), prepare_s (the check whether a point moved a quarter of the
    margin), limit_s (the step limiter), broad_s (the broad phase run again),
    check_s = broad_s + eval_s, share = check_s / iteration_s, newton_share
    (prepare, evaluation and limiter over an iteration with them, the broad
    phase not run)}; the exponent of check_s's growth over the range; and the
    same at 10,000 elements as two rods of 5,000 lying one on the other (every
    element pair along them within reach, friction: STACKED), a row of its own
    (elements 10,000, "stacked")."""
    import math
    exe = _newton_exe()
    rows = []
    cases = [(n, False) for n in ((1000, 10000) if quick else (1000, 10000, 100000))] + [(10000, True)]
    for n, stacked in cases:
        models = {"free": _model(ROD.format(n=n, length=0.05 * n, contact=""), f"self_rod_{n}_free"),
                  "self": _model(STACKED.format(n=n // 2, length=0.025 * n) if stacked else
                                 ROD.format(n=n, length=0.05 * n, contact=SELF), f"self_rod_{n}_{stacked}")}
        res = _paired(exe, models, 5, 1 if quick or n >= 100000 else 3)
        for mpath in models.values():
            mpath.unlink()
        med = {lab: {k: _median([p[k] for p in v]) for k in KEYS} for lab, v in res.items()}
        s, f = med["self"], med["free"]
        ev = s["interactions"] - f["interactions"]
        row = {"elements": n, "stacked": stacked, "iteration_s": s["iteration"], "free_iteration_s": f["iteration"],
               "eval_s": ev, "prepare_s": s["prepare"], "limit_s": s["limit"], "broad_s": s["beam_broad"],
               "check_s": s["beam_broad"] + ev}
        row["share"] = row["check_s"] / row["iteration_s"]
        newton = s["iteration"] + s["prepare"] + s["limit"]
        row["newton_share"] = (s["prepare"] + ev + s["limit"]) / newton
        rows.append(row)
        log(f"  contact: self-contact rod of {n}{' (stacked)' if stacked else ''} done")
    straight = [r for r in rows if not r["stacked"]]
    a, b = straight[0], straight[-1]
    exponent = math.log(b["check_s"] / a["check_s"]) / math.log(b["elements"] / a["elements"])
    return rows, exponent


def contact_cost(quick, log):
    """Rows {case, elements, iteration_s, assembly_s, interactions_s, factor_s,
    prepare_s, limit_s, contact_broad_s, beam_broad_s} for the rod with and
    without contact: CPU time, medians of 21 iterations, each case's median of
    interleaved passes (1 quick, else 7); with contact also ratio (the median
    over the passes of each pass's iteration against the rod without contact
    in the same pass), contact_share (its interactions' time over an
    iteration) and broad_share (the broad phase alone over an iteration)."""
    exe = _newton_exe()
    n = 200 if quick else 1000
    models = {}
    for case, contact in (("without contact", ""), ("on the ground", GROUND), ("beam on beam", None),
                          ("self-contact checked", SELF)):
        models[case] = _model(ROD.format(n=n, length=0.05 * n, contact=contact) if contact is not None else
                              STACKED.format(n=n // 2, length=0.025 * n), f"contact_rod_{case.split()[0]}")
    passes = 1 if quick else 7
    res = {}
    for k in range(passes):
        for case, mpath in models.items():
            res.setdefault(case, []).append(_run(exe, mpath, 21))
        log(f"  contact: pass {k + 1} of {passes} done")
    for mpath in models.values():
        mpath.unlink()
    rows = []
    for case in models:
        row = {"case": case, "elements": n}
        for k in KEYS:
            row[f"{k}_s"] = _median([p[k] for p in res[case]])
        rows.append(row)
    free = res["without contact"]
    for r in rows[1:]:
        mine = res[r["case"]]
        r["ratio"] = _median([m["iteration"] / f["iteration"] for m, f in zip(mine, free)])
        r["contact_share"] = (r["interactions_s"] - rows[0]["interactions_s"]) / r["iteration_s"]
        r["broad_share"] = r["contact_broad_s"] / r["iteration_s"]
        r["ratio_spread"] = (min(m["iteration"] / f["iteration"] for m, f in zip(mine, free)),
                             max(m["iteration"] / f["iteration"] for m, f in zip(mine, free)))
    return rows


def gripper_wall(log):
    """{wall_s per simulated second, steps, cutbacks, newton_iterations} of models/gripper_lift.toml."""
    out = WORK / "gripper"
    scene = ROOT / "models" / "gripper_lift.toml"
    t0 = time.perf_counter()
    r = subprocess.run([sys.executable, str(ROOT / "gen" / "cli.py"), "run", str(scene), "--quiet", "--out", str(out)],
                       capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if r.returncode != 0:
        raise RuntimeError(f"gripper_lift failed: {r.stderr[-500:]}")
    s = json.loads((out / "summary.json").read_text())
    t_end = 0.6
    log("  contact: gripper done")
    return {"wall_per_simulated_s": wall / t_end, "steps": s["steps"], "cutbacks": s["cutbacks"],
            "newton_iterations": s["newton_iterations"]}


def _met(ok):
    return "met" if ok else "**missed**"


def markdown(rows, grip, growth=None):
    free, ground = rows[0], rows[1]
    lines = ["## Contact", "",
             f"A rod of {free['elements']} `ancf_cable` elements (steel, 10 mm) lying on the ground, every element "
             "within the barrier's reach, friction 0.3, against the same rod without contact (bench/newton_iter.c, "
             "one thread, the thread's CPU time — the machine may be shared, and CPU time is the steadier —, medians "
             "of 21 iterations, the median of interleaved passes).  An iteration is the assembly (with the "
             "interactions) and the factorization with the solve; the solver's Newton iteration also runs the "
             "interactions' prepare and the step limiter, timed apart:", "",
             "| case | iteration | assembly | of which interactions | of which broad phase | factorization | "
             "prepare | step limiter |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['case']} | {r['iteration_s'] * 1e3:.3f} ms | {r['assembly_s'] * 1e3:.3f} ms | "
                     f"{r['interactions_s'] * 1e3:.3f} ms | {r['contact_broad_s'] * 1e3:.3f} ms | "
                     f"{r['factor_s'] * 1e3:.3f} ms | {r['prepare_s'] * 1e3:.3f} ms | {r['limit_s'] * 1e3:.3f} ms |")
    lo, hi = ground["ratio_spread"]
    lines += ["", "| target (issue 34) | measured | |", "|---|---|---|",
              f"| an iteration on the ground ≤ 1.5 × without contact | **{ground['ratio']:.2f}** × (passes "
              f"{lo:.2f}–{hi:.2f}); the contact's evaluation {ground['contact_share']:.0%} of an iteration | "
              f"{_met(ground['ratio'] <= 1.5)} |",
              f"| broad phase ≤ 10 % of an iteration | **{ground['broad_share']:.1%}** (the broad phase alone, "
              f"{ground['contact_broad_s'] * 1e3:.3f} ms: every element's sample points, their box in the "
              "primitive's frame against the primitive, inflated by the barrier's reach and the section's radius; "
              "here every element is a candidate) | "
              f"{_met(ground['broad_share'] <= 0.10)} |", ""]
    if len(rows) > 2:
        lines += [f"Beam on beam: the same {rows[2]['elements']} elements as two rods of {rows[2]['elements'] // 2} "
                  "lying one on the other, every element pair along them within the barrier's reach (2 mm), "
                  "friction 0.3, self-contact checked on both ([[beam_contact]]; the broad phase at the start, as "
                  "in a Newton iteration where no point moved a quarter of the broad phase's margin): an iteration "
                  f"costs **{rows[2]['ratio']:.2f}** times the rod's without contact (the pattern's coupling blocks "
                  f"make the factorization dearer too); the contact's own evaluation is "
                  f"{rows[2]['contact_share']:.0%} of an iteration.  The rod checked against itself (straight, "
                  "`self = true`, nothing within reach): "
                  f"{rows[3]['ratio']:.2f} times, the checking {rows[3]['contact_share']:.0%} of an iteration.", ""]
    if growth:
        g, e = growth
        lines += ["Self-contact checking (issue 35): the straight rod, `self = true`, nothing within reach, and at "
                  "10,000 elements also two rods of 5,000 lying one on the other (every element pair within reach, "
                  "friction); medians of 5 iterations, CPU time, each run paired with the rod without contact.  "
                  "Broad phase: the spatial hash run again at the same state (as when a point moved a quarter of "
                  "the margin); evaluation: the interactions' time less the rod's without contact; share: the two "
                  "over an iteration.  Per Newton iteration where the broad phase does not run: prepare (has a "
                  "point moved?), evaluation and step limiter over an iteration with them:", "",
                  "| elements | iteration | without contact | broad phase | evaluation | prepare | step limiter | "
                  "broad + evaluation | per Newton iteration |", "|---|---|---|---|---|---|---|---|---|"]
        for r in g:
            lines.append(f"| {r['elements']:,}{' stacked' if r['stacked'] else ''} | {r['iteration_s'] * 1e3:.2f} ms "
                         f"| {r['free_iteration_s'] * 1e3:.2f} ms | {r['broad_s'] * 1e3:.2f} ms | "
                         f"{r['eval_s'] * 1e3:.2f} ms | {r['prepare_s'] * 1e3:.2f} ms | {r['limit_s'] * 1e3:.2f} ms "
                         f"| {r['share']:.0%} | {r['newton_share']:.0%} |")
        ten = [r for r in g if r["elements"] == 10000]
        lines += ["", "| target (issue 35) | measured | |", "|---|---|---|"]
        for r in ten:
            lines.append(f"| broad phase + contact evaluation ≤ 25 % of an iteration, 10,000 elements"
                         f"{', two rods in contact' if r['stacked'] else ', self-contact checked'} | "
                         f"**{r['share']:.0%}** (per Newton iteration without the broad phase: "
                         f"{r['newton_share']:.0%}) | {_met(r['share'] <= 0.25)} |")
        straight = [r for r in g if not r["stacked"]]
        lines += [f"| growth of broad phase + evaluation from {straight[0]['elements']:,} to "
                  f"{straight[-1]['elements']:,} elements: exponent ≤ 1.1 | **{e:.2f}** | {_met(e <= 1.1)} |", ""]
    if grip:
        lines += [f"`models/gripper_lift.toml` (0.6 s simulated, dt = 1e-3): {grip['wall_per_simulated_s']:.2f} s of "
                  f"wall time per simulated second (the whole command), {grip['steps']} steps, {grip['cutbacks']} "
                  f"cut-backs, {grip['newton_iterations']} Newton iterations.", ""]
    return lines


if __name__ == "__main__":
    if "--self" in sys.argv:
        g, e = self_contact_growth("--quick" in sys.argv, print)
        for r in g:
            print(r)
        print("exponent", e)
        sys.exit(0)
    if "--cost" in sys.argv:                # the rods on the ground and on each other alone
        print("\n".join(markdown(contact_cost("--quick" in sys.argv, print), None)))
        sys.exit(0)
    rows = contact_cost("--quick" in sys.argv, print)
    grip = gripper_wall(print) if "--no-gripper" not in sys.argv else None
    print("\n".join(markdown(rows, grip, self_contact_growth("--quick" in sys.argv, print))))
