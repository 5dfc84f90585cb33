"""Committed CalculiX references: references/data/calculix_silicone.json (the
silicone strips) and references/data/calculix_cantilever.json (the seed
cantilever of Table 3, the bench's reference: reference_data(NAME, CANTILEVER)).

Each entry is one mesh study (calculix.study) of a scene with its overrides,
written by `python3 -m calculix ... --record NAME` (the command is stored in the
entry) and read by `reference_data(NAME)` without running ccx:

  scene, sets       the scene and its --set overrides
  analysis, sensor  static | dynamic; the sensor whose displacement is given
  meshes, grading   the mesh family (refined by `ratio` in the `refined`
                    directions, the others held), its grading (calculix.mesh)
  per_mesh          every mesh's final displacement, element and node counts,
                    ccx wall time (s, one thread)
  value, error      extrapolated final displacement [ux, uy, uz] (m) and its
                    error estimate (m): Roache's GCI of the mesh study plus the
                    checks' estimates
  order             observed order per component (None where not observed)
  checks            runs that bound what the family does not refine (a held
                    direction, the time step): label, the two runs, the largest
                    difference and the error estimate it adds (the two-run GCI
                    with safety factor 3 and the assumed order, 3 |d| / (2^p - 1))
  history           dynamic only: rows [t, ux, uy, uz, err_ux, err_uy, err_uz]
                    at every output time, extrapolated point by point, errors
                    including the checks' differences at that time
  ccx, command      ccx's version line and the command that reproduces the entry
"""
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

from gen.scene import ROOT

DATA = ROOT / "references" / "data" / "calculix_silicone.json"
# the seed cantilever (Table 3, models/cantilever_bend_100N_nu03.toml): the bench's reference
CANTILEVER = ROOT / "references" / "data" / "calculix_cantilever.json"


@dataclass
class ReferenceData:
    name: str
    scene: str
    sets: list
    analysis: str
    sensor: str
    meshes: list
    grading: str
    refined: str
    ratio: float
    per_mesh: list
    value: list
    error: list
    order: list
    ccx: str
    command: str
    checks: list = field(default_factory=list)
    history: list = field(default_factory=list)    # [(t, [ux, uy, uz], [err ...])]
    note: str = ""

    def relative_error(self, component=2):
        """Error estimate of a component of the final value as a fraction of it
        (static) or of the largest |u| of that component over the history (dynamic)."""
        if self.history:
            scale = max(abs(u[component]) for _, u, _ in self.history)
            return max(e[component] for _, _, e in self.history) / scale
        return self.error[component] / abs(self.value[component])

    def at(self, t, tol=1e-9):
        """(u, err) of the history at output time t (KeyError if t is not one)."""
        for tt, u, e in self.history:
            if abs(tt - t) <= tol:
                return u, e
        raise KeyError(f"{self.name}: no output at t = {t!r}")


def _load(path=DATA):
    return json.loads(Path(path).read_text(encoding="utf-8"))


def names(path=DATA):
    return sorted(_load(path)["references"])


def reference_data(name, path=DATA):
    """The committed reference `name` (ReferenceData); KeyError naming the known ones."""
    refs = _load(path)["references"]
    if name not in refs:
        raise KeyError(f"{path}: no CalculiX reference {name!r} (have: {', '.join(sorted(refs))})")
    d = dict(refs[name])
    hist = d.pop("history", None)
    rows = []
    if hist:
        for r in hist["rows"]:
            rows.append((r[0], r[1:4], r[4:7]))
    return ReferenceData(name=name, history=rows, **d)


def _r(x, digits=7):
    """A float rounded to `digits` significant digits (ccx prints 7), JSON-safe."""
    if x is None or not math.isfinite(x):
        return None
    return float(f"{x:.{digits - 1}e}")


def entry(study, sensor, command, checks=(), note=""):
    """The JSON entry of a calculix.study.Study and its checks (calculix.study.Check)."""
    p = study.problem
    ex = study.tip[sensor]
    value = [e.value for e in ex]
    err = [e.error for e in ex]
    checks = list(checks)
    add_final = [sum(c.final_error[k] for c in checks) for k in range(3)]
    out = {
        "scene": Path(p.path).stem, "sets": list(study.sets), "analysis": p.analysis, "sensor": sensor,
        "meshes": [r.label for r in study.runs], "grading": study.grading.spec() or "uniform",
        "refined": study.refined, "ratio": study.ratio,
        "per_mesh": [{"mesh": r.label, "elements": r.elements, "nodes": r.nodes, "wall_s": round(r.wall_s, 1),
                      "iterations": r.iterations, "u": [_r(x) for x in r.histories[sensor][-1][1]]}
                     for r in study.runs],
        "value": [_r(x) for x in value], "error": [_r(e + a, 3) for e, a in zip(err, add_final)],
        "order": [None if e.order is None else round(e.order, 3) for e in ex],
        "checks": [c.as_dict() for c in checks],
        "ccx": study.ccx_version, "command": command, "note": note,
    }
    if p.analysis == "dynamic":
        rows = []
        extra = {}
        for c in checks:
            for t, d in c.diff_history():
                extra.setdefault(round(t, 12), [0.0, 0.0, 0.0])
                for k in range(3):
                    extra[round(t, 12)][k] += c.factor * abs(d[k])
        for t, _, u, e in study.history(sensor):
            key = round(t, 12)
            if checks and key not in extra:
                continue                     # only times every check has
            a = extra.get(key, [0.0, 0.0, 0.0])
            rows.append([_r(t, 9)] + [_r(x) for x in u] + [_r(e[k] + a[k], 3) for k in range(3)])
        out["history"] = {"columns": ["t", "ux", "uy", "uz", "err_ux", "err_uy", "err_uz"], "rows": rows}
        last = rows[-1]
        out["value"] = last[1:4]
        out["error"] = last[4:7]
    return out


def record(name, entry_dict, path=DATA):
    """Write (or replace) one entry of the data file, keeping the others."""
    path = Path(path)
    doc = _load(path) if path.exists() else {}
    what = ("the seed cantilever (Table 3)" if Path(path).resolve() == CANTILEVER.resolve()
            else "the silicone strip scenes")
    doc.setdefault("about", f"CalculiX (ccx, C3D20R) references for {what}, one mesh study "
                   "each; written by `python3 -m calculix ... --record NAME`, read by "
                   "calculix.reference_data(NAME); see calculix/data.py for the fields.")
    doc.setdefault("references", {})[name] = entry_dict
    doc["references"] = dict(sorted(doc["references"].items()))
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(_dump(doc) + "\n", encoding="utf-8")
    return path


def _dump(obj, indent=0):
    """JSON with dicts indented, lists of numbers on one line and lists of lists
    one inner list a line (readable, small diffs)."""
    pad = " " * indent
    if isinstance(obj, dict):
        if not obj:
            return "{}"
        items = [f'{pad} {json.dumps(k)}: {_dump(v, indent + 1)}' for k, v in obj.items()]
        return "{\n" + ",\n".join(items) + f"\n{pad}}}"
    if isinstance(obj, list):
        if all(not isinstance(x, (dict, list)) for x in obj):
            return "[" + ", ".join(json.dumps(x) for x in obj) + "]"
        items = [f"{pad} {_dump(x, indent + 1)}" for x in obj]
        return "[\n" + ",\n".join(items) + f"\n{pad}]"
    return json.dumps(obj)
