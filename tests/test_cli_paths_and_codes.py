"""Command-line traps of a new user: paths relative to the caller's directory,
exit codes that tell bad input, usage errors and failed solves apart."""
import json
import re
import shutil
import subprocess
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


def test_a_test_file_given_to_build_sh_test_runs_only_that_file():
    """`./build.sh test tests/FILE.py` (or a node id, or a path from the caller's
    directory) collects that file's tests, not the whole tests/ folder as well;
    with no path the whole folder (checked against the files' own test
    functions, counted here by their `def test_` lines)."""
    own = (ROOT / "tests" / "test_numfmt.py").read_text().count("\ndef test_")
    for args, cwd in ((["tests/test_numfmt.py"], ROOT), (["test_numfmt.py"], ROOT / "tests"),
                      ([str(ROOT / "tests" / "test_numfmt.py")], BUILD)):
        r = run_cli(["test", *args, "--collect-only", "-q", "-n", "0"], cwd=cwd, env={"BK_CALLER_CWD": ""})
        assert r.returncode == 0 and f"{own} tests collected" in r.stdout, (args, r.stdout[-500:])
    r = run_cli(["test", "-k", "test_numfmt.py", "--collect-only", "-q", "-n", "0"])
    assert f"{own}/" in r.stdout and "deselected" in r.stdout, r.stdout[-500:]


def test_usage_errors_exit_64_and_are_listed_in_help():
    for args in (["run", "cantilever_bend_10N", "--bogus"], ["bogus-command"], ["run"]):
        r = run_cli(args)
        assert r.returncode == 64, (args, r.returncode, r.stderr)
        assert "error" in r.stderr and "Traceback" not in r.stderr, r.stderr
    h = run_cli(["--help"]).stdout
    for code in ("64", "130", "143", "99"):
        assert code in h, code
    readme = (ROOT / "docs" / "reference" / "commands.md").read_text()
    for code in ("| 64 |", "| 130 |", "| 143 |", "| 2 |", "| 1 |", "| 99 |"):
        assert code in readme, code


MECHANISM = """
[scene]
analysis = "static"
[material.alu]
law = "resultant"
E = 7.2e10
nu = 0.3
rho = 2700.0
[section.square]
shape = "rectangle"
b = 0.01
h = 0.01
[[beam]]
name = "arm"
element = "gef"
material = "alu"
section = "square"
start = [0.0, 0.0, 0.0]
end = END
elements = 4
[[constraint]]
type = "spherical"
a = "arm:start"
[[load]]
type = "force"
at = "arm:end"
value = FORCE
[static]
free_rigid_motion = true   # the spin about the axis is a rigid motion: let the solver meet it
"""


def _mechanism(end, force):
    d = Path(tempfile.mkdtemp(prefix="bk-mech-", dir=ensure_dir(BUILD / "runs")))
    p = d / "mechanism.toml"
    p.write_text(MECHANISM.replace("END", str(end)).replace("FORCE", str(force)))
    r = run_cli(["run", str(p), "--quiet", "--out", str(d / "out")])
    return r, json.loads((d / "out" / "summary.json").read_text())


def test_singular_tangent_is_named_with_its_likely_cause():
    """A beam on a spherical joint pulled along its axis can spin about the axis: the
    tangent is singular.  Before: "no convergence within the iteration limit; residual
    2.1e-08" (inclined beam) or "... last increment inf after 0 iterations, 12 cut-backs;
    ... a bifurcation or limit point was passed" (axis-aligned)."""
    r, s = _mechanism([1.0, 0.0, 0.0], [100.0, 0.0, 0.0])
    if r.returncode == 2:               # an exact zero pivot: no equilibrium can be computed
        msg = s["error"]
        assert "singular tangent" in msg and "likely cause: a rigid motion or mechanism" in msg, msg
        assert "inf" not in msg and "iteration limit" not in msg and "bifurcation" not in msg, msg
        assert s["cutbacks"] == 0, s      # cutting back cannot cure a singular reference state
    else:                               # a pivot at round-off: found, and said to be not unique
        assert r.returncode == 0
        assert any("numerically singular tangent" in w and "not unique" in w for w in s["warnings"]), s
    # turned in space the pivot is ~1e-15 instead of 0: the equilibrium is found (any
    # spin angle is one) and a warning says that it is not unique
    r, s = _mechanism([0.8, 0.5, 0.33166247903554], [80.0, 50.0, 33.166247903554])
    assert r.returncode == 0, s["error"]
    w = " ".join(s["warnings"])
    assert "numerically singular tangent" in w and "not unique" in w and "likely cause" in w, s["warnings"]
    assert sum("numerically singular tangent" in x for x in s["warnings"]) == 1, s["warnings"]


