"""The dynamic work-precision problems of the bench: the soft seed pendulum
against an independent Reissner beam and the falling silicone cantilever against
CalculiX, every element variant over meshes and time steps, with the
Richardson-extrapolated references of our own that check them."""
import math

from report.bench_runs import at_times, beam_variants, dist, pick, point, run, track


def richardson_reference(scene, sets, dts, sensor, times, tag):
    """Second-order Richardson extrapolation in dt of the sensor positions at
    `times` from runs with dts = (dt, dt / 2).  Returns (positions, estimate of
    the reference's error, wall seconds of the finer run)."""
    tr = []
    for dt in dts:
        s, err = run(scene, sets + [f"dynamic.dt={dt}"], f"{tag}-dt{dt}")
        if s is None or not s["converged"]:
            raise RuntimeError(f"dynamic reference {tag} dt={dt} failed: {err or s.get('error')}")
        pos = at_times(track(s["_rows"], sensor), times)
        if pos is None:
            raise RuntimeError(f"dynamic reference {tag} dt={dt}: output times missing")
        tr.append(pos)
    coarse, fine = tr
    ref = [tuple(f + (f - c) / 3.0 for f, c in zip(pf, pc)) for pf, pc in zip(fine, coarse)]
    unc = max(dist(f, r) for f, r in zip(fine, ref))
    return ref, unc, fine


