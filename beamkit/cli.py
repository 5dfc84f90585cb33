"""`./build.sh sweep` and `./build.sh fit` (python3 -m beamkit.cli sweep|fit ...).

Exit status: 0 every run converged (sweep) / the fit converged; 1 bad input
(one `error:` line); 2 sweep: the table is written but some runs failed (their
rows say why); fit: a run failed or the optimizer stopped without converging;
64 usage error; 130 sweep interrupted by Ctrl-C (the finished runs are kept).
"""
import argparse
import os
import sys

from gen.pipeline import caller_path

EXIT_OK, EXIT_INPUT, EXIT_FAILED, EXIT_USAGE, EXIT_INTERRUPTED = 0, 1, 2, 64, 130


class Parser(argparse.ArgumentParser):
    def __init__(self, *args, **kw):
        kw.setdefault("allow_abbrev", False)     # --thread is not --threads: unknown options exit 64
        super().__init__(*args, **kw)

    def error(self, message):
        self.print_usage(sys.stderr)
        print(f"error: {self.prog}: {message}", file=sys.stderr)
        sys.exit(EXIT_USAGE)


def _common(ap):
    ap.add_argument("scene", help="a name in models/ (without .toml) or a path to a .toml file")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="override a scene value in every run (as for ./build.sh run)")
    ap.add_argument("--out", metavar="DIR", help="results directory")
    ap.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                    help="an existing Dask scheduler, its address or its --scheduler-file "
                         "(default: $DASK_SCHEDULER_ADDRESS, else a local cluster)")
    ap.add_argument("--workers", type=int, metavar="N", help="workers of the local cluster (default: the cores)")
    ap.add_argument("--threads", type=int, default=1, metavar="N",
                    help="OpenMP threads of each solver (default 1: the workers share the cores)")
    ap.add_argument("--quiet", action="store_true", help="no progress, only errors and the result lines")


def _scene(spec):
    from beamkit.api import Scene
    s = str(spec)
    return Scene(caller_path(s) if (s.endswith(".toml") or "/" in s) else s)


def cmd_sweep(argv):
    ap = Parser(prog="build.sh sweep",
                description="Run every combination of scene values, each as its own solver process on a Dask "
                            "cluster; one row per run in OUT/sweep.csv (default out/sweeps/SCENE).")
    _common(ap)
    ap.add_argument("--grid", action="append", default=[], metavar="KEY=v1,v2,...", help="values of a key")
    ap.add_argument("--random", action="append", default=[], metavar="KEY=lo:hi",
                    help="uniform draws in [lo, hi] (integers when both are integers); with --samples")
    ap.add_argument("--samples", type=int, metavar="N", help="number of random draws")
    ap.add_argument("--seed", type=int, default=0, help="seed of the random draws (default 0)")
    ap.add_argument("--output", action="append", default=[], metavar="OUTPUT",
                    help="a column of sweep.csv: SENSOR.x|y|z|ux|uy|uz (final value), steps, newton_iterations, "
                         "cutbacks, load_factor, strain_energy, time, max_constraint_residual, frequency.N, "
                         "or a statistic over a time window NAME.FIELD:peak|max|min|amplitude|rms|mean[@T0:T1] "
                         "(FIELD: a sensor's x..uz, a joint's or actuator's value, rate, effort, power) (default: every sensor's ux, uy, uz, steps, newton_iterations)")
    ap.add_argument("--plot", metavar="OUTPUT", help="the output drawn against each swept key (default the first)")
    ap.add_argument("--vtk", action="store_true", help="keep the runs' ParaView frames (default: none)")
    a = ap.parse_args(argv)
    from beamkit.api import BeamkitError
    from beamkit.sweep import parse_grid, parse_range, sweep
    try:
        grid = dict(parse_grid(g) for g in a.grid)
        rnd = {}
        for r in a.random:
            k, lo, hi = parse_range(r)
            rnd[k] = (lo, hi)
        res = sweep(_scene(a.scene), grid=grid, random=rnd or None, samples=a.samples, seed=a.seed, sets=a.set,
                    out=caller_path(a.out) if a.out else None, outputs=a.output or None, plot=a.plot,
                    scheduler=a.scheduler, workers=a.workers, progress=not a.quiet, vtk=a.vtk, threads=a.threads)
    except BeamkitError as e:
        print(str(e), file=sys.stderr)
        return EXIT_INPUT
    except KeyboardInterrupt:
        print("\ninterrupted: the finished runs are kept (sweep.csv); the same command runs the rest",
              file=sys.stderr)
        return EXIT_INTERRUPTED
    nf = len(res.failed)
    print(f"sweep {res.out}: {len(res.rows)} runs ({res.reused} reused), {nf} failed, {res.wall_s:.1f} s; "
          f"table {res.csv}")
    for r in res.failed[:10]:
        print(f"  run {r['run']} ({r['dir']}): {r['error']}")
    if nf > 10:
        print(f"  ... and {nf - 10} more failed runs (sweep.csv, column error)")
    return EXIT_FAILED if nf else EXIT_OK


