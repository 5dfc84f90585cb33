"""Bad input: one error line naming the file, the key and what was expected, a
non-zero exit, never a crash; a failed solve keeps its converged steps."""
import json
import re
import tempfile
from pathlib import Path

from util import BUILD, ROOT, ensure_dir, load_run, run_cli

BASE = (ROOT / "models" / "cantilever_bend_10N.toml").read_text()


def run_text(text, name="bad", extra=()):
    d = Path(tempfile.mkdtemp(prefix="bk-bad-", dir=ensure_dir(BUILD / "bad")))
    p = d / f"{name}.toml"
    p.write_text(text)
    out = d / "out"
    r = run_cli(["run", str(p), "--out", str(out)] + list(extra))
    return r, p, out


def check_error(text, key, expected, name="bad"):
    r, p, _ = run_text(text, name)
    assert r.returncode == 1, f"exit {r.returncode}, stderr:\n{r.stderr}"
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    assert len(lines) == 1, f"expected one error line, got:\n{r.stderr}"
    line = lines[0]
    assert line.startswith("error: ") and str(p) in line, line
    assert key in line, f"key {key!r} not named in: {line}"
    assert re.search(expected, line), f"{expected!r} not in: {line}"
    assert "Traceback" not in r.stderr
    return line


def test_unknown_key():
    check_error(BASE.replace("elements = 10", "elements = 10\ncolour = 3"), "beam.arm.colour",
                "unknown key; expected one of")


def test_missing_key():
    check_error(BASE.replace('material = "alu"\n', ""), "beam.arm.material", "missing")


def test_wrong_type():
    check_error(BASE.replace("elements = 10", 'elements = "ten"'), "beam.arm.elements",
                "expected an integer, found the string 'ten'")
    check_error(BASE.replace("E = 7.2e10", 'E = "stiff"'), "material.alu.E", "expected a finite number")
    check_error(BASE.replace("end = [1.0, 0.0, 0.0]", "end = [1.0, 0.0]"), "beam.arm.end",
                "expected an array of 3 numbers")


def test_unknown_element():
    check_error(BASE.replace('element = "ancf3243"', 'element = "ancf9999"'), "beam.arm.element",
                "expected one of .*ancf3243.*found 'ancf9999'")


def test_unknown_material_law_and_missing_material():
    check_error(BASE.replace('law = "svk"', 'law = "rubberish"'), "material.alu.law",
                "expected one of .*svk.*found 'rubberish'")
    check_error(BASE.replace('material = "alu"', 'material = "steel"'), "beam.arm.material",
                r"no \[material.steel\]")


def test_non_positive_sizes():
    check_error(BASE.replace("b = 0.01", "b = -0.01"), "section.square.b", "expected a positive number")
    check_error(BASE.replace("elements = 10", "elements = 0"), "beam.arm.elements",
                r"expected an integer in \[1, ")
    check_error(BASE.replace("end = [1.0, 0.0, 0.0]", "end = [0.0, 0.0, 0.0]"), "beam.arm.end",
                "beam length must be positive")
    check_error(BASE.replace("E = 7.2e10", "E = 0.0"), "material.alu.E", "expected a positive number")
    check_error(BASE.replace("nu = 0.0", "nu = 0.5"), "material.alu.nu", r"expected a number in \(-1, 0.5\)")


def test_load_or_sensor_on_missing_beam():
    check_error(BASE.replace('at = "arm:end"\nvalue', 'at = "leg:end"\nvalue'), "load[0].at",
                "no beam named 'leg'")
    check_error(BASE.replace('name = "tip"\nat = "arm:end"', 'name = "tip"\nat = "leg:0.5"'),
                "sensor.tip.at", "no beam named 'leg'")
    check_error(BASE.replace('name = "tip"\nat = "arm:end"', 'name = "tip"\nat = "arm:2.5"'),
                "sensor.tip.at", "outside beam 'arm'")


def test_toml_syntax_and_missing_file():
    check_error(BASE.replace("[section.square]", "[section.square"), "TOML syntax", "TOML syntax")
    r = run_cli(["run", "no_such_scene"])
    assert r.returncode == 1 and "no models/no_such_scene.toml" in r.stderr, r.stderr
    r = run_cli(["run", "cantilever_bend_10N", "--set", "material.alu.E=abc"])
    assert r.returncode == 1 and "expected a numeric value" in r.stderr, r.stderr
    r = run_cli(["run", "cantilever_bend_10N", "--set", "material.steel.E=1"])
    assert r.returncode == 1 and "material.steel" in r.stderr, r.stderr


def test_a_bad_value_given_by_set_names_the_set_not_the_file():
    """The scene file holds a good value; the message names the --set that gave
    the bad one, with an array entry addressed by name or by index (the scene's
    message writes it load[0])."""
    cases = [(["beam.arm.elements=-4"], "error: --set beam.arm.elements=-4: beam.arm.elements: expected an integer"),
             (["beam.0.elements=0"], "error: --set beam.0.elements=0: beam.arm.elements: expected an integer"),
             (["beam.arm.elemnts=20"], "error: --set beam.arm.elemnts=20: beam.arm.elemnts: unknown key"),
             (["static.loadsteps=3"], "error: --set static.loadsteps=3: static.loadsteps: unknown key"),
             (["load.0.value=[0,0]"], "error: --set load.0.value=[0,0]: load[0].value: expected an array of 3"),
             (["beam.arm.elements=8", "beam.arm.element=ancf9999"],
              "error: --set beam.arm.element=ancf9999: beam.arm.element: expected one of")]
    for sets, msg in cases:
        r = run_cli(["run", "cantilever_bend_10N"] + [a for s in sets for a in ("--set", s)])
        lines = [l for l in r.stderr.splitlines() if l.strip()]
        assert r.returncode == 1 and len(lines) == 1 and lines[0].startswith(msg), (sets, r.stderr)
    # a message about the file's own value still names the file
    r, p, _ = run_text(BASE.replace("elements = 10", "elements = 0"), extra=["--set", "material.alu.E=7e10"])
    assert r.returncode == 1 and f"error: {p}: beam.arm.elements:" in r.stderr, r.stderr


