"""Calibration: scene parameters fitted to a measured sensor history by least
squares (SciPy's least_squares, trust-region reflective, within bounds).

    res = fit("silicone_fall_damped", "measured.csv",
              {"material.silicone.mu": (1e5, 1e6, 2e5), "material.silicone.kelvin_voigt": (0, 0.02)})
    res.values, res.stderr, res.rms

The data file is CSV (lines starting with # are comments): a time column `t`
or `time` (dynamics), or `load_factor` (statics), and any of the columns x, y, z
(the sensor's position, m) or ux, uy, uz (its displacement, m); an empty cell
is a missing value.  The residual is the model minus the measurement at every
measured value, the model's sensor history interpolated linearly in time.

Each parameter is scaled to [0, 1] over its bounds; the Jacobian is by forward
differences (step diff_step of the range, backward at the upper bound), its
columns run side by side on the Dask client.  Standard errors are the square
roots of the diagonal of s^2 (J^T J)^-1, s^2 = sum r^2 / (m - n) (m measured
values, n parameters).  A parameter the data do not identify stops the fit
with an error naming it: one whose finite-difference step moves the fitted
history by less than the solver resolves (1e-7 of the model length per
measured value), or, for several, a Jacobian whose columns (scaled to unit
length) have a condition number above 100 (forward differences with a step h
cannot tell a condition number beyond about 1/h from a singular Jacobian:
E and rho of a pendulum under gravity, of which only E/rho matters, give a
few hundred with the default step).
"""
import csv
import json
import math
import time
from pathlib import Path

import numpy as np

from beamkit.api import ROOT, BeamkitError, Scene, format_value, set_strings
from beamkit.sweep import check_bounds, run_id, unit_of

TIME_COLUMNS = ("t", "time", "load_factor")
COMPONENTS = ("x", "y", "z", "ux", "uy", "uz")
RESOLUTION = 1e-7          # of the model length: below it a change is the solver's tolerance
COLLINEAR_COND = 100.0


class RunFailed(BeamkitError):
    """A run of the fit failed (did not converge, ...): not bad input."""


class Data:
    """Measured points: t (n,), values {component: (n,) with nan for missing}."""

    def __init__(self, path, t, values, time_column="t"):
        self.path, self.t, self.values, self.time_column = path, t, values, time_column

    @property
    def count(self):
        return int(sum(np.isfinite(v).sum() for v in self.values.values()))


def read_data(path):
    """The measured history of a CSV file (see the module's text)."""
    path = str(path)
    try:
        with open(path, newline="", encoding="utf-8") as fh:
            lines = [ln for ln in fh if ln.strip() and not ln.lstrip().startswith("#")]
    except OSError as e:
        raise BeamkitError(f"error: {path}: cannot read the data file: {e.strerror}") from None
    except UnicodeDecodeError:
        raise BeamkitError(f"error: {path}: not UTF-8 text; expected a CSV file") from None
    rows = list(csv.reader(lines))
    if not rows:
        raise BeamkitError(f"error: {path}: empty; expected a header t,x,y,z (or ux,uy,uz) and rows")
    head = [h.strip() for h in rows[0]]
    tcol = [h for h in head if h in TIME_COLUMNS]
    comps = [h for h in head if h in COMPONENTS]
    if len(tcol) != 1:
        raise BeamkitError(f"error: {path}: expected one time column, t, time or load_factor; found columns "
                           f"{', '.join(head)}")
    if not comps:
        raise BeamkitError(f"error: {path}: no measured component; expected one or more of the columns "
                           f"x, y, z or ux, uy, uz; found {', '.join(head)}")
    if any(c in comps for c in ("x", "y", "z")) and any(c in comps for c in ("ux", "uy", "uz")):
        raise BeamkitError(f"error: {path}: columns of positions (x, y, z) and displacements (ux, uy, uz) "
                           f"together; expected one kind")
    idx = {h: head.index(h) for h in tcol + comps}
    t, vals = [], {c: [] for c in comps}
    for n, r in enumerate(rows[1:], start=2):
        def cell(h):
            j = idx[h]
            s = r[j].strip() if j < len(r) else ""
            if s == "":
                return math.nan
            try:
                v = float(s)
            except ValueError:
                raise BeamkitError(f"error: {path}: data row {n}: column {h}: {s!r} is not a number") from None
            if not math.isfinite(v):
                raise BeamkitError(f"error: {path}: data row {n}: column {h}: {s!r} is not finite")
            return v
        tv = cell(tcol[0])
        if math.isnan(tv):
            raise BeamkitError(f"error: {path}: data row {n}: column {tcol[0]}: missing")
        t.append(tv)
        for c in comps:
            vals[c].append(cell(c))
    if not t:
        raise BeamkitError(f"error: {path}: no data rows")
    d = Data(path, np.array(t), {c: np.array(v) for c, v in vals.items()}, tcol[0])
    if d.count == 0:
        raise BeamkitError(f"error: {path}: every measured value is missing")
    return d


