"""The work-precision results: the Pareto-optimal points of each problem, the
fastest configuration per error tolerance and the work-precision plot."""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TOLS = (1e-2, 1e-3, 1e-4)


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
