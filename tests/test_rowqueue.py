"""The result tables' rows formatted by the writer thread (runtime/base/csvrow.c
bk_rowqueue: recorded as values, formatted in order by the frames' writer
thread) have the text glibc's fprintf gives the same rows: the C harness
tests/rowqueue_check.c under AddressSanitizer + UBSan; and a dynamic and a
static run whose frames start that thread write the same tables as the same
runs without frames (formatted in the solver's thread)."""
import subprocess
import tempfile
from functools import lru_cache
from pathlib import Path

import pytest

from util import BUILD, build_runtime_program, ensure_dir, run_cli


def fresh():
    return Path(tempfile.mkdtemp(prefix="bk-rows-", dir=ensure_dir(BUILD / "runs")))


@lru_cache(maxsize=None)
def harness():
    return build_runtime_program(["rowqueue_check.c"], "rowqueue_check", "sanitize")


@pytest.mark.parametrize("step_bytes, cycle", [(0, 4), (3_000_000, 26), (10**9, 32)])
def test_queued_rows_are_glibc_text(step_bytes, cycle):
    """60,000 random rows over three tables (spanning chunks, with flushes and names
    longer than a string piece and than a row buffer): not one byte differs from fprintf's,
    with the queue's four chunks and with a cycle of 26 and of 32 (a large model's
    sections.csv: the solver goes on while the thread formats)."""
    d = fresh()
    r = subprocess.run([str(harness()), str(d), "60000", str(step_bytes)], capture_output=True, text=True,
                       timeout=600)
    assert "runtime error" not in r.stderr and "Sanitizer" not in r.stderr, r.stderr[-4000:]
    assert r.returncode == 0, (r.stdout, r.stderr[-4000:])
    got = dict(kv.split("=") for kv in r.stdout.split())
    assert int(got["cycle"]) == cycle, got
    assert int(got["differ"]) == 0 and int(got["chunks"]) > 2 * cycle and int(got["bytes"]) > 5_000_000, got


def _tables(scene, sets, names):
    out = fresh()
    assert run_cli(["run", scene, "--quiet", "--out", str(out)] + sets).returncode == 0
    return out, {n: (out / n).read_bytes() for n in names}


def test_last_rows_formatted_by_the_stop_when_the_thread_is_idle():
    """bk_rowqueue_stop formats the rows not yet handed over itself when the
    thread has done all it was given (no wake-up and wait at a run's end): the
    tables are still fprintf's bytes."""
    d = fresh()
    r = subprocess.run([str(harness()), str(d), "20000", "0", "idle"], capture_output=True, text=True, timeout=600)
    assert "runtime error" not in r.stderr and "Sanitizer" not in r.stderr, r.stderr[-4000:]
    assert r.returncode == 0, (r.stdout, r.stderr[-4000:])
    got = dict(kv.split("=") for kv in r.stdout.split())
    assert got["local"] == "1" and int(got["differ"]) == 0, got


def test_tables_the_same_with_and_without_the_writer_thread():
    """The soft pendulum (dynamics, 200 steps, 41 frames: the writer thread from its first
    frame) and the two-turn roll-up (statics, a frame per step: the thread from its second)
    write the same sensors, energy, reactions, newton and stability tables as without
    frames (output.vtk_every = 0: every row formatted in the solver's thread)."""
    dyn = ["--set", "dynamic.dt=1e-3", "--set", "dynamic.t_end=0.2"]
    names = ["sensors.csv", "energy.csv", "reactions.csv"]
    a_dir, a = _tables("pendulum_soft_ancf", dyn + ["--set", "output.vtk_every=5"], names)
    _, b = _tables("pendulum_soft_ancf", dyn + ["--set", "output.vtk_every=0"], names)
    assert len(list(a_dir.glob("step_*.vtu"))) == 41
    for n in names:
        assert a[n] == b[n] and a[n].count(b"\n") > 200, n
    names = ["sensors.csv", "reactions.csv", "newton.csv", "stability.csv"]
    a_dir, a = _tables("cantilever_rollup", [], names)
    _, b = _tables("cantilever_rollup", ["--set", "output.vtk_every=0"], names)
    assert len(list(a_dir.glob("step_*.vtu"))) >= 10
    for n in names:
        assert a[n] == b[n] and a[n].count(b"\n") > 10, n
