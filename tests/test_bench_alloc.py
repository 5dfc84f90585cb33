"""No heap allocation in the step loop, and one KLU symbolic analysis per run:
the solver's total allocation count (valgrind) does not grow with the number
of time steps.  Output is limited to the first and last steps
(dynamic.output_every) so that only the solve loop differs between the runs,
and results.h5 is off: the HDF5 library allocates on its writer thread when a
timed flush (every 0.5 s of wall time) falls, which depends on how long the run
takes under valgrind, not on the solve loop."""
import pytest
import re
import shutil

from util import BUILD, load_run, run_memcheck


def heap_allocs(scene, sets, tag, threads=1):
    r, out = run_memcheck(scene, sets, out=BUILD / "alloc" / tag, threads=threads)
    assert r.returncode == 0, r.stderr[-2000:]
    summary, _ = load_run(out)
    assert summary["converged"] and summary["symbolic_analyses"] == 1, summary
    m = re.search(r"total heap usage: ([\d,]+) allocs", r.stderr)
    assert m, r.stderr[-2000:]
    return int(m.group(1).replace(",", "")), summary


def check_steps(elements, threads, t_short=0.005, t_long=0.02):
    if shutil.which("valgrind") is None:
        raise AssertionError("valgrind is not installed (./build.sh deps)")
    base = [f"beam.strip.elements={elements}", "dynamic.dt=1e-3", "dynamic.output_every=100000",
            "output.hdf5=false"]
    a, sa = heap_allocs("silicone_fall", base + [f"dynamic.t_end={t_short}"], f"dyn{t_short}-{elements}", threads)
    b, sb = heap_allocs("silicone_fall", base + [f"dynamic.t_end={t_long}"], f"dyn{t_long}-{elements}", threads)
    assert sb["steps"] > sa["steps"] and sb["newton_iterations"] > sa["newton_iterations"]
    assert a == b, f"{b - a} more heap allocations for {sb['steps'] - sa['steps']} more steps " \
                   f"({sb['newton_iterations'] - sa['newton_iterations']} more Newton iterations)"


@pytest.mark.slow
def test_dynamic_step_loop_does_not_allocate_serial():
    check_steps(4, 1)


@pytest.mark.slow
def test_dynamic_step_loop_does_not_allocate_parallel():
    # 260 elements: above the serial limit (256, runtime/assembly/system_impl.h), OpenMP region per assembly
    check_steps(260, 2, 0.003, 0.006)
