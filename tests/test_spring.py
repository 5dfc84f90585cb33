"""The runtime's assembly and stability analysis against hand-written elements
(tests/spring_element.c: an axial spring and an inextensible link with an
element-internal multiplier) that reach it through the same bk_element /
bk_pair descriptors as the generated kernels (C harness tests/spring_check.c,
built with AddressSanitizer + UBSan).  References: hand-written matrices,
closed-form spring forces, finite differences, GSL's dense eigensolver, and
inertia counts known in closed form."""
import subprocess
from functools import lru_cache

from util import build_runtime_program


@lru_cache(maxsize=None)
def results():
    exe = build_runtime_program(["spring_element.c", "spring_check.c"], "spring_check", "sanitize")
    r = subprocess.run([str(exe)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, f"spring_check failed ({r.returncode}):\n{r.stdout}\n{r.stderr[-4000:]}"
    assert "runtime error" not in r.stderr and "Sanitizer" not in r.stderr, r.stderr[-4000:]
    out = {}
    for line in r.stdout.splitlines():
        d = dict(kv.split("=", 1) for kv in line.split())
        out[d.pop("case")] = d
    return out


def test_assembly_of_springs_matches_hand_computed_force_and_tangent():
    """Two springs at right angles (one end clamped): the assembled tangent at the
    reference equals k n n^T written out by hand; in a deformed state the internal
    force (reactions included) equals the closed-form spring forces, the tangent
    the central differences of the assembled force, the energy the closed form;
    the element mass is rho A l / 6 [2 1; 1 2] (x) I3 and gravity puts half of
    each element's weight on each node."""
    r = results()
    ref = r["reference_tangent"]
    assert int(ref["neq"]) == int(ref["expected_neq"])
    assert float(ref["err"]) <= 1e-15 and float(ref["fint"]) == 0.0, ref
    assert float(r["deformed_force"]["err"]) <= 1e-14, r["deformed_force"]
    assert float(r["deformed_tangent_fd"]["err"]) <= 1e-7, r["deformed_tangent_fd"]
    assert float(r["energy"]["err"]) <= 1e-13, r["energy"]
    assert float(r["mass"]["err"]) <= 1e-15, r["mass"]
    assert float(r["gravity"]["err"]) <= 1e-15, r["gravity"]
    assert float(r["gather_scatter"]["err"]) == 0.0, r["gather_scatter"]


def test_stability_inertia_of_spring_chains_and_truss():
    """Negative tangent eigenvalues on the constraint tangent space: a chain of
    springs (+1, -0.5, +2, -3) fixed at one end has two (Sylvester); tying the
    last node to the one before, by a linear constraint or by a link element
    whose multiplier the runtime knows by its field role, leaves one.  The
    two-bar truss has none with its apex up or snapped down and one with it
    flat, where the smallest eigenvalue is 2k(1 - L0); the critical point found
    between up and flat is where the interpolated K_yy vanishes."""
    r = results()
    for case in ("chain", "chain_lincon", "chain_link"):
        d = r[case]
        assert int(d["ok"]) == 1, d
        assert int(d["negative"]) == int(d["expected"]), (case, d)
        assert int(d["nmult"]) == int(d["expected_nmult"]), (case, d)
    c = r["chain"]
    assert float(c["tangent_err"]) <= 1e-15, c
    assert abs(float(c["eig_min"]) - float(c["eig_min_ref"])) <= 1e-10 * abs(float(c["eig_min_ref"])), c
    for case in ("truss_up", "truss_flat", "truss_down"):
        d = r[case]
        assert int(d["ok"]) == 1 and int(d["negative"]) == int(d["expected"]), (case, d)
        assert abs(float(d["eig_min"]) - float(d["eig_min_ref"])) <= 1e-9 * abs(float(d["eig_min_ref"])), (case, d)
    assert int(r["truss_flat"]["expected"]) == 1 and int(r["truss_up"]["expected"]) == 0
    t = r["truss_crossing"]
    assert abs(float(t["t"]) - float(t["expected"])) <= 1e-8, t
