"""Compile per-scene solvers: the runtime plus only the kernels a scene uses.

Objects are cached under out/build/<variant>/ and rebuilt when their source or
any header is newer.  A solver is linked from the runtime objects, the objects
of the element and pair kernels in use, and a generated kernel table naming
the pair descriptors (runtime/bk_kernel.h).
"""
import os
import sys
import threading
from pathlib import Path

from gen.solver_fresh import BuildError, LIBS, kernel_files as _kernel_files, kernel_headers, libs, linked_after_sources
from gen.solver_fresh import stamp_text as _stamp_text

try:                                   # hashlib's OpenSSL binding alone costs ~5 ms to import
    from _sha256 import sha256
except ImportError:                    # pragma: no cover
    from hashlib import sha256

ROOT = Path(__file__).resolve().parent.parent
RUNTIME = ROOT / "runtime"
KERNELS = ROOT / "out" / "kernels"
BUILD = ROOT / "out" / "build"
CC = os.environ.get("CC", "cc")
JOBS = max(1, min(os.cpu_count() or 1, int(os.environ.get("BK_JOBS", "2"))))



def runtime_sources():
    """Every C source of the runtime, in its layer folders (runtime/README.md),
    sorted: an analysis or interaction added as a new file needs no edit here."""
    return sorted(RUNTIME.rglob("*.c"))


def runtime_headers():
    """Every header of the runtime, and the generated option header it includes
    (out/kernels/bk_options.h): an object is stale when one is newer."""
    return sorted(RUNTIME.rglob("*.h")) + [KERNELS / "bk_options.h"]


# Build variants.  The runtime evaluates element kernels in parallel with OpenMP
# (results are bit-identical for any OMP_NUM_THREADS, see runtime/assembly/assembly.c); the
# sanitizer build keeps OpenMP so that it checks the code that runs.
#   release   -O2 -march=native: the instruction set of the machine it is built on
#   sanitize  AddressSanitizer + UBSan (`./build.sh run --sanitize`)
#   memcheck  for valgrind (`./build.sh run --memcheck`, and every test that runs
#             valgrind): valgrind 3.19 cannot decode AVX-512, which -march=native
#             emits on CPUs that have it, so this build is limited to x86-64-v3
#             (AVX2, FMA), which valgrind decodes, whatever the machine.
MEMCHECK_ARCH = "-march=x86-64-v3"
VARIANTS = {
    "release": ["-O2", "-march=native", "-fopenmp"],
    "sanitize": ["-O1", "-g", "-fno-omit-frame-pointer", "-fsanitize=address,undefined",
                 "-fno-sanitize-recover=all", "-fopenmp"],
    "memcheck": ["-O2", "-g", MEMCHECK_ARCH, "-fopenmp"],
}
# Generated kernels are long straight-line functions: debug info for them only
# costs compile time, so the sanitizer build compiles them without -g.
# -fopenmp-simd: the lane kernels' `#pragma omp simd` loops (no OpenMP runtime);
# -ffp-contract=fast (release): fused multiply-adds (ISO C mode turns them off);
# -fno-math-errno: sqrt as an instruction, vectorizable (kernels never read errno).
KERNEL_FLAGS = {
    "release": ["-O2", "-march=native", "-fopenmp-simd", "-ffp-contract=fast", "-fno-math-errno", "-fPIC"],
    "sanitize": ["-O1", "-fno-omit-frame-pointer", "-fsanitize=address,undefined",
                 "-fno-sanitize-recover=all", "-fopenmp-simd"],
    "memcheck": ["-O2", MEMCHECK_ARCH, "-fopenmp-simd", "-fno-math-errno", "-fPIC"],
}
WARN = ["-std=c11", "-D_POSIX_C_SOURCE=200809L", "-Wall", "-Wextra"]
INCLUDES = ["-I" + str(RUNTIME), "-I" + str(KERNELS), "-I/usr/include/suitesparse"]


