"""Command-line front end behind build.sh: run, gen, scenes.

Exit status (also in ./build.sh --help and the README):
  0   success (the solve converged)
  1   bad input: scene file, key or value, output directory (one `error:` line)
  2   the solve did not converge (results of every converged step are kept)
  64  usage error: unknown command or option, missing argument
  99  `run --memcheck`: valgrind reported an error or a leak
  130 interrupted by SIGINT (Ctrl-C), 143 by SIGTERM: results so far are kept and
      summary.json says "interrupted": true
"""
import os
import sys

try:                                   # the signal module's enum wrappers cost ~5 ms to import
    import _signal as signal
except ImportError:                    # pragma: no cover
    import signal

from gen.paths import caller_path, prepare_run_dir, scene_location
from gen.run_summary import add_scene_warnings, print_summary
from gen.scene import ROOT_DIR, SceneError, build, load_index, write_model

# Paths are str on the run path (a run of a built scene imports no pathlib).
MODELS = os.path.join(ROOT_DIR, "models")
RUNS = os.path.join(ROOT_DIR, "out", "runs")
RESULT_FILES = ("summary.json", "sensors.csv", "energy.csv", "modes.csv", "model.dat", "results.pvd")


EXIT_OK, EXIT_INPUT, EXIT_NOT_CONVERGED, EXIT_USAGE, EXIT_MEMCHECK = 0, 1, 2, 64, 99
EXIT_SIGNAL = {signal.SIGINT: 130, signal.SIGTERM: 143}
SIGNAL_NAME = {signal.SIGINT: "SIGINT", signal.SIGTERM: "SIGTERM"}


class UsageError(Exception):
    pass


def Parser(**kw):
    """An argparse parser with usage errors on exit status 64 (sysexits
    EX_USAGE), not 2, which is the status of a solve that did not converge
    (argparse is imported only for the command lines that need it)."""
    import argparse

    class _Parser(argparse.ArgumentParser):
        def error(self, message):
            self.print_usage(sys.stderr)
            print(f"error: {self.prog}: {message}", file=sys.stderr)
            sys.exit(EXIT_USAGE)

    return _Parser(**kw)


def scene_names():
    return sorted(n[:-5] for n in os.listdir(MODELS) if n.endswith(".toml") and not n.startswith("."))


def scene_path(spec):
    """The scene file (a str) of a scene argument, or SceneError."""
    p, named = scene_location(spec, MODELS)
    if not os.path.isfile(p):
        if not named:
            raise SceneError(f"error: {spec}: no such scene file (looked for {p})")
        raise SceneError(f"error: scene {str(spec)!r}: no models/{spec}.toml (scenes: {', '.join(scene_names())})")
    return p


def prepare_out_dir(out, default):
    """Create or reuse an output directory; never mix with foreign files."""
    why = prepare_run_dir(out)
    if why:
        raise SceneError(why)
    return str(out)


def solver_for(model, index, variant="release", log=None):
    """The solver binary (a str) for the model: reused as it is when linked after
    all its sources (gen/solver_fresh.py), else built (gen/solver_build.py)."""
    from gen.solver_fresh import linked_after_sources
    name = model["name"]
    suffix = "" if variant == "release" else f"-{variant}"
    exe = os.path.join(ROOT_DIR, "out", "bin", f"{name}{suffix}")
    if linked_after_sources(sorted(model["pairs"]), exe, index, variant):
        return exe
    from gen.solver_build import build_solver
    return str(build_solver(model["pairs"], exe, index, variant, log))


VALGRIND_SUPPRESSIONS = os.path.join(ROOT_DIR, "runtime", "valgrind.supp")


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
    meshing or the build): no step was taken."""
    path = os.path.join(str(out), "summary.json")
    if os.path.exists(path):
        return
    import json
    sig = SIGNAL_NAME.get(signo, str(signo))
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(json.dumps({
            "scene": name, "analysis": analysis, "converged": False, "interrupted": True, "signal": sig,
            "steps": 0, "newton_iterations": 0, "cutbacks": 0, "wall_s": 0.0, "sensors": {},
            "warnings": [], "error": f"interrupted by {sig} before the solve started"}, indent=1) + "\n")


def _scene_name(path):
    """(name, analysis) of a scene without meshing it."""
    from gen.scene import read_toml, NAME_RE
    try:
        sc = read_toml(path).get("scene", {})
    except SceneError:
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
    130 / 143."""

    def __init__(self):
        self.pid = None

    def __enter__(self):
        self.old = {sg: signal.signal(sg, self._handle) for sg in EXIT_SIGNAL}
        return self

    def __exit__(self, *exc):
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


def execute(scene, sets=(), out=None, variant="release", verbose=False, quiet=True, memcheck=False):
    """Validate, mesh, build and run one scene.  Returns (exit status, out dir as
    a pathlib.Path).  Raises SceneError for bad input.  out: a directory
    (relative paths are the caller's, see gen/paths.py)."""
    from pathlib import Path
    rc, out = _execute(scene, sets, out, variant, verbose, quiet, memcheck)
    return rc, Path(out)


