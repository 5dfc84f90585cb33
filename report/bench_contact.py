"""Contact in the bench: the cost of a Newton iteration of a rod of 1,000
ancf_cable elements lying on the ground (every element in contact, with
friction) against the same rod without contact (bench/newton_iter.c: the
assembly with the interactions, the contact's own share, the factorization),
the same 1,000 elements as two rods of 500 lying one on the other
(beam-to-beam contact, [[beam_contact]] with self-contact checked on both),
and the wall time of models/gripper_lift.toml per simulated second.
Run alone: /usr/bin/python3 -m report.bench_contact."""
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


def _iteration(exe, text, name, iterations):
    """bench_newton's medians {iteration_s, assembly_s, interactions_s, factor_s} for the scene text."""
    from gen.scene import build, write_model
    WORK.mkdir(parents=True, exist_ok=True)
    scene, mpath = WORK / f"{name}.toml", WORK / f"{name}.dat"
    scene.write_text(text)
    write_model(build(scene, []), mpath)
    r = subprocess.run([str(exe), str(mpath), str(iterations)], capture_output=True, text=True,
                       env=dict(os.environ, OMP_NUM_THREADS="1"))
    mpath.unlink()
    if r.returncode != 0:
        raise RuntimeError(f"bench_newton ({name}) failed: {r.stderr[-500:]}")
    d = dict(line.split("=", 1) for line in r.stdout.split())
    return {k: float(d[k]) for k in ("iteration_s", "assembly_s", "interactions_s", "factor_s")}


def self_contact_growth(quick, log):
    """The straight rod checked against itself (SELF) at 1,000, 10,000 and
    100,000 elements (quick: 1,000 and 10,000): rows {elements, iteration_s,
    check_s (its interactions less the rod's without contact: the broad
    phase's candidates' segment distances), share}, and the exponent of
    check_s's growth over the range."""
    exe = _newton_exe()
    rows = []
    for n in (1000, 10000) if quick else (1000, 10000, 100000):
        base = _iteration(exe, ROD.format(n=n, length=0.05 * n, contact=""), f"self_rod_{n}_free", 5)
        self = _iteration(exe, ROD.format(n=n, length=0.05 * n, contact=SELF), f"self_rod_{n}", 5)
        check = self["interactions_s"] - base["interactions_s"]
        rows.append({"elements": n, "iteration_s": self["iteration_s"], "free_iteration_s": base["iteration_s"],
                     "check_s": check, "share": check / self["iteration_s"]})
        log(f"  contact: self-contact rod of {n} done")
    import math
    a, b = rows[0], rows[-1]
    exponent = math.log(b["check_s"] / a["check_s"]) / math.log(b["elements"] / a["elements"])
    return rows, exponent