def test_an_iteration_limit_with_the_residual_met_says_which_test_failed():
    """Too few iterations (static.max_iterations = 3): the residual meets its
    tolerance, the increment does not.  Before: the message showed the residual
    under its tolerance, the increment without one, and the slack-cable hint."""
    d = Path(tempfile.mkdtemp(prefix="bk-maxit-", dir=ensure_dir(BUILD / "runs")))
    r = run_cli(["run", "silicone_cantilever_sag", "--quiet", "--out", str(d), "--set", "static.load_steps=1",
                 "--set", "static.max_iterations=3"])
    assert r.returncode == 2, r.stderr
    msg = json.loads((d / "summary.json").read_text())["error"]
    m = re.search(r"residual (\S+) \(tolerance (\S+)\), last increment (\S+) \(tolerance (\S+)\)", msg)
    assert m, msg
    res, rtol, inc, utol = (float(x) for x in m.groups())
    assert res <= rtol and inc > utol, msg
    assert "raise static.max_iterations" in msg and "slack cable" not in msg, msg


def test_cutback_counts_are_the_cutbacks_made():
    """Before: max_cutbacks = 0 reported "1 cut-backs"."""
    d = Path(tempfile.mkdtemp(prefix="bk-cut-", dir=ensure_dir(BUILD / "runs")))
    r = run_cli(["run", "pendulum_stiff_ancf", "--quiet", "--out", str(d), "--set", "dynamic.max_cutbacks=0",
                 "--set", "dynamic.dt=0.05", "--set", "dynamic.max_iterations=2"])
    assert r.returncode == 2
    s = json.loads((d / "summary.json").read_text())
    assert "0 cut-backs in a row" in s["error"] and s["cutbacks"] == 0, s
    r = run_cli(["run", "cantilever_rollup", "--quiet", "--out", str(d), "--set", "static.max_cutbacks=1",
                 "--set", "static.load_steps=1", "--set", "static.max_iterations=3"])
    assert r.returncode == 2
    s = json.loads((d / "summary.json").read_text())
    assert s["error"].endswith("1 cut-back") and s["cutbacks"] == 1, s


def test_the_run_line_counts_in_the_singular_for_one():
    """Before: "1 steps" (issue 39).  One load step of one element: "1 step,"
    and "1 element,"; the default run: "2 steps," and "10 elements,"."""
    r = run_cli(["run", "cantilever_bend_10N", "--set", "static.load_steps=1", "--set", "beam.arm.elements=1",
                 "--out", str(Path(tempfile.mkdtemp(prefix="bk-one-", dir=ensure_dir(BUILD / "runs"))))])
    assert r.returncode == 0 and "converged; 1 step, " in r.stdout and " 1 element, " in r.stdout, r.stdout
    r = run_cli(["run", "cantilever_bend_10N", "--out",
                 str(Path(tempfile.mkdtemp(prefix="bk-two-", dir=ensure_dir(BUILD / "runs"))))])
    assert r.returncode == 0 and "converged; 2 steps, " in r.stdout and " 10 elements, " in r.stdout, r.stdout


def test_the_solver_makes_a_missing_results_directory_and_refuses_a_file():
    """The per-scene solver run directly (out/bin/SCENE MODEL OUT_DIR): a missing
    OUT_DIR is made (its parent exists); a file, or a missing parent, is refused at
    once with one error line naming it (exit 1), before the model is read."""
    work = Path(tempfile.mkdtemp(prefix="bk-solver-dir-", dir=ensure_dir(BUILD / "runs")))
    r = run_cli(["run", "cantilever_bend_10N", "--quiet", "--out", str(work / "first")])
    assert r.returncode == 0, r.stderr
    solver, model = ROOT / "out" / "bin" / "cantilever_bend_10N", work / "first" / "model.dat"
    r = subprocess.run([str(solver), str(model), str(work / "made"), "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    a = json.loads((work / "first" / "summary.json").read_text())
    b = json.loads((work / "made" / "summary.json").read_text())
    assert a["sensors"] == b["sensors"] and a["converged"] and b["converged"]
    (work / "file").write_text("not a directory\n")
    for target, words in ((work / "file", "is not a directory"), (work / "no" / "such", "cannot make")):
        r = subprocess.run([str(solver), str(model), str(target), "--quiet"], capture_output=True, text=True)
        lines = [l for l in r.stderr.splitlines() if l.startswith("error")]
        assert r.returncode == 1 and len(lines) == 1 and str(target) in lines[0] and words in lines[0], r.stderr
