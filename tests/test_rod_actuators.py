"""Pneumatic chambers and tendons on rods (issue 37, verification 4 for gef,
euler_bernoulli, kirchhoff).  The line through the chamber's centroid or the tendon,
P = r + dy d1 + dz d2, is fixed in the rotating sections (the generated
section_line(), tests/test_follower_frame.py checks its derivatives); the loads are
those of the potential T l(q), l = integral of |P'| (a chamber: T = -p A), so the end
caps and, once curved, the walls act on the rod.  For a rod of the quadratic
potential, |P'| = 1 + Gamma_1 + K_2 dz - K_3 dy without shear and torsion: the
stationary state has the uniform strains Gamma_1 = -T/EA and K = T e/EI, for any
load: in the linear range and up to the roll-up (a full circle at T e = 2 pi EI/L,
its centreline of length L (1 - T/EA) closing on the clamp)."""
import math
import subprocess

import pytest

from util import BUILD, ensure_dir, run_scene

SCENE = """[scene]
analysis = "static"
[material.m]
law = "resultant"
E = 1.0e9
nu = 0.3
rho = 1000.0
[section.flat]
shape = "rectangle"
b = 0.01
h = 0.002
[[beam]]
name = "arm"
element = "{elem}"
material = "m"
section = "flat"
start = [0.0, 0.0, 0.0]
end = [1.0, 0.0, 0.0]
up = [0.0, 0.0, 1.0]
elements = {n}
[[constraint]]
type = "clamp"
a = "arm:start"
[[load]]
name = "act"
beam = "arm"
offset = [0.0, {e!r}]
{load}
[static]
load_steps = {steps}
[[sensor]]
name = "tip"
at = "arm:end"
"""
E, B, H, L = 1.0e9, 0.01, 0.002, 1.0
EI, EA = E * B * H**3 / 12, E * B * H
AREA, EOFF = 2.0e-6, -0.0008            # the chamber below the centreline; the tendon above it
T_ROLL = 2 * math.pi * EI / (abs(EOFF) * L)          # |T| e = 2 pi EI / L


def load_text(kind, T):
    """The [[load]] lines of a chamber (T = -p A) or a tendon of tension T."""
    if kind == "chamber":
        return f'type = "chamber"\narea = {AREA!r}\npressure = {-T / AREA!r}'
    return f'type = "tendon"\ntension = {T!r}'


def scene(tmp, name, elem, kind, T, n=20, steps=1):
    e = EOFF if kind == "chamber" else -EOFF
    p = tmp / f"{name}.toml"
    p.write_text(SCENE.format(elem=elem, n=n, e=e, load=load_text(kind, T), steps=steps))
    return p


def tip_state(out):
    """(tip rotation about the bending axis summed over the load steps, last row)."""
    import csv
    with open(out / "sensors.csv", newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["sensor"] == "tip"]
    ang, prev = 0.0, 0.0
    for r in rows:
        a = math.atan2(float(r["d3z"]), float(r["d3x"]))
        d = a - prev
        ang += d - 2 * math.pi * round(d / (2 * math.pi))
        prev = a
    return ang, rows[-1]


def closed_form(kind, T, elem):
    """(kappa, tip x, tip z) of the uniform state: curvature T e / EI toward the
    tendon (away from the chamber), the centreline stretched by -T/EA (none for
    the inextensible kirchhoff)."""
    e = EOFF if kind == "chamber" else -EOFF
    kappa = T * e / EI                          # > 0: the tip turns toward +z
    stretch = 1.0 if elem == "kirchhoff" else 1.0 - T / EA
    s = stretch * L
    return kappa, s * math.sin(kappa * L) / kappa, s * (1 - math.cos(kappa * L)) / kappa


@pytest.mark.parametrize("kind", ["chamber", "tendon"])
def test_linear_range_constant_curvature_T_e_over_EI(kind):
    """|T| e = 1e-3 of the roll-up's, gef, 20 elements, one step: tip rotation
    kappa L and tip deflection (1 - cos kappa L)/kappa with kappa = T e / EI
    (chamber: p A e / EI) within 1 % (measured: rotation 1 + 5e-12)."""
    d = ensure_dir(BUILD / "rod_actuators")
    T = 1e-3 * T_ROLL * (-1 if kind == "chamber" else 1)
    out = d / f"linear_{kind}"
    s, _ = run_scene(scene(d, f"linear_{kind}", "gef", kind, T), out=out)
    kappa, _, z = closed_form(kind, T, "gef")
    ang, _ = tip_state(out)
    w = s["sensors"]["tip"]["displacement"][2]
    print(kind, "rotation", ang / (kappa * L), "deflection", w / z)
    assert abs(ang / (kappa * L) - 1) <= 0.01 and abs(w / z - 1) <= 0.01, (ang, w, kappa)


