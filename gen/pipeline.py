"""Run a scene: the one run pipeline behind `./build.sh run` (gen/cli.py, also
when it repeats an identical run) and the Python API (beamkit/api.py, and so
sweeps and fits).  run() is that function (with where a run's paths point: the
caller's paths, the scene file, the run directory it prepares):

    scene + overrides -> model file: an identical earlier run's (gen/cache.py,
        without the scene compiler) or the scene compiler's (gen/scene/)
    -> the solver of its element x material pairs (gen/cache.py, the one
       solver cache) -> the solver run in the output directory -> results there

At import the standard library's os and sys only (and _signal), so that a
repeated run imports neither the scene compiler nor sympy (gen/run_summary.py
only for a scene with warnings); the scene compiler
is imported when a model must be built (and to raise its SceneError)."""
import os
import sys

try:                                   # the signal module's enum wrappers cost ~5 ms to import
    import _signal as signal
except ImportError:                    # pragma: no cover
    import signal

from gen import cache

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = os.path.join(ROOT, "models")
RUNS = os.path.join(ROOT, "out", "runs")
EXIT_MEMCHECK = 99
EXIT_SIGNAL = {signal.SIGINT: 130, signal.SIGTERM: 143}
SIGNAL_NAME = {signal.SIGINT: "SIGINT", signal.SIGTERM: "SIGTERM"}
VALGRIND_SUPPRESSIONS = os.path.join(ROOT, "runtime", "valgrind.supp")
REUSED = "  model and solver of an identical earlier run (out/cache/run/)"


# Paths given on the command line are the caller's: build.sh changes to the
# repository and passes the caller's working directory in BK_CALLER_CWD.
MARKER = ".beamkit-run"            # in every directory made by ./build.sh run
MARKER_TEXT = b"results of ./build.sh run; cleared on the next run into this directory\n"


def caller_path(p):
    """p (a str) as the user meant it: absolute, or relative to the caller's directory."""
    p = os.path.expanduser(str(p))
    return p if os.path.isabs(p) else os.path.join(os.environ.get("BK_CALLER_CWD") or os.getcwd(), p)


def user_path(p):
    """caller_path as a pathlib.Path."""
    from pathlib import Path
    return Path(caller_path(p))


def scene_location(spec, models):
    """(path, is a name in models/) of a scene argument: a `.toml` file or a path
    with a `/` is the caller's, anything else models/SPEC.toml."""
    spec = str(spec)
    if spec.endswith(".toml") or "/" in spec:
        return caller_path(spec), False
    return os.path.join(str(models), f"{spec}.toml"), True


def prepare_run_dir(out):
    """Create or clear a results directory (never one with foreign files) and mark
    it as made by ./build.sh run.  Returns None, or why it cannot be used."""
    out = str(out)
    if os.path.exists(out):
        if not os.path.isdir(out):
            return f"error: --out {out}: exists and is not a directory"
        entries = os.listdir(out)
        if entries and not os.path.exists(os.path.join(out, MARKER)):
            return (f"error: --out {out}: directory exists, is not empty and was not made by "
                    f"./build.sh run; choose a new or empty directory")
        for e in entries:
            p = os.path.join(out, e)
            if e == MARKER:
                continue
            if os.path.isdir(p) and not os.path.islink(p):
                import shutil
                shutil.rmtree(p)
            else:
                os.unlink(p)
    else:
        os.makedirs(out)
    marker = os.path.join(out, MARKER)
    try:                               # kept when it holds its text (truncating a file costs ext4 ~0.25 ms)
        with open(marker, "rb") as fh:
            if fh.read(len(MARKER_TEXT) + 1) == MARKER_TEXT:
                return None
    except OSError:
        pass
    with open(marker, "wb") as fh:
        fh.write(MARKER_TEXT)
    return None


def scene_error():
    """gen/scene's SceneError (bad input), importing the scene compiler only now:
    `except scene_error()` is evaluated only when an exception gets there."""
    from gen.scene import SceneError
    return SceneError


def scene_names():
    return sorted(n[:-5] for n in os.listdir(MODELS) if n.endswith(".toml") and not n.startswith("."))


def scene_path(spec):
    """The scene file (a str) of a scene argument, or SceneError."""
    p, named = scene_location(spec, MODELS)
    if not os.path.isfile(p):
        if not named:
            raise scene_error()(f"error: {spec}: no such scene file (looked for {p})")
        import difflib
        names = scene_names()
        near = difflib.get_close_matches(str(spec), names, n=3, cutoff=0.75)
        raise scene_error()(f"error: scene {str(spec)!r}: no models/{spec}.toml; "
                            + (f"did you mean {' or '.join(near)}? (./build.sh scenes lists all {len(names)})"
                               if near else f"expected one of: {', '.join(names)}"))
    return p


def prepare_out_dir(out):
    """Create or reuse an output directory (a str); never mix with foreign files."""
    why = prepare_run_dir(out)
    if why:
        raise scene_error()(why)
    return str(out)


