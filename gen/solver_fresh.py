"""Whether a built solver is current, in os.path only: the run of a built scene
imports this module, not the build rules of gen/solver_build.py (and so not
pathlib, threading and what they import: ~10 ms of a run's start-up).  The
same test gen/solver_build.py makes before it checks each object."""
import os

GEN = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(GEN)
RUNTIME = os.path.join(ROOT, "runtime")
KERNELS = os.path.join(ROOT, "out", "kernels")


class BuildError(Exception):
    pass


# The libraries every solver links (gen/solver_build.py).  SuiteSparse and GSL
# are linked statically (their .a files come with libsuitesparse-dev and
# libgsl-dev): loading their shared objects took 0.4-0.9 ms of each solver
# process here, a fifth of a small scene's run; libgomp, libmvec and libm stay
# shared.
# HDF5 (results.h5, runtime/output/h5.c) likewise: Debian's serial build
# (libhdf5-dev) with its szip and zlib filters.
LIBS = ["-Wl,-Bstatic", "-lklu", "-lldl", "-lamd", "-lcolamd", "-lbtf", "-lsuitesparseconfig", "-lgsl",
        "-lgslcblas", "-lhdf5_serial", "-lsz", "-laec", "-lz", "-Wl,-Bdynamic", "-lm"]
# The lane kernels' vector log, cbrt, pow (out/kernels/*_*.c, `declare simd`): glibc's libmvec.
if os.uname().sysname == "Linux" and os.uname().machine == "x86_64":   # (os.uname: no platform import)
    LIBS.insert(LIBS.index("-lm"), "-lmvec")


def libs(variant):
    """The link line's libraries of a build variant.  Release solvers are linked
    wholly statically (libgomp, libmvec, libm and libc too: their .a files come
    with gcc and libc6-dev): the dynamic loader's work was a quarter millisecond
    of each solver process here (Table 3: 2.48 -> 2.23 ms whole process, 40
    interleaved runs).  The sanitizer and valgrind builds stay dynamic: ASan and
    memcheck's allocator need the shared C library."""
    if variant == "release":
        return ["-static"] + [x for x in LIBS if not x.startswith("-Wl,-B")]
    return list(LIBS)


def stamp_text(variant, pairs):
    """What a solver's .pairs file holds: how it was linked (variant, libraries)
    and for which pairs (sorted)."""
    return variant + "\n" + " ".join(libs(variant)) + "\n" + "\n".join(pairs) + "\n"


def kernel_files(pairs, index):
    """The generated files (names in out/kernels) behind the given pair symbols,
    and the joint kernels every solver binds."""
    files = []
    for p in pairs:
        cands = index["pairs"] + ([index["body"]] if "body" in index else [])     # rigid bodies: index "body"
        match = [x for x in cands if f"{x['element']}_{x['material']}_{x['integration']}" == p]
        if not match:
            raise BuildError(f"no generated kernel {p}")
        for f in match[0]["files"]:
            if f not in files:
                files.append(f)
    for f in index.get("joints", {}).get("files", []):     # every solver binds the joint kernels
        if f not in files:
            files.append(f)
    for f in index.get("runtime", {}).get("files", []):    # and the runtime modules' kernels (contact, ...)
        if f not in files:
            files.append(f)
    return files


def kernel_headers(src):
    """Headers (paths) a generated kernel file `src` includes with "..." (its own,
    its element's, rod_common.h, rod_math.h, bk_kernel.h): an object is stale
    when one is newer."""
    st = os.stat(src)
    memo = (src, st.st_size, st.st_mtime_ns)
    if memo in _HEADERS:                                 # (a run asks twice: freshness, run cache)
        return list(_HEADERS[memo])
    deps = [os.path.splitext(src)[0] + ".h", os.path.join(RUNTIME, "bk_kernel.h"),
            os.path.join(RUNTIME, "bk_joint.h")]
    with open(src, encoding="utf-8") as fh:             # the includes are at the top (files are MBs)
        head = fh.read(8192)
    for line in head.splitlines()[:20]:
        if line.startswith('#include "'):
            h = os.path.join(KERNELS, line.split('"')[1])
            if os.path.exists(h) and h not in deps:
                deps.append(h)
    _HEADERS[memo] = tuple(deps)
    return deps


_HEADERS = {}                          # kernel_headers by (file, size, mtime_ns)


LOCK = os.path.join(ROOT, "out", "build", ".lock")


def runtime_mtimes(fp):
    """Modification times (ns) of runtime/'s sources and gen/solver_build.py
    from a run-cache fingerprint's text (gen/cache.py fingerprint)."""
    out = []
    for item in fp.split("\n"):
        path, _, rest = item.partition("\0")
        name = path.rpartition("/")[2]
        if (path.startswith("runtime/") and name.endswith((".c", ".h")) and not name.startswith(".")) \
                or path == "gen/solver_build.py":
            out.append(int(rest.rpartition("\0")[2]))
    return out


def linked_after_sources(pairs, out_path, index, variant, lock=True, fp=None):
    """The solver at out_path (a str) was linked for these pairs (sorted) and this
    build variant after the last change of every file it is made from (the
    runtime, the pairs' kernels and their headers, the kernel index, the build
    rules): then no object needs checking (what make would conclude, without
    the ~5 ms of checking each object).  Any doubt: False, and the full check
    runs.  lock: hold out/build/.lock shared meanwhile, so that a solver being
    linked by another process (gen/solver_build.py holds it exclusively) is
    not taken for a built one; False from within that lock.  fp: the
    fingerprint of gen/ and runtime/ (gen/cache.py) taken just now, for the
    times of runtime/ and gen/solver_build.py instead of stat-ing them again."""
    if lock:
        import fcntl
        try:
            with open(LOCK, "a") as fh:
                fcntl.flock(fh, fcntl.LOCK_SH)
                return linked_after_sources(pairs, out_path, index, variant, lock=False, fp=fp)
        except OSError:
            return False
    try:
        with open(out_path + ".pairs", encoding="utf-8") as fh:
            if fh.read() != stamp_text(variant, pairs):
                return False
        t = os.stat(out_path).st_mtime_ns
        if fp:
            srcs = []
            if any(ns > t for ns in runtime_mtimes(fp)):
                return False
        else:
            srcs = [os.path.join(d, n) for d, _, names in os.walk(RUNTIME) for n in names
                    if n.endswith((".c", ".h")) and not n.startswith(".")]
            srcs.append(os.path.join(GEN, "solver_build.py"))
        srcs += [os.path.join(KERNELS, "index.json"), os.path.join(KERNELS, "bk_options.h")]
        for f in kernel_files(pairs, index):
            src = os.path.join(KERNELS, f)
            srcs += [src] + kernel_headers(src)
        return all(os.stat(f).st_mtime_ns <= t for f in srcs)
    except (OSError, BuildError):
        return False
