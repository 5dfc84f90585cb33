"""./build.sh animate RUN_DIR (beamkit animate): the run's ParaView frames
(results.pvd) as a video, drawn offscreen (matplotlib's Agg: no display) and
encoded by ffmpeg.

  RUN_DIR/animation.mp4    H.264, one video frame per ParaView frame
  RUN_DIR/animation.gif    with --gif instead

Each frame shows the beams' surfaces coloured by a field (--field: a point
array's magnitude, default displacement, or a cell array such as
strain_energy_density) on one colour scale for the whole video, the sensors'
paths up to the frame's time as traces, a scale bar, the scene's name and the
time (or load factor).  The view is fixed (orthographic, the box of every
frame).  Options: --field NAME, --gif, --fps N (default 10), --out FILE.
"""
import json
import shutil
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

from report.plot import collection, read_csv, status_note  # noqa: E402

UNITS = {"displacement": "m", "section_force": "N", "section_moment": "N m", "section_force_stress": "Pa",
         "section_moment_stress": "Pa", "strain_energy_density": "J/m³"}
SKIP = ("points", "connectivity", "offsets", "types", "fields")


class AnimateError(Exception):
    pass


def _frames(run):
    from report import vtu
    frames = collection(run, "results.pvd")
    if not frames:
        raise AnimateError(f"{run}: no ParaView frames (results.pvd): was output.vtk_every = 0?")
    return [(vtu.read(path), t) for path, t in frames]


def _values(data, field):
    """Per cell: the field's value (a cell array, or the mean of a point array's
    magnitude over the cell's points)."""
    from report import vtu
    cells = vtu.cells(data)
    a = data[field]
    npts, ncell = len(data["points"]), len(cells)
    if a.shape[0] == ncell and npts != ncell:
        return np.abs(a) if a.ndim == 1 else np.linalg.norm(a, axis=1)
    mag = np.abs(a) if a.ndim == 1 else np.linalg.norm(a, axis=1)
    return np.array([mag[c].mean() for _, c in cells])



def color_range(vals):
    """(min, max) of the finite values of every frame: a rigid body has no
    section force (NaN there, drawn grey), which must not set the scale."""
    finite = [v[np.isfinite(v)] for v in vals]
    finite = [v for v in finite if len(v)]
    if not finite:
        return 0.0, 1.0
    return min(float(v.min()) for v in finite), max(float(v.max()) for v in finite)

def _nice(x):
    """The largest of 1, 2, 5 x 10^k at most x."""
    e = np.floor(np.log10(x))
    for m in (5.0, 2.0, 1.0):
        if m * 10 ** e <= x:
            return m * 10 ** e
    return 10 ** e


def _label(v):
    return f"{v:g} m" if v >= 1 else f"{v * 1e3:g} mm" if v >= 1e-3 else f"{v * 1e6:g} µm"


def _traces(run):
    """{sensor: (times, positions[n, 3])} from sensors.csv."""
    rows = read_csv(run / "sensors.csv")
    out = {}
    for r in rows:
        out.setdefault(r["sensor"], []).append((float(r["time"]), float(r["x"]), float(r["y"]), float(r["z"])))
    return {k: (np.array([v[0] for v in vs]), np.array([v[1:] for v in vs])) for k, vs in out.items()}


