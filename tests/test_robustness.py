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
