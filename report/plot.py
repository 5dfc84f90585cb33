"""./build.sh plot RUN_DIR: PNG plots of a run directory.

  sensors.png  sensor displacement components against time (dynamic) or load
               factor (static; modal runs about the static state: its load path)
  energy.png   kinetic, strain, potential and total energy (dynamic runs)
  modes.png    modal runs: one panel per mode (up to 16), the centreline of the
               state the modes are about and displaced by the drawn mode scale
  beam.png     the last ParaView frame (results.pvd) drawn in 3-D, coloured by
               displacement magnitude
  joints.png   the angle or displacement, rate and effort of every joint with an
               axis and every actuator (joints.csv, actuators.csv; plot_joints.py)
  reactions.png  every constraint's reaction force and moment (reactions.csv)
  path.png     arc-length runs (static.method = "arc_length"): the load factor
               against each sensor's displacement components, the limit points
               and bifurcations (summary.json critical_points) marked
  pull.png     runs with prescribed_motion constraints: each one's reaction
               along the point's displacement against that displacement (the
               force needed to pull or press it; e.g. a knot tightened)

Every title names the scene; a run that did not converge or was interrupted
says so on every plot.  Displacement axes span at least 1e-6 of the model
length (said on the axis when it applies), so round-off is not drawn as a signal.
"""
import csv
import json
import sys
import textwrap
import xml.etree.ElementTree as ET
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

FLOOR = 1e-6          # smallest displacement-axis range, relative to the model length
MAX_MODE_PANELS = 16


def read_csv(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def model_length(run):
    """The model length (the longest beam, m) from model.dat, or None."""
    p = run / "model.dat"
    if p.exists():
        with open(p) as fh:
            for line in fh:          # the scene record (gen/scene/model_file.py)
                if line.startswith("scene "):
                    for tok in line.split()[1:]:
                        if tok.startswith("length_scale="):
                            return float(tok.split("=", 1)[1])
                if line.startswith("q0"):
                    break
    return None


def status_note(summary):
    """'interrupted at ...' or 'NOT converged: <error>' for runs that did not finish; None otherwise."""
    if summary.get("interrupted", False):
        if summary.get("analysis") == "dynamic" and summary.get("time") is not None:
            return f"interrupted at t = {summary['time']:.6g} s"
        if summary.get("load_factor") is not None:
            return f"interrupted at load factor = {summary['load_factor']:.6g}"
        return "interrupted"
    if not summary.get("converged", False):
        return f"NOT converged: {summary.get('error') or 'no error message'}"
    return None


def decorate(fig, summary, what):
    """Suptitle 'SCENE: what' and, for unfinished runs, the status in red below it."""
    note = status_note(summary)
    title = f"{summary['scene']}: {what}"
    if note:
        title += " (NOT converged)" if note.startswith("NOT") else " (interrupted)"
    fig.suptitle(title, fontsize=11)
    top = 0.95
    if note:
        lines = textwrap.wrap(note, 110, break_on_hyphens=False)
        fig.text(0.5, 0.955, "\n".join(lines), ha="center", va="top", color="red", fontsize=8,
                 gid="status")
        top = 0.95 - 0.025 * len(lines)
    return top


def floor_ylim(ax, length, unit="m"):
    """If the data vary by less than FLOOR * length, show exactly that range about their
    middle (exact zeros and round-off alike), and say so on the axis."""
    if not length:
        return
    lo, hi = ax.dataLim.intervaly
    span = FLOOR * length
    if np.isfinite(lo) and np.isfinite(hi) and hi - lo < span:
        mid = 0.5 * (lo + hi)
        ax.set_ylim(mid - span / 2, mid + span / 2)
        ax.text(0.99, 0.03, f"axis range floor {span:.1g} {unit} ({FLOOR:g} of the model length)",
                transform=ax.transAxes, ha="right", va="bottom", fontsize=7, color="0.35", gid="floor")


def fig_sensors(run, summary, length):
    rows = read_csv(run / "sensors.csv")
    names = list(dict.fromkeys(r["sensor"] for r in rows))
    xlabel = "time (s)" if summary["analysis"] == "dynamic" else "load factor"
    what = "sensor displacements"
    if summary["analysis"] in ("modal", "buckling"):
        what += " on the load path of the static state"
    fig, ax = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    # a static run of one increment has two states, the reference and the end:
    # drawn as two points, not as a line that would suggest a path between them
    one = summary["analysis"] != "dynamic" and len({r["step"] for r in rows}) <= 2
    for n in names:
        r = [x for x in rows if x["sensor"] == n]
        t = [float(x["time"]) for x in r]
        for k, c in enumerate(("ux", "uy", "uz")):
            ax[k].plot(t, [float(x[c]) for x in r], marker="o" if one else "." if len(r) < 60 else None,
                       lw=0 if one else 1, label=n)
    if one:
        ax[0].text(0.5, 0.97, "one load increment: the reference and the final state only (no path between; "
                   "more static.load_steps draw it)", transform=ax[0].transAxes, ha="center", va="top",
                   fontsize=7, color="0.3", gid="one_increment")
    for k, c in enumerate(("ux", "uy", "uz")):
        ax[k].set_ylabel(f"{c} (m)")
        ax[k].grid(True, lw=0.3)
        floor_ylim(ax[k], length)
    if names:
        ax[0].legend(fontsize=8)
    ax[2].set_xlabel(xlabel)
    top = decorate(fig, summary, what)
    fig.tight_layout(rect=(0, 0, 1, top))
    return fig


def fig_energy(run, summary):
    e = read_csv(run / "energy.csv")
    t = [float(x["time"]) for x in e]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for k, label in (("kinetic", "kinetic"), ("strain", "strain"), ("gravity", "gravity potential"),
                     ("load_potential", "load potential"), ("total", "total")):
        ax.plot(t, [float(x[k]) for x in e], label=label, lw=1.5 if k == "total" else 1)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("energy (J)")
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=8)
    top = decorate(fig, summary, "energy balance")
    fig.tight_layout(rect=(0, 0, 1, top))
    return fig


