"""./build.sh bench: speed against error.  Writes out/report/bench.md, CSV files
(out/report/bench_*.csv) and PNG plots (out/report/bench_*.png):

  * work-precision diagrams: statics (seed Table 3 at -100 N, nu = 0.3, and the
    full roll-up of Table 5), dynamics (soft seed pendulum over 1 s, falling
    silicone cantilever over 0.5 s), one curve per element / integration
    variant, points for meshes and time steps; Pareto-optimal configurations for
    1e-2, 1e-3 and 1e-4 relative error;
  * kernels: time per internal-force and per force + tangent evaluation of every
    element x material pair, operation counts, GFLOP/s, ratio to the plain
    quadrature loop (bench/plain.c);
  * scaling: time per Newton iteration and peak memory for 10 ... 100,000
    elements, fitted exponent;
  * toolchain: regeneration time per kernel, per-scene solver compile time and size.

usage: ./build.sh bench [--quick]
"""
import csv
import json
import math
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from gen.cli import execute  # noqa: E402
from gen.scene import ROOT, SceneError  # noqa: E402
from report import bench_kernels, bench_targets  # noqa: E402

OUT = ROOT / "out" / "report"
WORK = OUT / "bench"
TOLS = (1e-2, 1e-3, 1e-4)

FREE = ["constraint.0.cross_section=free"]


def beam_variants(beam, law_key):
    """(label, --set overrides) of every element / integration variant."""
    res = [f"material.{law_key}.law=resultant"]
    b = f"beam.{beam}"
    return [
        ("ancf3243 full", [f"{b}.element=ancf3243", f"{b}.integration=full"]),
        ("ancf3243 sri", [f"{b}.element=ancf3243", f"{b}.integration=sri"]),
        ("ancf3333 full", [f"{b}.element=ancf3333", f"{b}.integration=full"]),
        ("ancf3273 reduced", [f"{b}.element=ancf3273", f"{b}.integration=reduced"]),
        ("ancf3273 full", [f"{b}.element=ancf3273", f"{b}.integration=full"]),
        ("ancf3363 reduced", [f"{b}.element=ancf3363", f"{b}.integration=reduced"]),
        ("ancf3363 full", [f"{b}.element=ancf3363", f"{b}.integration=full"]),
        ("ancf_cable", [f"{b}.element=ancf_cable"] + res),
        ("gef", [f"{b}.element=gef"] + res),
        ("euler_bernoulli", [f"{b}.element=euler_bernoulli"] + res),
        ("kirchhoff", [f"{b}.element=kirchhoff"] + res),
    ]


def pick(variants, labels):
    return [v for v in variants if v[0] in labels]


# ---------------------------------------------------------------- running