class _BuildLock:
    """One build at a time in out/build (tests run on several workers, users in
    several terminals): an exclusive lock on out/build/.lock while objects are
    compiled and solvers linked.  Re-entrant within a process."""
    _depth = 0
    _fh = None
    _mutex = threading.RLock()

    def __enter__(self):
        import fcntl
        _BuildLock._mutex.acquire()
        if _BuildLock._depth == 0:
            BUILD.mkdir(parents=True, exist_ok=True)
            _BuildLock._fh = open(BUILD / ".lock", "w")
            fcntl.flock(_BuildLock._fh, fcntl.LOCK_EX)
        _BuildLock._depth += 1
        return self

    def __exit__(self, *exc):
        import fcntl
        _BuildLock._depth -= 1
        if _BuildLock._depth == 0:
            fcntl.flock(_BuildLock._fh, fcntl.LOCK_UN)
            _BuildLock._fh.close()
            _BuildLock._fh = None
        _BuildLock._mutex.release()
        return False


build_lock = _BuildLock


def _newest(paths):
    return max((p.stat().st_mtime for p in paths if p.exists()), default=0.0)


def _flags_stamp(obj):
    return obj.with_name(obj.name + ".flags")


def _stale(src, obj, deps, flags=None):
    """An object is stale when older than its source or a dependency, or (when
    flags are given) compiled with other flags than these."""
    if not (obj.exists() and obj.stat().st_mtime >= max(src.stat().st_mtime, _newest(deps))):
        return True
    if flags is not None:
        st = _flags_stamp(obj)
        return not st.exists() or st.read_text() != " ".join(flags)
    return False


def _compile_many(jobs, log):
    """Compile (src, obj, flags, deps) jobs that are stale, two at a time, the
    largest source first (so that the jobs end close together)."""
    todo = [j for j in jobs if _stale(j[0], j[1], j[3], j[2])]
    todo.sort(key=lambda j: -j[0].stat().st_size)
    if not todo:
        return
    from concurrent.futures import ThreadPoolExecutor      # 8 ms: only when compiling
    with ThreadPoolExecutor(max_workers=min(JOBS, len(todo))) as ex:
        for f in [ex.submit(_compile, *j, log) for j in todo]:
            f.result()


def compile_object(src, obj, flags, deps, log=None):
    """Compile C source `src` to object `obj` with `flags` (plus the project's
    warnings and include paths) unless it is fresh: newer than src and every
    path in deps, and compiled with the same flags.  Returns True if compiled;
    raises BuildError with the compiler's messages."""
    with _BuildLock():
        return _compile(src, obj, flags, deps, log)


def _compile(src, obj, flags, deps, log):
    if not _stale(src, obj, deps, flags):
        return False
    obj.parent.mkdir(parents=True, exist_ok=True)
    cmd = [CC] + WARN + flags + INCLUDES + ["-c", str(src), "-o", str(obj)]
    if log:
        log(f"  cc {src.relative_to(ROOT)}")
    import subprocess                  # only when something is compiled (a run of a built solver needs none)
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise BuildError(f"compiling {src}:\n{r.stderr}")
    if r.stderr.strip():
        sys.stderr.write(r.stderr)
    _flags_stamp(obj).write_text(" ".join(flags))
    return True


def runtime_objects(variant="release", log=None, extra_sources=()):
    """Objects of the runtime sources (and extra_sources in runtime/) for a variant."""
    with _BuildLock():
        return _runtime_objects(variant, log, extra_sources)


def _runtime_objects(variant, log, extra_sources):
    flags = VARIANTS[variant]
    headers = runtime_headers()
    jobs = []
    for src in runtime_sources() + [RUNTIME / name for name in extra_sources]:
        obj = BUILD / variant / "runtime" / (src.stem + ".o")
        jobs.append((src, obj, flags, headers))
    _compile_many(jobs, log)
    return [j[1] for j in jobs]


def _kernel_headers(src):
    """gen/solver_fresh.kernel_headers as Paths."""
    return [Path(h) for h in kernel_headers(str(src))]


def kernel_objects(pairs, index, variant="release", log=None):
    """Objects for the element and pair files behind the given pair symbols
    (e.g. 'ancf3243_svk_full')."""
    with _BuildLock():
        return _kernel_objects(pairs, index, variant, log)


