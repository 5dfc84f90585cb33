"""The code's layout (issue 33): the runtime's folders are layers and a layer
includes only the layers below it; every runtime, generator, report and API
module has at most 500 lines and opens with a comment or docstring naming its
job; the analyses are reached only through their table.  A structural check:
it reads the source, it runs nothing."""
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RUNTIME = ROOT / "runtime"

# folder -> the folders it may include (besides its own and the kernel contract)
MAY_CALL = {
    "base": set(),
    "linalg": {"base"},
    "model": {"base"},
    "assembly": {"model", "linalg", "base"},
    "solver": {"assembly", "linalg", "base", "model"},
    "output": {"assembly", "model", "base"},
    "analysis": {"assembly", "model", "base", "linalg", "solver", "output"},
}
MAX_LINES = 500
INCLUDE_RE = re.compile(r'^#include "([a-z_]+)/[a-z_0-9]+\.h"', re.M)


def _runtime_files():
    return sorted(p for p in RUNTIME.rglob("*") if p.suffix in (".c", ".h"))


def test_runtime_folders_are_the_layers():
    folders = {p.name for p in RUNTIME.iterdir() if p.is_dir()}
    assert folders == set(MAY_CALL), f"runtime folders {sorted(folders)} != the layers {sorted(MAY_CALL)}"
    for d in folders:
        assert (RUNTIME / d / "README.md").exists(), f"runtime/{d}/ has no README.md saying what it owns"
    top = sorted(p.name for p in RUNTIME.iterdir() if p.is_file() and p.suffix in (".c", ".h"))
    assert top == ["bk_joint.h", "bk_kernel.h", "main.c"], top


def test_a_layer_includes_only_the_layers_below_it():
    bad = []
    for p in _runtime_files():
        rel = p.relative_to(RUNTIME)
        if len(rel.parts) < 2:
            continue
        layer = rel.parts[0]
        for used in INCLUDE_RE.findall(p.read_text()):
            if used != layer and used not in MAY_CALL[layer]:
                bad.append(f"runtime/{rel} includes {used}/ (a {layer}/ file may call {sorted(MAY_CALL[layer])})")
    assert not bad, "\n".join(bad)


def _modules():
    yield from _runtime_files()
    for d in ("gen", "report", "beamkit"):
        yield from sorted((ROOT / d).rglob("*.py"))


def test_every_module_is_at_most_500_lines_and_names_its_job_first():
    long, silent = [], []
    for p in _modules():
        text = p.read_text()
        n = text.count("\n")
        if n > MAX_LINES:
            long.append(f"{p.relative_to(ROOT)}: {n} lines")
        head = text.lstrip()
        if not text.strip() and p.name == "__init__.py":
            continue
        if p.suffix == ".py":
            ok = head.startswith(('"""', "'''", "#"))
        else:
            ok = head.startswith("/*")
        if not ok:
            silent.append(str(p.relative_to(ROOT)))
    assert not long, "modules above %d lines:\n" % MAX_LINES + "\n".join(long)
    assert not silent, "modules that do not open with a comment naming their job:\n" + "\n".join(silent)


def test_analyses_are_dispatched_through_their_table_only():
    main = (RUNTIME / "main.c").read_text()
    assert "bk_analysis_for(" in main
    assert not re.search(r"analysis\s*[=!]=", main), "main.c switches on the analysis"
    assert not re.search(r"bk_solve_(static|dynamic|modal|continuation)\s*\(", main)
    from gen.solver_build import analysis_table_source
    table = analysis_table_source()
    for name in ("static", "continuation", "dynamic", "modal", "buckling"):
        assert f"&bk_analysis_{name}" in table, f"analysis {name} is not in the generated table"


def test_no_analysis_switch_outside_the_table_and_the_model():
    """The analysis modules say which models they run; the layers below ask
    the model only whether its states form a path and in what (model.h)."""
    bad = []
    for p in _runtime_files():
        rel = p.relative_to(RUNTIME).as_posix()
        if rel.startswith("analysis/") or rel in ("model/model.h", "model/model.c"):
            continue
        text = re.sub(r"/\*.*?\*/", "", p.read_text(), flags=re.S)
        for m in re.finditer(r"analysis\s*[=!]=|\bBK_(STATIC|DYNAMIC|MODAL)\b", text):
            bad.append(f"runtime/{rel}:{text[:m.start()].count(chr(10)) + 1}: {m.group(0)}")
    assert not bad, "analysis switches below the analyses:\n" + "\n".join(bad)


# The model's load and constraint lists (model.h): the analyses, the solver and
# the output ask the interactions (assembly/interaction.h: what each depends
# on, their rate along the path) and the constraints (system.h) instead, so a
# new load type needs no edit there.
LOAD_FIELDS_RE = re.compile(r"(?:\b(?:m|model)|->\s*m)\s*->\s*(nforce|forces|nmoment|moments|ndload|dloads|"
                            r"ntendon|tendons|has_gravity|gravity|gravity_amp|gravity_ampid|nlincon|lincons|nnlcon|"
                            r"nlcons)\b|\bbk_(assemble_follower|assemble_loads|assemble_loads_in|loads_present|"
                            r"load_potentials|element_loads)\s*\(")
# file -> why it may read them
LOAD_READERS = {
    "output/forces.c": "the reactions: each constraint's force, from its own rows",
    "output/joint_out.c": "the joints' reactions in their own axes",
    "analysis/dyn_frame_setup.c": "the rotating frame is defined by its driven constraint (axis, point, drive)",
    "analysis/dyn_frame.c": "the rotating frame holds its own constraint's coordinates at their t = 0 rows",
}