def run(scene, sets, tag):
    """Run a scene; returns dict(summary, rows) or None with the error text."""
    out = WORK / "runs" / tag
    try:
        rc, out = execute(scene, sets, out)
    except SceneError as e:
        return None, str(e).strip()
    sp = out / "summary.json"
    if not sp.exists():
        return None, f"no summary (exit status {rc})"
    s = json.loads(sp.read_text())
    rows = []
    with open(out / "sensors.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    s["_rows"] = rows
    s["_rc"] = rc
    return s, None


def tip_xyz(s, sensor):
    p = s["sensors"][sensor]["position"]
    return [float(v) for v in p]


def track(rows, sensor):
    """{time: (x, y, z)} of one sensor."""
    out = {}
    for r in rows:
        if r["sensor"] == sensor:
            out[float(r["time"])] = (float(r["x"]), float(r["y"]), float(r["z"]))
    return out


def at_times(tr, times):
    """Positions at the given times: the stored time within 1e-7 s, else linear
    interpolation between the bracketing stored times (steps that a cut-back
    moved off the grid); None when a time is outside the run."""
    import bisect
    keys = sorted(tr)
    res = []
    for t in times:
        i = bisect.bisect_left(keys, t - 1e-7)
        if i < len(keys) and abs(keys[i] - t) <= 1e-7:
            res.append(tr[keys[i]])
            continue
        if i == 0 or i >= len(keys):
            return None
        t0, t1 = keys[i - 1], keys[i]
        a = (t - t0) / (t1 - t0)
        res.append(tuple((1 - a) * x0 + a * x1 for x0, x1 in zip(tr[t0], tr[t1])))
    return res


def dist(a, b):
    return math.sqrt(sum((x - y)**2 for x, y in zip(a, b)))


# ---------------------------------------------------------------- statics

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


def point(problem, label, n, dt, s, err, errfun):
    p = {"problem": problem, "variant": label, "elements": n, "dt": dt, "converged": False,
         "wall_s": math.nan, "newton_iterations": None, "steps": None, "error": math.nan, "failure": err or ""}
    if s is not None:
        p["converged"] = bool(s["converged"]) and s["_rc"] == 0
        p["wall_s"] = float(s["wall_s"])
        p["newton_iterations"] = s.get("newton_iterations")
        p["steps"] = s.get("steps")
        if p["converged"]:
            try:
                p["error"] = errfun(s)
            except (KeyError, TypeError, ValueError) as e:
                p["failure"] = f"no error: {e}"
        else:
            p["failure"] = (s.get("error") or f"exit status {s['_rc']}").splitlines()[0][:120]
    return p


# ---------------------------------------------------------------- dynamics

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
                points.append(point(f"Silicone fall discretization ({t_end:g} s, vs converged ancf3363)", label,
                                    n, dt, s, err,
                                    lambda s: max(dist(a, b) for a, b in
                                                  zip(at_times(track(s["_rows"], "tip"), times), ref)) / L))
        log(f"  silicone: {label}")
    return points, notes


# ---------------------------------------------------------------- Pareto

def pareto(points):
    """Marks p['pareto'] (no other point of the problem is both faster and more
    accurate) and returns {problem: {tol: fastest point with error <= tol}}."""
    best = {}
    probs = []
    for p in points:
        if p["problem"] not in probs:
            probs.append(p["problem"])
    for prob in probs:
        ok = [p for p in points if p["problem"] == prob and p["converged"] and math.isfinite(p["error"])]
        for p in points:
            if p["problem"] == prob:
                p["pareto"] = p in ok and not any(
                    (q["wall_s"] <= p["wall_s"] and q["error"] <= p["error"] and
                     (q["wall_s"] < p["wall_s"] or q["error"] < p["error"])) for q in ok)
        best[prob] = {}
        for tol in TOLS:
            cand = [p for p in ok if p["error"] <= tol]
            best[prob][tol] = min(cand, key=lambda p: p["wall_s"]) if cand else None
    return best


def config(p):
    s = f"{p['variant']}, {p['elements']} el."
    if p["dt"] is not None:
        s += f", dt = {p['dt']:g} s"
    return s


def plot_wp(points, problem, path):
    fig, ax = plt.subplots(figsize=(8, 5.5))
    labels = []
    for p in points:
        if p["problem"] == problem and p["variant"] not in labels:
            labels.append(p["variant"])
    markers = "os^vD<>phX*"
    for i, lab in enumerate(labels):
        pts = [p for p in points if p["problem"] == problem and p["variant"] == lab and p["converged"]
               and math.isfinite(p["error"]) and p["error"] > 0]
        if not pts:
            continue
        groups = {}
        for p in pts:
            groups.setdefault(p["elements"] if p["dt"] is not None else None, []).append(p)
        first = True
        for key, g in groups.items():
            g.sort(key=lambda p: (p["dt"] is None, -(p["dt"] or 0), p["elements"]))
            ls = "-" if key is None or key == max(k for k in groups if k is not None) else ":"
            ax.loglog([p["wall_s"] for p in g], [p["error"] for p in g], ls, marker=markers[i % len(markers)],
                      color=f"C{i % 10}", ms=4, lw=1, label=lab if first else None)
            first = False
    front = sorted([p for p in points if p["problem"] == problem and p.get("pareto")], key=lambda p: p["wall_s"])
    if front:
        ax.loglog([p["wall_s"] for p in front], [p["error"] for p in front], "k--", lw=0.8, label="Pareto front")
    for tol in TOLS:
        ax.axhline(tol, color="0.7", lw=0.5)
    ax.set_xlabel("solver wall time (s)")
    ax.set_ylabel("relative error")
    ax.set_title(problem)
    ax.grid(True, which="both", lw=0.2)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---------------------------------------------------------------- scaling

SCALING_PASSES = 3


def scaling(quick, log):
    """Time per Newton iteration (assembly + factorization + solve) and peak
    memory for one long ancf3243 x svk beam (elements of 0.1 m)."""
    from gen.scene import build, load_index, write_model
    from gen.solver_build import BUILD, VARIANTS, compile_object, build_solver, runtime_headers
    index = load_index()
    obj = BUILD / "release" / "bench" / "newton_iter.o"
    compile_object(ROOT / "bench" / "newton_iter.c", obj, VARIANTS["release"], runtime_headers())
    from gen.solver_build import runtime_objects
    robjs = [o for o in runtime_objects("release") if o.stem != "main"]
    exe = build_solver(["ancf3243_svk_full"], BUILD / "release" / "bench" / "bench_newton", index, "release",
                       main_objs=[obj] + robjs)
    sizes = (10, 100, 1000) if quick else (10, 30, 100, 300, 1000, 3000, 10000, 30000, 100000)
    scene = ROOT / "models" / "cantilever_bend_10N.toml"

    def one(n, threads, mpath):
        nit = 11 if n < 3000 else 7 if n <= 10000 else 5   # medians of 5 at least: single runs here scatter by ±15 %
        env = dict(os.environ, OMP_NUM_THREADS=str(threads))
        r = subprocess.run([str(exe), str(mpath), str(nit)], capture_output=True, text=True, env=env)
        if r.returncode != 0:
            raise RuntimeError(f"bench_newton {n} elements failed: {r.stderr[-500:]}")
        d = dict(line.split("=", 1) for line in r.stdout.split())
        row = {"elements": n, "threads": threads, "iterations": nit}
        for k, v in d.items():
            row[k] = float(v) if "." in v or "e" in v else int(v)
        return row

    # Every mesh is timed in SCALING_PASSES interleaved passes and keeps its
    # fastest (the host's slow spells last seconds to tens of seconds: they
    # reach one pass of a mesh, not all; the same estimator at every size, so
    # the exponent compares like with like).  The meshes up to 10,000 elements
    # are written once; the larger ones (hundreds of MB) anew in each pass.
    small = [n for n in sizes if n <= 10000]
    paths = {}
    for n in small:
        paths[n] = WORK / f"scaling_{n}.dat"
        write_model(build(scene, [f"beam.arm.elements={n}", f"beam.arm.end.0={0.1 * n}"]), paths[n])
    best = {}
    speedups = {}                       # n: the 2-thread speedups of the assembly, one a pass
    npass = 1 if quick else SCALING_PASSES
    for k in range(npass):
        for n in sizes:
            mpath = paths.get(n)
            if mpath is None:
                mpath = WORK / f"scaling_{n}.dat"
                write_model(build(scene, [f"beam.arm.elements={n}", f"beam.arm.end.0={0.1 * n}"]), mpath)
            pair = {}
            for threads in ((1, 2) if n in (1000, 10000) else (1,)):
                row = one(n, threads, mpath)
                pair[threads] = row["assembly_s"]
                old = best.get((n, threads))
                if old is None or row["iteration_s"] < old["iteration_s"]:
                    best[n, threads] = row
                # the fastest assembly on its own (the thread comparison's measure), over the passes
                best[n, threads]["assembly_min_s"] = min(row["assembly_s"], old["assembly_min_s"] if old else math.inf)
            if 2 in pair:                # back-to-back runs: a slow spell of the host reaches both alike
                speedups.setdefault(n, []).append(pair[1] / pair[2])
            if n not in paths:
                mpath.unlink()
                log(f"  scaling: {n} elements, pass {k + 1}")
        log(f"  scaling: pass {k + 1} done")
    for n in small:
        paths[n].unlink()
    for n, v in speedups.items():
        best[n, 2]["assembly_speedup"] = statistics.median(v)
    return [best[k] for k in sorted(best)]


def fit_exponent(rows, lo=100, hi=10000, threads=1):
    pts = [(math.log(r["elements"]), math.log(r["iteration_s"])) for r in rows
           if lo <= r["elements"] <= hi and r["threads"] == threads]
    if len(pts) < 2:
        return math.nan
    n = len(pts)
    mx, my = sum(p[0] for p in pts) / n, sum(p[1] for p in pts) / n
    return sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx)**2 for x, _ in pts)


