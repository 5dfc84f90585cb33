"""The one solver cache: where the solver of a set of element x material pairs
is, and getting it built when it is not current.

A per-scene solver is the runtime plus the kernels of the pairs a scene uses,
so solvers are kept by pair set and build variant: out/bin/solver_HASH
(release), solver_HASH-sanitize, solver_HASH-memcheck, HASH of the sorted pair
names.  One is reused as it is when linked after every file it is made from
(gen/solver_fresh.py), else built (gen/solver_build.py, imported only then).
A process also remembers the solvers it got (a Dask worker keeps them across
the runs it is given) and takes them again while their file is unchanged.
out/bin/SCENE (-sanitize, -memcheck) links to the solver of the scene's last
`./build.sh run`.  The command line, its fast re-run, the Python API, sweeps
and fits all get their solver here (through gen/pipeline.py).  os only at import."""
import os

try:                                   # hashlib's OpenSSL binding alone costs ~5 ms to import
    from _sha256 import sha256
except ImportError:                    # pragma: no cover
    from hashlib import sha256

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(ROOT, "out", "bin")

# Solvers this process has got: {(variant, pair, ...): (path, (size, mtime_ns))}.
_SOLVERS = {}


def _suffix(variant):
    return "" if variant == "release" else f"-{variant}"


def solver_path(pairs, variant="release"):
    """Where the solver of these pairs and this build variant is kept (a str)."""
    tag = sha256("\n".join(sorted(pairs)).encode()).hexdigest()[:16]
    return os.path.join(BIN, f"solver_{tag}{_suffix(variant)}")


def solver(pairs, variant="release", log=None, index=None):
    """The solver (a str) for these pair symbols (e.g. 'ancf3243_svk_full'):
    remembered, found current, or built.  index: out/kernels/index.json as
    gen/scene.load_index reads it (read here when needed).  Numeric overrides
    never change the pairs, so they never rebuild it.  Raises BuildError (and
    SceneError for a missing kernel index)."""
    pairs = sorted(pairs)
    key = (variant,) + tuple(pairs)
    hit = _SOLVERS.get(key)
    if hit is not None:
        try:
            st = os.stat(hit[0])
            if (st.st_size, st.st_mtime_ns) == hit[1]:
                return hit[0]
        except OSError:
            pass
    if index is None:
        from gen.scene import load_index
        index = load_index()
    exe = solver_path(pairs, variant)
    from gen.solver_fresh import linked_after_sources
    if not linked_after_sources(pairs, exe, index, variant):
        from gen.solver_build import build_solver
        exe = str(build_solver(pairs, exe, index, variant, log))
    st = os.stat(exe)
    _SOLVERS[key] = (exe, (st.st_size, st.st_mtime_ns))
    return exe


def link_scene(name, exe, variant="release"):
    """Point out/bin/NAME (-VARIANT) at the solver `exe` (in out/bin), unless it
    does already: the solver of that scene's last run, under the scene's name."""
    link = os.path.join(BIN, name + _suffix(variant))
    target = os.path.basename(exe)
    try:
        if os.readlink(link) == target:
            return
    except OSError:
        pass
    tmp = f"{link}.{os.getpid()}.tmp"
    try:
        os.symlink(target, tmp)
        os.replace(tmp, link)          # atomic: another run may be doing the same
    except OSError:
        try:
            os.unlink(tmp)
        except OSError:
            pass
