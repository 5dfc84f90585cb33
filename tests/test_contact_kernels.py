"""The generated contact kernels (gen/contact.py -> out/kernels/contact.c):
gaps to a half-space, a sphere and a segment's line with their gradients and
Hessians, the barrier, the friction profile and the static-to-kinetic step, against central differences
and against closed forms written independently in tests/contact_check.c
(built with AddressSanitizer + UBSan)."""
import functools
import os
import subprocess

from util import BUILD, ROOT, ensure_dir


@functools.lru_cache(maxsize=None)
def results():
    exe = ensure_dir(BUILD / "contact") / f"contact_check.{os.getpid()}"     # one per test worker
    r = subprocess.run(["cc", "-std=c11", "-O1", "-g", "-Wall", "-Wextra", "-Werror", "-fsanitize=address,undefined",
                        "-fno-sanitize-recover=all", f"-I{ROOT / 'out' / 'kernels'}", f"-I{ROOT / 'runtime'}",
                        str(ROOT / "tests" / "contact_check.c"), str(ROOT / "out" / "kernels" / "contact.c"),
                        "-o", str(exe), "-lm"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    r = subprocess.run([str(exe)], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and not r.stderr, r.stderr
    return dict(kv.split("=", 1) for kv in r.stdout.split())


def test_gaps_match_their_closed_forms_and_differences():
    d = results()
    assert float(d["closed_err"]) < 1e-13, d         # plane, sphere, line distance and t
    assert float(d["gap_grad_err"]) < 1e-7, d        # gradient against differences of the gap
    assert float(d["gap_hess_err"]) < 1e-6, d        # Hessian against differences of the gradient
    assert float(d["hess_sym_err"]) < 1e-12, d


def test_barrier_is_c2_at_its_reach_and_grows_without_bound_at_contact():
    d = results()
    assert float(d["barrier_err"]) < 1e-5, d
    b, db, ddb = (abs(float(v)) for v in d["barrier_at_shat"].split(","))
    assert b < 1e-20 and db < 1e-14 and ddb < 1e-6, d   # b, b', b'' -> 0 at shat (C2 with the zero beyond)
    assert float(d["barrier_near_0"]) > 1e-6, d          # shat^2 ln(1e12) = 2.8e-5 for shat = 1e-3


def test_friction_profile_is_c1_and_regular_at_zero_slip():
    d = results()
    assert float(d["friction_err"]) < 1e-6, d
    jump0, jump1 = (float(v) for v in d["friction_jump"].split(","))
    assert jump0 < 1e-10 and jump1 < 1e-6, d             # f1 = 1, f1' = 0 at eps from both sides
    assert abs(float(d["friction_f1y_at_0"]) - 2.0) < 1e-15, d   # f1/y -> 2/eps


def test_static_to_kinetic_step_is_c1_and_matches_its_closed_form():
    d = results()
    assert float(d["transition_err"]) < 1e-6, d          # h' against differences; h against 3 z^2 - 2 z^3
    a, b = (float(v) for v in d["transition_ends"].split(","))
    assert a < 1e-9 and b < 1e-9, d                      # h = 0, h' = 0 at eps; h = 1, h' = 0 at 2 eps


def test_a_body_frame_map_has_the_derivatives_of_its_differences_and_is_the_identity_in_the_reference():
    d = results()
    assert float(d["body_J_err"]) < 1e-8, d              # dz/dv against central differences of z
    assert float(d["body_T_err"]) < 1e-7, d              # d2z/dv2 against differences of dz/dv
    assert float(d["body_ref_err"]) < 1e-14, d           # at r = X, p = quaternion of R0: z = y


def test_a_sections_lever_arm_has_the_derivatives_of_its_differences_and_is_the_rotation():
    """bk_contact_lever (rolling: friction on the section's surface): w = R(p) a
    against Rodrigues' formula written in contact_check.c, dw/dp and
    sum f_i d2w_i/dp2 against central differences."""
    d = results()
    assert float(d["lever_closed_err"]) < 1e-14, d
    assert float(d["lever_J_err"]) < 1e-8, d
    assert float(d["lever_H_err"]) < 1e-7, d
