"""Parameter sweeps: every combination of values runs as its own solver process
on a Dask cluster (beamkit.cluster), into one table.

    res = sweep("pendulum_soft_ancf", grid={"beam.rod.elements": [4, 8, 16],
                                           "dynamic.dt": [0.01, 0.005]},
                sets={"dynamic.t_end": 1.0}, workers=2)
    res.rows, res.csv

The runs are every combination of the grid values (the first key varies
slowest), each with every random sample when `random` is given ({KEY: (lo, hi)},
`samples` draws, uniform; integers when lo and hi are integers; `seed`).  OUT
(default out/sweeps/NAME) gets sweep.csv (one row per run: run, dir, the swept
keys, converged, wall_s, the outputs, error), runs/ID/ (each run's directory;
ID is a hash of the scene and the run's overrides) and sweep_KEY.png (an output
against each swept key).  A finished run leaves runs/ID/sweep-run.json: a
sweep run again over the same directory reuses those and runs only the rest.
A run that fails (bad value, no convergence, a lost worker) is a row with its
error (and is not retried by a restart; delete its directory to retry it); an
interrupted run leaves no marker and runs again.  An output
NAME.FIELD:STAT[@T0:T1] is a statistic of a sensor's, joint's or actuator's
column over a time window of the run (beamkit/windows.py: peak, max, min,
amplitude, rms, mean).  Sweeps write no ParaView frames unless vtk=True (output.vtk_every=0).
"""
import hashlib
import itertools
import json
import math
import os
import re
import time
from pathlib import Path

from beamkit import windows
from beamkit.api import ROOT, BeamkitError, Scene, format_value, set_strings

MARKER = "sweep-run.json"
SUMMARY_OUTPUTS = ("steps", "newton_iterations", "cutbacks", "load_factor", "strain_energy", "time",
                   "max_constraint_residual")
SENSOR_COMPONENTS = {"x": ("position", 0), "y": ("position", 1), "z": ("position", 2),
                     "ux": ("displacement", 0), "uy": ("displacement", 1), "uz": ("displacement", 2)}
KEY_ERROR = re.compile(r": (--set \S+: |\S+: unknown key)")


def parse_grid(spec):
    """'KEY=v1,v2,...' -> (KEY, [values as text])."""
    key, eq, vals = str(spec).partition("=")
    key = key.strip()
    if not eq or not key:
        raise BeamkitError(f"error: --grid {spec}: expected KEY=v1,v2,...")
    values = [v.strip() for v in vals.split(",") if v.strip()]
    if not values:
        raise BeamkitError(f"error: --grid {spec}: no values; expected KEY=v1,v2,...")
    return key, values


def parse_range(spec, option="--random"):
    """'KEY=lo:hi' -> (KEY, lo, hi) with lo < hi; ints when both are written as integers."""
    key, eq, rng = str(spec).partition("=")
    key = key.strip()
    parts = rng.split(":")
    if not eq or not key or len(parts) < 2:
        raise BeamkitError(f"error: {option} {spec}: expected KEY=lo:hi")
    return (key,) + check_bounds(f"{option} {spec}", parts[0], parts[1])


def check_bounds(what, lo, hi):
    def num(v):
        if isinstance(v, (int, float)) and not isinstance(v, bool):
            return v
        t = str(v).strip()
        try:
            return int(t) if re.fullmatch(r"[+-]?\d+", t) else float(t)
        except ValueError:
            raise BeamkitError(f"error: {what}: {t!r} is not a number") from None
    lo, hi = num(lo), num(hi)
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise BeamkitError(f"error: {what}: bounds must be finite numbers")
    if lo >= hi:
        raise BeamkitError(f"error: {what}: lower bound {lo!r} must be below the upper bound {hi!r}")
    return lo, hi


