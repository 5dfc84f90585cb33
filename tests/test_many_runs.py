"""Many runs (issue 18): the Python API against ./build.sh run, sweeps on a local
Dask cluster and on a separately started scheduler with two workers, failed
runs and restarts, calibration against synthetic data, bad input."""
import csv
import json
import os
import signal
import subprocess
import sys
import time
import tomllib
import uuid
from pathlib import Path

import numpy as np
import pytest

from util import BUILD, ENV, PY, ROOT, ensure_dir, run_cli

sys.path.insert(0, str(ROOT))
from beamkit import BeamkitError, Scene  # noqa: E402
from beamkit.fit import fit, write_data  # noqa: E402
from beamkit.sweep import sweep  # noqa: E402

PEND = {"dynamic.t_end": 0.2, "dynamic.dt": 0.01}


def tmpdir(tag):
    import tempfile
    return Path(tempfile.mkdtemp(prefix=f"bk-{tag}-", dir=ensure_dir(BUILD / "many")))


def read_table(path, drop=("wall_s",)):
    with open(path, newline="") as fh:
        return [{k: v for k, v in r.items() if k not in drop} for r in csv.DictReader(fh)]


def test_api_reproduces_build_sh_run_to_the_last_digit():
    a, b, c = tmpdir("cli"), tmpdir("api"), tmpdir("dict")
    sets = ["dynamic.t_end=0.3", "material.rod.E=3.3e7"]
    r = run_cli(["run", "pendulum_soft_ancf", "--quiet", "--out", str(a)] + [x for s in sets for x in ("--set", s)])
    assert r.returncode == 0, r.stderr
    run = Scene("pendulum_soft_ancf").run({"dynamic.t_end": 0.3, "material.rod.E": 3.3e7}, out=b)
    doc = tomllib.loads((ROOT / "models" / "pendulum_soft_ancf.toml").read_text())
    run_d = Scene(doc, name="pendulum_soft_ancf").run(sets, out=c)
    for d in (b, c):
        for f in ("model.dat", "sensors.csv", "energy.csv"):
            assert (a / f).read_bytes() == (d / f).read_bytes(), f
        sa, sb = (json.loads((x / "summary.json").read_text()) for x in (a, d))
        for key in ("wall_s", "output_s"):            # the measured times
            sa.pop(key), sb.pop(key)
        assert sa == sb
    # the arrays hold the digits of the files
    with open(a / "sensors.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    s = run.sensor("B")
    assert s.displacement.shape == (len(rows), 3)
    assert [float(x["uz"]) for x in rows] == s.displacement[:, 2].tolist()
    assert [float(x["time"]) for x in rows] == s.time.tolist()
    assert run.converged and run_d.converged and run.energy["total"].shape == (len(rows),)
    assert run.summary["sensors"]["B"]["displacement"] == s.displacement[-1].tolist()
    modal = Scene("cantilever_modal").run(out=tmpdir("modal"))
    assert np.allclose(modal.frequencies, modal.summary["frequencies_hz"][:len(modal.frequencies)], rtol=1e-8)


def test_api_imports_no_sympy_and_reuses_the_solver():
    code = (
        "import sys, os\n"
        "from beamkit import Scene\n"
        "from gen.cache import _SOLVERS\n"
        "import beamkit.sweep, beamkit.fit, beamkit.cluster\n"
        f"sc = Scene('cantilever_bend_100N')\n"
        f"r1 = sc.run(out={str(tmpdir('ns1'))!r})\n"
        "path, st = next(iter(_SOLVERS.values()))\n"
        "m0 = os.stat(path).st_mtime_ns\n"
        f"r2 = sc.run({{'material.alu.E': 8e10, 'beam.arm.elements': 4}}, out={str(tmpdir('ns2'))!r})\n"
        "assert len(_SOLVERS) == 1 and os.stat(path).st_mtime_ns == m0, 'solver rebuilt'\n"
        "assert r2.summary['elements'] == 4 and r1.converged and r2.converged\n"
        "assert r1.newton is not None and len(r1.newton['residual']) > 0, r1.newton\n"
        "assert 'sympy' not in sys.modules, 'sympy imported'\n"
        "print('ok')\n")
    r = subprocess.run([PY, "-c", code], capture_output=True, text=True, env=ENV, timeout=120)
    assert r.returncode == 0 and r.stdout.strip() == "ok", r.stderr[-2000:]


def test_api_errors_are_the_command_lines():
    r = run_cli(["run", "cantilever_bend_100N", "--quiet", "--out", str(tmpdir("e")), "--set", "beam.arm.foo=1"])
    assert r.returncode == 1
    with pytest.raises(BeamkitError) as e:
        Scene("cantilever_bend_100N").run({"beam.arm.foo": 1}, out=tmpdir("e2"))
    assert str(e.value) == r.stderr.strip()
    with pytest.raises(BeamkitError, match="no models/no_such_scene.toml"):
        Scene("no_such_scene")


def test_dict_scene_reads_its_data_files_from_base_not_the_current_directory(monkeypatch):
    """Issue 40: a table amplitude's CSV file named by a relative path in a scene
    given to the API as a dict was read from the current directory.  Now it is read
    from Scene(..., base=DIR); without base it is refused with one line (a dict has
    no directory).  A decoy file of the same name in the current directory (the
    load doubled) is never read: the tip deflection equals the same scene written
    as a .toml file beside the data (`./build.sh run`) and the same table given
    inline, to the last digit."""
    data, cwd = tmpdir("dict-data"), tmpdir("dict-cwd")
    (data / "amp.csv").write_text("x,a\n0,0\n1,0.5\n")
    (cwd / "amp.csv").write_text("x,a\n0,0\n1,1.0\n")             # the decoy
    doc = {"scene": {"analysis": "static"},
           "material": {"alu": {"law": "resultant", "E": 7e10, "nu": 0.3, "rho": 2700.0}},
           "section": {"s": {"shape": "rectangle", "b": 0.01, "h": 0.01}},
           "beam": [{"name": "arm", "element": "gef", "material": "alu", "section": "s", "start": [0.0, 0.0, 0.0],
                     "end": [1.0, 0.0, 0.0], "elements": 4}],
           "constraint": [{"type": "clamp", "a": "arm:start"}],
           "amplitude": {"a": {"type": "table", "file": "amp.csv"}},
           "load": [{"type": "force", "at": "arm:end", "value": [0.0, 0.0, -1.0], "amplitude": "a"}],
           "sensor": [{"name": "tip", "at": "arm:end"}]}
    monkeypatch.chdir(cwd)
    with pytest.raises(BeamkitError, match=r"amplitude\.a\.file: the relative path 'amp\.csv' in a scene given as "
                                           r"a dict has no directory"):
        Scene(doc).run(out=tmpdir("dict-o0"))
    got = Scene(doc, base=data).run(out=tmpdir("dict-o1")).summary["sensors"]["tip"]["displacement"][2]
    toml = data / "beam.toml"
    toml.write_text("""[scene]
analysis = "static"
[material.alu]
law = "resultant"
E = 7e10
nu = 0.3
rho = 2700.0
[section.s]
shape = "rectangle"
b = 0.01
h = 0.01
[[beam]]
name = "arm"
element = "gef"
material = "alu"
section = "s"
start = [0.0, 0.0, 0.0]
end = [1.0, 0.0, 0.0]
elements = 4
[[constraint]]
type = "clamp"
a = "arm:start"
[amplitude.a]
type = "table"
file = "amp.csv"
[[load]]
type = "force"
at = "arm:end"
value = [0.0, 0.0, -1.0]
amplitude = "a"
[[sensor]]
name = "tip"
at = "arm:end"
""")
    out = tmpdir("dict-o2")
    run_cli(["run", str(toml), "--quiet", "--out", str(out)], check=True)
    from_file = json.loads((out / "summary.json").read_text())["sensors"]["tip"]["displacement"][2]
    inline = dict(doc, amplitude={"a": {"type": "table", "points": [[0.0, 0.0], [1.0, 0.5]]}})
    from_points = Scene(inline).run(out=tmpdir("dict-o3")).summary["sensors"]["tip"]["displacement"][2]
    assert got == from_file == from_points and got < 0, (got, from_file, from_points)
    decoy = Scene(doc, base=cwd).run(out=tmpdir("dict-o4")).summary["sensors"]["tip"]["displacement"][2]
    assert abs(decoy / got - 2.0) < 1e-3, (decoy, got)       # (linear: the decoy's doubled load)


def pendulum_grid():
    return {"beam.rod.elements": [3, 4], "dynamic.dt": [0.02, 0.01], "material.rod.E": [3e7, 4e7]}


def test_sweep_local_cluster_and_separate_scheduler_give_the_same_table():
    out_local, out_remote = tmpdir("swl"), tmpdir("swr")
    res = sweep("pendulum_soft_ancf", grid=pendulum_grid(), sets={"dynamic.t_end": 0.2}, out=out_local,
                workers=2, progress=False)
    assert len(res.rows) == 8 and not res.failed and res.reused == 0
    assert [p.name for p in res.plots] == ["sweep_beam.rod.elements.png", "sweep_dynamic.dt.png",
                                           "sweep_material.rod.E.png"]
    assert all(p.stat().st_size > 5000 for p in res.plots)
    # a run of the table is a run of ./build.sh run with the same values
    row = res.rows[5]
    one = Scene("pendulum_soft_ancf").run({"dynamic.t_end": 0.2, "output.vtk_every": 0,
                                           "beam.rod.elements": row["beam.rod.elements"],
                                           "dynamic.dt": row["dynamic.dt"],
                                           "material.rod.E": row["material.rod.E"]}, out=tmpdir("one"))
    assert one.summary["sensors"]["B"]["displacement"][2] == row["B.uz"]

    sched_file = tmpdir("sched") / "scheduler.json"
    env = dict(ENV, OMP_NUM_THREADS="1")
    procs = []
    try:
        procs.append(subprocess.Popen(["dask-scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                                       "--scheduler-file", str(sched_file)], env=env,
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True))
        for _ in range(2):
            procs.append(subprocess.Popen(["dask-worker", "--scheduler-file", str(sched_file), "--nthreads", "1",
                                           "--no-nanny", "--no-dashboard", "--host", "127.0.0.1"], env=env,
                                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                          start_new_session=True))
        from distributed import Client
        t0 = time.monotonic()
        while not sched_file.exists() and time.monotonic() - t0 < 60:
            time.sleep(0.2)
        addr = json.loads(sched_file.read_text())["address"]
        assert addr.startswith("tcp://127.0.0.1:")
        with Client(addr, timeout="30s") as c:
            c.wait_for_workers(2, timeout=90)
            pids = set(c.run(os.getpid).values())
        assert pids == {p.pid for p in procs[1:]}          # the runs go to the two worker processes
        from beamkit.cluster import connect
        with connect(str(sched_file)) as c:                 # the scheduler file names it too
            assert len(c.scheduler_info()["workers"]) == 2
        args = ["sweep", "pendulum_soft_ancf", "--set", "dynamic.t_end=0.2", "--out", str(out_remote), "--quiet",
                "--scheduler", addr]
        for k, v in pendulum_grid().items():
            args += ["--grid", f"{k}={','.join(map(str, v))}"]
        r = run_cli(args, timeout=300)
        assert r.returncode == 0, r.stderr[-2000:]
        assert "8 runs (0 reused), 0 failed" in r.stdout
    finally:
        for p in procs:
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGTERM)
        for p in procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()
    assert all(p.poll() is not None for p in procs)
    local = read_table(out_local / "sweep.csv")
    remote = read_table(out_remote / "sweep.csv")
    assert len(local) == 8 and local == remote


def test_sweep_keeps_failed_runs_and_a_restart_redoes_nothing():
    out = tmpdir("swf")
    grid = {"beam.arm.elements": [2, 3, 4, 0], "static.max_iterations": [25, 1]}
    res = sweep("cantilever_bend_100N", grid=grid, out=out, workers=2, progress=False,
                outputs=["tip.uz", "newton_iterations"])
    rows = res.rows
    assert len(rows) == 8
    assert [r["converged"] for r in rows] == [True, False] * 3 + [False, False]
    for r in rows[1:6:2]:
        assert "no convergence within the iteration limit" in r["error"] and r["tip.uz"] is None
    for r in rows[6:]:
        assert "beam.arm.elements: expected an integer in [1, 1000000], found 0" in r["error"]
    for r in rows[:6:2]:
        assert r["error"] == "" and r["tip.uz"] < -0.1
    table = read_table(out / "sweep.csv")
    assert [t["converged"] for t in table] == [str(r["converged"]) for r in rows]
    stamps = {p: p.stat().st_mtime_ns for p in (out / "runs").glob("*/sweep-run.json")}
    assert len(stamps) == 8
    again = sweep("cantilever_bend_100N", grid=grid, out=out, workers=2, progress=False,
                  outputs=["tip.uz", "newton_iterations"])
    assert again.reused == 8
    assert {p: p.stat().st_mtime_ns for p in (out / "runs").glob("*/sweep-run.json")} == stamps
    assert read_table(out / "sweep.csv") == table
    # an interrupted sweep: the run without its marker is the only one redone
    victim = out / rows[2]["dir"] / "sweep-run.json"
    victim.unlink()
    r = run_cli(["sweep", "cantilever_bend_100N", "--grid", "beam.arm.elements=2,3,4,0",
                 "--grid", "static.max_iterations=25,1", "--out", str(out), "--output", "tip.uz",
                 "--output", "newton_iterations", "--quiet", "--workers", "1"])
    assert r.returncode == 2 and "8 runs (7 reused), 5 failed" in r.stdout, r.stdout + r.stderr
    assert read_table(out / "sweep.csv") == table


def pendulum_data(true, sigma, seed=3):
    sc = Scene("pendulum_soft_ancf", sets={"dynamic.t_end": 0.4, "beam.rod.elements": 4, "dynamic.dt": 0.01})
    s = sc.run(true, out=tmpdir("truth")).sensor("B")
    rng = np.random.default_rng(seed)
    vals = {c: s.displacement[:, i] + sigma * rng.standard_normal(len(s.time)) for i, c in enumerate("xyz")
            if c != "y"}
    vals = {"u" + c: v for c, v in vals.items()}
    vals["uz"][::3] = np.nan                             # missing values
    path = write_data(tmpdir("data") / "measured.csv", s.time, vals, "synthetic: pendulum + noise")
    return sc, path


def test_fit_recovers_synthetic_parameters_within_three_standard_errors():
    true = {"material.rod.E": 3e7, "dynamic.rayleigh_alpha": 0.5}
    sc, path = pendulum_data(true, sigma=2e-3)
    res = fit(sc, path, {"material.rod.E": (1e7, 1e8, 2e7), "dynamic.rayleigh_alpha": (0.0, 2.0, 0.2)},
              workers=2, out=tmpdir("fit"), progress=False)
    for k, v in true.items():
        assert 0 < res.stderr[k] < 0.1 * v, res.stderr
        assert abs(res.values[k] - v) < 3 * res.stderr[k], (k, res.values[k], res.stderr[k])
    assert 1e-3 < res.rms < 3e-3                         # the noise level
    assert res.plot.stat().st_size > 5000 and (res.dir / "fit.json").exists()
    assert not res.at_bound and res.success


def test_fit_plot_title_carries_units():
    """fit.png's title names the scene and gives each value with its unit."""
    from types import SimpleNamespace
    from beamkit.fit import fit_title
    res = SimpleNamespace(keys=["material.s.E", "material.s.kelvin_voigt", "beam.b.elements"], rms=6.6e-7,
                          values={"material.s.E": 1194395.0, "material.s.kelvin_voigt": 4.777e-3,
                                  "beam.b.elements": 8.0},
                          stderr={"material.s.E": 178.0, "material.s.kelvin_voigt": 1.27e-4, "beam.b.elements": 0.5})
    assert fit_title(res, "finger") == ("finger: rms 6.6e-07 m\nE = 1.194e+06 ± 1.8e+02 Pa, "
                                        "kelvin_voigt = 0.004777 ± 0.00013 s, elements = 8 ± 0.5")


def test_fit_honours_max_runs_exactly():
    """--max-runs counts solver runs, the Jacobian's included (10 used to make 18):
    a budget the fit reaches stops it with the best run so far, not converged; a
    budget below what one step needs is refused before any run."""
    true = {"material.rod.E": 3e7, "dynamic.rayleigh_alpha": 0.5}
    sc, path = pendulum_data(true, sigma=2e-3)
    ps = {"material.rod.E": (1e7, 1e8, 2e7), "dynamic.rayleigh_alpha": (0.0, 2.0, 0.2)}
    res = fit(sc, path, ps, workers=2, out=tmpdir("fitb"), progress=False, max_nfev=7, plot=False)
    runs = json.loads((res.dir / "fit.json").read_text())["runs"]
    assert res.nfev == len(runs) <= 7 and not res.success and "--max-runs 7" in res.status
    assert abs(res.cost - min(r["cost"] for r in runs)) <= 1e-12 * res.cost
    with pytest.raises(BeamkitError, match=r"--max-runs 3 is too small: 2 parameters need at least 4 runs"):
        fit(sc, path, ps, workers=1, out=tmpdir("fitc3"), progress=False, max_nfev=3)


def test_fit_refuses_parameters_the_data_cannot_identify():
    sc, path = pendulum_data({"material.rod.E": 3e7}, sigma=1e-3)
    # under gravity alone only E / rho matters
    with pytest.raises(BeamkitError, match=r"do not identify (material.rod.E and material.rod.rho|"
                                           r"material.rod.rho and material.rod.E) apart"):
        fit(sc, path, {"material.rod.E": (1e7, 1e8, 2e7), "material.rod.rho": (1000, 5000)}, workers=1,
            out=tmpdir("fitu"), progress=False)
    # a static cantilever under a tip force: the density changes nothing
    cb = Scene("cantilever_bend_100N", sets={"static.load_steps": 4, "static.step_control": "fixed"})
    s = cb.run(out=tmpdir("cbt")).sensor("tip")
    data = write_data(tmpdir("cbd") / "m.csv", s.time, {"x": s.position[:, 0], "z": s.position[:, 2]})
    data.write_text(data.read_text().replace("t,x,z", "load_factor,x,z"))
    with pytest.raises(BeamkitError, match=r"error: fit: the data do not identify material.alu.rho: "):
        fit(cb, data, {"material.alu.E": (5e10, 1e11), "material.alu.rho": (1000, 5000)}, workers=1,
            out=tmpdir("fitc"), progress=False)


def test_bad_input_one_line_each():
    d = tmpdir("bad")
    bad_data = d / "nocols.csv"
    bad_data.write_text("t,a,b\n0,1,2\n")
    cases = [
        (["sweep", "cantilever_bend_100N", "--grid", "beam.arm.foo=1,2"],
         "beam.arm.foo: unknown key; expected one of"),
        (["sweep", "cantilever_bend_100N", "--grid", "beam.arms.elements=4,8"],
         "--grid beam.arms.elements: no entry named or numbered 'arms' in 'beam'"),
        (["sweep", "cantilever_bend_100N", "--random", "material.steel.E=1e10:2e10", "--samples", "2"],
         "--random material.steel.E: "),
        (["sweep", "cantilever_bend_100N", "--grid", "beam.arm.elements="],
         "error: --grid beam.arm.elements=: no values; expected KEY=v1,v2,..."),
        (["sweep", "cantilever_bend_100N", "--random", "material.alu.E=5e10:5e10", "--samples", "3"],
         "error: --random material.alu.E=5e10:5e10: lower bound 50000000000.0 must be below the upper bound"),
        (["sweep", "cantilever_bend_100N", "--grid", "beam.arm.elements=2", "--output", "nope.uz"],
         "error: --output nope.uz: no sensor 'nope'"),
        (["fit", "cantilever_bend_100N", "--data", str(bad_data), "--param", "material.alu.E=2e11:1e11"],
         "error: --param material.alu.E=2e11:1e11: lower bound 200000000000.0 must be below the upper bound"),
        (["fit", "cantilever_bend_100N", "--data", str(bad_data), "--param", "material.alu.E=5e10:1e11"],
         f"error: {bad_data}: no measured component; expected one or more of the columns x, y, z or ux, uy, uz"),
        (["fit", "cantilever_bend_100N", "--data", str(d / "missing.csv"), "--param", "material.alu.E=5e10:1e11"],
         f"error: {d / 'missing.csv'}: cannot read the data file"),
    ]
    for args, msg in cases:
        r = run_cli(args + ["--out", str(d / "o"), "--quiet"])
        lines = r.stderr.strip().splitlines()
        assert r.returncode == 1 and len(lines) == 1 and msg in lines[0], (args, r.stderr)


def _tagged(tag):
    """Processes whose environment holds BK_TEST_TAG=tag."""
    out = []
    for p in Path("/proc").iterdir():
        if p.name.isdigit():
            try:
                if f"BK_TEST_TAG={tag}".encode() in (p / "environ").read_bytes().split(b"\0"):
                    out.append(int(p.name))
            except OSError:
                pass
    return out


def test_unreachable_scheduler_fails_within_ten_seconds_and_leaves_nothing():
    # the sweep builds the scene's solver before it connects: built here first, so
    # that the ten seconds are the scheduler's (a fresh clone's first build of it
    # on a loaded machine took 50 s)
    run_cli(["run", "cantilever_bend_100N", "--quiet", "--out", str(tmpdir("unr-build"))], check=True)
    tag = uuid.uuid4().hex
    t0 = time.monotonic()
    r = run_cli(["sweep", "cantilever_bend_100N", "--grid", "beam.arm.elements=2,3", "--out",
                 str(tmpdir("unr")), "--scheduler", "tcp://127.0.0.1:9", "--quiet"],
                env={"BK_TEST_TAG": tag}, timeout=60)
    took = time.monotonic() - t0
    assert r.returncode == 1 and took < 10, (took, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(
        "error: --scheduler tcp://127.0.0.1:9: no Dask scheduler answered within"), r.stderr
    assert _tagged(tag) == []
