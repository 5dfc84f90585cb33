"""The sparse modal solver (issue 38 point 5; issue 33 point 7: modal through the
linear solver object): shift-invert Lanczos (runtime/linalg/lanczos.c) on the
Newton matrix factored by the linear solver object (runtime/analysis/
modal_sparse.c).  Verified against closed forms (the Lanczos routine on
problems with known eigenvalues, repeated and massless ones included; the
Euler-Bernoulli cantilever at a mesh too large for the dense solver) and
against the dense solver (GSL's generalized symmetric eigen-solver, a second
implementation written differently) on small models."""
import json
import math
import re
import subprocess
import tempfile
from pathlib import Path

from report.timoshenko_modes import clamped_free_hz
from util import BUILD, ROOT, build_runtime_program, ensure_dir, run_cli

# the steel cantilever of models/cantilever_modal.toml
E, NU, RHO, B, H, L = 2.1e11, 0.3, 7850.0, 0.01, 0.01, 1.0
EI, RHOA = E * B * H**3 / 12, RHO * B * H
BETA_L = (1.87510407, 4.69409113, 7.85475744)


def _run(scene, sets, ok=True):
    out = Path(tempfile.mkdtemp(prefix="bk-msparse-", dir=ensure_dir(BUILD / "runs")))
    args = ["run", str(scene), "--quiet", "--out", str(out)]
    for s in sets:
        args += ["--set", s]
    r = run_cli(args)
    if ok:
        assert r.returncode == 0, r.stderr[-2000:]
        return json.loads((out / "summary.json").read_text())["frequencies_hz"]
    return r


def test_lanczos_finds_closed_form_eigenvalues_repeated_and_massless_ones_included():
    exe = build_runtime_program(["lanczos_check.c"], "lanczos_check", "sanitize")
    r = subprocess.run([str(exe)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    cases = {m["case"]: m for m in (dict(kv.split("=") for kv in line.split()) for line in r.stdout.splitlines())}
    assert set(cases) == {"repeated", "massless", "second_difference"}
    for name, c in cases.items():
        assert c["rc"] == "0" and c["nconv"] == c["want"], (name, c)
        assert float(c["eig_err"]) < 1e-10, (name, c)       # against the closed form
        assert float(c["residual"]) < 1e-9, (name, c)       # |OP x - theta x|_M / theta
        assert float(c["orth"]) < 1e-10, (name, c)          # X^T M X = I


def test_gef_cantilever_frequencies_are_the_timoshenko_beams():
    """The first three bending frequencies of the gef cantilever (100 elements,
    each twice: square section) against the clamped-free Timoshenko beam (shear
    with Cowper's coefficient, rotary inertia), computed by shooting on its
    differential equations (report/timoshenko_modes.py): within 2e-7 (seen: 8e-8
    for the third, 1e-8 for the first; Euler-Bernoulli is 8e-5 to 1.3e-3 away)."""
    f = _run(ROOT / "models" / "cantilever_modal.toml",
             ["beam.arm.elements=100", "modal.modes=6", "output.vtk_every=0"])
    for k in range(3):
        ref = clamped_free_hz(E, NU, RHO, B, H, L, k + 1)
        for got in f[2 * k:2 * k + 2]:
            assert abs(got - ref) < 2e-7 * ref, (k + 1, got, ref)


def test_sparse_modes_equal_the_dense_solvers_on_small_models():
    for scene, n in (("cantilever_modal", 6), ("tip_mass_cantilever", 4)):
        dense = _run(ROOT / "models" / f"{scene}.toml", [f"modal.modes={n}", "modal.solver=dense"])
        sparse = _run(ROOT / "models" / f"{scene}.toml", [f"modal.modes={n}", "modal.solver=sparse"])
        assert len(dense) == len(sparse) == n
        for d, s in zip(dense, sparse):
            assert abs(s - d) <= 1e-8 * d, (scene, dense, sparse)


def test_free_beam_rigid_modes_at_zero_and_elastic_modes_as_dense(tmp_path):
    text = (ROOT / "models" / "cantilever_modal.toml").read_text()
    free = re.sub(r"\[\[constraint\]\]\ntype = \"clamp\"\na = \"arm:start\"\n", "", text)
    assert free != text
    scene = tmp_path / "free_beam.toml"
    scene.write_text(free)
    dense = _run(scene, ["modal.modes=10", "modal.solver=dense"])
    sparse = _run(scene, ["modal.modes=10", "modal.solver=sparse"])
    assert all(f < 1e-3 for f in sparse[:6]), sparse          # six rigid motions
    for d, s in zip(dense[6:], sparse[6:]):
        assert abs(s - d) <= 1e-6 * d, (dense, sparse)
    # free-free Euler-Bernoulli: beta L = 4.7300408 (the shear-flexible beam a little lower)
    f1 = 4.7300408**2 / (2 * math.pi * L * L) * math.sqrt(EI / RHOA)
    assert abs(sparse[6] - f1) < 2e-3 * f1 and abs(sparse[7] - f1) < 2e-3 * f1


def test_a_model_too_large_for_the_dense_solver_against_beam_theory():
    """400 elements (5,600 free DOFs): `auto` takes the sparse solver; the dense one
    refuses with a line naming its limit and the way out."""
    scene = ROOT / "models" / "cantilever_modal.toml"
    sets = ["beam.arm.elements=400", "modal.modes=6", "output.vtk_every=0"]
    f = _run(scene, sets)
    # Euler-Bernoulli, less the shear and rotary inertia of this (Timoshenko) beam:
    # to first order the frequency falls by a fraction c (beta r)^2 (1 + E / (kappa G)),
    # r^2 = I / A, c of order one (0.5-0.7 for these modes)
    shear = 1.0 + E / (5.0 / 6.0 * E / (2.0 * 1.3))
    for k in range(3):                    # each bending frequency twice (square section)
        ref = BETA_L[k] ** 2 / (2 * math.pi * L * L) * math.sqrt(EI / RHOA)
        bound = (BETA_L[k] / L) ** 2 * (H * H / 12.0) * shear
        timoshenko = clamped_free_hz(E, NU, RHO, B, H, L, k + 1)
        for got in f[2 * k:2 * k + 2]:
            assert 0.3 * bound < (ref - got) / ref < bound, (k, got, ref, bound)
            assert abs(got - timoshenko) < 1e-6 * timoshenko, (k, got, timoshenko)   # seen: 3.1e-7
    r = _run(scene, sets + ["modal.solver=dense"], ok=False)
    assert r.returncode != 0
    assert "limited to 4000 free DOFs; this model has 5600" in r.stderr and 'modal.solver = "sparse"' in r.stderr


def test_sparse_solver_refuses_nonlinear_joints_about_a_static_state():
    r = _run(ROOT / "models" / "universal_pendulum.toml", ["modal.solver=sparse"], ok=False)
    assert r.returncode != 0
    assert "sparse modal solver does not take joints nonlinear" in r.stderr and "modal.solver = \"dense\"" in r.stderr
