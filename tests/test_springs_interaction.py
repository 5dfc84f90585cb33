"""The spring interaction ([[spring]]: gen/scene/spring.py, runtime/assembly/
spring.c), the interaction added through the module path of issue 33 (its
C module, its scene module, its tests: no other file names it).  Verified
against differences of its energy (forces) and of its forces (Jacobian), the
ends evaluated by the elements' own kernels; against beam theory (a cantilever
propped by a spring: tip deflection P / (3EI/L^3 + k)); against the closed
form of a mass on a spring (period 2 pi sqrt(m/k)); bad input gives one line."""
import csv
import json
import math
import subprocess
import tempfile
from pathlib import Path

from util import BUILD, ROOT, ensure_dir, run_cli

E, SIDE, L = 2.1e11, 0.01, 1.0
EI = E * SIDE**4 / 12

BEAM = """[scene]
analysis = "{analysis}"
[material.steel]
law = "{law}"
E = 2.1e11
nu = 0.3
rho = 7850.0
[section.square]
shape = "rectangle"
b = 0.01
h = 0.01
[[beam]]
name = "arm"
element = "{element}"
material = "steel"
section = "square"
start = [0.0, 0.0, 0.0]
end = [1.0, 0.0, 0.0]
up = [0.0, 0.0, 1.0]
elements = {elements}
"""

BODY = """[[body]]
name = "m"
mass = 2.0
center = [1.5, 0.2, 0.1]
inertia = [1e-3, 2e-3, 3e-3]
"""


def _scene(tmp, text, name="s"):
    p = Path(tmp) / f"{name}.toml"
    p.write_text(text)
    return p


def _run(scene, sets=(), ok=True):
    out = Path(tempfile.mkdtemp(prefix="bk-spring-", dir=ensure_dir(BUILD / "runs")))
    args = ["run", str(scene), "--quiet", "--out", str(out)]
    for s in sets:
        args += ["--set", s]
    r = run_cli(args)
    if ok:
        assert r.returncode == 0, r.stderr[-2000:]
    return r, out


def _build_check():
    from gen.solver_build import VARIANTS, build_solver, compile_object, runtime_headers, runtime_objects
    from util import all_pair_symbols
    pairs, index = all_pair_symbols()
    pairs = [p for p in pairs if p.startswith(("gef_resultant", "ancf3243_svk"))] + ["rigid_body_rigid_full"]
    obj = BUILD / "sanitize" / "springs_check.o"
    compile_object(ROOT / "tests" / "springs_check.c", obj, VARIANTS["sanitize"], runtime_headers())
    objs = [o for o in runtime_objects("sanitize") if o.name != "main.o"] + [obj]
    return build_solver(pairs, BUILD / "sanitize" / "springs_check", index, "sanitize", main_objs=objs)


def test_forces_and_jacobian_against_differences(tmp_path):
    """Springs between elements of one beam, from a beam point inside an element to a
    body, to a fixed point, of zero rest length and compressed; gef and ancf3243."""
    exe = _build_check()
    springs = """[[spring]]
name = "across"
a = "arm:0.13"
b = "arm:0.81"
stiffness = 300.0
rest_length = 0.5
[[spring]]
name = "to_body"
a = "arm:0.55"
b = "m"
stiffness = 120.0
[[spring]]
name = "ground"
a = "arm:end"
b = [1.2, -0.3, 0.4]
stiffness = 80.0
rest_length = 0.0
[[spring]]
name = "body_ground"
a = "m"
b = [1.0, 1.0, 1.0]
stiffness = 50.0
rest_length = 2.5
"""
    for element, law in (("gef", "resultant"), ("ancf3243", "svk")):
        text = BEAM.format(analysis="static", law=law, element=element, elements=4) + BODY + springs
        r, out = _run(_scene(tmp_path, text, element), ["static.load_steps=1", "static.free_rigid_motion=true"],
                      ok=False)
        assert (out / "model.dat").exists(), r.stderr[-2000:]
        c = subprocess.run([str(exe), str(out / "model.dat")], capture_output=True, text=True, timeout=300)
        assert c.returncode == 0, c.stderr
        ferr, fmax, jerr, jmax = map(float, c.stdout.split())
        assert fmax > 1.0 and ferr < 1e-6 * fmax, (element, ferr, fmax)
        assert jmax > 1.0 and jerr < 1e-6 * jmax, (element, jerr, jmax)


