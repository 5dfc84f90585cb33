"""Modal analysis takes the interactions' stiffness (springs, joint motors,
contact, loads that turn with the structure), dense and sparse solvers alike:
a spring used to be left out without a word.  References: the closed forms of
a mass on springs, sqrt(k/m), and the Euler-Bernoulli frequency equation of a
cantilever with a spring at its tip, solved here."""
import math

import pytest
from scipy.optimize import brentq

from util import run_text

BODY = """[scene]
analysis = "modal"
[[body]]
name = "m"
mass = 2.0
center = [0.0, 0.0, 0.0]
inertia = [1e-3, 1e-3, 1e-3]
[[spring]]
a = "m"
b = [0.3, 0.0, 0.0]
stiffness = 800.0
[[spring]]
a = "m"
b = [0.0, 0.3, 0.0]
stiffness = 200.0
[[spring]]
a = "m"
b = [0.0, 0.0, 0.3]
stiffness = 50.0
[modal]
modes = 6
"""

E, RHO, B, L, K = 2.1e11, 7800.0, 0.01, 1.0, 1.0e4
CANTILEVER = f"""[scene]
analysis = "modal"
[material.steel]
law = "resultant"
E = {E}
nu = 0.3
rho = {RHO}
[section.sq]
shape = "rectangle"
b = {B}
h = {B}
[[beam]]
name = "arm"
element = "gef"
material = "steel"
section = "sq"
start = [0.0, 0.0, 0.0]
end = [{L}, 0.0, 0.0]
up = [0.0, 0.0, 1.0]
elements = 10
[[constraint]]
type = "clamp"
a = "arm:start"
[[spring]]
a = "arm:end"
b = [{L}, 0.0, -0.1]
stiffness = {K}
[modal]
modes = 3
solver = "SOLVER"
"""


def _run(text, name):
    return run_text(text, name, "bk-modal")


def test_mass_on_three_springs_has_the_frequencies_sqrt_k_over_m():
    """A 2 kg body on springs of 50, 200 and 800 N/m along z, y and x (at its
    centre: its rotations are free, three zero frequencies)."""
    f = _run(BODY, "body")["frequencies_hz"]
    ref = [0.0] * 3 + [math.sqrt(k / 2.0) / (2 * math.pi) for k in (50.0, 200.0, 800.0)]
    assert len(f) == 6 and all(abs(a - b) < 1e-9 * ref[-1] for a, b in zip(f, ref)), (f, ref)


def _spring_cantilever_frequency(k, which):
    """The which-th bending frequency (Hz) of an Euler-Bernoulli cantilever with a
    spring k at its tip: w = A (cosh bx - cos bx) + B (sinh bx - sin bx) (the
    clamp), w''(L) = 0 and EI w'''(L) = k w(L); the determinant's roots in b."""
    EI, rA = E * B**4 / 12, RHO * B * B

    def det(b):
        ch, sh, c, s = math.cosh(b * L), math.sinh(b * L), math.cos(b * L), math.sin(b * L)
        return (ch + c) * (EI * b**3 * (ch + c) - k * (sh - s)) - (sh + s) * (EI * b**3 * (sh - s) - k * (ch - c))
    grid = [0.1 + 0.001 * i for i in range(12000)]
    roots = [brentq(det, a, b, xtol=1e-14) for a, b in zip(grid, grid[1:]) if det(a) * det(b) < 0]
    if k == 0:
        assert abs(roots[0] * L - 1.8751040687) < 1e-9      # the textbook cantilever root
    return roots[which] ** 2 * math.sqrt(EI / rA) / (2 * math.pi)


@pytest.mark.parametrize("solver", ["dense", "sparse"])
def test_cantilever_with_a_tip_spring_against_the_frequency_equation(solver):
    """gef, 10 elements (L/h = 100: shear and rotary inertia below 1e-4): the
    bending mode in the spring's plane at 28.4575 Hz (the spring's k L^3/EI = 57;
    without it 8.3819 Hz) and the one across it, untouched, within 0.05 %."""
    f = _run(CANTILEVER.replace("SOLVER", solver), f"tip_spring_{solver}")["frequencies_hz"]
    across, spring = _spring_cantilever_frequency(0.0, 0), _spring_cantilever_frequency(K, 0)
    assert abs(f[0] / across - 1) < 5e-4 and abs(f[1] / spring - 1) < 5e-4, (f, across, spring)
