"""OpenMP element evaluation: results bit-identical for any thread count
(runtime/assembly/assembly.c evaluates fixed groups of up to 8 elements with the lane
kernels; each thread takes one contiguous part of the groups and adds directly
into the entries only its part touches, entries shared between parts are
staged and summed in element order), and the KLU analysis done once per run.
No timings here."""
import json
import os
import subprocess
import tempfile
from pathlib import Path

from util import BUILD, ENV, ROOT, ensure_dir

FILES = ("sensors.csv", "energy.csv", "sections.csv")   # (section forces: on the threads from 256 elements)


def run_threads(scene, sets, threads):
    out = Path(tempfile.mkdtemp(prefix=f"bk-omp{threads}-", dir=ensure_dir(BUILD / "parallel")))
    args = [str(ROOT / "build.sh"), "run", scene, "--quiet", "--out", str(out)]
    for s in sets:
        args += ["--set", s]
    r = subprocess.run(args, capture_output=True, text=True, env=dict(ENV, OMP_NUM_THREADS=str(threads)),
                       timeout=600)
    assert r.returncode == 0, f"{scene} with {threads} threads failed:\n{r.stderr[-2000:]}"
    return out


def same_results(scene, sets, threads=(1, 2, 3)):
    outs = [run_threads(scene, sets, t) for t in threads]
    for f in FILES:
        base = outs[0] / f
        if not base.exists():
            continue
        for o, t in zip(outs[1:], threads[1:]):
            assert (o / f).read_bytes() == base.read_bytes(), \
                f"{scene}: {f} differs between {threads[0]} and {t} threads"
    s = [json.loads((o / "summary.json").read_text()) for o in outs]
    for x, t in zip(s[1:], threads[1:]):
        for k in ("newton_iterations", "steps", "strain_energy", "sensors"):
            assert x[k] == s[0][k], f"{scene}: summary {k} differs with {t} threads"
    return s[0]


def test_static_bit_identical_for_1_2_3_threads():
    # 260 elements (above the runtime's serial limit of 256): 33 lane groups (the last one partly
    # filled), parallel path and parallel scatter taken
    s = same_results("cantilever_bend_100N_nu03", ["beam.arm.elements=260"])
    assert s["converged"]
    assert s["symbolic_analyses"] == 1, "the KLU symbolic analysis must run once per run"


def test_dynamic_bit_identical_for_1_2_threads():
    s = same_results("silicone_fall", ["beam.strip.elements=260", "dynamic.t_end=0.005"], threads=(1, 2))
    assert s["converged"]
    assert s["symbolic_analyses"] == 1


def test_resultant_beam_bit_identical_for_1_2_threads():
    same_results("cantilever_rollup", ["beam.arm.element=gef", "material.alu.law=resultant",
                                       "beam.arm.elements=260", "static.load_steps=4"], threads=(1, 2))


def test_mixed_pairs_bit_identical_for_1_2_3_threads():
    """Two beams of different pairs (133 `sri` + 131 `full` elements, above the serial
    limit of 256): lane groups end at the pair boundary, both last groups are partly
    filled."""
    s = same_results("double_pendulum_soft_ancf", ["beam.rod1.elements=133", "beam.rod1.integration=sri",
                                                   "beam.rod2.elements=131", "dynamic.t_end=0.004",
                                                   "dynamic.dt=1e-3"])
    assert s["converged"]
