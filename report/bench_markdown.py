"""The text of out/report/bench.md from the bench's results: the headline with
its targets, then the work-precision, kernel, scaling and toolchain sections."""
import math
import os
import time

from report import bench_targets, bench_threads
from report.bench_pareto import TOLS, config
from report.bench_scaling import SCALING_PASSES, fit_exponent


def fmt_t(t):
    if not math.isfinite(t):
        return "n/a"
    if t < 1e-3:
        if t < 1e-5:
            return f"{t * 1e6:.2f} us"
        return f"{t * 1e6:.1f} us" if t < 1e-4 else f"{t * 1e3:.2f} ms"
    return f"{t * 1e3:.1f} ms" if t < 1 else f"{t:.2f} s"


def bench_kernels_flags():
    from gen.solver_build import KERNEL_FLAGS, VARIANTS
    return sorted(set(VARIANTS["release"]) | set(KERNEL_FLAGS["release"]) - {"-fPIC"})


def bench_markdown(quick, cpu, krows, points, spoints, snotes, dnotes, best, problems, pngs, srows, tc, targets,
                   t_all):
    """The lines of bench.md."""
    # ---- targets
    def kr(name):
        return next((r for r in krows if r["pair"] == name), None)
    k1, k2 = kr("ancf3243_svk_full"), kr("ancf3363_arruda_boyce_reduced")
    ops_pt = int(k1["hdr_force_tangent_per_point"]) if k1 and k1["hdr_force_tangent_per_point"].isdigit() else None
    expo = fit_exponent(srows, 100, 10000 if not quick else 1000)
    expo_big = fit_exponent(srows, 1000, 100000) if not quick else math.nan
    s1 = {r["elements"]: r for r in srows if r["threads"] == 1}
    s2 = {r["elements"]: r for r in srows if r["threads"] == 2}
    # where the growth is: the same fit from 10,000 elements on, per part, and the cost per unit
    beyond = {k: fit_exponent(srows, 10000, 100000, key=k) if not quick else math.nan
              for k in ("iteration_s", "assembly_s", "factor_s")}
    per_unit = [n for n in (1000, 10000, 100000) if n in s1]
    unit = {"n": " / ".join(f"{n:,}" for n in per_unit),
            "factor": " / ".join(f"{1e9 * s1[n]['factor_s'] / s1[n]['equations']:.0f}" for n in per_unit),
            "assembly": " / ".join(f"{1e9 * s1[n]['assembly_s'] / n:.0f}" for n in per_unit),
            "mb": " / ".join(f"{s1[n]['maxrss_kb'] / 1024:.0f}" for n in per_unit)}
    nbig = max(s2) if s2 else None
    par = s2[nbig].get("assembly_speedup", s1[nbig]["assembly_s"] / s2[nbig]["assembly_s"]) \
        if nbig in s2 else math.nan
    big = max((r for r in srows if r["threads"] == 1), key=lambda r: r["elements"])
    # memory per element: the slope of the peak memory between the two largest runs
    n_a, n_b = sorted(s1)[-2:] if len(s1) >= 2 else (None, None)
    kb_per_el = ((s1[n_b]["maxrss_kb"] - s1[n_a]["maxrss_kb"]) / (n_b - n_a)) if n_a else math.nan
    load = os.getloadavg()
    regen_total = tc["regen_total_s"]

    def met(ok):
        return "met" if ok else "**missed**"

    L = ["# Speed against error (`./build.sh bench" + (" --quick`)" if quick else "`)"), ""]
    L += [f"CPU: {cpu['model']}, {cpu['mhz']:.0f} MHz, {os.cpu_count()} cores; {cpu['isa']}: "
          f"{cpu['flops_per_cycle']} double flop/cycle/core.  Peak {cpu['peak_gflops']:.1f} GFLOP/s per core, "
          f"measured (`bench/peak.c`: chains of fused multiply-adds on 8-double vectors, the faster of a run "
          f"before and one after the kernels); every share of peak below is of this figure.  Read off "
          f"/proc/cpuinfo (flop/cycle x nominal MHz) it would be {cpu['nominal_gflops']:.1f} GFLOP/s, which "
          f"assumes the nominal clock under vector load and the FMA units of the flags' widest ISA.  "
          f"Kernels and solvers compiled with `{' '.join(bench_kernels_flags())}`; the lane kernels (8 elements "
          f"per call) prefer 512-bit vectors (`BK_LANE_TARGET`, gen/emit.py).  Wall times are the solver's "
          f"own (`summary.json` `wall_s`: model read to results written), on a shared machine: expect a few "
          f"% noise." + (f"  **--quick**: a subset (fewer variants, meshes and steps, shorter dynamics)." if quick
                         else ""), ""]
    L += ["## Headline", "",
          "Fastest configuration reaching each relative error (Pareto-optimal; error definitions and references "
          "below), and the configuration closest to the reference:", "",
          "| problem | ≤ 1e-2 | ≤ 1e-3 | ≤ 1e-4 | lowest error |", "|---|---|---|---|---|"]
    for prob in problems:
        cells = []
        for tol in TOLS:
            b = best[prob][tol]
            cells.append(f"{config(b)}: {fmt_t(b['wall_s'])} (err {b['error']:.1e})" if b else "not reached")
        ok = [p for p in points if p["problem"] == prob and p["converged"] and math.isfinite(p["error"])]
        low = min(ok, key=lambda p: (p["error"], p["wall_s"])) if ok else None
        cells.append(f"{config(low)}: {fmt_t(low['wall_s'])} (err {low['error']:.1e})" if low else "none")
        L.append(f"| {prob} | " + " | ".join(cells) + " |")
    L += ["", "| target | measured | status |", "|---|---|---|"]
    if k1:
        L.append(f"| ancf3243 x svk force + upper tangent ≤ 3,000 operations per quadrature point | "
                 f"{ops_pt} per point ({k1['ops_force_tangent']} per element, 12 points) | {met(ops_pt and ops_pt <= 3000)} |")
        L.append(f"| ancf3243 x svk generated ≥ 5x the plain loop (force + tangent) | "
                 f"{k1['speedup_force_tangent']:.1f}x ({fmt_t(k1['t_force_tangent_s'])} vs "
                 f"{fmt_t(k1['t_plain_force_tangent_s'])}), {k1['gflops_force_tangent']:.2f} GFLOP/s = "
                 f"{100 * k1['gflops_force_tangent'] / cpu['peak_gflops']:.0f} % of one core's peak | "
                 f"{met(k1['speedup_force_tangent'] >= 5)} |")
    k3 = kr("ancf3243_svk_sri")
    if k3:
        L.append(f"| ancf3243 x svk `sri` force + tangent ≤ 0.9 µs per element on one core | "
                 f"{fmt_t(k3['t_force_tangent_s'])} per element ({'lane kernels, 8 elements per call' if k3['lanes'] else 'one element per call'}; "
                 f"one element per call: {fmt_t(k3['t_scalar_force_tangent_s'])}) | "
                 f"{met(k3['t_force_tangent_s'] <= 0.9e-6)} |")
    cont = [r for r in krows if r["material"] != "resultant"]
    if cont:
        worst = min(cont, key=lambda r: r["gflops_force_tangent"])
        pct = 100 * worst["gflops_force_tangent"] / cpu["peak_gflops"]
        L.append(f"| every continuum pair's force + tangent ≥ 30 % of one core's peak | lowest of the "
                 f"{len(cont)} pairs measured: {worst['element']} x {worst['material']} {worst['integration']} "
                 f"{worst['gflops_force_tangent']:.1f} GFLOP/s = {pct:.0f} % of the measured "
                 f"{cpu['peak_gflops']:.1f} GFLOP/s ({100 * worst['gflops_force_tangent'] / cpu['nominal_gflops']:.0f} % "
                 f"of the nominal {cpu['nominal_gflops']:.1f}); "
                 f"{sum(100 * r['gflops_force_tangent'] / cpu['peak_gflops'] >= 30 for r in cont)} of {len(cont)} "
                 f"at ≥ 30 % | {met(pct >= 30)} |")
    if k2:
        L.append(f"| ancf3363 x arruda_boyce (reduced) generated ≥ 3x the plain loop | "
                 f"{k2['speedup_force_tangent']:.1f}x ({fmt_t(k2['t_force_tangent_s'])} vs "
                 f"{fmt_t(k2['t_plain_force_tangent_s'])}), {k2['gflops_force_tangent']:.2f} GFLOP/s = "
                 f"{100 * k2['gflops_force_tangent'] / cpu['peak_gflops']:.0f} % of peak | "
                 f"{met(k2['speedup_force_tangent'] >= 3)} |")
    L.append(f"| Newton iteration cost linear in elements (exponent ≤ 1.1, 100 … {min(big['elements'], 10000):,}) | "
             f"{expo:.3f} | {met(expo <= 1.1)} |")
    if not quick:
        L.append(f"| Newton iteration cost linear up to 100,000 elements (exponent ≤ 1.05, 1,000 … "
                 f"{big['elements']:,}); memory per element | {expo_big:.3f}; {kb_per_el:.1f} kB per element "
                 f"(peak memory {s1[n_a]['maxrss_kb'] / 1024:.0f} MB at {n_a:,}, {s1[n_b]['maxrss_kb'] / 1024:.0f} MB "
                 f"at {n_b:,} elements); from 10,000 to {big['elements']:,}: {beyond['iteration_s']:.3f} (assembly "
                 f"{beyond['assembly_s']:.3f}, factor + solve {beyond['factor_s']:.3f}); per unit at "
                 f"{unit['n']} elements: factor + solve per equation {unit['factor']} ns, assembly per element "
                 f"{unit['assembly']} ns, working set {unit['mb']} MB | {met(expo_big <= 1.05)} |")
    fa = [r for r in srows]
    one_an = all(r["analyses"] == 1 for r in fa)
    no_full = all(r["full_factorizations"] == 1 for r in fa)
    L.append(f"| symbolic analysis once per run; no allocation in the step loop | "
             f"{'1 analysis' if one_an else 'several analyses'} per run; after the first, "
             f"{'every' if no_full else 'not every'} factorization is in place (band LU, or KLU refactor) "
             f"({sum(r['factorizations'] - r['full_factorizations'] for r in fa)} of "
             f"{sum(r['factorizations'] for r in fa)} in the scaling runs); assembly writes into buffers made at "
             f"set-up; the heap allocation count of a dynamic run (valgrind) does not grow with the number of "
             f"steps, serial and parallel (tests/test_bench_alloc.py) | {met(one_an and no_full)} |")
    L.append(f"| assembly of 10,000 elements with 2 threads ≥ 1.7x one thread, bit-identical for any thread "
             f"count (deterministic parallel scatter) | OpenMP: the lane groups in 8 contiguous parts per thread, each "
             f"taken by the next free thread, which adds directly into the entries only that part touches; entries "
             f"shared by two parts are staged and summed in element order after the region; bit-identical results for 1, 2, 3 threads "
             f"(tests/test_parallel.py); assembly at {nbig:,} elements "
             f"{par:.2f}x as fast with 2 threads as with 1 (median over "
             f"{1 if quick else SCALING_PASSES} passes of the ratio of back-to-back runs, each the median "
             f"assembly of its iterations; machine load average {load[0]:.1f} on "
             f"{os.cpu_count()} cores during the run; target ≥ 1.7x) | {met(par >= 1.7 and nbig >= 10000)} |")
    L.append(f"| incremental regeneration; full regeneration < 10 min | unchanged pairs are skipped by input hash "
             f"(re-run: {tc['regen_incremental_redone']} units redone, {tc['regen_incremental_s']:.1f} s); "
             f"{tc['regen_scope']}: {regen_total:.0f} s | "
             f"{met(tc['regen_incremental_redone'] == 0 and (quick or regen_total < 600))} |")
    for target, measured, status in bench_targets.target_rows(targets, met):
        L.append(f"| {target} | {measured} | {status} |")
    if "threads" in targets:
        L.append("| %s | %s | %s |" % bench_threads.target_row(targets["threads"], met))
    L += ["", "Around the solve (`bench_targets.json`): the front end is the whole `./build.sh run` process minus "
          "the solver's own wall time; the output and stability shares are the solver's own account "
          "(`summary.json` `output_s`, `stability_s`: the time inside its output calls, every table, frame and the "
          "section forces they show, and inside the stability checks, over its `wall_s`), with the difference "
          "of whole runs as a cross-check (the default run against `output.vtk_every = 0` and "
          "`static.stability = false`; the CSV tables cannot be switched off; they are flushed at most every "
          "0.5 s); solver runs are interleaved, medians of "
          f"{3 if quick else 9} runs each.  Two floors set by the machine, measured beside them: a process "
          "started as the whole command is (posix_spawn, `/bin/true`), and the creation of a file as a run's "
          "output creates one (in a fresh directory, 1 kB written after it); the files counted are those a "
          "default run creates within its `wall_s` (all but `summary.json`).", ""]

    # ---- work-precision sections
    notes = dict(snotes + dnotes)
    L += ["## Work-precision", "",
          "One curve per element / integration variant; in statics the points are meshes "
          f"({', '.join(str(m) for m in sorted({p['elements'] for p in spoints}))} elements), in dynamics time steps "
          "(solid: finest mesh, dotted: coarser mesh).  All points: `out/report/bench_workprecision.csv` "
          "(`pareto` marks the non-dominated ones).", ""]
    keymap = {problems[0]: "table3"}
    for prob in problems:
        key = {"Table 3": "table3", "Roll-up": "rollup", "Soft pen": "pendulum",
               "Silicone fall discretization": "silicone_disc", "Silicone sag": "silicone_sag",
               "Silicone fall, tip at": "silicone_end", "Silicone": "silicone"}
        note = next((notes[v] for k, v in key.items() if prob.startswith(k)), "")
        if prob.startswith("Table 3") and "table3_solid" in notes:
            note += "  " + notes["table3_solid"]
        L += [f"### {prob}", "", note, "", f"![work-precision]({pngs[prob].name})", "",
              "| variant | elements | dt (s) | wall | Newton it. | error | Pareto |", "|---|---|---|---|---|---|---|"]
        for p in points:
            if p["problem"] != prob:
                continue
            e = f"{p['error']:.2e}" if p["converged"] and math.isfinite(p["error"]) else f"failed: {p['failure']}"
            L.append(f"| {p['variant']} | {p['elements']} | {p['dt'] if p['dt'] is not None else ''} | "
                     f"{fmt_t(p['wall_s'])} | {p['newton_iterations']} | {e} | {'yes' if p.get('pareto') else ''} |")
        L.append("")
    del keymap

    # ---- kernels
    L += ["## Kernels", "",
          f"Per element at a deformed state (element 0.1 x 0.01 x 0.01 m), single thread, the shortest of "
          f"{'3' if quick else '3 passes x 5'} repeats of a loop timed for ≥ {'1' if quick else '4'} ms of the "
          "thread's CPU time (a time slice given to another process does not count; what other load remains, e.g. "
          "the host's other tenants, only slows a loop down, and it comes in spells of seconds: each pass times "
          "every pair once, so a pair's samples lie seconds apart; the shortest is the kernel's own rate, where "
          "single medians scattered by up to 1.5x between runs on this shared machine).  "
          "'t f', 't f+K': as the solvers call them, i.e. the lane kernels (8 elements per call, vectorized across "
          "elements; runtime/bk_kernel.h, \"Lane kernels\") divided by 8 where the pair has them; '1 el.': the "
          "one-element kernel.  Operations from the "
          "kernel headers (add + mul + div + call, per element; force + tangent computes the upper triangle).  "
          "Plain loop: bench/plain.c, the hand-written quadrature loop (F, invariants, P and dP/dF by the chain "
          "rule through I1, I2, J, full tangent), compiled with the same flags; it agrees with the generated "
          "kernels to the last digits (columns 'diff'); it exists for the single-rule continuum variants.", "",
          f"![kernels](bench_kernels.png)", "",
          "| pair | DOF | pts | ops f | ops f+K (per pt) | t f | t f+K | t f+K 1 el. | GFLOP/s f / f+K | % peak f+K | "
          "plain f+K | ratio f / f+K | diff f, K |", "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in krows:
        ratio = (f"{r['speedup_force']:.1f} / {r['speedup_force_tangent']:.1f}"
                 if math.isfinite(r["speedup_force_tangent"]) else "n/a")
        diff = (f"{r['plain_rel_diff_f']:.0e}, {r['plain_rel_diff_K']:.0e}"
                if math.isfinite(r["plain_rel_diff_K"]) else "")
        L.append(f"| {r['element']} × {r['material']} {r['integration']} | {r['ndof']} | {r['nqp']} | "
                 f"{r['ops_force']} | {r['ops_force_tangent']} ({r['hdr_force_tangent_per_point'] or '-'}) | "
                 f"{fmt_t(r['t_force_s'])} | {fmt_t(r['t_force_tangent_s'])} | "
                 f"{fmt_t(r['t_scalar_force_tangent_s']) if r['lanes'] else '(same)'} | "
                 f"{r['gflops_force']:.2f} / {r['gflops_force_tangent']:.2f} | "
                 f"{100 * r['gflops_force_tangent'] / cpu['peak_gflops']:.0f} % | "
                 f"{fmt_t(r['t_plain_force_tangent_s'])} | {ratio} | {diff} |")
    gmax = max(r["gflops_force_tangent"] for r in krows)
    L += ["", f"Best force + tangent rate {gmax:.2f} GFLOP/s = {100 * gmax / cpu['peak_gflops']:.0f} % of the "
          f"{cpu['peak_gflops']:.1f} GFLOP/s measured single-core peak (nominal: {cpu['flops_per_cycle']} flop/cycle "
          f"x {cpu['mhz']:.0f} MHz from /proc/cpuinfo = {cpu['nominal_gflops']:.1f} GFLOP/s).  One element's kernel is a long dependency chain after CSE "
          "(few independent operations to pair into vectors), so the one-element kernels run near the scalar rate; "
          "the lane kernels run the same straight-line code on 8 elements at once, one vector lane each "
          "(the generator prints the body inside `#pragma omp simd` over the lanes, structure-of-arrays data).  "
          "The operation counts are those of the one-element code (an FMA counts 2); the rods (`gef`, "
          "`euler_bernoulli`, `kirchhoff`, `ancf_cable`) have no lane kernels yet.", ""]

    # ---- scaling
    L += ["## Scaling", "",
          "One long `ancf3243` x `svk` beam (elements 0.1 m long, clamped), bench/newton_iter.c: the model read "
          "as the solver reads it, then the median over several Newton iterations at a deformed state of "
          "assembly (forces and tangent), then numeric factorization with the solve as a Newton iteration with a new "
          "matrix does them (the band LU up to its storage limit, its forward substitution inside the elimination; KLU "
          "refactor beyond): iteration = assembly + factor.  The solve column is one more solve with kept factors (an "
          "iteration that reuses them).  Every mesh is timed in "
          f"{1 if quick else SCALING_PASSES} interleaved passes and each row is its fastest pass.  Peak memory: "
          "VmHWM of that process (model, system, matrix, factors).", "",
          "![scaling](bench_scaling.png)", "",
          "| elements | threads | equations | nnz | iteration | assembly | factor + solve | solve (kept factors) | set-up | peak memory |",
          "|---|---|---|---|---|---|---|---|---|---|"]
    for r in srows:
        L.append(f"| {r['elements']:,} | {r['threads']} | {r['equations']:,} | {r['nnz']:,} | "
                 f"{fmt_t(r['iteration_s'])} | {fmt_t(r['assembly_s'])} | {fmt_t(r['factor_s'])} | "
                 f"{fmt_t(r['solve_s'])} | {fmt_t(r['setup_s'])} | {r['maxrss_kb'] / 1024:.1f} MB |")
    L += ["", f"Fitted exponent of the iteration time (1 thread, so that other load on the machine does not "
          f"distort it), least squares on log-log from 100 to {min(big['elements'], 10000):,} elements: **{expo:.3f}**" + (f", from 1,000 to {big['elements']:,}: **{expo_big:.3f}**" if not quick else "") + ".  "
          f"Assembly at {nbig:,} elements with 2 threads: {par:.2f}x the speed of 1 thread (load average "
          f"{load[0]:.1f} / {load[1]:.1f} / {load[2]:.1f} on {os.cpu_count()} cores when the report was written: "
          f"with other processes on the cores the second thread mostly waits for CPU time, and the parts are "
          f"fixed: the thread that is descheduled holds up the end of the assembly).", ""]

    # ---- toolchain
    c = tc["compile"]
    L += ["## Toolchain", "",
          f"Regeneration ({tc['regen_scope']}, forced, into a scratch directory): {regen_total:.1f} s wall; "
          f"a second run with unchanged inputs redid {tc['regen_incremental_redone']} units in "
          f"{tc['regen_incremental_s']:.1f} s (cache: the input hash in each file's header).  Per unit "
          "(seconds of one worker, derivation + CSE + printing):", "",
          "| unit | regenerate |", "|---|---|"]
    for n, t in tc["regen"]:
        L.append(f"| {n} | {t:.1f} s |")
    L += ["", f"Per-scene solver for `{c['scene']}` from an empty build directory: runtime objects "
          f"{c['runtime_s']:.1f} s, then the kernels it uses and the link {c['kernels_and_link_s']:.1f} s.  "
          f"Solver size {c['size'] / 1024:.0f} KiB"
          + (f" ({c['stripped_size'] / 1024:.0f} KiB stripped)" if c["stripped_size"] else "") +
          f".  Pair descriptors linked (symbols `bk_pair_*` in the binary): {', '.join(c['linked_pairs'])}: only "
          f"the element x material files of the pair the scene uses ({', '.join(c['pairs'])}; its integration "
          f"variants share one file).", ""]
    L += [f"Report written in {time.time() - t_all:.0f} s.", ""]
    return L