def memcheck_command(solver_cmd):
    """valgrind memcheck around a solver command: every error and every leak kind
    fails the run with status 99 (libgomp's own start-up allocation, reachable
    until exit, is suppressed by runtime/valgrind.supp).  The solver must be the
    `memcheck` build (gen/solver_build.py): valgrind cannot decode AVX-512."""
    return ["valgrind", "--tool=memcheck", f"--error-exitcode={EXIT_MEMCHECK}", "--leak-check=full",
            "--errors-for-leak-kinds=all", "--show-leak-kinds=all",
            f"--suppressions={VALGRIND_SUPPRESSIONS}"] + list(solver_cmd)


def write_interrupted_summary(out, name, analysis, signo):
    """summary.json of a run interrupted before the solver wrote one (during
    meshing or the build): no step was taken.  True when it wrote one."""
    path = os.path.join(str(out), "summary.json")
    if os.path.exists(path):
        return False
    import json
    sig = SIGNAL_NAME.get(signo, str(signo))
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(json.dumps({
            "scene": name, "analysis": analysis, "converged": False, "interrupted": True, "signal": sig,
            "steps": 0, "newton_iterations": 0, "cutbacks": 0, "wall_s": 0.0, "sensors": {},
            "warnings": [], "error": f"interrupted by {sig} before the solve started"}, indent=1) + "\n")
    return True


def _scene_name(path):
    """(name, analysis) of a scene without meshing it."""
    from gen.scene import read_toml, NAME_RE
    try:
        sc = read_toml(path).get("scene", {})
    except scene_error():
        sc = {}
    name = (sc.get("name") if isinstance(sc.get("name"), str) and NAME_RE.match(sc["name"])
            else os.path.splitext(os.path.basename(str(path)))[0])
    an = sc.get("analysis") if isinstance(sc.get("analysis"), str) else "static"
    return name, an


class _Interrupt(Exception):
    def __init__(self, signo):
        self.signo = signo


class _Signals:
    """SIGINT and SIGTERM during a run: before the solver starts they raise
    _Interrupt (meshing and the build stop at once); while it runs they are
    passed on to it, and it stops at its next step, keeps its results and exits
    130 / 143.  Not entered for the API (captured runs): a Dask worker runs
    them on threads, which cannot set signal handlers."""

    def __init__(self, active=True):
        self.pid = None
        self.active = active

    def __enter__(self):
        if self.active:
            self.old = {sg: signal.signal(sg, self._handle) for sg in EXIT_SIGNAL}
        return self

    def __exit__(self, *exc):
        if self.active:
            for sg, h in self.old.items():
                signal.signal(sg, h)
        return False

    def _handle(self, signo, _frame):
        if self.pid is None:
            raise _Interrupt(signo)
        try:
            os.kill(self.pid, signo)
        except ProcessLookupError:
            pass

    def run(self, cmd):
        self.pid = os.posix_spawnp(cmd[0], cmd, os.environ)   # cheaper than fork + exec of this process
        _, status = os.waitpid(self.pid, 0)
        rc = os.waitstatus_to_exitcode(status)
        if rc < 0 and -rc in EXIT_SIGNAL:      # the solver died of the signal itself
            rc = EXIT_SIGNAL[-rc]
        return rc


class Outcome:
    """What run() did: rc (the solver's exit status, or 130 / 143 when
    interrupted before it started), out (the output directory, a str), name,
    analysis, warnings (the scene reader's), stderr (the solver's, when
    captured), reused (the model and solver of an identical earlier run)."""
    __slots__ = ("rc", "out", "name", "analysis", "warnings", "stderr", "reused")

    def __init__(self, rc, out, name, analysis, warnings, stderr=None, reused=False):
        self.rc, self.out, self.name, self.analysis = rc, out, name, analysis
        self.warnings, self.stderr, self.reused = warnings, stderr, reused


def _stderr_line(line):
    print(line, file=sys.stderr, flush=True)


def _print_warnings(name, warnings):
    for w in warnings:
        print(f"warning: {name}: {w}", file=sys.stderr)


def _reuse(path, sets, out, quiet, verbose):
    """(entry, out dir) of an identical earlier run, its model file written into
    the output directory; None when there is none or the directory is not
    usable (the full path then says why)."""
    hit = cache.lookup(os.path.realpath(path), sets)
    if hit is None:
        return None
    entry, model = hit
    dest = os.path.normpath(out) if out else os.path.join(RUNS, entry["name"])
    if prepare_run_dir(dest) is not None:
        return None
    if not quiet:
        _print_warnings(entry["name"], entry["warnings"])
        if verbose:
            print(REUSED, file=sys.stderr)
    with open(os.path.join(dest, "model.dat"), "wb") as fh:
        fh.write(model)
    return entry, dest


