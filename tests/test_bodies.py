"""Rigid bodies and joints nonlinear in q (gen/body.py, runtime/assembly/constraints.c), each
against a reference that is not our own element: finite differences of the
generated joint kernels, the Euler-Bernoulli frequency equation with a tip mass
and Rayleigh's estimate, beam theory, rigid multibody models integrated with
SciPy, small-oscillation closed forms and the slider-crank kinematics."""
import ctypes
import math
import re

import numpy as np
import pytest

from util import ROOT, build_shared_kernels, run_scene
from test_bad_input import check_error

NX, NPARAM = 14, 26


class JointKind(ctypes.Structure):
    _fields_ = [("name", ctypes.c_char_p), ("nrow", ctypes.c_int), ("eval", ctypes.c_void_p),
                ("hessian", ctypes.c_void_p)]


def _joint_kinds():
    lib = ctypes.CDLL(str(build_shared_kernels()))
    n = ctypes.c_int.in_dll(lib, "bk_njoint_kinds").value
    table = (ctypes.POINTER(JointKind) * n).in_dll(lib, "bk_joint_kinds")
    D = ctypes.POINTER(ctypes.c_double)
    out = {}
    for k in range(n):
        jk = table[k].contents
        ev = ctypes.CFUNCTYPE(None, D, D, D, D)(jk.eval)
        he = ctypes.CFUNCTYPE(None, D, D, D, D)(jk.hessian)
        out[jk.name.decode()] = (jk.nrow, ev, he)
    return lib, out


def _p(a):
    return a.ctypes.data_as(ctypes.POINTER(ctypes.c_double))


def joint_g(nrow, ev, prm):
    """x -> (g, G) of a joint kernel's eval at the parameters prm."""
    def g_of(xx):
        g, G = np.zeros(nrow), np.zeros(nrow * NX)
        ev(_p(np.ascontiguousarray(xx, dtype=float)), _p(prm), _p(g), _p(G))
        return g, G.reshape(nrow, NX)
    return g_of


def check_joint_derivatives(nrow, ev, he, x, prm, nu, name):
    """A joint kernel's G and Hessian term sum nu_k d2 g_k at x against central
    differences of g and of G^T nu; the Hessian term symmetric."""
    g_of = joint_g(nrow, ev, prm)
    _, G0 = g_of(x)
    H = np.zeros(NX * NX)
    he(_p(np.ascontiguousarray(x, dtype=float)), _p(prm), _p(nu), _p(H))
    H = H.reshape(NX, NX)
    h = 1e-6
    Gfd, Hfd = np.zeros((nrow, NX)), np.zeros((NX, NX))
    for j in range(NX):
        e = np.zeros(NX)
        e[j] = h
        (gp, Gp), (gm, Gm) = g_of(x + e), g_of(x - e)
        Gfd[:, j] = (gp - gm) / (2 * h)
        Hfd[:, j] = (Gp.T @ nu - Gm.T @ nu) / (2 * h)
    assert np.abs(G0 - Gfd).max() <= 1e-7 * max(1.0, np.abs(G0).max()), name
    assert np.abs(H - Hfd).max() <= 1e-6 * max(1.0, np.abs(H).max()), name
    assert np.abs(H - H.T).max() <= 1e-12 * max(1.0, np.abs(H).max()), name


