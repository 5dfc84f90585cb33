"""The mesh study: the same scene on 2-3 C3D20R meshes refined by a constant
factor, ccx runs (cached), and Richardson extrapolation of every sensor's
displacement components (final values; for dynamics also the whole history,
time point by time point)."""
import csv
import math
from dataclasses import dataclass, field
from pathlib import Path

from calculix.deck import write_deck
from calculix.extrapolate import richardson
from calculix.results import history
from calculix.run import CACHE, run_deck
from calculix.scene import read_scene


def parse_mesh(text):
    """'NXxNYxNZ' -> (nx, ny, nz)."""
    try:
        n = tuple(int(x) for x in str(text).lower().split("x"))
    except ValueError:
        n = ()
    if len(n) != 3 or min(n) < 1:
        raise ValueError(f"mesh {text!r}: expected NXxNYxNZ with positive integers, e.g. 16x4x2")
    return n


def default_base(prob):
    """Coarsest default mesh: two elements through the height h, an even count
    along b with elements at most twice as wide as high, and axial elements about
    3 h long (ccx needs a few hundred Newton iterations for the nearly
    incompressible large-deflection cases, so the finest of three meshes has to
    stay near 15,000 degrees of freedom)."""
    nz = 2
    ny = max(2, 2 * math.ceil(prob.b / (2 * prob.h)))
    nx = max(2, round(prob.length / (6 * prob.h)))
    return nx, ny, nz


def refine(base, levels=3, ratio=2):
    return [tuple(n * ratio**k for n in base) for k in range(levels)]


def check_meshes(meshes):
    """The constant refinement ratio of a mesh sequence (ValueError if it is not one)."""
    if len(meshes) < 2:
        raise ValueError("a mesh study needs 2 or 3 meshes")
    if len(meshes) > 3:
        raise ValueError(f"{len(meshes)} meshes: Richardson extrapolation here takes 2 or 3")
    ratios = {meshes[k + 1][i] / meshes[k][i] for k in range(len(meshes) - 1) for i in range(3)}
    if len(ratios) != 1 or min(ratios) <= 1:
        raise ValueError("meshes " + ", ".join("x".join(map(str, m)) for m in meshes)
                         + ": expected every count refined by one constant factor > 1")
    return ratios.pop()


@dataclass
class Run:
    mesh: tuple
    elements: int
    nodes: int
    wall_s: float
    directory: str
    histories: dict          # sensor -> [(time, [ux, uy, uz])]

    @property
    def label(self):
        return "x".join(map(str, self.mesh))


@dataclass
class Study:
    problem: object
    ratio: float
    runs: list
    tip: dict = field(default_factory=dict)     # sensor -> [Extrapolation per component]
    order: float = None                         # assumed order (two meshes)

    def final(self, sensor):
        """Extrapolated final displacement [ux, uy, uz] and error estimates of a sensor."""
        return [e.value for e in self.tip[sensor]], [e.error for e in self.tip[sensor]]

    def history(self, sensor):
        """[(time, per-mesh [u], extrapolated [u], error [u])] over the common output times."""
        hs = [dict((round(t, 12), u) for t, u in r.histories[sensor]) for r in self.runs]
        times = sorted(set.intersection(*(set(h) for h in hs)))
        out = []
        for t in times:
            scale = max(abs(x) for h in hs for x in h[t])
            ex = [self._extrapolate([h[t][c] for h in hs], scale) for c in range(3)]
            out.append((t, [h[t] for h in hs], [e.value for e in ex], [e.error for e in ex]))
        return out

    def _extrapolate(self, vals, scale):
        """Richardson on one component; differences below 1e-6 of the largest
        component (`scale`) are round-off: ccx's .dat prints 7 digits."""
        return richardson(vals, self.ratio, order=self.order, tiny=1e-6 * scale)

    def write_history_csv(self, path, sensor):
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        labels = [r.label for r in self.runs]
        with open(path, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(["time"] + [f"{c}_{lab}" for lab in labels for c in ("ux", "uy", "uz")]
                       + ["ux", "uy", "uz", "err_ux", "err_uy", "err_uz"])
            for t, per, ex, err in self.history(sensor):
                w.writerow([f"{t:.9g}"] + [f"{x:.7e}" for u in per for x in u]
                           + [f"{x:.7e}" for x in ex] + [f"{x:.2e}" for x in err])
        return path

    def as_dict(self):
        return {"scene": self.problem.path, "analysis": self.problem.analysis, "ratio": self.ratio,
                "meshes": [{"mesh": r.label, "elements": r.elements, "nodes": r.nodes, "wall_s": r.wall_s,
                            "final": {s: h[-1][1] for s, h in r.histories.items()}} for r in self.runs],
                "extrapolated": {s: [e.as_dict() for e in ex] for s, ex in self.tip.items()}}


def reference(scene, sets=(), meshes=None, levels=3, ratio=2, order=None,
              increments=None, threads=1, cache=CACHE, log=None):
    """Run the mesh study of a scene; `meshes` a list of (nx, ny, nz) (default: the
    default base refined `levels` times by `ratio`)."""
    prob = read_scene(scene, sets)
    meshes = [tuple(m) for m in (meshes or refine(default_base(prob), levels, ratio))]
    r = check_meshes(meshes)
    if len(meshes) == 2 and order is None:
        raise ValueError("two meshes need an assumed order (order=...); three give the observed order")
    runs = []
    for m in meshes:
        text, mesh, sets_ = write_deck(prob, *m, increments=increments)
        if log:
            log(f"mesh {mesh.label}: {len(mesh.elements)} C3D20R, {len(mesh.coords)} nodes ...")
        d, info = run_deck(text, cache=cache, threads=threads)
        hist = {name: history(d / "job.dat", nset) for name, nset, _ in sets_}
        last = {name: h[-1][0] for name, h in hist.items()}
        end = 1.0 if prob.analysis == "static" else prob.t_end
        for name, t in last.items():
            if abs(t - end) > 1e-6 * end:
                raise RuntimeError(f"ccx stopped at time {t:g} of {end:g} on mesh {mesh.label} ({d})")
        runs.append(Run(m, len(mesh.elements), len(mesh.coords), info["wall_s"], str(d), hist))
    st = Study(prob, r, runs, order=order if len(meshes) == 2 else None)
    for name, _ in prob.sensors:
        finals = [run.histories[name][-1][1] for run in runs]
        scale = max(abs(x) for u in finals for x in u)
        st.tip[name] = [st._extrapolate([u[c] for u in finals], scale) for c in range(3)]
    return st