def combinations(grid=None, random=None, samples=None, seed=0):
    """The runs' overrides, a list of {KEY: value}: grid {KEY: [values]} (product,
    first key slowest) x random {KEY: (lo, hi)} (`samples` uniform draws)."""
    grid = dict(grid or {})
    random = dict(random or {})
    for k, vals in grid.items():
        if isinstance(vals, (str, bytes)) or not hasattr(vals, "__iter__"):
            raise BeamkitError(f"error: --grid {k}: expected a list of values")
        if len(list(vals)) == 0:
            raise BeamkitError(f"error: --grid {k}=: no values; expected KEY=v1,v2,...")
    for k in random:
        if k in grid:
            raise BeamkitError(f"error: --random {k}: already a --grid key")
    if random and (samples is None or int(samples) < 1):
        raise BeamkitError("error: --random needs --samples N (N >= 1)")
    if samples is not None and not random:
        raise BeamkitError("error: --samples: no --random KEY=lo:hi to draw")
    if not grid and not random:
        raise BeamkitError("error: sweep: nothing to sweep; give --grid KEY=v1,v2,... or --random KEY=lo:hi")
    draws = [{}]
    if random:
        import numpy as np
        rng = np.random.default_rng(seed)
        bounds = {k: check_bounds(f"--random {k}", *v) for k, v in random.items()}
        draws = []
        for _ in range(int(samples)):
            d = {}
            for k, (lo, hi) in bounds.items():
                d[k] = int(rng.integers(lo, hi + 1)) if isinstance(lo, int) and isinstance(hi, int) \
                    else float(rng.uniform(lo, hi))
            draws.append(d)
    keys = list(grid)
    out = []
    for combo in itertools.product(*(list(grid[k]) for k in keys)):
        for d in draws:
            out.append(dict(zip(keys, combo), **d))
    return out


def run_id(scene, params):
    """A run's directory name: a hash of the scene, its overrides and this run's."""
    h = hashlib.sha256(json.dumps({"scene": scene.doc, "path": scene.path, "name": scene.name,
                                   "sets": scene.sets, "params": set_strings(params)},
                                  sort_keys=True).encode())
    return h.hexdigest()[:16]


def execute(scene, params, out_dir, threads=1):
    """One run of a sweep (on a Dask worker): the run's record, always (errors
    included); `sweep-run.json` in out_dir once it is done."""
    t0 = time.monotonic()
    rec = {"id": Path(out_dir).name, "params": set_strings(params), "converged": False, "wall_s": None,
           "summary": None, "error": None}
    try:
        r = scene.run(params, out=out_dir, threads=threads)
        s = r.summary
        rec.update(converged=r.converged, wall_s=r.wall_s, error=None if r.converged else (r.error or "not converged"),
                   summary={k: v for k, v in s.items() if k not in ("warnings",)})
        if s.get("interrupted"):           # not done: no marker, a restart runs it again
            rec["error"] = r.error or "interrupted"
            rec["total_s"] = time.monotonic() - t0
            return rec
    except BeamkitError as e:
        rec["error"] = str(e)
    except Exception as e:                 # anything else is this run's row, not the sweep's end
        rec["error"] = f"error: {type(e).__name__}: {e}"
    rec["total_s"] = time.monotonic() - t0
    try:
        Path(out_dir).mkdir(parents=True, exist_ok=True)
        tmp = Path(out_dir) / (MARKER + ".tmp")
        tmp.write_text(json.dumps(rec, indent=1) + "\n")
        os.replace(tmp, Path(out_dir) / MARKER)
    except OSError:
        pass
    return rec


def default_outputs(scene):
    sensors = [s.get("name") for s in scene.doc.get("sensor", []) if isinstance(s, dict)]
    return [f"{n}.{c}" for n in sensors if isinstance(n, str) for c in ("ux", "uy", "uz")] + \
        ["steps", "newton_iterations"]


