"""Welds of an ANCF node to a rod node or a rigid body (gen/scene/weld.py, the weld
kinds of gen/body.py), each against a reference that is not our own element:
the cantilever closed forms of beam theory (bending, shear, torsion with the
continuum sections' polar moment), central differences of the generated
constraint functions, and rigid motions built here."""
import math

import numpy as np
import pytest

from test_bad_input import check_error
from test_bodies import NX, _joint_kinds, check_joint_derivatives, joint_g
from util import BUILD, ensure_dir, run_text

E, B, L = 7.2e10, 0.01, 1.0
EI, GA, GJ = E * B**4 / 12, 5 / 6 * E / 2 * B * B, E / 2 * B**4 / 6
ROD = ("gef", "euler_bernoulli", "kirchhoff")

HEAD = """[scene]
analysis = "static"

[material.alu]
law = "svk"
E = 7.2e10
nu = 0.0
rho = RHO

[material.alu_rod]
law = "resultant"
E = 7.2e10
nu = 0.0
rho = RHO

[section.square]
shape = "rectangle"
b = 0.01
h = 0.01

[static]
load_steps = 1
"""


def _beam(name, element, x0, x1, n=10, d=(1.0, 0.0, 0.0), up=(0.0, 0.0, 1.0)):
    mat = "alu" if element.startswith("ancf") and element != "ancf_cable" else "alu_rod"
    s = [x0 * c for c in d]
    e = [x1 * c for c in d]
    return (f'[[beam]]\nname = "{name}"\nelement = "{element}"\nmaterial = "{mat}"\nsection = "square"\n'
            f"start = {s}\nend = {e}\nup = {list(up)}\nelements = {n}\n")


def _con(kind, a, b=None, extra=""):
    return f'[[constraint]]\ntype = "{kind}"\na = "{a}"\n' + (f'b = "{b}"\n' if b else "") + extra


def _run(text, name):
    return run_text(text, name, "bk-weld")


def _two_segments(first, second, a_first=True, kind="fixed", P=0.01):
    """A 1 m cantilever: `first` on [0, 0.5] clamped at 0, `second` on [0.5, 1],
    welded at 0.5 (side a the first segment's end or, a_first false, the second's
    start), P down at the tip."""
    weld = _con(kind, "s1:end", "s2:start") if a_first else _con(kind, "s2:start", "s1:end")
    return (HEAD.replace("RHO", "2700.0") + _beam("s1", first, 0.0, 0.5) + _beam("s2", second, 0.5, 1.0)
            + _con("clamp", "s1:start") + weld
            + f'[[load]]\ntype = "force"\nat = "s2:end"\nvalue = [0.0, 0.0, {-P}]\n'
            + '[[sensor]]\nname = "tip"\nat = "s2:end"\n')


def _shear_length(*elements):
    """Length of the segments (0.5 m each) with transverse shear (all but the
    Euler-Bernoulli ones: ancf_cable, euler_bernoulli, kirchhoff)."""
    return sum(0.5 for e in elements if e not in ("ancf_cable", "euler_bernoulli", "kirchhoff"))


@pytest.mark.parametrize("first,second,a_first,kind", [
    ("ancf3243", "gef", True, "fixed"), ("gef", "ancf3243", True, "fixed"),
    ("ancf3243", "gef", False, "clamp"), ("euler_bernoulli", "ancf3363", False, "fixed"),
    ("gef", "ancf_cable", True, "fixed")])
def test_ancf_welded_to_a_rod_bends_as_one_cantilever(first, second, a_first, kind):
    """A cantilever of an ANCF segment and a rod segment of the same section welded
    at midspan, either at the clamp, the weld's side a either: the tip deflection
    under a small tip load P against Timoshenko's P L^3/(3 EI) + P L_s/(k G A)
    (L_s: the length of the shear-deformable segments, k = 5/6) within 1 %."""
    P = 0.01
    s = _run(_two_segments(first, second, a_first, kind, P), f"{first}_{second}")
    w = -s["sensors"]["tip"]["displacement"][2]
    ref = P * L**3 / (3 * EI) + P * _shear_length(first, second) / GA
    assert abs(w / ref - 1) < 0.01, (w, ref)
    r = s["reactions"][1]
    # the weld carries P and its moment about the weld point to side a (statics of the tip half)
    sign = 1.0 if a_first else -1.0
    assert abs(r["force"][2] - sign * -P) < 1e-6 * P, r
    assert abs(r["moment"][1] - sign * P * 0.5) < 2e-3 * P * 0.5, r


