"""Command-line front end behind build.sh: run, gen, scenes."""
import argparse
import json
import shutil
import subprocess
import sys
from pathlib import Path

from gen.scene import ROOT, SceneError, build, load_index, write_model

MODELS = ROOT / "models"
RUNS = ROOT / "out" / "runs"
MARKER = ".beamkit-run"
RESULT_FILES = ("summary.json", "sensors.csv", "energy.csv", "modes.csv", "model.dat", "results.pvd")


def scene_path(spec):
    p = Path(spec)
    if spec.endswith(".toml") or "/" in spec:
        if not p.is_file():
            raise SceneError(f"error: {spec}: no such scene file")
        return p
    cand = MODELS / f"{spec}.toml"
    if not cand.is_file():
        names = sorted(x.stem for x in MODELS.glob("*.toml"))
        raise SceneError(f"error: scene {spec!r}: no models/{spec}.toml (scenes: {', '.join(names)})")
    return cand


def prepare_out_dir(out, default):
    """Create or reuse an output directory; never mix with foreign files."""
    out = Path(out)
    if out.exists():
        if not out.is_dir():
            raise SceneError(f"error: --out {out}: exists and is not a directory")
        entries = [e for e in out.iterdir()]
        if entries and not (out / MARKER).exists():
            raise SceneError(f"error: --out {out}: directory exists, is not empty and was not made by "
                             f"./build.sh run; choose a new or empty directory")
        for e in entries:
            if e.name == MARKER:
                continue
            if e.is_dir() and not e.is_symlink():
                shutil.rmtree(e)
            else:
                e.unlink()
    else:
        out.mkdir(parents=True)
    (out / MARKER).write_text("results of ./build.sh run; cleared on the next run into this directory\n")
    return out


def solver_for(model, index, variant="release", log=None):
    from gen.solver_build import build_solver
    name = model["name"]
    suffix = "" if variant == "release" else f"-{variant}"
    return build_solver(model["pairs"], ROOT / "out" / "bin" / f"{name}{suffix}", index, variant, log)


def execute(scene, sets=(), out=None, variant="release", verbose=False, quiet=True):
    """Validate, mesh, build and run one scene.  Returns (exit status, out dir).
    Raises SceneError for bad input."""
    path = scene_path(str(scene))
    model = build(path, sets)
    index = load_index()
    out = prepare_out_dir(out or RUNS / model["name"], RUNS)
    write_model(model, out / "model.dat")
    log = None if quiet else (lambda s: print(s, file=sys.stderr))
    try:
        solver = solver_for(model, index, variant, log)
    except Exception as e:
        raise SceneError(f"error: building the solver for {path}: {e}")
    cmd = [str(solver), str(out / "model.dat"), str(out)]
    if verbose:
        cmd.append("--verbose")
    elif quiet:
        cmd.append("--quiet")
    return subprocess.run(cmd).returncode, out


def cmd_run(argv):
    ap = argparse.ArgumentParser(
        prog="build.sh run",
        description="Build the per-scene solver if stale and run it. Results go to out/runs/SCENE/ "
                    "(summary.json, sensors.csv, model.dat) or to --out DIR.")
    ap.add_argument("scene", help="a name in models/ (without .toml) or a path to a .toml file")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="override a scene value, e.g. material.alu.E=3e7, beam.arm.elements=20 or "
                         "beam.arm.integration=full (arrays of tables are addressed by name or index, "
                         "array entries by index: load.0.value.2=-10); no kernel regeneration")
    ap.add_argument("--out", metavar="DIR", help="output directory (default out/runs/SCENE)")
    ap.add_argument("--quiet", action="store_true", help="print only errors")
    ap.add_argument("--verbose", action="store_true", help="log every load step")
    ap.add_argument("--sanitize", action="store_true",
                    help="build and run the solver with AddressSanitizer and UBSan")
    a = ap.parse_args(argv)
    try:
        rc, out = execute(a.scene, a.set, a.out, "sanitize" if a.sanitize else "release",
                          a.verbose, a.quiet)
    except SceneError as e:
        print(str(e), file=sys.stderr)
        return 1
    summ = out / "summary.json"
    if not a.quiet and summ.exists():
        print_summary(json.loads(summ.read_text()), out)
    return rc


def print_summary(s, out):
    status = "converged" if s["converged"] else "NOT converged"
    print(f"scene {s['scene']} ({s['analysis']}): {status}; {s['steps']} steps, "
          f"{s['newton_iterations']} Newton iterations, {s['dofs']} DOFs, {s['elements']} elements, "
          f"wall {s['wall_s']:.3f} s")
    for name, v in s["sensors"].items():
        p, u = v["position"], v["displacement"]
        print(f"  sensor {name}: position [{p[0]:.6e}, {p[1]:.6e}, {p[2]:.6e}] m, "
              f"displacement [{u[0]:.6e}, {u[1]:.6e}, {u[2]:.6e}] m")
    if s["analysis"] == "modal":
        print_modes(out)
    print(f"  results in {out}/")


def print_modes(out):
    """The frequency table of a modal run (from modes.csv), and where the shapes are."""
    path = Path(out) / "modes.csv"
    if not path.exists():
        return
    import csv
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    if not rows:
        return
    print(f"  {'mode':>4}  {'frequency (Hz)':>15}  {'omega (rad/s)':>15}  {'shape scale (m)':>15}")
    for r in rows:
        print(f"  {int(r['mode']):4d}  {float(r['frequency_hz']):15.9g}  {float(r['omega']):15.9g}  "
              f"{float(r['scale_m']):15.4g}")
    if (Path(out) / "modes.pvd").exists():
        print("  mode shapes: modes.pvd (mode_NN.vtu, time value = mode number), displaced by the scale above\n"
              "  (largest translation 10 % of the model length, section rotation at most 0.5 rad); point data\n"
              "  mode_shape is the mode normalized to a largest translation of 1")


def cmd_scenes(argv):
    for p in sorted(MODELS.glob("*.toml")):
        print(p.stem)
    return 0


def main(argv):
    if not argv:
        print("usage: python3 -m gen.cli {run,gen,scenes} ...", file=sys.stderr)
        return 1
    cmd, rest = argv[0], argv[1:]
    if cmd == "run":
        return cmd_run(rest)
    if cmd == "gen":
        from gen.generate import main as gen_main
        return gen_main(rest)
    if cmd == "scenes":
        return cmd_scenes(rest)
    print(f"error: unknown command {cmd!r}", file=sys.stderr)
    return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