def check_outputs(scene, outputs):
    sensors = [s.get("name") for s in scene.doc.get("sensor", []) if isinstance(s, dict)]
    for o in outputs:
        if o in SUMMARY_OUTPUTS or re.fullmatch(r"frequency\.[1-9]\d*", o):
            continue
        if windows.is_window(o):         # a statistic over a time window (beamkit/windows.py)
            err = windows.check(scene.doc, scene.path, o)
            if err:
                raise BeamkitError(err)
            continue
        name, dot, comp = o.rpartition(".")
        if dot and comp in SENSOR_COMPONENTS:
            if name not in sensors:
                raise BeamkitError(f"error: --output {o}: no sensor {name!r} in {scene.path} "
                                   f"(sensors: {', '.join(map(str, sensors)) or 'none'})")
            continue
        raise BeamkitError(f"error: --output {o}: unknown output; expected SENSOR.x, .y, .z, .ux, .uy, .uz, "
                           f"{', '.join(SUMMARY_OUTPUTS)}, frequency.N or NAME.FIELD:STAT[@T0:T1]")


def output_value(summary, o):
    if not summary:
        return None
    if o in SUMMARY_OUTPUTS:
        return summary.get(o)
    if o.startswith("frequency."):
        f = summary.get("frequencies_hz") or []
        i = int(o.split(".")[1]) - 1
        return f[i] if i < len(f) else None
    name, _, comp = o.rpartition(".")
    field, i = SENSOR_COMPONENTS[comp]
    try:
        return summary["sensors"][name][field][i]
    except (KeyError, IndexError, TypeError):
        return None


class SweepResult:
    """rows: one dict per run (run, dir, the swept keys, converged, wall_s, the
    outputs, error) in the order of the combinations; csv, plots: paths;
    reused: runs taken from an earlier sweep; wall_s: the sweep's time, timing:
    its parts (setup_s: the scene and solver, runs_s: the cluster and the runs,
    plots_s)."""

    def __init__(self, rows, keys, outputs, out, csv, plots, reused, wall_s):
        self.rows, self.keys, self.outputs, self.out = rows, keys, outputs, out
        self.csv, self.plots, self.reused, self.wall_s = csv, plots, reused, wall_s

    @property
    def failed(self):
        return [r for r in self.rows if not r["converged"]]

    def column(self, name):
        import numpy as np
        return np.array([np.nan if r[name] in (None, "") else float(r[name]) for r in self.rows])