def test_joint_kernels_match_finite_differences():
    """G = dg/dx and H = sum nu_k d2g_k/dx2 of every generated joint against central
    differences of g and of G^T nu, at random frames (quaternions not of unit
    length), offsets, axes and drive values (c, s); g is invariant under rescaling either
    quaternion (of p_b alone for the welds of an ANCF node, whose x[0..5] are nodal
    vectors: tests/test_weld.py checks them at the scenes' parameters too)."""
    _, kinds = _joint_kinds()
    assert set(kinds) == {"spherical", "revolute", "universal", "fixed", "prismatic", "prescribed_rotation",
                          "prescribed_translation", "weld_vectors", "weld_vector", "weld_tangent"}
    rng = np.random.default_rng(7)
    for name, (nrow, ev, he) in sorted(kinds.items()):
        for trial in range(3):
            x = rng.normal(size=NX)
            prm = rng.normal(size=NPARAM)
            g_of = joint_g(nrow, ev, prm)
            g0, _ = g_of(x)
            check_joint_derivatives(nrow, ev, he, x, prm, rng.normal(size=nrow), name)
            xs = x.copy()
            if not name.startswith("weld"):
                xs[3:7] *= 1.7
            xs[10:14] *= 0.6
            assert np.allclose(g_of(xs)[0], g0, rtol=1e-12, atol=1e-12), name


# ----------------------------------------------------------------------------
# A tip mass on a cantilever (models/tip_mass_cantilever.toml)

E, B = 2.1e11, 0.01
EI = E * B**4 / 12
M_TIP, J_TIP, M_BEAM, LEN = 0.5, 1.23e-4, 7850.0 * B * B * 1.0, 1.0


def tip_mass_frequency(M, J):
    """First bending frequency (Hz) of an Euler-Bernoulli cantilever with a tip mass M
    and rotary inertia J: the root of det of the four boundary conditions
    w(0) = w'(0) = 0, EI w''(L) = w^2 J w'(L), EI w'''(L) = -w^2 M w(L)."""
    from scipy.optimize import brentq
    m = M_BEAM / LEN

    def det(w):
        b = (m * w * w / EI)**0.25
        c, s, ch, sh = math.cos(b * LEN), math.sin(b * LEN), math.cosh(b * LEN), math.sinh(b * LEN)
        W = [c, s, ch, sh]
        W1 = [-b * s, b * c, b * sh, b * ch]
        W2 = [-b * b * c, -b * b * s, b * b * ch, b * b * sh]
        W3 = [b**3 * s, -b**3 * c, b**3 * sh, b**3 * ch]
        rows = [[1, 0, 1, 0], [0, b, 0, b], [EI * W2[k] - w * w * J * W1[k] for k in range(4)],
                [EI * W3[k] + w * w * M * W[k] for k in range(4)]]
        return np.linalg.det(np.array(rows))
    ws = np.linspace(1.0, 100.0, 400)
    v = [det(w) for w in ws]
    k = next(i for i in range(len(ws) - 1) if v[i] * v[i + 1] < 0)
    return brentq(det, ws[k], ws[k + 1], xtol=1e-12) / (2 * math.pi)


def test_tip_mass_first_frequency_vs_frequency_equation_and_rayleigh():
    """Modal: the first bending frequency with a 0.5 kg tip mass (fixed joint to a
    rigid body) against the exact Euler-Bernoulli frequency equation (to 2e-4) and
    Rayleigh's estimate f = (1/2 pi) sqrt(3 EI / L^3 / (M + 33/140 m_beam)) (33/140 =
    0.2357; to 0.3 %, its own error here being 0.13 %); without the body the beam's
    own first frequency, so the body is what lowers it."""
    s, _ = run_scene("tip_mass_cantilever")
    f = s["frequencies_hz"]
    exact = tip_mass_frequency(M_TIP, J_TIP)
    rayleigh = math.sqrt(3 * EI / LEN**3 / (M_TIP + 33 / 140 * M_BEAM)) / (2 * math.pi)
    assert abs(f[0] - exact) / exact < 2e-4, (f[0], exact)
    assert abs(f[1] - exact) / exact < 2e-4, (f[1], exact)       # the same in the other plane
    assert abs(f[0] - rayleigh) / rayleigh < 3e-3, (f[0], rayleigh)
    bare = 1.8751**2 / (2 * math.pi * LEN**2) * math.sqrt(EI / (M_BEAM / LEN))
    assert f[0] < 0.6 * bare


