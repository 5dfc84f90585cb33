"""Ctrl-C and SIGTERM during a run: the run stops cleanly (no traceback), keeps
every converged step, writes summary.json with "interrupted": true, exits 130
(SIGINT) or 143 (SIGTERM), and the run directory can be plotted."""
import csv
import json
import os
import signal
import subprocess
import tempfile
import time
from pathlib import Path

from util import BUILD, ENV, ROOT, ensure_dir, run_cli


def start(scene, sets, out):
    args = [str(ROOT / "build.sh"), "run", scene, "--quiet", "--out", str(out)]
    for s in sets:
        args += ["--set", s]
    # a session of its own: killpg then reaches the front end and the solver, as
    # Ctrl-C at a terminal reaches the foreground process group
    return subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=ENV,
                            start_new_session=True)


def wait_rows(out, n, proc, timeout=300):
    t0 = time.time()
    path = out / "sensors.csv"
    while time.time() - t0 < timeout:
        assert proc.poll() is None, "the run ended before it could be interrupted: " + proc.stderr.read()[-2000:]
        if path.exists() and sum(1 for _ in open(path)) > n:
            return
        time.sleep(0.05)
    raise AssertionError("no progress")


def check_interrupted(out, proc, code, signame):
    so, se = proc.communicate(timeout=120)
    assert proc.returncode == code, (proc.returncode, se[-3000:])
    assert "Traceback" not in se, se[-3000:]
    assert f"interrupted by {signame}" in se, se[-3000:]
    s = json.loads((out / "summary.json").read_text())
    assert s["interrupted"] is True and s["signal"] == signame and s["converged"] is False, s
    with open(out / "sensors.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    steps = sorted({int(r["step"]) for r in rows})
    assert steps == list(range(s["steps"] + 1)), (steps[-3:], s["steps"])   # every converged step, once
    assert s["steps"] >= 20
    r = run_cli(["plot", str(out)])
    assert r.returncode == 0, r.stderr[-2000:]
    assert (out / "sensors.png").exists()
    return s


def test_ctrl_c_during_a_dynamic_run():
    out = Path(tempfile.mkdtemp(prefix="bk-int-", dir=ensure_dir(BUILD / "runs")))
    p = start("double_pendulum_soft_gef", ["dynamic.t_end=50", "dynamic.output_every=1"], out)
    wait_rows(out, 60, p)
    os.killpg(p.pid, signal.SIGINT)
    s = check_interrupted(out, p, 130, "SIGINT")
    assert 0 < s["time"] < 50


def test_sigterm_to_the_front_end_during_a_static_run():
    """SIGTERM sent to the build.sh process only (as `kill PID` does): passed on to the solver."""
    out = Path(tempfile.mkdtemp(prefix="bk-int-", dir=ensure_dir(BUILD / "runs")))
    p = start("cantilever_rollup", ["static.load_steps=100000", "static.stability=false", "static.step_control=fixed"], out)
    wait_rows(out, 40, p)
    os.kill(p.pid, signal.SIGTERM)
    s = check_interrupted(out, p, 143, "SIGTERM")
    assert 0 < s["load_factor"] < 1
