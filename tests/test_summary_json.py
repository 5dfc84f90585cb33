"""summary.json is JSON whatever happened (issue 36: a refused modal run wrote
"strain_energy": -nan and the Python side failed on it): every number goes
through bk_json_num (a non-finite one is null) and the JSON text an analysis or
an interaction hands over is repaired (bk_json_repair: bare nan / inf words
become null, strings untouched).  Parsed strictly: NaN and Infinity refused."""
import json
import subprocess
from functools import lru_cache

from util import build_runtime_program, run_cli, BUILD, ensure_dir
import tempfile


def strict(text):
    def refuse(c):
        raise ValueError(f"not JSON: {c}")
    return json.loads(text, parse_constant=refuse)


@lru_cache(maxsize=None)
def harness():
    return build_runtime_program(["json_check.c"], "json_check", "sanitize")


def test_repair_and_numbers():
    cases = ['[1.5, nan, -nan, inf, -inf, 1e-05, -2.5E+10, null, true, false]',
             '{"a": -nan, "b": [nan], "c": "nan and inf stay in a string \\" nan"}',
             '{"about": "reference", "load_factors": [3.5, -1], "critical_load_factor": null}', '[]']
    r = subprocess.run([str(harness())] + cases, capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and "runtime error" not in r.stderr and "Sanitizer" not in r.stderr, r.stderr
    lines = r.stdout.splitlines()
    assert strict(lines[0]) == [1.5, None, None, None, None, 1e-05, -2.5e10, None, True, False]
    assert strict(lines[1]) == {"a": None, "b": [None], "c": 'nan and inf stay in a string " nan'}
    assert strict(lines[2]) == json.loads(cases[2])
    assert strict(lines[3]) == []
    assert strict(lines[4]) == [None, None, None, None, 0.1]


def test_failed_runs_write_strict_json():
    """Failed runs (an inverted state refused; an iteration limit) still write
    a summary that parses strictly."""
    for scene, sets in (("cantilever_axial_10kN", ["load.0.value.0=-1e9", "static.max_cutbacks=0",
                                                   "static.load_steps=1"]),
                        ("tendon_finger", ["static.max_cutbacks=0", "static.max_iterations=2"])):
        out = tempfile.mkdtemp(prefix="bk-json-", dir=ensure_dir(BUILD / "runs"))
        args = ["run", scene, "--quiet", "--out", out]
        for s in sets:
            args += ["--set", s]
        r = run_cli(args)
        assert r.returncode == 2, r.stderr
        s = strict(open(f"{out}/summary.json").read())
        assert s["converged"] is False and s["error"], s