def test_tip_mass_with_offset_sags_as_beam_theory_says():
    """Statics: the body's centre of mass 0.1 m beyond the end (the weld carries the
    force M g and the moment 0.1 M g), plus the beam's own weight: tip deflection
    M g L^3/(3 EI) + 0.1 M g L^2/(2 EI) + q L^4/(8 EI) (linear theory; the load is
    small, 1.8 % of L) to 5e-4 (measured 1.8e-4: the geometric nonlinearity), and the
    body turned rigidly with the end section."""
    s, rows = run_scene("tip_mass_cantilever", ["scene.analysis=static", "body.0.center.0=1.1"])
    g, e = 9.81, 0.1
    w = M_TIP * g * LEN**3 / (3 * EI) + e * M_TIP * g * LEN**2 / (2 * EI) + M_BEAM * g * LEN**3 / (8 * EI)
    uz = s["sensors"]["end"]["displacement"][2]
    assert abs(-uz - w) / w < 5e-4, (uz, w)
    end, body = s["sensors"]["end"], s["sensors"]["mass"]
    d3 = np.array(end["d3"])
    assert np.allclose(np.array(body["position"]), np.array(end["position"]) + e * d3, atol=1e-9)
    assert np.allclose(body["d1"], end["d3"], atol=1e-9)          # body axes welded to the section
    # reactions (reactions.csv / summary.json): the weld (a joint nonlinear in q,
    # -s G^T nu on the beam end) exerts the body's weight and its moment about
    # the end node on the beam; the clamp carries the body's and the beam's weight
    # and their moment about the root, both from the deformed positions (sensors)
    re = {r["type"]: r for r in s["reactions"]}
    W = M_TIP * g
    weld, clamp = re["fixed"], re["clamp"]
    assert np.allclose(weld["force"], [0.0, 0.0, -W], atol=1e-9 * W), weld
    lever = np.array(body["position"]) - np.array(weld["point"])
    assert np.allclose(weld["moment"], np.cross(lever, [0.0, 0.0, -W]), atol=1e-9 * W), weld
    assert np.allclose(clamp["force"], [0.0, 0.0, W + M_BEAM * g], atol=1e-8 * W), clamp
    my = clamp["moment"][1]
    assert W * body["position"][0] < -my < W * body["position"][0] + M_BEAM * g * 0.5 + 1e-9, clamp


def test_tip_mass_free_vibration_period():
    """Dynamics: a free vibration from a small rigid rotation velocity; the period
    between upward zero crossings of the tip deflection against the frequency
    equation (to 0.5 %; measured 8e-6), the tip mass and the beam end together throughout."""
    s, rows = run_scene("tip_mass_cantilever", ["scene.analysis=dynamic", "load.0.value.2=0.0",
                                                "dynamic.t_end=0.7"])
    t = np.array([float(r["time"]) for r in rows if r["sensor"] == "mass"])
    z = np.array([float(r["uz"]) for r in rows if r["sensor"] == "mass"])
    ze = np.array([float(r["uz"]) for r in rows if r["sensor"] == "end"])
    assert np.abs(z - ze).max() < 1e-9
    up = [t[i] - z[i] * (t[i + 1] - t[i]) / (z[i + 1] - z[i]) for i in range(1, len(z) - 1)
          if z[i] <= 0.0 < z[i + 1]]
    assert len(up) >= 2, up
    period = (up[-1] - up[0]) / (len(up) - 1)
    f = 1.0 / period
    exact = tip_mass_frequency(M_TIP, J_TIP)
    assert abs(f - exact) / exact < 5e-3, (f, exact)


# ----------------------------------------------------------------------------
# Rigid double pendulum (models/double_pendulum_revolute.toml, double_pendulum_body.toml)