def sweep(scene, grid=None, random=None, samples=None, seed=0, sets=None, out=None, outputs=None, plot=None,
          scheduler=None, workers=None, progress=True, vtk=False, threads=1, client=None):
    """Run every combination (see the module's text); returns a SweepResult.
    scene: a Scene, a name in models/, a path or a dict; client: an open
    distributed.Client to use instead of scheduler/workers."""
    from beamkit.cluster import Progress, connect
    t0 = time.monotonic()
    sc = scene if isinstance(scene, Scene) else Scene(scene)
    if sets:
        sc = sc.with_sets(sets)
    if not vtk and not any(s.startswith("output.vtk_every=") for s in sc.sets):
        sc = sc.with_sets(["output.vtk_every=0"])
    grid = {k: [format_value(v) for v in vals] if not isinstance(vals, (str, bytes)) else vals
            for k, vals in (grid or {}).items()}
    combos = combinations(grid, random, samples, seed)
    keys = list(grid) + [k for k in (random or {}) if k not in grid]
    outputs = list(outputs) if outputs else default_outputs(sc)
    check_outputs(sc, outputs)
    if plot is not None and plot not in outputs:
        check_outputs(sc, [plot])
    # One build here: a key the scene does not have stops the sweep before any
    # run (a bad value is that run's row), and the solver is built once.
    first = None
    try:
        first = sc.model(combos[0])
        sc.solver(first["pairs"])
    except BeamkitError as e:
        if KEY_ERROR.search(str(e)):
            # a key of the grid or the draws is named as the user gave it (the
            # scene reader applies every value as a --set)
            text = str(e)
            for opt, keys in (("--grid", grid), ("--random", random or {})):
                for k in keys:
                    text = text.replace(f"--set {k}:", f"{opt} {k}:")
                    if text.startswith(f"error: --set {k}="):      # (gen/scene blame_set: --set KEY=VALUE: ...)
                        text = f"error: {opt} {k}: " + text.split(": ", 2)[2]
            if text != str(e):
                raise BeamkitError(text) from None
            raise
    name = first["name"] if first else (sc.name or Path(str(sc.path)).stem)
    out = Path(out) if out else ROOT / "out" / "sweeps" / name
    runs_dir = out / "runs"
    runs_dir.mkdir(parents=True, exist_ok=True)
    ids = [run_id(sc, c) for c in combos]
    records, todo, queued = {}, [], set()
    for i, (c, rid) in enumerate(zip(combos, ids)):
        rec = _done(runs_dir / rid, rid)
        if rec is not None:
            records[rid] = rec
        elif rid not in queued:
            queued.add(rid)
            todo.append((i, rid, c))
    reused = len(records)
    bar = Progress(len(combos), "runs", enabled=progress)
    bar.done = reused
    if progress and reused:
        print(f"sweep: {reused} of {len(combos)} runs done before, reused", flush=True)
    t_runs = time.monotonic()
    if todo:
        ctx = _given(client) if client is not None else connect(scheduler, workers)
        with ctx as cl:
            from distributed import as_completed
            futs = {cl.submit(execute, sc, c, str(runs_dir / rid), threads, pure=False,
                              key=f"beamkit-run-{rid}-{os.getpid()}-{i}"): rid for i, rid, c in todo}
            try:
                for f in as_completed(list(futs), loop=cl.loop):
                    rid = futs[f]
                    try:
                        rec = f.result()
                    except Exception as e:     # the worker was lost, ...
                        rec = {"id": rid, "params": [], "converged": False, "wall_s": None, "summary": None,
                               "error": f"error: the run's task failed: {type(e).__name__}: {e}"}
                    records[rid] = rec
                    bar.update(failed=not rec["converged"])
            except BaseException:
                for f in futs:
                    f.cancel()
                _write(out, combos, ids, records, keys, outputs)
                raise
    rows = _write(out, combos, ids, records, keys, outputs)
    t_plots = time.monotonic()
    plots = plot_sweep(out, rows, keys, plot or outputs[0], scene=name) if rows else []
    res = SweepResult(rows, keys, outputs, out, out / "sweep.csv", plots, reused, time.monotonic() - t0)
    res.timing = {"setup_s": t_runs - t0, "runs_s": t_plots - t_runs, "plots_s": time.monotonic() - t_plots}
    return res


class _given:
    def __init__(self, client):
        self.client = client

    def __enter__(self):
        return self.client

    def __exit__(self, *exc):
        return False


def _done(d, rid):
    try:
        rec = json.loads((d / MARKER).read_text())
    except (OSError, ValueError):
        return None
    return rec if rec.get("id") == rid else None


