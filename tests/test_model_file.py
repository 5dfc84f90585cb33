"""The model file is versioned and its scalar records are named fields
(gen/scene/model_file.py RECORDS, read by name in runtime/model/model.c): a file of
another version, a renamed or missing field, or material parameters that do not
match the kernel's parameter names are refused with one line naming them."""
import json
import re
import subprocess
import tempfile
from pathlib import Path

from gen.scene import model_file
from util import BUILD, ROOT, ensure_dir, run_cli


def _run():
    """The scene run, and its solver: out/bin/cantilever_bend_10N resolved, taken
    only when that solver links the scene's kernel (another test on the other
    worker may relink the name to a solver of other kernels between the run and
    here: tests/test_fast_run.py runs the scene with ancf3363)."""
    out = Path(tempfile.mkdtemp(prefix="bk-mf-", dir=ensure_dir(BUILD / "runs")))
    for _ in range(5):
        r = run_cli(["run", "cantilever_bend_10N", "--quiet", "--out", str(out)])
        assert r.returncode == 0, r.stderr
        solver = (ROOT / "out" / "bin" / "cantilever_bend_10N").resolve()
        pairs = Path(str(solver) + ".pairs")
        if pairs.exists() and "ancf3243_svk_full" in pairs.read_text().split():
            return out, solver
    raise AssertionError(f"out/bin/cantilever_bend_10N kept linking a solver without ancf3243_svk_full ({solver})")


def _solve(solver, out, text):
    p = out / "edited.dat"
    p.write_text(text)
    work = out / "w"
    work.mkdir(exist_ok=True)
    return subprocess.run([str(solver), str(p), str(work), "--quiet"], capture_output=True, text=True)


def test_every_record_field_is_written_by_name_in_schema_order():
    out, _ = _run()
    text = (out / "model.dat").read_text()
    assert text.startswith(f"beamkit-model {model_file.VERSION}\n")
    for rec, fields in model_file.RECORDS.items():
        line = next(l for l in text.splitlines() if l.startswith(rec + " "))
        assert [t.split("=", 1)[0] for t in line.split()[1:]] == list(fields), (rec, line)
    assert re.search(r"^mat rho=\S+ params=2 lambda=\S+ mu=\S+ visc=0", text, re.M), text


def test_other_version_renamed_field_and_wrong_parameter_names_are_refused():
    out, solver = _run()
    text = (out / "model.dat").read_text()
    r = _solve(solver, out, text.replace(f"beamkit-model {model_file.VERSION}", "beamkit-model 1", 1))
    assert r.returncode == 1 and f"format version 1, this solver reads version {model_file.VERSION}" in r.stderr, \
        r.stderr
    r = _solve(solver, out, text.replace(" rtol=", " r_tol=", 1))
    assert r.returncode == 1 and "record 'static': expected field 'rtol=...'" in r.stderr, r.stderr
    r = _solve(solver, out, text.replace(" lambda=", " kappa=", 1))
    assert r.returncode == 1 and "material parameter 1 is 'kappa', kernel ancf3243_svk expects 'lambda'" in r.stderr, \
        r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


def test_option_records_are_checked_by_the_generated_descriptor_table():
    """runtime/model/options.c reads the option records by out/kernels/bk_options.h
    (gen/options_schema.py): choices by name, numbers and integers in range."""
    out, solver = _run()
    text = (out / "model.dat").read_text()
    assert " step_control=adaptive\n" in text and " about=reference solver=auto\n" in text
    r = _solve(solver, out, text.replace(" solver=auto", " solver=lanczos", 1))
    assert r.returncode == 1 and "modal.solver: 'lanczos' is not supported by this solver (expected one of: " \
                                 "auto dense sparse)" in r.stderr, r.stderr
    r = _solve(solver, out, text.replace(" step_control=adaptive", " step_control=adaptve", 1))
    assert r.returncode == 1 and "static.step_control: 'adaptve' is not supported by this solver (expected one of: " \
                                 "adaptive fixed)" in r.stderr, r.stderr
    r = _solve(solver, out, text.replace(" rho_inf=0.8 ", " rho_inf=1.5 ", 1))
    assert r.returncode == 1 and "dynamic.rho_inf: expected a number in [0, 1], found 1.5" in r.stderr, r.stderr
    r = _solve(solver, out, text.replace(" max_iterations=25 ", " max_iterations=0 ", 1))
    assert r.returncode == 1 and "static.max_iterations: expected an integer in [1, 10000], found '0'" in r.stderr, \
        r.stderr


def test_scene_warnings_travel_in_the_model_file_and_lead_summary_warnings():
    """The scene reader's warnings are the model file's last records (one line
    each, backslash and newline escaped) and the solver lists them first in
    summary.json, as written, each once beside its own warnings."""
    out, solver = _run()
    text = (out / "model.dat").read_text()
    assert text.endswith("\nwarnings 0\nend\n"), text[-200:]
    odd = 'a back\\slash, a "quote",\na second line and ünïcode'
    scene = ["locking ahead", odd]
    lines = "".join("warning " + model_file._line(w) + "\n" for w in scene)
    assert lines.count("\n") == 2
    r = _solve(solver, out, text.replace("\nwarnings 0\n", f"\nwarnings 2\n{lines}", 1))
    assert r.returncode == 0, r.stderr
    s = json.loads((out / "w" / "summary.json").read_text(encoding="utf-8"))
    assert s["warnings"] == scene
    r = _solve(solver, out, text.replace("\nwarnings 0\n", "\nwarnings 2\nwarning only one\n", 1))
    assert r.returncode == 1 and "expected keyword 'warning', found 'end'" in r.stderr, r.stderr
