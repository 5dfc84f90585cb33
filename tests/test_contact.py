"""The contact interaction of the runtime (runtime/assembly/contact_force.c)
on in-memory spring chains (tests/contact_runtime_check.c, AddressSanitizer +
UBSan): its Jacobian against central differences of its residual for a
half-space, a sphere and a capsule; a chain settling on the ground under its
weight (Newton with the step limiter: no iterate through the surface, the
contact force equals the weight); the step limiter against a correction that
would cross the surface.  Scene-level contact (keys, outputs, friction, the
closed-form cases of issue 34) is not there yet."""
import subprocess
from functools import lru_cache

from util import build_runtime_program


@lru_cache(maxsize=None)
def results():
    exe = build_runtime_program(["contact_runtime_check.c", "spring_element.c"], "contact_runtime_check", "sanitize")
    r = subprocess.run([str(exe)], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and "runtime error" not in r.stderr, r.stderr[-3000:]
    out = {}
    for line in r.stdout.splitlines():
        d = dict(kv.split("=", 1) for kv in line.split())
        out[d.pop("case")] = d
    return out


def test_jacobian_matches_differences_of_the_residual():
    for case in ("jacobian_half_space", "jacobian_sphere", "jacobian_capsule", "jacobian_box",
                 "jacobian_turned_capsule"):
        d = results()[case]
        assert int(d["active"]) > 0 and float(d["min_distance"]) > 0, (case, d)   # the barrier acts
        assert float(d["err"]) < 1e-6, (case, d)


def test_a_chain_rests_on_the_ground_with_the_contact_force_equal_to_its_weight():
    d = results()["resting_chain"]
    assert d["converged"] == "1" and d["crossed"] == "0", d
    assert float(d["balance_err"]) < 1e-9, d             # sum of contact forces = weight
    assert 0.0 < float(d["min_distance"]) < float(d["shat"]), d   # inside the barrier, never through


def test_step_limiter_keeps_a_tenth_of_the_distance():
    d = results()["step_limit"]
    before, after = float(d["distance_before"]), float(d["distance_after"])
    assert 0.0 < float(d["alpha"]) < 1.0, d
    assert abs(after - 0.1 * before) < 1e-12, d          # 90 % of the way to the surface, not through it


def test_friction_jacobian_and_coulomb_limit():
    """The lagged friction (sticking below the slip tolerance, sliding beyond)
    against central differences of its force, and, sliding far, the
    tangential force mu times the normal force of the lagged state."""
    d = results()["jacobian_friction"]
    assert int(d["active"]) > 0, d
    assert float(d["err"]) < 1e-6, d
    assert abs(float(d["coulomb_ratio"]) - float(d["mu"])) < 1e-3 * float(d["mu"]), d


def test_broad_phase_keeps_the_elements_within_reach_only():
    """A chain of 8 elements at z = 0.115 over a sphere of radius 0.1 (section
    radius 0.01, reach 0.01): the two elements meeting above the centre come
    within R + r + reach = 0.12 of it, the next are 0.125 away along x; the
    same with the sphere moved by 0.25 along x; the step limiter of a fall of
    0.2 keeps 0.9 of the nearest point's distance 0.005 (the far elements'
    too)."""
    d = results()["broad_phase"]
    assert int(d["candidates"]) == 2 and int(d["candidates_moved"]) == 2, d
    assert int(d["active"]) == 2, d                      # the two elements' points above the centre
    assert abs(float(d["alpha"]) - 0.9 * 0.005 / 0.2) < 1e-12, d
