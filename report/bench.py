"""./build.sh bench: speed against error.  Writes out/report/bench.md, CSV files
(out/report/bench_*.csv) and PNG plots (out/report/bench_*.png):

  * work-precision diagrams: statics (seed Table 3 at -100 N, nu = 0.3, and the
    full roll-up of Table 5), dynamics (soft seed pendulum over 1 s, falling
    silicone cantilever over 0.5 s), one curve per element / integration
    variant, points for meshes and time steps; Pareto-optimal configurations for
    1e-2, 1e-3 and 1e-4 relative error;
  * kernels: time per internal-force and per force + tangent evaluation of every
    element x material pair, operation counts, GFLOP/s, ratio to the plain
    quadrature loop (bench/plain.c);
  * contact: a 1,000-element rod on the ground against the same rod without
    contact (cost per Newton iteration, the contact's and its broad phase's
    shares, CPU time), self-contact checking from 1,000 to 100,000 elements
    (its share of an iteration, the growth exponent), the gripper's
    wall time per simulated second (report/bench_contact.py); the sparse modal
    solve of a 10,000-element beam (report/bench_modal.py); the band LU against
    LAPACK's band solver, reference and OpenBLAS (report/bench_band.py);
  * scaling: time per Newton iteration and peak memory for 10 ... 100,000
    elements, fitted exponent; a 10,000-element static run with 1 and 2 threads
    end to end, and where its wall goes (report/bench_threads.py);
  * toolchain: regeneration time per kernel, per-scene solver compile time and size.

The parts: report/bench_kernels.py (kernels), bench_statics.py and
bench_dynamics.py (the work-precision problems, run through bench_runs.py),
bench_pareto.py (Pareto fronts and their plots), bench_scaling.py,
bench_toolchain.py, bench_targets.py (the targets around the solve) and
bench_markdown.py (the text of bench.md); this module runs them in order and
writes the CSV files and plots.

usage: ./build.sh bench [--quick]
"""
import csv
import json
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from report import bench_kernels, bench_targets  # noqa: E402
from report.bench_dynamics import dynamics  # noqa: E402
from report.bench_markdown import bench_markdown  # noqa: E402
from report.bench_pareto import pareto, plot_wp  # noqa: E402
from report.bench_runs import OUT, WORK  # noqa: E402
from report import bench_contact  # noqa: E402
from report import bench_band  # noqa: E402
from report import bench_modal  # noqa: E402
from report import bench_threads  # noqa: E402
from report.bench_scaling import plot_scaling, scaling  # noqa: E402
from report.bench_statics import statics  # noqa: E402
from report.bench_toolchain import toolchain  # noqa: E402


def write_csv(path, rows, keys):
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow(r)


