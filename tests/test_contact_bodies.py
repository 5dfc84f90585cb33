"""Contact with primitives that are not fixed spheres, capsules or planes
(gen/scene/contact.py; runtime/assembly/contact_geometry.c) against closed
forms: a sphere that belongs to a rigid body (models/contact_ball_on_cantilever.toml)
passes the body's whole weight to the beam it rests on, and the beam's tip
sags by the cantilever's closed form; a narrow box as the prop of a
propped cantilever carries 3 q L / 8 like the ball of
models/contact_propped_cantilever.toml, and so does the same box given
tilted by 0.2 rad and 1 mm low, turned level about its centre (`turn`) and
lifted (`motion`) by the load factor.""" 
import math

from test_contact_scenes import _contact, out_dir, run_scene_expect_error
from util import ROOT, run_cli, run_scene

Q, L, EI = 2700.0 * 1e-4 * 9.81, 1.0, 7.0e10 * 0.01 ** 4 / 12


def test_a_ball_body_on_a_cantilever_passes_its_weight_and_bends_it_by_the_closed_form():
    out = out_dir()
    s, _ = run_scene(ROOT / "models" / "contact_ball_on_cantilever.toml", out=out)
    c = _contact(s)
    P = 0.2 * 9.81
    fz = c["sets"][0]["force"][2]
    assert abs(-fz / P - 1) < 1e-9, fz                      # the body's vertical balance: all through the contact
    import csv
    with open(out / "sensors.csv", newline="") as fh:
        tip = [r for r in csv.DictReader(fh) if r["sensor"] == "tip"][-1]
    ref = P * L ** 3 / (3 * EI) + Q * L ** 4 / (8 * EI)
    assert abs(-float(tip["uz"]) / ref - 1) < 1e-3, (tip["uz"], ref)
    # the reference state (the ball placed within the barrier's reach: 26 N of
    # barrier force at load factor 0) is no equilibrium: its negative eigenvalue
    # is not compared with the path's.  Before: "went from 1 to 0 ... (critical
    # load factor 1.1e-13): a point of regained stability was passed"
    assert s["warnings"] == [] and s["stability"]["events"] == [], s["warnings"]
    with open(out / "stability.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert rows[0]["negative_eigenvalues"] == "1" and all(r["negative_eigenvalues"] == "0" for r in rows[1:]), rows


def _box_prop(extra, drop=0.0):
    """The propped cantilever with a box (4 mm along the beam) for the ball,
    its top where the ball's was (lowered by `drop` in the reference)."""
    text = (ROOT / "models" / "contact_propped_cantilever.toml").read_text()
    ball = 'shape = "sphere"\ncenter = [1.0, 0.0, -0.015001]\nradius = 0.01\n'
    assert ball in text
    p = out_dir() / "box.toml"
    p.write_text(text.replace(ball, f'shape = "box"\ncenter = [1.0, 0.0, {-0.015001 - drop!r}]\n'
                                    'size = [0.004, 0.05, 0.02]\n' + extra))
    return run_scene(p)[0]


def test_a_narrow_box_props_a_cantilever_with_three_eighths_of_the_load():
    fz = _contact(_box_prop(""))["sets"][0]["force"][2]
    assert abs(fz / (3 * Q * L / 8) - 1) < 5e-3, fz


def test_a_tilted_box_turned_level_by_the_load_factor_props_it_the_same():
    th, drop = 0.2, 0.001
    extra = (f"axes = [[{math.cos(th)!r}, 0.0, {-math.sin(th)!r}], [0.0, 1.0, 0.0]]\n"
             f"turn = [0.0, {-th!r}, 0.0]\nmotion = [0.0, 0.0, {drop!r}]\n")
    fz = _contact(_box_prop(extra, drop))["sets"][0]["force"][2]
    assert abs(fz / (3 * Q * L / 8) - 1) < 5e-3, fz


def test_bad_primitives_are_one_clear_line():
    text = (ROOT / "models" / "contact_ball_on_cantilever.toml").read_text()
    for old, new, msg in (('body = "ball"', 'body = "bowl"', "contact[0].body: expected the name of a [[body]]"),
                          ('body = "ball"', 'body = "ball"\nmotion = [0.0, 0.0, 0.1]',
                           "contact[0].motion: a primitive of a body moves with the body"),
                          ('radius = 0.02', 'size = [0.1, 0.0, 0.1]', "contact[0].size: not a key of a sphere"),
                          ('shape = "sphere"', 'shape = "box"\nsize = [0.1, 0.0, 0.1]',
                           "contact[0].radius: not a key of a box")):
        p = out_dir() / "bad.toml"
        p.write_text(text.replace(old, new))
        assert msg in run_scene_expect_error(p)


PVSCRIPT = r"""
import json, sys
import numpy as np
from paraview.simple import PVDReader
from paraview import servermanager as sm
from vtk.numpy_interface import dataset_adapter as dsa
reader = PVDReader(FileName=sys.argv[1])
out = {"times": list(reader.TimestepValues), "frames": []}
for t in reader.TimestepValues:
    reader.UpdatePipeline(t)
    d = dsa.WrapDataObject(sm.Fetch(reader))
    out["frames"].append({"points": np.asarray(d.Points).tolist() if d.GetNumberOfPoints() else [],
                          "force": np.asarray(d.PointData["force"]).tolist() if d.GetNumberOfPoints() else [],
                          "normal_force": np.asarray(d.PointData["normal_force"]).tolist()
                          if d.GetNumberOfPoints() else []})
json.dump(out, open(sys.argv[2], "w"))
"""


def test_contact_points_and_forces_are_in_the_paraview_frames():
    """contacts.pvd (one contacts_NNNNNN.vtp per step_NNNNNN.vtu frame) read by
    ParaView's pvpython: the load factors of the frames; in the last the
    contact points' forces sum to summary.json's force on the beam and their
    points are those of contacts.csv."""
    import csv
    import json
    import shutil
    import subprocess
    pvpython = shutil.which("pvpython")
    assert pvpython, "pvpython not found: ./build.sh deps installs the Debian package paraview"
    out = out_dir()
    s, _ = run_scene(ROOT / "models" / "contact_ball_on_cantilever.toml", out=out)
    script, dump = out / "read_contacts.py", out / "contacts.json"
    script.write_text(PVSCRIPT)
    r = subprocess.run([pvpython, str(script), str(out / "contacts.pvd"), str(dump)], capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 0, r.stderr[-3000:]
    data = json.loads(dump.read_text())
    assert data["times"] == [0.0, 0.25, 0.5, 0.875, 1.0], data["times"]
    last = data["frames"][-1]
    total = [sum(f[k] for f in last["force"]) for k in range(3)]
    ref = s["contact"]["sets"][0]["force"]
    assert all(abs(a - b) <= 1e-8 * 2.0 for a, b in zip(total, ref)), (total, ref)
    with open(out / "contacts.csv", newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["step"] == "4"]
    assert len(rows) == len(last["points"]) >= 1
    for row, p in zip(rows, last["points"]):
        assert all(abs(float(row[k]) - v) < 1e-8 for k, v in zip("xyz", p)), (row, p)


def _gripper(mu):
    """models/gripper_lift.toml with friction mu: the cylinder's height and the
    bases' against time (sensors.csv), and the summary."""
    import csv
    text = (ROOT / "models" / "gripper_lift.toml").read_text()
    assert "\nfriction = 0.8\n" in text
    p = out_dir() / "gripper.toml"
    p.write_text(text.replace("\nfriction = 0.8\n", f"\nfriction = {mu!r}\n"))
    out = out_dir()
    s, _ = run_scene(p, out=out)
    h = {"cylinder": {}, "base": {}}
    with open(out / "sensors.csv", newline="") as fh:
        for r in csv.DictReader(fh):
            h[r["sensor"]][round(float(r["time"]), 6)] = float(r["uz"])
    return s, h


def test_a_gripper_lifts_a_cylinder_by_friction_and_drops_it_without():
    """Two tendon-driven silicone fingers hold a 50 g cylinder body and lift
    their bases 30 mm (0.25 s to 0.55 s): with friction 0.8 the cylinder
    rises with them (within 5 %; measured 0.1 %) at dt = 1e-3 with almost no
    cut-back, and no sample point ever goes through its surface; with 0.1 it
    slips out and falls (far below where it was held)."""
    def at(series, t):
        return series[min(series, key=lambda x: abs(x - t))]

    s, h = _gripper(0.8)
    assert s["converged"] and _contact(s)
    cyl = {t: at(h["cylinder"], t) for t in (0.25, 0.6)}
    base = {t: at(h["base"], t) for t in (0.25, 0.6)}
    rise = cyl[0.6] - cyl[0.25]
    assert abs(base[0.6] - base[0.25] - 0.03) < 1e-9
    assert abs(rise / 0.03 - 1) < 0.05, rise
    assert s["cutbacks"] <= 0.02 * s["steps"], s                 # the step contact does not force small steps
    s, h = _gripper(0.1)
    assert s["converged"] and _contact(s)
    assert at(h["cylinder"], 0.6) - at(h["cylinder"], 0.25) < -0.1, h["cylinder"]   # fell, did not follow


def test_contact_with_bodies_boxes_and_turning_primitives_is_clean_under_sanitizers():
    """The ball body, the gripper (a capsule of a body touched by continuum
    elements: the body-frame chain rule and the coupling blocks) and the
    tilted, turned box run with AddressSanitizer and UBSan (--sanitize): exit
    0 and no report; the ball body under valgrind's memcheck too (exit 0, not
    99)."""
    scenes = [ROOT / "models" / "contact_ball_on_cantilever.toml", ROOT / "models" / "gripper_lift.toml"]
    th = 0.2
    text = (ROOT / "models" / "contact_propped_cantilever.toml").read_text()
    ball = 'shape = "sphere"\ncenter = [1.0, 0.0, -0.015001]\nradius = 0.01\n'
    box = out_dir() / "box.toml"
    box.write_text(text.replace(ball, 'shape = "box"\ncenter = [1.0, 0.0, -0.016001]\nsize = [0.004, 0.05, 0.02]\n'
                                      f"axes = [[{math.cos(th)!r}, 0.0, {-math.sin(th)!r}], [0.0, 1.0, 0.0]]\n"
                                      f"turn = [0.0, {-th!r}, 0.0]\nmotion = [0.0, 0.0, 0.001]\n"))
    for scene in scenes + [box]:
        r = run_cli(["run", str(scene), "--sanitize", "--quiet", "--out", str(out_dir())])
        assert r.returncode == 0 and "runtime error" not in r.stderr and "Sanitizer" not in r.stderr, \
            (scene, r.returncode, r.stderr[-2000:])
    r = run_cli(["run", str(scenes[0]), "--memcheck", "--quiet", "--out", str(out_dir())])   # and valgrind's
    assert r.returncode == 0, (r.returncode, r.stderr[-2000:])                                # memcheck: 99