def parse_params(params):
    """{KEY: (lo, hi[, start])} or ["KEY=lo:hi[:start]", ...] -> [(KEY, lo, hi, start or None)]."""
    out = []
    items = params.items() if isinstance(params, dict) else [(None, p) for p in params]
    for k, spec in items:
        if k is None:
            key, eq, rng = str(spec).partition("=")
            parts = rng.split(":")
            if not eq or not key.strip() or len(parts) not in (2, 3):
                raise BeamkitError(f"error: --param {spec}: expected KEY=lo:hi or KEY=lo:hi:start")
            key, what = key.strip(), f"--param {spec}"
        else:
            parts, key, what = list(spec), k, f"--param {k}"
            if len(parts) not in (2, 3):
                raise BeamkitError(f"error: {what}: expected (lo, hi) or (lo, hi, start)")
        lo, hi = check_bounds(what, parts[0], parts[1])
        start = None
        if len(parts) == 3:
            try:
                start = float(parts[2])
            except (TypeError, ValueError):
                raise BeamkitError(f"error: {what}: start {parts[2]!r} is not a number") from None
            if not lo <= start <= hi:
                raise BeamkitError(f"error: {what}: start {start!r} outside [{lo!r}, {hi!r}]")
        if any(key == o[0] for o in out):
            raise BeamkitError(f"error: --param {key}: given twice")
        out.append((key, float(lo), float(hi), None if start is None else float(start)))
    if not out:
        raise BeamkitError("error: fit: no --param KEY=lo:hi to fit")
    return out


def history(scene, params, out_dir, sensor, threads=1):
    """One evaluation (on a Dask worker): the sensor's time, position and
    displacement histories, or the run's error."""
    try:
        r = scene.run(params, out=out_dir, threads=threads)
        if not r.converged:
            return {"error": r.error or "not converged"}
        s = r.sensor(sensor)
        return {"error": None, "time": s.time, "position": s.position, "displacement": s.displacement,
                "wall_s": r.wall_s}
    except BeamkitError as e:
        return {"error": str(e)}
    except Exception as e:
        return {"error": f"error: {type(e).__name__}: {e}"}


class FitResult:
    """values, stderr: {KEY: number}; cost (½ Σ r²), rms (m), residual (the
    vector, m), m (measured values), nfev (solver runs), jacobian (m x n, per
    unit of each parameter), covariance, correlation; dir, plot (paths);
    at_bound: keys whose value is at a bound (their standard error assumes
    the bound is not active)."""

    def __init__(self, **kw):
        self.__dict__.update(kw)

    def table(self):
        w = max(len(k) for k in self.values)
        lines = [f"  {'parameter':<{w}}  {'value':>14}  {'std. error':>11}  {'start':>12}  bounds"]
        for k in self.values:
            lo, hi = self.bounds[k]
            note = "  (at a bound)" if k in self.at_bound else ""
            lines.append(f"  {k:<{w}}  {self.values[k]:14.7g}  {self.stderr[k]:11.3g}  {self.start[k]:12.5g}  "
                         f"[{lo:g}, {hi:g}]{note}")
        return "\n".join(lines)


