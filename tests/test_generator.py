"""The generator: shape functions against the seed, invariant derivatives
against sympy differentiation, freshness and determinism of out/kernels/."""
import pytest
import filecmp
import os
import subprocess
import tempfile
from pathlib import Path

import sympy as sp

from gen.element import L, XI, Y, Z, shape_functions
from gen.elements import all_elements
from gen.invariants import (COMPONENTS, cofactor, component_first, component_second,
                            first_derivatives, second_derivatives)
from util import ENV, PY, ROOT, run_cli


def test_ancf3243_shape_functions_are_seed_eq3():
    elem = all_elements()["ancf3243"][0]
    xi, l = XI, L
    eta, zeta = Y / l, Z / l          # the seed writes eta = y/l, zeta = z/l
    seed = [1 - 3 * xi**2 + 2 * xi**3, l * (xi - 2 * xi**2 + xi**3), l * (eta - xi * eta),
            l * (zeta - xi * zeta), 3 * xi**2 - 2 * xi**3, l * (-xi**2 + xi**3), l * xi * eta, l * xi * zeta]
    got = shape_functions(elem)
    assert len(got) == 8
    for a, (g, s) in enumerate(zip(got, seed)):
        assert sp.simplify(g - s) == 0, f"N{a}: generated {g}, seed {s}"


def test_invariant_derivatives_match_sympy_diff():
    Fs = sp.Matrix(3, 3, sp.symbols("f0:9", real=True))
    C = Fs.T * Fs
    b = Fs * Fs.T
    I1 = C.trace()
    I2 = (I1**2 - (C * C).trace()) / 2
    J = Fs.det()
    inv = {"I1": I1, "I2": I2, "J": J}
    d1 = first_derivatives(Fs, C, I1, cofactor(Fs))
    d2 = second_derivatives(Fs, C, b, I1)
    for (I, Jc) in COMPONENTS:        # components of C in the element frame
        inv[f"C{I}{Jc}"] = C[I, Jc]
        d1[f"C{I}{Jc}"] = component_first(Fs, I, Jc)
        d2[f"C{I}{Jc}"] = component_second(I, Jc)
    vals = dict(zip(Fs, [1.1, 0.2, -0.3, 0.15, 0.9, 0.25, -0.1, 0.35, 1.2]))
    for name, expr in inv.items():
        for i in range(3):
            for Jj in range(3):
                ref = sp.diff(expr, Fs[i, Jj]).subs(vals)
                got = d1[name][i, Jj].subs(vals)
                assert abs(float(ref - got)) < 1e-12, (name, i, Jj, ref, got)
                for k in range(3):
                    for Ll in range(3):
                        ref2 = sp.diff(expr, Fs[i, Jj], Fs[k, Ll]).subs(vals)
                        got2 = sp.sympify(d2[name](i, Jj, k, Ll)).subs(vals)
                        assert abs(float(ref2 - got2)) < 1e-12, (name, i, Jj, k, Ll, ref2, got2)


# Hash seeds: sympy's term order inside a derivation may follow Python's string
# hashes.  The two tests below regenerate under two fixed seeds and compare with
# the committed files, so together they show the output is the same under both
# (each is one generation: two of the suite's slowest steps, not three).
GEN_CHECK_SEED = "12345"
SUBSET_SEED = "0"


@pytest.mark.slow
def test_gen_check_passes_on_committed_kernels():
    """Every generated file regenerated (PYTHONHASHSEED 12345): byte-identical to out/kernels/."""
    r = run_cli(["gen", "--check"], env={"PYTHONHASHSEED": GEN_CHECK_SEED})
    assert r.returncode == 0, r.stdout + r.stderr


@pytest.mark.slow
def test_generation_is_byte_identical_across_hash_seeds():
    """A representative subset (the load kernel, ancf3243 with every material, ancf3363 x
    Arruda-Boyce) regenerated under PYTHONHASHSEED 0 into a new directory: identical to
    the committed files, which the gen --check test above reproduces under seed 12345."""
    assert SUBSET_SEED != GEN_CHECK_SEED
    subset = "loads,ancf3243,ancf3363_arruda_boyce"
    env = dict(ENV, PYTHONHASHSEED=SUBSET_SEED)
    with tempfile.TemporaryDirectory(prefix="bk-gen-") as tmp:
        d = Path(tmp)
        r = subprocess.run([PY, "-m", "gen.cli", "gen", "--force", "--only", subset, "--out", str(d)], env=env,
                           capture_output=True, text=True, cwd=ROOT)
        assert r.returncode == 0, r.stderr
        names = sorted(p.name for p in d.iterdir())
        assert len(names) >= 10, names
        match, mismatch, errors = filecmp.cmpfiles(d, ROOT / "out" / "kernels", names, shallow=False)
    assert not mismatch and not errors, f"differ from committed out/kernels: {mismatch + errors}"
