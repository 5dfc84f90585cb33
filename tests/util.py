"""Helpers shared by the tests: running scenes, building test programs."""
import csv
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BUILD = ROOT / "out" / "build" / "tests"
PY = "/usr/bin/python3"
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
ENV.update(PYTHONPATH=str(ROOT), PYTHONPYCACHEPREFIX=str(ROOT / "out" / "pycache"))


def run_cli(args, check=False, timeout=600, env=None, cwd=None):
    """./build.sh ARGS -> CompletedProcess (text); env: extra environment variables."""
    r = subprocess.run([str(ROOT / "build.sh")] + list(args), capture_output=True, text=True,
                       env=dict(ENV, **(env or {})), timeout=timeout, cwd=cwd)
    if check and r.returncode != 0:
        raise AssertionError(f"./build.sh {' '.join(args)} failed ({r.returncode}):\n{r.stderr[-3000:]}")
    return r


def run_scene(scene, sets=(), out=None, extra=()):
    """Run a scene (name or path) and return (summary dict, sensor rows)."""
    out = Path(out or tempfile.mkdtemp(prefix="bk-run-", dir=ensure_dir(BUILD / "runs")))
    if out.exists() and not any(out.iterdir()):
        pass
    args = ["run", str(scene), "--quiet", "--out", str(out)] + list(extra)
    for s in sets:
        args += ["--set", s]
    r = run_cli(args)
    if r.returncode != 0:
        raise AssertionError(f"scene {scene} {list(sets)} failed ({r.returncode}):\n{r.stderr[-3000:]}")
    return load_run(out)


def run_text(text, name, prefix="bk-text"):
    """Write scene text to a fresh directory as NAME.toml, run it (its results in
    out/ there) and return its summary, which must say converged."""
    d = Path(tempfile.mkdtemp(prefix=f"{prefix}-{name}-", dir=ensure_dir(BUILD / "runs")))
    (d / f"{name}.toml").write_text(text)
    s, _ = run_scene(d / f"{name}.toml", out=d / "out")
    assert s["converged"], name
    return s


def run_memcheck(scene, sets=(), out=None, threads=None, timeout=900):
    """`./build.sh run SCENE --memcheck`: the valgrind build of the solver
    (-march=x86-64-v3, never -march=native: valgrind cannot decode AVX-512) run
    under valgrind memcheck.  Every test that runs valgrind goes through here
    (tests/test_valgrind_builds.py checks it).  Returns (CompletedProcess, out)."""
    out = Path(out or tempfile.mkdtemp(prefix="bk-vg-", dir=ensure_dir(BUILD / "runs")))
    args = ["run", str(scene), "--memcheck", "--quiet", "--out", str(out)]
    for s in sets:
        args += ["--set", s]
    env = {"OMP_NUM_THREADS": str(threads)} if threads else None
    return run_cli(args, timeout=timeout, env=env), out


