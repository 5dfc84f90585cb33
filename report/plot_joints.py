"""The joint plots of ./build.sh plot (report/plot.py): joints.png, the angle or
displacement, rate and effort of every joint with an axis (joints.csv) and of
every actuator (actuators.csv) against time or load factor; reactions.png, the
force and moment components of every constraint's reaction (reactions.csv)."""
import csv

import matplotlib.pyplot as plt
import numpy as np


def _read(path):
    if not path.exists():
        return []
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def _series(rows, key):
    """{name: (t, rows)} in the order of first appearance."""
    out = {}
    for r in rows:
        out.setdefault(r[key], []).append(r)
    return {n: (np.array([float(x["time"]) for x in rs]), rs) for n, rs in out.items()}


def fig_joints(run, summary, decorate):
    """joints.png, or None when the run has neither joints with an axis nor actuators."""
    joints = _series(_read(run / "joints.csv"), "name")
    acts = _series(_read(run / "actuators.csv"), "actuator")
    if not joints and not acts:
        return None
    xlabel = "time (s)" if summary["analysis"] == "dynamic" else "load factor"
    fig, ax = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    for label, series in (("joint", joints), ("actuator", acts)):
        for n, (t, rs) in series.items():
            rot = rs[0]["motion"] == "rotation"
            name = f"{label} {n} ({'rad, N m' if rot else 'm, N'})"
            for k, c in enumerate(("value", "rate", "effort")):
                ax[k].plot(t, [float(x[c]) for x in rs], lw=1, ls="-" if label == "joint" else "--", label=name)
    for k, c in enumerate(("angle or displacement", "rate (1/s)", "effort (torque or force)")):
        ax[k].set_ylabel(c)
        ax[k].grid(True, lw=0.3)
    ax[0].legend(fontsize=8)
    ax[2].set_xlabel(xlabel)
    top = decorate(fig, summary, "joints and actuators (joints.csv, actuators.csv)")
    fig.tight_layout(rect=(0, 0, 1, top))
    return fig


def fig_reactions(run, summary, decorate):
    """reactions.png, or None without reactions.csv rows."""
    rows = _series(_read(run / "reactions.csv"), "name")
    if not rows:
        return None
    xlabel = "time (s)" if summary["analysis"] == "dynamic" else "load factor"
    fig, ax = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for n, (t, rs) in rows.items():
        for k, (cols, unit) in enumerate(((("Fx", "Fy", "Fz"), "N"), (("Mx", "My", "Mz"), "N m"))):
            for c in cols:
                v = np.array([float(x[c]) for x in rs])
                if np.abs(v).max() > 0:
                    ax[k].plot(t, v, lw=1, label=f"{n} {c}")
    ax[0].set_ylabel("force on frame a (N)")
    ax[1].set_ylabel("moment about the joint point (N m)")
    for a in ax:
        a.grid(True, lw=0.3)
        if a.get_legend_handles_labels()[0]:
            a.legend(fontsize=7, ncol=2)
    ax[1].set_xlabel(xlabel)
    top = decorate(fig, summary, "constraint reactions (reactions.csv)")
    fig.tight_layout(rect=(0, 0, 1, top))
    return fig