def _write(out, combos, ids, records, keys, outputs):
    """sweep.csv of the runs done so far, in the combinations' order."""
    import csv
    rows = []
    for i, (c, rid) in enumerate(zip(combos, ids)):
        rec = records.get(rid)
        if rec is None:
            continue
        row = {"run": i, "dir": f"runs/{rid}"}
        row.update({k: format_value(c[k]) for k in keys})
        row["converged"] = bool(rec["converged"])
        row["wall_s"] = rec.get("wall_s")
        for o in outputs:
            if not rec["converged"]:
                row[o] = None
            elif windows.is_window(o):       # read once from the run's tables, kept in its record
                row[o] = rec.setdefault("windows", {}).get(o)
                if o not in rec["windows"]:
                    row[o] = rec["windows"][o] = windows.value(Path(out) / "runs" / rid, o)
            else:
                row[o] = output_value(rec.get("summary"), o)
        row["error"] = rec.get("error") or ""
        rows.append(row)
    cols = ["run", "dir"] + keys + ["converged", "wall_s"] + outputs + ["error"]
    tmp = Path(out) / "sweep.csv.tmp"
    with open(tmp, "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(cols)
        for r in rows:
            w.writerow(["" if r[k] is None else (repr(r[k]) if isinstance(r[k], float) else r[k]) for k in cols])
    os.replace(tmp, Path(out) / "sweep.csv")
    return rows


def _num(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return None


_UNITS = {"E": "Pa", "G": "Pa", "mu": "Pa", "lambda": "Pa", "c10": "Pa", "c01": "Pa", "kappa": "Pa", "kelvin_voigt": "s",
          "lambda_m": "", "nu": "", "rho": "kg/m³", "EA": "N", "GA1": "N", "GA2": "N", "GJ": "N m²", "EI1": "N m²",
          "EI2": "N m²", "b": "m", "h": "m", "radius": "m", "start": "m", "end": "m", "tension": "N",
          "pressure": "Pa", "area": "m²", "offset": "m", "value": "N or N m", "elements": "",
          "ux": "m", "uy": "m", "uz": "m", "x": "m", "y": "m", "z": "m", "strain_energy": "J", "wall_s": "s",
          "steps": "", "newton_iterations": "", "frequency": "Hz"}


def unit_of(key):
    """The unit of a scene key or a sweep output ('' when it has none or is not known)."""
    from gen.options_schema import OPTIONS
    for o in OPTIONS:
        if o.name == key:
            return o.unit
    parts = key.split(".")
    if parts[0] == "frequency":
        return "Hz"
    return _UNITS.get(parts[-1], _UNITS.get(parts[0], ""))


def _with_unit(key):
    u = unit_of(key)
    return f"{key} ({u})" if u else key


def plot_sweep(out, rows, keys, output, scene=""):
    """sweep_KEY.png: `output` against each swept key, one line per combination
    of the other keys (points only for random draws); units on the axes, the
    scene's name in the title."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    paths = []
    for k in keys:
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
        xs_all = [_num(r[k]) for r in rows]
        numeric = all(x is not None for x in xs_all)
        cats = list(dict.fromkeys(r[k] for r in rows))
        others = [o for o in keys if o != k]
        groups = {}
        for r in rows:
            groups.setdefault(tuple(r[o] for o in others), []).append(r)
        for g, rs in list(groups.items())[:12]:
            pts = sorted(((_num(r[k]) if numeric else cats.index(r[k]), _num(r[output]))
                          for r in rs if r["converged"] and _num(r[output]) is not None))
            if not pts:
                continue
            label = ", ".join(f"{o}={v}" for o, v in zip(others, g)) or None
            style = "o-" if len(rs) > 1 and len(groups) < len(rows) else "o"
            ax.plot([p[0] for p in pts], [p[1] for p in pts], style, ms=4, label=label)
        if numeric:
            pos = [x for x in xs_all if x is not None]
            if pos and min(pos) > 0 and max(pos) / min(pos) >= 20:
                ax.set_xscale("log")
        else:
            ax.set_xticks(range(len(cats)), cats)
        nfail = sum(not r["converged"] for r in rows)
        ax.set_xlabel(_with_unit(k))
        ax.set_ylabel(_with_unit(output))
        ax.set_title((f"{scene}: " if scene else "") + f"{output} against {k}" +
                     (f" ({nfail} failed runs not drawn)" if nfail else ""), fontsize=10)
        if 1 < len(groups) <= 12:
            ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        p = Path(out) / f"sweep_{re.sub(r'[^A-Za-z0-9_.-]', '_', k)}.png"
        fig.savefig(p, dpi=100)
        plt.close(fig)
        paths.append(p)
    return paths