def fit(scene, data, params, sensor=None, sets=None, out=None, scheduler=None, workers=None, client=None,
        diff_step=1e-3, max_nfev=30, threads=1, progress=True, plot=True):
    """Fit params to data (a path or a Data); see the module's text.  Returns a FitResult."""
    from scipy.optimize import least_squares
    from beamkit.cluster import connect
    from beamkit.sweep import _given
    t0 = time.monotonic()
    sc = scene if isinstance(scene, Scene) else Scene(scene)
    if sets:
        sc = sc.with_sets(sets)
    if not any(s.startswith("output.vtk_every=") for s in sc.sets):
        sc = sc.with_sets(["output.vtk_every=0"])
    spec = parse_params(params)
    d = data if isinstance(data, Data) else read_data(data)
    sensors = [s.get("name") for s in sc.doc.get("sensor", []) if isinstance(s, dict)]
    if sensor is None:
        if len(sensors) != 1:
            raise BeamkitError(f"error: {sc.path}: {len(sensors)} sensors ({', '.join(map(str, sensors))}); "
                               f"name the measured one with --sensor")
        sensor = sensors[0]
    elif sensor not in sensors:
        raise BeamkitError(f"error: --sensor {sensor}: no such sensor in {sc.path} "
                           f"(sensors: {', '.join(map(str, sensors)) or 'none'})")
    keys = [p[0] for p in spec]
    lo = np.array([p[1] for p in spec])
    hi = np.array([p[2] for p in spec])
    start = {}
    model0 = sc.model()                    # the scene as given: its values of the keys are the default starts
    for k, a, b, s in spec:
        if s is None:
            cur = _current_value(sc.doc, sc.sets, k)
            s = cur if cur is not None and a <= cur <= b else 0.5 * (a + b)
        start[k] = float(s)
    # a key the scene does not have stops here, before any run
    sc.model({k: start[k] for k in keys})
    sc.solver(model0["pairs"])
    name = model0["name"]
    out = Path(out) if out else ROOT / "out" / "fit" / name
    evals = out / "evals"
    evals.mkdir(parents=True, exist_ok=True)
    rng = hi - lo
    length = float(model0["length_scale"])
    cache = {}
    log = []
    if max_nfev < len(keys) + 2:
        raise BeamkitError(f"error: fit: --max-runs {max_nfev} is too small: {len(keys)} parameters need at least "
                           f"{len(keys) + 2} runs (the start, one per parameter for the Jacobian, one step)")
    last_jac, u_of = {}, {}

    def phys(u):
        return lo + np.clip(u, 0.0, 1.0) * rng

    def params_of(u):
        return {k: float(v) for k, v in zip(keys, phys(u))}

    def evaluate(cl, us):
        """Residual vectors at the scaled points us (run side by side)."""
        want = []
        for u in us:
            p = params_of(u)
            tkey = tuple(set_strings(p))
            if tkey not in cache and tkey not in [w[0] for w in want]:
                want.append((tkey, p))
                u_of[f"evals/{run_id(sc, p)}"] = np.array(u, dtype=float)
        if len(log) + len(want) > max_nfev:
            raise _Budget()               # --max-runs counts solver runs, the Jacobian's included
        futs = [(tkey, p, cl.submit(history, sc, p, str(evals / run_id(sc, p)), sensor, threads, pure=False))
                for tkey, p in want]
        for tkey, p, f in futs:
            h = f.result()
            if h["error"]:
                raise RunFailed(f"error: fit: the run at {_fmt(p)} failed: {h['error']}")
            cache[tkey] = (_residual(h, d, sc.path), run_id(sc, p))
            log.append({"params": p, "cost": 0.5 * float(np.sum(cache[tkey][0] ** 2)), "dir": f"evals/{run_id(sc, p)}"})
            if progress:
                print(f"fit: run {len(log)}: {_fmt(p)}: rms {math.sqrt(2 * log[-1]['cost'] / d.count):.4g} m",
                      flush=True)
        return [cache[tuple(set_strings(params_of(u)))][0] for u in us]

    ctx = _given(client) if client is not None else connect(scheduler, workers)
    with ctx as cl:
        def fun(u):
            return evaluate(cl, [u])[0]

        def jac(u):
            hs = np.where(u + diff_step <= 1.0, diff_step, -diff_step)
            pts = [u] + [u + hs[i] * np.eye(len(u))[i] for i in range(len(u))]
            res = evaluate(cl, pts)
            J = np.column_stack([(res[i + 1] - res[0]) / hs[i] for i in range(len(u))])
            identifiable(J, hs, keys, length, d.count)
            last_jac["J"] = J
            return J

        u0 = (np.array([start[k] for k in keys]) - lo) / rng
        try:
            r = least_squares(fun, u0, jac=jac, bounds=(0.0, 1.0), method="trf", x_scale=1.0,
                              max_nfev=max_nfev, xtol=1e-6, ftol=1e-8, gtol=1e-8)
        except _Budget:
            r = _budget_result(log, u_of, last_jac["J"], max_nfev)
    u = r.x
    vals = params_of(u)
    resid = fun_cached(cache, vals)
    m, n = resid.size, len(keys)
    J = r.jac / rng                        # per unit of each parameter
    dof = max(1, m - n)
    s2 = float(resid @ resid) / dof
    cov = s2 * np.linalg.inv(J.T @ J)
    se = np.sqrt(np.diag(cov))
    corr = cov / np.outer(se, se)
    best = run_id(sc, vals)
    at_bound = [k for k, x in zip(keys, u) if x <= 1e-9 or x >= 1 - 1e-9]
    res = FitResult(keys=keys, values=vals, stderr=dict(zip(keys, map(float, se))), start=start,
                    bounds={k: (float(a), float(b)) for k, a, b in zip(keys, lo, hi)},
                    cost=0.5 * float(resid @ resid), rms=math.sqrt(float(resid @ resid) / m), residual=resid,
                    m=m, nfev=len(log), jacobian=J, covariance=cov, correlation=corr, dir=out,
                    best_dir=evals / best, at_bound=at_bound, status=r.message, success=bool(r.status > 0), sensor=sensor,
                    data=d, wall_s=time.monotonic() - t0, plot=None)
    (out / "fit.json").write_text(json.dumps({
        "scene": str(sc.path), "sets": sc.sets, "data": str(d.path), "sensor": sensor,
        "parameters": {k: {"value": vals[k], "stderr": res.stderr[k], "start": start[k],
                           "bounds": list(res.bounds[k])} for k in keys},
        "correlation": corr.tolist(), "cost": res.cost, "rms_m": res.rms, "measured_values": m,
        "runs": log, "best_run": f"evals/{best}", "at_bound": at_bound, "status": r.message,
        "wall_s": res.wall_s}, indent=1) + "\n")
    if plot:
        res.plot = plot_fit(res, sc)
    return res


