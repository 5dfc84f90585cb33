"""The static hard cases: 1. compression far past buckling, 2. roll-up to two
turns (with its Newton convergence plot), 3. torsion, 5. nearly incompressible
Arruda-Boyce, 6. very slender and very thick cantilevers (report/hard.py)."""
import csv
import math

from report.hard_closed_forms import EI, L, M_TWO_TURNS, PCR, elastica_compressed
from report.hard_runs import CONTINUUM, RODS, RUNS, convergence_rate, element_sets, label, newton_rows, run


# --------------------------------------------------------------------- case 1
def case_compression(quick):
    lines = ["## 1. Compression far past buckling", "",
             f"Seed cantilever (L = 1 m, 10 mm square, E = 72 GPa, ν = 0), Euler load "
             f"P_cr = π²EI/(4L²) = {PCR:.3f} N.  Straight: the axial load alone in one step; "
             "the solver stays on the (unstable) straight branch and the inertia check reports "
             "the negative eigenvalues (expected: 2 per mode with (2k−1)² P_cr < P, i.e. 2 at −1 kN, "
             "8 at −10 kN) and the first critical load (bisection on the inertia of the tangent "
             "interpolated between the two equilibria).  Imperfect: plus 1 N lateral at the tip, "
             "20 load steps with `static.stable_path = true`; the tip vs the inextensible elastica.", "",
             "| element | load | straight: negative eig. (expected) | first critical load (N) | error vs P_cr | "
             "imperfect: converged, steps, cut-backs, iterations | tip x, z (m) | elastica x, z | tip error / L |",
             "|---|---|---|---|---|---|---|---|---|"]
    rows = []
    elems = [("ancf3243", "full"), ("ancf3243", "sri"), ("ancf3363", "reduced"), ("gef", None),
             ("euler_bernoulli", None), ("kirchhoff", None), ("ancf3243", "full", 40)]
    if quick:
        elems = [("ancf3243", "full"), ("gef", None)]
    for P in (1000.0, 10000.0):
        ex, ez = elastica_compressed(P)
        expect = 2 * sum(1 for k in range(1, 50) if (2 * k - 1) ** 2 * PCR < P)
        for element, integ, *nel in elems:
            es = element_sets("arm", element, integ) + [f"beam.arm.elements={nel[0] if nel else 10}"]
            name = label(element, integ) + (f", {nel[0]} el." if nel else "")
            s1 = run("cantilever_buckling_imperfect", es + [f"load.0.value.0={-P}", "load.1.value.2=0",
                                                            "static.load_steps=1"],
                     f"compress-straight-{element}-{integ}-{nel[0] if nel else 10}-{int(P)}")
            st = s1.get("stability", {})
            ev = st.get("events") or [{}]
            pc = (ev[0].get("critical_load_factor") or float("nan")) * P
            s2 = run("cantilever_buckling_imperfect", es + [f"load.0.value.0={-P}", "static.stable_path=true"],
                     f"compress-imperfect-{element}-{integ}-{nel[0] if nel else 10}-{int(P)}")
            tip = s2["sensors"]["tip"]["position"]
            err = math.hypot(tip[0] - ex, tip[2] - ez)
            rows.append(dict(element=name, load=P, negative=st.get("negative_eigenvalues"),
                             expected=expect, p_crit=pc, imperfect_converged=s2["converged"],
                             steps=s2["steps"], cutbacks=s2["cutbacks"], iterations=s2["newton_iterations"],
                             tip_x=tip[0], tip_z=tip[2], elastica_x=ex, elastica_z=ez, tip_error=err))
            lines.append(f"| {name} | −{P / 1000:g} kN | {st.get('negative_eigenvalues')} ({expect}) | "
                         f"{pc:.2f} | {100 * (pc / PCR - 1):+.2f} % | {s2['converged']}, {s2['steps']}, "
                         f"{s2['cutbacks']}, {s2['newton_iterations']} | {tip[0]:.4f}, {tip[2]:.4f} | "
                         f"{ex:.4f}, {ez:.4f} | {err:.2e} |")
    lines += ["", "The inertia count is right for every element (2 negative eigenvalues per buckling mode passed).  "
              "The bisection estimate of the first critical load is within 0.2 % of P_cr for the ANCF "
              "elements, `gef` and `kirchhoff`; for `euler_bernoulli` it is off by 5–19 %: its internal "
              "multipliers are regularized in the inertia check (see runtime/solver/stability.h), which perturbs the "
              "nearly singular interpolated tangents the bisection probes.  On the imperfect path "
              "`euler_bernoulli` needs many cut-backs (its inertia flickers near the critical load) and at "
              "−10 kN ends on another equilibrium than the elastica's.  ANCF continuum elements with 10 "
              "elements are coarse at these curvatures (the clamp curvature at −1 kN is about 8 /m): "
              "`ancf3243` with 40 elements is within 3e-3 L of the elastica at −1 kN and 9e-3 L at −10 kN.  "
              "Without `stable_path` the imperfect runs at −10 kN stay near the straight, unstable branch "
              "(the count of negative eigenvalues in `summary.json` says so).", ""]
    return lines, rows