@pytest.mark.parametrize("elem,kind,n,tol", [("gef", "chamber", 20, 0.01), ("gef", "tendon", 20, 0.01),
                                             ("euler_bernoulli", "chamber", 20, 0.01),
                                             ("kirchhoff", "tendon", 20, 0.01), ("gef", "tendon", 40, 1e-3)])
def test_rollup_full_circle(elem, kind, n, tol):
    """|T| e = 2 pi EI / L (chamber: p A e), 20 load steps: the tip section turns by
    2 pi and the tip comes back to the clamp, and at every load step the tip is at the
    closed form's, within 1 % (of 2 pi, of L) with 20 elements; with 40 within 1e-3.
    Measured (turn / 2 pi, gap / L): gef chamber 0.99475, 0.53 %; gef tendon 1.00539,
    0.53 %; euler_bernoulli chamber 0.99475, 0.53 %; kirchhoff tendon 1.00541, 0.54 %;
    gef tendon, 40 elements, 1.00033, 0.033 %: the tendon's length, integrated at five
    points of the quadratic position interpolation, converges as 1/n^4 (the rod's
    energy, at its two Gauss points, holds the uniform state exactly)."""
    d = ensure_dir(BUILD / "rod_actuators")
    T = T_ROLL * (-1 if kind == "chamber" else 1)
    name = f"rollup_{elem}_{kind}_{n}"
    out = d / name
    run_scene(scene(d, name, elem, kind, T, n=n, steps=20), out=out)
    ang, last = tip_state(out)
    gap = math.hypot(float(last["x"]), float(last["z"]))
    import csv
    with open(out / "sensors.csv", newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["sensor"] == "tip"]
    worst = 0.0
    for r in rows:
        lam = float(r["time"])
        if lam <= 0:
            continue
        _, x, z = closed_form(kind, lam * T, elem)
        worst = max(worst, math.hypot(float(r["x"]) - x, float(r["z"]) - z) / L)
    print(elem, kind, n, "turn", ang / (2 * math.pi), "gap", gap / L, "worst", worst)
    assert abs(ang / (2 * math.pi) - 1) <= tol and gap <= tol * L and worst <= tol, (ang, gap, worst)


def test_rod_tendon_and_chamber_jacobians_against_central_differences():
    """bk_assemble_loads' Jacobian of a tendon and a chamber on part of a gef rod
    (4 elements, every DOF perturbed: a turned, deformed state) against central
    differences of the load vector (tests/loads_check.c)."""
    from test_loads_outputs import build_loads_check
    exe = build_loads_check()
    d = ensure_dir(BUILD / "rod_actuators")
    for kind, T in (("tendon", 3.0), ("chamber", -2.0)):
        p = scene(d, f"jac_{kind}", "gef", kind, T, n=4)
        p.write_text(p.read_text().replace('beam = "arm"\n', 'from = "arm:0.1"\nto = "arm:0.8"\n'))
        out = d / f"jac_{kind}"
        run_scene(p, out=out)
        r = subprocess.run([str(exe), str(out / "model.dat"), "1.0"], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        err, big = map(float, r.stdout.split())
        print(kind, err, big)
        assert big > 0 and err < 1e-6 * big, (kind, err, big)


@pytest.mark.parametrize("change,key,expected", [
    (("offset = [0.0, -0.0008]", "offset = [0.0, -0.0012]"), "load[0].offset", "lies outside the section"),
    (("offset = [0.0, -0.0008]", "offset = [0.004, 0.0]"), "load[0].offset", "a circle of diameter"),
    (("area = 2e-06", "area = 3.0e-5"), "load[0].area", "does not fit in the section"),
    (('element = "gef"', 'element = "ancf_cable"'), "load[0].beam", "and rods"),
])
def test_bad_rod_chambers_give_one_line(change, key, expected):
    from test_bad_input import check_error
    text = SCENE.format(elem="gef", n=4, e=EOFF, load=load_text("chamber", -10.0), steps=1)
    assert change[0] in text, change
    text = text.replace(*change)
    if "circle" in expected:
        text = text.replace('shape = "rectangle"\nb = 0.01\nh = 0.002', 'shape = "circle"\nradius = 0.003')
    if "ancf_cable" in change[1]:           # the cable takes equal bending stiffnesses only
        text = text.replace("b = 0.01\n", "b = 0.002\n")
    check_error(text, key, expected)
