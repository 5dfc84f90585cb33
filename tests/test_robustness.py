"""The runtime under AddressSanitizer + UndefinedBehaviorSanitizer."""
from util import load_run, run_cli, run_memcheck, BUILD, ensure_dir
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
    """One static run of the solver under valgrind memcheck (`run --memcheck`): no errors,
    no leaks (the OpenMP runtime's own start-up allocation, reachable until exit, is
    suppressed by runtime/valgrind.supp)."""
    r, out = run_memcheck("cantilever_bend_10N")
    assert r.returncode == 0, r.stderr[-4000:]
    assert "ERROR SUMMARY: 0 errors" in r.stderr, r.stderr[-4000:]
    s, rows = load_run(out)
    assert s["converged"] and len(rows) == s["steps"] + 1