# --------------------------------------------------------------------- case 2
def case_rollup(quick):
    lines = ["## 2. Roll-up to two full turns", "",
             f"End moment 4πEI/L = {M_TWO_TURNS:.4f} N m on the seed cantilever (10 elements); the fewest "
             "equal load steps (tried 1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48) that converge with "
             "`max_cutbacks = 0` (default secant predictor, 25 iterations per step).  The exact "
             "tip is back at the clamp; the rate is the observed order of the last Newton iterations.", "",
             "| element | fewest steps | Newton iterations | tip distance from the clamp / L | order at the last iteration | wall (s) |",
             "|---|---|---|---|---|---|"]
    rows = []
    elems = [(e, None) for e in RODS] + CONTINUUM
    if quick:
        elems = [("gef", None), ("ancf3243", "full")]
    for element, integ in elems:
        found = None
        for n in (1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48):
            s = run("cantilever_rollup", element_sets("arm", element, integ) +
                    [f"load.0.value.2={M_TWO_TURNS!r}", f"static.load_steps={n}", "static.max_cutbacks=0",
                     "static.stability=false"], f"rollup-{element}-{integ}")
            if s["converged"]:
                found = (n, s)
                break
        if not found:
            lines.append(f"| {label(element, integ)} | > 48 | | | | |")
            rows.append(dict(element=label(element, integ), steps=None))
            continue
        n, s = found
        tip = s["sensors"]["tip"]["position"]
        d = math.hypot(tip[0], tip[1])
        rate = convergence_rate(s["_out"])
        rows.append(dict(element=label(element, integ), steps=n, iterations=s["newton_iterations"],
                         tip_distance=d, rate=rate, wall=s["_wall"]))
        lines.append(f"| {label(element, integ)} | {n} | {s['newton_iterations']} | {d:.2e} | {rate:.2f} | "
                     f"{s['_wall']:.1f} |")
    lines += ["", "Before the rotation trust region (quaternion updates limited to 0.15, unit quaternions after "
              "every update) `gef` and `euler_bernoulli` needed 24 steps.  The continuum elements' tip error is "
              "their discretization error at a curvature of 4π/m with 10 elements (see "
              "`seed_tables.md` for the one-turn case).", ""]
    return lines, rows