def _tip_body(element, a_body=False, load=None, e=0.1, m=0.01):
    """A 1 m `element` cantilever (density 1 kg/m^3) with a body of mass m welded to
    its end, the body's centre e beyond the end on the axis, gravity -z (or `load`
    on the body)."""
    weld = _con("fixed", "tip", "arm:end") if a_body else _con("fixed", "arm:end", "tip")
    text = (HEAD.replace("RHO", "1.0") + _beam("arm", element, 0.0, 1.0, n=10) + _con("clamp", "arm:start") + weld
            + f'[[body]]\nname = "tip"\nmass = {m}\ncenter = [{1.0 + e}, 0.0, 0.0]\ninertia = [1e-6, 2e-6, 3e-6]\n'
            + '[[sensor]]\nname = "end"\nat = "arm:end"\n[[sensor]]\nname = "body"\nat = "tip"\n')
    return text + (load or '[[load]]\ntype = "gravity"\nvalue = [0.0, 0.0, -9.81]\n')


@pytest.mark.parametrize("element,a_body", [("ancf3243", False), ("ancf3363", True), ("ancf_cable", False)])
def test_body_welded_to_an_ancf_tip_under_gravity(element, a_body):
    """A body (mass m, centre e beyond the tip) welded to an ANCF cantilever's end,
    under gravity: the end's deflection and the body's rotation (its axes) against
    beam theory for the tip force P = m g, the moment P e and the beam's own
    weight q: w = P L^3/(3EI) + P e L^2/(2EI) + q L^4/(8EI) (+ (P + q L/2) L/(kGA)
    for the continuum elements), theta = P L^2/(2EI) + P e L/EI + q L^3/(6EI), within 1 %;
    the body's centre follows the end rigidly (w + e sin theta)."""
    m, e, g = 0.01, 0.1, 9.81
    P, q = m * g, 1.0 * B * B * g
    s = _run(_tip_body(element, a_body), f"body_{element}")
    w = -s["sensors"]["end"]["displacement"][2]
    shear = (P + q * L / 2) * L / GA if element != "ancf_cable" else 0.0
    w_ref = P * L**3 / (3 * EI) + P * e * L**2 / (2 * EI) + q * L**4 / (8 * EI) + shear
    th_ref = P * L**2 / (2 * EI) + P * e * L / EI + q * L**3 / (6 * EI)
    d1 = s["sensors"]["body"]["d1"]
    th = math.atan2(d1[2], d1[0]) * -1.0
    assert abs(w / w_ref - 1) < 0.01, (w, w_ref)
    assert abs(th / th_ref - 1) < 0.01, (th, th_ref)
    wb = -s["sensors"]["body"]["displacement"][2]
    assert abs(wb - (w + e * math.sin(th))) < 1e-3 * wb, (wb, w, th)


@pytest.mark.parametrize("element", ["ancf3243", "ancf3363"])
def test_torque_through_the_weld_twists_the_ancf_beam(element):
    """A torque T about the axis on a body welded to the end of an ANCF cantilever:
    the body turns by T L / (G J) with the continuum sections' torsion constant,
    the polar moment J = I1 + I2 = b^4/6 (their sections do not warp;
    docs/explanation/elements.md), within 1 %."""
    T = 0.01
    load = f'[[load]]\ntype = "moment"\nat = "tip"\nvalue = [{T}, 0.0, 0.0]\n'
    s = _run(_tip_body(element, load=load, e=0.0), f"torsion_{element}")
    d2 = s["sensors"]["body"]["d2"]
    phi = math.atan2(d2[2], d2[1])
    assert abs(phi / (T * L / GJ) - 1) < 0.01, (phi, T * L / GJ)


# ----------------------------------------------------------------------------
# The constraint functions of every family x rod / body, at the scenes' parameters

def _quat(axis, angle):
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    return np.concatenate([[math.cos(angle / 2)], math.sin(angle / 2) * a])


def _qmul(p, r):
    return np.concatenate([[p[0] * r[0] - p[1:] @ r[1:]], p[0] * r[1:] + r[0] * p[1:] + np.cross(p[1:], r[1:])])


def _qrot(p):
    p = p / np.linalg.norm(p)
    s, v = p[0], p[1:]
    V = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + 2 * (s * V + V @ V)


# slots of x per kind: "r" a position, "v" a nodal vector, "p" a quaternion, "-" unused
SLOTS = {"spherical": "rrr----rrrpppp", "weld_vectors": "vvvvvv----pppp", "weld_vector": "vvv-------pppp",
         "weld_tangent": "vvv-------pppp"}


def _move(kind, dofs, x, Q, qQ, t, side=None):
    """x moved rigidly by (Q, t) (or only the slots with dof in `side`)."""
    y = x.copy()
    lay = SLOTS[kind]
    for start in (0, 3, 7, 10):
        if dofs[start] < 0 or (side is not None and dofs[start] not in side):
            continue
        c = lay[start]
        if c == "p":
            y[start:start + 4] = _qmul(qQ, x[start:start + 4])
        elif c == "r":
            y[start:start + 3] = Q @ x[start:start + 3] + t
        elif c == "v":
            y[start:start + 3] = Q @ x[start:start + 3]
    return y