def _execute(scene, sets, out, variant, verbose, quiet, memcheck):
    """execute() with the out dir as a str (the command line's path: no pathlib)."""
    path = scene_path(str(scene))
    want = caller_path(out) if out else None
    out = None
    with _Signals() as sig:
        model = None
        try:
            log = None if quiet else (lambda line: print(line, file=sys.stderr, flush=True))
            model = build(path, sets, log=log, out_dir=want or RUNS)
            if not quiet:
                for w in model.get("warnings", []):
                    print(f"warning: {model['name']}: {w}", file=sys.stderr)
            index = load_index()
            out = prepare_out_dir(want or os.path.join(RUNS, model["name"]), RUNS)
            model_file = os.path.join(out, "model.dat")
            write_model(model, model_file)
            log = None if quiet else (lambda s: print(s, file=sys.stderr))
            try:
                solver = solver_for(model, index, "memcheck" if memcheck else variant, log)
            except _Interrupt:
                raise
            except Exception as e:
                raise SceneError(f"error: building the solver for {path}: {e}")
            if variant == "release" and not memcheck:
                from gen.fastrun import record
                record(str(path), list(sets), model_file, solver, model["name"], model["analysis"],
                       model.get("warnings", []))
        except _Interrupt as e:
            name, analysis = (model["name"], model["analysis"]) if model else _scene_name(path)
            if out is None:                    # interrupted while meshing
                out = prepare_out_dir(want or os.path.join(RUNS, name), RUNS)
            write_interrupted_summary(out, name, analysis, e.signo)
            print(f"interrupted by {SIGNAL_NAME.get(e.signo, e.signo)} before the solve started "
                  f"(summary in {out}/)", file=sys.stderr)
            return EXIT_SIGNAL[e.signo], out
        cmd = [str(solver), os.path.join(out, "model.dat"), out]
        if verbose:
            cmd.append("--verbose")
        elif quiet:
            cmd.append("--quiet")
        if memcheck:
            cmd = memcheck_command(cmd)
        rc = sig.run(cmd)
    if rc in EXIT_SIGNAL.values():
        write_interrupted_summary(out, model["name"], model["analysis"],
                                  signal.SIGINT if rc == 130 else signal.SIGTERM)
    add_scene_warnings(out, model.get("warnings", []))
    return rc, out


def cmd_run(argv):
    from gen.fastrun import parse
    simple = parse(argv)
    if simple is not None:             # the common forms (scene, --set, --out, --quiet or --verbose):
        scene, sets, out, quiet, verbose = simple   # no argument parser to import
        return run_and_report(scene, sets, out, "release", verbose, quiet, False)
    ap = Parser(
        prog="build.sh run",
        description="Build the per-scene solver if stale and run it. Results go to out/runs/SCENE/ "
                    "(summary.json, sensors.csv, model.dat) or to --out DIR.")
    ap.add_argument("scene", help="a name in models/ (without .toml) or a path to a .toml file")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="override a scene value, e.g. material.alu.E=3e7, beam.arm.elements=20 or "
                         "beam.arm.integration=full (arrays of tables are addressed by name or index, "
                         "array entries by index: load.0.value.2=-10); no kernel regeneration")
    ap.add_argument("--out", metavar="DIR", help="output directory (default out/runs/SCENE)")
    ap.add_argument("--quiet", action="store_true", help="print only errors")
    ap.add_argument("--verbose", action="store_true", help="log every load step")
    ap.add_argument("--sanitize", action="store_true",
                    help="build and run the solver with AddressSanitizer and UBSan")
    ap.add_argument("--memcheck", action="store_true",
                    help="build the solver for valgrind (-march=x86-64-v3) and run it under valgrind "
                         "memcheck: any error or leak exits with status 99")
    a = ap.parse_args(argv)
    if a.sanitize and a.memcheck:
        ap.error("--sanitize and --memcheck exclude each other")
    return run_and_report(a.scene, a.set, a.out, "sanitize" if a.sanitize else "release", a.verbose, a.quiet,
                          a.memcheck)


def run_and_report(scene, sets, out, variant, verbose, quiet, memcheck):
    """execute() and the summary on the console; the exit status."""
    try:
        rc, out = _execute(scene, sets, out, variant, verbose, quiet, memcheck)
    except SceneError as e:
        print(str(e), file=sys.stderr)
        return EXIT_INPUT
    summ = os.path.join(out, "summary.json")
    if not quiet and os.path.exists(summ):
        import json
        with open(summ, encoding="utf-8") as fh:
            print_summary(json.load(fh), out)
    return rc


def cmd_scenes(argv):
    try:
        print("\n".join(scene_names()), flush=True)
    except BrokenPipeError:            # `./build.sh scenes | head`: the reader has enough
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    return 0


def main(argv):
    if not argv:
        print("usage: python3 -m gen.cli {run,gen,scenes} ...", file=sys.stderr)
        return EXIT_USAGE
    cmd, rest = argv[0], argv[1:]
    if cmd == "run":
        return cmd_run(rest)
    if cmd == "gen":
        from gen.generate import main as gen_main
        return gen_main(rest)
    if cmd == "scenes":
        return cmd_scenes(rest)
    print(f"error: unknown command {cmd!r}", file=sys.stderr)
    return EXIT_USAGE


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