# ---------------------------------------------------------------- toolchain

def toolchain(quick, log):
    from gen.generate import generate
    res = {"regen": [], "compile": {}}
    tmp = Path(tempfile.mkdtemp(prefix="bk-bench-gen-"))
    try:
        lines = []
        only = "ancf3243_svk" if quick else None
        t0 = time.time()
        generate(tmp / "kernels", force=True, log=lines.append, only=only)
        res["regen_total_s"] = time.time() - t0
        res["regen_scope"] = "ancf3243_svk only (--quick)" if quick else "every element and pair (2 worker processes)"
        for ln in lines:
            ln = ln.strip()
            if ": generated (" in ln:
                name, rest = ln.split(": generated (")
                res["regen"].append((name, float(rest.rstrip(" s)"))))
        t0 = time.time()
        lines = []
        generate(tmp / "kernels", log=lines.append, only=only)
        res["regen_incremental_s"] = time.time() - t0
        res["regen_incremental_redone"] = sum(": generated" in x for x in lines)
        log("  toolchain: regeneration")
        # A per-scene solver from scratch in an empty build directory.
        import gen.solver_build as sb
        from gen.scene import build, load_index
        index = load_index()
        model = build(ROOT / "models" / "cantilever_bend_100N.toml", [])
        old = sb.BUILD
        sb.BUILD = tmp / "build"
        try:
            t0 = time.time()
            robjs = sb.runtime_objects("release")
            t1 = time.time()
            exe = sb.build_solver(model["pairs"], tmp / "solver", index, "release", main_objs=robjs)
            t2 = time.time()
        finally:
            sb.BUILD = old
        nm = subprocess.run(["nm", str(exe)], capture_output=True, text=True).stdout
        linked = sorted({w.split()[-1][len("bk_pair_"):] for w in nm.splitlines() if " bk_pair_" in w})
        strip_size = None
        try:
            shutil.copy(exe, tmp / "solver.stripped")
            subprocess.run(["strip", str(tmp / "solver.stripped")], check=True)
            strip_size = (tmp / "solver.stripped").stat().st_size
        except (OSError, subprocess.CalledProcessError):
            pass
        res["compile"] = {"scene": "cantilever_bend_100N", "pairs": model["pairs"], "runtime_s": t1 - t0,
                          "kernels_and_link_s": t2 - t1, "size": exe.stat().st_size, "stripped_size": strip_size,
                          "linked_pairs": linked}
        log("  toolchain: solver compile")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return res


# ---------------------------------------------------------------- report

def fmt_t(t):
    if not math.isfinite(t):
        return "n/a"
    if t < 1e-3:
        if t < 1e-5:
            return f"{t * 1e6:.2f} us"
        return f"{t * 1e6:.1f} us" if t < 1e-4 else f"{t * 1e3:.2f} ms"
    return f"{t * 1e3:.1f} ms" if t < 1 else f"{t:.2f} s"


