"""What `./build.sh run` prints after a solve, and the scene warnings it adds to
a summary.json the front end wrote itself (a run interrupted before the solver
started: the solver lists them in its own, from the model file); standard
library os only, so that the run pipeline (gen/pipeline.py) can use it on a
repeated run without the scene compiler."""
import os


def _json_string(s):
    """s as the solver writes a JSON string (runtime/output/output.c json_string)."""
    out = ['"']
    for c in s:
        if c in '"\\':
            out.append("\\" + c)
        elif ord(c) < 0x20:
            out.append(f"\\u{ord(c):04x}")
        else:
            out.append(c)
    out.append('"')
    return "".join(out)


_WARNINGS = '\n  "warnings": ['


def add_scene_warnings(out, warnings):
    """The scene reader's warnings (likely locking element choices, ...) go first
    into summary.json "warnings", beside any others, as the solver lists them.  The solver writes that
    array one string a line (its strings have no raw newline), so it is edited as
    text: no json import on the run path, the solver's layout kept."""
    path = os.path.join(str(out), "summary.json")
    if not warnings or not os.path.exists(path):
        return
    with open(path, encoding="utf-8") as fh:
        text = fh.read()
    i = text.find(_WARNINGS)
    end = text.find("],\n", i) if i >= 0 else -1
    if end < 0:                        # not the solver's layout: through json
        import json
        s = json.loads(text)
        s["warnings"] = list(warnings) + [w for w in s.get("warnings", []) if w not in warnings]
        text = json.dumps(s, indent=1) + "\n"
    else:
        j = i + len(_WARNINGS)
        ours = [_json_string(w) for w in warnings]
        theirs = [ln.strip().rstrip(",") for ln in text[j:end].split("\n") if ln.strip()]
        items = ours + [e for e in theirs if e not in ours]
        text = text[:j] + ",".join("\n    " + e for e in items) + "\n  " + text[end:]
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as fh:
        fh.write(text)
    os.replace(tmp, path)


def print_summary(s, out):
    status = ("converged" if s["converged"] else
              "interrupted (results so far kept)" if s.get("interrupted") else "NOT converged")
    def n(k, word):
        return f"{k} {word}" + ("" if k == 1 else "s")

    # a modal run has modes, not steps and Newton iterations
    work = (n(len(s["frequencies_hz"]), "mode") if s["analysis"] == "modal" and "frequencies_hz" in s
            else f"{n(s['steps'], 'step')}, {n(s['newton_iterations'], 'Newton iteration')}")
    print(f"scene {s['scene']} ({s['analysis']}): {status}; {work}, {s['dofs']} DOFs, "
          f"{n(s['elements'], 'element')}, wall {s['wall_s']:.3f} s")
    for name, v in s["sensors"].items():
        p, u = v["position"], v["displacement"]
        print(f"  sensor {name}: position [{p[0]:.6e}, {p[1]:.6e}, {p[2]:.6e}] m, "
              f"displacement [{u[0]:.6e}, {u[1]:.6e}, {u[2]:.6e}] m")
    if s["analysis"] == "modal":
        print_modes(out)
    if s["analysis"] == "buckling" and s.get("buckling"):
        print(f"  critical load factors ({s['buckling']['about']} state): "
              + ", ".join(f"{x:.9g}" for x in s["buckling"]["load_factors"])
              + "; mode shapes: modes.pvd (mode_NN.vtu)")
    if s.get("warnings"):
        n = len(s["warnings"])
        print(f"  {n} warning{'s' if n > 1 else ''}: the result may be wrong (see above and summary.json)")
    print(f"  results in {out}/")


def print_modes(out):
    """The frequency table of a modal run (from modes.csv), and where the shapes are."""
    path = os.path.join(str(out), "modes.csv")
    if not os.path.exists(path):
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
    if os.path.exists(os.path.join(str(out), "modes.pvd")):
        print("  mode shapes: modes.pvd (mode_NN.vtu, time value = mode number), displaced by the scale above\n"
              "  (largest translation 10 % of the model length, section rotation at most 0.5 rad); point data\n"
              "  mode_shape is the mode normalized to a largest translation of 1")