def load_run(out):
    out = Path(out)
    summary = json.loads((out / "summary.json").read_text())
    with open(out / "sensors.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    return summary, rows


def ensure_dir(p):
    Path(p).mkdir(parents=True, exist_ok=True)
    return Path(p)


def tip(summary, name="tip"):
    return summary["sensors"][name]["displacement"]


def rel(a, b):
    return abs(a - b) / abs(b)


def all_pair_symbols(index=None):
    from gen.scene import load_index
    index = index or load_index()
    return [f"{p['element']}_{p['material']}_{p['integration']}" for p in index["pairs"]], index


def build_program(src, name, variant="sanitize", pairs=None):
    """Compile tests/<src> and link it with the kernel table of `pairs`
    (default: every generated pair).  Returns the executable path."""
    from gen.solver_build import VARIANTS, compile_object, build_solver, runtime_headers
    allp, index = all_pair_symbols()
    pairs = pairs or allp
    src = ROOT / "tests" / src
    obj = BUILD / variant / (Path(src).stem + ".o")
    compile_object(src, obj, VARIANTS[variant], runtime_headers())
    return build_solver(pairs, BUILD / variant / name, index, variant, main_objs=[obj])


def build_runtime_program(srcs, name, variant="sanitize"):
    """Compile tests/<src> for each of srcs and link them with the runtime objects
    (all but main.c) into a test program; no generated kernels.  Returns its path."""
    from gen.solver_build import (CC, LIBS, VARIANTS, build_lock, compile_object, kernel_objects, runtime_headers,
                                  runtime_objects)
    flags = VARIANTS[variant]
    deps = runtime_headers() + list((ROOT / "tests").glob("*.h"))
    _, index = all_pair_symbols()
    with build_lock():
        # the runtime but main.c, and the kernels every solver links (joints, contact)
        objs = [o for o in runtime_objects(variant) if o.name != "main.o"] + kernel_objects([], index, variant)
        for src in srcs:
            obj = BUILD / variant / (Path(src).stem + ".o")
            compile_object(ROOT / "tests" / src, obj, flags + ["-I" + str(ROOT / "tests")], deps)
            objs.append(obj)
        exe = ensure_dir(BUILD / variant) / name
        if exe.exists() and exe.stat().st_mtime >= max(o.stat().st_mtime for o in objs):
            return exe
        r = subprocess.run([CC] + flags + [str(o) for o in objs] + ["-o", str(exe)] + LIBS,
                           capture_output=True, text=True)
        if r.returncode != 0:
            raise AssertionError(f"linking {exe} failed:\n{r.stderr[-3000:]}")
        return exe


def build_shared_kernels():
    """Every generated kernel (release objects, position independent) as one shared
    library for ctypes, relinked when an object is newer."""
    from gen.solver_build import CC, build_lock, kernel_objects
    pairs, index = all_pair_symbols()
    with build_lock():
        objs = kernel_objects(pairs, index, "release")
        lib = ensure_dir(BUILD) / "libkernels.so"
        if lib.exists() and lib.stat().st_mtime >= max(o.stat().st_mtime for o in objs):
            return lib
        tmp = lib.with_name(lib.name + ".tmp")
        r = subprocess.run([CC, "-shared", "-o", str(tmp)] + [str(o) for o in objs] + ["-lm"],
                           capture_output=True, text=True)
        if r.returncode != 0:
            raise AssertionError(f"linking {lib} failed:\n{r.stderr[-3000:]}")
        tmp.replace(lib)
        return lib


class Kernel:
    """ctypes access to one generated element x material x integration kernel."""

    def __init__(self, element, material, integration="full", ntab=None, ndof=None):
        import ctypes
        import json
        self.lib = ctypes.CDLL(str(build_shared_kernels()))
        idx = json.loads((ROOT / "out" / "kernels" / "index.json").read_text())
        e = idx["elements"][element]
        self.ndof = e["ndof"]
        self.nodes = e["nodes"]
        self.ntab = e["integrations"][integration]["ntab"]
        D = ctypes.POINTER(ctypes.c_double)
        self._tab = getattr(self.lib, f"{element}_{integration}_tabulate")
        self._energy = getattr(self.lib, f"{element}_{material}_{integration}_energy")
        self._energy.restype = ctypes.c_double
        self._force = getattr(self.lib, f"{element}_{material}_{integration}_force")
        self._ft = getattr(self.lib, f"{element}_{material}_{integration}_force_tangent")
        self.ct = ctypes

    def _arr(self, a):
        import numpy as np
        a = np.ascontiguousarray(a, dtype=float)
        return a, a.ctypes.data_as(self.ct.POINTER(self.ct.c_double))

    def tabulate(self, geom, q0=None):
        import numpy as np
        tab = np.zeros(self.ntab)
        from gen import contract
        geom = list(geom) + [0.0] * (contract.ngeom() - len(geom))
        g, gp = self._arr(geom)
        q0, q0p = self._arr(self.straight_reference(geom[0]) if q0 is None else q0)
        t, tp = self._arr(tab)
        self._tab(gp, q0p, tp)
        return t

    def straight_reference(self, length):
        """Reference coordinates of the straight element along +x, section axes +y, +z
        (continuum elements read their reference map from them)."""
        from fractions import Fraction
        unit = {"r_x": [1.0, 0.0, 0.0], "r_y": [0.0, 1.0, 0.0], "r_z": [0.0, 0.0, 1.0]}
        q0 = []
        for nd in self.nodes:
            for f, dim in nd["fields"]:
                if f == "r":
                    q0 += [float(Fraction(nd["xi"])) * length, 0.0, 0.0]
                else:
                    q0 += unit.get(f, [0.0] * dim)
        return q0 + [0.0] * (self.ndof - len(q0))

    def eval(self, q, tab, mat):
        import numpy as np
        q, qp = self._arr(q)
        t, tp = self._arr(tab)
        m, mp = self._arr(mat)
        f = np.zeros(self.ndof)
        K = np.zeros(self.ndof * self.ndof)
        f, fp = self._arr(f)
        K, Kp = self._arr(K)
        U = self._energy(qp, tp, mp)
        self._ft(qp, tp, mp, fp, Kp)
        return U, f.copy(), K.reshape(self.ndof, self.ndof).copy()


def scratch_copy(dst):
    """A copy of the project's tracked files (the working tree's content) in dst,
    for tests that follow a recipe which edits the code (docs/howto/add-*.md).
    The release objects of this checkout's runtime and kernels are built first
    (the suite's runs and kernel tests need them anyway) and copied with their
    times, as are the sources: the copy's build recompiles only what its edits
    make stale (gen/solver_build.py compares times and flags).  Returns dst."""
    import shutil
    from gen.solver_build import BUILD as OBJ, build_lock, kernel_objects, runtime_objects
    files = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True).stdout
    dst = Path(dst)
    for rel_ in filter(None, files.decode().split("\0")):
        src = ROOT / rel_
        if src.is_file():
            (dst / rel_).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dst / rel_)
    allp, index = all_pair_symbols()
    with build_lock():
        runtime_objects("release")
        kernel_objects(allp, index, "release")
        for sub in ("runtime", "kernels"):
            shutil.copytree(OBJ / "release" / sub, dst / "out" / "build" / "release" / sub)
    return dst