def main(argv):
    quick = "--quick" in argv
    unknown = [a for a in argv if a != "--quick"]
    if unknown:
        print(f"error: bench: unknown argument {unknown[0]!r} (usage: ./build.sh bench [--quick])", file=sys.stderr)
        return 1
    OUT.mkdir(parents=True, exist_ok=True)
    WORK.mkdir(parents=True, exist_ok=True)
    t_all = time.time()

    def log(s):
        print(f"[{time.time() - t_all:6.1f} s]{s}", file=sys.stderr, flush=True)

    log(" kernels")
    only = None
    if quick:
        only = {"ancf3243_svk_full", "ancf3243_svk_sri", "ancf3363_arruda_boyce_reduced", "ancf3363_svk_reduced",
                "ancf3333_neo_hookean_full", "gef_resultant_full", "ancf_cable_resultant_full"}
    peaks = [bench_kernels.measured_peak()]       # before and after the kernels: the faster of the two
    krows = bench_kernels.run(WORK, repeats=3 if quick else 5, target=0.001 if quick else 0.004, only=only,
                              passes=1 if quick else 3)
    peaks.append(bench_kernels.measured_peak())
    cpu = bench_kernels.cpu_peak()
    cpu["nominal_gflops"], cpu["peak_gflops"] = cpu["peak_gflops"], max(peaks)
    log(" statics")
    spoints, snotes = statics(quick, log)
    log(" dynamics")
    dpoints, dnotes = dynamics(quick, log)
    points = spoints + dpoints
    best = pareto(points)
    log(" scaling")
    srows = scaling(quick, log)
    log(" contact")
    crows, grip = bench_contact.contact_cost(quick, log), bench_contact.gripper_wall(log)
    log(" sparse modes")
    modal_row = bench_modal.sparse_modes(quick, log)
    log(" band LU against LAPACK")
    band = bench_band.band_vs_lapack(quick, log)
    sgrow = bench_contact.self_contact_growth(quick, log)
    log(" toolchain")
    tc = toolchain(quick, log)
    log(" targets around the solve")
    targets = bench_targets.measure(WORK, quick, log)
    log(" both cores end to end")
    targets["threads"] = bench_threads.end_to_end(WORK, quick, log, srows)
    (OUT / "bench_targets.json").write_text(json.dumps(targets, indent=1) + "\n")

    # ---- files
    write_csv(OUT / "bench_workprecision.csv", points,
              ["problem", "variant", "elements", "dt", "converged", "wall_s", "newton_iterations", "steps",
               "error", "pareto", "failure"])
    write_csv(OUT / "bench_kernels.csv", krows,
              ["pair", "element", "material", "integration", "ndof", "nqp", "ops_force", "ops_force_tangent",
               "hdr_force_per_point", "hdr_force_tangent_per_point", "lanes", "t_force_s", "t_force_tangent_s",
               "t_scalar_force_s", "t_scalar_force_tangent_s",
               "gflops_force", "gflops_force_tangent", "t_plain_force_s", "t_plain_force_tangent_s",
               "speedup_force", "speedup_force_tangent", "plain_rel_diff_f", "plain_rel_diff_K", "lanes_rel_diff"])
    write_csv(OUT / "bench_scaling.csv", srows,
              ["elements", "threads", "dofs", "equations", "nnz", "iterations", "iteration_s", "assembly_s", "assembly_min_s",
               "factor_s", "solve_s", "setup_s", "analyses", "factorizations", "full_factorizations", "maxrss_kb"])
    write_csv(OUT / "bench_toolchain.csv", [{"unit": n, "regen_s": t} for n, t in tc["regen"]], ["unit", "regen_s"])
    problems = []
    for p in points:
        if p["problem"] not in problems:
            problems.append(p["problem"])
    pngs = {}
    for prob in problems:
        slug = prob.split(" (")[0].lower().replace(" ", "_").replace("-", "")
        pngs[prob] = OUT / f"bench_wp_{slug}.png"
        plot_wp(points, prob, pngs[prob])
    plot_scaling(srows, OUT / "bench_scaling.png")
    plot_kernels(krows, cpu, OUT / "bench_kernels.png")

    L = bench_markdown(quick, cpu, krows, points, spoints, snotes, dnotes, best, problems, pngs, srows, tc, targets,
                       t_all)
    L += [""] + bench_contact.markdown(crows, grip, sgrow)
    L += bench_modal.markdown(modal_row)
    L += bench_band.markdown(band)
    (OUT / "bench.md").write_text("\n".join(L))
    log(f" wrote {OUT / 'bench.md'}")
    print(f"bench: {OUT / 'bench.md'} ({time.time() - t_all:.0f} s)")
    return 0


def plot_kernels(rows, cpu, path):
    fig, ax = plt.subplots(figsize=(10, 5))
    names = [f"{r['element']}×{r['material']} {r['integration']}" for r in rows]
    x = range(len(rows))
    ax.bar([i - 0.2 for i in x], [r["gflops_force_tangent"] for r in rows], 0.4, label="force + tangent")
    ax.bar([i + 0.2 for i in x], [r["gflops_force"] for r in rows], 0.4, label="force")
    ax.set_xticks(list(x))
    ax.set_xticklabels(names, rotation=75, fontsize=7)
    ax.set_ylabel("GFLOP/s (one core)")
    ax.set_title(f"generated kernels; single-core peak {cpu['peak_gflops']:.0f} GFLOP/s (measured)")
    ax.legend(fontsize=8)
    ax.grid(True, axis="y", lw=0.2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