def test_newton_failure_keeps_converged_steps():
    """Compression far beyond the St. Venant-Kirchhoff bar's limit load
    E A / (3 sqrt 3) (at stretch 1/sqrt 3): the first steps converge, then the solve
    fails; exit 2, the message names step, load factor and residual, sensors.csv
    keeps every converged step, and the last converged load is below the limit."""
    text = (ROOT / "models" / "cantilever_axial_m1kN.toml").read_text()
    text = text.replace("value = [-1000.0, 0.0, 0.0]", "value = [-5.0e6, 0.0, 0.0]")
    text = text.replace("load_steps = 1", "load_steps = 10\nstep_control = \"fixed\"")
    r, p, out = run_text(text, "collapse")
    assert r.returncode == 2, f"exit {r.returncode}\n{r.stderr}"
    lines = [l for l in r.stderr.splitlines() if l.startswith("error")]
    assert len(lines) == 1, r.stderr
    m = re.search(r"failed at step (\d+), load factor ([0-9.e+-]+) .*residual ([0-9.e+-]+)", lines[0])
    assert m, lines[0]
    summary, rows = load_run(out)
    assert summary["converged"] is False and summary["error"]
    steps = sorted({int(r_["step"]) for r_ in rows})
    assert steps == list(range(summary["steps"] + 1)) and summary["steps"] >= 2, steps
    limit = 7.2e10 * 1e-4 / (3 * 3**0.5) / 5.0e6
    assert 0.9 * limit <= summary["load_factor"] <= limit, (summary["load_factor"], limit)


def test_unconstrained_beam_is_refused_naming_its_free_motion():
    """A cantilever without its clamp, in statics: refused before the solve
    (exit 1, one line) naming the six free rigid motions; with [static]
    free_rigid_motion = true the solver meets the singular tangent (exit 2)."""
    text = BASE.split("[[constraint]]")[0] + "[[load]]" + BASE.split("[[load]]")[1]
    r, p, out = run_text(text, "floating")
    assert r.returncode == 1, r.stderr
    assert "free to move as a rigid body in statics (a translation along x; a translation along y; " \
           "a translation along z (and 3 more))" in r.stderr, r.stderr
    r, p, out = run_text(text.replace("[static]", "[static]\nfree_rigid_motion = true"), "floating")
    assert r.returncode == 2, r.stderr
    assert "singular tangent" in r.stderr and "constrained" in r.stderr, r.stderr


def test_a_pinned_beam_is_refused_naming_its_rotations():
    """Held by a spherical joint at its start only, the beam can turn about
    the pin: the three rotations (about axes through the model's centre, so
    two come with a translation) are named; a clamp instead runs."""
    text = BASE.replace('type = "clamp"', 'type = "spherical"')
    assert text != BASE
    r, p, out = run_text(text, "pinned")
    assert r.returncode == 1 and "a rotation about x" in r.stderr and "rotation about y" in r.stderr \
        and "rotation about z" in r.stderr, r.stderr


def test_cable_resultant_material_needs_only_ea_and_ei(tmp_path):
    """ancf_cable reads EA and EI only: a resultant material without GA1, GA2,
    GJ (and EI2 = EI1) runs it -- with the cable's closed-form small tip
    deflection P L^3 / (3 EI) -- and gef, which uses them, is refused naming them."""
    import json
    base = """[scene]
analysis = "static"
[material.m]
law = "resultant"
EA = 1.0e7
EI1 = 2.0
rho = 1.0
[section.round]
shape = "circle"
radius = 0.01
[[beam]]
name = "c"
element = "ELEMENT"
material = "m"
section = "round"
start = [0.0, 0.0, 0.0]
end = [1.0, 0.0, 0.0]
elements = 8
[[constraint]]
type = "clamp"
a = "c:start"
[[load]]
type = "force"
at = "c:end"
value = [0.0, 0.0, -1e-4]
[[sensor]]
name = "tip"
at = "c:end"
"""
    scene = tmp_path / "cable.toml"
    scene.write_text(base.replace("ELEMENT", "ancf_cable"))
    r = run_cli(["run", str(scene), "--quiet", "--out", str(tmp_path / "out")])
    assert r.returncode == 0, r.stderr[-2000:]
    s = json.loads((tmp_path / "out" / "summary.json").read_text())
    uz = s["sensors"]["tip"]["displacement"][2]
    assert abs(uz / (-1e-4 / (3 * 2.0)) - 1) < 1e-3, uz
    scene.write_text(base.replace("ELEMENT", "gef"))
    r = run_cli(["run", str(scene), "--quiet", "--out", str(tmp_path / "out2")])
    assert r.returncode == 1 and "element gef uses GA1, GA2, GJ" in r.stderr, r.stderr
