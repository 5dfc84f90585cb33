"""What a run reuses instead of redoing: the one solver cache, and the records
of earlier runs that let an identical `./build.sh run` skip the scene compiler.
gen/pipeline.py gets every run's solver here (the command line, its repeated
run, the reports, the Python API, sweeps and fits).  Standard library os only
at import (sha256 from its C module): a repeated run imports neither the scene
compiler nor sympy.

Solvers.  A per-scene solver is the runtime plus the kernels of the element x
material pairs a scene uses, so solvers are kept by pair set and build variant:
out/bin/solver_HASH (release), solver_HASH-sanitize, solver_HASH-memcheck, HASH
of the sorted pair names.  One is reused as it is when linked after every file
it is made from (gen/solver_fresh.py), else built (gen/solver_build.py,
imported only then).  A process also remembers the solvers it got (a Dask
worker keeps them across the runs it is given) and takes them again while
their file is unchanged.  out/bin/SCENE (-sanitize, -memcheck) links to the
solver of the scene's last `./build.sh run`.

Runs.  out/cache/run/KEY.dat is the model file an earlier run wrote, KEY.run
its solver, scene name, analysis, scene warnings and kernel files.  A run is
"the same" when these are byte-identical: the scene file's path and contents,
every --set, and the state (name, size, modification time) of every file of
gen/ (the scene compiler and the build rules) and runtime/; and the files of
out/kernels/ the run was made from are in the state the entry records (the
kernel index the scene compiler reads, and what the solver is linked from:
bk_options.h, the scene's pairs' kernels, the joint and runtime kernels every
solver binds, and their headers, as gen/solver_fresh.py checks them; the
others cannot change the run, and stat-ing all of out/kernels/ was ~0.15 ms of
a repeated run).  The solver binary must still be the one that run used (same
size and modification time: a relinked solver is another binary).
`./build.sh run` finds such a run without Python first (frontend/, a copy
of key(), fingerprint() and the entry format in C; tests/test_run_cached.py
holds the two together): change them together."""
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
    if not linked_after_sources(pairs, exe, index, variant, fp=launcher_fingerprint()):
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


# Records of earlier runs (out/cache/run/).

CACHE = os.path.join(ROOT, "out", "cache", "run")
KERNELS = os.path.join(ROOT, "out", "kernels")
SOURCES = (("gen", True), ("runtime", True))
MAX_MODEL_BYTES = 8 << 20          # larger models are not cached (their solve dominates anyway)
MAX_ENTRIES = 400                  # the oldest entries beyond these are removed
PRUNE_SLACK = 40                   # ... when there are this many more (checked by one record in 16)


_MEMO = {}                             # the fingerprint this process computed


def fingerprint_once():
    """fingerprint() of the repository, computed once per process: a run changes
    none of its files (a kernel regenerated meanwhile only makes the entry it
    records miss later).  The launcher's (launcher_fingerprint) when it started
    this process."""
    if "fp" not in _MEMO:
        _MEMO["fp"] = launcher_fingerprint() or fingerprint()
    return _MEMO["fp"]


def launcher_fingerprint():
    """The fingerprint out/bin/run-cached computed for the key of the run it
    handed to this process (frontend/run_key.c): BK_FINGERPRINT, "PID:" and the
    text with tabs for its NULs, taken (and removed from the environment, so
    that no child inherits it) only when PID is this process's -- the launcher
    execs Python, directly or through build.sh, so the pid is its own; a value
    left in a user's environment names another.  None otherwise.  It saves the
    walk of gen/ and runtime/ (1.8 ms) and the solver's check of runtime/ (1.5 ms)."""
    if "launcher" not in _MEMO:
        text = os.environ.pop("BK_FINGERPRINT", "")
        pid, _, fp = text.partition(":")
        _MEMO["launcher"] = fp.replace("\t", "\0") if fp and pid == str(os.getpid()) else None
    return _MEMO["launcher"]


def fingerprint(root=ROOT, sources=SOURCES):
    """Names, sizes and modification times of the files the model and the solver
    are made from (sorted): any edit, regeneration or checkout changes it."""
    items = []
    cut = len(os.path.join(root, ""))   # paths below root start with root + "/" (os.path.relpath: ~20x slower)

    def walk(d, recursive):
        try:
            with os.scandir(d) as it:
                for e in it:
                    if e.is_dir(follow_symlinks=False):
                        if recursive and e.name != "__pycache__":
                            walk(e.path, True)
                    elif e.is_file():
                        st = e.stat()
                        items.append(f"{e.path[cut:]}\0{st.st_size}\0{st.st_mtime_ns}")
        except FileNotFoundError:
            pass

    for d, rec in sources:
        walk(os.path.join(root, d), rec)
    items.sort()
    return "\n".join(items)


def key(scene, scene_bytes, sets, fp):
    h = sha256(b"beamkit-run-cache 2\0")
    h.update(scene.encode() + b"\0" + scene_bytes + b"\0")
    for s in sets:
        h.update(s.encode() + b"\0")
    h.update(fp.encode())
    return h.hexdigest()[:32]


