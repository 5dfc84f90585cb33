"""The toolchain part of the bench: regeneration time per kernel (forced, then
incremental) and the compile time and size of a per-scene solver."""
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

from gen.scene import ROOT


def toolchain(quick, log):
    from gen.generate import generate
    res = {"regen": [], "compile": {}}
    tmp = Path(tempfile.mkdtemp(prefix="bk-bench-gen-"))
    try:
        lines = []
        only = "ancf3243_svk" if quick else None
        t0 = time.time()
        generate(tmp / "kernels", force=True, log=lines.append, only=only)
        res["regen_total_s"] = time.time() - t0
        res["regen_scope"] = "ancf3243_svk only (--quick)" if quick else "every element and pair (2 worker processes)"
        for ln in lines:
            ln = ln.strip()
            if ": generated (" in ln:
                name, rest = ln.split(": generated (")
                res["regen"].append((name, float(rest.rstrip(" s)"))))
        t0 = time.time()
        lines = []
        generate(tmp / "kernels", log=lines.append, only=only)
        res["regen_incremental_s"] = time.time() - t0
        res["regen_incremental_redone"] = sum(": generated" in x for x in lines)
        log("  toolchain: regeneration")
        # A per-scene solver from scratch in an empty build directory.
        import gen.solver_build as sb
        from gen.scene import build, load_index
        index = load_index()
        model = build(ROOT / "models" / "cantilever_bend_100N.toml", [])
        old = sb.BUILD
        sb.BUILD = tmp / "build"
        try:
            t0 = time.time()
            robjs = sb.runtime_objects("release")
            t1 = time.time()
            exe = sb.build_solver(model["pairs"], tmp / "solver", index, "release", main_objs=robjs)
            t2 = time.time()
        finally:
            sb.BUILD = old
        nm = subprocess.run(["nm", str(exe)], capture_output=True, text=True).stdout
        linked = sorted({w.split()[-1][len("bk_pair_"):] for w in nm.splitlines() if " bk_pair_" in w})
        strip_size = None
        try:
            shutil.copy(exe, tmp / "solver.stripped")
            subprocess.run(["strip", str(tmp / "solver.stripped")], check=True)
            strip_size = (tmp / "solver.stripped").stat().st_size
        except (OSError, subprocess.CalledProcessError):
            pass
        res["compile"] = {"scene": "cantilever_bend_100N", "pairs": model["pairs"], "runtime_s": t1 - t0,
                          "kernels_and_link_s": t2 - t1, "size": exe.stat().st_size, "stripped_size": strip_size,
                          "linked_pairs": linked}
        log("  toolchain: solver compile")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return res
