"""Command-line traps of a new user: paths relative to the caller's directory,
exit codes that tell bad input, usage errors and failed solves apart."""
import json
import shutil
import tempfile
from pathlib import Path

from util import BUILD, ROOT, ensure_dir, run_cli


def test_relative_scene_and_out_paths_are_the_callers():
    work = Path(tempfile.mkdtemp(prefix="bk-cwd-", dir=ensure_dir(BUILD / "runs")))
    shutil.copy(ROOT / "models" / "cantilever_bend_10N.toml", work / "my.toml")
    r = run_cli(["run", "my.toml", "--quiet", "--out", "rel"], cwd=work, env={"BK_CALLER_CWD": ""})
    assert r.returncode == 0, r.stderr
    s = json.loads((work / "rel" / "summary.json").read_text())
    assert s["converged"] and s["scene"] == "my"
    assert not (ROOT / "rel").exists()
    # names in models/ still work from anywhere; plot takes a relative RUN_DIR
    r = run_cli(["run", "cantilever_bend_10N", "--quiet", "--out", "byname"], cwd=work, env={"BK_CALLER_CWD": ""})
    assert r.returncode == 0, r.stderr
    assert (work / "byname" / "summary.json").exists()
    r = run_cli(["plot", "byname"], cwd=work, env={"BK_CALLER_CWD": ""})
    assert r.returncode == 0, r.stderr
    assert (work / "byname" / "sensors.png").exists()
    r = run_cli(["run", "missing.toml"], cwd=work, env={"BK_CALLER_CWD": ""})
    assert r.returncode == 1 and str(work / "missing.toml") in r.stderr, r.stderr


def test_usage_errors_exit_64_and_are_listed_in_help():
    for args in (["run", "cantilever_bend_10N", "--bogus"], ["bogus-command"], ["run"]):
        r = run_cli(args)
        assert r.returncode == 64, (args, r.returncode, r.stderr)
        assert "error" in r.stderr and "Traceback" not in r.stderr, r.stderr
    h = run_cli(["--help"]).stdout
    for code in ("64", "130", "143", "99"):
        assert code in h, code
    readme = (ROOT / "README.md").read_text()
    for code in ("| 64 |", "| 130 |", "| 143 |", "| 2 |", "| 1 |", "| 99 |"):
        assert code in readme, code