def cmd_fit(argv):
    ap = Parser(prog="build.sh fit",
                description="Fit scene values to a measured sensor history (least squares within bounds, "
                            "finite-difference Jacobian columns in parallel on Dask); results in OUT "
                            "(default out/fit/SCENE): fit.json, fit.png, the runs in evals/.")
    _common(ap)
    ap.add_argument("--data", required=True, metavar="MEASURED.csv",
                    help="CSV: t (or time, load_factor) and any of x, y, z or ux, uy, uz; empty cells are missing")
    ap.add_argument("--param", action="append", default=[], metavar="KEY=lo:hi[:start]",
                    help="a value to fit within [lo, hi] (start: default the scene's value, else the middle)")
    ap.add_argument("--sensor", help="the measured sensor (default the scene's only one)")
    ap.add_argument("--diff-step", type=float, default=1e-3, metavar="H",
                    help="finite-difference step, a fraction of each parameter's range (default 1e-3)")
    ap.add_argument("--max-runs", type=int, default=30, metavar="N",
                    help="most residual evaluations of the optimizer (default 30)")
    a = ap.parse_args(argv)
    from beamkit.api import BeamkitError
    from beamkit.fit import RunFailed, fit
    if not a.param:
        ap.error("fit needs at least one --param KEY=lo:hi")
    try:
        res = fit(_scene(a.scene), caller_path(a.data), a.param, sensor=a.sensor, sets=a.set,
                  out=caller_path(a.out) if a.out else None, scheduler=a.scheduler, workers=a.workers,
                  diff_step=a.diff_step, max_nfev=a.max_runs, threads=a.threads, progress=not a.quiet)
    except RunFailed as e:
        print(str(e), file=sys.stderr)
        return EXIT_FAILED
    except BeamkitError as e:
        print(str(e), file=sys.stderr)
        return EXIT_INPUT
    except KeyboardInterrupt:
        print("\ninterrupted: the runs so far are in OUT/evals/", file=sys.stderr)
        return EXIT_INTERRUPTED
    print(f"fit {res.dir}: {res.m} measured values, {res.nfev} runs, {res.wall_s:.1f} s; {res.status}")
    print(res.table())
    print(f"  residual: rms {res.rms:.4g} m, cost {res.cost:.4g} m^2; plot {res.plot}")
    if res.at_bound:
        print(f"  at a bound: {', '.join(res.at_bound)} (widen the bounds; its standard error assumes it free)")
    if not res.success:
        print(f"error: fit: the optimizer stopped before converging ({res.status}); raise --max-runs",
              file=sys.stderr)
        return EXIT_FAILED
    return EXIT_OK


def main(argv):
    if not argv or argv[0] not in ("sweep", "fit"):
        print("usage: python3 -m beamkit.cli {sweep,fit} ...", file=sys.stderr)
        return EXIT_USAGE
    os.environ.setdefault("MPLBACKEND", "Agg")
    return (cmd_sweep if argv[0] == "sweep" else cmd_fit)(argv[1:])


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