def rigid_double_pendulum(ts, m=0.27, L=1.0, g=9.81):
    """Angles (from +x, in the x-z plane) of two uniform rods (mass m, length L,
    inertia m L^2/12) hinged at the origin and to each other, released straight and
    horizontal: Lagrange's equations integrated with SciPy (DOP853, rtol 1e-11)."""
    from scipy.integrate import solve_ivp

    def rhs(t, y):
        t1, t2, w1, w2 = y
        c, s = math.cos(t1 - t2), math.sin(t1 - t2)
        A = np.array([[4 / 3 * m * L * L, 0.5 * m * L * L * c], [0.5 * m * L * L * c, m * L * L / 3]])
        f = -np.array([0.5 * m * L * L * s * w2 * w2 + 1.5 * m * g * L * math.cos(t1),
                       -0.5 * m * L * L * s * w1 * w1 + 0.5 * m * g * L * math.cos(t2)])
        a = np.linalg.solve(A, f)
        return [w1, w2, a[0], a[1]]
    sol = solve_ivp(rhs, (0.0, ts[-1]), [0.0, 0.0, 0.0, 0.0], t_eval=ts, rtol=1e-11, atol=1e-12, method="DOP853")
    return sol.y[0], sol.y[1]


def _xz(rows, name, cols=("x", "z")):
    rs = [r for r in rows if r["sensor"] == name]
    return np.array([float(r["time"]) for r in rs]), np.array([[float(r[c]) for c in cols] for r in rs])


def test_stiff_double_pendulum_revolute_joints_vs_rigid_ode():
    """Two very stiff gef rods, a revolute to the ground and a revolute between the
    beams (nonlinear in q): the free end over 1 s against the rigid double pendulum
    (measured 7.6e-5 m of a 2 m reach at dt = 1 ms)."""
    s, rows = run_scene("double_pendulum_revolute")
    t, X = _xz(rows, "C")
    t1, t2 = rigid_double_pendulum(t)
    ref = np.c_[np.cos(t1) + np.cos(t2), np.sin(t1) + np.sin(t2)]
    assert np.abs(X - ref).max() < 2e-4, np.abs(X - ref).max()
    assert s["max_constraint_residual"] < 1e-10


def test_double_pendulum_with_a_rigid_body_link_vs_rigid_ode():
    """The second link a rigid body hinged to the stiff beam by a revolute joint: its
    centre of mass and its axis e1 against the same rigid model (measured 1.9e-5 m
    and 5e-5 rad at dt = 1 ms; the rotation of the body is second order in dt)."""
    s, rows = run_scene("double_pendulum_body")
    t, X = _xz(rows, "link2")
    _, D = _xz(rows, "link2", ("d1x", "d1z"))
    t1, t2 = rigid_double_pendulum(t)
    ref = np.c_[np.cos(t1) + 0.5 * np.cos(t2), np.sin(t1) + 0.5 * np.sin(t2)]
    assert np.abs(X - ref).max() < 6e-5, np.abs(X - ref).max()
    assert np.abs(D - np.c_[np.cos(t2), np.sin(t2)]).max() < 1.5e-4
    assert s["max_constraint_residual"] < 1e-10


# ----------------------------------------------------------------------------
# Universal joint, prismatic joint

def test_universal_joint_pendulum_frequencies():
    """Modal about the static equilibrium: a body hanging from a universal joint has
    two pendulum modes, omega^2 = M g d / (J_k + M d^2) about the two cross arms; the
    restoring stiffness is the joint's geometric stiffness (multipliers x Hessian)."""
    s, _ = run_scene("universal_pendulum")
    M, g, d = 2.0, 9.81, 0.3
    ref = sorted(math.sqrt(M * g * d / (J + M * d * d)) / (2 * math.pi) for J in (0.01, 0.02))
    assert np.allclose(s["frequencies_hz"][:2], ref, rtol=1e-6), (s["frequencies_hz"], ref)


