"""Issue 16, outputs and loads: reactions (reactions.csv, summary.json) that
balance the applied loads, section forces (sections.csv) against equilibrium
of the free part (closed forms and hand calculation), amplitudes, distributed,
follower and tendon loads against closed forms, their Jacobians against central
differences of the load vector, and the bad-input messages."""
import csv
import math
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import pytest

from util import BUILD, ROOT, build_program, ensure_dir, run_cli, run_scene

E, B, H = 7.2e10, 0.01, 0.01
EI = E * B * H**3 / 12
MODELS = ROOT / "models"


def rows(out, name):
    with open(Path(out) / name, newline="") as fh:
        return list(csv.DictReader(fh))


def vec(r, *keys):
    return np.array([float(r[k]) for k in keys])


def run(scene, sets=(), text=None):
    out = Path(tempfile.mkdtemp(prefix="bk-lo-", dir=ensure_dir(BUILD / "runs")))
    if text is not None:
        p = out / "scene.toml"
        p.write_text(text)
        scene = p
    summary, _ = run_scene(scene, sets, out=out / "run")
    return summary, out / "run"


GEF_BEAM = """
[scene]
analysis = "static"
[material.alu]
law = "resultant"
E = 7.2e10
nu = 0.3
rho = 2700.0
[section.square]
shape = "rectangle"
b = 0.01
h = 0.01
[[beam]]
name = "arm"
element = "{element}"
material = "alu"
section = "square"
start = [0.0, 0.0, 0.0]
end = [1.0, 0.0, 0.0]
elements = 10
"""


@pytest.mark.parametrize("element", ["gef", "euler_bernoulli", "kirchhoff"])
def test_reactions_balance_the_loads_3d_rods(element):
    """Clamped rod, tip force and moment and a mid-span force, large 3-D
    deflection: the clamp's force and moment (about the clamp; from the
    quaternion DOFs' generalized forces) balance the loads at their deformed
    points."""
    text = GEF_BEAM.format(element=element) + """
[[constraint]]
type = "clamp"
a = "arm:start"
[[load]]
type = "force"
at = "arm:end"
value = [0.0, 30.0, -50.0]
[[load]]
type = "moment"
at = "arm:end"
value = [5.0, 0.0, 2.0]
[[load]]
type = "force"
at = "arm:0.5"
value = [10.0, 0.0, 20.0]
[static]
load_steps = 4
rtol = 1e-12
[[sensor]]
name = "tip"
at = "arm:end"
[[sensor]]
name = "mid"
at = "arm:0.5"
"""
    summary, out = run(None, text=text)
    tip = np.array(summary["sensors"]["tip"]["position"])
    mid = np.array(summary["sensors"]["mid"]["position"])
    assert np.linalg.norm(tip - [1, 0, 0]) > 0.2                 # large deflection
    (rc,) = summary["reactions"]
    F, M = np.array(rc["force"]), np.array(rc["moment"])
    Ft, Mt, Fm = np.array([0, 30, -50.0]), np.array([5, 0, 2.0]), np.array([10, 0, 20.0])
    assert np.abs(F + Ft + Fm).max() < 1e-8 * 60
    assert np.abs(M + np.cross(tip, Ft) + Mt + np.cross(mid, Fm)).max() < 1e-8 * 60
    last = rows(out, "reactions.csv")[-1]
    assert np.allclose(vec(last, "Fx", "Fy", "Fz"), F, rtol=0, atol=1e-12)


def test_reactions_with_multiplier_constraints_ancf_free_clamp():
    """ANCF cantilever, 100 N at the tip (seed Table 3, large deflection), with
    the `free` clamp (slope directions by linear constraints, reactions from
    their multipliers, -s G^T nu, mapped through the slopes' work-conjugate
    moment): force P, moment P times the tip's horizontal offset."""
    summary, _ = run("cantilever_bend_100N", ["constraint.0.cross_section=free", "static.rtol=1e-12"])
    (rc,) = summary["reactions"]
    x_tip = summary["sensors"]["tip"]["position"][0]
    z_tip = summary["sensors"]["tip"]["position"][2]
    assert np.abs(np.array(rc["force"]) - [0, 0, 100.0]).max() < 1e-7
    assert np.abs(np.array(rc["moment"]) - [0, -100.0 * x_tip, 0]).max() < 1e-7
    assert z_tip < -0.4


def test_simply_supported_beam_reactions_and_midspan_moment():
    """Statically determinate: pinned at one end, a roller (point_on_line, two
    linear constraints) at the other, P at mid-span: reactions P/2, section
    moment -P x / 2 about d1 (sagging) left of the load, -P L / 4 under it (hand
    calculation)."""
    P = 2.0
    # a revolute pin (it also holds the twist about the beam's own axis) and a roller
    text = GEF_BEAM.format(element="gef") + f"""
[[constraint]]
type = "revolute"
a = "arm:start"
axis = [0.0, 1.0, 0.0]
[[constraint]]
type = "point_on_line"
a = "arm:end"
axis = [1.0, 0.0, 0.0]
[[load]]
type = "force"
at = "arm:0.5"
value = [0.0, 0.0, {-P}]
"""
    summary, out = run(None, text=text)
    r0, r1 = summary["reactions"]
    assert np.abs(np.array(r0["force"]) - [0, 0, P / 2]).max() < 1e-9
    assert np.abs(np.array(r1["force"]) - [0, 0, P / 2]).max() < 1e-9
    assert np.abs(r0["moment"]).max() < 1e-9 and np.abs(r1["moment"]).max() < 1e-9
    for r in rows(out, "sections.csv"):
        if r["step"] != "1":
            continue
        s = float(r["s"])
        m_ref = -P / 2 * min(s, 1.0 - s)            # sagging: the moment vector along -d1
        assert abs(float(r["M2"]) - m_ref) < 1e-6 * P, (s, r["M2"], m_ref)
        assert abs(abs(float(r["Q3"])) - P / 2) < 1e-5 * P       # the section turned by 2e-3 rad