class _Budget(Exception):
    """The next evaluation would pass --max-runs."""


def _budget_result(log, u_of, J, max_runs):
    """least_squares' result fields for a fit stopped by the run budget: the best
    run so far, the last Jacobian (of a nearby point), status 0 (not converged)."""
    from types import SimpleNamespace
    best = min(log, key=lambda e: e["cost"])
    return SimpleNamespace(x=u_of[best["dir"]], jac=J, status=0, message=f"the run budget (--max-runs {max_runs}) was used up "
                           "before the optimizer converged; the best run so far is reported")


def fun_cached(cache, vals):
    return cache[tuple(set_strings(vals))][0]


def identifiable(J, hs, keys, length, m):
    """Refuse a Jacobian (scaled parameters) the data cannot invert."""
    col = np.linalg.norm(J, axis=0)
    floor = RESOLUTION * length * math.sqrt(m)
    for i, k in enumerate(keys):
        if col[i] * abs(hs[i]) < floor:
            raise BeamkitError(f"error: fit: the data do not identify {k}: changing it by {abs(hs[i]):g} of its "
                               f"range moves the fitted history by {col[i] * abs(hs[i]):.2g} m, below what the "
                               f"solver resolves ({floor:.2g} m); the Jacobian is rank-deficient. Fix {k} "
                               f"(--set) or measure what it changes")
    if len(keys) > 1:
        Jn = J / col
        sv, vt = np.linalg.svd(Jn, full_matrices=False)[1:]
        cond = sv[0] / sv[-1] if sv[-1] > 0 else math.inf
        if cond > COLLINEAR_COND:
            v = np.abs(vt[-1])
            names = [keys[i] for i in np.argsort(-v) if v[i] > 0.3]
            raise BeamkitError(f"error: fit: the data do not identify {' and '.join(names)} apart: their "
                               f"effects on the history are nearly proportional (Jacobian rank-deficient, "
                               f"condition {cond:.3g}); fix one of them (--set)")