def dynamics(quick, log):
    points, notes = [], []
    # Soft seed pendulum, E = 3e7 Pa, 1 s.
    scene = "pendulum_soft_ancf"
    t_end = 0.2 if quick else 1.0
    times = [round(0.1 * k, 10) for k in range(1, int(round(t_end / 0.1)) + 1)]
    allv = beam_variants("rod", "rod")
    variants = pick(allv, ("ancf3243 full", "gef")) if quick else \
        [v for v in allv if v[0] not in ("ancf3273 full", "ancf3363 full")]
    base = [f"dynamic.t_end={t_end}"]
    # Reference: the planar Reissner beam of references/pendulum_reissner.py (numpy/scipy, an
    # implementation sharing nothing with ours), committed as references/data/pendulum_reissner.json.
    from references import pendulum_reissner
    reiss = pendulum_reissner.load()
    ref = [reiss[round(t, 10)][0] for t in times]
    ref_unc = max(reiss[round(t, 10)][1] for t in times)
    # our gef, Richardson-extrapolated in dt, as the stated check of that reference
    rmesh, rdts = (8, (1e-3, 5e-4)) if quick else (32, (5e-4, 2.5e-4))
    rsets = allv[8][1] + base
    gref, unc_dt, _ = richardson_reference(scene, rsets + [f"beam.rod.elements={rmesh}"], rdts, "B", times,
                                           f"pend-ref-{rmesh}")
    s, err = run(scene, rsets + [f"beam.rod.elements={rmesh // 2}", f"dynamic.dt={rdts[1]}"], "pend-ref-mesh")
    unc_mesh = math.nan
    if s is not None and s["converged"]:
        pos = at_times(track(s["_rows"], "B"), times)
        unc_mesh = max(dist(a, b) for a, b in zip(pos, gref)) if pos else math.nan
    gef_d = max(dist(a, b) for a, b in zip(gref, ref))
    notes.append(("pendulum", f"Reference: a planar geometrically exact (Reissner/Simo) beam written "
                  f"independently in numpy/scipy (references/pendulum_reissner.py: x, z, theta per node, "
                  f"quadratic elements, reduced integration, E and nu of the scene, Cowper shear factor, "
                  f"consistent translational and rotary inertia, pinned, released from the horizontal; "
                  f"solve_ivp Radau, rtol 1e-10), meshes of {', '.join(map(str, pendulum_reissner.meshes()))} "
                  f"elements Richardson-extrapolated point by point; "
                  f"committed as references/data/pendulum_reissner.json (regenerate: /usr/bin/python3 -m "
                  f"references.pendulum_reissner --write).  Its estimated error is at most {ref_unc:.1e} m at "
                  f"these times.  Check: our `gef` (resultant beam), {rmesh} elements, generalized-alpha "
                  f"(rho_inf = 0.8), dt = {rdts[0]} and {rdts[1]} s Richardson-extrapolated (its own estimates "
                  f"{unc_dt:.1e} m from the step, {unc_mesh:.1e} m between {rmesh // 2} and {rmesh} elements) is "
                  f"at most {gef_d:.1e} m from it.  The continuum ANCF elements converge towards the resultant "
                  f"model slowly (at 10 elements they are 1e-2 ... 6e-2 away, see the table); continuum and "
                  f"resultant models of this slender rod differ by order (h/L)^2 = 1e-4.  Error = max over "
                  f"t = 0.1, 0.2, ... {t_end} s of |r_B(t) - r_B,ref(t)| / L, L = 1 m."))
    meshes = (10,) if quick else (4, 16)
    dts = (1e-2, 2e-3) if quick else (1e-2, 5e-3, 2e-3, 1e-3)
    for label, sets in variants:
        for n in meshes:
            for dt in dts:
                s, err = run(scene, sets + base + [f"beam.rod.elements={n}", f"dynamic.dt={dt}"],
                             f"pend-{label.replace(' ', '_')}-{n}-{dt}")
                points.append(point(f"Soft pendulum ({t_end:g} s)", label, n, dt, s, err,
                                    lambda s: max(dist(a, b) for a, b in
                                                  zip(at_times(track(s["_rows"], "B"), times), ref)) / 1.0))
        log(f"  pendulum: {label}")

    # Falling silicone cantilever, 0.5 s.
    scene = "silicone_fall"
    t_end = 0.1 if quick else 0.5
    L = 0.25
    times = [round(0.05 * k, 10) for k in range(1, int(round(t_end / 0.05)) + 1)]
    base = [f"dynamic.t_end={t_end}"]
    cont = [("ancf3243 full", ["beam.strip.element=ancf3243", "beam.strip.integration=full"]),
            ("ancf3243 sri", ["beam.strip.element=ancf3243", "beam.strip.integration=sri"]),
            ("ancf3333 full", ["beam.strip.element=ancf3333", "beam.strip.integration=full"]),
            ("ancf3273 reduced", ["beam.strip.element=ancf3273", "beam.strip.integration=reduced"]),
            ("ancf3363 reduced", ["beam.strip.element=ancf3363", "beam.strip.integration=reduced"])]
    variants = pick(cont, ("ancf3243 sri", "ancf3363 reduced")) if quick else cont
    rmesh, rdts = (8, (5e-4, 2.5e-4)) if quick else (32, (5e-4, 2.5e-4))
    rsets = cont[4][1] + base
    ref, unc_dt, _ = richardson_reference(scene, rsets + [f"beam.strip.elements={rmesh}"], rdts, "tip", times,
                                          f"sil-ref-{rmesh}")
    s, err = run(scene, rsets + [f"beam.strip.elements={rmesh // 2}", f"dynamic.dt={rdts[1]}"], "sil-ref-mesh")
    unc_mesh = math.nan
    if s is not None and s["converged"]:
        pos = at_times(track(s["_rows"], "tip"), times)
        unc_mesh = max(dist(a, b) for a, b in zip(pos, ref)) if pos else math.nan
    # the independent check of that reference: CalculiX C3D20R, mesh-extrapolated
    # (references/data/calculix_silicone.json; its own error estimate ~2e-4 m)
    from calculix import reference_data
    ccx = reference_data("silicone_fall")
    ccx_pos = []
    for t in times:
        u, _ = ccx.at(t)
        ccx_pos.append((L + u[0], u[1], u[2]))
    ccx_dist = max(dist(a, b) for a, b in zip(ccx_pos, ref))
    ccx_err = max(max(e[0], e[2]) for _, _, e in ccx.history)
    notes.append(("silicone", f"Reference: CalculiX (ccx, C3D20R solid of the same strip, Arruda-Boyce, "
                  f"mesh-extrapolated; its own error estimate {ccx_err:.1e} m = {ccx_err / L:.1e} L; "
                  f"references/data/calculix_silicone.json).  Error = max over t = 0.05, 0.10, ... {t_end} s of "
                  f"|tip(t) - tip_ccx(t)| / L, L = 0.25 m.  The beams' own converged limit (`ancf3363` "
                  f"`reduced`, next section) is itself {ccx_dist:.1e} m ({ccx_dist / L:.1e} L) from the solid: "
                  f"the beam model's difference from a 3-D solid.  Coarser configurations can come closer than "
                  f"that, their discretization error partly cancelling it, so an error below {ccx_dist / L:.1e} "
                  f"here is agreement with the solid, not convergence (the headline's last column shows the "
                  f"closest; the next section shows the convergence).  "
                  f"Arruda-Boyce, kappa = 1000 mu: `ancf3243 full` and `ancf3333` lock volumetrically and level "
                  f"off far from the reference."))
    notes.append(("silicone_disc", f"Discretization error only, **not an independent reference**: the same runs "
                  f"against our own `ancf3363` `reduced` limit ({rmesh} elements, dt = {rdts[0]} and {rdts[1]} s, "
                  f"Richardson-extrapolated; estimated error {unc_dt:.1e} m from the step and {unc_mesh:.1e} m "
                  f"between {rmesh // 2} and {rmesh} elements), which is {ccx_dist:.1e} m ({ccx_dist / L:.1e} L) "
                  f"from the CalculiX solid above.  It shows how fast each element converges to its own limit; "
                  f"the accuracy against the physical strip is the section above."))
    # the solid's meshes (their tips at the study's end, 0.5 s, are recorded) in a
    # problem of their own: error of the tip at t_end
    from report.bench_solid import note as solid_note, solid_points
    solid_end = abs(t_end - 0.5) < 1e-12
    ccx_end = (L + ccx.value[0], ccx.value[1], ccx.value[2])
    if solid_end:
        points += solid_points(f"Silicone fall, tip at {t_end:g} s", ccx, L)
        notes.append(("silicone_end", "The same runs measured at t_end only, |tip(0.5 s) - tip_ccx(0.5 s)| / L, beside "
                      "the solid's meshes (the study keeps each mesh's tip at its end only).  "
                      + solid_note(ccx, "Arruda-Boyce, dynamic, 0.5 s")))
    meshes = (8,) if quick else (4, 8, 16)
    dts = (2e-3, 1e-3) if quick else (5e-3, 2e-3, 1e-3)
    for label, sets in variants:
        for n in meshes:
            for dt in dts:
                s, err = run(scene, sets + base + [f"beam.strip.elements={n}", f"dynamic.dt={dt}"],
                             f"sil-{label.replace(' ', '_')}-{n}-{dt}")
                points.append(point(f"Silicone fall ({t_end:g} s)", label, n, dt, s, err,
                                    lambda s: max(dist(a, b) for a, b in
                                                  zip(at_times(track(s["_rows"], "tip"), times), ccx_pos)) / L))
                if solid_end:           # the same run, measured at t_end only (beside the solid's meshes)
                    points.append(point(f"Silicone fall, tip at {t_end:g} s", label, n, dt, s, err,
                                        lambda s: dist(at_times(track(s["_rows"], "tip"), [t_end])[0],
                                                       ccx_end) / L))
                points.append(point(f"Silicone fall discretization ({t_end:g} s, vs converged ancf3363)", label,
                                    n, dt, s, err,
                                    lambda s: max(dist(a, b) for a, b in
                                                  zip(at_times(track(s["_rows"], "tip"), times), ref)) / L))
        log(f"  silicone: {label}")
    return points, notes
