"""`./build.sh run` of a scene run before with the same file and the same --set:
the model file of that run is reused and its solver started directly, without
importing the scene compiler (standard library only: os, sys, signal, sha256;
json to print the summary), so that the start-up beyond the solve is a few tens of milliseconds.

A run is "the same" when these are byte-identical: the scene file's path and
contents, every --set, and the state (name, size, modification time) of every
file the model and the solver are made from: gen/ (the scene compiler and the
build rules), runtime/ and out/kernels/.  The solver binary must still be the one
that run used (same size and modification time: a run of the same scene with
other element choices links another binary at the same path).  Anything else, and
every option but --out, --quiet and --verbose, goes through gen/cli.py, which
records a new entry after building (out/cache/run/KEY.run + KEY.dat).  The
reuse skips the scene reader's disk-space check for the output directory; its
warnings were recorded and are printed and added to summary.json as before.

Usage (build.sh): python3 -S -c 'import sys; from gen.fastrun import main;
sys.exit(main(sys.argv[1:]))' run ARGS...  (falls back to gen/cli.py).  Imported,
so that its bytecode is cached (a script is compiled at every start), but not
with -m, which would import importlib.util; with -S, no site packages: the full
path adds them back.  `python3 -S gen/fastrun.py run ARGS...` works the same."""
import os
import sys

try:                                   # the signal module's enum wrappers cost ~5 ms to import
    import _signal as signal
except ImportError:                    # pragma: no cover
    import signal

try:                                   # hashlib's OpenSSL binding alone costs ~5 ms to import
    from _sha256 import sha256
except ImportError:                    # pragma: no cover
    from hashlib import sha256

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if ROOT not in sys.path:               # run as a script: gen/ is importable from the repository
    sys.path.insert(0, ROOT)
from gen.paths import caller_path, prepare_run_dir, scene_location  # noqa: E402
CACHE = os.path.join(ROOT, "out", "cache", "run")
SOURCES = (("gen", True), ("runtime", True), (os.path.join("out", "kernels"), False))
MAX_MODEL_BYTES = 8 << 20          # larger models are not cached (their solve dominates anyway)
MAX_ENTRIES = 400                  # the oldest entries beyond these are removed
PRUNE_SLACK = 40                   # ... when there are this many more
EXIT_SIGNAL = {signal.SIGINT: 130, signal.SIGTERM: 143}


_MEMO = {}                             # the fingerprint this process computed (see main)


def fingerprint_once():
    """fingerprint() of the repository, computed once per process: a run changes
    none of its files (a kernel regenerated meanwhile only makes the entry it
    records miss later)."""
    if "fp" not in _MEMO:
        _MEMO["fp"] = fingerprint()
    return _MEMO["fp"]


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
    h = sha256(b"beamkit-run-cache 1\0")
    h.update(scene.encode() + b"\0" + scene_bytes + b"\0")
    for s in sets:
        h.update(s.encode() + b"\0")
    h.update(fp.encode())
    return h.hexdigest()[:32]


def scene_file(spec):
    """The scene file as gen/cli.py resolves it, or None (then gen/cli.py says why)."""
    p, _ = scene_location(spec, os.path.join(ROOT, "models"))
    return os.path.realpath(p) if os.path.isfile(p) else None


def parse(argv):
    """(scene, sets, out, quiet, verbose) of the argument forms this path takes, else None."""
    scene, sets, out, quiet, verbose = None, [], None, False, False
    i = 0
    while i < len(argv):
        a = argv[i]
        if a in ("--set", "--out") and i + 1 < len(argv):
            if a == "--set":
                sets.append(argv[i + 1])
            else:
                out = argv[i + 1]
            i += 2
            continue
        if a == "--quiet":
            quiet = True
        elif a == "--verbose":
            verbose = True
        elif a.startswith("-") or scene is not None:
            return None                # anything else: the full command line
        else:
            scene = a
        i += 1
    if scene is None or (quiet and verbose):
        return None
    return scene, sets, out, quiet, verbose


def lookup(scene, sets):
    """(cache entry, model bytes) of an identical earlier run, or None."""
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
    except (OSError, ValueError, KeyError, IndexError):
        return None
    if [st.st_size, st.st_mtime_ns] != entry["solver_stat"]:
        return None
    return entry, model


ENTRY_FIELDS = ("version", "scene", "solver", "solver_size", "solver_mtime_ns", "name", "analysis")


def write_entry(e):
    """An entry as text: one `field value` line each, then one line per warning."""
    lines = [f"{f} {e[f]}" for f in ENTRY_FIELDS] + ["warning " + w.replace("\n", " ") for w in e["warnings"]]
    return "\n".join(lines) + "\n"


def read_entry(text):
    e = {"warnings": []}
    for line in text.splitlines():
        f, _, v = line.partition(" ")
        if f == "warning":
            e["warnings"].append(v)
        elif f in ENTRY_FIELDS:
            e[f] = v
    if e.get("version") != "1" or any(f not in e for f in ENTRY_FIELDS):
        raise ValueError("not a run-cache entry")
    e["solver_stat"] = [int(e["solver_size"]), int(e["solver_mtime_ns"])]
    return e


