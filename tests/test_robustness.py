"""The runtime under AddressSanitizer + UndefinedBehaviorSanitizer."""
from util import load_run, run_cli, BUILD, ensure_dir
import tempfile


def test_static_scene_clean_under_asan_ubsan():
    out = tempfile.mkdtemp(prefix="bk-asan-", dir=ensure_dir(BUILD / "runs"))
    r = run_cli(["run", "cantilever_bend3d_50N", "--sanitize", "--quiet", "--out", out])
    assert r.returncode == 0, r.stderr[-4000:]
    assert "Sanitizer" not in r.stderr and "runtime error" not in r.stderr, r.stderr[-4000:]
    s, rows = load_run(out)
    assert s["converged"] and len(rows) == s["steps"] + 1


def test_dynamic_scene_clean_under_asan_ubsan():
    out = tempfile.mkdtemp(prefix="bk-asan-", dir=ensure_dir(BUILD / "runs"))
    r = run_cli(["run", "pendulum_soft_gef", "--sanitize", "--quiet", "--out", out, "--set", "dynamic.t_end=0.1"])
    assert r.returncode == 0, r.stderr[-4000:]
    assert "Sanitizer" not in r.stderr and "runtime error" not in r.stderr, r.stderr[-4000:]
    s, rows = load_run(out)
    assert s["converged"] and s["steps"] == 10


def test_valgrind_memcheck_clean():
    """One static run of the release solver under valgrind memcheck: no errors, no leaks
    (the OpenMP runtime's own start-up allocation, reachable until exit, is suppressed by
    tests/valgrind.supp)."""
    import subprocess
    from pathlib import Path
    out = Path(tempfile.mkdtemp(prefix="bk-vg-", dir=ensure_dir(BUILD / "runs")))
    r = run_cli(["run", "cantilever_bend_10N", "--quiet", "--out", str(out)])
    assert r.returncode == 0, r.stderr
    solver = Path(__file__).resolve().parent.parent / "out" / "bin" / "cantilever_bend_10N"
    supp = Path(__file__).resolve().parent / "valgrind.supp"  # libgomp's own start-up allocation only
    v = subprocess.run(["valgrind", "--error-exitcode=99", "--leak-check=full", "--errors-for-leak-kinds=all",
                        f"--suppressions={supp}",
                        "--show-leak-kinds=all", "-q", str(solver), str(out / "model.dat"), str(out), "--quiet"],
                       capture_output=True, text=True, timeout=600)
    assert v.returncode == 0, v.stderr[-4000:]
