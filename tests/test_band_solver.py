"""The band LU that solves the Newton systems of beam models (runtime/linalg/bandlu.c,
chosen by runtime/linalg/linsolve.c when the matrix is a narrow band in reverse
Cuthill-McKee order) against dense Gaussian elimination with complete pivoting
written independently in the C harness tests/band_check.c (AddressSanitizer +
UBSan), on chain, saddle-point (multipliers with a zero diagonal, a closed
loop), indefinite, badly row-scaled and singular matrices given in a scrambled
numbering.  (Every scene test of the suite solves its beams with the band LU.)"""
import subprocess
from functools import lru_cache

from util import build_runtime_program


@lru_cache(maxsize=None)
def results():
    exe = build_runtime_program(["band_check.c"], "band_check", "sanitize")
    r = subprocess.run([str(exe)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, f"band_check failed ({r.returncode}):\n{r.stdout}\n{r.stderr[-4000:]}"
    assert "runtime error" not in r.stderr and "Sanitizer" not in r.stderr, r.stderr[-4000:]
    out = {}
    for line in r.stdout.splitlines():
        d = dict(kv.split("=", 1) for kv in line.split())
        out[d.pop("case")] = d
    return out


def test_band_lu_matches_dense_elimination():
    """Every solvable case agrees with the dense solve to 1e-10 (relative, max
    norm), through bk_band_* and through the linear-solver object, which picks
    the band; the scrambled chain is recovered as a band of width 2 x 12 - 1
    each side (node blocks of 12 coupled to their neighbours).  bk_band_factor_solve
    (the nonlinear solver's call with a new matrix) gives bit for bit what
    bk_band_factor then bk_band_solve give, and so does a plan used again
    (after interchanges, after its storage served as scratch) what a fresh one
    gives."""
    r = results()
    for case in ("chain", "kkt", "indefinite", "scaled"):
        d = r[case]
        assert d["plan"] == "0" and d["factor"] == "0", (case, d)
        assert float(d["err"]) <= 1e-10, (case, d)
        assert d["lin_band"] == "1" and d["lin_factor"] == "0" and float(d["lin_err"]) <= 1e-9, (case, d)
        # the one-pass factorization with the forward substitution inside gives the same bits
        assert d["fused_same"] == "1", (case, d)
        # a plan factoring another matrix, and again after its storage was used as
        # scratch, gives the bits of a fresh plan (the rows it zeroes are enough)
        assert d["reuse_same"] == "1", (case, d)
    assert int(r["chain"]["kl"]) == 23 and int(r["chain"]["ku"]) == 23, r["chain"]
    # the linear-solver object's three backends, each chosen explicitly, solve the
    # same systems (the dense LU is an independent elimination over all n^2 entries)
    for case in ("chain", "kkt", "indefinite", "scaled"):
        for k in ("band_err", "klu_err", "dense_err"):
            assert float(r[case][k]) <= 1e-9, (case, k, r[case])
    # the closed loop of the saddle-point case widens the band but keeps it a band
    assert int(r["kkt"]["kl"]) <= 60, r["kkt"]


def test_band_ldlt_inertia_matches_jacobi_eigenvalues():
    """The symmetric band LDL^T of the stability check (no pivoting; the
    saddle-point case has multipliers, so its inertia counts them as negative):
    its negative pivots equal the negative eigenvalues by cyclic Jacobi
    rotations of the dense matrix, its solve reproduces the known solution and its
    product with a vector the dense product."""
    r = results()
    for case in ("indefinite", "kkt"):
        d = r[case]
        assert d["sym_factor"] == "0", (case, d)
        assert int(d["sym_negative"]) == int(d["jacobi_negative"]), (case, d)
        assert float(d["sym_err"]) <= 1e-6, (case, d)   # (1e-8 regularization: cond ~ 1e8)
        assert float(d["sym_matvec_err"]) <= 1e-12, (case, d)   # the band product against the dense one
    assert int(r["indefinite"]["jacobi_negative"]) > 0          # the shift really made it indefinite
    assert int(r["kkt"]["jacobi_negative"]) >= 3                 # at least one per multiplier


def test_band_lu_reports_a_singular_matrix():
    d = results()["singular"]
    assert d["factor"] == "1", d
    assert d["lin_factor"] == "1", d          # BK_LIN_SINGULAR



def test_band_lu_solves_a_newton_matrix_as_lapack_does():
    """The runtime's band LU against LAPACK's dgbtrf/dgbtrs (another
    implementation: reference LAPACK) on the Newton matrix of seed Table 3 at a
    deformed state (bench/newton_iter.c writes it, bench/band_lapack.c solves
    it both ways): the same solution to round-off."""
    import subprocess
    from report.bench_band import matrices, programs
    from util import BUILD, ensure_dir
    mats = matrices(lambda s: None, [("Table 3", "cantilever_bend_100N_nu03", [])],
                    ensure_dir(BUILD / "band_lapack"))
    exe = programs()["reference LAPACK 3"]
    r = subprocess.run([str(exe), str(mats["Table 3"]), "3"], capture_output=True, text=True, check=True)
    d = dict(line.split("=", 1) for line in r.stdout.split())
    assert int(d["n"]) == 120 and int(d["kl"]) == 23
    assert float(d["solution_difference"]) < 1e-8


@lru_cache(maxsize=None)
def split_results():
    exe = build_runtime_program(["bandsplit_check.c"], "bandsplit_check", "sanitize")
    r = subprocess.run([str(exe)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, f"bandsplit_check failed ({r.returncode}):\n{r.stdout}\n{r.stderr[-4000:]}"
    assert "runtime error" not in r.stderr and "Sanitizer" not in r.stderr, r.stderr[-4000:]
    return {d.pop("case"): d for d in (dict(kv.split("=", 1) for kv in line.split()) for line in r.stdout.splitlines())}


def test_split_band_lu_matches_dense_elimination():
    """The band LU in two halves and a separator (runtime/linalg/bandsplit.c,
    the linear solver of bands of BK_BANDSPLIT_MIN unknowns and more) against a
    dense LU with row pivoting written in tests/bandsplit_check.c: chains of 60
    nodes, diagonally dominant, with small diagonals (row interchanges inside
    the halves), with multiplier rows of zero diagonal, and badly row-scaled:
    the solution to 1e-10 (relative, max norm; 1e-9 for the 1e12 row-scale
    spread), residual to 1e-12; the same bits with 1 and 2 OpenMP threads and
    for a second factorization with the same plan; a zero column is reported
    singular, a NaN as non-finite."""
    r = split_results()
    for case in ("chain", "weak", "kkt", "scaled"):
        d = r[case]
        assert d["plan"] == "0" and d["factor"] == "0", (case, d)
        assert float(d["err"]) <= (1e-9 if case == "scaled" else 1e-10), (case, d)
        assert float(d["res"]) <= 1e-12, (case, d)
        assert d["same_threads"] == "1" and d["same_again"] == "1", (case, d)
        assert int(d["s"]) == max(int(d["kl"]), int(d["ku"])), (case, d)
    assert r["singular"]["factor"] == "1", r["singular"]
    assert r["nonfinite"]["factor"] == "2", r["nonfinite"]


def test_split_band_ldlt_inertia_matches_a_sturm_count():
    """The symmetric band L D L^T in two halves and a separator
    (runtime/linalg/symsplit.c: the stability checks' inertia of bands of
    BK_BANDSPLIT_MIN unknowns and more) against Householder tridiagonalization
    and a Sturm count written in tests/symsplit_check.c: random symmetric band
    matrices of 34 node blocks with a scrambled numbering, dominant and not,
    indefinite, and a regularized saddle point: the negative pivots equal the
    negative eigenvalues exactly (and the whole band's L D L^T's count), the
    determinant's sign agrees and its log to 1e-9, a solve's residual to 1e-12
    (1e-7 for the saddle point: its -1e-8 diagonals make pivots of 1e8);
    the same bits with 1 and 2 threads and with the blocks' storage lent; a zero
    pivot and a NaN are reported."""
    exe = build_runtime_program(["symsplit_check.c"], "symsplit_check", "sanitize")
    r = subprocess.run([str(exe)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, f"symsplit_check failed ({r.returncode}):\n{r.stdout}\n{r.stderr[-4000:]}"
    assert "runtime error" not in r.stderr and "Sanitizer" not in r.stderr, r.stderr[-4000:]
    res = {d.pop("case"): d for d in (dict(kv.split("=", 1) for kv in line.split()) for line in r.stdout.splitlines())}
    for case in ("dominant", "indefinite", "kkt"):
        d = res[case]
        assert d["plan"] == "0" and d["factor"] == "0", (case, d)
        assert int(d["neg"]) == int(d["sturm"]) == int(d["band_neg"]), (case, d)
        assert d["sign"] == "1" and float(d["logdet"]) <= 1e-9, (case, d)
        assert float(d["res"]) <= (1e-7 if case == "kkt" else 1e-12), (case, d)
        assert d["same_threads"] == "1" and d["lent"] == "1", (case, d)
    assert 0 < int(res["indefinite"]["neg"]) < int(res["indefinite"]["n"]), res["indefinite"]
    assert int(res["kkt"]["neg"]) >= 2 * 33, res["kkt"]          # at least one per multiplier
    assert res["zero"]["factor"] == "-1" and res["nonfinite"]["factor"] == "-1", res
