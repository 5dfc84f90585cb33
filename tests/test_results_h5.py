"""results.h5 (runtime/output/h5.c, docs/reference/results_h5.md) read back with h5py:
every table equals its CSV at the CSV's printed precision (bit for bit for the
%.17g columns), the states agree with independent quantities (the reference
geometry of the scene, the tip sensor, finite differences of q for the
velocities), and a run that fails or is interrupted keeps every step it wrote."""
import csv
import json
import os
import re
import signal
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np
import pytest

h5py = pytest.importorskip("h5py")

from util import BUILD, ENV, ROOT, ensure_dir, run_cli


def _out(prefix):
    return Path(tempfile.mkdtemp(prefix=prefix, dir=ensure_dir(BUILD / "runs")))


def _run(scene, sets=(), expect_rc=0):
    out = _out("bk-h5-")
    args = ["run", str(scene), "--quiet", "--out", str(out)]
    for s in sets:
        args += ["--set", s]
    r = run_cli(args)
    assert r.returncode == expect_rc, (r.returncode, r.stderr[-3000:])
    return out


def _digits(text):
    """Significant digits printed in a CSV number."""
    m = re.match(r"^[-+]?(\d*)\.?(\d*)", text)
    d = (m.group(1) + m.group(2)).lstrip("0")
    return max(1, len(d))


def check_tables_equal_csv(out):
    """Every CSV of the run that has a table in results.h5 holds the same rows:
    integers and names equal, numbers equal at the printed precision (exactly
    when printed with 17 digits or fewer that round-trip)."""
    checked = []
    with h5py.File(out / "results.h5", "r") as f:
        for name in f["tables"]:
            ds = f["tables"][name][()]
            with open(out / f"{name}.csv", newline="") as fh:
                rows = list(csv.reader(fh))
            header, rows = rows[0], rows[1:]
            assert list(ds.dtype.names) == header, (name, ds.dtype.names, header)
            assert len(ds) == len(rows), (name, len(ds), len(rows))
            for i, row in enumerate(rows):
                for c, text in enumerate(row):
                    v = ds[i][c]
                    kind = ds.dtype[c].kind
                    if kind == "S":
                        assert v.decode() == text, (name, i, header[c])
                    elif kind == "i":
                        assert int(v) == int(text), (name, i, header[c])
                    elif text in ("nan", "-nan"):
                        assert np.isnan(v), (name, i, header[c])
                    else:
                        d = _digits(text)
                        assert float(f"{v:.{d}g}") == float(text), (name, i, header[c], v, text)
            checked.append(name)
    return checked


def tip_dofs(f, beam="arm"):
    """The position DOFs (x, y, z) of the last node of a beam, from /dofs."""
    node = f["dofs/node"][()]
    field = f["dofs/field"][()]
    b = f["dofs/beam"][()]
    comp = f["dofs/component"][()]
    on = (b == beam.encode()) & (field == b"r")
    last = node[on].max()
    idx = {comp[i].decode(): i for i in np.nonzero(on & (node == last))[0]}
    return [idx["x"], idx["y"], idx["z"]]


