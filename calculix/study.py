"""The mesh study: the same scene on 2-3 C3D20R meshes refined by a constant
factor, ccx runs (cached), and Richardson extrapolation of every sensor's
displacement components (final values; for dynamics also the whole history,
time point by time point)."""
import csv
import math
from dataclasses import dataclass, field
from pathlib import Path

from calculix.deck import final_time, write_deck
from calculix.extrapolate import richardson
from calculix.mesh import Grading, parse_grading
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
    """(constant refinement ratio, refined directions) of a mesh sequence, or
    ValueError.  Every count is refined by one constant factor, or some counts are
    held fixed on every mesh (e.g. 16x2x2, 32x2x2, 64x2x2 refines the axis only:
    the extrapolation then removes the error of the refined directions only)."""
    if len(meshes) < 2:
        raise ValueError("a mesh study needs 2 or 3 meshes")
    if len(meshes) > 3:
        raise ValueError(f"{len(meshes)} meshes: Richardson extrapolation here takes 2 or 3")
    per_dir = [{meshes[k + 1][i] / meshes[k][i] for k in range(len(meshes) - 1)} for i in range(3)]
    refined = "".join(d for d, r in zip("xyz", per_dir) if r != {1.0})
    ratios = set().union(*(r for r in per_dir if r != {1.0}))
    if not refined or len(ratios) != 1 or min(ratios) <= 1:
        raise ValueError("meshes " + ", ".join("x".join(map(str, m)) for m in meshes)
                         + ": expected the counts refined by one constant factor > 1 (counts not refined "
                         "held fixed on every mesh)")
    return ratios.pop(), refined


@dataclass
class Run:
    mesh: tuple
    elements: int
    nodes: int
    wall_s: float
    directory: str
    histories: dict          # sensor -> [(time, [ux, uy, uz])]
    iterations: int = 0      # Newton iterations, all increments and attempts (ccx's .sta)
    ccx: str = ""            # ccx's version line

    @property
    def label(self):
        return "x".join(map(str, self.mesh))


def _iterations(sta):
    """Sum of the ITRS column of a ccx .sta file (0 if absent)."""
    total = 0
    try:
        lines = Path(sta).read_text(encoding="utf-8", errors="replace").splitlines()
    except OSError:
        return 0
    for ln in lines[2:]:
        parts = ln.split()
        if len(parts) >= 4:
            try:
                total += int(parts[3])
            except ValueError:
                pass
    return total


def run_mesh(prob, m, grading, increments=None, threads=1, cache=CACHE, log=None):
    """Run (or re-use) ccx on one mesh (nx, ny, nz) of a Problem; a Run."""
    text, mesh, sets_ = write_deck(prob, *m, increments=increments, grading=grading)
    if log:
        log(f"mesh {mesh.label}: {len(mesh.elements)} C3D20R, {len(mesh.coords)} nodes ...")
    d, info = run_deck(text, cache=cache, threads=threads)
    hist = {name: history(d / "job.dat", nset) for name, nset, _ in sets_}
    end = final_time(prob)
    for name, h in hist.items():
        if abs(h[-1][0] - end) > 1e-6 * end:
            raise RuntimeError(f"ccx stopped at time {h[-1][0]:g} of {end:g} on mesh {mesh.label} ({d})")
    return Run(tuple(m), len(mesh.elements), len(mesh.coords), info["wall_s"], str(d), hist,
               _iterations(d / "job.sta"), info.get("ccx", ""))


@dataclass
class Check:
    """Two runs differing in one thing the mesh family does not refine (a held
    section direction, the time step): `other` refines it by `ratio` over `base`.
    With an assumed order p the base run's error is about d / (1 - ratio^-p), d
    the difference; the estimate added to the reference is the two-run GCI with
    safety factor 3, 3 |d| / (ratio^p - 1) (|d| for ratio 2, p = 2)."""
    label: str
    base: Run
    other: Run
    sensor: str
    order: float = 2.0
    ratio: float = 2.0

    @property
    def factor(self):
        return 3.0 / (self.ratio**self.order - 1.0)

    def diff_history(self):
        """[(t, other - base)] over the common output times."""
        a = {round(t, 12): u for t, u in self.base.histories[self.sensor]}
        b = {round(t, 12): u for t, u in self.other.histories[self.sensor]}
        return [(t, [b[t][k] - a[t][k] for k in range(3)]) for t in sorted(set(a) & set(b))]

    @property
    def final_diff(self):
        return self.diff_history()[-1][1]

    @property
    def final_error(self):
        return [self.factor * abs(d) for d in self.final_diff]

    def max_diff(self):
        return [max(abs(d[k]) for _, d in self.diff_history()) for k in range(3)]

    def as_dict(self):
        return {"label": self.label, "base": self.base.label, "other": self.other.label,
                "assumed_order": self.order, "ratio": self.ratio, "factor": round(self.factor, 6),
                "final_diff": [float(f"{d:.3e}") for d in self.final_diff],
                "max_abs_diff": [float(f"{d:.3e}") for d in self.max_diff()],
                "wall_s": [round(self.base.wall_s, 1), round(self.other.wall_s, 1)]}


