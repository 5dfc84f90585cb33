"""The resultant beams (gef, euler_bernoulli, kirchhoff, ancf_cable) against closed
forms: the elastica (elliptic integrals, GSL), roll-up, torsion, shear compliance,
Castigliano for a curved beam, rigid motions of an arc, load-unload cycles."""
import ctypes
import math
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import sympy as sp

from references.elastica import tip_load_cantilever
from references.seed_tables import value
from util import BUILD, ROOT, Kernel, ensure_dir, load_run, rel, run_scene, tip

E, L, B, H, NU = 7.2e10, 1.0, 0.01, 0.01, 0.3
EI = E * B * H**3 / 12
RESULTANT = ["material.alu.law=resultant"]
ELEMENTS = ("gef", "euler_bernoulli", "kirchhoff", "ancf_cable")


def angle_z(rows):
    out, prev = 0.0, None
    for r in rows:
        if r["sensor"] != "tip":
            continue
        a = math.atan2(float(r["d3y"]), float(r["d3x"]))
        if prev is not None:
            d = a - prev
            out += d - 2 * math.pi * round(d / (2 * math.pi))
        prev = a
    return math.degrees(out)


def elastica_gsl():
    exe = ensure_dir(BUILD) / "elastica_gsl"
    src = ROOT / "tests" / "elastica_gsl.c"
    if not exe.exists() or exe.stat().st_mtime < src.stat().st_mtime:
        r = subprocess.run(["cc", "-std=c11", "-O2", "-Wall", "-Wextra", str(src), "-o", str(exe),
                            "-lgsl", "-lgslcblas", "-lm"], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
    return lambda Lb, EIb, P: tuple(float(x) for x in subprocess.run(
        [str(exe), repr(Lb), repr(EIb), repr(P)], capture_output=True, text=True, check=True).stdout.split())


def test_rotation_functions_match_high_precision():
    """rod_math.h (series near zero, closed forms elsewhere) against 40-digit sympy values,
    on both sides of each switch and at zero."""
    from gen.rodmath import _s as s, _u as u, closed_forms
    cf = closed_forms()
    src = ensure_dir(BUILD) / "rod_math_check.c"
    cases = [(0.0, 1.0), (1e-12, 0.3), (0.2, 2.0), (3.9999, 0.7), (4.0001, 1.3), (20.0, 0.5),
             (0.2499, 1.0), (0.2501, 1.0), (0.9, 3.0), (2.0, -0.3), (0.5, 0.01)]
    lines = ['#include <stdio.h>', f'#include "{ROOT / "out" / "kernels" / "rod_math.h"}"', "int main(void) {"]
    for x, y in cases:
        lines.append(f'printf("%.17g %.17g %.17g %.17g %.17g %.17g %.17g\\n", bk_sh({x!r}), bk_sh1({x!r}), '
                     f"bk_sh2({x!r}), bk_sh3({x!r}), bk_at({x!r}, {y!r}), bk_at_u({x!r}, {y!r}), bk_at_uu({x!r}, {y!r}));")
    lines.append("return 0; }")
    src.write_text("\n".join(lines) + "\n")
    exe = src.with_suffix("")
    r = subprocess.run(["cc", "-std=c11", "-O2", "-Wall", "-Wextra", str(src), "-o", str(exe), "-lm"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    out = subprocess.run([str(exe)], capture_output=True, text=True, check=True).stdout.split("\n")
    names = ("bk_sh", "bk_sh1", "bk_sh2", "bk_sh3", "bk_at", "bk_at_u", "bk_at_uu")
    worst = 0.0
    for (x, y), line in zip(cases, out):
        got = [float(v) for v in line.split()]
        for name, g in zip(names, got):
            e = cf[name]
            xx = sp.Float("1e-24", 250) if x == 0.0 else sp.Float(x, 250)   # u -> 0: the limit
            ref = float(e.subs({u: xx, s: sp.Float(y, 250)}).evalf(200))
            err = abs(g - ref) / max(abs(ref), 1e-300)
            worst = max(worst, err)
            assert err <= 1e-12, (name, x, y, g, ref, err)


def test_tables_3_4_ten_elements():
    """10 elements: within 0.1 % of ABAQUS, or of the analytic elastica (GSL elliptic
    integrals) where the two differ by more than 0.1 % (u in Table 3)."""
    el = elastica_gsl()
    cases = [("cantilever_bend_10N", 3, "Fz=-10 N", 10.0, (("u", 0), ("w", 2))),
             ("cantilever_bend_100N", 3, "Fz=-100 N", 100.0, (("u", 0), ("w", 2))),
             ("cantilever_bend3d_50N", 4, "Fy=Fz=-50 N", 50.0 * math.sqrt(2), (("u", 0), ("v", 1), ("w", 2)))]
    bad = []
    for scene, table, load, P, comps in cases:
        u_el, w_el = el(L, EI, P)
        w_el = -w_el if table == 3 else -w_el / math.sqrt(2)     # along the load; 3-D: diagonal
        exact = {"u": u_el, "v": w_el, "w": w_el}
        for elem in ELEMENTS:
            s, _ = run_scene(scene, RESULTANT + [f"beam.arm.element={elem}"])
            d = tip(s)
            for q, k in comps:
                ab = value(table, load, 0.0, q, "abaqus_b32")
                ref, which = (ab, "ABAQUS") if rel(ab, exact[q]) <= 1e-3 else (exact[q], "elastica")
                if rel(d[k], ref) > 1e-3:
                    bad.append(f"{elem} {scene} {q}: {d[k]:.6e} vs {which} {ref:.6e} ({rel(d[k], ref):.2e})")
    assert not bad, "\n".join(bad)


def test_rollup_and_torsion():
    """Table 5 (M = 2 pi EI/L): gef, euler_bernoulli, kirchhoff within 0.1 degree of 360,
    ancf_cable within 0.5; Table 6 at 10 N m: gef within 0.5 % of T L/(G J), J = 0.1406 b^4."""
    for elem, tol in (("gef", 0.1), ("euler_bernoulli", 0.1), ("kirchhoff", 0.1), ("ancf_cable", 0.5)):
        s, rows = run_scene("cantilever_rollup", RESULTANT + [f"beam.arm.element={elem}"])
        a = angle_z(rows)
        assert abs(a - 360.0) <= tol, f"{elem}: roll-up angle {a:.5f} degrees"
    s, rows = run_scene("cantilever_torsion_10Nm", RESULTANT + ["beam.arm.element=gef"])
    ang = 0.0
    prev = None
    for r in rows:
        a = math.atan2(float(r["d1z"]), float(r["d1y"]))
        if prev is not None:
            d = a - prev
            ang += d - 2 * math.pi * round(d / (2 * math.pi))
        prev = a
    G = E / (2 * (1 + NU))
    exact = 10.0 * L / (G * 0.1406 * B**4)
    assert rel(ang, exact) <= 5e-3, (math.degrees(ang), math.degrees(exact))


def test_kirchhoff_against_elliptic_integral_elastica():
    """Kirchhoff (inextensible, shear-rigid), 20 elements, tip loads with P L^2/EI = 0.5 ... 20:
    tip displacements within 1e-4 (relative to L) of the closed-form elastica."""
    el = elastica_gsl()
    for alpha in (0.5, 2.0, 5.0, 20.0):
        P = alpha * EI / L**2
        s, _ = run_scene("cantilever_bend_10N", RESULTANT + ["beam.arm.element=kirchhoff", "beam.arm.elements=20",
                                                            f"load.0.value.2={-P}", "static.load_steps=20"])
        u, w = el(L, EI, P)
        d = tip(s)
        assert abs(d[0] - u) <= 1e-4 * L and abs(d[2] + w) <= 1e-4 * L, (alpha, d, u, w)


def test_timoshenko_minus_euler_bernoulli_is_shear_compliance():
    """Short thick cantilever (L/h = 5), tiny tip load: w_gef - w_EB = P L / (k G A) within 1 %."""
    P = 1e-3
    sets = RESULTANT + ["beam.arm.elements=10", "section.square.b=0.2", "section.square.h=0.2",
                        f"load.0.value.2={-P}", "static.load_steps=1"]
    s_t, _ = run_scene("cantilever_bend_10N_nu03", sets + ["beam.arm.element=gef"])
    s_e, _ = run_scene("cantilever_bend_10N_nu03", sets + ["beam.arm.element=euler_bernoulli"])
    diff = tip(s_e)[2] - tip(s_t)[2]
    G = E / (2 * (1 + NU))
    k = 10 * (1 + NU) / (12 + 11 * NU)
    exact = P * L / (k * G * 0.2 * 0.2)
    assert rel(diff, exact) <= 1e-2, (diff, exact)
    assert rel(tip(s_e)[2], -P * L**3 / (3 * E * 0.2**4 / 12)) <= 1e-3


ARC = """[scene]
analysis = "static"
[material.steel]
law = "resultant"
E = 2.0e11
nu = 0.3
rho = 7800.0
[section.round]
shape = "circle"
radius = 0.01
[[beam]]
name = "hook"
element = "{elem}"
material = "steel"
section = "round"
start = [1.0, 0.0, 0.0]
arc_center = [0.0, 0.0, 0.0]
arc_axis = [0.0, 0.0, 1.0]
arc_angle = 90.0
elements = {n}
[[constraint]]
type = "clamp"
a = "hook:start"
[[load]]
type = "force"
at = "hook:end"
value = {force}
[static]
load_steps = 1
[[sensor]]
name = "tip"
at = "hook:end"
"""


def castigliano_quarter_circle(R, P_dir, E, nu, r):
    """Tip deflection along the load of a quarter circle (radius R, clamped at angle 0,
    free at 90 degrees, in the xy plane) by Castigliano: U = int (M^2/2EI + T^2/2GJ +
    N^2/2EA + V^2/2kGA) R dphi, delta = dU/dP.  P_dir: 'z' (out of plane) or 'x' (in plane)."""
    P, phi = sp.symbols("P phi", positive=True)
    G = E / (2 * (1 + nu))
    A, I = sp.pi * r**2, sp.pi * r**4 / 4
    J = 2 * I
    k = sp.Rational(6) * (1 + sp.nsimplify(nu)) / (7 + 6 * sp.nsimplify(nu))
    # section at angle phi: position R (cos phi, sin phi); tip at (0, R); tangent (-sin, cos)
    if P_dir == "z":
        # load P along -z at the tip: bending about the radial axis and torsion about the tangent
        dx, dy = 0 - R * sp.cos(phi), R - R * sp.sin(phi)     # tip minus section
        # moment of the tip force (0, 0, -P) about the section: r x F = (-P dy, P dx, 0)
        Mv = sp.Matrix([-P * dy, P * dx, 0])
        t = sp.Matrix([-sp.sin(phi), sp.cos(phi), 0])
        T = Mv.dot(t)
        Mb = sp.sqrt(sp.simplify(Mv.dot(Mv) - T**2))
        V = P
        U = sp.integrate((Mb**2 / (2 * E * I) + T**2 / (2 * G * J) + V**2 / (2 * k * G * A)) * R, (phi, 0, sp.pi / 2))
    else:
        # load P along -x at the tip (in plane): bending about z, axial and shear
        dx, dy = -R * sp.cos(phi), R - R * sp.sin(phi)
        F = sp.Matrix([-P, 0, 0])
        Mz = dx * F[1] - dy * F[0]
        t = sp.Matrix([-sp.sin(phi), sp.cos(phi), 0])
        N = F.dot(t)
        V = F.dot(sp.Matrix([sp.cos(phi), sp.sin(phi), 0]))
        U = sp.integrate((Mz**2 / (2 * E * I) + N**2 / (2 * E * A) + V**2 / (2 * k * G * A)) * R, (phi, 0, sp.pi / 2))
    return float(sp.diff(U, P).subs(P, 1))


def test_quarter_circle_matches_castigliano():
    """A quarter-circle cantilever (R = 1 m, round section r = 1 cm) under a small tip load,
    out of plane and in plane: gef tip deflection per unit load within 0.2 % of Castigliano's."""
    d = ensure_dir(BUILD / "arc")
    for direction, force, comp in (("z", "[0.0, 0.0, -1.0]", 2), ("x", "[-1.0, 0.0, 0.0]", 0)):
        p = d / f"quarter_{direction}.toml"
        p.write_text(ARC.format(elem="gef", n=16, force=force))
        s, _ = run_scene(p)
        got = -tip(s)[comp]
        exact = castigliano_quarter_circle(1.0, direction, 2.0e11, 0.3, 0.01)
        assert rel(got, exact) <= 2e-3, (direction, got, exact)


def test_arc_rigid_motion_has_zero_strain():
    """A curved gef element (30 degrees of a 1 m arc): tabulated from its reference
    coordinates, then rotated by 200 degrees and translated: energy and force vanish."""
    from gen.scene import frame_quaternion
    k = Kernel("gef", "resultant")
    R0, ang = 1.0, math.radians(30)
    q0 = []
    for xi in (0.0, 0.5, 1.0):
        phi = xi * ang
        X = [R0 * math.cos(phi), R0 * math.sin(phi), 0.0]
        t = [-math.sin(phi), math.cos(phi), 0.0]
        d2 = [0.0, 0.0, 1.0]
        d1 = [d2[1] * t[2] - d2[2] * t[1], d2[2] * t[0] - d2[0] * t[2], d2[0] * t[1] - d2[1] * t[0]]
        q0 += X + frame_quaternion(t, d1, d2)
    q0 = np.array(q0)
    geom = [R0 * ang, 0.02, 0.02, math.pi * 1e-4, 7.85e-9, 7.85e-9, 1.57e-8]
    tab = k.tabulate(geom, q0)
    mat = [1.0e7, 4.0e6, 4.0e6, 2.0e3, 2.0e3, 2.0e3]
    th = math.radians(200)
    axis = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
    qr = np.concatenate([[math.cos(th / 2)], math.sin(th / 2) * axis])
    Rm = (math.cos(th) * np.eye(3) + math.sin(th) * np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]],
                                                               [-axis[1], axis[0], 0]])
          + (1 - math.cos(th)) * np.outer(axis, axis))
    q = q0.copy()
    for n in range(3):
        q[7 * n:7 * n + 3] = Rm @ q0[7 * n:7 * n + 3] + np.array([0.4, -2.0, 1.0])
        s, v = q0[7 * n + 3], q0[7 * n + 4:7 * n + 7]
        q[7 * n + 3] = qr[0] * s - qr[1:] @ v
        q[7 * n + 4:7 * n + 7] = qr[0] * v + s * qr[1:] + np.cross(qr[1:], v)
    U0, f0, _ = k.eval(q0, tab, mat)
    U, f, K = k.eval(q, tab, mat)
    fscale = mat[0]                     # force of a unit axial strain
    assert abs(U0) <= 1e-12 * fscale and np.abs(f0).max() <= 1e-10 * fscale, (U0, np.abs(f0).max())
    assert abs(U) <= 1e-12 * fscale and np.abs(f).max() <= 1e-10 * fscale, (U, np.abs(f).max())


def test_load_unload_cycles_return_to_reference():
    """Path independence: three roll-up load-unload cycles (the tip turns 360 degrees and
    back each time); at every return the beam is straight again and at every full load
    the tip is where it was the first time, to round-off."""
    s, rows = run_scene("cantilever_rollup", RESULTANT + ["beam.arm.element=gef", "static.cycles=3"])
    assert s["converged"]
    tips = [r for r in rows if r["sensor"] == "tip"]
    zero = [r for r in tips if float(r["time"]) == 0.0]
    full = [r for r in tips if float(r["time"]) == 1.0]
    assert len(zero) == 4 and len(full) == 4
    for r in zero:
        assert max(abs(float(r[k])) for k in ("ux", "uy", "uz")) <= 1e-12, r
    for r in full[1:]:
        assert max(abs(float(r[k]) - float(full[0][k])) for k in ("x", "y", "z")) <= 1e-12