def test_cantilever_root_moment_small_and_large_deflection():
    """Root section moment of a tip-loaded ANCF cantilever: P L at 1 N (small
    deflection) and P times the tip's horizontal offset at 100 N (seed Table 3);
    along the beam M2(s) = P (x_tip - x(s)), the section's own point (the
    nodal rows), and the ParaView frames' point data of both kinds."""
    for P, scene in ((1.0, "cantilever_bend_10N"), (100.0, "cantilever_bend_100N")):
        sets = ["static.rtol=1e-12"] + (["load.0.value.2=-1.0"] if P == 1.0 else [])
        summary, out = run(scene, sets)
        x_tip = summary["sensors"]["tip"]["position"][0]
        sec = [r for r in rows(out, "sections.csv") if int(r["step"]) == summary["steps"]]
        root = [r for r in sec if r["element"] == "0" and r["source"] == "nodal" and r["point"] == "0"][0]
        if P == 1.0:
            assert abs(float(root["M2"]) - P * 1.0) < 2e-4 * P
        assert abs(float(root["M2"]) - P * x_tip) < 1e-8 * P
        stress = [r for r in sec if r["source"] == "stress"]
        sec = [r for r in sec if r["source"] == "nodal"]
        for r in sec:
            assert abs(float(r["M2"]) - P * (x_tip - float(r["x"]))) < 1e-7 * P
        # the ParaView frame carries them as point data, linear along each element
        from report import vtu
        frame = vtu.read(out / f"step_{summary['steps']:06d}.vtu")
        assert abs(frame["section_moment"][0][1] - float(root["M2"])) < 1e-12 * P
        assert abs(frame["section_force"][-1][0] - float(sec[-1]["N"])) < 1e-12 * P
        # and the elements' own (integrated-stress) resultants, constant beyond the outer sample points
        assert abs(frame["section_moment_stress"][0][1] - float(stress[0]["M2"])) < 1e-12 * P
        assert abs(frame["section_force_stress"][-1][2] - float(stress[-1]["Q3"])) < 1e-12 * P


def stress_rows(out, step):
    """The rows of the elements' own stress resultants (not the nodal-force rows)."""
    return [r for r in rows(out, "sections.csv") if r["step"] == str(step) and r["source"] != "nodal"]


def comps(r, *keys):
    return np.array([float(r[k]) for k in keys])


ROD_SOURCES = {"gef": "law", "euler_bernoulli": "law;multiplier:Q2 Q3", "kirchhoff": "law;multiplier:N Q2 Q3"}


@pytest.mark.parametrize("element", ["gef", "euler_bernoulli", "kirchhoff"])
def test_rod_stress_resultants_cantilever_small_and_large_deflection(element):
    """Rods, tip force P down: the law's moment at the Gauss points against
    the statics of the free part, M2(s) = P (L - s) at 1 N (beam theory) and
    P (x_tip - x(s)) at 180 N (P L^2 / EI = 3: the tip moves 0.25 L back and
    0.6 L down; the lever arm from the rows' own positions), |n| = P (the shear
    from G A Gamma, or the multipliers of Gamma_2 = Gamma_3 = 0), and the tip
    and the moment at the first Gauss point against the inextensible elastica
    (references/elastica.py).  At 1 N the difference to beam theory is the
    deflection itself (u_x = 1.85e-5 L)."""
    from references.elastica import tip_load_cantilever
    for P, tol_m in ((1.0, 3e-5), (180.0, 1e-9)):
        text = GEF_BEAM.format(element=element) + f"""
[[constraint]]
type = "clamp"
a = "arm:start"
[[load]]
type = "force"
at = "arm:end"
value = [0.0, 0.0, {-P}]
[static]
rtol = 1e-12
load_steps = {1 if P == 1.0 else 6}
[[sensor]]
name = "tip"
at = "arm:end"
"""
        summary, out = run(None, text=text)
        tip = np.array(summary["sensors"]["tip"]["position"])
        sec = stress_rows(out, summary["steps"])
        assert len(sec) == 20 and {r["source"] for r in sec} == {ROD_SOURCES[element]}
        for r in sec:
            s, x = float(r["s"]), float(r["x"])
            m_ref = P * (1.0 - s) if P == 1.0 else P * (tip[0] - x)
            assert abs(float(r["M2"]) - m_ref) < tol_m * P, (P, s, r["M2"], m_ref)
            assert abs(np.linalg.norm(comps(r, "N", "Q2", "Q3")) - P) < 1e-9 * P, (P, s)
            assert abs(float(r["T"])) < 1e-9 * P and abs(float(r["M3"])) < 1e-9 * P
        if P == 1.0:
            assert all(abs(float(r["Q3"]) + P) < 1e-4 * P for r in sec)
        else:
            u, w = tip_load_cantilever(1.0, P, EI)
            assert abs(tip[0] - (1 + u)) < 2e-4 and abs(tip[2] + w) < 2e-4, (tip, u, w)
            root = min(sec, key=lambda r: float(r["s"]))
            # the elastica's lever arm at the first Gauss point's own position
            assert abs(float(root["M2"]) - P * (1 + u - float(root["x"]))) < 3e-4 * P


