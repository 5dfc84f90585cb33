"""Generated kernels against finite differences and rigid motions (C harness
tests/kernel_check.c, built with AddressSanitizer + UBSan)."""
import pytest
import subprocess

from util import build_program


def parse(out):
    rows = []
    for line in out.splitlines():
        d = dict(kv.split("=", 1) for kv in line.split())
        rows.append(d)
    return rows


def test_force_tangent_finite_differences_and_rigid_motion():
    """20 random deformed states and 20 rigid motions per pair and geometry (optimized build)."""
    exe = build_program("kernel_check.c", "kernel_check", "release")
    check(exe, 20)


@pytest.mark.slow
def test_kernels_clean_under_asan_ubsan():
    """The same checks, 2 states per pair, with AddressSanitizer + UBSan."""
    exe = build_program("kernel_check.c", "kernel_check", "sanitize")
    check(exe, 2)


def check(exe, nstate):
    r = subprocess.run([str(exe), str(nstate)], capture_output=True, text=True, timeout=1800)
    assert r.returncode == 0, f"kernel_check failed ({r.returncode}):\n{r.stdout}\n{r.stderr[-4000:]}"
    assert "runtime error" not in r.stderr and "Sanitizer" not in r.stderr, r.stderr[-4000:]
    rows = parse(r.stdout)
    assert rows, "no pairs checked"
    worst = []
    for d in rows:
        assert int(d["states"]) >= nstate
        checks = {"fd_force": 1e-6, "fd_tangent": 1e-6, "sym": 1e-14, "consist": 1e-12,
                  "rigid_energy": 1e-10, "rigid_force": 1e-10, "fd_viscous": 1e-8, "fd_moment": 1e-8,
                  "fd_dissipation": 1e-8, "fd_visc_tangent": 1e-6, "visc_sym": 1e-14, "visc_consist": 1e-12,
                  "visc_lanes": 1e-11}
        continuum = d["pair"].startswith("ancf3") and "_resultant_" not in d["pair"]
        if continuum:             # every continuum pair has Kelvin-Voigt damping, lane kernels included
            for k in ("fd_viscous", "fd_dissipation", "fd_visc_tangent", "visc_lanes"):
                if not float(d[k]) >= 0:
                    worst.append(f"{d['pair']} geometry {d['geom']}: {k} not checked ({d[k]})")
        for k, tol in checks.items():
            v = float(d[k])
            if not v <= tol:             # (-1: not applicable)
                worst.append(f"{d['pair']} geometry {d['geom']}: {k} = {v:.3e} > {tol:.0e}")
        # lane kernels (BK_LANES elements per call) against the one-element kernels: round-off
        continuum = d["pair"].startswith("ancf3") and "_resultant_" not in d["pair"]
        for k in ("lanes_f", "lanes_K"):
            v = float(d[k])
            if continuum and not 0 <= v <= 1e-11:
                worst.append(f"{d['pair']} geometry {d['geom']}: {k} = {v:.3e} (lane kernels vs one element)")
    assert not worst, "\n".join(worst)
