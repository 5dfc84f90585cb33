"""A scene fuzzer: mutates the scenes in models/ (deleted keys, wrong types,
NaN/Inf, zero/negative/huge numbers, empty arrays, unknown enum values,
duplicated names, truncated and binary files), validates each mutant in
process, and runs the accepted ones through the sanitizer build of the solver.

Outcome classes: rejected (SceneError: one line `error: FILE: KEY: ...`),
solved (exit 0), failed cleanly (exit 2, with an error line), crashed (a Python
exception, a signal, a sanitizer report, an unexpected exit status, or more
than one error line), hung (timeout).

usage: python3 tests/fuzz_scenes.py [COUNT] [SEED]
"""
import copy
import math
import random
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))

from gen.scene import SceneError, build, load_index, write_model  # noqa: E402

# Seeds that run quickly (static scenes, short dynamics, modal).
SEEDS = ["cantilever_bend_10N", "cantilever_axial_1kN_free_section", "cantilever_rollup",
         "cantilever_bend3d_50N", "pendulum_soft_gef", "cantilever_modal", "silicone_fall_damped",
         "double_pendulum_soft_ancf", "cantilever_gravity"]
ENUM_KEYS = {"element", "law", "type", "shape", "analysis", "integration", "cross_section", "distribution",
             "about", "material", "section", "a", "b", "at", "name"}


def dump(doc):
    """TOML text of a scene document (tables, arrays of tables, scalars, arrays)."""
    def val(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, int):
            return str(v)
        if isinstance(v, float):
            if math.isnan(v):
                return "nan"
            if math.isinf(v):
                return "inf" if v > 0 else "-inf"
            return repr(v)
        if isinstance(v, str):
            return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
        if isinstance(v, list):
            return "[" + ", ".join(val(x) for x in v) + "]"
        if isinstance(v, dict):
            return "{" + ", ".join(f"{k} = {val(x)}" for k, x in v.items()) + "}"
        raise TypeError(type(v))
    out = []
    for k, v in doc.items():
        if isinstance(v, dict) and v and all(isinstance(x, dict) for x in v.values()):
            for sub, t in v.items():
                out.append(f"[{k}.{sub}]")
                out += [f"{kk} = {val(vv)}" for kk, vv in t.items()]
        elif isinstance(v, dict):
            out.append(f"[{k}]")
            out += [f"{kk} = {val(vv)}" for kk, vv in v.items()]
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for t in v:
                out.append(f"[[{k}]]")
                out += [f"{kk} = {val(vv)}" for kk, vv in t.items()]
        else:
            out.insert(0, f"{k} = {val(v)}")
    return "\n".join(out) + "\n"


def leaves(doc, path=()):
    """(path, value) of every scalar or array-of-scalars leaf."""
    if isinstance(doc, dict):
        for k, v in doc.items():
            yield from leaves(v, path + (k,))
    elif isinstance(doc, list) and doc and all(isinstance(x, dict) for x in doc):
        for i, v in enumerate(doc):
            yield from leaves(v, path + (i,))
    else:
        yield path, doc


def get_parent(doc, path):
    node = doc
    for p in path[:-1]:
        node = node[p]
    return node


WEIRD_NUMBERS = [0, -1, 0.0, -1.0, 1e300, -1e300, 1e-300, float("nan"), float("inf"), float("-inf"),
                 10**12, -(10**12), 3]
WEIRD_VALUES = ["", "bogus", "no_such_thing", True, [], [1.0], [1.0, 2.0, 3.0, 4.0], {"x": 1}, "../../etc",
                "a b", "x" * 300]