@pytest.mark.parametrize("element", ["gef", "kirchhoff"])
def test_rod_stress_resultants_axial_force_and_torsion(element):
    """Tip force F along the axis and tip torque T0 about it: N = F (E A
    Gamma_1 of the law, or the multiplier of the inextensible Kirchhoff beam)
    and T = T0 (G J K_1) at every Gauss point, no bending."""
    F, T0 = 1000.0, 5.0
    text = GEF_BEAM.format(element=element) + f"""
[[constraint]]
type = "clamp"
a = "arm:start"
[[load]]
type = "force"
at = "arm:end"
value = [{F}, 0.0, 0.0]
[[load]]
type = "moment"
at = "arm:end"
value = [{T0}, 0.0, 0.0]
[static]
rtol = 1e-12
"""
    summary, out = run(None, text=text)
    sec = stress_rows(out, summary["steps"])
    assert len(sec) == 20
    for r in sec:
        assert abs(float(r["N"]) - F) < 1e-9 * F and abs(float(r["T"]) - T0) < 1e-9 * T0, r
        assert np.abs(comps(r, "Q2", "Q3")).max() < 1e-9 * F and np.abs(comps(r, "M2", "M3")).max() < 1e-9 * T0


def test_l_frame_stress_resultants_by_hand():
    """The welded L-frame (models/l_frame_weld.toml: leg a 1 m along x, leg b
    0.5 m along y, 1 N down at b's end): on leg a bending P (1 - x) and torsion
    P a (a = 0.5 m), on leg b bending P (a - s) and no torsion, shear P
    (hand calculation on the reference geometry; the tip deflection, 4.3 mm,
    changes them by 4e-5), and |m| = |(r_tip - r) x P| (statics of the
    current state) to round-off."""
    P, a = 1.0, 0.5
    summary, out = run("l_frame_weld", ["static.rtol=1e-12"])
    tip = np.array(summary["sensors"]["tip"]["position"])
    sec = stress_rows(out, summary["steps"])
    assert len(sec) == 2 * (10 + 6)
    for r in sec:
        s, x = float(r["s"]), comps(r, "x", "y", "z")
        T, Mb = float(r["T"]), np.linalg.norm(comps(r, "M2", "M3"))
        if r["beam"] == "a":
            assert abs(abs(T) - P * a) < 2e-4 * P * a and abs(Mb - P * (1 - s)) < 2e-4 * P, (s, T, Mb)
        else:
            assert abs(T) < 2e-4 * P * a and abs(Mb - P * (a - s)) < 2e-4 * P, (s, T, Mb)
        assert abs(np.linalg.norm(comps(r, "N", "Q2", "Q3")) - P) < 1e-9 * P
        m_ref = np.cross(tip - x, [0, 0, -P])
        assert abs(np.linalg.norm(comps(r, "T", "M2", "M3")) - np.linalg.norm(m_ref)) < 1e-9 * P, (r["beam"], s)


@pytest.mark.parametrize("P", [1.0, 100.0])
def test_continuum_integrated_stress_cantilever_and_balance(P):
    """ANCF 3243 cantilever (the seed's Table 3 beam, 40 elements; 1 N small,
    100 N large deflection) with a second force F = P/2 at x = 0.45 m: the
    first Piola-Kirchhoff traction integrated over the reference section at
    the axial Gauss stations against the statics of the free part (lever arms
    from the rows' and the sensors' own positions), and the force and moment
    balance between two stations on either side of F against the applied
    loads.  The 3243's section slopes are linear along the element, so its
    bending strain and the integrated moment are constant within an element:
    beam theory is met at the middle station (xi = 1/2), where the shear force
    is also accurate (at the outer stations it oscillates by about 3 % of P at
    100 N: the element's own transverse shear stress).  Middle stations at
    least 0.05 m (5 section heights, two elements) from the clamp and from F
    (Saint-Venant zones of the 3-D stress)."""
    F, xF = 0.5 * P, 0.45
    text = (MODELS / "cantilever_bend_100N.toml").read_text().replace(
        "value = [0.0, 0.0, -100.0]", f"value = [0.0, 0.0, {-P}]").replace("elements = 10", "elements = 40")
    text += f"""
[[load]]
type = "force"
at = "arm:{xF}"
value = [0.0, 0.0, {-F}]
[[sensor]]
name = "mid"
at = "arm:{xF}"
"""
    summary, out = run(None, sets=["static.rtol=1e-12"], text=text)
    tip = np.array(summary["sensors"]["tip"]["position"])
    xm = np.array(summary["sensors"]["mid"]["position"])
    sec = stress_rows(out, summary["steps"])
    assert len(sec) == 120 and {r["source"] for r in sec} == {"stress"}
    if P == 100.0:
        assert tip[2] < -0.4
    worst = {"M": 0.0, "n": 0.0}
    for r in sec:
        s, x = float(r["s"]), float(r["x"])
        assert abs(float(r["Q2"])) < 1e-9 * P and abs(float(r["T"])) < 1e-9 * P and abs(float(r["M3"])) < 1e-9 * P
        if s < 0.05 or abs(s - xF) < 0.05 or r["point"] != "1":
            continue
        Pn = P + (F if s < xF else 0.0)
        m_ref = P * (tip[0] - x) + (F * (xm[0] - x) if s < xF else 0.0)
        worst["M"] = max(worst["M"], abs(float(r["M2"]) - m_ref) / (P + F))
        worst["n"] = max(worst["n"], abs(np.linalg.norm(comps(r, "N", "Q3")) - Pn) / Pn)
    print(P, worst)
    assert worst["M"] < (1e-6 if P == 1.0 else 1e-3) and worst["n"] < 5e-3, worst
    # balance between the middle stations of elements 14 and 21 (x = 0.3625, 0.5375 m), F between them:
    # n_a = n_b + F (vertical forces), M_a = M_b + P (x_b - x_a) + F (x_F - x_a)
    a = next(r for r in sec if r["element"] == "14" and r["point"] == "1")
    b = next(r for r in sec if r["element"] == "21" and r["point"] == "1")
    na, nb = np.linalg.norm(comps(a, "N", "Q3")), np.linalg.norm(comps(b, "N", "Q3"))
    bal = float(a["M2"]) - float(b["M2"]) - P * (float(b["x"]) - float(a["x"])) - F * (xm[0] - float(a["x"]))
    print(P, na - nb - F, bal)
    assert abs(na - nb - F) < 2e-3 * P and abs(bal) < 2e-4 * (P + F), (na, nb, F, bal)

