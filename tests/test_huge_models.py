"""Huge models: the cost is estimated before meshing; a model the machine cannot
hold is refused at once with the estimate and the key; large ones show the
estimate and meshing progress.  Before: elements = 1000000 was accepted and ran
silent for over 40 s at 2 GB before anything showed."""
import time

from gen import estimate
from gen.scene import ROOT, SceneError, build, load_index
from util import run_cli


def test_model_beyond_the_memory_is_refused_before_meshing():
    t0 = time.time()
    r = run_cli(["run", "cantilever_bend_10N", "--set", "beam.arm.elements=1000000",
                 "--set", "beam.arm.element=ancf3363"])
    assert r.returncode == 1, r.stderr
    line = r.stderr.strip().splitlines()[-1]
    assert "error: --set beam.arm.elements=1000000: beam.arm.elements:" in line and "GB of memory" in line and \
        "expected fewer elements" in line, line
    assert time.time() - t0 < 20          # refused before meshing (meshing alone takes over 30 s)


def test_estimate_is_shown_and_meshing_reports_progress():
    lines = []
    m = build(ROOT / "models" / "cantilever_bend_10N.toml",
              ["beam.arm.elements=300000", "beam.arm.element=ancf_cable", "material.alu.law=resultant"],
              log=lines.append)
    assert m["ndof"] == 6 * 300001
    assert any(l.startswith("meshing: ") and "of 300000 elements" in l for l in lines), lines
    e = estimate.estimate([("beam.arm", "ancf3243", 200000)], load_index(), 11)
    shown = []
    estimate.check(e, [("beam.arm", "ancf3243", 200000)], str(ROOT / "out"), lambda k, m: None, shown.append)
    assert len(shown) == 1 and "200000 elements: about" in shown[0] and "per Newton iteration" in shown[0], shown


def test_element_count_limit():
    r = run_cli(["run", "cantilever_bend_10N", "--set", "beam.arm.elements=2000000"])
    assert r.returncode == 1 and "beam.arm.elements" in r.stderr and "1000000" in r.stderr, r.stderr
