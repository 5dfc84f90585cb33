"""Modal output a user can read (frequency table on the console, one file per mode,
the static frames kept, mode shapes at a stated scale, read back with ParaView's
pvpython) and honest plots (mode shapes, an axis floor against round-off,
failed and interrupted runs marked, the scene name in every title)."""
import csv
import json
import math
import re
import shutil
import subprocess
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from util import BUILD, ROOT, ensure_dir, run_cli

# the steel cantilever of models/cantilever_modal.toml
E, RHO, B, H, L = 2.1e11, 7850.0, 0.01, 0.01, 1.0
EI, RHOA = E * B * H**3 / 12, RHO * B * H
BETA_L = (1.87510407, 4.69409113, 7.85475744)
NELEM, NX, RING = 20, 4, 8             # elements; frame stations per element, ring points (rectangle)


def fresh():
    return Path(tempfile.mkdtemp(prefix="bk-modal-", dir=ensure_dir(BUILD / "runs")))


def eb_frequency(bl):
    """Euler-Bernoulli cantilever: f = (beta L)^2 / (2 pi L^2) sqrt(EI / (rho A))."""
    return bl * bl / (2 * math.pi * L * L) * math.sqrt(EI / RHOA)


def eb_shape(x, bl):
    """Euler-Bernoulli cantilever mode shape (clamped at x = 0), tip value 1."""
    b = bl / L
    s = (math.cosh(bl) + math.cos(bl)) / (math.sinh(bl) + math.sin(bl))
    w = lambda t: np.cosh(b * t) - np.cos(b * t) - s * (np.sinh(b * t) - np.sin(b * t))
    return w(np.asarray(x)) / w(L)


