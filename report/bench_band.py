"""The band LU against LAPACK's band solver in the bench (issue 38 point 6):
the Newton matrix of seed Table 3 (10 ancf3243 elements), of the soft seed
pendulum and of the same pendulum with 1,000 elements, factored and solved by
the runtime's band LU (runtime/linalg/bandlu.c) and by LAPACK's dgbtrf +
dgbtrs in the same order and band (bench/band_lapack.c), with reference LAPACK
(liblapack3) and with OpenBLAS when it is installed (Debian libopenblas-dev;
or BK_OPENBLAS_DIR, a folder holding libopenblas.so).  Medians of interleaved
calls, one thread.  The solver keeps the band LU while it is the faster.
Run alone: /usr/bin/python3 -m report.bench_band [--quick]."""
import os
import subprocess
import sys
from pathlib import Path

from gen.scene import ROOT
from report.bench_runs import WORK

SCENES = [("Table 3 (10 ancf3243)", "cantilever_bend_100N_nu03", []),
          ("soft pendulum (10 ancf3243)", "pendulum_soft_ancf", []),
          ("soft pendulum, 1,000 elements", "pendulum_soft_ancf", ["beam.0.elements=1000"])]
OPENBLAS_DIRS = ["/usr/lib/x86_64-linux-gnu/openblas-pthread", "/usr/lib/x86_64-linux-gnu/openblas-openmp",
                 "/usr/lib/x86_64-linux-gnu/openblas-serial"]


# Debian's OpenBLAS unpacked into out/ (not installed: installing it would make it
# the system's libblas.so.3 and liblapack.so.3 for every program, numpy too).
FETCHED = ROOT / "out" / "openblas"
FETCHED_DIR = FETCHED / "usr" / "lib" / "x86_64-linux-gnu" / "openblas-pthread"


def _fetch_openblas(log):
    """Debian's libopenblas0-pthread downloaded (apt-get download) and unpacked into
    out/openblas; False (said in the log) when that fails, e.g. without the archive."""
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        r = subprocess.run(["apt-get", "download", "libopenblas0-pthread"], cwd=tmp, capture_output=True, text=True)
        debs = list(Path(tmp).glob("libopenblas0-pthread_*.deb"))
        if r.returncode != 0 or not debs:
            log(f"  band: OpenBLAS not installed and not downloadable ({(r.stderr or '').strip()[-200:]})")
            return False
        FETCHED.mkdir(parents=True, exist_ok=True)
        subprocess.run(["dpkg-deb", "-x", str(debs[0]), str(FETCHED)], check=True)
        log(f"  band: OpenBLAS unpacked from {debs[0].name} into {FETCHED}")
    return (FETCHED_DIR / "libopenblas.so.0").exists()


def _openblas_dir(log=print, fetch=False):
    """A folder holding libopenblas.so.0: BK_OPENBLAS_DIR, Debian's installed OpenBLAS,
    or Debian's package unpacked into out/openblas (fetched when none is there and
    `fetch`: the bench does, a test does not)."""
    dirs = [os.environ.get("BK_OPENBLAS_DIR")] + OPENBLAS_DIRS + [str(FETCHED_DIR)]
    for d in dirs:
        if d and (Path(d) / "libopenblas.so.0").exists():
            return d
    return str(FETCHED_DIR) if fetch and _fetch_openblas(log) else None


def matrices(log, scenes=SCENES, work=WORK / "band"):
    """{label: matrix file} written by bench/newton_iter.c for each scene."""
    from gen.scene import build, load_index, write_model
    from gen.solver_build import BUILD, VARIANTS, build_solver, compile_object, runtime_headers, runtime_objects
    obj = BUILD / "release" / "bench" / "newton_iter.o"
    compile_object(ROOT / "bench" / "newton_iter.c", obj, VARIANTS["release"], runtime_headers())
    robjs = [o for o in runtime_objects("release") if o.stem != "main"]
    work.mkdir(parents=True, exist_ok=True)
    files = {}
    for label, scene, sets in scenes:
        m = build(ROOT / "models" / f"{scene}.toml", sets)
        exe = build_solver(m["pairs"], BUILD / "release" / "bench" / ("bench_newton_" + "_".join(sorted(m["pairs"]))),
                           load_index(), "release", main_objs=[obj] + robjs)
        model, mat = work / f"{len(files)}.dat", work / f"{len(files)}.bin"
        write_model(m, model)
        r = subprocess.run([str(exe), str(model), "1", str(mat)], capture_output=True, text=True,
                           env=dict(os.environ, OMP_NUM_THREADS="1"))
        if r.returncode != 0:
            raise RuntimeError(f"bench_newton ({scene}) failed: {r.stderr[-500:]}")
        files[label] = mat
    log("  band: matrices written")
    return files