# --------------------------------------------------------------------- case 3
def case_torsion(quick):
    lines = ["## 3. Torsion past the twisted-shaft buckling load", "",
             "Seed Table 6 (100 N m about the axis, ν = 0.3, 10 elements, 50 load steps, "
             "`stable_path` off so the straight twisted path is followed): the twist along the path and the "
             "changes of the tangent's inertia.  For the clamped-free shaft under an axial torque the "
             "classical (Greenhill) instability appears when M L/√(EI₁ EI₂) reaches about π "
             "(load-type dependent); here M_G = π√(EI₁EI₂)/L ≈ "
             f"{math.pi * EI / L:.1f} N m for the reference.", "",
             "| element | converged | twist at 100 N m (°) | T L/(G J) (°) | stability events (load factor → N m) | "
             "negative eig. at the end |",
             "|---|---|---|---|---|---|"]
    rows = []
    G, J = 7.2e10 / 2.6, 0.1406e-8
    lin = 100.0 * L / (G * J) * 180 / math.pi
    elems = [("gef", None), ("ancf3243", "sri"), ("ancf3363", "reduced")]
    if quick:
        elems = [("gef", None)]
    for element, integ in elems:
        s = run("cantilever_torsion_100Nm", element_sets("arm", element, integ), f"torsion-{element}-{integ}")
        with open(s["_out"] / "sensors.csv", newline="") as fh:
            tr = [r for r in csv.DictReader(fh) if r["sensor"] == "tip"]
        # twist of d1 about the axis, unwrapped along the path
        ang, prev = 0.0, 0.0
        for r in tr:
            a = math.atan2(float(r["d1z"]), float(r["d1y"]))
            da = (a - prev + math.pi) % (2 * math.pi) - math.pi
            ang += da
            prev = a
        ev = s.get("stability", {}).get("events", [])
        evs = ", ".join(f"{e['negative_before']}→{e['negative_after']} at "
                        f"{100 * (e['critical_load_factor'] or float('nan')):.1f}" for e in ev) or "none"
        rows.append(dict(element=label(element, integ), converged=s["converged"], twist_deg=math.degrees(ang),
                         linear_deg=lin, events=evs, negative=s.get("stability", {}).get("negative_eigenvalues")))
        lines.append(f"| {label(element, integ)} | {s['converged']} | {math.degrees(ang):.2f} | {lin:.2f} | {evs} | "
                     f"{s.get('stability', {}).get('negative_eigenvalues')} |")
    lines += ["", "ABAQUS's 213° in the seed is a buckled, out-of-plane configuration.  The torque here is "
              "fixed in space (an axial torque): on a cantilever that load is not conservative, the tangent is "
              "not symmetric, and its loss of stability is not a static bifurcation that the inertia of the "
              "symmetric part detects.  No change of inertia is found on the straight path up to 100 N m; "
              "detecting the torsional (Greenhill) instability needs the unsymmetric eigenproblem or a "
              "dynamic perturbation run — not done yet.", ""]
    return lines, rows


# --------------------------------------------------------------------- case 5
def case_incompressible(quick):
    lines = ["## 5. Nearly incompressible Arruda–Boyce", "",
             "Silicone strip (0.25 × 0.02 × 0.01 m, μ = 0.3 MPa, λ_m = 3, ρ = 1100) sagging under gravity, "
             "8 elements, 10 load steps; tip deflection relative to `ancf3363 (reduced)` with 32 elements at the "
             "same κ (locking shows as a too-small deflection), Newton iterations, cut-backs.", "",
             "| element | κ/μ | converged | tip w (mm) | w / w_ref | iterations | cut-backs | rate |",
             "|---|---|---|---|---|---|---|---|"]
    rows = []
    elems = CONTINUUM if not quick else [("ancf3243", "full"), ("ancf3363", "reduced")]
    for ratio in (1e3, 1e4):
        kappa = ratio * 3.0e5
        ref = run("silicone_cantilever_sag", ["beam.strip.element=ancf3363", "beam.strip.integration=reduced",
                                              f"beam.strip.elements={16 if quick else 32}",
                                              f"material.silicone.kappa={kappa!r}"], f"incomp-ref-{ratio:g}")
        wref = ref["sensors"]["tip"]["displacement"][2]
        for element, integ in elems:
            s = run("silicone_cantilever_sag", [f"beam.strip.element={element}", f"beam.strip.integration={integ}",
                                                f"material.silicone.kappa={kappa!r}"],
                    f"incomp-{element}-{integ}-{ratio:g}")
            w = s["sensors"]["tip"]["displacement"][2] if s["converged"] else float("nan")
            rate = convergence_rate(s["_out"])
            rows.append(dict(element=label(element, integ), kappa_over_mu=ratio, converged=s["converged"],
                             w=w, ratio=w / wref, iterations=s["newton_iterations"], cutbacks=s["cutbacks"],
                             rate=rate))
            lines.append(f"| {label(element, integ)} | {ratio:g} | {s['converged']} | {1e3 * w:.3f} | "
                         f"{w / wref:.3f} | {s['newton_iterations']} | {s['cutbacks']} | {rate:.2f} |")
    lines.append("")
    return lines, rows


