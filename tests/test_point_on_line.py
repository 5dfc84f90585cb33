"""The point-on-line joint (gen/scene/joints.py point_on_line): a cantilever whose tip
rides on a line along its axis is a propped cantilever.  Mid-span force P in the
linear regime: deflection 7 P L^3 / (768 E I) + shear (Timoshenko, gef), tip across
the axis 0, along it free."""
import json
import tempfile
from pathlib import Path

from util import BUILD, ensure_dir, run_cli

SCENE = """
[scene]
analysis = "static"
[material.steel]
law = "resultant"
E = 2.1e11
nu = 0.3
rho = 7850.0
[section.sq]
shape = "rectangle"
b = 0.02
h = 0.02
[[beam]]
name = "arm"
element = "gef"
material = "steel"
section = "sq"
start = [0.0, 0.0, 0.0]
end = [2.0, 0.0, 0.0]
elements = 16
[[constraint]]
type = "clamp"
a = "arm:start"
[[constraint]]
type = "point_on_line"
a = "arm:end"
axis = [1.0, 0.0, 0.0]
[[load]]
type = "force"
at = "arm:1.0"
value = [0.0, 0.0, -100.0]
[static]
load_steps = 1
[[sensor]]
name = "mid"
at = "arm:1.0"
[[sensor]]
name = "tip"
at = "arm:end"
"""


def test_propped_cantilever():
    d = Path(tempfile.mkdtemp(prefix="bk-pol-", dir=ensure_dir(BUILD / "runs")))
    (d / "propped.toml").write_text(SCENE)
    r = run_cli(["run", str(d / "propped.toml"), "--quiet", "--out", str(d / "out")])
    assert r.returncode == 0, r.stderr
    s = json.loads((d / "out" / "summary.json").read_text())
    E, b, L, P, nu = 2.1e11, 0.02, 2.0, 100.0, 0.3
    I, A, G = b**4 / 12, b * b, E / (2 * (1 + nu))
    k = 10 * (1 + nu) / (12 + 11 * nu)
    # Timoshenko propped cantilever by superposition: the prop force R makes the tip deflection of
    # the cantilever under P at a = L/2 vanish (bending and shear flexibilities)
    a, kGA = L / 2, k * G * A
    tip_P = P * a**2 * (3 * L - a) / (6 * E * I) + P * a / kGA
    R = tip_P / (L**3 / (3 * E * I) + L / kGA)
    w_ref = P * a**3 / (3 * E * I) + P * a / kGA - R * (a**2 * (3 * L - a) / (6 * E * I) + a / kGA)
    assert abs(R / P - 5 / 16) < 0.01       # Euler-Bernoulli: 5 P / 16
    w = -s["sensors"]["mid"]["displacement"][2]
    assert abs(w / w_ref - 1) < 1e-3, (w, w_ref)
    tip = s["sensors"]["tip"]["displacement"]
    assert abs(tip[1]) < 1e-12 and abs(tip[2]) < 1e-12, tip
    assert s["converged"]