def test_analyses_and_output_ask_the_interactions_not_the_load_lists():
    """A guard that fails when a file of analysis/, solver/ or output/ (other
    than the reaction outputs named in LOAD_READERS) reads the model's loads,
    tendons or constraints, or calls a load type's own assembly (or its
    forces along an element: the section forces ask the interactions'
    element_loads)."""
    bad, used = [], set()
    for p in _runtime_files():
        rel = p.relative_to(RUNTIME).as_posix()
        if rel.split("/")[0] not in ("analysis", "solver", "output"):
            continue
        text = re.sub(r"/\*.*?\*/", "", p.read_text(), flags=re.S)
        for m in LOAD_FIELDS_RE.finditer(text):
            if rel in LOAD_READERS:
                used.add(rel)
                continue
            bad.append(f"runtime/{rel}:{text[:m.start()].count(chr(10)) + 1}: {m.group(0)}")
    assert not bad, "load or constraint lists read outside assembly/ (ask the interactions):\n" + "\n".join(bad)
    assert used == set(LOAD_READERS), f"allowed but no longer reading them: {sorted(set(LOAD_READERS) - used)}"


def test_the_load_list_guard_sees_a_reader():
    """The pattern of the guard above matches the reads it forbids (it could
    otherwise pass on any file)."""
    for line in ("if (m->nmoment > 0)", "s->m->nnlcon", "m->forces[i].amp", "bk_assemble_follower(s, q, 1.0, f, 0)",
                 "m -> ntendon", "bk_element_loads(s, q, x, e, Qe)"):
        assert LOAD_FIELDS_RE.search(line), line
    for line in ("m->nsensor", "bk_assemble_interactions(s, q, &p, f, 0)", "m->forcesx", "o->forces.sec",
                 "it->ops->element_loads(it->self, s, q, x, e, Qe)"):
        assert not LOAD_FIELDS_RE.search(line), line


# Options of one analysis read below the analyses: file -> why it may
ANALYSIS_OPTION_READERS = {
    "output/forces.c": "dynamic.rayleigh_alpha/beta: the damping forces in the reactions",
    "output/sections.c": "dynamic.rayleigh_alpha/beta: the damping forces in the section forces",
    "solver/stability.c": "static.eigenvalues: an option of the stability service itself",
    "solver/stability_setup.c": "static.eigenvalues: an option of the stability service itself",
}


def test_output_and_solver_read_no_analysis_options():
    """The output learns what an analysis writes from the analysis (its
    module's plan, analysis.h / output.h: the end of its path, its frames,
    modes, stability), not by reading static.method, cycles, dynamic.t_end or
    modal.modes: a guard that fails on such a read outside the files named in
    ANALYSIS_OPTION_READERS."""
    pat = re.compile(r"\bBK_METHOD_\w+|->\s*(stat|dyn|modal)\s*\.\s*\w+")
    assert pat.search("m->stat.method") and pat.search("v->m->modal.modes") and not pat.search("o->plan.end")
    bad = []
    for p in _runtime_files():
        rel = p.relative_to(RUNTIME).as_posix()
        if rel.split("/")[0] not in ("output", "solver") or rel in ANALYSIS_OPTION_READERS:
            continue
        text = re.sub(r"/\*.*?\*/", "", p.read_text(), flags=re.S)
        for m in pat.finditer(text):
            bad.append(f"runtime/{rel}:{text[:m.start()].count(chr(10)) + 1}: {m.group(0)}")
    assert not bad, "analysis options read in output/ or solver/ (tell the output through the plan):\n" + \
        "\n".join(bad)


def test_output_asks_the_plan_not_the_model_for_the_path():
    """Whether the states form a path, and in what, the output learns from the
    analysis (its plan's `path`, output.h), not from the model: a guard that
    fails on a call of bk_model_on_path, bk_model_in_time or bk_model_in_load
    in output/."""
    pat = re.compile(r"\bbk_model_(on_path|in_time|in_load)\s*\(")
    assert pat.search("if (bk_model_on_path(m))") and pat.search("bk_model_in_time (o->m)")
    assert not pat.search("o->plan.path != BK_PATH_NONE")
    bad = []
    for p in _runtime_files():
        rel = p.relative_to(RUNTIME).as_posix()
        if rel.split("/")[0] != "output":
            continue
        text = re.sub(r"/\*.*?\*/", "", p.read_text(), flags=re.S)
        for m in pat.finditer(text):
            bad.append(f"runtime/{rel}:{text[:m.start()].count(chr(10)) + 1}: {m.group(0)}")
    assert not bad, "output/ asks the model for the path (use the plan's path):\n" + "\n".join(bad)


def test_output_and_analyses_know_no_interaction_by_its_record():
    """The layers above assembly/ ask the interactions (interaction.h: e.g.
    keeps_apart for the overlap check, element_loads for the section forces),
    not the model for an interaction's record by name: a guard that fails on a
    call of bk_model_record_find in output/, analysis/ or solver/."""
    pat = re.compile(r"\bbk_model_record_find\s*\(")
    assert pat.search('bk_model_record_find(m, "beam_contact")') and not pat.search("bk_interactions_keep_apart(s)")
    bad = []
    for p in _runtime_files():
        rel = p.relative_to(RUNTIME).as_posix()
        if rel.split("/")[0] not in ("output", "analysis", "solver"):
            continue
        text = re.sub(r"/\*.*?\*/", "", p.read_text(), flags=re.S)
        for m in pat.finditer(text):
            bad.append(f"runtime/{rel}:{text[:m.start()].count(chr(10)) + 1}: {m.group(0)}")
    assert not bad, "an interaction's record looked up above assembly/ (ask the interactions):\n" + "\n".join(bad)