def test_prismatic_block_slides_down_the_incline():
    """Dynamics: a block on a frictionless prismatic joint inclined 30 degrees slides
    s = g sin(30 deg) t^2/2 along it (to 1e-6 of s; generalized-alpha is exact for
    constant acceleration up to the Newton tolerance) and does not turn."""
    s, rows = run_scene("prismatic_slide")
    t, X = _xz(rows, "block", ("x", "y", "z"))
    _, D = _xz(rows, "block", ("d1x", "d1y", "d1z", "d3x", "d3y", "d3z"))
    sl = 0.5 * 9.81 * 0.5 * t**2
    ref = np.c_[sl * math.cos(math.pi / 6), 0 * sl, -sl * 0.5]
    assert np.abs(X - ref).max() < 1e-6 * sl.max() + 1e-12, np.abs(X - ref).max()
    assert np.abs(D - np.array([1, 0, 0, 0, 0, 1])).max() < 1e-10


def test_cart_pendulum_frequency():
    """Dynamics: a rigid bob hung from a cart by a revolute joint between two bodies,
    the cart on a horizontal prismatic joint: the swing frequency (zero crossings of
    the bob's axis) against omega^2 = (M + m) m g l / ((M + m)(J + m l^2) - m^2 l^2)
    (measured 1.6e-5 apart), the cart staying on its line."""
    s, rows = run_scene("cart_pendulum")
    t, Z = _xz(rows, "bob", ("d1z",))
    z = Z[:, 0]
    up = [t[i] - z[i] * (t[i + 1] - t[i]) / (z[i + 1] - z[i]) for i in range(1, len(z) - 1) if z[i] <= 0.0 < z[i + 1]]
    assert len(up) >= 2
    f = (len(up) - 1) / (up[-1] - up[0])
    M, m, g, l, J = 1.0, 0.5, 9.81, 0.4, 0.004
    ref = math.sqrt((M + m) * m * g * l / ((M + m) * (J + m * l * l) - m * m * l * l)) / (2 * math.pi)
    assert abs(f - ref) / ref < 2e-4, (f, ref)
    _, C = _xz(rows, "cart", ("y", "z"))
    assert np.abs(C).max() < 1e-12


# ----------------------------------------------------------------------------
# Slider-crank (models/slider_crank.toml)

def _slider(rows):
    t, X = _xz(rows, "slider", ("x", "y", "z"))
    return t, X


def test_slider_crank_rigid_limit_kinematics():
    """A very stiff connecting rod (E = 1e13 Pa, no damping): the slider follows the
    rigid slider-crank x = r cos th + sqrt(l^2 - r^2 sin^2 th) over one and a half
    turns (measured 3e-8 m) and stays on its line; the crank pin on its circle."""
    s, rows = run_scene("slider_crank", ["material.rod.E=1e13", "dynamic.rayleigh_beta=0.0"])
    r, l, w = 0.15, 0.5, 4 * math.pi
    t, X = _slider(rows)
    th = w * t
    xr = r * np.cos(th) + np.sqrt(l * l - (r * np.sin(th))**2)
    assert np.abs(X[:, 0] - xr).max() < 1e-6, np.abs(X[:, 0] - xr).max()
    assert np.abs(X[:, 1:]).max() < 1e-9
    _, P = _xz(rows, "crankpin", ("x", "y"))
    assert np.abs(P - np.c_[r * np.cos(th), r * np.sin(th)]).max() < 1e-6


def test_slider_crank_flexible_rod_shortens_by_its_axial_force():
    """The flexible rod (E A = 1.13e5 N): after the start transient has decayed, the
    slider lags the rigid mechanism by the rod's quasi-static shortening, cos(phi) N l
    / (E A) with N = (M + m_rod/2) x''_rigid / cos(phi) (the slider's and half the
    rod's inertia force; phi the rod angle): to 10 % of its largest value (measured
    5 %, the rest the phase lag of the damping and the rod's axial dynamics)."""
    s, rows = run_scene("slider_crank")
    r, l, w, M = 0.15, 0.5, 4 * math.pi, 0.5
    EA, mrod = 1e9 * math.pi * 0.006**2, 100 * math.pi * 0.006**2 * l
    t, X = _slider(rows)

    def xrig(tt):
        th = w * tt
        return r * np.cos(th) + np.sqrt(l * l - (r * np.sin(th))**2)
    h = 1e-5
    acc = (xrig(t + h) - 2 * xrig(t) + xrig(t - h)) / h**2
    phi = np.arcsin(r * np.sin(w * t) / l)
    est = -(M + mrod / 2) * acc * l / EA
    dev = X[:, 0] - xrig(t)
    late = t >= 0.25
    assert np.abs(dev[late] - est[late]).max() < 0.1 * np.abs(est).max(), \
        (np.abs(dev[late] - est[late]).max(), np.abs(est).max())
    assert np.abs(est).max() > 5e-5                  # the effect is well above the solver's errors
    assert abs(phi).max() < 0.31