def csv_rows(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def pvd(path):
    return [(d.get("file"), float(d.get("timestep"))) for d in ET.parse(path).getroot().findall("Collection/DataSet")]


def vtu_points(path):
    from report import vtu
    return vtu.read(path)["points"]


def sagging_modal_scene(d):
    """cantilever_modal about its static state under gravity, in 4 load steps."""
    text = (ROOT / "models" / "cantilever_modal.toml").read_text()
    text = text.replace("[modal]\nmodes = 6", '[modal]\nmodes = 6\nabout = "static"')
    text += '\n[[load]]\ntype = "gravity"\nvalue = [0.0, 0.0, -9.81]\n\n[static]\nload_steps = 4\nstep_control = "fixed"\n'
    p = d / "cantilever_modal_sag.toml"
    p.write_text(text)
    return p


def printed_modes(stdout):
    """(mode, Hz, rad/s, scale) rows of the console's frequency table."""
    rows = []
    for line in stdout.splitlines():
        m = re.fullmatch(r"\s+(\d+)\s+(\S+)\s+(\S+)\s+(\S+)", line)
        if m:
            rows.append((int(m.group(1)), float(m.group(2)), float(m.group(3)), float(m.group(4))))
    return rows


def test_modal_about_static_keeps_static_frames_and_writes_mode_files():
    """Modes about the sagged state (gravity, 4 load steps): the static frames step_0..4
    stay as they were (results.pvd lists each once, their tips are the static sensor
    rows, the last one sags by the Euler-Bernoulli w L^4 / (8 EI) to 0.3 %); the modes
    are in mode_01..06.vtu, modes.pvd (each once, time value = mode number), modes.csv
    and mode_sensors.csv; sensors.csv holds only the static rows; the console table
    equals modes.csv and summary.json; the frequencies are the Euler-Bernoulli
    cantilever's (beta L = 1.8751, 4.6941, 7.8548, each twice) within 0.5 %."""
    d = fresh()
    out = d / "o"
    r = run_cli(["run", str(sagging_modal_scene(d)), "--out", str(out)])
    assert r.returncode == 0, r.stderr
    steps = pvd(out / "results.pvd")
    assert [f for f, _ in steps] == [f"step_{k:06d}.vtu" for k in range(5)], steps
    assert [t for _, t in steps] == [0.0, 0.25, 0.5, 0.75, 1.0]
    assert sorted(p.name for p in out.glob("step_*.vtu")) == [f for f, _ in steps]
    modes = pvd(out / "modes.pvd")
    assert modes == [(f"mode_{k:02d}.vtu", float(k)) for k in range(1, 7)], modes
    assert sorted(p.name for p in out.glob("mode_*.vtu")) == [f for f, _ in modes]
    rows = csv_rows(out / "sensors.csv")
    assert [int(x["step"]) for x in rows] == list(range(5)) and [float(x["time"]) for x in rows] == [t for _, t in steps]
    for (f, _), row in zip(steps, rows):          # the frames are the static states, not modes
        tip = vtu_points(out / f)[NX * (RING + 1) * NELEM - 1]   # last centreline point
        assert np.allclose(tip, [float(row[k]) for k in ("x", "y", "z")], atol=1e-8), (f, tip, row)
    w = RHOA * 9.81
    sag = w * L**4 / (8 * EI)
    assert abs(-float(rows[-1]["uz"]) - sag) <= 3e-3 * sag, (rows[-1]["uz"], sag)
    table = csv_rows(out / "modes.csv")
    msens = csv_rows(out / "mode_sensors.csv")
    assert [int(x["mode"]) for x in table] == list(range(1, 7))
    assert [(int(x["mode"]), x["sensor"]) for x in msens] == [(k, "tip") for k in range(1, 7)]
    summary = json.loads((out / "summary.json").read_text())
    printed = printed_modes(r.stdout)
    assert [p[0] for p in printed] == list(range(1, 7)), r.stdout
    for p, row, fs in zip(printed, table, summary["frequencies_hz"]):
        f, om = float(row["frequency_hz"]), float(row["omega"])
        assert abs(p[1] - f) <= 1e-8 * f and abs(p[2] - om) <= 1e-8 * om and abs(f - fs) <= 1e-12 * f, (p, row, fs)
        assert abs(om - 2 * math.pi * f) <= 1e-12 * om
        assert abs(p[3] - float(row["scale_m"])) <= 1e-3 * float(row["scale_m"])
    f = [float(x["frequency_hz"]) for x in table]
    for k, bl in enumerate(BETA_L):
        exact = eb_frequency(bl)
        for g in f[2 * k:2 * k + 2]:
            assert abs(g - exact) <= 5e-3 * exact, (k, g, exact)


PVSCRIPT = r"""
import json, sys
import numpy as np
from paraview.simple import PVDReader
from paraview import servermanager as sm
from vtk.numpy_interface import dataset_adapter as dsa
reader = PVDReader(FileName=sys.argv[1])
out = {"times": list(reader.TimestepValues), "modes": []}
for t in reader.TimestepValues:
    reader.UpdatePipeline(t)
    d = dsa.WrapDataObject(sm.Fetch(reader))
    out["modes"].append({"points": np.asarray(d.Points).tolist(),
                         "displacement": np.asarray(d.PointData["displacement"]).tolist(),
                         "mode_shape": np.asarray(d.PointData["mode_shape"]).tolist(),
                         "scale": float(d.FieldData["MODE_SCALE"][0]),
                         "frequency": float(d.FieldData["FREQUENCY_HZ"][0])})
json.dump(out, open(sys.argv[2], "w"))
"""


def test_mode_files_read_with_paraview():
    """modes.pvd read by ParaView's pvpython: time values 1..6, 20 x 4 x 9 points per
    mode, the largest point displacement is the scale stated in modes.csv (and in the
    file), the largest mode_shape is 1 and displacement = scale x mode_shape; the
    points minus the displacement are the reference (the state the modes are about);
    the first bending mode's centreline is the Euler-Bernoulli mode shape to 1 %."""
    pvpython = shutil.which("pvpython")
    assert pvpython, "pvpython not found: ./build.sh deps installs the Debian package paraview"
    out = fresh()
    assert run_cli(["run", "cantilever_modal", "--quiet", "--out", str(out)]).returncode == 0
    script, dump = out / "read_modes.py", out / "modes.json"
    script.write_text(PVSCRIPT)
    r = subprocess.run([pvpython, str(script), str(out / "modes.pvd"), str(dump)], capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 0, r.stderr[-3000:]
    data = json.loads(dump.read_text())
    assert data["times"] == [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
    table = csv_rows(out / "modes.csv")
    ref = vtu_points(out / "step_000000.vtu")               # the reference state
    for m, row in zip(data["modes"], table):
        pts, disp, shape = (np.array(m[k]) for k in ("points", "displacement", "mode_shape"))
        assert len(pts) == NELEM * NX * (RING + 1), len(pts)
        scale = float(row["scale_m"])
        assert abs(m["scale"] - scale) <= 1e-8 * scale and abs(m["frequency"] - float(row["frequency_hz"])) <= 1e-9 * m["frequency"]
        assert abs(np.linalg.norm(disp, axis=1).max() - scale) <= 1e-7 * scale
        assert abs(np.linalg.norm(shape, axis=1).max() - 1.0) <= 1e-7
        assert np.allclose(disp, scale * shape, atol=1e-8 * scale)
        assert np.allclose(pts - disp, ref, atol=1e-8)
    assert float(table[0]["scale_m"]) == 0.1 * L                    # first mode: 10 % of the length
    centre = np.arange(NELEM * NX) * (RING + 1) + RING              # centreline points
    pts, disp = np.array(data["modes"][0]["points"]), np.array(data["modes"][0]["displacement"])
    x, w = pts[centre, 0] - disp[centre, 0], np.linalg.norm(disp[centre], axis=1)
    w = w / w[np.argmax(x)]
    assert np.max(np.abs(w - eb_shape(x, BETA_L[0]))) <= 1e-2, np.max(np.abs(w - eb_shape(x, BETA_L[0])))


def test_plot_draws_mode_shapes():
    """./build.sh plot of a modal run: modes.png, one panel per mode titled with its
    number and frequency, the displaced centreline's tip at the mode's scale off the
    reference; no sensors.png across modes; the scene name in every title."""
    from report.plot import figures
    import matplotlib.pyplot as plt
    out = fresh()
    assert run_cli(["run", "cantilever_modal", "--quiet", "--out", str(out)]).returncode == 0
    figs = figures(out)
    assert set(figs) == {"modes.png", "beam.png"}, set(figs)
    table = csv_rows(out / "modes.csv")
    axes = [a for a in figs["modes.png"].axes if a.get_visible()]
    assert len(axes) == 6
    for ax, row in zip(axes, table):
        f = float(row["frequency_hz"])
        assert ax.get_title().startswith(f"mode {row['mode']}: {f:.5g} Hz"), ax.get_title()
        base, moved = ax.lines[-2], ax.lines[-1]                    # last element's centreline
        tip = moved.get_ydata()[-1] - base.get_ydata()[-1]
        assert abs(abs(tip) - float(row["scale_m"])) <= 2e-3 * float(row["scale_m"]), (tip, row)
    for name, fig in figs.items():
        assert fig._suptitle.get_text().startswith("cantilever_modal: "), name
        plt.close(fig)
    r = run_cli(["plot", str(out)])
    assert r.returncode == 0 and (out / "modes.png").read_bytes()[:4] == b"\x89PNG", r.stderr


def test_plot_axis_floor_and_load_factor_label():
    """A static bend in z (uy = 0): every displacement axis spans at least 1e-6 of the
    model length, the uy axis says it is at that floor, the x axis is the load factor,
    the title names the scene and the run is not marked as failed."""
    from report.plot import figures
    import matplotlib.pyplot as plt
    out = fresh()
    assert run_cli(["run", "cantilever_bend_10N", "--quiet", "--out", str(out)]).returncode == 0
    uy = [abs(float(x["uy"])) for x in csv_rows(out / "sensors.csv")]
    assert max(uy) < 1e-12, max(uy)
    fig = figures(out)["sensors.png"]
    axes = fig.axes
    for ax in axes:
        lo, hi = ax.get_ylim()
        assert hi - lo >= 1e-6 * L * (1 - 1e-9), (ax.get_ylabel(), lo, hi)
    assert axes[1].get_ylabel() == "uy (m)"
    notes = [t.get_text() for t in axes[1].texts]
    assert any("floor 1e-06 m" in n and "model length" in n for n in notes), notes
    assert axes[2].get_xlabel() == "load factor"
    assert fig._suptitle.get_text() == "cantilever_bend_10N: sensor displacements"
    assert not [t for t in fig.texts if t.get_gid() == "status"]
    plt.close(fig)


def status_texts(fig):
    return [" ".join(t.get_text().split()) for t in fig.texts if t.get_gid() == "status"]


def test_plot_marks_failed_and_interrupted_runs():
    """The roll-up forced to fail (one Newton iteration, no cut-backs): every plot says
    'NOT converged: <the error of summary.json>'; a summary with "interrupted": true says
    'interrupted at load factor = ...' (static) or 'interrupted at t = ... s' (dynamic)."""
    from report.plot import figures, status_note
    import matplotlib.pyplot as plt
    d = fresh()
    r = run_cli(["run", "cantilever_rollup", "--quiet", "--out", str(d / "o"), "--set", "static.max_iterations=1",
                 "--set", "static.max_cutbacks=0"])
    assert r.returncode == 2, r.stderr
    summary = json.loads((d / "o" / "summary.json").read_text())
    assert not summary["converged"] and summary["error"]
    figs = figures(d / "o")
    assert set(figs) >= {"sensors.png", "beam.png"}
    for name, fig in figs.items():
        assert status_texts(fig) == [f"NOT converged: {' '.join(summary['error'].split())}"], (name, status_texts(fig))
        assert "cantilever_rollup" in fig._suptitle.get_text() and "NOT converged" in fig._suptitle.get_text()
        plt.close(fig)
    summary.update(interrupted=True, load_factor=0.4, error="interrupted by signal 2")
    (d / "o" / "summary.json").write_text(json.dumps(summary))
    for name, fig in figures(d / "o").items():
        assert status_texts(fig) == ["interrupted at load factor = 0.4"], (name, status_texts(fig))
        plt.close(fig)
    assert status_note({"analysis": "dynamic", "interrupted": True, "time": 0.125, "converged": False}) == \
        "interrupted at t = 0.125 s"
    assert status_note({"analysis": "dynamic", "converged": True}) is None


def test_one_increment_static_run_is_drawn_as_two_states_and_says_so():
    """A static run of one load increment: sensors.png draws the reference and the
    final state as points (no line suggesting a path between) and says why."""
    from report.plot import figures
    import matplotlib.pyplot as plt
    out = fresh()
    r = run_cli(["run", "cantilever_bend_100N", "--quiet", "--out", str(out), "--set", "static.load_steps=1",
                 "--set", "static.step_control=fixed"])
    assert r.returncode == 0, r.stderr
    assert len({x["step"] for x in csv_rows(out / "sensors.csv")}) == 2
    fig = figures(out)["sensors.png"]
    for ax in fig.axes:
        for line in ax.get_lines():
            assert line.get_linewidth() == 0 and line.get_marker() == "o"
    assert [t for t in fig.axes[0].texts if t.get_gid() == "one_increment"]
    plt.close(fig)


def test_sweep_axes_carry_units():
    from beamkit.sweep import _with_unit, unit_of
    assert unit_of("material.alu.E") == "Pa" and unit_of("dynamic.dt") == "s" and unit_of("tip.uz") == "m"
    assert unit_of("frequency.1") == "Hz" and unit_of("beam.arm.elements") == "" and unit_of("material.a.rho") == "kg/m³"
    assert _with_unit("section.s.b") == "section.s.b (m)" and _with_unit("newton_iterations") == "newton_iterations"


def test_the_console_counts_modes_not_steps():
    """A modal run's line says how many modes it found (it takes no steps and
    no Newton iterations)."""
    from util import run_cli
    r = run_cli(["run", "cantilever_modal", "--set", "modal.modes=4", "--out",
                 str(BUILD / "runs" / "modal_console")])
    assert r.returncode == 0, r.stderr[-2000:]
    first = r.stdout.splitlines()[0]
    assert "(modal): converged; 4 modes, " in first and "step" not in first and "Newton" not in first, first
