"""Reactions of every constraint kind (reactions.csv, summary.json) against
statics and rigid-body dynamics worked out here by hand, not by our elements:
each joint reports the force and moment it exerts on frame a, about the joint
point, and in dynamics from step 0 (the multipliers of the consistent initial
accelerations)."""
import csv
import tempfile
from pathlib import Path

import numpy as np
import pytest

from util import BUILD, ensure_dir, run_scene

STEEL = """
[material.steel]
law = "resultant"
E = 2.1e11
nu = 0.3
rho = 7850.0

[section.sq]
shape = "rectangle"
b = 0.01
h = 0.01
"""


def _beam(name, start, end, n=6):
    return (f'[[beam]]\nname = "{name}"\nelement = "gef"\nmaterial = "steel"\nsection = "sq"\n'
            f"start = {list(start)}\nend = {list(end)}\nelements = {n}\n")


def _run(text, sets=()):
    d = Path(tempfile.mkdtemp(prefix="bk-react-", dir=ensure_dir(BUILD / "runs")))
    (d / "scene.toml").write_text(text)
    s, _ = run_scene(d / "scene.toml", sets, out=d / "out")
    with open(d / "out" / "reactions.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    return s, rows


def _fm(r):
    return np.array(r["force"]), np.array(r["moment"]), np.array(r["point"])


def test_clamp_with_b_reports_the_loads_of_fixed_and_statics():
    """The L-frame's corner as `clamp` with b and as `fixed`: the joint carries to
    beam a the tip load P and its moment (r_tip - r_corner) x P from the deformed
    positions (was 0 for `clamp`)."""
    P = np.array([0.0, 0.0, -1.0])
    base = "[scene]\nanalysis = \"static\"\n" + STEEL + _beam("a", (0, 0, 0), (1, 0, 0), 10) + \
        _beam("b", (1, 0, 0), (1, 0.5, 0)) + \
        '[[constraint]]\ntype = "clamp"\na = "a:start"\n' + \
        '[[constraint]]\ntype = "KIND"\na = "a:end"\nb = "b:start"\n' + \
        f'[[load]]\ntype = "force"\nat = "b:end"\nvalue = {list(P)}\n' + \
        '[[sensor]]\nname = "tip"\nat = "b:end"\n'
    got = {}
    for kind in ("clamp", "fixed"):
        s, _ = _run(base.replace("KIND", kind))
        F, M, x0 = _fm(s["reactions"][1])
        tip = np.array(s["sensors"]["tip"]["position"])
        assert np.allclose(F, P, atol=1e-9), (kind, F)
        assert np.allclose(M, np.cross(tip - x0, P), atol=1e-9), (kind, M)
        got[kind] = (F, M)
    assert np.allclose(got["clamp"][1], got["fixed"][1], atol=1e-12)


def test_beam_joints_to_ground_balance_a_determinate_beam():
    """A beam on a revolute joint (axis y) at its start and a roller (point_on_line
    along x) at its end, a force (Px, 0, Pz) at 0.3 m: the roller takes only the
    z force of the lever rule about the hinge, the hinge the rest and no moment,
    each about its own point; a cantilever driven to 0.4 rad by prescribed_rotation
    and one clamped, both with a tip force and moment: -P and -(r_tip x P) - C."""
    P = np.array([3.0, 0.0, -2.0])
    text = "[scene]\nanalysis = \"static\"\n" + STEEL + _beam("a", (0, 0, 0), (1, 0, 0), 10) + \
        '[[constraint]]\ntype = "revolute"\na = "a:start"\naxis = [0.0, 1.0, 0.0]\n' + \
        '[[constraint]]\ntype = "point_on_line"\na = "a:end"\naxis = [1.0, 0.0, 0.0]\n' + \
        f'[[load]]\ntype = "force"\nat = "a:0.3"\nvalue = {list(P)}\n' + \
        '[[sensor]]\nname = "p"\nat = "a:0.3"\n'
    s, _ = _run(text)
    (FA, MA, xA), (FB, MB, xB) = _fm(s["reactions"][0]), _fm(s["reactions"][1])
    xP = np.array(s["sensors"]["p"]["position"])
    fz = np.cross(xP - xA, P)[1] / (xB - xA)[0]        # no moment about the hinge axis y
    assert np.allclose(FB, [0.0, 0.0, fz], atol=1e-9), FB
    assert np.allclose(MB, 0.0, atol=1e-9), MB
    assert np.allclose(FA, -P - FB, atol=1e-9), FA
    assert np.allclose(MA, 0.0, atol=1e-8), MA
    P = np.array([0.0, 1.0, -2.0])
    C = np.array([0.1, 0.2, 0.0])
    for support in ('type = "clamp"', 'type = "prescribed_rotation"\naxis = [0.0, 0.0, 1.0]\nangle = 0.4'):
        text = "[scene]\nanalysis = \"static\"\n" + STEEL + _beam("a", (0, 0, 0), (1, 0, 0), 10) + \
            f'[[constraint]]\n{support}\na = "a:start"\n' + \
            f'[[load]]\ntype = "force"\nat = "a:end"\nvalue = {list(P)}\n' + \
            f'[[load]]\ntype = "moment"\nat = "a:end"\nvalue = {list(C)}\n' + \
            '[[sensor]]\nname = "tip"\nat = "a:end"\n'
        s, _ = _run(text)
        F, M, x0 = _fm(s["reactions"][0])
        tip = np.array(s["sensors"]["tip"]["position"])
        assert np.allclose(F, -P, atol=1e-7), (support, F)
        assert np.allclose(M, -np.cross(tip - x0, P) - C, atol=1e-7), (support, M)
        if "prescribed" in support:
            assert tip[1] > 0.35                                    # it did turn


def _rigid_start(kind, m, J, d, g, axes):
    """Rigid body on a joint at O to the ground, released from rest: the force and
    moment about O the joint exerts, from d'Alembert's principle written here
    (allowed translations T and rotations B; the constraint force and moment do no
    work on them)."""
    n = axes[0] / np.linalg.norm(axes[0])
    T = {"prismatic": [n]}.get(kind, [])
    B = {"spherical": list(np.eye(3)), "revolute": [n], "fixed": [], "prismatic": [],
         "universal": [n, axes[1] / np.linalg.norm(axes[1])]}[kind]
    nt, nb = len(T), len(B)

    def loads(z):
        a_o = sum((z[i] * T[i] for i in range(nt)), np.zeros(3))
        alpha = sum((z[nt + i] * B[i] for i in range(nb)), np.zeros(3))
        a_c = a_o + np.cross(alpha, d)
        F = m * a_c - m * g
        M = J @ alpha + np.cross(d, m * a_c) - np.cross(d, m * g)
        return F, M

    def work(z):
        F, M = loads(z)
        return np.array([F @ t for t in T] + [M @ b for b in B])

    k = nt + nb
    z = np.zeros(k)
    if k:
        w0 = work(z)
        A = np.array([work(np.eye(k)[i]) - w0 for i in range(k)]).T
        z = np.linalg.solve(A, -w0)
    return loads(z)


@pytest.mark.parametrize("kind", ["spherical", "revolute", "universal", "fixed", "prismatic"])
def test_body_joint_reactions_from_step_0(kind):
    """A rigid body (2 kg, principal moments 0.02, 0.03, 0.04 kg m^2, centre of mass
    (0.3, 0.1, -0.2) m from the joint) on one joint to the ground under gravity,
    released from rest: at step 0 the joint's force and moment about the joint point
    equal the rigid-body closed form to 1e-9 (d'Alembert, _rigid_start)."""
    m, Jd, d = 2.0, [0.02, 0.03, 0.04], np.array([0.3, 0.1, -0.2])
    g = np.array([0.0, 0.0, -9.81])
    axes = [np.array([0.0, 1.0, 0.2]), np.array([1.0, 0.0, 0.0])]
    extra = ""
    if kind in ("revolute", "prismatic", "universal"):
        extra += f"axis = {list(axes[0])}\n"
    if kind == "universal":
        axes[0] = np.array([0.0, 1.0, 0.0])
        extra = f"axis = {list(axes[0])}\naxis_b = {list(axes[1])}\n"
    text = f'[scene]\nanalysis = "dynamic"\n[[body]]\nname = "link"\nmass = {m}\ncenter = {list(d)}\n' \
        f"inertia = {Jd}\n[[constraint]]\ntype = \"{kind}\"\na = \"link\"\nat = [0.0, 0.0, 0.0]\n{extra}" \
        f'[[load]]\ntype = "gravity"\nvalue = {list(g)}\n[dynamic]\nt_end = 0.002\ndt = 0.001\n' \
        '[[sensor]]\nname = "link"\nat = "link"\n'
    _, rows = _run(text)
    r0 = [r for r in rows if r["step"] == "0"][0]
    F = np.array([float(r0[k]) for k in ("Fx", "Fy", "Fz")])
    M = np.array([float(r0[k]) for k in ("Mx", "My", "Mz")])
    x0 = np.array([float(r0[k]) for k in ("x", "y", "z")])
    Fr, Mr = _rigid_start(kind, m, np.diag(Jd), d, g, axes)
    assert np.allclose(x0, 0.0, atol=1e-12), x0
    assert np.allclose(F, Fr, atol=1e-9 * m * 9.81), (F, Fr)
    assert np.allclose(M, Mr, atol=1e-9 * m * 9.81), (M, Mr)
    assert np.linalg.norm(Fr) > 1.0                # not a trivial case