def read_vtu(path):
    """Points, displacements, cells (type, connectivity) and field data of a .vtu."""
    from report import vtu
    d = vtu.read(path)
    return d["points"], d["displacement"], vtu.cells(d), d["fields"]


def collection(run, name):
    """(file, time value) of each data set of a .pvd collection (empty if absent)."""
    pvd = run / name
    if not pvd.exists():
        return []
    return [(run / d.get("file"), float(d.get("timestep")))
            for d in ET.parse(pvd).getroot().findall("Collection/DataSet")]


def direction_label(v):
    names = "xyz"
    k = int(np.argmax(np.abs(v)))
    if abs(v[k]) > 1.0 - 5e-7:          # within 1e-3 rad of a global axis
        return f"{'-' if v[k] < 0 else ''}{names[k]} (m)"
    return f"along ({v[0]:.2f}, {v[1]:.2f}, {v[2]:.2f}) (m)"


def perpendicular(e1):
    a = np.zeros(3)
    a[int(np.argmin(np.abs(e1)))] = 1.0
    u = a - (a @ e1) * e1
    return u / np.linalg.norm(u)


def mode_panel(ax, vtu, length):
    """One mode: the centreline of the base state (grey) and displaced by the mode (blue),
    projected on the beam's main direction and the direction the mode moves it most."""
    pts, disp, cells, fields = read_vtu(vtu)
    lines = [c for ty, c in cells if ty == 4]
    idx = np.concatenate(lines) if lines else np.zeros(0, dtype=int)
    base, d = pts[idx] - disp[idx], disp[idx]
    c = base - base.mean(axis=0)
    e1 = np.linalg.svd(c, full_matrices=False)[2][0] if np.ptp(c) > 0 else np.array([1.0, 0, 0])
    e1 = e1 * np.sign(e1[np.argmax(np.abs(e1))])
    perp = d - np.outer(d @ e1, e1)
    tol = 1e-9 * (length or 1.0)
    note = None
    if np.abs(perp).max(initial=0.0) > tol:
        e2 = np.linalg.svd(perp, full_matrices=False)[2][0]
    else:
        e2 = perpendicular(e1)
        note = "axial mode" if np.abs(d).max(initial=0.0) > tol else "the centreline does not move (torsion)"
    e2 = e2 * np.sign(e2[np.argmax(np.abs(e2))])
    for line in lines:
        b = pts[line] - disp[line]
        ax.plot(b @ e1, b @ e2, color="0.6", lw=1, ls="--")
        ax.plot(pts[line] @ e1, pts[line] @ e2, color="C0", lw=1.5)
    value = (f"load factor {fields['LOAD_FACTOR']:.6g}" if "LOAD_FACTOR" in fields      # buckling
             else f"{fields.get('FREQUENCY_HZ', float('nan')):.5g} Hz")
    ax.set_title(f"mode {int(fields.get('MODE', 0))}: {value}, "
                 f"scale {fields.get('MODE_SCALE', float('nan')):.3g} m", fontsize=9)
    ax.set_xlabel(direction_label(e1), fontsize=8)
    ax.set_ylabel(direction_label(e2), fontsize=8)
    ax.tick_params(labelsize=7)
    ax.grid(True, lw=0.3)
    floor_ylim(ax, length)
    if note:
        ax.text(0.5, 0.75, note, transform=ax.transAxes, ha="center", fontsize=8, color="0.3")


