"""The warning for a continuum section held rigid (a clamp, or a weld to a rod or
body) at the end of a uniformly meshed ancf3363 beam: the boundary layer there
and the grading that resolves it."""


def graded_clamp_warning(mesh, where, beam, s, what="a rigid clamp"):
    """A rigid clamp (or a weld, which holds the section the same way) at an end of
    a uniformly meshed ancf3363 beam: the section held whole there starts a 3-D boundary layer its elements resolve only when short
    (measured against CalculiX, tests/test_silicone_large.py)."""
    lens = beam["elem_lens"]
    if beam["element"] != "ancf3363" or len(lens) < 2 or max(lens) > 1.5 * min(lens):
        return
    end = "start" if s <= 0.5 * beam["length"] else "end"
    mesh.warnings.append(f"{where}: {what} at the {end} of beam {beam['name']} (ancf3363, uniform mesh): "
                         "the boundary layer of the held section makes 10 uniform elements 6.7 % too stiff against "
                         f"a solid model; grade toward the clamp (beam.grading = {20 if end == 'start' else 0.05}: "
                         "0.48 %) or use cross_section = \"free\"")
