"""Results that are likely wrong say so, on the console and in summary.json
"warnings", even when Newton converged.  Before: -1e9 N along the default
cantilever "converged" with the beam turned inside out (tip at x = -5.9 m), +1e9 N
stretched it 6 times, and nothing was said."""
import json
import tempfile
from pathlib import Path

from util import BUILD, ensure_dir, run_cli


def run(scene, sets, quiet=False):
    out = Path(tempfile.mkdtemp(prefix="bk-warn-", dir=ensure_dir(BUILD / "runs")))
    args = ["run", scene, "--out", str(out)] + (["--quiet"] if quiet else [])
    for s in sets:
        args += ["--set", s]
    r = run_cli(args)
    return r, json.loads((out / "summary.json").read_text())


def test_inverted_beam_is_reported():
    r, s = run("cantilever_axial_10kN", ["load.0.value.0=-1e9"])
    assert r.returncode == 0 and s["converged"]
    w = "\n".join(s["warnings"])
    assert "is inverted" in w and "J = det F" in w, s["warnings"]
    assert "warning: cantilever_axial_10kN: element" in r.stderr and "inverted" in r.stderr, r.stderr
    assert "warnings: the result may be wrong" in r.stdout, r.stdout


def test_huge_stretch_is_outside_the_range_of_the_law():
    r, s = run("cantilever_axial_10kN", ["load.0.value.0=1e9"], quiet=True)
    assert s["converged"]
    w = "\n".join(s["warnings"])
    assert "principal Green strain" in w and "range law svk is meant for" in w, s["warnings"]
    assert "volume ratio J" in w, s["warnings"]
    assert r.stderr == "", r.stderr          # --quiet: warnings only in summary.json


def test_moderate_load_has_no_warning():
    r, s = run("cantilever_bend_100N", [])
    assert s["converged"] and s["warnings"] == [], s["warnings"]
    assert "warning" not in r.stderr


def test_bifurcation_passed_is_a_warning():
    """The straight compressed cantilever at -1 kN in one step passes the Euler load (148 N)."""
    r, s = run("cantilever_buckling_imperfect", ["load.0.value.0=-1000", "load.1.value.2=0",
                                                 "static.load_steps=1"], quiet=True)
    assert s["converged"]
    w = [x for x in s["warnings"] if "negative tangent eigenvalues went from 0 to 2" in x]
    assert len(w) == 1 and "bifurcation or limit point" in w[0], s["warnings"]
    lam = s["stability"]["events"][0]["critical_load_factor"]
    assert f"{lam:.6g}" in w[0], (lam, w[0])


def test_locking_element_choice_is_a_warning():
    sets = ["beam.strip.elements=4", "dynamic.t_end=0.001", "dynamic.dt=0.001"]
    r, s = run("silicone_fall", sets + ["beam.strip.element=ancf3273", "beam.strip.integration=reduced"], quiet=True)
    w = "\n".join(s["warnings"])
    assert "volumetric locking" in w and 'use integration = "sri"' in w, s["warnings"]
    r, s = run("silicone_fall", sets + ["beam.strip.element=ancf3273", "beam.strip.integration=sri"], quiet=True)
    assert not any("locking" in x for x in s["warnings"]), s["warnings"]
    r, s = run("cantilever_bend_100N_nu03", ["beam.arm.integration=full"], quiet=True)
    assert any("Poisson locking" in x for x in s["warnings"]), s["warnings"]
