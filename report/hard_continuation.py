"""The continuation hard case (8): the two-bar truss snap-through, the deep
arch, Lee's frame and the Euler load of the seed cantilever by arc length, the
branch switch onto the post-buckled elastica, and the plot of their paths
(report/hard.py)."""
import math
from pathlib import Path

from gen.scene import ROOT
from references import lee_frame as lee_frame_ref
from report.hard_closed_forms import PCR, elastica_compressed, truss_closed_form
from report.hard_runs import OUT, RUNS, run


# --------------------------------------------------------------------- case 8
def case_continuation(quick):
    lines = ["## 8. Continuation: limit points, snap-through, bifurcation", "",
             "`static.method = \"arc_length\"` (runtime/analysis/continuation.c): cylindrical arc-length constraint, tangent "
             "predictor oriented along the last increment, arc length from the iteration count, limit points "
             "refined by bisection on the arc length, bifurcations from the change of the negative-eigenvalue "
             "count (bisection on the inertia).  `gef` is the reference element.  Lee's frame with a follower "
             "load is not here (tests/test_continuation.py checks it with `gef`).  The ANCF continuum "
             "elements take no rigid beam-to-beam joint (Lee's frame) and no curved reference (the arch).", "",
             "| benchmark | element | converged | steps | iterations | critical points (load) | reference | error |",
             "|---|---|---|---|---|---|---|---|"]
    rows = []
    fmax, _ = truss_closed_form()
    truss_text = (ROOT / "models" / "truss_snap_through.toml").read_text()
    cable = RUNS / "truss_cable.toml"
    cable.parent.mkdir(parents=True, exist_ok=True)
    cable.write_text(truss_text.replace('type = "revolute"\na = "bar:start"\naxis = [0.0, 1.0, 0.0]',
                                        'type = "spherical"\na = "bar:start"'))
    cases = [("two-bar truss, F_max", "truss_snap_through", "bar", 400.0, fmax, "closed form",
              ["gef", "euler_bernoulli", "ancf_cable"]),
             ("deep arch 215°, P_cr", "deep_arch_215", "arch", 1000.0, 897.0, "DaDeppo & Schmidt 1975",
              ["gef", "euler_bernoulli", "kirchhoff"]),
             ("Lee's frame, P_max L²/EI", "lee_frame", ("column", "beam"), 1.0,
              lee_frame_ref.load()["dead"]["limit"][0], "Reissner shooting, references/lee_frame.py",
              ["gef", "euler_bernoulli", "kirchhoff"]),
             ("seed cantilever, Euler load", "cantilever_euler_arc", "arm", 200.0, PCR, "π²EI/(4L²)",
              ["gef", "euler_bernoulli", "ancf3243", "ancf3363"])]
    if quick:
        cases = [(c[0], c[1], c[2], c[3], c[4], c[5], c[6][:1]) for c in cases]
    paths = []
    for title, scene, beam, load, ref, refname, elems in cases:
        for element in elems:
            sets = [f"beam.{b}.element={element}" for b in (beam if isinstance(beam, tuple) else (beam,))]
            if element.startswith("ancf3"):
                sets += ["material.alu.law=svk"] + (["beam.arm.integration=reduced"] if element == "ancf3363" else [])
            sc = str(cable) if element == "ancf_cable" else scene
            s = run(sc, sets if element != "ancf_cable" else [f"beam.{beam}.element={element}"],
                    f"arc-{scene}-{element}")
            crit = s.get("critical_points", [])
            first = next((c for c in crit if c["load_factor"] is not None), None)
            val = first["load_factor"] * load if first else float("nan")
            lines.append(f"| {title} | {element} | {s['converged']} | {s['steps']} | {s['newton_iterations']} | "
                         + (", ".join(f"{c['type'].replace('_', ' ')} {c['load_factor'] * load:.4g}" for c in crit)
                            or "none")
                         + f" | {ref:.4g} ({refname}) | {100 * (val / ref - 1):+.2f} % |")
            rows.append(dict(benchmark=scene, element=element, converged=s["converged"], steps=s["steps"],
                             iterations=s["newton_iterations"], critical=val, reference=ref))
            paths.append((title, element, s))
    # branch switch onto the post-buckled elastica (P = 200 N): tip vs the inextensible elastica
    # the scene's section is 10 x 10.1 mm (a simple bifurcation, in the weaker plane)
    ex, ez = elastica_compressed(200.0, math.pi ** 2 * 7.2e10 * 0.0101 * 0.01 ** 3 / 12 / 4)
    lines += ["", "Branch switch (`static.branch_switch`, models/cantilever_postbuckling.toml): 200 N on the seed "
              "cantilever (10 x 10.1 mm) without imperfection; tip at the full load against the inextensible elastica "
              f"(x = {ex:.5f} L, deflection {ez:.5f} L).", "",
              "| element | converged | steps | iterations | tip x (m) | deflection (m) | tip error / L | warnings |",
              "|---|---|---|---|---|---|---|---|"]
    for element in (["gef"] if quick else ["gef", "euler_bernoulli", "ancf3243"]):
        sets = [f"beam.arm.element={element}"] + (["material.alu.law=svk"] if element.startswith("ancf3") else [])
        s = run("cantilever_postbuckling", sets, f"arc-postbuckling-{element}")
        p = s["sensors"]["tip"]["position"]
        dfl = math.hypot(p[1], p[2])
        err = math.hypot(p[0] - ex, dfl - ez)
        lines.append(f"| {element} | {s['converged']} | {s['steps']} | {s['newton_iterations']} | {p[0]:.5f} | "
                     f"{dfl:.5f} | {err:.1e} | {len(s.get('warnings', []))} |")
        rows.append(dict(benchmark="cantilever_postbuckling", element=element, converged=s["converged"],
                         steps=s["steps"], iterations=s["newton_iterations"], critical=err, reference=0.0))
        paths.append(("post-buckling (branch switch)", element, s))
    lines += ["", "The truss is exact for every element with the axial law ½EA(|r′|−1)² (a straight pin-ended bar "
              "carries its axial force only); the path passes both limit points and ends on the inverted branch.  "
              "The arch's limit point needs no imperfection (the supports are not symmetric).  "
              "`euler_bernoulli`'s bifurcation estimate is off by several per cent for the reason given in case 1 "
              "(its regularized internal multipliers in the inertia check); `kirchhoff` is inextensible, so an "
              "axial load moves nothing on the straight path and arc-length has no tangent to follow there "
              "(it stops with that message).  The continuum ANCF elements take no curved reference (no arch).  "
              "The branch switch follows the elastica with the rod elements; with `ancf3243` the switch step "
              "does not converge (the cause is not investigated yet) and "
              "the path goes on along the straight branch with a warning.  The square section leaves the "
              "buckling plane free: the count of negative eigenvalues flickers on the post-buckled path (a "
              "neutral direction), which the critical-point list filters as flicker.", ""]
    try:
        plot_paths(paths, OUT / "hard_continuation_paths.png")
        lines += ["![continuation paths](hard_continuation_paths.png)", ""]
    except ImportError:
        lines += ["(matplotlib missing: no plot)", ""]
    return lines, rows