FAMILIES = ("ancf3243", "ancf3273", "ancf3333", "ancf3363", "ancf_cable")


def _weld_model(element, other):
    """The model of an `element` beam along a skew direction welded at its end to
    `other` (a gef beam continuing it, or a body with a full inertia tensor: frames
    not aligned with the axes), as the scene compiler builds it."""
    from gen.scene import build
    d = np.array([0.6, 0.48, 0.64])
    text = HEAD.replace("RHO", "1.0") + _beam("arm", element, 0.0, 1.0, n=2, d=d, up=(0.0, 0.8, -0.6))
    if other == "body":
        text += ('[[body]]\nname = "tip"\nmass = 1.0\ncenter = [0.7, 0.5, 0.9]\n'
                 "inertia = [2.0, 3.0, 4.0, 0.3, -0.2, 0.1]\n" + _con("fixed", "tip", "arm:end"))
    else:
        text += _beam("rod", "gef", 1.0, 1.5, n=2, d=d, up=(0.0, 0.8, -0.6)) + _con("fixed", "arm:end", "rod:start")
    p = ensure_dir(BUILD / "weld") / f"{element}_{other}.toml"
    p.write_text(text)
    m = build(str(p))
    (r,) = [x for x in m["reactions"] if x[1] == "fixed"]
    return m, m["nlcons"][r[8]: r[8] + r[10]]


@pytest.mark.parametrize("element", FAMILIES)
@pytest.mark.parametrize("other", ["rod", "body"])
def test_weld_constraints_against_rigid_motions_and_central_differences(element, other):
    """Every family x (rod node, body): the weld's joints as the scene compiler
    builds them (a skew beam, a body with a full inertia tensor).  g = 0 in the
    reference and after any rigid motion of both sides (built here from
    quaternions); g != 0 when only the frame turns about an axis across the
    beam; a turn of the frame about the cable's tangent and a stretch of r_x are
    free; the rows are independent (the stacked Jacobian has full rank); G and
    sum nu_k d2 g_k against central differences at random states."""
    _, kinds = _joint_kinds()
    m, joints = _weld_model(element, other)
    rng = np.random.default_rng(3)
    names = [j[0] for j in joints]
    assert names[0] == "spherical" and all(n in SLOTS for n in names)
    frame = set(joints[0][1][7:14])
    tangent = np.array([0.6, 0.48, 0.64])
    Qr = _qrot(_quat([0.3, -1.0, 0.5], 1.1))
    rows, total = [], 0
    for kind, dofs, x0, prm24, _ in joints:
        nrow, ev, he = kinds[kind]
        prm = np.array(list(prm24) + [0.0, 0.0])
        x0 = np.array(x0, float)
        g_of = joint_g(nrow, ev, prm)
        g0, G0 = g_of(x0)
        assert np.abs(g0).max() < 1e-12, (kind, g0)
        qQ = _quat([0.3, -1.0, 0.5], 1.1)
        assert np.abs(g_of(_move(kind, dofs, x0, Qr, qQ, np.array([0.2, -0.4, 1.0])))[0]).max() < 1e-12, kind
        across = np.cross(tangent, [0.0, 0.0, 1.0])
        q_small = _quat(across, 1e-3)
        turned = g_of(_move(kind, dofs, x0, _qrot(q_small), q_small, np.zeros(3), side=frame))[0]
        if np.abs(prm[3:12]).max() > 0.0:      # (a body's offset, or a nonzero reference vector)
            assert np.abs(turned).max() > 1e-5, kind
        if kind == "weld_tangent":
            q_tw = _quat(tangent, 0.7)
            assert np.abs(g_of(_move(kind, dofs, x0, _qrot(q_tw), q_tw, np.zeros(3), side=frame))[0]).max() < 1e-12
        for i in range(nrow):
            row = np.zeros(m["ndof"])
            for k in range(NX):
                if dofs[k] >= 0:
                    row[dofs[k]] += G0[i, k]
            rows.append(row)
        total += nrow
        for trial in range(2):
            check_joint_derivatives(nrow, ev, he, x0 + 0.3 * rng.normal(size=NX), prm, rng.normal(size=nrow), kind)
    assert np.linalg.matrix_rank(np.array(rows), tol=1e-9) == total
    expected = 3 + (2 if element == "ancf_cable" else 6 if element in ("ancf3243", "ancf3333") else 15)
    assert total == expected
    if element in ("ancf3243", "ancf3273", "ancf_cable"):        # r_x's stretch is free (and all of it but a cable's)
        rx = [joints[0][1][2] + k for k in (1, 2, 3)]            # (r_x follows r in each node)
        on_rx = np.array(rows)[:, rx]
        if element == "ancf_cable":
            assert np.abs(on_rx @ m["q0"][rx[0]: rx[0] + 3]).max() < 1e-12 and np.abs(on_rx).max() > 0.5
        else:
            assert not np.abs(on_rx).any()


