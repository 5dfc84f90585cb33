"""Point masses ([[point_mass]]: gen/scene/point_masses.py, bk_element_mass and
bk_element_weight), against closed forms: the Euler-Bernoulli frequency equation
of a cantilever with a tip mass and no rotary inertia, and the static deflection
of a cantilever under the weight of a mass between nodes (beam theory)."""
import math

from util import ROOT, run_scene
from test_bad_input import check_error
from test_bodies import EI, LEN, M_BEAM, tip_mass_frequency

BASE = (ROOT / "models" / "tip_mass_cantilever.toml").read_text()
BODY = '''[[body]]
name = "tip"
mass = 0.5
center = [1.0, 0.0, 0.0]
inertia = [1.23e-4, 1.23e-4, 1.23e-4]
'''
WELD = '''[[constraint]]
type = "fixed"
a = "arm:end"
b = "tip"
'''
SENSOR = '''[[sensor]]
name = "mass"
at = "tip"
'''


def _scene(tmp_path, extra, analysis="modal"):
    text = BASE.replace(BODY, "").replace(WELD, "").replace(SENSOR, "")
    text = text.replace('analysis = "modal"', f'analysis = "{analysis}"') + extra
    p = tmp_path / "scene.toml"
    p.write_text(text)
    return p


def test_point_mass_at_the_tip_lowers_the_frequency_as_the_frequency_equation_says(tmp_path):
    """A 0.5 kg point mass at the free end of the steel cantilever of
    models/tip_mass_cantilever.toml (no rotary inertia, no body): the first bending
    frequency against the frequency equation with M = 0.5 kg, J = 0 (to 2e-4)."""
    s, _ = run_scene(_scene(tmp_path, '[[point_mass]]\nat = "arm:end"\nmass = 0.5\n'))
    exact = tip_mass_frequency(0.5, 0.0)
    f = s["frequencies_hz"]
    assert abs(f[0] / exact - 1) < 2e-4 and abs(f[1] / exact - 1) < 2e-4, (f[:2], exact)
    print(f"point mass at the tip: {f[0]:.6f} Hz against {exact:.6f} Hz")


def test_weight_of_a_point_mass_between_nodes_bends_the_cantilever_by_beam_theory(tmp_path):
    """Statics under gravity: 2 kg at 0.35 m (between the nodes at 0.3 and 0.4 m of
    10 elements) on the 1 m steel cantilever: tip deflection W a^2 (3 L - a) / (6 EI)
    + q L^4 / (8 EI) (the beam's own weight), within 0.2 %; the reaction carries the
    whole weight (m_beam + 2 kg) g."""
    text = '[[point_mass]]\nat = "arm:0.35"\nmass = 2.0\n[[sensor]]\nname = "tip"\nat = "arm:end"\n'
    p = _scene(tmp_path, text, "static")
    p.write_text(p.read_text().replace("elements = 20", "elements = 10"))
    s, _ = run_scene(p)
    W, a, g = 2.0 * 9.81, 0.35, 9.81
    q = M_BEAM / LEN * g
    ref = W * a**2 * (3 * LEN - a) / (6 * EI) + q * LEN**4 / (8 * EI)
    w = -s["sensors"]["tip"]["displacement"][2]
    assert abs(w / ref - 1) < 2e-3, (w, ref)
    Fz = s["reactions"][0]["force"][2]
    assert abs(Fz - (M_BEAM + 2.0) * g) < 1e-6 * (M_BEAM + 2.0) * g, Fz
    print(f"point mass between nodes: tip {w:.6e} m against {ref:.6e} m")


def test_bad_point_masses(tmp_path):
    """One line each: a point mass on a body, beyond the beam's end, without mass."""
    base = BASE.replace(SENSOR, "")
    check_error(base + '[[point_mass]]\nat = "tip"\nmass = 1.0\n', "point_mass[0].at", "is a rigid body")
    check_error(base + '[[point_mass]]\nat = "arm:1.5"\nmass = 1.0\n', "point_mass[0].at", "outside beam 'arm'")
    check_error(base + '[[point_mass]]\nat = "arm:end"\n', "point_mass[0].mass", "missing")
