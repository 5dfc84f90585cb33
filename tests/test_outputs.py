"""Result files: ParaView frames against the sensors, determinism, output
directories and names, failure reports of dynamic runs, progress line, help,
plots."""
import csv
import json
import os
import pty
import shutil
import subprocess
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from util import BUILD, ENV, ROOT, ensure_dir, load_run, run_cli


def fresh():
    return Path(tempfile.mkdtemp(prefix="bk-out-", dir=ensure_dir(BUILD / "runs")))


def vtu_centreline(path):
    from report import vtu
    d = vtu.read(path)
    pts, disp = d["points"], d["displacement"]
    lines = [c for t, c in vtu.cells(d) if t == 4]
    return pts, disp, lines


def test_paraview_frames_match_the_sensors():
    """Every frame of results.pvd: the end of the last centreline polyline is the tip sensor
    (position and displacement, 1e-8 m), for a static ANCF run and a dynamic gef run; the
    collection's times are the sensors' times."""
    for scene, sets in (("cantilever_bend3d_50N", ["static.load_steps=10", "static.step_control=fixed"]),
                        ("pendulum_soft_gef", ["dynamic.t_end=0.2"])):
        out = fresh()
        r = run_cli(["run", scene, "--quiet", "--out", str(out)] + sum((["--set", x] for x in sets), []))
        assert r.returncode == 0, r.stderr
        sensor = "tip" if "cantilever" in scene else "B"
        with open(out / "sensors.csv", newline="") as fh:
            rows = {float(x["time"]): x for x in csv.DictReader(fh) if x["sensor"] == sensor}
        frames = ET.parse(out / "results.pvd").getroot().findall("Collection/DataSet")
        assert len(frames) >= 5
        for f in frames:
            t = float(f.get("timestep"))
            pts, disp, lines = vtu_centreline(out / f.get("file"))
            row = min(rows.items(), key=lambda kv: abs(kv[0] - t))[1]
            assert abs(float(row["time"]) - t) < 1e-12
            tip = pts[lines[-1][-1]]
            assert np.allclose(tip, [float(row[k]) for k in ("x", "y", "z")], atol=1e-8), (t, tip, row)
            assert np.allclose(disp[lines[-1][-1]], [float(row[k]) for k in ("ux", "uy", "uz")], atol=1e-8)


def test_same_scene_twice_gives_identical_results():
    """Two runs of a static and a dynamic scene: every result file byte-identical,
    summary.json identical but for its measured times (wall_s, output_s, stability_s)."""
    for scene, sets in (("cantilever_bend_100N", []), ("pendulum_soft_ancf", ["--set", "dynamic.t_end=0.2"])):
        a, b = fresh(), fresh()
        for d in (a, b):
            assert run_cli(["run", scene, "--quiet", "--out", str(d)] + sets).returncode == 0
        names = sorted(p.name for p in a.iterdir())
        assert names == sorted(p.name for p in b.iterdir())
        for n in names:
            if n == "summary.json":
                sa, sb = json.loads((a / n).read_text()), json.loads((b / n).read_text())
                for key in ("wall_s", "output_s", "stability_s"):
                    assert (key in sa) == (key in sb), key
                    sa.pop(key, None), sb.pop(key, None)
                assert sa == sb
            else:
                assert (a / n).read_bytes() == (b / n).read_bytes(), n


def test_names_cannot_escape_and_out_dirs_are_not_mixed():
    d = fresh()
    base = (ROOT / "models" / "cantilever_bend_10N.toml").read_text()
    for text, key in ((base.replace('[scene]', '[scene]\nname = "../../evil"'), "scene.name"),
                      (base.replace('name = "arm"', 'name = "a/b"'), "beam[0].name"),
                      (base.replace('name = "tip"', 'name = "$(touch x)"'), "sensor[0].name")):
        p = d / "s.toml"
        p.write_text(text)
        r = run_cli(["run", str(p), "--out", str(d / "o")])
        assert r.returncode == 1 and key in r.stderr and "expected a name" in r.stderr, r.stderr
    foreign = fresh()
    (foreign / "precious.txt").write_text("keep me")
    r = run_cli(["run", "cantilever_bend_10N", "--out", str(foreign)])
    assert r.returncode == 1 and "not empty" in r.stderr
    assert (foreign / "precious.txt").read_text() == "keep me"
    own = fresh()
    assert run_cli(["run", "cantilever_bend_100N", "--quiet", "--out", str(own), "--set", "static.load_steps=10",
                    "--set", "static.step_control=fixed"]).returncode == 0
    n_before = len(list(own.glob("step_*.vtu")))
    assert run_cli(["run", "cantilever_bend_10N", "--quiet", "--out", str(own)]).returncode == 0
    n_after = len(list(own.glob("step_*.vtu")))
    assert n_before == 11 and n_after == 3, (n_before, n_after)     # old frames removed


