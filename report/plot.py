"""./build.sh plot RUN_DIR: PNG plots of a run directory.

  sensors.png  sensor displacement components against time (dynamic), load factor
               (static) or mode (modal)
  energy.png   kinetic, strain, potential and total energy (dynamic runs)
  beam.png     the last ParaView frame (results.pvd) drawn in 3-D, coloured by
               displacement magnitude
"""
import csv
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402


def read_csv(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def plot_sensors(run, summary):
    rows = read_csv(run / "sensors.csv")
    names = list(dict.fromkeys(r["sensor"] for r in rows))
    xlabel = {"dynamic": "time (s)", "static": "load factor", "modal": "frequency (Hz)"}[summary["analysis"]]
    fig, ax = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    for n in names:
        r = [x for x in rows if x["sensor"] == n]
        t = [float(x["time"]) for x in r]
        for k, c in enumerate(("ux", "uy", "uz")):
            ax[k].plot(t, [float(x[c]) for x in r], marker="." if len(r) < 60 else None, lw=1, label=n)
    for k, c in enumerate(("ux", "uy", "uz")):
        ax[k].set_ylabel(f"{c} (m)")
        ax[k].grid(True, lw=0.3)
    ax[0].legend(fontsize=8)
    ax[0].set_title(f"{summary['scene']}: sensor displacements")
    ax[2].set_xlabel(xlabel)
    fig.tight_layout()
    fig.savefig(run / "sensors.png", dpi=110)
    plt.close(fig)


def plot_energy(run):
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
    ax.set_title("energy balance")
    fig.tight_layout()
    fig.savefig(run / "energy.png", dpi=110)
    plt.close(fig)


def read_vtu(path):
    """Points, displacements and cells (connectivity lists) of an ASCII .vtu."""
    root = ET.parse(path).getroot()
    piece = root.find("UnstructuredGrid/Piece")
    arr = lambda node: np.array(node.text.split(), dtype=float)
    pts = arr(piece.find("Points/DataArray")).reshape(-1, 3)
    disp = arr(piece.find("PointData/DataArray[@Name='displacement']")).reshape(-1, 3)
    cells = piece.find("Cells")
    conn = arr(cells.find("DataArray[@Name='connectivity']")).astype(int)
    offs = arr(cells.find("DataArray[@Name='offsets']")).astype(int)
    types = arr(cells.find("DataArray[@Name='types']")).astype(int)
    out, start = [], 0
    for o, ty in zip(offs, types):
        out.append((ty, conn[start:o]))
        start = o
    return pts, disp, out


def last_frame(run):
    pvd = run / "results.pvd"
    if not pvd.exists():
        return None, None
    sets = ET.parse(pvd).getroot().findall("Collection/DataSet")
    if not sets:
        return None, None
    return run / sets[-1].get("file"), float(sets[-1].get("timestep"))


def render_beam(vtu, out_png, title):
    pts, disp, cells = read_vtu(vtu)
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
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(out_png, dpi=110)
    plt.close(fig)


def main(argv):
    if len(argv) != 1 or argv[0] in ("-h", "--help"):
        print(__doc__.strip(), file=sys.stderr)
        return 0 if argv and argv[0] in ("-h", "--help") else 1
    from gen.paths import user_path
    run = user_path(argv[0])
    if not (run / "summary.json").exists() or not (run / "sensors.csv").exists():
        print(f"error: {run}: not a run directory (expected summary.json and sensors.csv)", file=sys.stderr)
        return 1
    import json
    summary = json.loads((run / "summary.json").read_text())
    plot_sensors(run, summary)
    made = ["sensors.png"]
    if (run / "energy.csv").exists():
        plot_energy(run)
        made.append("energy.png")
    vtu, t = last_frame(run)
    if vtu is not None:
        render_beam(vtu, run / "beam.png", f"{summary['scene']} at {'t' if summary['analysis'] == 'dynamic' else 'load'} = {t:.4g}")
        made.append("beam.png")
    print(f"wrote {', '.join(str(run / m) for m in made)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
