"""The Python side has no import cycle (issue 33: gen/cli.py and gen/fastrun.py
imported each other), and the run pipeline's modules import on their own: a
fresh interpreter each, the command line's without the scene compiler, the
API's without sympy."""
import ast
import subprocess

from util import ENV, PY, ROOT


def import_graph():
    """{module: modules of gen/ and beamkit/ it imports}, imports inside
    functions included (a lazy import closes a cycle too)."""
    mods = {}
    for pkg in ("gen", "beamkit"):
        for p in (ROOT / pkg).rglob("*.py"):
            name = ".".join(p.relative_to(ROOT).with_suffix("").parts)
            mods[name.removesuffix(".__init__")] = p
    graph = {}
    for m, p in mods.items():
        deps = set()
        for n in ast.walk(ast.parse(p.read_text())):
            names = []
            if isinstance(n, ast.Import):
                names = [a.name for a in n.names]
            elif isinstance(n, ast.ImportFrom) and n.module and not n.level:
                names = [n.module] + [f"{n.module}.{a.name}" for a in n.names]
            for x in names:
                while x and x not in mods:
                    x = x.rpartition(".")[0]
                if x and x != m and not m.startswith(x + "."):     # a package's own modules import it
                    deps.add(x)
        graph[m] = deps
    return graph


def cycles(graph):
    """Import cycles: the strongly connected components of more than one module."""
    index, low, stack, on, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                found.append(sorted(comp))

    for v in graph:
        if v not in index:
            visit(v)
    return found


def test_no_import_cycles():
    g = import_graph()
    assert "gen.pipeline" in g["gen.cli"] and "gen.pipeline" in g["beamkit.api"] and "gen.cache" in g["gen.pipeline"]
    assert cycles(g) == []
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


def test_run_pipeline_modules_import_alone():
    light = ("gen.cli", "gen.pipeline", "gen.cache", "gen.solver_fresh", "gen.run_summary")
    for m in light + ("gen.solver_build", "beamkit.api", "beamkit.sweep", "beamkit.fit"):
        heavy = "('sympy', 'gen.scene', 'pathlib')" if m in light else "('sympy',)"
        code = (f"import sys, {m}\n"
                f"bad = [x for x in {heavy} if x in sys.modules]\n"
                f"assert not bad, bad\n")
        opt = ["-S"] if m in light else []          # build.sh run starts without the site packages
        r = subprocess.run([PY] + opt + ["-c", code], capture_output=True, text=True, env=ENV, cwd=ROOT)
        assert r.returncode == 0, (m, r.stderr[-2000:])


def test_run_with_new_set_value_imports_no_slow_stdlib_module(tmp_path):
    """A run that changes only a number (the scene compiled again, the solver
    reused) imports none of the standard library modules whose import alone was
    3-5 ms of it each (re with enum, json, collections, importlib, pathlib): the
    scene compiler and the run cache do without them.  Regression guard of the
    front end's speed; `./build.sh bench` times it."""
    out = tmp_path / "run"
    code = ("import sys\n"
            "from gen.cli import main\n"
            f"rc = main(['run', 'cantilever_bend_100N_nu03', '--quiet', '--out', {str(out)!r}, "
            "'--set', 'material.alu.E=7.2000000123e10'])\n"
            "slow = ('re', 'enum', 'json', 'collections', 'importlib', 'pathlib', 'sympy')\n"
            "print(rc, [m for m in slow if m in sys.modules])\n")
    env = dict(ENV, BK_NO_FAST_RUN="1")
    # the first run may build the solver and parse the scene and kernel index
    # anew (gen/derived.py); the second is the one a user repeats
    for _ in range(2):
        r = subprocess.run([PY, "-S", "-X", "frozen_modules=on", "-c", code], capture_output=True, text=True,
                           env=env, cwd=ROOT)
        assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.split("\n")[0] == "0 []", (r.stdout, r.stderr[-2000:])
    assert (out / "summary.json").exists()