def fig_modes(run, summary, length):
    sets = collection(run, "modes.pvd")
    if not sets:
        return None
    shown = sets[:MAX_MODE_PANELS]
    ncol = min(3, len(shown))
    nrow = (len(shown) + ncol - 1) // ncol
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.2 * ncol, 3.2 * nrow + 0.8), squeeze=False)
    for ax, (vtu, _) in zip(axes.flat, shown):
        mode_panel(ax, vtu, length)
    for ax in list(axes.flat)[len(shown):]:
        ax.set_visible(False)
    what = "mode shapes (grey: the state the modes are about)"
    if len(sets) > len(shown):
        what += f", first {len(shown)} of {len(sets)}"
    top = decorate(fig, summary, what)
    fig.tight_layout(rect=(0, 0, 1, top))
    return fig


def fig_beam(vtu, summary, title):
    pts, disp, cells, _ = read_vtu(vtu)
    mag = np.linalg.norm(disp, axis=1)
    quads = [c for ty, c in cells if ty == 9]
    lines = [c for ty, c in cells if ty == 4]
    fig = plt.figure(figsize=(8, 6))
    ax = fig.add_subplot(111, projection="3d")
    polys = [pts[c] for c in quads]
    vals = np.array([mag[c].mean() for c in quads]) if quads else np.zeros(0)
    norm = plt.Normalize(vals.min() if len(vals) else 0, vals.max() if len(vals) and vals.max() > 0 else 1)
    pc = Poly3DCollection(polys, facecolors=plt.cm.viridis(norm(vals)), edgecolors="none", linewidths=0)
    ax.add_collection3d(pc)
    for c in lines:
        ax.plot(*pts[c].T, color="k", lw=0.8)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    mid, span = (lo + hi) / 2, max((hi - lo).max(), 1e-9) / 2
    ax.set_xlim(mid[0] - span, mid[0] + span)
    ax.set_ylim(mid[1] - span, mid[1] + span)
    ax.set_zlim(mid[2] - span, mid[2] + span)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    sm = plt.cm.ScalarMappable(cmap="viridis", norm=norm)
    fig.colorbar(sm, ax=ax, shrink=0.6, label="|displacement| (m)")
    top = decorate(fig, summary, title)
    fig.tight_layout(rect=(0, 0, 1, top))
    return fig


def path_panel(ax, rows, summary, sensor):
    """Load factor against the displacement components of one sensor that move,
    with the critical points of the path marked (limit points: triangles,
    bifurcations: squares)."""
    r = [x for x in rows if x["sensor"] == sensor]
    lam = [float(x["time"]) for x in r]
    big = max((abs(float(x[c])) for x in r for c in ("ux", "uy", "uz")), default=0.0)
    comps = [c for c in ("ux", "uy", "uz") if any(abs(float(x[c])) > 1e-9 * big for x in r)] or ["ux"]
    for c in comps:
        ax.plot([float(x[c]) for x in r], lam, marker="." if len(r) < 80 else None, ms=3, lw=1,
                label=f"{sensor} {c}")
    for cp in summary.get("critical_points", []):
        u = cp.get("displacement", {}).get(sensor)
        if not u or cp.get("load_factor") is None:
            continue
        lim = cp["type"] == "limit_point"
        for c in comps:
            v = u["xyz".index(c[1])]
            if v is None:
                continue
            ax.plot([v], [cp["load_factor"]], "v" if lim else "s", color="red" if lim else "tab:blue", ms=7,
                    mfc="none", mew=1.5)
            ax.annotate(f"{'limit' if lim else 'bifurcation'} {cp['load_factor']:.4g}", (v, cp["load_factor"]),
                        textcoords="offset points", xytext=(6, 4), fontsize=7)
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel(f"displacement of {sensor} (m)")
    ax.set_ylabel("load factor")
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=7)


