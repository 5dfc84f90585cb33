"""No heap allocation in the step loop, and one KLU symbolic analysis per run:
the solver's total allocation count (valgrind) does not grow with the number
of time steps.  Output is limited to the first and last steps
(dynamic.output_every) so that only the solve loop differs between the runs."""
import re
import shutil
import subprocess

from util import BUILD, ROOT, ensure_dir, run_scene


def heap_allocs(scene, sets, tag, threads=1):
    out = ensure_dir(BUILD / "alloc" / tag)
    summary, _ = run_scene(scene, sets, out=out)
    assert summary["converged"] and summary["symbolic_analyses"] == 1, summary
    solver = ROOT / "out" / "bin" / summary["scene"]
    work = ensure_dir(BUILD / "alloc" / (tag + "-vg"))
    for p in work.iterdir():
        p.unlink() if p.is_file() else shutil.rmtree(p)
    r = subprocess.run(["valgrind", "--tool=memcheck", "--error-exitcode=3", str(solver),
                        str(out / "model.dat"), str(work), "--quiet"],
                       capture_output=True, text=True, timeout=900, env={"OMP_NUM_THREADS": str(threads), "PATH": "/usr/bin:/bin"})
    assert r.returncode == 0, r.stderr[-2000:]
    m = re.search(r"total heap usage: ([\d,]+) allocs", r.stderr)
    assert m, r.stderr[-2000:]
    return int(m.group(1).replace(",", "")), summary


def check_steps(elements, threads):
    if shutil.which("valgrind") is None:
        raise AssertionError("valgrind is not installed (./build.sh deps)")
    base = [f"beam.strip.elements={elements}", "dynamic.dt=1e-3", "dynamic.output_every=100000"]
    a, sa = heap_allocs("silicone_fall", base + ["dynamic.t_end=0.005"], f"dyn5-{elements}", threads)
    b, sb = heap_allocs("silicone_fall", base + ["dynamic.t_end=0.02"], f"dyn20-{elements}", threads)
    assert sb["steps"] > sa["steps"] and sb["newton_iterations"] > sa["newton_iterations"]
    assert a == b, f"{b - a} more heap allocations for {sb['steps'] - sa['steps']} more steps " \
                   f"({sb['newton_iterations'] - sa['newton_iterations']} more Newton iterations)"


def test_dynamic_step_loop_does_not_allocate_serial():
    check_steps(4, 1)


def test_dynamic_step_loop_does_not_allocate_parallel():
    # 40 elements: above the parallel threshold, OpenMP region per assembly
    check_steps(40, 2)