def render(run, field="displacement", fps=10, gif=False, out=None, log=print):
    """Writes the video; returns its path."""
    from report import vtu
    run = Path(run)
    summary = json.loads((run / "summary.json").read_text())
    frames = _frames(run)
    first = frames[0][0]
    fields = [k for k in first if k not in SKIP]
    if field not in fields:
        raise AnimateError(f"--field {field!r}: not a field of the frames (fields: {', '.join(fields)})")
    vals = [_values(d, field) for d, _ in frames]
    vmin, vmax = color_range(vals)
    norm = plt.Normalize(vmin, vmax if vmax > vmin else vmin + 1.0)
    allp = np.vstack([d["points"] for d, _ in frames])
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    mid, half = (lo + hi) / 2, max((hi - lo).max(), 1e-9) / 2 * 1.05
    bar = _nice(half * 0.8)
    traces = _traces(run) if (run / "sensors.csv").exists() else {}
    kind = summary.get("analysis")
    note = status_note(summary)
    out = Path(out) if out else run / ("animation.gif" if gif else "animation.mp4")
    fig = plt.figure(figsize=(8, 6), dpi=100)
    images, enc = [], None
    if not gif:
        ff = shutil.which("ffmpeg")
        if not ff:
            raise AnimateError("ffmpeg is not installed (Debian package ffmpeg; ./build.sh animate installs it "
                               "when run as root), or use --gif")
        w, h = fig.canvas.get_width_height()
        enc = subprocess.Popen([ff, "-y", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgb24", "-s",
                                f"{w}x{h}", "-r", str(fps), "-i", "-", "-c:v", "libx264", "-pix_fmt", "yuv420p",
                                "-r", str(fps), str(out)], stdin=subprocess.PIPE)
    try:
        for k, ((d, t), v) in enumerate(zip(frames, vals)):
            fig.clf()
            ax = fig.add_subplot(111, projection="3d")
            ax.set_proj_type("ortho")
            cells = vtu.cells(d)
            pts = d["points"]
            quads = [(c, val) for (ty, c), val in zip(cells, v) if ty == 9]
            if quads:
                qv = np.array([x for _, x in quads], dtype=float)
                colors = plt.cm.viridis(norm(qv))
                colors[~np.isfinite(qv)] = (0.75, 0.75, 0.75, 1.0)
                ax.add_collection3d(Poly3DCollection([pts[c] for c, _ in quads], edgecolors="none", linewidths=0,
                                                     facecolors=colors))
            for (ty, c) in cells:
                if ty == 4:
                    ax.plot(*pts[c].T, color="k", lw=0.8)
            for name, (ts, xs) in traces.items():
                sel = ts <= t + 1e-12 * max(1.0, abs(t))
                if sel.any():
                    ax.plot(*xs[sel].T, lw=0.9, label=name)
                    ax.scatter(*xs[sel][-1], s=10)
            ax.set_xlim(mid[0] - half, mid[0] + half)
            ax.set_ylim(mid[1] - half, mid[1] + half)
            ax.set_zlim(mid[2] - half, mid[2] + half)
            ax.set_xlabel("x (m)")
            ax.set_ylabel("y (m)")
            ax.set_zlabel("z (m)")
            x0 = np.array([mid[0] - half * 0.95, mid[1] - half * 0.95, mid[2] - half * 0.95])
            ax.plot([x0[0], x0[0] + bar], [x0[1]] * 2, [x0[2]] * 2, color="k", lw=3)
            ax.text(x0[0] + bar / 2, x0[1], x0[2] + 0.06 * half, _label(bar), ha="center", fontsize=8)
            if traces:
                ax.legend(loc="upper right", fontsize=7)
            sm = plt.cm.ScalarMappable(cmap="viridis", norm=norm)
            unit = UNITS.get(field, "")
            name = f"|{field}|" if first[field].ndim > 1 else field
            fig.colorbar(sm, ax=ax, shrink=0.6, label=f"{name} ({unit})" if unit else name)
            when = f"t = {t:.4g} s" if kind == "dynamic" else f"load factor {t:.4g}"
            fig.suptitle(f"{summary['scene']}: {when}" + (" (not converged)" if note else ""), fontsize=11)
            fig.canvas.draw()
            rgb = np.asarray(fig.canvas.buffer_rgba())[..., :3]
            if enc:
                enc.stdin.write(np.ascontiguousarray(rgb).tobytes())
            else:
                from PIL import Image
                images.append(Image.fromarray(np.array(rgb)))
            if log and (k + 1) % 10 == 0:
                log(f"  frame {k + 1} of {len(frames)}")
    finally:
        plt.close(fig)
        if enc:
            enc.stdin.close()
            rc = enc.wait()
            if rc != 0:
                raise AnimateError(f"ffmpeg failed ({rc}) writing {out}")
    if gif:
        images[0].save(out, save_all=True, append_images=images[1:], duration=int(1000 / fps), loop=0)
    return out


def main(argv):
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__.strip(), file=sys.stderr)
        return 0 if argv else 64
    opts = {"field": "displacement", "fps": 10, "gif": False, "out": None}
    run, i = None, 0
    while i < len(argv):
        a = argv[i]
        if a == "--gif":
            opts["gif"] = True
        elif a in ("--field", "--fps", "--out") and i + 1 < len(argv):
            i += 1
            opts[a[2:]] = argv[i]
        elif a.startswith("-"):
            print(f"error: animate: unknown option {a!r} (--field NAME, --gif, --fps N, --out FILE)", file=sys.stderr)
            return 64
        elif run is None:
            run = a
        else:
            print(f"error: animate: one run directory expected, found {a!r} too", file=sys.stderr)
            return 64
        i += 1
    from gen.pipeline import user_path
    run = user_path(run)
    if not (run / "summary.json").exists():
        print(f"error: {run}: not a run directory (expected summary.json)", file=sys.stderr)
        return 1
    try:
        fps = int(opts["fps"])
        if not 1 <= fps <= 120:
            raise ValueError
    except ValueError:
        print(f"error: animate: --fps {opts['fps']!r}: expected an integer from 1 to 120", file=sys.stderr)
        return 64
    try:
        out = render(run, opts["field"], fps, opts["gif"], user_path(opts["out"]) if opts["out"] else None)
    except AnimateError as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