def fig_path(run, summary):
    rows = read_csv(run / "sensors.csv")
    names = list(dict.fromkeys(r["sensor"] for r in rows))
    fig, axes = plt.subplots(1, max(len(names), 1), figsize=(6 * max(len(names), 1), 5), squeeze=False)
    for ax, n in zip(axes[0], names):
        path_panel(ax, rows, summary, n)
    top = decorate(fig, summary, "load-displacement path (arc length)")
    fig.tight_layout(rect=(0, 0, 1, top))
    return fig


def fig_pull(run, summary):
    """pull.png: per prescribed_motion of reactions.csv, the reaction force's
    component along the point's displacement from its first row against the
    displacement's length; None when there is none."""
    p = run / "reactions.csv"
    rows = [r for r in read_csv(p) if r["type"] == "prescribed_motion"] if p.exists() else []
    if not rows:
        return None
    fig, ax = plt.subplots(figsize=(7, 5))
    for name in dict.fromkeys(r["name"] for r in rows):
        mine = [r for r in rows if r["name"] == name]
        x0 = np.array([float(mine[0][k]) for k in "xyz"])
        u = np.array([[float(r[k]) for k in "xyz"] for r in mine]) - x0
        F = np.array([[float(r[k]) for k in ("Fx", "Fy", "Fz")] for r in mine])
        d = np.linalg.norm(u, axis=1)
        along = np.einsum("ij,ij->i", F, u) / np.where(d > 0, d, 1.0)
        ax.plot(d * 1e3, along, marker=".", label=f"{name} ({mine[0]['at']})")
    ax.set_xlabel("displacement of the point (mm)")
    ax.set_ylabel("reaction along the displacement (N)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    top = decorate(fig, summary, "prescribed motions: force against displacement")
    fig.tight_layout(rect=(0, 0, 1, top))
    return fig


def figures(run):
    """The plots of a run directory as {PNG file name: matplotlib Figure} (not saved)."""
    run = Path(run)
    summary = json.loads((run / "summary.json").read_text())
    length = model_length(run)
    figs = {}
    rows = read_csv(run / "sensors.csv")
    if summary["analysis"] not in ("modal", "buckling") or len({r["step"] for r in rows}) > 1:
        figs["sensors.png"] = fig_sensors(run, summary, length)
    if (run / "energy.csv").exists():
        figs["energy.png"] = fig_energy(run, summary)
    if "critical_points" in summary:
        figs["path.png"] = fig_path(run, summary)
    from report.plot_joints import fig_joints, fig_reactions
    for name, fn in (("joints.png", fig_joints), ("reactions.png", fig_reactions)):
        f = fn(run, summary, decorate)
        if f is not None:
            figs[name] = f
    pull = fig_pull(run, summary)
    if pull is not None:
        figs["pull.png"] = pull
    if summary["analysis"] in ("modal", "buckling"):
        f = fig_modes(run, summary, length)
        if f is not None:
            figs["modes.png"] = f
    frames = collection(run, "results.pvd")
    if frames:
        vtu, t = frames[-1]
        where = {"dynamic": f"t = {t:.4g} s", "static": f"load factor {t:.4g}",
                 "modal": f"the state the modes are about (load factor {t:.4g})",
                 "buckling": f"the state the modes are about (load factor {t:.4g})"}[summary["analysis"]]
        figs["beam.png"] = fig_beam(vtu, summary, where)
    return figs


def main(argv):
    if len(argv) != 1 or argv[0] in ("-h", "--help"):
        print(__doc__.strip(), file=sys.stderr)
        return 0 if argv and argv[0] in ("-h", "--help") else 1
    from gen.pipeline import user_path
    run = user_path(argv[0])
    if not (run / "summary.json").exists() or not (run / "sensors.csv").exists():
        print(f"error: {run}: not a run directory (expected summary.json and sensors.csv)", file=sys.stderr)
        return 1
    figs = figures(run)
    for name, fig in figs.items():
        fig.savefig(run / name, dpi=110)
        plt.close(fig)
    summary = json.loads((run / "summary.json").read_text())
    if summary["analysis"] in ("modal", "buckling") and "modes.png" not in figs:
        print(f"note: {run}: no modes.pvd (ParaView output off: output.vtk_every = 0?): no modes.png",
              file=sys.stderr)
    print(f"wrote {', '.join(str(run / m) for m in figs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
