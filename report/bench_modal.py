"""Sparse modal analysis in the bench (issue 38 point 5): the lowest 10 modes of
the steel cantilever of models/cantilever_modal.toml meshed with 10,000 gef
elements (140,000 free DOFs, far above the dense solver's 4,000) by
shift-invert Lanczos, the whole command's wall time and peak memory, the first
frequency against Euler-Bernoulli beam theory.
Run alone: /usr/bin/python3 -m report.bench_modal [--quick]."""
import json
import math
import os
import resource
import subprocess
import sys
import time

from gen.scene import ROOT
from report.bench_runs import WORK

E, RHO, SIDE, L = 2.1e11, 7850.0, 0.01, 1.0


def sparse_modes(quick, log):
    """{elements, free_dofs, wall_s, maxrss_kb, f1_hz, f1_beam_theory_hz}."""
    n = 1000 if quick else 10000
    out = WORK / "modal_sparse"
    scene = ROOT / "models" / "cantilever_modal.toml"
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    t0 = time.perf_counter()
    r = subprocess.run([sys.executable, str(ROOT / "gen" / "cli.py"), "run", str(scene), "--quiet", "--out", str(out),
                        "--set", f"beam.arm.elements={n}", "--set", "modal.modes=10", "--set", "output.vtk_every=0"],
                       capture_output=True, text=True, env=dict(os.environ, PYTHONPATH=str(ROOT)))
    wall = time.perf_counter() - t0
    if r.returncode != 0:
        raise RuntimeError(f"sparse modal run failed: {r.stderr[-500:]}")
    rss = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    s = json.loads((out / "summary.json").read_text())
    ei, rhoa = E * SIDE**4 / 12, RHO * SIDE * SIDE
    log("  modal: sparse done")
    return {"elements": n, "free_dofs": s.get("dofs", 14 * n), "wall_s": wall,
            "maxrss_kb": rss if rss > before else None, "f1_hz": s["frequencies_hz"][0],
            "f1_beam_theory_hz": 1.87510407**2 / (2 * math.pi * L * L) * math.sqrt(ei / rhoa)}


def markdown(row):
    rss = f", peak memory {row['maxrss_kb'] / 1024:.0f} MB" if row["maxrss_kb"] else ""
    return ["## Sparse modal analysis", "",
            f"The lowest 10 modes of the steel cantilever (`models/cantilever_modal.toml`) with {row['elements']:,} "
            f"`gef` elements ({row['free_dofs']:,} DOFs; the dense solver stops at 4,000) by shift-invert Lanczos "
            f"with the linear solver object: **{row['wall_s']:.2f} s** for the whole command{rss} (target: "
            f"seconds).  First frequency {row['f1_hz']:.6f} Hz against Euler-Bernoulli {row['f1_beam_theory_hz']:.6f} "
            "Hz (the beam is shear-flexible: a little lower).", ""]


if __name__ == "__main__":
    print("\n".join(markdown(sparse_modes("--quick" in sys.argv, print))))