def plot_paths(paths, path):
    """Load factor against the first sensor's largest displacement component per benchmark and
    element, critical points marked (report/plot.py path_panel)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from report.plot import read_csv
    titles = list(dict.fromkeys(p[0] for p in paths))
    fig, axes = plt.subplots(1, len(titles), figsize=(5.5 * len(titles), 4.5), squeeze=False)
    for ax, title in zip(axes[0], titles):
        for _, element, s in (p for p in paths if p[0] == title):
            rows = read_csv(Path(s["_out"]) / "sensors.csv")
            name = rows[0]["sensor"] if rows else None
            r = [x for x in rows if x["sensor"] == name]
            comp = max(("ux", "uy", "uz"), key=lambda c: max(abs(float(x[c])) for x in r))
            line, = ax.plot([float(x[comp]) for x in r], [float(x["time"]) for x in r], lw=1, marker=".", ms=2,
                            label=f"{element} ({name} {comp})")
            for cp in s.get("critical_points", []):
                u = cp["displacement"].get(name)
                if u and u["xyz".index(comp[1])] is not None and cp["load_factor"] is not None:
                    ax.plot([u["xyz".index(comp[1])]], [cp["load_factor"]],
                            "v" if cp["type"] == "limit_point" else "s", color=line.get_color(), ms=7, mfc="none")
        ax.axhline(0.0, color="0.6", lw=0.5)
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("displacement (m)")
        ax.set_ylabel("load factor")
        ax.grid(True, lw=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("Arc-length paths (triangles: limit points, squares: bifurcations)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
