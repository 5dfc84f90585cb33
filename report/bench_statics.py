"""The static work-precision problems of the bench: seed Table 3 at -100 N
(nu = 0.3) against CalculiX and the full roll-up of Table 5 against its exact
solution, every element variant over a range of meshes."""
import math

from report.bench_runs import beam_variants, dist, pick, point, run, tip_xyz


def statics(quick, log):
    """Work-precision points of the two static problems, and their references."""
    points, notes = [], []
    allv = beam_variants("arm", "alu")
    meshes = (2, 8, 32) if quick else (2, 4, 8, 16, 32, 64)
    if quick:
        variants = pick(allv, ("ancf3243 full", "ancf3363 reduced", "gef"))
    else:
        variants = allv

    # Seed Table 3, -100 N, nu = 0.3: CalculiX C3D20R (NLGEOM), mesh-extrapolated
    # (references/data/calculix_cantilever.json; calculix/ regenerates it, the command is in the entry).
    scene = "cantilever_bend_100N_nu03"
    from calculix.data import CANTILEVER, reference_data
    ccx = reference_data("table3_rigid", CANTILEVER)
    ccx_free = reference_data("table3_free", CANTILEVER)
    u_ref = [1.0 + ccx.value[0], ccx.value[1], ccx.value[2]]
    L = 1.0
    ref_unc = math.hypot(ccx.error[0], ccx.error[2]) / L
    free_d = math.hypot(ccx_free.value[0] - ccx.value[0], ccx_free.value[2] - ccx.value[2]) / L
    # our own converged element, for the statement of how far it is from the reference
    s, err = run(scene, allv[5][1] + ["beam.arm.elements=128"], "t3-ref-128")
    if s is None or not s["converged"]:
        raise RuntimeError(f"Table 3 ancf3363 run (128 elements) failed: {err or s.get('error')}")
    own_d = dist(tip_xyz(s, "tip"), u_ref) / L
    from references.elastica import tip_load_cantilever
    eu, ew = tip_load_cantilever(1.0, 100.0, 7.2e10 * 0.01**4 / 12, n=2000)
    el = (1.0 + eu, -ew)
    notes.append(("table3", f"Reference: CalculiX (ccx, {ccx.ccx.split(',')[0].replace('CalculiX Version', 'version')}) "
                  f"C3D20R solid, NLGEOM, St. Venant-Kirchhoff with the scene's E and nu, every node of the "
                  f"clamped face fixed (the scene's clamp), the -100 N tip force as a uniform traction on the end "
                  f"face; meshes {', '.join(ccx.meshes)} graded towards the clamp ({ccx.grading}), "
                  f"Richardson-extrapolated (observed order {ccx.order[2]:.2f}), the section's 2 x 2 elements "
                  f"checked against 4 x 4 (references/data/calculix_cantilever.json, entry table3_rigid, with "
                  f"the command that regenerates it).  Tip at ({u_ref[0]:.7f}, {u_ref[2]:.7f}) m (x, z), "
                  f"estimated error {ref_unc:.1e} L (the section check's difference {ccx.checks[0]['final_diff'][2]:.1e} m "
                  f"dominates; with a section order of 1 it would be twice that).  `ancf3363` `reduced` with "
                  f"128 elements is {own_d:.1e} L from it (still converging, order ~1.4; extrapolated over "
                  f"32/64/128 elements it is within 1.3e-5 m, tests/test_independent_references.py).  The solid's "
                  f"clamp and the beam's: a solid whose clamped face may contract in its plane and only stays "
                  f"plane (entry table3_free) has its tip {free_d:.1e} L from the fully fixed face, the size of "
                  f"the clamp's modelling choice; beamkit's default clamp (cross_section = rigid, every nodal "
                  f"coordinate fixed) matches the fully fixed face.  For comparison the inextensible "
                  f"Euler-Bernoulli elastica (GSL shooting, references/elastica.py) gives a tip at "
                  f"({el[0]:.9f}, {el[1]:.9f}) m: {dist((u_ref[0], u_ref[2]), el) / L:.1e} L from the solid, the "
                  f"size of the shear, extension and Poisson effects.  Error = |tip - reference| / L; errors "
                  f"below {ref_unc:.0e} are within the reference's own uncertainty."))
    for label, sets in variants:
        for n in meshes:
            s, err = run(scene, sets + [f"beam.arm.elements={n}"], f"t3-{label.replace(' ', '_')}-{n}")
            points.append(point("Table 3 (-100 N, nu = 0.3)", label, n, None, s, err,
                                lambda s: dist(tip_xyz(s, "tip"), u_ref) / L))
        log(f"  table 3: {label}")
    from report.bench_solid import note as solid_note, solid_points
    points += solid_points("Table 3 (-100 N, nu = 0.3)", ccx, L)
    notes.append(("table3_solid", solid_note(ccx, "St. Venant-Kirchhoff, the clamped face fixed")))

    # Silicone cantilever sagging under its weight (Arruda-Boyce, kappa = 1000 mu):
    # CalculiX C3D20R, rigid clamp, mesh-extrapolated (calculix_silicone.json).
    from calculix import reference_data
    sil = reference_data("silicone_cantilever_sag_rigid")
    Ls = 0.25
    u_sil = [Ls + sil.value[0], sil.value[1], sil.value[2]]
    sil_variants = [("ancf3243 sri", ["beam.strip.element=ancf3243", "beam.strip.integration=sri"]),
                    ("ancf3273 reduced", ["beam.strip.element=ancf3273", "beam.strip.integration=reduced"]),
                    ("ancf3363 reduced", ["beam.strip.element=ancf3363", "beam.strip.integration=reduced"])]
    if quick:
        sil_variants = sil_variants[::2]
    sil_meshes = (2, 8) if quick else (2, 4, 8, 16, 32)
    notes.append(("silicone_sag", f"Reference: CalculiX C3D20R solid of the silicone strip sagging under its weight "
                  f"(`models/silicone_cantilever_sag.toml`, Arruda-Boyce, kappa = 1000 mu, the clamped face "
                  f"fixed: beamkit's `cross_section = rigid`), mesh-extrapolated: tip at ({u_sil[0]:.7f}, "
                  f"{u_sil[2]:.7f}) m, its own error estimate {max(sil.error[0], sil.error[2]):.1e} m.  Error = "
                  f"|tip - reference| / L, L = 0.25 m.  " + solid_note(sil, "the same strip and law")))
    for label, sets in sil_variants:
        for n in sil_meshes:
            s, err = run("silicone_cantilever_sag", sets + ["constraint.0.cross_section=rigid",
                                                            f"beam.strip.elements={n}"],
                         f"sag-{label.replace(' ', '_')}-{n}")
            points.append(point("Silicone sag (static)", label, n, None, s, err,
                                lambda s: dist(tip_xyz(s, "tip"), u_sil) / Ls))
        log(f"  silicone sag: {label}")
    points += solid_points("Silicone sag (static)", sil, Ls)

    # Roll-up, M = 2 pi EI / L: exact solution, the tip returns to the clamp.
    scene = "cantilever_rollup"
    notes.append(("rollup", "Exact solution: under M = 2 pi E I / L the beam rolls up into a full circle and the tip "
                  "returns to the clamp at the origin.  Error = |tip position| / L.  (For the St. Venant-Kirchhoff "
                  "continuum elements the exact solution of their own continuum model is not exactly a circle "
                  "closing at the clamp: their error levels off at that modelling difference.)"))
    for label, sets in variants:
        for n in meshes:
            s, err = run(scene, sets + [f"beam.arm.elements={n}"], f"ru-{label.replace(' ', '_')}-{n}")
            points.append(point("Roll-up (Table 5)", label, n, None, s, err,
                                lambda s: dist(tip_xyz(s, "tip"), (0.0, 0.0, 0.0)) / L))
        log(f"  roll-up: {label}")
    return points, notes
