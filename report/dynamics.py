"""out/report/pendulum.md and PNG plots: the seed's simple and double pendulums and
the falling silicone cantilever for every applicable element, with wall time,
steps, Newton iterations, energy drift and the largest constraint residual.

usage: python3 -m report.dynamics [--quick]
"""
import csv
import json
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from gen.cli import execute  # noqa: E402
from gen.scene import ROOT, SceneError  # noqa: E402

OUT = ROOT / "out" / "report"
RES = ["material.rod.law=resultant"]
PENDULUM_ELEMENTS = [
    ("ancf3243", ["beam.rod.element=ancf3243"]),
    ("ancf3243 sri", ["beam.rod.element=ancf3243", "beam.rod.integration=sri"]),
    ("ancf3333", ["beam.rod.element=ancf3333"]),
    ("ancf3273", ["beam.rod.element=ancf3273"]),
    ("ancf3363", ["beam.rod.element=ancf3363"]),
    ("ancf_cable", ["beam.rod.element=ancf_cable"] + RES),
    ("gef", ["beam.rod.element=gef"] + RES),
    ("euler_bernoulli", ["beam.rod.element=euler_bernoulli"] + RES),
    ("kirchhoff", ["beam.rod.element=kirchhoff"] + RES),
]


def run(scene, sets, tag):
    out = OUT / "runs" / tag
    t0 = time.time()
    try:
        rc, out = execute(scene, sets, out)
    except SceneError as e:
        return None, str(e)
    s = json.loads((out / "summary.json").read_text())
    with open(out / "sensors.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    with open(out / "energy.csv", newline="") as fh:
        en = list(csv.DictReader(fh))
    s["_wall"] = time.time() - t0
    scale = max(abs(float(e["gravity"])) for e in en) or 1.0
    s["_drift"] = max(abs(float(e["total"])) for e in en) / scale
    s["_rows"] = rows
    s["_rc"] = rc
    return s, None


def series(rows, sensor):
    r = [x for x in rows if x["sensor"] == sensor]
    return [float(x["time"]) for x in r], {k: [float(x[k]) for x in r] for k in ("ux", "uy", "uz")}


def table_row(label, dt, s, err):
    if s is None:
        return f"| {label} | {dt} | failed: {err} | | | | | |"
    status = "yes" if s["converged"] else f"no: {s.get('error')}"
    return (f"| {label} | {dt} | {status} | {s['wall_s']:.2f} | {s['steps']} | {s['newton_iterations']} | "
            f"{s['_drift']:.2e} | {s['max_constraint_residual']:.1e} |")


HEAD = ["| element | dt (s) | completed | wall (s) | steps | Newton it. | energy drift | max constraint residual |",
        "|---|---|---|---|---|---|---|---|"]


def plot(path, title, curves, sensor):
    fig, ax = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
    for label, rows in curves:
        t, u = series(rows, sensor)
        for k, comp in enumerate(("ux", "uy", "uz")):
            ax[k].plot(t, u[comp], label=label, lw=1)
    for k, comp in enumerate(("x", "y", "z")):
        ax[k].set_ylabel(f"{sensor}: u{comp} (m)")
        ax[k].grid(True, lw=0.3)
    ax[2].set_xlabel("time (s)")
    ax[0].set_title(title)
    ax[0].legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv):
    quick = "--quick" in argv
    OUT.mkdir(parents=True, exist_ok=True)
    t_all = time.time()
    lines = ["# Dynamics: the seed's pendulums and the falling silicone cantilever", "",
             "Generalized-alpha (rho_inf = 0.8 unless stated) for index-3 constrained systems.  Energy",
             "drift: largest |kinetic + strain + gravity potential - initial| over the run, relative to",
             "the largest gravity potential change; with rho_inf < 1 the scheme dissipates high",
             "frequencies, so the drift measures that dissipation.  Constraint residual: largest",
             "|G q - g| over all steps (m).", ""]
    t_end = "0.5" if quick else "2.0"
    for E, scene_tag, dts in (("3e7", "soft", ("1e-2", "1e-4")), ("7e11", "stiff", ("1e-2", "1e-4"))):
        lines += [f"## Simple pendulum, E = {E} Pa (models/pendulum_{scene_tag}_*.toml), {t_end} s", ""] + HEAD
        curves = []
        for label, sets in PENDULUM_ELEMENTS:
            for dt in dts:
                if quick and dt == "1e-4":
                    continue
                extra = sets + [f"dynamic.dt={dt}", f"dynamic.t_end={t_end}", f"material.rod.E={E}",
                                f"dynamic.output_every={1 if dt == '1e-2' else 100}"]
                s, err = run("pendulum_soft_ancf", extra, f"pendulum-{scene_tag}-{label.replace(' ', '_')}-{dt}")
                lines.append(table_row(label, dt, s, err))
                if s is not None:
                    curves.append((f"{label}, dt={dt}", s["_rows"]))
        png = OUT / f"pendulum_{scene_tag}.png"
        plot(png, f"simple pendulum, E = {E} Pa: point B", curves, "B")
        lines += ["", f"![point B]({png.name})", ""]
    for E, tag in (("2e8", "soft"), ("7.2e10", "stiff")):
        lines += [f"## Double pendulum, E = {E} Pa (models/double_pendulum_{tag}_*.toml), dt = 1e-4 s", ""] + HEAD
        curves = []
        for label, scene in (("ancf3243", f"double_pendulum_{tag}_ancf"), ("gef", f"double_pendulum_{tag}_gef")):
            extra = ["dynamic.t_end=0.3"] if quick else []
            s, err = run(scene, extra, f"double-{tag}-{label}")
            lines.append(table_row(label, "1e-4", s, err))
            if s is not None:
                curves.append((label, s["_rows"]))
        png = OUT / f"double_pendulum_{tag}.png"
        plot(png, f"double pendulum, E = {E} Pa: point C", curves, "C")
        lines += ["", f"![point C]({png.name})", ""]
    lines += ["## Falling silicone cantilever (models/silicone_fall*.toml), 0.5 s, dt = 1e-3 s", ""] + HEAD
    curves = []
    for label, sets in (("ancf3243 full", ["beam.strip.element=ancf3243", "beam.strip.integration=full"]),
                        ("ancf3243 sri", ["beam.strip.element=ancf3243", "beam.strip.integration=sri"]),
                        ("ancf3273", ["beam.strip.element=ancf3273", "beam.strip.integration=reduced"]),
                        ("ancf3363", ["beam.strip.element=ancf3363", "beam.strip.integration=reduced"])):
        for scene in ("silicone_fall", "silicone_fall_damped"):
            extra = sets + (["dynamic.t_end=0.1"] if quick else [])
            s, err = run(scene, extra, f"{scene}-{label.replace(' ', '_')}")
            lines.append(table_row(f"{label}{', damped' if 'damped' in scene else ''}", "1e-3", s, err))
            if s is not None:
                curves.append((f"{label}{', KV' if 'damped' in scene else ''}", s["_rows"]))
    png = OUT / "silicone_fall.png"
    plot(png, "falling silicone cantilever: tip", curves, "tip")
    lines += ["", f"![tip]({png.name})", "",
              "ancf3243 full locks (nearly incompressible): it barely moves.  ancf3243 sri is too soft;",
              "ancf3273 and ancf3363 fall alike.  Kelvin-Voigt damping: retardation time 5 ms.", "",
              f"Generated by `./build.sh report` in {time.time() - t_all:.0f} s."]
    (OUT / "pendulum.md").write_text("\n".join(lines) + "\n")
    print(f"wrote {OUT / 'pendulum.md'}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
