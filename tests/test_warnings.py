"""Results that are likely wrong say so, on the console and in summary.json
"warnings", even when Newton converged.  Before: -1e9 N along the default
cantilever "converged" with the beam turned inside out (tip at x = -5.9 m), +1e9 N
stretched it 6 times, and nothing was said."""
import json
import tempfile
from pathlib import Path

from util import BUILD, ROOT, ensure_dir, run_cli


def run(scene, sets, quiet=False):
    out = Path(tempfile.mkdtemp(prefix="bk-warn-", dir=ensure_dir(BUILD / "runs")))
    args = ["run", scene, "--out", str(out)] + (["--quiet"] if quiet else [])
    for s in sets:
        args += ["--set", s]
    r = run_cli(args)
    return r, json.loads((out / "summary.json").read_text())


def test_inverted_beam_is_refused():
    """-1e9 N in one increment: Newton converges to the beam turned inside out
    (J < 0 at quadrature points: finite forces for svk), which is not accepted
    (issue 36): the increment is refused; without cut-backs the run stops with
    a non-zero exit naming the element, where it is and its J, and keeps only
    the reference row.  With cut-backs the path stops before the inversion
    (svk's compressive limit point): no accepted row is inverted."""
    r, s = run("cantilever_axial_10kN", ["load.0.value.0=-1e9", "static.load_steps=1", "static.max_cutbacks=0"])
    assert r.returncode != 0 and not s["converged"] and s["steps"] == 0
    err = s["error"]
    assert "not physical" in err and "element 1 (ancf3243 x svk) near (" in err and "J = det F = " in err, err
    assert float(err.split("J = det F = ")[1].split()[0]) < 0, err
    assert f"error: cantilever_axial_10kN: {err}" in r.stderr, r.stderr
    r, s = run("cantilever_axial_10kN", ["load.0.value.0=-1e9"], quiet=True)
    assert r.returncode != 0 and not s["converged"]
    assert not any("is inverted" in w for w in s["warnings"]), s["warnings"]
    assert 0 < s["sensors"]["tip"]["position"][0] < 1, s["sensors"]


def test_inverted_step_is_refused_in_dynamics():
    """The same bar in dynamics under -1e8 N from t = 0 on: its tip element is
    crushed within a microsecond; a step that ends with it inside out is cut
    back like a failed one, and when it cannot be cut further the run stops
    (non-zero exit) at that time, naming the element and its J."""
    text = (ROOT / "models" / "cantilever_axial_10kN.toml").read_text().replace(
        'analysis = "static"', 'analysis = "dynamic"') + "\n[dynamic]\nt_end = 0.01\ndt = 1e-3\n"
    out = Path(tempfile.mkdtemp(prefix="bk-warn-", dir=ensure_dir(BUILD / "runs")))
    (out / "bar.toml").write_text(text)
    r = run_cli(["run", str(out / "bar.toml"), "--quiet", "--out", str(out / "run"), "--set",
                 "load.0.value.0=-1e8"])
    s = json.loads((out / "run" / "summary.json").read_text())
    assert r.returncode != 0 and not s["converged"], r.stderr
    err = s["error"]
    assert err.startswith("dynamic solve failed at step ") and "element 10 (ancf3243 x svk)" in err, err
    assert "turned inside out: J = det F = -" in err, err


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


def test_displacement_beyond_a_hundred_model_sizes_is_flagged():
    """1e15 N stretches the 1 m svk bar past 100 m: flagged as not credible
    (units, or a load beyond the structure), with the element and the factor."""
    r, s = run("cantilever_axial_10kN", ["load.0.value.0=1e15"], quiet=True)
    w = [x for x in s["warnings"] if "times the model's size" in x]
    assert len(w) == 1 and "not credible" in w[0] and "check the units" in w[0], s["warnings"]
    assert float(w[0].split(" m, ")[0].split("moved ")[1]) > 100, w[0]
    r, s = run("cantilever_axial_10kN", ["load.0.value.0=1e9"], quiet=True)     # stretched 6 times: no flag
    assert not any("times the model's size" in x for x in s["warnings"]), s["warnings"]


def test_implausible_units_are_named_before_the_solve():
    """The finger written in millimetres with E in MPa and rho in t/mm^3: each
    value outside what solids and structures have gets a warning naming the
    likely mistake; the run still goes (the values may be meant)."""
    sets = ["material.silicone.E=1.2", "material.silicone.rho=1.1e-9", "beam.f.end.0=2e4",
            "section.finger.b=2e4"]
    r, s = run("tendon_finger", sets + ["static.max_iterations=1", "static.max_cutbacks=0"], quiet=True)
    w = "\n".join(s["warnings"])
    assert "E = 1.2 Pa is below 1 kPa" in w and "MPa" in w, w
    assert "rho = 1.1e-09 kg/m^3 is below 1 kg/m^3" in w and "g/cm^3" in w, w
    assert "length 2e+04 m is above 10 km" in w and "in mm?" in w, w
    r, s = run("tendon_finger", ["section.finger.b=0.2", "static.max_iterations=1", "static.max_cutbacks=0"],
               quiet=True)
    assert any("larger than the beam's length 0.1 m" in x for x in s["warnings"]), s["warnings"]
    r, s = run("tendon_finger", ["static.max_iterations=1", "static.max_cutbacks=0"], quiet=True)
    assert not any("kPa" in x or "kg/m^3" in x or "length" in x for x in s["warnings"]), s["warnings"]