# ----------------------------------------------------------------------------
# Fixed joint (weld) between two beams (models/l_frame_weld.toml)

def test_l_frame_welded_at_right_angle_vs_beam_theory():
    """Statics: two beams welded at 90 degrees by a fixed joint, 1 N out of plane at
    the free end: bending of both legs, torsion of the first and shear (Timoshenko,
    Cowper's k; GJ with J = 0.1406 b^4) from linear theory, to 3e-4 (measured
    6.7e-5); the weld keeps the corner's two nodes together and at right angles."""
    s, rows = run_scene("l_frame_weld")
    E, nu, b, P, L, a = 2.1e11, 0.3, 0.01, 1.0, 1.0, 0.5
    G, A, I, J = E / (2 * (1 + nu)), b * b, b**4 / 12, 0.1406 * b**4
    k = 10 * (1 + nu) / (12 + 11 * nu)
    w = P * L**3 / (3 * E * I) + P * a**3 / (3 * E * I) + P * a * a * L / (G * J) + P * (L + a) / (k * G * A)
    uz = s["sensors"]["tip"]["displacement"][2]
    assert abs(-uz - w) / w < 3e-4, (uz, w)
    assert s["converged"]


def test_weld_of_two_colinear_beams_vibrates_as_one_beam():
    """Modal: the second leg turned to continue the first (a 1.5 m cantilever made of
    two beams and a fixed joint): the first two bending frequencies against
    Euler-Bernoulli's (beta L = 1.8751, 4.6941; to 5e-4, measured 3.5e-5 and 2.3e-4:
    shear and rotary inertia)."""
    s, _ = run_scene("l_frame_weld", ["scene.analysis=modal", "beam.b.end.0=1.5", "beam.b.end.1=0.0"])
    E, b, L = 2.1e11, 0.01, 1.5
    ref = [bl**2 / (2 * math.pi * L * L) * math.sqrt(E * b**4 / 12 / (7850 * b * b)) for bl in (1.8751041, 4.6940911)]
    f = s["frequencies_hz"]
    assert abs(f[0] - ref[0]) / ref[0] < 5e-4 and abs(f[2] - ref[1]) / ref[1] < 5e-4, (f, ref)


# ----------------------------------------------------------------------------
# Bad input: one line naming the file and the key

TIP = (ROOT / "models" / "tip_mass_cantilever.toml").read_text()
UNI = (ROOT / "models" / "universal_pendulum.toml").read_text()