def test_dynamic_failure_keeps_steps_and_says_where():
    """A Neo-Hookean bar crushed by an axial force far beyond what it can carry, in dynamics: the
    run stops with time, step size, residual and cause on one line, exit 2, every accepted
    step kept.  (The force a step at t = 0.25 ms and dt_min = dt / 4: with the step
    controller's memory the crushed bar would otherwise be followed at small steps
    through its collapse.)"""
    d = fresh()
    text = (ROOT / "models" / "cantilever_axial_m1kN.toml").read_text()
    text = text.replace('analysis = "static"', 'analysis = "dynamic"').replace('law = "svk"', 'law = "neo_hookean"').replace(
        "value = [-1000.0, 0.0, 0.0]", 'value = [-5.0e6, 0.0, 0.0]\namplitude = {type = "step", t0 = 0.00025}')
    text += "\n[dynamic]\nt_end = 0.01\ndt = 1e-4\ndt_min = 2.5e-5\n"
    p = d / "collapse.toml"
    p.write_text(text)
    r = run_cli(["run", str(p), "--out", str(d / "o")])
    assert r.returncode == 2, r.stderr
    err = [l for l in r.stderr.splitlines() if l.startswith("error")]
    assert len(err) == 1 and "dynamic solve failed at step" in err[0] and "time" in err[0] and "residual" in err[0], r.stderr
    s, rows = load_run(d / "o")
    assert not s["converged"] and s["steps"] >= 1
    assert len({x["step"] for x in rows}) == s["steps"] + 1


def _private_solver(scene, sets=()):
    """A run of `scene` and a private copy of its solver that reads that run's
    model.dat (another test may relink out/bin/SCENE for other elements at any
    time: then build again and copy again); (run directory, solver, frames)."""
    out = fresh()
    solver = out.parent / (out.name + "-solver")
    for _ in range(5):
        assert run_cli(["run", scene, "--quiet", "--out", str(out)] + list(sets)).returncode == 0
        shutil.copy2(ROOT / "out" / "bin" / scene, solver)
        frames = sorted(p.name for p in out.glob("step_*.vtu"))
        probe = subprocess.run([str(solver), str(out / "model.dat"), str(out), "--quiet"], capture_output=True)
        if probe.returncode == 0:
            break
    return out, solver, frames


def _run_into(solver, out, run_dir):
    return subprocess.run([str(solver), str(out / "model.dat"), str(run_dir), "--quiet"], capture_output=True,
                          text=True, timeout=600)


def _fails_once(p, path, reason):
    """The run exited with status 1 and reported one write error, PATH's."""
    assert p.returncode == 1, (p.returncode, p.stderr)
    assert f"error: {path}: cannot write: {reason}" in p.stderr, p.stderr
    assert p.stderr.count("cannot write") == 1, p.stderr


def test_frame_written_directly_that_cannot_be_is_an_error():
    """Seed Table 3 writes its two frames directly (too few for the background
    writer): the last one's name taken by a directory is reported with its path
    and reason, the run exits with status 1, the other frame, the tables and
    summary.json are still written."""
    out, solver, frames = _private_solver("cantilever_bend_100N_nu03")
    assert len(frames) == 2, frames
    run_dir = fresh()
    (run_dir / frames[1]).mkdir()
    _fails_once(_run_into(solver, out, run_dir), f"{run_dir}/{frames[1]}", "Is a directory")
    assert (run_dir / frames[0]).is_file() and (run_dir / "sections.csv").is_file()
    assert json.loads((run_dir / "summary.json").read_text())["converged"]


def test_table_that_cannot_be_written_is_an_error():
    """A result table whose bytes cannot be written (newton.csv a link to
    /dev/full: every write fails with ENOSPC, as on a full disk; a short run
    writes its tables only when it closes them) is reported with its path and
    reason before summary.json is written, and the run exits with status 1."""
    out, solver, _ = _private_solver("cantilever_bend_100N_nu03")
    run_dir = fresh()
    os.symlink("/dev/full", run_dir / "newton.csv")
    _fails_once(_run_into(solver, out, run_dir), f"{run_dir}/newton.csv", "No space left on device")
    assert (run_dir / "sensors.csv").read_text().count("\n") == 3
    assert json.loads((run_dir / "summary.json").read_text())["converged"]


def test_frame_that_cannot_be_written_is_an_error():
    """A ParaView frame past the second of a run long enough for the background
    writer that cannot be created -- its name taken by a directory -- is
    reported with its path and reason, the run exits with status 1, and the
    frames before and after it and summary.json are still written."""
    out, solver, frames = _private_solver("pendulum_soft_gef", ["--set", "dynamic.t_end=0.2"])
    assert len(frames) >= 6, frames
    run_dir = fresh()
    (run_dir / frames[3]).mkdir()
    _fails_once(_run_into(solver, out, run_dir), f"{run_dir}/{frames[3]}", "Is a directory")
    written = sorted(q.name for q in run_dir.glob("step_*.vtu") if q.is_file())
    assert written == [f for f in frames if f != frames[3]], written
    assert json.loads((run_dir / "summary.json").read_text())["converged"]