def record(scene, sets, model_path, solver, name, analysis, warnings):
    """Called by gen/cli.py after building: the entry a later identical run reuses.
    Written before the solve (the fingerprint is of the files that made it)."""
    try:
        size = os.path.getsize(model_path)
        if size > MAX_MODEL_BYTES:
            return
        with open(scene, "rb") as fh:
            text = fh.read()
        scene = os.path.realpath(scene)
        k = key(scene, text, list(sets), fingerprint_once())
        os.makedirs(CACHE, exist_ok=True)
        st = os.stat(solver)
        entry = {"version": "1", "scene": scene, "solver": os.path.abspath(solver), "solver_size": st.st_size,
                 "solver_mtime_ns": st.st_mtime_ns, "name": name, "analysis": analysis,
                 "warnings": list(warnings)}
        for ext, data in ((".dat", None), (".run", write_entry(entry))):
            tmp = os.path.join(CACHE, f"{k}{ext}.{os.getpid()}.tmp")
            if data is None:
                with open(model_path, "rb") as src, open(tmp, "wb") as dst:
                    dst.write(src.read())
            else:
                with open(tmp, "w", encoding="utf-8") as fh:
                    fh.write(data)
            os.replace(tmp, os.path.join(CACHE, k + ext))
        prune()
    except OSError:
        pass                           # no cache: the next run takes the full path


def prune(limit=MAX_ENTRIES, slack=PRUNE_SLACK):
    """Remove the least recently written entries beyond `limit`, once there are
    `slack` more than that (the names are listed on every record, the entries'
    times read only then: stat-ing all of them on every run cost ~2 ms)."""
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


def run_solver(cmd):
    """Start the solver; SIGINT and SIGTERM are passed on to it (it stops at its next
    step, keeps its results and exits 130 / 143).  Returns its exit status."""
    pid = None
    pending = []

    def handle(signo, _frame):
        if pid is None:
            pending.append(signo)
        else:
            try:
                os.kill(pid, signo)
            except ProcessLookupError:
                pass

    old = {sg: signal.signal(sg, handle) for sg in EXIT_SIGNAL}
    try:
        pid = os.posix_spawn(cmd[0], cmd, os.environ)
        for sg in pending:
            os.kill(pid, sg)
        _, status = os.waitpid(pid, 0)
    finally:
        for sg, h in old.items():
            signal.signal(sg, h)
    rc = os.waitstatus_to_exitcode(status)
    if rc < 0 and -rc in EXIT_SIGNAL:
        rc = EXIT_SIGNAL[-rc]
    return rc


def fast_run(argv):
    """Exit status of the reused run, or None when this path does not apply."""
    a = parse(argv)
    if a is None:
        return None
    spec, sets, want, quiet, verbose = a
    scene = scene_file(spec)
    if scene is None:
        return None
    hit = lookup(scene, sets)
    if hit is None:
        return None
    entry, model = hit
    out = os.path.normpath(caller_path(want)) if want else os.path.join(ROOT, "out", "runs", entry["name"])
    if prepare_run_dir(out) is not None:
        return None                    # gen/cli.py says why
    if not quiet:
        for w in entry["warnings"]:
            print(f"warning: {entry['name']}: {w}", file=sys.stderr)
        if verbose:
            print("  model and solver of an identical earlier run (out/cache/run/)", file=sys.stderr)
    with open(os.path.join(out, "model.dat"), "wb") as fh:
        fh.write(model)
    cmd = [entry["solver"], os.path.join(out, "model.dat"), out]
    if verbose:
        cmd.append("--verbose")
    elif quiet:
        cmd.append("--quiet")
    rc = run_solver(cmd)
    from gen.run_summary import add_scene_warnings, print_summary
    if rc in EXIT_SIGNAL.values() and not os.path.exists(os.path.join(out, "summary.json")):
        from gen.cli import write_interrupted_summary
        import signal as sigmod
        write_interrupted_summary(out, entry["name"], entry["analysis"],
                                  sigmod.SIGINT if rc == 130 else sigmod.SIGTERM)
    add_scene_warnings(out, entry["warnings"])
    summ = os.path.join(out, "summary.json")
    if not quiet and os.path.exists(summ):
        import json
        with open(summ, encoding="utf-8") as fh:
            print_summary(json.load(fh), out.rstrip("/"))
    return rc


class SiteOnDemand:
    """The last import finder while the site packages are not loaded: the first
    top-level import that the standard library and the repository cannot
    satisfy (sympy to generate a kernel, matplotlib to plot, ...) loads them
    (site.main(), with its .pth files) and is retried; a run that needs none,
    e.g. a scene with new --set numbers and a built solver, never pays for them."""
    names = None                       # top-level names in the site directories (listed once)

    @staticmethod
    def find_spec(name, path=None, target=None):
        if path is not None:           # a submodule: its package was found without the site
            return None
        import site                    # with -S, importing it changes nothing; site.main() does
        if SiteOnDemand.names is None:
            SiteOnDemand.names = set()
            for d in site.getsitepackages() + [site.getusersitepackages()]:
                try:
                    SiteOnDemand.names.update(n.split(".", 1)[0] for n in os.listdir(d))
                except OSError:
                    pass
        if name not in SiteOnDemand.names:   # a probe of the standard library (msvcrt, nt, ...)
            return None
        sys.meta_path.remove(SiteOnDemand)
        site.main()
        from importlib.machinery import PathFinder
        return PathFinder.find_spec(name)


def main(argv):
    if argv and argv[0] == "run":
        rc = fast_run(argv[1:])
        if rc is not None:
            return rc
    if sys.flags.no_site:              # build.sh starts this with -S (15 ms less): the
        sys.meta_path.append(SiteOnDemand)   # site packages come when an import needs them
    import gen.fastrun                 # this script's module is __main__: hand its fingerprint
    gen.fastrun._MEMO.update(_MEMO)    # on to the module gen/cli.py records with
    from gen.cli import main as cli_main
    return cli_main(argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