def test_static_run_results_h5_equals_the_csvs_and_the_geometry():
    out = _run("cantilever_rollup")
    s = json.loads((out / "summary.json").read_text())
    checked = check_tables_equal_csv(out)
    assert {"sensors", "reactions", "sections", "newton"} <= set(checked), checked
    with h5py.File(out / "results.h5", "r") as f:
        assert f.attrs["scene"] == b"cantilever_rollup" and f.attrs["analysis"] == b"static"
        assert f.attrs["time_name"] == b"load_factor"
        assert b"m," in f.attrs["units"]
        nd = s["dofs"]
        assert f["q"].shape == (s["steps"] + 1, nd) and "qd" not in f
        assert list(f["step"][()]) == list(range(s["steps"] + 1))
        assert f["time"][0] == 0.0 and f["time"][-1] == s["load_factor"] == 1.0
        # the reference state: 10 ancf3243 elements on [0, 1] m along x: node k at x = k/10,
        # slopes r_x = (1, 0, 0), r_y = (0, 1, 0), r_z = (0, 0, 1) (up = z)
        q0, node, field, comp = f["q"][0], f["dofs/node"][()], f["dofs/field"][()], f["dofs/component"][()]
        assert sorted(set(node)) == list(range(11)) and len(node) == nd == 11 * 12
        for i in range(nd):
            fld, c = field[i].decode(), "xyz".index(comp[i].decode())
            want = {"r": [node[i] / 10.0, 0.0, 0.0], "r_x": [1.0, 0.0, 0.0], "r_y": [0.0, 1.0, 0.0],
                    "r_z": [0.0, 0.0, 1.0]}[fld][c]
            assert abs(q0[i] - want) < 1e-15, (i, fld, c, q0[i], want)
        # the tip sensor is the position of the last node in every step
        tip = f["tables/sensors"][()]
        td = tip_dofs(f)
        xyz = np.stack([tip["x"], tip["y"], tip["z"]], axis=1)
        np.testing.assert_allclose(f["q"][:, td], xyz, rtol=0, atol=1e-14)
        np.testing.assert_array_equal(f["time"][()], tip["time"])
        assert np.abs(f["q"][-1, td] - f["q"][0, td]).max() > 0.3      # (it moved)


def test_dynamic_run_velocities_are_the_time_derivative_of_q():
    out = _run("pendulum_soft_ancf", ["dynamic.output_every=1", "dynamic.t_end=0.1", "dynamic.dt=1e-3"])
    check_tables_equal_csv(out)
    with h5py.File(out / "results.h5", "r") as f:
        assert f.attrs["time_name"] == b"time"
        q, qd, t = f["q"][()], f["qd"][()], f["time"][()]
        assert q.shape == qd.shape and q.shape[0] == len(t) >= 50
        assert "energy" in f["tables"]
        # central differences of the states (dt uniform) against the integrator's qd, past
        # the start's high-frequency transient (the first 10 steps): 0.6 % of the largest
        # speed here; the same with qd one step off: 7 %
        h = np.diff(t)
        assert np.allclose(h, h[0], rtol=1e-9)
        fd = (q[2:] - q[:-2]) / (2 * h[0])
        scale = np.abs(qd).max()
        assert scale > 0.1
        err = np.abs(fd - qd[1:-1])[10:].max() / scale
        assert err < 1.5e-2, err


def test_failing_run_keeps_every_converged_step_in_results_h5():
    scene = _out("bk-h5-scene-") / "truss_load_control.toml"
    text = (ROOT / "models" / "truss_snap_through.toml").read_text()
    text = text.replace('method = "arc_length"', 'method = "load_control"').replace("target_load_factor = 1.0\n", "")
    scene.write_text(text)
    out = _run(scene, ["static.load_steps=20", "static.step_control=fixed", "static.max_cutbacks=0"], expect_rc=2)
    s = json.loads((out / "summary.json").read_text())
    assert s["converged"] is False and s["steps"] >= 5
    check_tables_equal_csv(out)
    with h5py.File(out / "results.h5", "r") as f:
        assert list(f["step"][()]) == list(range(s["steps"] + 1))
        np.testing.assert_allclose(f["time"][()], np.arange(s["steps"] + 1) / 20.0, rtol=1e-14, atol=0)


def test_sigint_keeps_every_written_step_in_results_h5():
    out = _out("bk-h5-int-")
    args = [str(ROOT / "build.sh"), "run", "double_pendulum_soft_gef", "--quiet", "--out", str(out),
            "--set", "dynamic.t_end=50", "--set", "dynamic.output_every=1"]
    p = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=ENV,
                         start_new_session=True)
    t0 = time.time()
    while not ((out / "sensors.csv").exists() and sum(1 for _ in open(out / "sensors.csv")) > 100):
        assert p.poll() is None, p.stderr.read()[-2000:]
        assert time.time() - t0 < 300, "no progress"
        time.sleep(0.05)
    os.killpg(p.pid, signal.SIGINT)
    p.communicate(timeout=120)
    assert p.returncode == 130
    s = json.loads((out / "summary.json").read_text())
    assert s["interrupted"] is True
    check_tables_equal_csv(out)
    with h5py.File(out / "results.h5", "r") as f:
        assert list(f["step"][()]) == list(range(s["steps"] + 1))
        assert f["q"].shape[0] == f["qd"].shape[0] == s["steps"] + 1
        assert np.isfinite(f["qd"][()]).all()


