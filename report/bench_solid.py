"""The solid model beside the beams in the work-precision diagrams (issue 38
point 7): every mesh of a CalculiX C3D20R mesh study (calculix/, the
project's CalculiX module; references/data/calculix_*.json keeps each mesh's
tip displacement and ccx's wall time on this machine, with the command that
regenerates the entry) as a point of its own variant "CalculiX C3D20R solid":
its error against the study's Richardson-extrapolated value, measured like the
beams' error, and its wall time.  The solid's time is ccx's whole run (one
thread, the same machine type), the beams' the solver's wall time.  The
solids' errors are their distance from their own extrapolated limit, which is
the reference the beams are measured against."""
import math

SOLID = "CalculiX C3D20R solid"


def solid_points(problem, ref, length, components=(0, 2), dt=None):
    """Work-precision points (report/bench_runs.py point's fields) of the mesh
    study `ref` (calculix.data.ReferenceData): error = |u_mesh - u_extrapolated|
    over `components`, divided by `length`."""
    points = []
    for pm in ref.per_mesh:
        err = math.sqrt(sum((pm["u"][k] - ref.value[k])**2 for k in components)) / length
        points.append({"problem": problem, "variant": SOLID, "elements": pm["elements"], "dt": dt,
                       "converged": True, "wall_s": float(pm["wall_s"]), "newton_iterations": pm.get("iterations"),
                       "steps": None, "error": err, "failure": ""})
    return points


def note(ref, what):
    """A sentence for the problem's note: the solid's meshes and times."""
    runs = ", ".join(f"{pm['mesh']} ({pm['elements']:,} C3D20R, {pm['wall_s']:.1f} s)" for pm in ref.per_mesh)
    return (f"The solid ({SOLID}, {what}): the meshes {runs} of the study behind the reference, each at its "
            f"distance from the extrapolated value, with ccx's wall time recorded on this machine type "
            f"(`{ref.command}`).")
