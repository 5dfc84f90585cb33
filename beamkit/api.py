"""Scenes and runs from Python: the scene compiler of `./build.sh run` (gen/scene/,
no sympy), the same per-scene solver, results as numpy arrays.

    from beamkit import Scene
    sc = Scene("pendulum_soft_ancf", sets={"dynamic.t_end": 0.5})
    run = sc.run({"beam.rod.elements": 20}, out="/tmp/pend20")
    run.converged, run.wall_s, run.sensor("B").displacement[-1]

A run is gen/pipeline.py's run(), the function behind `./build.sh run`, with
the same solver cache (gen/cache.py).  A scene is a name in models/, a
path to a TOML file, or a dict of the same tables (parsed TOML).  Overrides are the keys of `--set` (a dict or a list of
"KEY=VALUE" strings).  Bad input raises BeamkitError with the one-line message
of the command line; a run that does not converge is returned
(`run.converged` False, `run.error`), not raised.
"""
import csv
import json
from pathlib import Path

import numpy as np

from gen import cache, pipeline
from gen.scene import ROOT, SceneError, build, read_toml

MODELS = ROOT / "models"
RUNS = ROOT / "out" / "runs"
EXIT_OK, EXIT_INPUT, EXIT_NOT_CONVERGED = 0, 1, 2
EXIT_SIGNAL = {130: "SIGINT", 143: "SIGTERM"}
BUILDING = "error: building the solver for "


class BeamkitError(Exception):
    """Bad input (scene, key, value, data file, options) or a failed build; str()
    is the one-line message, `error: FILE: KEY: what was expected`."""


def set_strings(sets):
    """Overrides as `KEY=VALUE` strings: from a dict {key: value}, a list of
    strings or of (key, value) pairs.  Values print as `--set` would take them."""
    if sets is None:
        return []
    items = sets.items() if isinstance(sets, dict) else sets
    out = []
    for it in items:
        if isinstance(it, str):
            out.append(it)
            continue
        k, v = it
        out.append(f"{k}={format_value(v)}")
    return out


def format_value(v):
    """A value as `--set` text: booleans true/false, floats with every digit (repr)."""
    if isinstance(v, (bool, np.bool_)):
        return "true" if v else "false"
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    if isinstance(v, (float, np.floating)):
        return repr(float(v))
    return str(v)


class Scene:
    """A scene to run many times.  source: a name in models/, a path to a .toml
    file, or a dict of tables (then `name` names it; default its scene.name or
    "scene").  sets: overrides applied to every run.  base: the directory of
    the scene's relative data paths (table and path CSV files); default the
    scene file's; a dict scene without it takes absolute paths only."""

    def __init__(self, source, sets=None, name=None, base=None):
        self.sets = set_strings(sets)
        self.base = str(Path(base).resolve()) if base is not None else None
        if isinstance(source, dict):
            self.doc = json.loads(json.dumps(source))      # plain data, a copy
            sc = self.doc.get("scene") if isinstance(self.doc.get("scene"), dict) else {}
            self.name = name or (sc.get("name") if isinstance(sc.get("name"), str) else "scene")
            self.path = f"<dict scene {self.name}>"
        else:
            try:
                self.path = str(Path(pipeline.scene_path(source)))
                self.doc = read_toml(self.path)
            except SceneError as e:
                raise BeamkitError(str(e)) from None
            self.name = name

    def __repr__(self):
        return f"Scene({self.path!r}, sets={self.sets!r})"

    def with_sets(self, sets):
        """A copy with more overrides."""
        s = Scene.__new__(Scene)
        s.__dict__.update(self.__dict__)
        s.sets = self.sets + set_strings(sets)
        return s

    def model(self, sets=None, out_dir=None):
        """The meshed model (plain data, as gen/scene builds it) with these overrides."""
        try:
            return build(self.path, self.sets + set_strings(sets), name=self.name,
                         out_dir=out_dir or RUNS, doc=self.doc, base=self.base)
        except SceneError as e:
            raise BeamkitError(str(e)) from None

    def solver(self, pairs):
        """The solver for these element x material pairs (gen/cache.py):
        built once and reused while its file is unchanged.  Numeric overrides
        never change the pairs, so they never rebuild it."""
        try:
            return cache.solver(pairs)
        except SceneError as e:
            raise BeamkitError(str(e)) from None
        except Exception as e:             # BuildError: the compiler's messages
            first = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
            raise BeamkitError(f"{BUILDING}{self.path}: {first}") from None

    def run(self, sets=None, out=None, threads=None, verbose=False):
        """Mesh the scene with these overrides, write the model file into `out`
        (default out/runs/NAME, cleared first) and run the solver.  threads: the
        solver's OpenMP threads (default: the environment's).  Returns a Run."""
        try:
            r = pipeline.run(self.path, self.sets + set_strings(sets), str(out) if out else None, doc=self.doc,
                             base=self.base,
                             name=self.name, verbose=verbose, quiet=not verbose, threads=threads, capture=True)
        except SceneError as e:
            msg = str(e)
            if msg.startswith(BUILDING):      # the compiler's messages: the first line
                msg = msg.strip().splitlines()[0]
            raise BeamkitError(msg) from None
        out = Path(r.out)
        if r.rc == EXIT_INPUT:
            last = [x for x in r.stderr.strip().splitlines() if x.strip()]
            raise BeamkitError(last[-1] if last else f"error: {out}/model.dat: the solver refused the model")
        if not (out / "summary.json").exists():
            raise BeamkitError(f"error: {out}: the solver exited with status {r.rc} and wrote no "
                               f"summary.json: {r.stderr.strip()[-300:]}")
        return Run(out, r.rc, r.stderr)