def programs(log=print, fetch=False):
    """{LAPACK name: bench_band executable} (reference LAPACK, and OpenBLAS: installed,
    or Debian's package unpacked into out/openblas)."""
    from gen.solver_build import BUILD, CC, VARIANTS, WARN
    out = BUILD / "release" / "bench"
    out.mkdir(parents=True, exist_ok=True)
    src = [str(ROOT / "bench" / "band_lapack.c"), str(ROOT / "runtime" / "linalg" / "bandlu.c"),
           str(ROOT / "runtime" / "base" / "bigalloc.c")]
    flags = VARIANTS["release"] + WARN + ["-I" + str(ROOT / "runtime")]
    progs = {}
    exe = out / "bench_band_reference"
    subprocess.run([CC] + flags + src + ["-o", str(exe), "-llapack", "-lblas", "-lm"], check=True)
    progs["reference LAPACK 3"] = exe
    d = _openblas_dir(log, fetch)
    if d:
        exe = out / "bench_band_openblas"
        subprocess.run([CC] + flags + src + ["-o", str(exe), f"-L{d}", f"-Wl,-rpath,{d}", "-l:libopenblas.so.0", "-lm"],
                       check=True)
        progs["OpenBLAS"] = exe
    return progs


def band_vs_lapack(quick, log):
    """Rows {problem, lapack, n, kl, ku, band_s, lapack_s, ratio, solution_difference}."""
    mats, progs = matrices(log), programs(log, fetch=True)
    rows = []
    for label, mat in mats.items():
        for lib, exe in progs.items():
            reps = 21 if "1,000" in label else (51 if quick else 401)
            r = subprocess.run([str(exe), str(mat), str(reps)], capture_output=True, text=True,
                               env=dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1"))
            if r.returncode != 0:
                raise RuntimeError(f"bench_band ({label}, {lib}) failed: {r.stderr[-500:]}")
            d = dict(line.split("=", 1) for line in r.stdout.split())
            row = {"problem": label, "lapack": lib, "n": int(d["n"]), "kl": int(d["kl"]), "ku": int(d["ku"]),
                   "band_s": float(d["band_s"]), "lapack_s": float(d["lapack_s"]),
                   "solution_difference": float(d["solution_difference"])}
            row["ratio"] = row["lapack_s"] / row["band_s"]
            rows.append(row)
    log("  band: timed")
    return rows, _openblas_dir() is not None


def markdown(res):
    rows, openblas = res
    L = ["## Band LU against LAPACK", "",
         "One factorization and solve of a Newton matrix, filled from its sparse values as a Newton iteration "
         "does: the runtime's band LU (`runtime/linalg/bandlu.c`: row scaling, threshold pivoting, the forward "
         "substitution during the elimination) against LAPACK's `dgbtrf` + `dgbtrs` on the same band "
         "(`bench/band_lapack.c`), one thread, medians of interleaved calls.", "",
         "| problem | LAPACK | n | kl / ku | band LU | LAPACK | LAPACK / band LU | solutions differ by |",
         "|---|---|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        L.append(f"| {r['problem']} | {r['lapack']} | {r['n']:,} | {r['kl']} / {r['ku']} | {r['band_s'] * 1e6:.1f} µs | "
                 f"{r['lapack_s'] * 1e6:.1f} µs | {r['ratio']:.2f} | {r['solution_difference']:.1e} |")
    faster = all(r["ratio"] > 1 for r in rows)
    L += ["", ("The band LU is the faster on every matrix and stays the solver's."
               if faster else "LAPACK is faster on some matrix above: the solver should take it there."), ""]
    if not openblas:
        L += ["OpenBLAS is neither installed here (Debian `libopenblas-dev`; or `BK_OPENBLAS_DIR`) nor could "
              "Debian's `libopenblas0-pthread` be downloaded into out/openblas: reference LAPACK only.", ""]
    return L


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT))
    print("\n".join(markdown(band_vs_lapack("--quick" in sys.argv, print))))
