"""Command-line front end behind build.sh: run, gen, scenes (a run itself is
gen/pipeline.py's run()).

`./build.sh run` starts it as python3 -S -c 'import sys; from gen.cli import
run_command; run_command(sys.argv[1:])' run ARGS...: imported, so that its bytecode
is cached (a script is compiled at every start), but not with -m, which would
import importlib.util; with -S, no site packages: they are loaded when an
import needs them (SiteOnDemand), and a repeated run, or one with new --set
numbers and a built solver, needs none.

Exit status (also in ./build.sh --help and docs/reference/commands.md):
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

from gen import pipeline
from gen.pipeline import MODELS, caller_path, scene_error, scene_names

EXIT_OK, EXIT_INPUT, EXIT_NOT_CONVERGED, EXIT_USAGE = 0, 1, 2, 64   # 99, 130, 143: gen/pipeline.py


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

    kw.setdefault("allow_abbrev", False)         # --thread is not --threads: unknown options exit 64
    return _Parser(**kw)


def execute(scene, sets=(), out=None, variant="release", verbose=False, quiet=True, memcheck=False):
    """A run as `./build.sh run` makes it (gen/pipeline.py run(), recorded for an
    identical run later); the reports' entry.  Returns (exit status, out dir as
    a pathlib.Path).  Raises SceneError for bad input.  out: a directory
    (relative paths are the caller's, see gen/pipeline.py caller_path)."""
    from pathlib import Path
    res = _run(scene, sets, out, variant, verbose, quiet, memcheck, reuse=False)
    return res.rc, Path(res.out)


def _run(scene, sets, out, variant, verbose, quiet, memcheck, reuse, threads=None):
    return pipeline.run(str(scene), sets, caller_path(out) if out else None, variant=variant, memcheck=memcheck,
                        verbose=verbose, quiet=quiet, reuse=reuse, remember=True, threads=threads)


def parse(argv):
    """(scene, sets, out, quiet, verbose, threads) of the common argument forms
    (scene, --set, --out, --threads N, --quiet or --verbose), which need no
    argument parser; else None."""
    scene, sets, out, quiet, verbose, threads = None, [], None, False, False, None
    i = 0
    while i < len(argv):
        a = argv[i]
        if a in ("--set", "--out", "--threads") and i + 1 < len(argv):
            if a == "--set":
                sets.append(argv[i + 1])
            elif a == "--out":
                out = argv[i + 1]
            elif argv[i + 1].isdigit() and 1 <= int(argv[i + 1]) <= 1024:
                threads = int(argv[i + 1])
            else:
                return None                # the parser says what is wrong
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
    return scene, sets, out, quiet, verbose, threads


def _thread_count(text):
    """--threads N: an integer from 1 to 1024."""
    import argparse
    if not text.isdigit() or not 1 <= int(text) <= 1024:
        raise argparse.ArgumentTypeError(f"expected an integer from 1 to 1024, found {text!r}")
    return int(text)


def cmd_run(argv):
    simple = parse(argv)
    if simple is not None:             # the common forms: no argument parser to import, and an
        scene, sets, out, quiet, verbose, threads = simple   # identical earlier run is reused
        return run_and_report(scene, sets, out, "release", verbose, quiet, False, reuse=True, threads=threads)
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
    ap.add_argument("--threads", type=_thread_count, metavar="N",
                    help="OpenMP threads of the solver's element evaluation (default: every core); results "
                         "are the same bits for any N")
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
                          a.memcheck, threads=a.threads)


def run_and_report(scene, sets, out, variant, verbose, quiet, memcheck, reuse=False, threads=None):
    """The run and its summary on the console; the exit status."""
    try:
        res = _run(scene, sets, out, variant, verbose, quiet, memcheck, reuse, threads)
    except scene_error() as e:
        print(str(e), file=sys.stderr)
        return EXIT_INPUT
    summ = os.path.join(res.out, "summary.json")
    if not quiet and os.path.exists(summ):
        import json
        from gen.run_summary import print_summary
        with open(summ, encoding="utf-8") as fh:
            print_summary(json.load(fh), res.out.rstrip("/") if res.reused else res.out)
    return res.rc


def _description(name):
    """The scene's [scene] description (empty when it has none or cannot be read)."""
    from gen.scene.files import read_toml
    try:
        scene = read_toml(os.path.join(MODELS, f"{name}.toml")).get("scene")
    except scene_error():
        return ""
    d = scene.get("description", "") if isinstance(scene, dict) else ""
    return d if isinstance(d, str) else ""


def cmd_scenes(argv):
    try:
        names = scene_names()
        width = max(map(len, names), default=0)
        print("\n".join(f"{n:<{width}}  {_description(n)}".rstrip() for n in names), flush=True)
    except BrokenPipeError:            # `./build.sh scenes | head`: the reader has enough
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    return 0


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
    if sys.flags.no_site and SiteOnDemand not in sys.meta_path:   # build.sh run: -S (15 ms less)
        sys.meta_path.append(SiteOnDemand)
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


def run_command(argv):
    """main(argv), then the process ends at once with its status: stdout and
    stderr flushed, the interpreter's teardown of its ~50 modules skipped (3 ms
    of a run with a new --set value here; the command needs none of it: no
    atexit handler, no thread left running, every file it wrote closed).  A
    failed flush (a closed pipe) and an exception leave by the usual exit.
    build.sh run and frontend/python_start.c start the front end with this."""
    rc = main(argv)
    try:
        sys.stdout.flush()
        sys.stderr.flush()
    except Exception:
        sys.exit(rc)
    os._exit(rc)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