def test_weld_bad_input_one_line():
    """A rod point not at the ANCF node, an unknown point or body, a joint point
    `at` off the ANCF node, a cross_section key, and a joint the weld does not
    cover (revolute: no axis of an ANCF node): one clear line each."""
    base = _two_segments("ancf3243", "gef")
    check_error(base.replace('start = [0.5, 0.0, 0.0]\nend = [1.0', 'start = [0.52, 0.0, 0.0]\nend = [1.0'),
                "constraint[1].b", "must coincide in the reference configuration")
    check_error(base.replace('b = "s2:start"', 'b = "s3:start"'), "constraint[1].b", "no beam named 's3'")
    check_error(base.replace('b = "s2:start"', 'b = "s2:start"\nat = [0.5, 0.1, 0.0]'), "constraint[1].at",
                "must be the ANCF node")
    check_error(base.replace('type = "fixed"\na = "s1:end"', 'type = "clamp"\ncross_section = "free"\na = "s1:end"'),
                "constraint[1].cross_section", "no cross_section")
    body = _tip_body("ancf3243")
    check_error(body.replace('b = "tip"', 'b = "top"'), "constraint[1].b", "a body name")
    check_error(body.replace('type = "fixed"\na = "arm:end"', 'type = "revolute"\naxis = [0.0, 1.0, 0.0]\n'
                             'a = "arm:end"'), "constraint[1].a",
                "a revolute joint needs a rotation on both sides.*fixed to a rod point or a body")


def test_body_welded_to_an_ancf_tip_vibrates_as_the_frequency_equation_says():
    """Modal: models/tip_mass_cantilever.toml with its steel beam as ancf3243 (St.
    Venant-Kirchhoff, nu = 0, 20 elements) and its body welded by the ANCF weld:
    the first bending frequency (both planes) against the Euler-Bernoulli frequency
    equation with the tip mass and its rotary inertia (4.40045 Hz) within 0.1 %
    (measured 3.1e-4)."""
    from test_bodies import J_TIP, M_TIP, tip_mass_frequency
    from util import ROOT
    text = (ROOT / "models" / "tip_mass_cantilever.toml").read_text()
    text = text.replace('element = "gef"', 'element = "ancf3243"').replace('law = "resultant"', 'law = "svk"') \
        .replace("nu = 0.3", "nu = 0.0")
    s = _run(text, "tip_mass_ancf")
    f = s["frequencies_hz"]
    ref = tip_mass_frequency(M_TIP, J_TIP)
    assert abs(f[0] / ref - 1) < 1e-3 and abs(f[1] / ref - 1) < 1e-3, (f, ref)


def test_rotated_composite_cantilever_deflects_the_rotated_way():
    """Rotation invariance: the ancf3243-gef composite cantilever (weld a the rod)
    turned rigidly about a skew axis (every point, direction and load: the frames
    of the weld no longer the global axes) gives the turned tip displacement to
    1e-7 of it."""
    import rotate_scene as rs
    d = ensure_dir(BUILD / "weld")
    src = d / "composite.toml"
    src.write_text(_two_segments("ancf3243", "gef", a_first=False))
    R = rs.rotation([0.3, -0.5, 0.8], 0.9)
    rot = d / "composite_rotated.toml"
    rot.write_text(rs.rotated(src, R))
    u0 = np.array(_run(src.read_text(), "composite")["sensors"]["tip"]["displacement"])
    u1 = np.array(_run(rot.read_text(), "composite_rotated")["sensors"]["tip"]["displacement"])
    assert np.abs(u1 - np.array(R) @ u0).max() < 1e-7 * np.abs(u0).max(), (u1, np.array(R) @ u0)


def test_weld_of_a_uniform_ancf3363_warns_as_a_rigid_clamp_does():
    """A weld holds the ANCF section rigid as a rigid clamp does, so a uniformly
    meshed ancf3363 segment at a weld gets the clamp's grading warning
    (tests/test_clamp_grading.py, the measured boundary layer); a segment graded
    toward the weld does not."""
    text = _two_segments("euler_bernoulli", "ancf3363", False, "fixed")
    s = _run(text, "eb_3363_warn")
    w = [x for x in s["warnings"] if "a weld (the section held rigid" in x]
    assert len(w) == 1 and "beam s2" in w[0] and "beam.grading = 20" in w[0], s["warnings"]
    graded = text.replace('name = "s2"\n', 'name = "s2"\ngrading = 20\n')
    s = _run(graded, "eb_3363_graded")
    assert not any("a weld (the section held rigid" in x for x in s["warnings"]), s["warnings"]