CONTINUUM_CASES = [("ancf3243", "sri", "svk", 0.3, 7e-3), ("ancf3273", "sri", "neo_hookean", 0.3, 2e-3),
                   ("ancf3333", "full", "svk", 0.0, 1e-4), ("ancf3363", "reduced", "neo_hookean", 0.3, 1e-4)]


@pytest.mark.parametrize("element,integration,law,nu,tol_t", CONTINUUM_CASES)
def test_continuum_section_resultants_per_element(element, integration, law, nu, tol_t):
    """Integrated first Piola-Kirchhoff traction of each continuum element
    (10 elements, the seed's beam): under a tip force of 1 mN (linear regime)
    the Gauss-weighted mean of M2 over an element's three stations against
    beam theory P (L - s) at its middle; for the elements without an axial
    slope unknown (3333, 3363) the Gauss-weighted mean of the shear force
    equals the element's end force (the virtual work of the mode dr = X e_z,
    an identity of the element, to the equilibrium residual), while the stations themselves
    carry the element's oscillating transverse shear stress; under a tip
    torque of 10 N m, T = 10 N m at the stations of the interior elements to
    tol_t (the 3243 and 3273 carry part of the torque in their generalized
    slope forces: 0.6 % and 0.2 %)."""
    w = (5 / 18, 8 / 18, 5 / 18)
    base = (MODELS / "cantilever_bend_100N.toml").read_text().replace(
        'element = "ancf3243"', f'element = "{element}"\nintegration = "{integration}"').replace(
        'law = "svk"', f'law = "{law}"').replace("nu = 0.0", f"nu = {nu}")
    P = 1e-3
    summary, out = run(None, sets=["static.rtol=1e-12", "static.load_steps=1"],
                       text=base.replace("value = [0.0, 0.0, -100.0]", f"value = [0.0, 0.0, {-P}]"))
    sec = [r for r in rows(out, "sections.csv") if r["step"] == str(summary["steps"])]
    worst_m, worst_q = 0.0, 0.0
    for e in range(10):
        st = [r for r in sec if r["element"] == str(e) and r["source"] != "nodal"]
        end = [r for r in sec if r["element"] == str(e) and r["source"] == "nodal"][1]
        assert len(st) == 3 and abs(float(st[1]["xi"]) - 0.5) < 1e-15
        for r in st:
            assert max(abs(float(r[k])) for k in ("Q2", "T", "M3")) < 1e-7 * P
        if 1 <= e <= 8:
            m = sum(wk * float(r["M2"]) for wk, r in zip(w, st))
            worst_m = max(worst_m, abs(m - P * (1.0 - float(st[1]["s"]))) / P)
        if element in ("ancf3333", "ancf3363"):
            q = sum(wk * float(r["Q3"]) for wk, r in zip(w, st))
            worst_q = max(worst_q, abs(q - float(end["Q3"])) / P)
    print(element, worst_m, worst_q)
    # the nodal end forces themselves carry the equilibrium residual, about 5e-8 P at this load
    assert worst_m < 2e-5 and worst_q < 2e-7, (worst_m, worst_q)
    T0 = 10.0
    summary, out = run(None, sets=["static.rtol=1e-12"], text=base.replace(
        "value = [0.0, 0.0, -100.0]", "value = [0.0, 0.0, 0.0]") + f"""
[[load]]
type = "moment"
at = "arm:end"
value = [{T0}, 0.0, 0.0]
""")
    sec = stress_rows(out, summary["steps"])
    err = max(abs(float(r["T"]) - T0) / T0 for r in sec if 1 <= int(r["element"]) <= 8)
    print(element, "torsion", err)
    assert err < tol_t, err


def test_curved_frame_bending_and_torsion_by_hand():
    """Quarter-circle gef cantilever (R = 1 m, in the x-y plane) with an
    out-of-plane tip force P: at the section at angle phi, M = P R sin(a - phi)
    about the radial direction and T = P R (1 - cos(a - phi)) (a = 90 deg)."""
    P, R = 0.5, 1.0
    text = GEF_BEAM.format(element="gef").replace('end = [1.0, 0.0, 0.0]', """arc_center = [0.0, 1.0, 0.0]
arc_axis = [0.0, 0.0, 1.0]
arc_angle = 90.0""").replace("elements = 10", "elements = 12") + f"""
[[constraint]]
type = "clamp"
a = "arm:start"
[[load]]
type = "force"
at = "arm:end"
value = [0.0, 0.0, {-P}]
"""
    summary, out = run(None, text=text)
    n, kinds = 0, {}
    for r in rows(out, "sections.csv"):
        if r["step"] != "1":
            continue
        phi = float(r["s"]) / R
        a = math.pi / 2 - phi
        # section frame: e3 the tangent, e2 = up = z, e1 = e2 x e3 points outward
        # hand calculation on the reference geometry: the deflection (1e-3 R) moves the arms
        assert abs(abs(float(r["M2"])) - P * R * math.sin(a)) < 2e-4 * P * R, (phi, r["M2"])
        assert abs(abs(float(r["T"])) - P * R * (1 - math.cos(a))) < 2e-4 * P * R, (phi, r["T"])
        assert abs(abs(float(r["Q3"])) - P) < 1e-4 * P
        n += 1
        kinds[r["source"]] = kinds.get(r["source"], 0) + 1
    # the element ends (nodal forces) and the law's n = C Gamma, m = D K at the two Gauss points
    assert n == 48 and kinds == {"nodal": 24, "law": 24}, kinds