def test_propped_cantilever_against_beam_theory(tmp_path):
    """Tip load P = 1 N on a cantilever whose tip hangs on a spring k to the ground
    below: deflection P / (3EI/L^3 + k), the spring's share k / (k + 3EI/L^3) of P."""
    k = 525.0
    text = BEAM.format(analysis="static", law="resultant", element="gef", elements=10) + f"""
[[constraint]]
type = "clamp"
a = "arm:start"
[[load]]
type = "force"
at = "arm:end"
value = [0.0, 0.0, -1.0]
[[spring]]
name = "prop"
a = "arm:end"
b = [1.0, 0.0, -0.5]
stiffness = {k}
[[sensor]]
name = "tip"
at = "arm:end"
"""
    _, out = _run(_scene(tmp_path, text))
    s = json.loads((out / "summary.json").read_text())
    kb = 3 * EI / L**3
    tip = s["sensors"]["tip"]["displacement"] if isinstance(s["sensors"], dict) else None
    rows = list(csv.DictReader(open(out / "sensors.csv", newline="")))
    uz = float(rows[-1]["uz"]) if "uz" in rows[-1] else tip[2]
    assert abs(-uz / (1.0 / (kb + k)) - 1) < 2e-4, uz        # shear adds 4e-5
    assert abs(s["springs"]["prop"]["tension"] / (-k / (k + kb)) - 1) < 2e-4
    lines = (out / "springs.csv").read_text().splitlines()
    assert lines[0] == "step,time,spring,length,extension,tension" and len(lines) == 3


def test_mass_on_a_spring_oscillates_at_sqrt_k_over_m(tmp_path):
    k, m, v = 800.0, 2.0, 0.05
    period = 2 * math.pi * math.sqrt(m / k)
    text = f"""[scene]
analysis = "dynamic"
[[body]]
name = "m"
mass = {m}
center = [0.0, 0.0, 0.0]
inertia = [1e-3, 1e-3, 1e-3]
[[spring]]
a = "m"
b = [0.0, 0.0, 0.3]
stiffness = {k}
[[initial_velocity]]
body = "m"
velocity = [0.0, 0.0, {v}]
[[sensor]]
name = "m"
at = "m"
[dynamic]
t_end = {3 * period}
dt = {period / 400}
rho_inf = 1.0
"""
    _, out = _run(_scene(tmp_path, text))
    rows = [r for r in csv.DictReader(open(out / "sensors.csv", newline="")) if r.get("sensor", "m") == "m"]
    t = [float(r["time"]) for r in rows]
    z = [float(r["uz"]) for r in rows]
    ups = [t[i] - z[i] * (t[i + 1] - t[i]) / (z[i + 1] - z[i]) for i in range(1, len(z) - 1)
           if z[i] < 0.0 <= z[i + 1]]
    assert len(ups) >= 2, ups
    measured = (ups[-1] - ups[0]) / (len(ups) - 1)
    assert abs(measured / period - 1) < 1e-3, (measured, period)
    amp = max(abs(x) for x in z)
    assert abs(amp / (v * period / (2 * math.pi)) - 1) < 1e-3, amp


def test_bad_input_one_line_each(tmp_path):
    base = BEAM.format(analysis="static", law="resultant", element="gef", elements=2) + """
[[constraint]]
type = "clamp"
a = "arm:start"
"""
    for extra, needle in (('[[spring]]\na = "arm:end"\nb = [0, 0, 1]\n', "spring[0].stiffness: missing"),
                          ('[[spring]]\na = "leg:end"\nb = [0, 0, 1]\nstiffness = 1.0\n', "no beam named 'leg'"),
                          ('[[spring]]\na = "arm:end"\nb = "arm:end"\nstiffness = 1.0\n', "same point as .a"),
                          ('[[spring]]\na = "arm:end"\nb = [0, 0, 1]\nstiffness = -1.0\n', "spring[0].stiffness"),
                          ('[[spring]]\na = "arm:end"\nb = [0, 0, 1]\nstiffness = 1.0\ndamping = 2.0\n',
                           "damping")):
        r, _ = _run(_scene(tmp_path, base + extra), ok=False)
        assert r.returncode != 0
        err = [x for x in r.stderr.splitlines() if x.startswith("error")]
        assert len(err) == 1 and needle in err[0], (needle, r.stderr[-600:])