def write_csv(path, rows, keys):
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow(r)


def main(argv):
    quick = "--quick" in argv
    unknown = [a for a in argv if a != "--quick"]
    if unknown:
        print(f"error: bench: unknown argument {unknown[0]!r} (usage: ./build.sh bench [--quick])", file=sys.stderr)
        return 1
    OUT.mkdir(parents=True, exist_ok=True)
    WORK.mkdir(parents=True, exist_ok=True)
    t_all = time.time()

    def log(s):
        print(f"[{time.time() - t_all:6.1f} s]{s}", file=sys.stderr, flush=True)

    log(" kernels")
    only = None
    if quick:
        only = {"ancf3243_svk_full", "ancf3243_svk_sri", "ancf3363_arruda_boyce_reduced", "ancf3363_svk_reduced",
                "ancf3333_neo_hookean_full", "gef_resultant_full", "ancf_cable_resultant_full"}
    peaks = [bench_kernels.measured_peak()]       # before and after the kernels: the faster of the two
    krows = bench_kernels.run(WORK, repeats=3 if quick else 5, target=0.001 if quick else 0.004, only=only,
                              passes=1 if quick else 3)
    peaks.append(bench_kernels.measured_peak())
    cpu = bench_kernels.cpu_peak()
    cpu["nominal_gflops"], cpu["peak_gflops"] = cpu["peak_gflops"], max(peaks)
    log(" statics")
    spoints, snotes = statics(quick, log)
    log(" dynamics")
    dpoints, dnotes = dynamics(quick, log)
    points = spoints + dpoints
    best = pareto(points)
    log(" scaling")
    srows = scaling(quick, log)
    log(" toolchain")
    tc = toolchain(quick, log)
    log(" targets around the solve")
    targets = bench_targets.measure(WORK, quick, log)
    (OUT / "bench_targets.json").write_text(json.dumps(targets, indent=1) + "\n")

    # ---- files
    write_csv(OUT / "bench_workprecision.csv", points,
              ["problem", "variant", "elements", "dt", "converged", "wall_s", "newton_iterations", "steps",
               "error", "pareto", "failure"])
    write_csv(OUT / "bench_kernels.csv", krows,
              ["pair", "element", "material", "integration", "ndof", "nqp", "ops_force", "ops_force_tangent",
               "hdr_force_per_point", "hdr_force_tangent_per_point", "lanes", "t_force_s", "t_force_tangent_s",
               "t_scalar_force_s", "t_scalar_force_tangent_s",
               "gflops_force", "gflops_force_tangent", "t_plain_force_s", "t_plain_force_tangent_s",
               "speedup_force", "speedup_force_tangent", "plain_rel_diff_f", "plain_rel_diff_K", "lanes_rel_diff"])
    write_csv(OUT / "bench_scaling.csv", srows,
              ["elements", "threads", "dofs", "equations", "nnz", "iterations", "iteration_s", "assembly_s", "assembly_min_s",
               "factor_s", "solve_s", "setup_s", "analyses", "factorizations", "full_factorizations", "maxrss_kb"])
    write_csv(OUT / "bench_toolchain.csv", [{"unit": n, "regen_s": t} for n, t in tc["regen"]], ["unit", "regen_s"])
    problems = []
    for p in points:
        if p["problem"] not in problems:
            problems.append(p["problem"])
    pngs = {}
    for prob in problems:
        slug = prob.split(" (")[0].lower().replace(" ", "_").replace("-", "")
        pngs[prob] = OUT / f"bench_wp_{slug}.png"
        plot_wp(points, prob, pngs[prob])
    plot_scaling(srows, OUT / "bench_scaling.png")
    plot_kernels(krows, cpu, OUT / "bench_kernels.png")

    # ---- targets
    def kr(name):
        return next((r for r in krows if r["pair"] == name), None)
    k1, k2 = kr("ancf3243_svk_full"), kr("ancf3363_arruda_boyce_reduced")
    ops_pt = int(k1["hdr_force_tangent_per_point"]) if k1 and k1["hdr_force_tangent_per_point"].isdigit() else None
    expo = fit_exponent(srows, 100, 10000 if not quick else 1000)
    expo_big = fit_exponent(srows, 1000, 100000) if not quick else math.nan
    s1 = {r["elements"]: r for r in srows if r["threads"] == 1}
    s2 = {r["elements"]: r for r in srows if r["threads"] == 2}
    nbig = max(s2) if s2 else None
    par = s2[nbig].get("assembly_speedup", s1[nbig]["assembly_s"] / s2[nbig]["assembly_s"]) \
        if nbig in s2 else math.nan
    big = max((r for r in srows if r["threads"] == 1), key=lambda r: r["elements"])
    # memory per element: the slope of the peak memory between the two largest runs
    n_a, n_b = sorted(s1)[-2:] if len(s1) >= 2 else (None, None)
    kb_per_el = ((s1[n_b]["maxrss_kb"] - s1[n_a]["maxrss_kb"]) / (n_b - n_a)) if n_a else math.nan
    load = os.getloadavg()
    regen_total = tc["regen_total_s"]

    def met(ok):
        return "met" if ok else "**missed**"

    L = ["# Speed against error (`./build.sh bench" + (" --quick`)" if quick else "`)"), ""]
    L += [f"CPU: {cpu['model']}, {cpu['mhz']:.0f} MHz, {os.cpu_count()} cores; {cpu['isa']}: "
          f"{cpu['flops_per_cycle']} double flop/cycle/core.  Peak {cpu['peak_gflops']:.1f} GFLOP/s per core, "
          f"measured (`bench/peak.c`: chains of fused multiply-adds on 8-double vectors, the faster of a run "
          f"before and one after the kernels); every share of peak below is of this figure.  Read off "
          f"/proc/cpuinfo (flop/cycle x nominal MHz) it would be {cpu['nominal_gflops']:.1f} GFLOP/s, which "
          f"assumes the nominal clock under vector load and the FMA units of the flags' widest ISA.  "
          f"Kernels and solvers compiled with `{' '.join(bench_kernels_flags())}`; the lane kernels (8 elements "
          f"per call) prefer 512-bit vectors (`BK_LANE_TARGET`, gen/emit.py).  Wall times are the solver's "
          f"own (`summary.json` `wall_s`: model read to results written), on a shared machine: expect a few "
          f"% noise." + (f"  **--quick**: a subset (fewer variants, meshes and steps, shorter dynamics)." if quick
                         else ""), ""]
    L += ["## Headline", "",
          "Fastest configuration reaching each relative error (Pareto-optimal; error definitions and references "
          "below), and the configuration closest to the reference:", "",
          "| problem | ≤ 1e-2 | ≤ 1e-3 | ≤ 1e-4 | lowest error |", "|---|---|---|---|---|"]
    for prob in problems:
        cells = []
        for tol in TOLS:
            b = best[prob][tol]
            cells.append(f"{config(b)}: {fmt_t(b['wall_s'])} (err {b['error']:.1e})" if b else "not reached")
        ok = [p for p in points if p["problem"] == prob and p["converged"] and math.isfinite(p["error"])]
        low = min(ok, key=lambda p: (p["error"], p["wall_s"])) if ok else None
        cells.append(f"{config(low)}: {fmt_t(low['wall_s'])} (err {low['error']:.1e})" if low else "none")
        L.append(f"| {prob} | " + " | ".join(cells) + " |")
    L += ["", "| target | measured | status |", "|---|---|---|"]
    if k1:
        L.append(f"| ancf3243 x svk force + upper tangent ≤ 3,000 operations per quadrature point | "
                 f"{ops_pt} per point ({k1['ops_force_tangent']} per element, 12 points) | {met(ops_pt and ops_pt <= 3000)} |")
        L.append(f"| ancf3243 x svk generated ≥ 5x the plain loop (force + tangent) | "
                 f"{k1['speedup_force_tangent']:.1f}x ({fmt_t(k1['t_force_tangent_s'])} vs "
                 f"{fmt_t(k1['t_plain_force_tangent_s'])}), {k1['gflops_force_tangent']:.2f} GFLOP/s = "
                 f"{100 * k1['gflops_force_tangent'] / cpu['peak_gflops']:.0f} % of one core's peak | "
                 f"{met(k1['speedup_force_tangent'] >= 5)} |")
    k3 = kr("ancf3243_svk_sri")
    if k3:
        L.append(f"| ancf3243 x svk `sri` force + tangent ≤ 0.9 µs per element on one core | "
                 f"{fmt_t(k3['t_force_tangent_s'])} per element ({'lane kernels, 8 elements per call' if k3['lanes'] else 'one element per call'}; "
                 f"one element per call: {fmt_t(k3['t_scalar_force_tangent_s'])}) | "
                 f"{met(k3['t_force_tangent_s'] <= 0.9e-6)} |")
    cont = [r for r in krows if r["material"] != "resultant"]
    if cont:
        worst = min(cont, key=lambda r: r["gflops_force_tangent"])
        pct = 100 * worst["gflops_force_tangent"] / cpu["peak_gflops"]
        L.append(f"| every continuum pair's force + tangent ≥ 30 % of one core's peak | lowest of the "
                 f"{len(cont)} pairs measured: {worst['element']} x {worst['material']} {worst['integration']} "
                 f"{worst['gflops_force_tangent']:.1f} GFLOP/s = {pct:.0f} % of the measured "
                 f"{cpu['peak_gflops']:.1f} GFLOP/s ({100 * worst['gflops_force_tangent'] / cpu['nominal_gflops']:.0f} % "
                 f"of the nominal {cpu['nominal_gflops']:.1f}); "
                 f"{sum(100 * r['gflops_force_tangent'] / cpu['peak_gflops'] >= 30 for r in cont)} of {len(cont)} "
                 f"at ≥ 30 % | {met(pct >= 30)} |")
    if k2:
        L.append(f"| ancf3363 x arruda_boyce (reduced) generated ≥ 3x the plain loop | "
                 f"{k2['speedup_force_tangent']:.1f}x ({fmt_t(k2['t_force_tangent_s'])} vs "
                 f"{fmt_t(k2['t_plain_force_tangent_s'])}), {k2['gflops_force_tangent']:.2f} GFLOP/s = "
                 f"{100 * k2['gflops_force_tangent'] / cpu['peak_gflops']:.0f} % of peak | "
                 f"{met(k2['speedup_force_tangent'] >= 3)} |")
    L.append(f"| Newton iteration cost linear in elements (exponent ≤ 1.1, 100 … {min(big['elements'], 10000):,}) | "
             f"{expo:.3f} | {met(expo <= 1.1)} |")
    if not quick:
        L.append(f"| Newton iteration cost linear up to 100,000 elements (exponent ≤ 1.05, 1,000 … "
                 f"{big['elements']:,}); memory per element | {expo_big:.3f}; {kb_per_el:.1f} kB per element "
                 f"(peak memory {s1[n_a]['maxrss_kb'] / 1024:.0f} MB at {n_a:,}, {s1[n_b]['maxrss_kb'] / 1024:.0f} MB "
                 f"at {n_b:,} elements) | {met(expo_big <= 1.05)} |")
    fa = [r for r in srows]
    one_an = all(r["analyses"] == 1 for r in fa)
    no_full = all(r["full_factorizations"] == 1 for r in fa)
    L.append(f"| symbolic analysis once per run; no allocation in the step loop | "
             f"{'1 analysis' if one_an else 'several analyses'} per run; after the first, "
             f"{'every' if no_full else 'not every'} factorization is in place (band LU, or KLU refactor) "
             f"({sum(r['factorizations'] - r['full_factorizations'] for r in fa)} of "
             f"{sum(r['factorizations'] for r in fa)} in the scaling runs); assembly writes into buffers made at "
             f"set-up; the heap allocation count of a dynamic run (valgrind) does not grow with the number of "
             f"steps, serial and parallel (tests/test_bench_alloc.py) | {met(one_an and no_full)} |")
    L.append(f"| assembly of 10,000 elements with 2 threads ≥ 1.7x one thread, bit-identical for any thread "
             f"count (deterministic parallel scatter) | OpenMP: the lane groups in 8 contiguous parts per thread, each "
             f"taken by the next free thread, which adds directly into the entries only that part touches; entries "
             f"shared by two parts are staged and summed in element order after the region; bit-identical results for 1, 2, 3 threads "
             f"(tests/test_parallel.py); assembly at {nbig:,} elements "
             f"{par:.2f}x as fast with 2 threads as with 1 (median over "
             f"{1 if quick else SCALING_PASSES} passes of the ratio of back-to-back runs, each the median "
             f"assembly of its iterations; machine load average {load[0]:.1f} on "
             f"{os.cpu_count()} cores during the run; target ≥ 1.7x) | {met(par >= 1.7 and nbig >= 10000)} |")
    L.append(f"| incremental regeneration; full regeneration < 10 min | unchanged pairs are skipped by input hash "
             f"(re-run: {tc['regen_incremental_redone']} units redone, {tc['regen_incremental_s']:.1f} s); "
             f"{tc['regen_scope']}: {regen_total:.0f} s | "
             f"{met(tc['regen_incremental_redone'] == 0 and (quick or regen_total < 600))} |")
    for target, measured, status in bench_targets.target_rows(targets, met):
        L.append(f"| {target} | {measured} | {status} |")
    L += ["", "Around the solve (`bench_targets.json`): the front end is the whole `./build.sh run` process minus "
          "the solver's own wall time; the output and stability shares are the solver's own account "
          "(`summary.json` `output_s`, `stability_s`: the time inside its output calls, every table, frame and the "
          "section forces they show, and inside the stability checks, over its `wall_s`), with the difference "
          "of whole runs as a cross-check (the default run against `output.vtk_every = 0` and "
          "`static.stability = false`; the CSV tables cannot be switched off; they are flushed at most every "
          "0.5 s); solver runs are interleaved, medians of "
          f"{3 if quick else 9} runs each.", ""]

    # ---- work-precision sections
    notes = dict(snotes + dnotes)
    L += ["## Work-precision", "",
          "One curve per element / integration variant; in statics the points are meshes "
          f"({', '.join(str(m) for m in sorted({p['elements'] for p in spoints}))} elements), in dynamics time steps "
          "(solid: finest mesh, dotted: coarser mesh).  All points: `out/report/bench_workprecision.csv` "
          "(`pareto` marks the non-dominated ones).", ""]
    keymap = {problems[0]: "table3"}
    for prob in problems:
        key = {"Table 3": "table3", "Roll-up": "rollup", "Soft pen": "pendulum",
               "Silicone fall discretization": "silicone_disc", "Silicone": "silicone"}
        note = next((notes[v] for k, v in key.items() if prob.startswith(k)), "")
        L += [f"### {prob}", "", note, "", f"![work-precision]({pngs[prob].name})", "",
              "| variant | elements | dt (s) | wall | Newton it. | error | Pareto |", "|---|---|---|---|---|---|---|"]
        for p in points:
            if p["problem"] != prob:
                continue
            e = f"{p['error']:.2e}" if p["converged"] and math.isfinite(p["error"]) else f"failed: {p['failure']}"
            L.append(f"| {p['variant']} | {p['elements']} | {p['dt'] if p['dt'] is not None else ''} | "
                     f"{fmt_t(p['wall_s'])} | {p['newton_iterations']} | {e} | {'yes' if p.get('pareto') else ''} |")
        L.append("")
    del keymap

    # ---- kernels
    L += ["## Kernels", "",
          f"Per element at a deformed state (element 0.1 x 0.01 x 0.01 m), single thread, the shortest of "
          f"{'3' if quick else '3 passes x 5'} repeats of a loop timed for ≥ {'1' if quick else '4'} ms of the "
          "thread's CPU time (a time slice given to another process does not count; what other load remains, e.g. "
          "the host's other tenants, only slows a loop down, and it comes in spells of seconds: each pass times "
          "every pair once, so a pair's samples lie seconds apart; the shortest is the kernel's own rate, where "
          "single medians scattered by up to 1.5x between runs on this shared machine).  "
          "'t f', 't f+K': as the solvers call them, i.e. the lane kernels (8 elements per call, vectorized across "
          "elements; runtime/bk_kernel.h, \"Lane kernels\") divided by 8 where the pair has them; '1 el.': the "
          "one-element kernel.  Operations from the "
          "kernel headers (add + mul + div + call, per element; force + tangent computes the upper triangle).  "
          "Plain loop: bench/plain.c, the hand-written quadrature loop (F, invariants, P and dP/dF by the chain "
          "rule through I1, I2, J, full tangent), compiled with the same flags; it agrees with the generated "
          "kernels to the last digits (columns 'diff'); it exists for the single-rule continuum variants.", "",
          f"![kernels](bench_kernels.png)", "",
          "| pair | DOF | pts | ops f | ops f+K (per pt) | t f | t f+K | t f+K 1 el. | GFLOP/s f / f+K | % peak f+K | "
          "plain f+K | ratio f / f+K | diff f, K |", "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in krows:
        ratio = (f"{r['speedup_force']:.1f} / {r['speedup_force_tangent']:.1f}"
                 if math.isfinite(r["speedup_force_tangent"]) else "n/a")
        diff = (f"{r['plain_rel_diff_f']:.0e}, {r['plain_rel_diff_K']:.0e}"
                if math.isfinite(r["plain_rel_diff_K"]) else "")
        L.append(f"| {r['element']} × {r['material']} {r['integration']} | {r['ndof']} | {r['nqp']} | "
                 f"{r['ops_force']} | {r['ops_force_tangent']} ({r['hdr_force_tangent_per_point'] or '-'}) | "
                 f"{fmt_t(r['t_force_s'])} | {fmt_t(r['t_force_tangent_s'])} | "
                 f"{fmt_t(r['t_scalar_force_tangent_s']) if r['lanes'] else '(same)'} | "
                 f"{r['gflops_force']:.2f} / {r['gflops_force_tangent']:.2f} | "
                 f"{100 * r['gflops_force_tangent'] / cpu['peak_gflops']:.0f} % | "
                 f"{fmt_t(r['t_plain_force_tangent_s'])} | {ratio} | {diff} |")
    gmax = max(r["gflops_force_tangent"] for r in krows)
    L += ["", f"Best force + tangent rate {gmax:.2f} GFLOP/s = {100 * gmax / cpu['peak_gflops']:.0f} % of the "
          f"{cpu['peak_gflops']:.1f} GFLOP/s measured single-core peak (nominal: {cpu['flops_per_cycle']} flop/cycle "
          f"x {cpu['mhz']:.0f} MHz from /proc/cpuinfo = {cpu['nominal_gflops']:.1f} GFLOP/s).  One element's kernel is a long dependency chain after CSE "
          "(few independent operations to pair into vectors), so the one-element kernels run near the scalar rate; "
          "the lane kernels run the same straight-line code on 8 elements at once, one vector lane each "
          "(the generator prints the body inside `#pragma omp simd` over the lanes, structure-of-arrays data).  "
          "The operation counts are those of the one-element code (an FMA counts 2); the rods (`gef`, "
          "`euler_bernoulli`, `kirchhoff`, `ancf_cable`) have no lane kernels yet.", ""]

    # ---- scaling
    L += ["## Scaling", "",
          "One long `ancf3243` x `svk` beam (elements 0.1 m long, clamped), bench/newton_iter.c: the model read "
          "as the solver reads it, then the median over several Newton iterations at a deformed state of "
          "assembly (forces and tangent), then numeric factorization with the solve as a Newton iteration with a new "
          "matrix does them (the band LU up to its storage limit, its forward substitution inside the elimination; KLU "
          "refactor beyond): iteration = assembly + factor.  The solve column is one more solve with kept factors (an "
          "iteration that reuses them).  Every mesh is timed in "
          f"{1 if quick else SCALING_PASSES} interleaved passes and each row is its fastest pass.  Peak memory: "
          "VmHWM of that process (model, system, matrix, factors).", "",
          "![scaling](bench_scaling.png)", "",
          "| elements | threads | equations | nnz | iteration | assembly | factor + solve | solve (kept factors) | set-up | peak memory |",
          "|---|---|---|---|---|---|---|---|---|---|"]
    for r in srows:
        L.append(f"| {r['elements']:,} | {r['threads']} | {r['equations']:,} | {r['nnz']:,} | "
                 f"{fmt_t(r['iteration_s'])} | {fmt_t(r['assembly_s'])} | {fmt_t(r['factor_s'])} | "
                 f"{fmt_t(r['solve_s'])} | {fmt_t(r['setup_s'])} | {r['maxrss_kb'] / 1024:.1f} MB |")
    L += ["", f"Fitted exponent of the iteration time (1 thread, so that other load on the machine does not "
          f"distort it), least squares on log-log from 100 to {min(big['elements'], 10000):,} elements: **{expo:.3f}**" + (f", from 1,000 to {big['elements']:,}: **{expo_big:.3f}**" if not quick else "") + ".  "
          f"Assembly at {nbig:,} elements with 2 threads: {par:.2f}x the speed of 1 thread (load average "
          f"{load[0]:.1f} / {load[1]:.1f} / {load[2]:.1f} on {os.cpu_count()} cores when the report was written: "
          f"with other processes on the cores the second thread mostly waits for CPU time, and the parts are "
          f"fixed: the thread that is descheduled holds up the end of the assembly).", ""]

    # ---- toolchain
    c = tc["compile"]
    L += ["## Toolchain", "",
          f"Regeneration ({tc['regen_scope']}, forced, into a scratch directory): {regen_total:.1f} s wall; "
          f"a second run with unchanged inputs redid {tc['regen_incremental_redone']} units in "
          f"{tc['regen_incremental_s']:.1f} s (cache: the input hash in each file's header).  Per unit "
          "(seconds of one worker, derivation + CSE + printing):", "",
          "| unit | regenerate |", "|---|---|"]
    for n, t in tc["regen"]:
        L.append(f"| {n} | {t:.1f} s |")
    L += ["", f"Per-scene solver for `{c['scene']}` from an empty build directory: runtime objects "
          f"{c['runtime_s']:.1f} s, then the kernels it uses and the link {c['kernels_and_link_s']:.1f} s.  "
          f"Solver size {c['size'] / 1024:.0f} KiB"
          + (f" ({c['stripped_size'] / 1024:.0f} KiB stripped)" if c["stripped_size"] else "") +
          f".  Pair descriptors linked (symbols `bk_pair_*` in the binary): {', '.join(c['linked_pairs'])}: only "
          f"the element x material files of the pair the scene uses ({', '.join(c['pairs'])}; its integration "
          f"variants share one file).", ""]
    L += [f"Report written in {time.time() - t_all:.0f} s.", ""]
    (OUT / "bench.md").write_text("\n".join(L))
    log(f" wrote {OUT / 'bench.md'}")
    print(f"bench: {OUT / 'bench.md'} ({time.time() - t_all:.0f} s)")
    return 0


def bench_kernels_flags():
    from gen.solver_build import KERNEL_FLAGS, VARIANTS
    return sorted(set(VARIANTS["release"]) | set(KERNEL_FLAGS["release"]) - {"-fPIC"})


def plot_scaling(rows, path):
    fig, ax = plt.subplots(1, 2, figsize=(10, 4.2))
    r2 = sorted([r for r in rows if r["threads"] == 1], key=lambda r: r["elements"])
    n = [r["elements"] for r in r2]
    for k, lab in (("iteration_s", "iteration"), ("assembly_s", "assembly"), ("factor_s", "factorization"),
                   ("solve_s", "solve")):
        ax[0].loglog(n, [r[k] for r in r2], "o-", ms=3, label=lab)
    if n:
        ax[0].loglog(n, [r2[0]["iteration_s"] * x / n[0] for x in n], "k:", lw=0.8, label="linear")
    ax[0].set_xlabel("elements")
    ax[0].set_ylabel("time per Newton iteration (s)")
    ax[0].legend(fontsize=8)
    ax[0].grid(True, which="both", lw=0.2)
    ax[1].loglog(n, [r["maxrss_kb"] / 1024 for r in r2], "o-", ms=3)
    ax[1].set_xlabel("elements")
    ax[1].set_ylabel("peak memory (MB)")
    ax[1].grid(True, which="both", lw=0.2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_kernels(rows, cpu, path):
    fig, ax = plt.subplots(figsize=(10, 5))
    names = [f"{r['element']}×{r['material']} {r['integration']}" for r in rows]
    x = range(len(rows))
    ax.bar([i - 0.2 for i in x], [r["gflops_force_tangent"] for r in rows], 0.4, label="force + tangent")
    ax.bar([i + 0.2 for i in x], [r["gflops_force"] for r in rows], 0.4, label="force")
    ax.set_xticks(list(x))
    ax.set_xticklabels(names, rotation=75, fontsize=7)
    ax.set_ylabel("GFLOP/s (one core)")
    ax.set_title(f"generated kernels; single-core peak {cpu['peak_gflops']:.0f} GFLOP/s (measured)")
    ax.legend(fontsize=8)
    ax.grid(True, axis="y", lw=0.2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