def test_progress_line_on_a_terminal_only():
    """A long run shows one updating progress line (at most every 2 s, none in the
    first 2 s) when stderr is a terminal; in a log (not a terminal) whole lines at
    most every 10 s (none for a run under 10 s); none with --quiet (issue 36)."""
    # 150,000 steps: about 6 s on an idle machine here (the terminal line appears after 2 s)
    sets = ["--set", "dynamic.dt=2e-5", "--set", "dynamic.t_end=3", "--set", "output.vtk_every=0"]
    out, solver, _ = _private_solver("pendulum_soft_ancf", sets)
    args = [str(solver), str(out / "model.dat"), str(out)]
    master, slave = pty.openpty()
    p = subprocess.run(args, stderr=slave, stdout=subprocess.DEVNULL, timeout=900)
    os.close(slave)
    text = b""
    while True:
        try:
            chunk = os.read(master, 65536)
        except OSError:
            break
        if not chunk:
            break
        text += chunk
    os.close(master)
    assert p.returncode == 0
    assert b"\r" in text and b"s left" in text and b"iterations/s" in text and b", dt 2e-05" in text, text[-500:]
    q = subprocess.run(args + ["--quiet"], capture_output=True, timeout=900)
    assert q.returncode == 0 and b"left" not in q.stderr
    q = subprocess.run(args, capture_output=True, timeout=900)          # not a terminal: a log
    wall = json.loads((out / "summary.json").read_text())["wall_s"]
    lines = [x for x in q.stderr.decode().splitlines() if "s left" in x]
    assert q.returncode == 0 and b"\r" not in q.stderr
    assert len(lines) <= wall / 10.0 and (wall < 11.0 or lines), (wall, lines)


def test_help_lists_commands_and_options():
    r = subprocess.run([str(ROOT / "build.sh"), "--help"], capture_output=True, text=True, env=ENV)
    assert r.returncode == 0
    for word in ("test", "run SCENE", "--set", "--out", "gen", "--check", "bench", "plot", "report", "scenes",
                 "sweep SCENE", "--grid", "--random", "--scheduler", "fit SCENE", "--data", "--param"):
        assert word in r.stdout, word
    r = subprocess.run([str(ROOT / "build.sh"), "run", "--help"], capture_output=True, text=True, env=ENV)
    assert r.returncode == 0
    for word in ("--set", "--out", "--quiet", "--verbose", "--sanitize"):
        assert word in r.stdout, word


def test_plot_writes_pngs():
    out = fresh()
    assert run_cli(["run", "pendulum_soft_gef", "--quiet", "--out", str(out), "--set", "dynamic.t_end=0.3"]).returncode == 0
    r = run_cli(["plot", str(out)])
    assert r.returncode == 0, r.stderr
    for n in ("sensors.png", "energy.png", "beam.png"):
        data = (out / n).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10000, n


def test_frames_show_the_section_forces_of_their_own_step():
    """Consistency of two outputs made on different paths (not a verification
    against a reference): a small model's section forces and their rows are made
    by the rows' writer thread from a copy of the state, and a frame made by that
    thread reads them there (runtime/output/sections.c).  In every frame of a
    dynamic run (HDF5 started on the thread) and of an arc-length run, the
    section_force and section_moment arrays hold, bit for bit, each element end's
    N, Q2, Q3 and T, M2, M3 of sections.csv's nodal rows of the frame's own step,
    and no other step's."""
    for scene, sets in (("pendulum_soft_ancf", ["dynamic.dt=1e-3", "dynamic.t_end=0.3"]), ("lee_frame", [])):
        out = fresh()
        r = run_cli(["run", scene, "--quiet", "--out", str(out)] + sum((["--set", x] for x in sets), []))
        assert r.returncode == 0, r.stderr
        nodal = {}
        with open(out / "sections.csv", newline="") as fh:
            for row in csv.DictReader(fh):
                if row["source"] == "nodal":
                    step = int(row["step"])
                    nodal.setdefault(step, []).append((tuple(float(row[k]) for k in ("N", "Q2", "Q3")),
                                                       tuple(float(row[k]) for k in ("T", "M2", "M3"))))
        from report import vtu
        frames = sorted(out.glob("step_*.vtu"))
        assert len(frames) >= 10 and len(nodal) >= len(frames)
        for path in frames:
            step = int(path.stem.split("_")[1])
            d = vtu.read(path)
            forces = {tuple(v) for v in np.asarray(d["section_force"]).reshape(-1, 3)}
            moments = {tuple(v) for v in np.asarray(d["section_moment"]).reshape(-1, 3)}
            for f, m in nodal[step]:
                assert f in forces and m in moments, (scene, path.name, f, m)
            # (the check can tell steps apart: another step's forces are not all in this frame)
            other = next((s for s in sorted(nodal) if s != step and set(nodal[s]) != set(nodal[step])), None)
            assert other is not None and not all(f in forces for f, _ in nodal[other]), (scene, path.name)