def contact_cost(quick, log):
    """Rows {case, elements, iteration_s, assembly_s, interactions_s, factor_s}
    for the rod with and without contact, medians of 21 iterations (best of 3
    interleaved passes)."""
    from gen.scene import build, load_index, write_model
    from gen.solver_build import BUILD, VARIANTS, build_solver, compile_object, runtime_headers, runtime_objects
    index = load_index()
    obj = BUILD / "release" / "bench" / "newton_iter.o"
    compile_object(ROOT / "bench" / "newton_iter.c", obj, VARIANTS["release"], runtime_headers())
    robjs = [o for o in runtime_objects("release") if o.stem != "main"]
    exe = build_solver(["ancf_cable_resultant_full"], BUILD / "release" / "bench" / "bench_newton_cable", index,
                       "release", main_objs=[obj] + robjs)
    n = 200 if quick else 1000
    WORK.mkdir(parents=True, exist_ok=True)
    paths = {}
    for case, contact in (("without contact", ""), ("on the ground", GROUND), ("beam on beam", None),
                          ("self-contact checked", SELF)):
        scene = WORK / f"contact_rod_{case.split()[0]}.toml"
        scene.write_text(ROD.format(n=n, length=0.05 * n, contact=contact) if contact is not None else
                         STACKED.format(n=n // 2, length=0.025 * n))
        paths[case] = WORK / f"contact_rod_{case.split()[0]}.dat"
        write_model(build(scene, []), paths[case])
    best = {}
    env = dict(os.environ, OMP_NUM_THREADS="1")
    for _ in range(1 if quick else 3):
        for case, mpath in paths.items():
            r = subprocess.run([str(exe), str(mpath), "21"], capture_output=True, text=True, env=env)
            if r.returncode != 0:
                raise RuntimeError(f"bench_newton ({case}) failed: {r.stderr[-500:]}")
            d = dict(line.split("=", 1) for line in r.stdout.split())
            row = {"case": case, "elements": n}
            for k in ("iteration_s", "assembly_s", "interactions_s", "factor_s"):
                row[k] = float(d[k])
            if case not in best or row["iteration_s"] < best[case]["iteration_s"]:
                best[case] = row
        log("  contact: pass done")
    for mpath in paths.values():
        mpath.unlink()
    rows = [best["without contact"], best["on the ground"], best["beam on beam"], best["self-contact checked"]]
    for r in rows[1:]:
        r["ratio"] = r["iteration_s"] / rows[0]["iteration_s"]
        r["contact_share"] = (r["interactions_s"] - rows[0]["interactions_s"]) / r["iteration_s"]
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


def markdown(rows, grip, growth=None):
    lines = ["## Contact", "",
             f"A rod of {rows[0]['elements']} `ancf_cable` elements (steel, 10 mm) lying on the ground, every element "
             "within the barrier's reach, friction 0.3 (bench/newton_iter.c, one thread, medians of 21 iterations, "
             "best of 3 passes), against the same rod without contact:", "",
             "| case | iteration | assembly | of which interactions | factorization |", "|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['case']} | {r['iteration_s'] * 1e3:.3f} ms | {r['assembly_s'] * 1e3:.3f} ms | "
                     f"{r['interactions_s'] * 1e3:.3f} ms | {r['factor_s'] * 1e3:.3f} ms |")
    lines += ["", f"Cost of an iteration with contact / without: **{rows[1]['ratio']:.2f}** (target ≤ 1.5); the "
              f"contact's own evaluation (every sample point's gap, barrier and friction: there is no separate broad "
              f"phase against primitives, each point's exact distance is the test) is {rows[1]['contact_share']:.0%} "
              "of an iteration.", ""]
    if len(rows) > 2:
        lines += [f"Beam on beam: the same {rows[2]['elements']} elements as two rods of {rows[2]['elements'] // 2} "
                  "lying one on the other, every element pair along them within the barrier's reach (2 mm), "
                  "friction 0.3, self-contact checked on both ([[beam_contact]]; the broad phase at the start, as "
                  "in a Newton iteration where no point moved a quarter of the broad phase's margin): an iteration "
                  f"costs **{rows[2]['ratio']:.2f}** times the rod's without contact (the pattern's coupling blocks "
                  f"make the factorization dearer too); the contact's own evaluation is "
                  f"{rows[2]['contact_share']:.0%} of an iteration.  The rod checked against itself (straight, "
                  "`self = true`, nothing within reach: the candidates' segment distances only): "
                  f"{rows[3]['ratio']:.2f} times, the checking {rows[3]['contact_share']:.0%} of an iteration.", ""]
    if growth:
        g, e = growth
        lines += ["Self-contact checking (the straight rod, `self = true`, nothing within reach; medians of 5 "
                  "iterations): its cost (the interactions' time less the rod's without contact: the broad phase's "
                  "candidates' segment distances) against the element count (target of issue 35: ≤ 25 % of an "
                  "iteration at 10,000 elements, growth exponent ≤ 1.1):", "",
                  "| elements | iteration | without contact | checking | share |", "|---|---|---|---|---|"]
        for r in g:
            lines.append(f"| {r['elements']:,} | {r['iteration_s'] * 1e3:.2f} ms | "
                         f"{r['free_iteration_s'] * 1e3:.2f} ms | {r['check_s'] * 1e3:.2f} ms | {r['share']:.0%} |")
        lines += ["", f"Growth exponent of the checking from {g[0]['elements']:,} to {g[-1]['elements']:,} elements: "
                  f"**{e:.2f}**.", ""]
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
    rows = contact_cost("--quick" in sys.argv, print)
    grip = gripper_wall(print) if "--no-gripper" not in sys.argv else None
    print("\n".join(markdown(rows, grip, self_contact_growth("--quick" in sys.argv, print))))