def test_distributed_load_cantilever():
    """0.5 N/m over the whole gef cantilever and 1 N/m over its outer half:
    tip deflection q L^4 / 8 EI + q (3 L^4 - 4 a^3 L + a^4) / 24 EI (Euler-Bernoulli;
    shear adds 1e-4), reactions and the section moments from statics."""
    summary, out = run("cantilever_distributed", ["static.rtol=1e-12"])
    w = 0.5 / (8 * EI) + 1.0 * (3 - 4 * 0.125 + 0.0625) / (24 * EI)
    uz = summary["sensors"]["tip"]["displacement"][2]
    assert abs(-uz / w - 1) < 3e-4, (uz, w)
    (rc,) = summary["reactions"]
    assert abs(rc["force"][2] - 1.0) < 1e-9
    assert abs(rc["moment"][1] + (0.25 + 0.375)) < 1e-5
    for r in rows(out, "sections.csv"):
        if r["step"] != "1":
            continue
        s = float(r["s"])
        m_ref = 0.5 * (1 - s) ** 2 / 2 + (1.0 * (1 - s) ** 2 / 2 if s >= 0.5 else 0.5 * (0.75 - s))
        assert abs(float(r["M2"]) - m_ref) < 1e-5, (s, r["M2"], m_ref)


def test_follower_force_and_moment_turn_with_the_tip_section():
    """gef cantilever, follower tip force 100 N along -d2 and torque 10 N m
    about d3 of the tip section: the clamp's force is +100 d2(tip) and its
    moment balances 10 d3(tip) + r_tip x F, with d2, d3 from sensors.csv."""
    summary, out = run("cantilever_follower", ["static.rtol=1e-12"])
    tip = [r for r in rows(out, "sensors.csv") if r["sensor"] == "tip"][-1]
    d2, d3 = vec(tip, "d2x", "d2y", "d2z"), vec(tip, "d3x", "d3y", "d3z")
    x = vec(tip, "x", "y", "z")
    (rc,) = summary["reactions"]
    F, M = np.array(rc["force"]), np.array(rc["moment"])
    assert abs(d2[2]) < 0.9                                 # the tip section has turned
    assert np.abs(F - 100 * d2).max() < 1e-7
    assert np.abs(M + 10 * d3 + np.cross(x, -100 * d2)).max() < 1e-7


def test_follower_pressure_on_a_ring_is_pure_hoop_compression():
    """Closed ring, uniform follower pressure p: N = -p R in every section,
    no bending, no net reaction (clamp + closing joint)."""
    p, R = 1000.0, 0.5
    summary, out = run("ring_pressure", ["static.rtol=1e-12"])
    for r in rows(out, "sections.csv"):
        if r["step"] == "2":
            # element ends: equilibrium of the nodal forces; Gauss points: EA Gamma_1 of the law
            assert abs(float(r["N"]) / (-p * R) - 1) < (2e-5 if r["source"] == "nodal" else 5e-5), r
            assert abs(float(r["M2"])) < 1e-4 * p * R * R and abs(float(r["M3"])) < 1e-4 * p * R * R
    tot = sum(np.array(rc["force"]) for rc in summary["reactions"])
    assert np.abs(tot).max() < 1e-8 * p * R


