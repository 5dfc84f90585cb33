"""What a run will cost, estimated before meshing: memory, disk for the
ParaView frames and time per Newton iteration, from the element counts and the
element kinds.  Runs that cannot fit refuse with one error line naming the key
to change; large ones print the estimate first.

The constants were measured on this project's machines (Debian 12, 2 cores):
the solver holds about 30 bytes per entry of the element tangents (values,
pattern, KLU factors, LDL^T of the stability check) plus 2 kB per element; the
scene compiler about 2.6 kB per element while the solver runs; a binary frame
about 3.5 kB per continuum element (section rings) and 0.5 kB per rod element;
a Newton iteration about 40 ns per tangent entry.
"""
import os

SOLVER_BYTES_PER_ENTRY = 30.0
SOLVER_BYTES_PER_ELEMENT = 2000.0
MESH_BYTES_PER_ELEMENT = 2600.0
FRAME_BYTES = {"continuum": 3500.0}
FRAME_BYTES_OTHER = 500.0
SECONDS_PER_ENTRY_ITERATION = 40e-9


def available_memory():
    """Bytes the machine can give (MemAvailable), or None if unknown."""
    try:
        with open("/proc/meminfo") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return None


def estimate(beams, index, frames):
    """beams: [(where, element name, element count)]; frames: expected ParaView
    frames.  Returns a dict of estimates (bytes, seconds)."""
    mem = disk = t_it = 0.0
    n = 0
    for _, ename, nel in beams:
        e = index["elements"][ename]
        nd = e["ndof"]
        n += nel
        mem += nel * (SOLVER_BYTES_PER_ENTRY * nd * nd + SOLVER_BYTES_PER_ELEMENT + MESH_BYTES_PER_ELEMENT)
        disk += nel * FRAME_BYTES.get(e["kind"], FRAME_BYTES_OTHER) * frames
        t_it += nel * nd * nd * SECONDS_PER_ENTRY_ITERATION
    return {"elements": n, "memory": mem, "disk": disk, "iteration_s": t_it}


def _gb(x):
    return f"{x / 1e9:.3g} GB" if x >= 1e8 else f"{x / 1e6:.3g} MB"


def check(est, beams, out_dir, fail, log=None):
    """Refuses (fail(key, message)) a run that cannot fit in memory or on disk;
    logs the estimate of a large one."""
    avail = available_memory()
    biggest = max(beams, key=lambda b: b[2])
    key = f"{biggest[0]}.elements"
    if avail is not None and est["memory"] > 0.8 * avail:
        fail(key, f"{est['elements']} elements need about {_gb(est['memory'])} of memory, this machine has "
                  f"{_gb(avail)} available; expected fewer elements (at most about "
                  f"{int(biggest[2] * 0.8 * avail / est['memory'])} here)")
    try:
        st = os.statvfs(out_dir if os.path.isdir(out_dir) else os.path.dirname(out_dir) or ".")
        free = st.f_bavail * st.f_frsize              # as shutil.disk_usage (not imported: ~1.5 ms)
    except OSError:
        free = None
    if free is not None and est["disk"] > 0.9 * free:
        fail("output.vtk_every", f"the ParaView frames would take about {_gb(est['disk'])} and the disk has "
                                 f"{_gb(free)} free; expected a larger output.vtk_every (or 0: no frames) or "
                                 f"fewer elements ({key})")
    if log and (est["memory"] > 1e9 or est["iteration_s"] > 5 or est["disk"] > 2e9):
        log(f"estimate: {est['elements']} elements: about {_gb(est['memory'])} of memory"
            f"{f' (of {_gb(avail)} available)' if avail else ''}, {est['iteration_s']:.3g} s per Newton "
            f"iteration, {_gb(est['disk'])} of ParaView frames")