def lookup(scene, sets):
    """(cache entry, model bytes) of an identical earlier run of the scene file
    `scene` (a real path) with these --set strings, or None."""
    try:
        with open(scene, "rb") as fh:
            text = fh.read()
    except OSError:
        return None
    k = key(scene, text, sets, fingerprint_once())
    try:
        with open(os.path.join(CACHE, k + ".run"), encoding="utf-8") as fh:
            entry = read_entry(fh.read())
        with open(os.path.join(CACHE, k + ".dat"), "rb") as fh:
            model = fh.read()
            st = os.stat(entry["solver"])
        if [st.st_size, st.st_mtime_ns] != entry["solver_stat"]:
            return None
        for name, state in entry["kernels"]:
            st = os.stat(os.path.join(KERNELS, name))
            if [st.st_size, st.st_mtime_ns] != state:
                return None
    except (OSError, ValueError, KeyError, IndexError):
        return None
    return entry, model


ENTRY_FIELDS = ("version", "scene", "solver", "solver_size", "solver_mtime_ns", "name", "analysis")


def write_entry(e):
    """An entry as text: one `field value` line each, then one line per warning
    and one `kernel NAME SIZE MTIME_NS` per kernel file."""
    lines = [f"{f} {e[f]}" for f in ENTRY_FIELDS] + ["warning " + w.replace("\n", " ") for w in e["warnings"]]
    lines += [f"kernel {n} {size} {ns}" for n, (size, ns) in e["kernels"]]
    return "\n".join(lines) + "\n"


def read_entry(text):
    e = {"warnings": [], "kernels": []}
    for line in text.splitlines():
        f, _, v = line.partition(" ")
        if f == "warning":
            e["warnings"].append(v)
        elif f == "kernel":
            n, size, ns = v.split(" ")
            e["kernels"].append((n, [int(size), int(ns)]))
        elif f in ENTRY_FIELDS:
            e[f] = v
    if e.get("version") != "2" or any(f not in e for f in ENTRY_FIELDS) or not e["kernels"]:
        raise ValueError("not a run-cache entry")
    e["solver_stat"] = [int(e["solver_size"]), int(e["solver_mtime_ns"])]
    return e


def kernel_files(exe):
    """The names of the files of out/kernels/ a run with the solver `exe` is made
    from (sorted): the kernel index, and what gen/solver_fresh.py checks the
    solver against (its pairs from its .pairs stamp)."""
    from gen.scene import SceneError, load_index   # (parsed once per index: no json import each run)
    from gen.solver_fresh import BuildError, kernel_files as pair_files, kernel_headers
    with open(exe + ".pairs", encoding="utf-8") as fh:
        pairs = fh.read().split("\n")[2:]
    try:
        index = load_index()
    except SceneError as e:
        raise ValueError(str(e)) from None
    names = {"index.json", "bk_options.h"}
    try:
        files = pair_files([p for p in pairs if p], index)
    except BuildError as e:
        raise ValueError(str(e)) from None
    for f in files:
        src = os.path.join(KERNELS, f)
        names.add(f)
        names.update(os.path.basename(h) for h in kernel_headers(src) if os.path.dirname(h) == KERNELS)
    return sorted(names)


def record(scene, sets, model_path, exe, name, analysis, warnings):
    """The entry a later identical run reuses, written after the model file and
    the solver, before the solve (the fingerprint is of the files that made them)."""
    try:
        size = os.path.getsize(model_path)
        if size > MAX_MODEL_BYTES:
            return
        with open(scene, "rb") as fh:
            text = fh.read()
        scene = os.path.realpath(scene)
        k = key(scene, text, list(sets), fingerprint_once())
        os.makedirs(CACHE, exist_ok=True)
        st = os.stat(exe)
        kernels = []
        for n in kernel_files(exe):
            ks = os.stat(os.path.join(KERNELS, n))
            kernels.append((n, (ks.st_size, ks.st_mtime_ns)))
        entry = {"version": "2", "scene": scene, "solver": os.path.abspath(exe), "solver_size": st.st_size,
                 "solver_mtime_ns": st.st_mtime_ns, "name": name, "analysis": analysis,
                 "warnings": list(warnings), "kernels": kernels}
        for ext, data in ((".dat", None), (".run", write_entry(entry))):
            tmp = os.path.join(CACHE, f"{k}{ext}.{os.getpid()}.tmp")
            if data is None:
                with open(model_path, "rb") as src, open(tmp, "wb") as dst:
                    dst.write(src.read())
            else:
                with open(tmp, "w", encoding="utf-8") as fh:
                    fh.write(data)
            os.replace(tmp, os.path.join(CACHE, k + ext))
        if k.startswith("0"):          # one record in 16 (by key) counts the entries: listing them
            prune()                    # was 0.5 ms of every run with a new --set value
    except (OSError, ValueError, KeyError):
        pass                           # no cache: the next run takes the full path


def prune(limit=MAX_ENTRIES, slack=PRUNE_SLACK):
    """Remove the least recently written entries beyond `limit`, once there are
    `slack` more than that (record() lists the names for one record in 16, the
    entries' times are read only then: stat-ing all of them on every run cost
    ~2 ms, listing them 0.5 ms; the cache holds some 16 entries more on average)."""
    names = [n for n in os.listdir(CACHE) if n.endswith(".run")]
    if len(names) <= limit + slack:
        return
    runs = []
    for n in names:
        try:
            runs.append((os.stat(os.path.join(CACHE, n)).st_mtime_ns, n[:-4]))
        except FileNotFoundError:
            pass
    runs.sort()
    for _, k in runs[:max(0, len(runs) - limit)]:
        for ext in (".run", ".dat"):
            try:
                os.unlink(os.path.join(CACHE, k + ext))
            except FileNotFoundError:
                pass