def _kernel_objects(pairs, index, variant, log):
    flags = KERNEL_FLAGS[variant]
    files = _kernel_files(pairs, index)
    jobs = []
    for f in files:
        src = KERNELS / f
        if not src.exists():
            raise BuildError(f"{src} is missing: run ./build.sh gen")
        obj = BUILD / variant / "kernels" / (Path(f).stem + ".o")
        jobs.append((src, obj, flags, _kernel_headers(src)))
    _compile_many(jobs, log)
    return [j[1] for j in jobs]


def kernel_table_source(pairs, version):
    """The kernel table of one solver: the pair descriptors it links.  `version`
    is the kernel header version the kernels were generated for (index.json
    "kernel_version"); the table does not compile against another header."""
    if not isinstance(version, int):
        raise BuildError("out/kernels/index.json states no kernel_version: regenerate with ./build.sh gen")
    lines = ['/* kernel table of one solver -- generated by gen/solver_build.py */',
             '#include "bk_kernel.h"',
             f"#if !defined(BK_KERNEL_VERSION) || BK_KERNEL_VERSION != {version}",
             f'#error "out/kernels was generated for runtime/bk_kernel.h version {version}: '
             'regenerate with ./build.sh gen"',
             "#endif"]
    lines += [f"extern const bk_pair bk_pair_{p};" for p in pairs]
    lines.append("const bk_pair *const bk_linked_pairs[] = {" +
                 ", ".join(f"&bk_pair_{p}" for p in pairs) + "};")
    lines.append(f"const int bk_nlinked_pairs = {len(pairs)};")
    return "\n".join(lines) + "\n"


def build_solver(pairs, out_path, index, variant="release", log=None, main_objs=None, extra_flags=()):
    """Link a solver for the given pairs at out_path (rebuilt only when stale)."""
    with _BuildLock():
        return _build_solver(pairs, out_path, index, variant, log, main_objs, extra_flags)


def _build_solver(pairs, out_path, index, variant, log, main_objs, extra_flags):
    pairs = sorted(pairs)
    if main_objs is None and not extra_flags and linked_after_sources(pairs, str(out_path), index, variant, lock=False):
        return Path(out_path)
    key = sha256((variant + "\n" + "\n".join(pairs)).encode()).hexdigest()[:16]
    tdir = BUILD / variant / "tables"
    tdir.mkdir(parents=True, exist_ok=True)
    tsrc = tdir / f"table_{key}.c"
    text = kernel_table_source(pairs, index.get("kernel_version"))
    if not tsrc.exists() or tsrc.read_text() != text:
        tsrc.write_text(text)
    tobj = tsrc.with_suffix(".o")
    _compile(tsrc, tobj, VARIANTS[variant], [RUNTIME / "bk_kernel.h"], log)
    objs = (main_objs if main_objs is not None else runtime_objects(variant, log)) + \
        kernel_objects(pairs, index, variant, log) + [tobj]
    out_path = Path(out_path)
    stamp = out_path.with_name(out_path.name + ".pairs")
    stamp_text = _stamp_text(variant, pairs)
    fresh = (out_path.exists() and stamp.exists() and stamp.read_text() == stamp_text
             and out_path.stat().st_mtime >= _newest(objs))
    if fresh:
        if main_objs is None and not extra_flags:
            os.utime(out_path)         # checked against every object now: the quick test above holds next time
        return out_path
    out_path.parent.mkdir(parents=True, exist_ok=True)
    cmd = [CC] + VARIANTS[variant] + list(extra_flags) + [str(o) for o in objs] + ["-o", str(out_path)] + libs(variant)
    if log:
        log(f"  link {out_path.relative_to(ROOT) if out_path.is_relative_to(ROOT) else out_path}")
    import shlex
    import subprocess
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise BuildError(f"linking {out_path}:\n{r.stderr}\ncommand: {shlex.join(cmd)}")
    stamp.write_text(stamp_text)
    return out_path