def run(source, sets=None, out=None, threads=None):
    """Scene(source).run(sets, out): one run."""
    return Scene(source).run(sets, out, threads)


class Sensor:
    """The history of one sensor: arrays over the output steps.  step (int),
    time (s; load factor in statics), position and displacement (n x 3, m),
    d1, d2, d3 (n x 3: the section vectors, see docs/reference/outputs.md)."""

    def __init__(self, name, cols):
        self.name = name
        self.step = cols["step"].astype(int)
        self.time = cols["time"]
        self.position = np.column_stack([cols["x"], cols["y"], cols["z"]])
        self.displacement = np.column_stack([cols["ux"], cols["uy"], cols["uz"]])
        for d in ("d1", "d2", "d3"):
            setattr(self, d, np.column_stack([cols[d + c] for c in "xyz"]))

    def __repr__(self):
        return f"Sensor({self.name!r}, {len(self.time)} steps)"


def read_csv(path):
    """A results CSV as {column: numpy array}: numeric columns as float64 (with
    every digit the solver printed), text columns as str arrays; None if absent."""
    try:
        fh = open(path, newline="", encoding="utf-8")
    except FileNotFoundError:
        return None
    with fh:
        rows = list(csv.reader(fh))
    if not rows:
        return None
    head, body = rows[0], rows[1:]
    cols = {}
    for j, h in enumerate(head):
        vals = [r[j] if j < len(r) else "" for r in body]
        try:
            cols[h] = np.array([float(v) if v != "" else np.nan for v in vals], dtype=float)
        except ValueError:
            cols[h] = np.array(vals, dtype=str)
    return cols


class Run:
    """The results of one run in its directory (read when first asked for).

    summary        summary.json as a dict
    converged, error, wall_s, returncode, dir
    sensor(NAME)   a Sensor (numpy histories); sensors: {name: Sensor}
    energy         energy.csv (dynamic) as {column: array}, else None
    newton         newton.csv (static) as {column: array}, else None
    stability      stability.csv (static) as {column: array}, else None
    frequencies    modal: the natural frequencies (Hz) from modes.csv, else None
    modes          modes.csv as {column: array}, else None
    """

    def __init__(self, out, returncode=0, stderr=""):
        self.dir = Path(out)
        self.returncode = returncode
        self.stderr = stderr
        self._summary = None
        self._sensors = None

    def __repr__(self):
        return f"Run({str(self.dir)!r}, converged={self.converged})"

    @property
    def summary(self):
        if self._summary is None:
            try:
                self._summary = json.loads((self.dir / "summary.json").read_text(encoding="utf-8"))
            except (OSError, ValueError) as e:
                raise BeamkitError(f"error: {self.dir}/summary.json: cannot read: {e}") from None
        return self._summary

    @property
    def converged(self):
        return bool(self.summary.get("converged"))

    @property
    def error(self):
        return self.summary.get("error")

    @property
    def wall_s(self):
        return float(self.summary.get("wall_s", float("nan")))

    @property
    def sensors(self):
        if self._sensors is None:
            cols = read_csv(self.dir / "sensors.csv") or {}
            out = {}
            if cols:
                names = cols["sensor"]
                for n in dict.fromkeys(names.tolist()):
                    sel = names == n
                    out[n] = Sensor(n, {k: v[sel] for k, v in cols.items() if k != "sensor"})
            self._sensors = out
        return self._sensors

    def sensor(self, name):
        try:
            return self.sensors[name]
        except KeyError:
            raise BeamkitError(f"error: {self.dir}: no sensor {name!r} (sensors: "
                               f"{', '.join(self.sensors) or 'none'})") from None

    @property
    def energy(self):
        return read_csv(self.dir / "energy.csv")

    @property
    def newton(self):
        return read_csv(self.dir / "newton.csv")

    @property
    def stability(self):
        return read_csv(self.dir / "stability.csv")

    @property
    def modes(self):
        return read_csv(self.dir / "modes.csv")

    @property
    def frequencies(self):
        m = self.modes
        return None if m is None or "frequency_hz" not in m else m["frequency_hz"]
