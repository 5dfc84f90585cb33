"""Byte-for-byte comparison of every output file of scene runs before and after
a change (issue 33: a refactor leaves every output file unchanged but for its
timings).

  /usr/bin/python3 -m report.diff_runs run DIR [--root REPO] [--from NAME] [SCENE ...]
      runs each scene (a name in models/ or a .toml path; default: every scene
      of models/ and the mechanism scenes of the tests, see extra_scenes) into
      DIR/NAME with the build.sh of REPO (default this repository: another
      one, e.g. `git archive main | tar -x -C REPO`, runs the code before a
      change); --from starts at the scene NAME (to resume)
  /usr/bin/python3 -m report.diff_runs compare BEFORE AFTER   lists the files
      that differ; summary.json is compared without its timing keys (TIMING),
      model.dat (the model file, whose format a change may bump) is reported
      apart, and an HDF5 file whose bytes differ is compared by its content
      (every dataset's values, dtype and shape, every attribute: the file's
      layout follows the solver's timed flushes, runtime/output/output.c
      spent_flush, so its bytes depend on the wall clock).  Exit 1 when an
      output differs.
"""
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TIMING = ("wall_s", "output_s", "stability_s", "threads")      # summary.json keys measured, not computed
APART = ("model.dat",)


def extra_scenes(dest):
    """The scenes of the tests with joint actuators and forces at body points
    (models/ has none), as .toml files in dest."""
    sys.path.insert(0, str(ROOT / "tests"))
    import test_actuators as A
    import test_body_loads as B
    import test_mechanisms as M
    import test_spinning_hub as H
    dest.mkdir(parents=True, exist_ok=True)
    pd = '[[actuator]]\nname = "pd"\njoint = "hinge"\nkp = 4.0\nkd = 0.7\nsetpoint = 0.5\n'
    motor = '[amplitude.wave]\ntype = "sine"\nfrequency = 1.0\n' \
            '[[actuator]]\nname = "motor"\njoint = "hinge"\neffort = 0.5\neffort_amplitude = "wave"\n'
    static_link = B.LINK.replace('analysis = "dynamic"', 'analysis = "static"')
    scenes = {
        "act_two_bodies": A.TWO_BODIES,
        "act_motor_link": A.LINK + motor,
        "act_pd_link": A.LINK + pd,
        "act_modal": A.LINK.replace('analysis = "dynamic"', 'analysis = "modal"')
        + '[modal]\nmodes = 1\n[[actuator]]\nname = "spring"\njoint = "hinge"\nkp = 4.0\n',
        "bload_static_point": static_link + '[[load]]\ntype = "force"\nat = "link"\npoint = [0.5, 0.0, 0.0]\n'
        'value = [0.0, -2.0, 0.0]\n[[actuator]]\nname = "spring"\njoint = "hinge"\nkp = 5.0\n'
        '[static]\nload_steps = 4\n',
        "bload_dynamic_points": A.TWO_BODIES.replace("t_end = 0.002", "t_end = 0.2") +
        '[[load]]\ntype = "force"\nat = "arm"\npoint = [0.5, 0.2, 0.05]\nvalue = [3.0, -2.0, 1.0]\n'
        '[[load]]\ntype = "force"\nat = "base"\npoint = [0.1, -0.1, 0.2]\nvalue = [-1.0, 0.5, 2.0]\n'
        'amplitude = {type = "sine", frequency = 2.0}\n',
        "mech_all_parts": M.ALL_PARTS,
        "hub_motor_link": H.MOTOR_LINK,
        "hub_motor_arm": H.MOTOR_ARM,
    }
    out = []
    for name, text in scenes.items():
        (dest / f"{name}.toml").write_text(text)
        out.append(dest / f"{name}.toml")
    return out


def run(dest, args):
    dest, repo, start = Path(dest), ROOT, None
    while args and args[0] in ("--root", "--from"):
        if args[0] == "--root":
            repo = Path(args[1]).resolve()
        else:
            start = args[1]
        args = args[2:]
    scenes = args or (sorted((ROOT / "models").glob("*.toml")) +
                      extra_scenes(Path(tempfile.mkdtemp(prefix="bk-diff-"))))
    scenes = [Path(sc) if str(sc).endswith(".toml") else ROOT / "models" / f"{sc}.toml" for sc in scenes]
    if start:
        scenes = scenes[[sc.stem for sc in scenes].index(start):]
    for sc in scenes:
        t0 = time.time()
        r = subprocess.run([str(repo / "build.sh"), "run", str(sc), "--quiet", "--threads", "1", "--out",
                            str(dest / sc.stem)], capture_output=True, text=True)
        (dest / sc.stem).mkdir(parents=True, exist_ok=True)
        (dest / sc.stem / "exit_status").write_text(f"{r.returncode}\n{r.stderr[-2000:]}")
        print(f"{sc.stem}: exit {r.returncode}, {time.time() - t0:.1f} s (loaded machine)", flush=True)


def _summary(path):
    d = json.loads(path.read_text())
    for k in TIMING:
        d.pop(k, None)
    return d


def _h5_content(path):
    """{name: (dtype, shape, bytes)} of every dataset and attribute of an HDF5 file."""
    import h5py
    import numpy as np
    out = {}

    def add(name, obj):
        if isinstance(obj, h5py.Dataset):
            v = np.asarray(obj[()])
            out[name] = (str(v.dtype), v.shape, v.tobytes())
        for k, a in obj.attrs.items():
            v = np.asarray(a)
            out[f"{name}@{k}"] = (str(v.dtype), v.shape, v.tobytes())
    with h5py.File(path, "r") as f:
        add("/", f)
        f.visititems(add)
    return out


def compare(a, b):
    a, b = Path(a), Path(b)
    bad, apart, same, h5 = [], [], 0, 0
    for run_a in sorted(p for p in a.iterdir() if p.is_dir()):
        run_b = b / run_a.name
        files = sorted({p.relative_to(run_a) for p in run_a.rglob("*") if p.is_file()} |
                       ({p.relative_to(run_b) for p in run_b.rglob("*") if p.is_file()} if run_b.is_dir() else set()))
        for f in files:
            fa, fb = run_a / f, run_b / f
            if not fa.exists() or not fb.exists():
                bad.append(f"{run_a.name}/{f}: only {'after' if fb.exists() else 'before'}")
            elif f.name == "summary.json":
                if _summary(fa) == _summary(fb):
                    same += 1
                else:
                    bad.append(f"{run_a.name}/{f}: differs (timings left out)")
            elif f.name in APART:
                if fa.read_bytes() != fb.read_bytes():
                    apart.append(f"{run_a.name}/{f}")
            elif fa.read_bytes() == fb.read_bytes():
                same += 1
            elif f.suffix == ".h5" and _h5_content(fa) == _h5_content(fb):
                h5 += 1
            else:
                bad.append(f"{run_a.name}/{f}: differs")
    print(f"{same} files identical ({', '.join(TIMING)} of summary.json left out)")
    print(f"{h5} HDF5 files with the same content but other bytes (timed flushes)")
    print(f"{len(apart)} files of {', '.join(APART)} differ (the model file, compared apart)")
    for line in bad:
        print("DIFF", line)
    return 1 if bad else 0


if __name__ == "__main__":
    if len(sys.argv) >= 3 and sys.argv[1] == "run":
        run(sys.argv[2], sys.argv[3:])
    elif len(sys.argv) == 4 and sys.argv[1] == "compare":
        sys.exit(compare(sys.argv[2], sys.argv[3]))
    else:
        sys.exit(__doc__)