@pytest.mark.parametrize("frames", [[], ["output.vtk_every=0"]], ids=["frames", "no_frames"])
def test_a_table_the_writer_thread_mirrors_is_written_by_it_past_4_mb(frames):
    """From a static run's 8th output step its tables' rows go to results.h5's
    thread, which formats them and mirrors them into results.h5 (csvrow.h, h5.h).
    200 elements, 30 fixed load steps: 1000 rows of sections.csv a state, so the
    thread's rows pass 4 MB (16,912 rows) before the run ends; the thread then
    makes the file itself and appends them.  The tables equal the CSVs, and the
    states, handed over only at the end, are contiguous while sections is chunked
    (the solve thread's own rows would have handed a set over at 4 MB, and the
    states would be chunked too).  A run slower than the 0.5 s flush interval
    hands sets over anyway: tried up to 3 times for one that is not.  Without
    frames the rows go to results.h5's thread all the same (not to a thread of
    their own, which would leave the mirror to the solve thread)."""
    sets = ["beam.arm.elements=200", "static.step_control=fixed", "static.load_steps=30",
            "static.stability=false"] + frames
    for _ in range(3):
        out = _run("cantilever_bend_10N", sets)
        check_tables_equal_csv(out)
        if json.loads((out / "summary.json").read_text())["wall_s"] < 0.4:
            break
    else:
        pytest.skip("three runs took 0.4 s or more: the timed flushes hand sets over")
    with h5py.File(out / "results.h5", "r") as f:
        assert f["tables/sections"].shape == (31 * 1000,) and f["tables/sections"].chunks is not None
        assert f["q"].chunks is None and list(f["step"][()]) == list(range(31))


def test_hdf5_false_writes_no_file_and_the_same_csvs():
    a = _run("cantilever_bend_100N")
    b = _run("cantilever_bend_100N", ["output.hdf5=false"])
    assert (a / "results.h5").exists() and not (b / "results.h5").exists()
    for name in ("sensors.csv", "reactions.csv", "sections.csv"):
        assert (a / name).read_bytes() == (b / name).read_bytes(), name


@pytest.mark.parametrize("scene", ["contact_capstan", "tendon_finger_dynamic", "lee_frame"])
def test_every_table_of_contact_tendon_and_arc_length_runs_is_in_results_h5(scene):
    """The interactions' tables (contacts, contact totals), a dynamic tendon run's
    energy, an arc-length run's Newton record: each equal to its CSV, and every CSV
    the run wrote row by row has its table."""
    out = _run(scene)
    checked = set(check_tables_equal_csv(out))
    csvs = {p.stem for p in out.glob("*.csv")}
    assert csvs <= checked, csvs - checked


def test_results_h5_that_cannot_be_written_is_an_error():
    """results.h5's name taken by a directory: one line naming it, exit status 1,
    the CSV tables and summary.json still written."""
    out = _run("cantilever_bend_100N")
    first = (out / "model.dat").read_text().split("\n", 3)[1]
    solver = ROOT / "out" / "bin" / dict(kv.split("=", 1) for kv in first.split()[1:])["name"]
    run_dir = _out("bk-h5-bad-")
    (run_dir / "results.h5").mkdir()
    p = subprocess.run([str(solver), str(out / "model.dat"), str(run_dir), "--quiet"], capture_output=True, text=True)
    assert p.returncode == 1, (p.returncode, p.stderr)
    assert p.stderr.count("cannot write") == 1 and f"error: {run_dir}/results.h5: cannot write: " in p.stderr, p.stderr
    assert (run_dir / "sensors.csv").read_bytes() == (out / "sensors.csv").read_bytes()
    assert json.loads((run_dir / "summary.json").read_text())["converged"]