def test_bad_bodies_and_joints():
    check_error(TIP.replace('a = "arm:end"\nb = "tip"', 'a = "tip"\nb = "tip"'), "constraint[1].b",
                "and itself")
    check_error(TIP.replace('a = "arm:end"\nb = "tip"', 'a = "arm:end"\nb = "arm:end"'), "constraint[1].b",
                "and itself")
    check_error(TIP.replace("inertia = [1.23e-4, 1.23e-4, 1.23e-4]", "inertia = [1e-4, 1e-4, -1e-4]"),
                "body.tip.inertia", "positive definite")
    check_error(TIP.replace("inertia = [1.23e-4, 1.23e-4, 1.23e-4]", "inertia = [1e-4, 1e-4, 3e-4]"),
                "body.tip.inertia", "triangle inequality")
    check_error(TIP.replace("inertia = [1.23e-4, 1.23e-4, 1.23e-4]", "inertia = [1e-4, 1e-4, 1e-4, 2e-4, 0, 0]"),
                "body.tip.inertia", "positive definite")
    check_error(TIP.replace('inertia = [1.23e-4, 1.23e-4, 1.23e-4]', 'inertia = "heavy"'),
                "body.tip.inertia", "expected")
    check_error(TIP.replace("mass = 0.5", "mass = 0.0"), "body.tip.mass", "positive")
    check_error(TIP.replace('name = "tip"\nmass', 'name = "arm"\nmass'), "body.arm.name", "duplicate name")
    check_error(TIP.replace('type = "fixed"\na = "arm:end"\nb = "tip"',
                            'type = "revolute"\na = "arm:end"\nb = "tip"\naxis = [0.0, 0.0, 0.0]'),
                "constraint[1].axis", "nonzero")
    check_error(TIP.replace('type = "fixed"\na = "arm:end"\nb = "tip"', 'type = "fixed"\na = "tip"'),
                "constraint[1].at", "needs the joint point")
    check_error(TIP.replace('element = "gef"', 'element = "ancf3243"').replace('law = "resultant"', 'law = "svk"')
                .replace('type = "fixed"\na = "arm:end"\nb = "tip"',
                         'type = "revolute"\na = "arm:end"\nb = "tip"\naxis = [0.0, 1.0, 0.0]'),
                "constraint[1].a", "needs a rotation on both sides; .*fixed to a rod point or a body")
    check_error(UNI.replace("axis_b = [0.0, 1.0, 0.0]", "axis_b = [1.0, 1.0, 0.0]"), "constraint[0].axis_b",
                "perpendicular")
    check_error(UNI.replace('a = "bob"', 'a = "rob"'), "constraint[0].a", "a body name")
    check_error(UNI.replace("[[body]]", "[[body]]\ncolour = 1"), "body[0].colour", "unknown key")


def test_rigid_body_linking_two_beams_acts_as_a_weld():
    """A body between the two legs of the L-frame, welded to both (`fixed` joints
    beam-body, the body's centre 5 cm off the corner): with no gravity it is a rigid
    link, so the tip deflects as with the direct weld (same closed form, 3e-4); in
    modal analysis its mass lowers the first frequency."""
    text = (ROOT / "models" / "l_frame_weld.toml").read_text()
    text = text.replace('[[constraint]]\ntype = "fixed"\na = "a:end"\nb = "b:start"',
                        '[[body]]\nname = "corner"\nmass = 0.2\ncenter = [1.0, 0.0, 0.05]\n'
                        'inertia = [1e-4, 1e-4, 1e-4]\n\n'
                        '[[constraint]]\ntype = "fixed"\na = "a:end"\nb = "corner"\n\n'
                        '[[constraint]]\ntype = "fixed"\na = "corner"\nb = "b:start"')
    assert "corner" in text
    from util import BUILD, ensure_dir
    p = ensure_dir(BUILD / "bodies") / "l_frame_body.toml"
    p.write_text(text)
    s, _ = run_scene(p)
    E, nu, b, P, L, a = 2.1e11, 0.3, 0.01, 1.0, 1.0, 0.5
    G, A, I, J = E / (2 * (1 + nu)), b * b, b**4 / 12, 0.1406 * b**4
    k = 10 * (1 + nu) / (12 + 11 * nu)
    w = P * L**3 / (3 * E * I) + P * a**3 / (3 * E * I) + P * a * a * L / (G * J) + P * (L + a) / (k * G * A)
    assert abs(-s["sensors"]["tip"]["displacement"][2] - w) / w < 3e-4
    f_body = run_scene(p, ["scene.analysis=modal"])[0]["frequencies_hz"][0]
    f_weld = run_scene("l_frame_weld", ["scene.analysis=modal"])[0]["frequencies_hz"][0]
    assert f_body < 0.95 * f_weld, (f_body, f_weld)