def _build(path, sets, out, doc, name, variant, quiet, console, base=None):
    """Mesh the scene (the scene compiler), write model.dat into the output
    directory and get the solver: (model, out dir, solver)."""
    from gen.scene import build, write_model
    log = _stderr_line if console and not quiet else None
    model = build(path, sets, name=name, log=log, out_dir=out or RUNS, doc=doc, base=base)
    if console and not quiet:
        _print_warnings(model["name"], model.get("warnings", []))
    dest = prepare_out_dir(out or os.path.join(RUNS, model["name"]))
    write_model(model, os.path.join(dest, "model.dat"))
    try:
        exe = cache.solver(model["pairs"], variant, log)
    except _Interrupt:
        raise
    except Exception as e:
        raise scene_error()(f"error: building the solver for {path}: {e}")
    return model, dest, exe


def run(scene, sets=(), out=None, *, doc=None, name=None, variant="release", memcheck=False, verbose=False,
        quiet=True, threads=None, capture=False, reuse=False, remember=False, base=None):
    """Run one scene; returns an Outcome, raises SceneError for bad input (the
    one-line `error:` message of the command line).

    scene: a name in models/ or a scene file's path (the caller's, caller_path);
    with doc (the scene's tables, parsed TOML) only its label in messages;
    base: the directory of its relative data paths (default the scene file's).
    sets: `--set` strings.  out: the output directory (a str as the caller
    means it; default out/runs/NAME).  variant: the solver build, release or
    sanitize; memcheck: the memcheck build run under valgrind.  verbose / quiet:
    the solver's --verbose / --quiet.
    capture: the API's run: the solver's stderr captured (stdout dropped unless
    verbose), OMP_NUM_THREADS=threads, no messages and no signal handling of
    this process; else the command line's: messages on stderr, the solver on
    the terminal, SIGINT / SIGTERM passed on.
    reuse: take the model file and solver of an identical earlier run without
    the scene compiler (a release run of a scene file).  remember: record this
    run for that (release) and link out/bin/NAME to its solver."""
    if memcheck:
        variant = "memcheck"
    sets = list(sets)
    path = scene if doc is not None else scene_path(scene)
    console = not capture
    with _Signals(active=console) as sig:
        model = dest = None
        try:
            hit = _reuse(path, sets, out, quiet, verbose) if reuse and doc is None and variant == "release" else None
            if hit is not None:
                entry, dest = hit
                exe, run_name, analysis, warnings = entry["solver"], entry["name"], entry["analysis"], \
                    entry["warnings"]
            else:
                model, dest, exe = _build(path, sets, out, doc, name, variant, quiet, console, base)
                run_name, analysis, warnings = model["name"], model["analysis"], model.get("warnings", [])
                # a scene that reads data files (CSV paths, tables) is compiled anew each run:
                # the run cache keys on the scene file and the --sets alone
                if remember and variant == "release" and not model.get("inputs"):
                    cache.record(str(path), sets, os.path.join(dest, "model.dat"), exe, run_name, analysis,
                                     warnings)
            if remember:
                cache.link_scene(run_name, exe, variant)
        except _Interrupt as e:
            run_name, analysis = (model["name"], model["analysis"]) if model else _scene_name(path)
            if dest is None:                   # interrupted while meshing
                dest = prepare_out_dir(out or os.path.join(RUNS, run_name))
            write_interrupted_summary(dest, run_name, analysis, e.signo)
            print(f"interrupted by {SIGNAL_NAME.get(e.signo, e.signo)} before the solve started "
                  f"(summary in {dest}/)", file=sys.stderr)
            return Outcome(EXIT_SIGNAL[e.signo], dest, run_name, analysis, [])
        cmd = [exe, os.path.join(dest, "model.dat"), dest]
        if verbose:
            cmd.append("--verbose")
        elif quiet:
            cmd.append("--quiet")
        if memcheck:
            cmd = memcheck_command(cmd)
        stderr = None
        if capture:
            rc, stderr = _captured(cmd, verbose, threads)
        else:
            if threads:                # (the command line's process: its environment is the solver's)
                os.environ["OMP_NUM_THREADS"] = str(int(threads))
            rc = sig.run(cmd)
    # (the solver lists the scene's warnings in its summary.json: they travel in the model file)
    if console and rc in EXIT_SIGNAL.values() and \
            write_interrupted_summary(dest, run_name, analysis, signal.SIGINT if rc == 130 else signal.SIGTERM) \
            and warnings:
        from gen.run_summary import add_scene_warnings
        add_scene_warnings(dest, warnings)
    return Outcome(rc, dest, run_name, analysis, warnings, stderr, hit is not None)


def _captured(cmd, verbose, threads):
    """The solver run for the API: (exit status, its stderr)."""
    import subprocess
    env = dict(os.environ, OMP_NUM_THREADS=str(int(threads))) if threads else None
    r = subprocess.run(cmd, stdout=None if verbose else subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                       env=env)
    return r.returncode, r.stderr
