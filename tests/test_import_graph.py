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