def mutate(text, rng):
    """One mutation of a scene text; returns (kind, bytes)."""
    kind = rng.choice(["delete", "type", "number", "number", "enum", "empty", "duplicate", "truncate",
                       "binary", "vector"])
    if kind == "truncate":
        cut = rng.randrange(1, max(2, len(text)))
        return kind, text[:cut].encode()
    if kind == "binary":
        data = bytearray(text.encode())
        for _ in range(rng.randint(1, 8)):
            data[rng.randrange(len(data))] = rng.randrange(256)
        return kind, bytes(data)
    doc = tomllib.loads(text)
    items = [(p, v) for p, v in leaves(doc) if p]
    path, value = rng.choice(items)
    parent = get_parent(doc, path)
    key = path[-1]
    if kind == "delete":
        del parent[key]
    elif kind == "type":
        parent[key] = rng.choice(WEIRD_VALUES + [1.5, 7])
    elif kind == "number":
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            parent[key] = rng.choice(WEIRD_NUMBERS)
        elif isinstance(value, list) and value:
            value[rng.randrange(len(value))] = rng.choice(WEIRD_NUMBERS)
        else:
            parent[key] = rng.choice(WEIRD_NUMBERS)
    elif kind == "enum":
        enum_items = [(p, v) for p, v in items if p[-1] in ENUM_KEYS]
        if enum_items:
            path, value = rng.choice(enum_items)
            get_parent(doc, path)[path[-1]] = rng.choice(WEIRD_VALUES[:4] + ["gef", "svk", "circle", "static"])
    elif kind == "empty":
        parent[key] = []
    elif kind == "vector":
        vec_items = [(p, v) for p, v in items if isinstance(v, list)]
        if vec_items:
            path, value = rng.choice(vec_items)
            get_parent(doc, path)[path[-1]] = rng.choice([[], [0.0, 0.0, 0.0], [1.0, "x", 2.0], [1e308, 1e308, 1e308]])
    elif kind == "duplicate":
        arrays = [k for k, v in doc.items() if isinstance(v, list) and v and isinstance(v[0], dict)]
        if arrays:
            k = rng.choice(arrays)
            doc[k].append(copy.deepcopy(rng.choice(doc[k])))
    return kind, dump(doc).encode()


def solver_for(model, index):
    from gen.solver_build import build_solver
    return build_solver(model["pairs"], ROOT / "out" / "build" / "tests" / "fuzz" / "solver", index, "sanitize")


def run_one(path, index, timeout=120):
    """Validate and (if valid) solve one scene file; returns (outcome, detail)."""
    try:
        model = build(path)
    except SceneError as e:
        msg = str(e)
        rest = msg[len(f"error: {path}: "):]
        if "\n" in msg.strip() or not msg.startswith(f"error: {path}: ") or ": " not in rest:
            return "crashed", f"rejection not one line naming the file and a key: {msg!r}"
        return "rejected", msg
    except RecursionError as e:
        return "crashed", f"RecursionError: {e}"
    except Exception as e:                     # any other exception is a crash of the front door
        import traceback
        return "crashed", traceback.format_exc()
    out = Path(tempfile.mkdtemp(prefix="fz-", dir=path.parent))
    write_model(model, out / "model.dat")
    solver = solver_for(model, index)
    try:
        r = subprocess.run([str(solver), str(out / "model.dat"), str(out), "--quiet"], capture_output=True,
                           text=True, timeout=timeout, errors="replace")
    except subprocess.TimeoutExpired:
        return "hung", f"no result after {timeout} s"
    err = r.stderr
    if "Sanitizer" in err or "runtime error" in err or r.returncode not in (0, 1, 2):
        return "crashed", f"exit {r.returncode}: {err[-2000:]}"
    if r.returncode == 0:
        return "solved", ""
    lines = [l for l in err.splitlines() if l.strip()]
    if len(lines) != 1 or not lines[0].startswith("error: "):
        return "crashed", f"failure not reported in one line: {err[-2000:]}"
    return "failed", lines[0]


def fuzz(count=300, seed=1, workdir=None, log=None):
    rng = random.Random(seed)
    index = load_index()
    work = Path(workdir or tempfile.mkdtemp(prefix="bk-fuzz-"))
    work.mkdir(parents=True, exist_ok=True)
    texts = {s: (ROOT / "models" / f"{s}.toml").read_text() for s in SEEDS}
    counts, problems = {}, []
    for i in range(count):
        seed_name = SEEDS[i % len(SEEDS)]
        kind, data = mutate(texts[seed_name], rng)
        # keep dynamic mutants short
        text = data.decode(errors="replace")
        if "double_pendulum" in seed_name:
            data = data.replace(b"t_end = 2.0", b"t_end = 0.002")
        if "silicone" in seed_name:
            data = data.replace(b"t_end = 0.5", b"t_end = 0.01")
        if "pendulum_soft" in seed_name:
            data = data.replace(b"t_end = 2.0", b"t_end = 0.1")
        path = work / f"m{i:04d}_{seed_name}_{kind}.toml"
        path.write_bytes(data)
        outcome, detail = run_one(path, index)
        counts[outcome] = counts.get(outcome, 0) + 1
        if outcome in ("crashed", "hung"):
            problems.append((path, outcome, detail))
        if log:
            log(f"{path.name}: {outcome}")
        del text
    return counts, problems


if __name__ == "__main__":
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 300
    sd = int(sys.argv[2]) if len(sys.argv) > 2 else 1
    counts, problems = fuzz(n, sd)
    print(f"tried {n}: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
    for p, o, d in problems:
        print(f"{o}: {p}\n{d}\n")
    sys.exit(1 if problems else 0)