def test_load_jacobians_against_central_differences():
    """dQ/dq of follower forces, moments, distributed follower loads and
    tendons (runtime/assembly/loads.c) against central differences of Q itself; the
    follower tip loads also on a continuum element (its section frame is the
    Gram-Schmidt frame of its slopes); the tendon also on ancf3363 (its line
    rides on the affine part of sections that can deform)."""
    exe = build_loads_check()
    ancf = ["beam.arm.element=ancf3243", "material.alu.law=svk"]
    for scene, x, el, more in (("cantilever_follower", 0.7, "arm", []), ("ring_pressure", 1.0, "ring", []),
                               ("tendon_ancf", 1.0, "arm", []), ("cantilever_follower", 0.7, "arm", ancf),
                               ("tendon_finger", 1.0, "f", [])):
        _, out = run(scene, [f"beam.{el}.elements=4"] + more)
        r = subprocess.run([str(exe), str(out / "model.dat"), str(x)], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        err, big = map(float, r.stdout.split())
        assert big > 0 and err < 1e-6 * big, (scene, err, big)


def build_loads_check():
    from gen.solver_build import VARIANTS, build_solver, compile_object, runtime_headers, runtime_objects
    from util import all_pair_symbols
    pairs, index = all_pair_symbols()
    pairs = [p for p in pairs if p.startswith(("gef_resultant", "ancf3243_svk", "ancf3363_neo_hookean"))]
    obj = BUILD / "sanitize" / "loads_check.o"
    compile_object(ROOT / "tests" / "loads_check.c", obj, VARIANTS["sanitize"], runtime_headers())
    objs = [o for o in runtime_objects("sanitize") if o.name != "main.o"] + [obj]
    return build_solver(pairs, BUILD / "sanitize" / "loads_check", index, "sanitize", main_objs=objs)


def tip_angle(out):
    r = [r for r in rows(out, "sensors.csv") if r["sensor"] == "tip"][-1]
    return math.atan2(float(r["d3z"]), float(r["d3x"]))


def test_tendon_bends_at_constant_curvature_T_d_over_EI():
    """ANCF beam, tendon at d = 4 mm above the centreline from the clamp to the
    tip pulled with T: curvature T d / E I (small strain), here from the tip
    slope; no net reaction (the tendon's loads are internal)."""
    summary, out = run("tendon_ancf", ["static.rtol=1e-12"])
    k_ref = 150.0 * 0.004 / EI
    assert abs(tip_angle(out) / k_ref - 1) < 2e-4
    assert np.abs(summary["reactions"][0]["force"]).max() < 1e-6
    summary, out = run("tendon_ancf", ["load.0.tension=15000", "beam.arm.elements=40", "static.load_steps=4"])
    assert abs(tip_angle(out) / (15000 * 0.004 / EI) - 1) < 1e-2        # kappa L = 1 rad


def test_amplitudes_static_table_and_prescribed_rotation_ramp():
    """Tip force times a load-factor table (0, 1 at 0.5, 0.25 at 1), the clamp
    turned by 0.5 rad times a ramp from 0.5 to 1: tip at
    R(theta) (L, 0, -a P L^3 / 3 EI) at each load factor (gef, shear 3e-4)."""
    for variant in ("inline", "csv"):
        if variant == "inline":
            _, out = run("cantilever_amplitudes")
        else:
            d = Path(tempfile.mkdtemp(prefix="bk-amp-", dir=ensure_dir(BUILD / "runs")))
            (d / "amp.csv").write_text("x,a\n0,0\n0.5,1\n1,0.25\n")
            text = (MODELS / "cantilever_amplitudes.toml").read_text().replace(
                "points = [[0.0, 0.0], [0.5, 1.0], [1.0, 0.25]]", 'file = "amp.csv"')
            (d / "s.toml").write_text(text)
            run_scene(d / "s.toml", out=d / "run")
            out = d / "run"
        w = 1.0 / (3 * EI)
        for r in rows(out, "sensors.csv"):
            lam = float(r["time"])
            a = np.interp(lam, [0, 0.5, 1], [0, 1, 0.25])
            th = 0.5 * min(max((lam - 0.5) / 0.5, 0), 1)
            x = vec(r, "x", "y", "z")
            assert abs(x[0] - math.cos(th)) < 1e-4 and abs(x[1] - math.sin(th)) < 1e-4, (lam, x)
            assert abs(x[2] + a * w) < 1e-3 * w + 1e-12, (lam, x[2], a * w)


def test_amplitude_sine_in_dynamics_quasi_static():
    """Tip force 1 N (1 - cos 2 pi t)/2 on a gef cantilever: against the
    first-mode response (f1 = 8.34 Hz from Euler-Bernoulli) of that forcing,
    u = w (1/2 - cos(W t)/(2(1 - r^2)) + r^2 cos(w1 t)/(2(1 - r^2)))."""
    _, out = run("cantilever_sine_load")
    A, rho = B * H, 2700.0
    w = 1.0 / (3 * EI)
    om = 1.8751040687**2 * math.sqrt(EI / (rho * A))
    Om = 2 * math.pi
    r2 = (Om / om) ** 2
    worst = 0.0
    for r in rows(out, "sensors.csv"):
        t = float(r["time"])
        a = 0.5 - 0.5 * math.cos(Om * t) / (1 - r2) + 0.5 * r2 / (1 - r2) * math.cos(om * t)
        worst = max(worst, abs(float(r["uz"]) + a * w))
    assert worst < 6e-3 * w


def test_dynamic_reactions_include_inertia_rigid_pendulum():
    """Stiff gef pendulum released horizontally: the pin force against the
    rigid rod's m a_cm - m g from the current angle (omega^2 = 3 g sin(th)/L,
    alpha = 3 g cos(th)/2L), after the release transient (t > 0.1 s)."""
    _, out = run("pendulum_stiff_gef", ["dynamic.t_end=1.0", "dynamic.rho_inf=0.0", "material.rod.E=7e13"])
    g, L, m = 9.81, 1.0, 2700 * 1e-4
    S, R = rows(out, "sensors.csv"), rows(out, "reactions.csv")
    assert len(S) == len(R) > 50
    worst = 0.0
    for s, r in zip(S, R):
        if float(s["time"]) <= 0.1:
            continue
        th = math.atan2(-float(s["z"]), float(s["x"]))
        w2, al = 3 * g * math.sin(th) / L, 3 * g * math.cos(th) / (2 * L)
        er, et = np.array([math.cos(th), 0, -math.sin(th)]), np.array([-math.sin(th), 0, -math.cos(th)])
        F = m * (L / 2) * (al * et - w2 * er) + np.array([0, 0, m * g])
        worst = max(worst, np.abs(F - vec(r, "Fx", "Fy", "Fz")).max())
    assert worst < 0.02 * m * g


BAD_BASE = (MODELS / "cantilever_amplitudes.toml").read_text()


def check_error(text, key, expected, files=()):
    d = Path(tempfile.mkdtemp(prefix="bk-bad-", dir=ensure_dir(BUILD / "bad")))
    for name, body in files:
        (d / name).write_text(body)
    p = d / "bad.toml"
    p.write_text(text)
    r = run_cli(["run", str(p), "--out", str(d / "out")])
    assert r.returncode == 1, r.stderr
    lines = [ln for ln in r.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith(f"error: {p}: {key}:"), r.stderr
    assert expected in lines[0], lines[0]


def test_bad_amplitudes_tendons_and_followers():
    check_error(BAD_BASE.replace('type = "table"', 'type = "smooth_step"'), "amplitude.up_down.type",
                "expected one of")
    check_error(BAD_BASE.replace("[0.5, 1.0], [1.0, 0.25]", "[0.5, 1.0], [0.4, 0.25]"),
                "amplitude.up_down.points", "out of time order")
    check_error(BAD_BASE.replace("points = [[0.0, 0.0], [0.5, 1.0], [1.0, 0.25]]", 'file = "a.csv"'),
                "amplitude.up_down.file", "out of time order", files=[("a.csv", "0,0\n0.5,1\n0.5,2\n")])
    check_error(BAD_BASE.replace('amplitude = "up_down"', 'amplitude = "nope"'), "load[0].amplitude",
                "no [amplitude.nope] table")
    tendon = (MODELS / "tendon_ancf.toml").read_text()
    check_error(tendon.replace("offset = [0.0, 0.004]", "offset = [0.0, 0.006]"), "load[0].offset",
                "outside the section")
    check_error(tendon.replace('element = "ancf3243"', 'element = "ancf_cable"')
                .replace('law = "svk"', 'law = "resultant"').replace('integration = "sri"\n', ""),
                "load[0].beam", "and rods (gef, euler_bernoulli, kirchhoff)")
    cable = (MODELS / "cantilever_follower.toml").read_text().replace('element = "gef"', 'element = "ancf_cable"')
    check_error(cable, "load[0].follower", "no section frame")
    dist = (MODELS / "cantilever_distributed.toml").read_text()
    check_error(dist.replace('from = "arm:0.5"\nto = "arm:end"', 'from = "arm:0.5"\nto = "arm:0.2"'), "load[1].to",
                "beyond `from`")


def test_follower_pressure_ramped_in_dynamics():
    """The ring of ring_pressure.toml in dynamics, the pressure ramped in over
    20 ms (the breathing mode has a 0.6 ms period: quasi-static): hoop force
    -p R at 30 ms, inertia and all (dynamic reactions and section forces)."""
    text = (MODELS / "ring_pressure.toml").read_text()
    text = text.replace('analysis = "static"', 'analysis = "dynamic"').replace(
        "[static]\nload_steps = 2\n", "[dynamic]\nt_end = 0.03\ndt = 1e-3\nrho_inf = 0.5\n").replace(
        "follower = true", 'follower = true\namplitude = {type = "ramp", t0 = 0.0, t1 = 0.02}')
    _, out = run(None, text=text)
    last = [r for r in rows(out, "sections.csv") if r["step"] == "30"]
    assert len([r for r in last if r["source"] == "nodal"]) == 32 and len(last) == 64
    for r in last:
        assert abs(float(r["N"]) / -500.0 - 1) < 1e-3, r
    mid = [r for r in rows(out, "sections.csv") if r["step"] == "10"]
    for r in mid:                                            # half the pressure at 10 ms
        assert abs(float(r["N"]) / -250.0 - 1) < 1e-2, r


def test_modal_about_static_state_under_distributed_load():
    """Loads enter a modal analysis only through its static state: the state
    under the distributed loads of cantilever_distributed, with its reactions
    (1 N, 0.625 N m), and the first frequency of the clamped beam (Euler-
    Bernoulli 8.34 Hz; the tiny load does not shift it)."""
    summary, out = run("cantilever_distributed", ["scene.analysis=modal", "modal.about=static", "modal.modes=2"])
    (rc,) = summary["reactions"]
    assert abs(rc["force"][2] - 1.0) < 1e-9 and abs(rc["moment"][1] + 0.625) < 1e-5
    f1 = 1.8751040687**2 / (2 * math.pi) * math.sqrt(EI / (2700.0 * B * H))
    assert abs(summary["frequencies_hz"][0] / f1 - 1) < 2e-3


def test_cable_reactions_through_the_slope_and_axial_section_force():
    """ancf_cable cantilever (positions and slopes r_x only), tip force: the
    clamp's moment is the work-conjugate moment of the slope forces, P times
    the tip's horizontal offset; its sections report N (and T = 0) only."""
    P = 20.0
    text = GEF_BEAM.format(element="ancf_cable") + f"""
[[constraint]]
type = "clamp"
a = "arm:start"
[[load]]
type = "force"
at = "arm:end"
value = [0.0, 0.0, {-P}]
[static]
rtol = 1e-12
load_steps = 2
[[sensor]]
name = "tip"
at = "arm:end"
"""
    summary, out = run(None, text=text)
    x_tip = summary["sensors"]["tip"]["position"][0]
    (rc,) = summary["reactions"]
    assert x_tip < 0.995                                     # 1.1 cm of deflection
    assert np.abs(np.array(rc["force"]) - [0, 0, P]).max() < 1e-8 * P
    assert np.abs(np.array(rc["moment"]) - [0, -P * x_tip, 0]).max() < 1e-8 * P
    for r in rows(out, "sections.csv"):
        if r["step"] == "2":
            assert math.isnan(float(r["M2"])) and abs(float(r["T"])) < 1e-9 * P
    tip = [r for r in rows(out, "sections.csv") if r["step"] == "2" and r["source"] == "nodal"][-1]
    d3 = vec([r for r in rows(out, "sensors.csv") if r["step"] == "2"][-1], "d3x", "d3y", "d3z")
    assert abs(float(tip["N"]) - np.dot([0, 0, -P], d3 / np.linalg.norm(d3))) < 1e-8 * P



def test_cable_law_axial_force_and_clamp_boundary_layer():
    """ancf_cable bar, 4 elements, axial tip force F: at the Gauss points N =
    n.t with n = W_a - d/dx W_b of the cable's energy (gen/cable.py) tends to
    F away from the clamp, T = 0 (no torsion), no
    section axes (Q2, Q3, M2, M3 NaN).  The clamp also fixes |r_x| = 1, so the
    axial strain and the law's N vanish at the root and recover along the
    beam, 2 % off in the third element, 0.4 % in the last (the element's own
    strain field; the nodal rows give N = F everywhere)."""
    F = 1000.0
    text = GEF_BEAM.format(element="ancf_cable").replace("elements = 10", "elements = 4") + f"""
[[constraint]]
type = "clamp"
a = "arm:start"
[[load]]
type = "force"
at = "arm:end"
value = [{F}, 0.0, 0.0]
[static]
rtol = 1e-12
"""
    summary, out = run(None, text=text)
    sec = [r for r in rows(out, "sections.csv") if r["step"] == str(summary["steps"])]
    law = [r for r in sec if r["source"] == "law+dM/ds"]
    assert len(law) == 16 and len(sec) == 24
    for r in sec:
        assert all(math.isnan(float(r[k])) for k in ("Q2", "Q3", "M2", "M3")) and abs(float(r["T"])) < 1e-9 * F
        if r["source"] == "nodal":
            assert abs(float(r["N"]) - F) < 1e-9 * F
    err = [max(abs(float(r["N"]) - F) / F for r in law if r["element"] == str(e)) for e in range(4)]
    assert err[2] < 3e-2 and err[3] < 5e-3, err          # decaying by about 6 per element
    root = [float(r["N"]) for r in law if r["element"] == "0"]
    assert root[0] < 0.5 * F                                 # the boundary layer of the clamped |r_x|

def test_gravity_with_amplitudes_static_step_and_dynamic_ramp():
    """Self-weight q = rho A g of a gef cantilever: with a step at load factor
    0.5 the tip is at rest before and at q L^4 / 8 EI from it (statics); ramped
    in over 1 s (first period 0.12 s) the dynamic tip and clamp force are within
    2 % of the static values at 1.5 s."""
    q = 2700.0 * B * H * 9.81
    w = q / (8 * EI)
    text = GEF_BEAM.format(element="gef") + """
[[constraint]]
type = "clamp"
a = "arm:start"
[[load]]
type = "gravity"
value = [0.0, 0.0, -9.81]
amplitude = {type = "step", t0 = 0.5}
[static]
load_steps = 4
step_control = "fixed"
[[sensor]]
name = "tip"
at = "arm:end"
"""
    _, out = run(None, text=text)
    for r in rows(out, "sensors.csv"):
        uz = float(r["uz"])
        assert (uz == 0.0) if float(r["time"]) < 0.5 else abs(-uz / w - 1) < 1e-3, r
    text = text.replace('{type = "step", t0 = 0.5}', '{type = "ramp", t0 = 0.0, t1 = 1.0}').replace(
        'analysis = "static"', 'analysis = "dynamic"').replace(
        '[static]\nload_steps = 4\nstep_control = "fixed"', "[dynamic]\nt_end = 1.5\ndt = 5e-3\nrho_inf = 0.6")
    summary, out = run(None, text=text)
    assert abs(-summary["sensors"]["tip"]["displacement"][2] / w - 1) < 0.02
    assert abs(summary["reactions"][0]["force"][2] / q - 1) < 0.02


ENERGY_GEF = """[scene]
analysis = "dynamic"
[material.alu]
law = "resultant"
E = 7.2e10
nu = 0.3
rho = 2700.0
[section.square]
shape = "rectangle"
b = 0.01
h = 0.01
[[beam]]
name = "arm"
element = "gef"
material = "alu"
section = "square"
start = [0.0, 0.0, 0.0]
end = [1.0, 0.0, 0.0]
up = [0.0, 0.0, 1.0]
elements = 8
[[constraint]]
type = "clamp"
a = "arm:start"
[[load]]
type = "force"
at = "arm:end"
value = [0.0, 0.0, -20.0]
amplitude = {type = "step", t0 = 0.0}
[[load]]
type = "distributed"
beam = "arm"
value = [0.0, -10.0, 0.0]
[dynamic]
t_end = 0.15
dt = 1e-3
rho_inf = 1.0
"""


def _energy_rows(text, name):
    d = Path(tempfile.mkdtemp(prefix="bk-energy-", dir=ensure_dir(BUILD / "runs")))
    (d / f"{name}.toml").write_text(text)
    run_scene(d / f"{name}.toml", out=d / "out")
    with open(d / "out" / "energy.csv", newline="") as fh:
        return list(csv.DictReader(fh))


def test_energy_counts_the_potential_of_amplitude_loads_distributed_loads_and_tendons():
    """Released from rest under loads switched on at t = 0 (a step amplitude)
    and then constant, with no dissipation (rho_inf = 1), kinetic + strain +
    load potential stays at its start value 0: the potential of a dead load
    with an amplitude (-a f . u), of a distributed dead load and of a tendon
    (T times the change of its length) is counted.  Without them the total
    would swing with the strain and kinetic energy."""
    tendon = (ROOT / "models" / "tendon_ancf.toml").read_text().replace(
        'analysis = "static"', 'analysis = "dynamic"').replace(
        "tension = 150.0", 'tension = 150.0\namplitude = {type = "step", t0 = 0.0}').replace(
        "[static]\nload_steps = 2", "[dynamic]\nt_end = 0.02\ndt = 2e-4\nrho_inf = 1.0")
    for name, text in (("gef_force_and_distributed", ENERGY_GEF), ("ancf_tendon", tendon)):
        rows = _energy_rows(text, name)
        kin = max(float(r["kinetic"]) for r in rows)
        lp = min(float(r["load_potential"]) for r in rows)
        assert kin > 0.0 and lp < -kin, (name, kin, lp)
        drift = max(abs(float(r["total"])) for r in rows)
        assert drift < 1e-3 * kin, (name, drift, kin)
