"""How `./build.sh run` starts Python: fast enough that a repeated run costs a
few tens of milliseconds beyond the solve.  The run itself is gen/pipeline.py's
(through gen/cli.py): an identical earlier run is reused there without the
scene compiler (gen/run_cache.py); this module only starts the interpreter's
side of it without the site packages.

Usage (build.sh): python3 -S -c 'import sys; from gen.fastrun import main;
sys.exit(main(sys.argv[1:]))' run ARGS...  Imported, so that its bytecode is
cached (a script is compiled at every start), but not with -m, which would
import importlib.util; with -S, no site packages: they are loaded when an
import needs them (SiteOnDemand).  `python3 -S gen/fastrun.py run ARGS...`
works the same."""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if ROOT not in sys.path:               # run as a script: gen/ is importable from the repository
    sys.path.insert(0, ROOT)


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
    if sys.flags.no_site:              # build.sh starts this with -S (15 ms less): the
        sys.meta_path.append(SiteOnDemand)   # site packages come when an import needs them
    from gen.cli import main as cli_main
    return cli_main(argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
