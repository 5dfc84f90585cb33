"""ancf3363 next to a rigid clamp (issue 37): a uniform mesh there is too stiff (the
3-D boundary layer of the held section; measured against CalculiX in
tests/test_silicone_large.py: 10 uniform elements 6.7 %, graded 20 toward the
clamp 0.48 %), so the scene compiler warns and names the grading to use."""
from util import run_scene


def test_uniform_ancf3363_at_a_rigid_clamp_warns_with_the_grading():
    s, _ = run_scene("tendon_finger", sets=["beam.f.elements=4"])
    w = [x for x in s["warnings"] if "rigid clamp at the start" in x]
    assert len(w) == 1 and "beam.grading = 20" in w[0] and "6.7 %" in w[0], s["warnings"]


def test_graded_or_free_clamp_does_not_warn():
    for sets in (["beam.f.grading=20"], ["constraint.0.cross_section=free"]):
        s, _ = run_scene("tendon_finger", sets=["beam.f.elements=4"] + sets)
        assert not any("rigid clamp at the" in x for x in s["warnings"]), (sets, s["warnings"])