@dataclass
class Study:
    problem: object
    ratio: float
    runs: list
    tip: dict = field(default_factory=dict)     # sensor -> [Extrapolation per component]
    order: float = None                         # assumed order (two meshes)
    grading: Grading = Grading()
    refined: str = "xyz"                        # directions refined by `ratio` (the others held)
    sets: tuple = ()                            # the scene's --set overrides

    @property
    def ccx_version(self):
        return next((r.ccx for r in self.runs if r.ccx), "")

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
        """Richardson on one component; differences below 1e-5 of the largest
        component (`scale`) count as converged: ccx's .dat prints 7 digits and its
        Newton stops at 1e-6, so smaller differences are noise, and an order
        observed from noise (near 0) would blow the extrapolation up."""
        return richardson(vals, self.ratio, order=self.order, tiny=1e-5 * scale)

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
                "grading": self.grading.spec() or "uniform", "refined": self.refined,
                "meshes": [{"mesh": r.label, "elements": r.elements, "nodes": r.nodes, "wall_s": r.wall_s,
                            "final": {s: h[-1][1] for s, h in r.histories.items()}} for r in self.runs],
                "extrapolated": {s: [e.as_dict() for e in ex] for s, ex in self.tip.items()}}


def reference(scene, sets=(), meshes=None, levels=3, ratio=2, order=None,
              increments=None, threads=1, cache=CACHE, log=None, grading=None):
    """Run the mesh study of a scene; `meshes` a list of (nx, ny, nz) (default: the
    default base refined `levels` times by `ratio`); `grading` a calculix.mesh.Grading
    or its text ('x=geometric:8,z=geometric:3'; default uniform), the same for
    every mesh, so the family stays self-similar."""
    if grading is None or isinstance(grading, str):
        grading = parse_grading(grading)
    prob = read_scene(scene, sets)
    meshes = [tuple(m) for m in (meshes or refine(default_base(prob), levels, ratio))]
    r, refined = check_meshes(meshes)
    if len(meshes) == 2 and order is None:
        raise ValueError("two meshes need an assumed order (order=...); three give the observed order")
    runs = [run_mesh(prob, m, grading, increments, threads, cache, log) for m in meshes]
    st = Study(prob, r, runs, order=order if len(meshes) == 2 else None, grading=grading, refined=refined,
               sets=tuple(sets))
    for name, _ in prob.sensors:
        finals = [run.histories[name][-1][1] for run in runs]
        scale = max(abs(x) for u in finals for x in u)
        st.tip[name] = [st._extrapolate([u[c] for u in finals], scale) for c in range(3)]
    return st


def check(study, other_mesh=None, base_mesh=None, extra_sets=(), label="", order=2.0, ratio=None,
          increments=None, threads=1, cache=CACHE, log=None):
    """A Check of a study: `base_mesh` (a mesh of the study; default the one with
    the axial count of `other_mesh`, or the middle mesh) against `other_mesh`
    (default the same mesh) with the scene's overrides plus `extra_sets` (e.g.
    dynamic.dt halved).  `ratio` defaults to the refinement of the mesh counts,
    or 2 when only `extra_sets` differ."""
    by_mesh = {r.mesh: r for r in study.runs}
    if base_mesh is None:
        if other_mesh is not None:
            cands = [r.mesh for r in study.runs if r.mesh[0] == other_mesh[0]]
            if not cands:
                raise ValueError(f"check mesh {'x'.join(map(str, other_mesh))}: the study has no mesh with "
                                 f"{other_mesh[0]} axial elements to compare it with")
            base_mesh = cands[-1]
        else:
            base_mesh = study.runs[len(study.runs) // 2].mesh
    base_mesh = tuple(base_mesh)
    other_mesh = tuple(other_mesh or base_mesh)
    if base_mesh in by_mesh:
        base = by_mesh[base_mesh]
    else:
        base = run_mesh(study.problem, base_mesh, study.grading, increments, threads, cache, log)
    prob = read_scene(study.problem.path, list(study.sets) + list(extra_sets)) if extra_sets else study.problem
    other = run_mesh(prob, other_mesh, study.grading, increments, threads, cache, log)
    if ratio is None:
        rs = {o / b for o, b in zip(other_mesh, base_mesh) if o != b}
        if len(rs) > 1:
            raise ValueError(f"check {'x'.join(map(str, base_mesh))} -> {'x'.join(map(str, other_mesh))}: "
                             "expected the changed counts refined by one factor")
        ratio = rs.pop() if rs else 2.0
    sensor = study.problem.sensors[0][0]
    return Check(label or f"{base.label} -> {other.label}" + (f" with {' '.join(extra_sets)}" if extra_sets else ""),
                 base, other, sensor, order, ratio)