# --------------------------------------------------------------------- case 6
def case_slenderness(quick):
    lines = ["## 6. Very slender and very thick beams", "",
             "Cantilever L = 1 m, square section h = L/1000 or L/5, E = 72 GPa, ν = 0.3, 10 elements, tip "
             "force giving a linear deflection of 1e-3 L (1 step): tip deflection vs Timoshenko beam theory "
             "δ = PL³/(3EI) + PL/(κGA) (κ = 5/6), the tangent's condition estimate |λ|max/|λ|min at the "
             "reference (inertia check) and KLU's pivot ratio.", "",
             "| element | L/h | converged | δ / δ_beam − 1 | cond. estimate | KLU rcond | iterations |",
             "|---|---|---|---|---|---|---|"]
    rows = []
    E, nu = 7.2e10, 0.3
    G = E / (2 * (1 + nu))
    elems = [("ancf3243", "full"), ("ancf3243", "sri"), ("ancf3363", "reduced"), ("ancf3273", "full"),
             ("gef", None), ("euler_bernoulli", None), ("kirchhoff", None), ("ancf_cable", None)]
    if quick:
        elems = [("ancf3243", "sri"), ("gef", None)]
    for slender in (1000, 5):
        h = L / slender
        I, A = h ** 4 / 12, h * h
        P = 1e-3 * L * 3 * E * I / L ** 3
        for element, integ in elems:
            shear = P * L / (5 / 6 * G * A) if element in ("gef",) or element.startswith("ancf3") else 0.0
            ref = P * L ** 3 / (3 * E * I) + shear
            sets = element_sets("arm", element, integ) + [
                f"section.square.b={h!r}", f"section.square.h={h!r}", f"load.0.value.2={-P!r}",
                "static.load_steps=1", "material.alu.nu=0.3", "static.eigenvalues=true"]
            s = run("cantilever_bend_10N", sets, f"slender-{element}-{integ}-{slender}")
            w = -s["sensors"]["tip"]["displacement"][2] if s["converged"] else float("nan")
            st = s.get("stability", {})
            with open(s["_out"] / "stability.csv", newline="") as fh:
                r0 = next(csv.DictReader(fh))
            cond = float(r0["eig_max"]) / abs(float(r0["eig_min"])) if float(r0["eig_min"]) else float("inf")
            rc = [float(r["rcond"]) for r in newton_rows(s["_out"]) if r["rcond"] not in ("", "0.000e+00")]
            rows.append(dict(element=label(element, integ), slenderness=slender, converged=s["converged"],
                             rel_error=w / ref - 1, cond=cond, rcond=min(rc) if rc else float("nan"),
                             iterations=s["newton_iterations"]))
            lines.append(f"| {label(element, integ)} | {slender} | {s['converged']} | {w / ref - 1:+.2e} | "
                         f"{cond:.1e} | {min(rc) if rc else float('nan'):.1e} | {s['newton_iterations']} |")
            del st
    lines += ["", "Euler–Bernoulli, Kirchhoff and the cable have no shear compliance, compared with PL³/(3EI) "
              "alone; the ANCF continuum elements and `gef` with the Timoshenko value.  ν = 0.3 makes "
              "`ancf3243` full integration lock (Poisson locking), as in the seed tables.", ""]
    return lines, rows


def plot_rollup_iterations(path):
    """Residual history of the two-turn roll-up per element (the first solve)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for d in sorted(RUNS.glob("rollup-*")):
        try:
            rows = newton_rows(d)
        except OSError:
            continue
        last = rows[-1]["attempt"] if rows else None
        r = [float(x["residual"]) / max(float(x["reference"]), 1e-300) for x in rows if x["attempt"] == last]
        if r:
            ax.semilogy(range(len(r)), r, marker=".", label=d.name.replace("rollup-", "").replace("-None", ""))
    ax.set_xlabel("Newton iteration (last load step)")
    ax.set_ylabel("relative residual")
    ax.set_title("Roll-up to two turns: Newton convergence")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