def _residual(h, d, where):
    t = h["time"]
    if d.t.min() < t[0] - 1e-12 * max(1.0, abs(t[-1])) or d.t.max() > t[-1] * (1 + 1e-9) + 1e-12:
        raise BeamkitError(f"error: {d.path}: measured times [{d.t.min():g}, {d.t.max():g}] reach beyond the "
                           f"run's [{t[0]:g}, {t[-1]:g}] ({where}); shorten the data or lengthen the run")
    out = []
    for c, v in d.values.items():
        field, j = ("displacement", "xyz".index(c[1])) if c.startswith("u") else ("position", "xyz".index(c))
        pred = np.interp(d.t, t, h[field][:, j])
        ok = np.isfinite(v)
        out.append(pred[ok] - v[ok])
    return np.concatenate(out)


def _fmt(p):
    return ", ".join(f"{k}={v:.6g}" for k, v in p.items())


def _current_value(doc, sets, key):
    """The number the scene (with its overrides) has at KEY, or None."""
    for s in reversed(sets):
        k, _, v = s.partition("=")
        if k == key:
            try:
                return float(v)
            except ValueError:
                return None
    node = doc
    for p in key.split("."):
        if isinstance(node, dict):
            node = node.get(p)
        elif isinstance(node, list):
            m = [t for t in node if isinstance(t, dict) and t.get("name") == p]
            node = m[0] if len(m) == 1 else (node[int(p)] if p.isdigit() and int(p) < len(node) else None)
        else:
            return None
    return float(node) if isinstance(node, (int, float)) and not isinstance(node, bool) else None


def fit_title(res, name):
    """fit.png's title: the scene's name, the rms residual, each fitted value
    with its standard error and unit."""
    vals = ", ".join(f"{k.split('.')[-1]} = {res.values[k]:.4g} ± {res.stderr[k]:.2g} {unit_of(k)}".rstrip()
                     for k in res.keys)
    return f"{name}: rms {res.rms:.3g} m\n{vals}"


def plot_fit(res, sc):
    """fit.png: each measured component against time, with the fitted model's history."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from beamkit.api import Run
    d = res.data
    s = Run(res.best_dir).sensor(res.sensor)
    comps = list(d.values)
    fig, axes = plt.subplots(len(comps), 1, figsize=(6.4, 2.4 * len(comps) + 0.6), sharex=True, squeeze=False)
    for ax, c in zip(axes[:, 0], comps):
        field, j = ("displacement", "xyz".index(c[1])) if c.startswith("u") else ("position", "xyz".index(c))
        ok = np.isfinite(d.values[c])
        ax.plot(d.t[ok], d.values[c][ok], ".", ms=3, color="k", label="measured")
        ax.plot(s.time, getattr(s, field)[:, j], "-", color="C3", label="fitted")
        ax.set_ylabel(f"{res.sensor} {c} (m)")
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    axes[-1, 0].set_xlabel("load factor" if d.time_column == "load_factor" else "time (s)")
    fig.suptitle(fit_title(res, sc.name or Path(str(sc.path)).stem), fontsize=9)
    fig.tight_layout()
    p = Path(res.dir) / "fit.png"
    fig.savefig(p, dpi=100)
    plt.close(fig)
    return p


def write_data(path, t, values, comment=None):
    """A data file read_data reads: t and the columns of `values` (nan: missing)."""
    with open(path, "w", newline="", encoding="utf-8") as fh:
        if comment:
            for line in comment.splitlines():
                fh.write(f"# {line}\n")
        w = csv.writer(fh)
        cols = list(values)
        w.writerow(["t"] + cols)
        for i, ti in enumerate(t):
            w.writerow([format_value(float(ti))] + ["" if not np.isfinite(values[c][i])
                                                    else format_value(float(values[c][i])) for c in cols])
    return path


__all__ = ["fit", "read_data", "write_data", "parse_params", "FitResult", "Data"]
