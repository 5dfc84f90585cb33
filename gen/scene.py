"""Scene files: read the TOML, validate every key, mesh the beams and write the
model file the C solver reads (runtime/model.c documents the format).

Every error is one line: `error: FILE: KEY: what was expected, what was found`
raised as SceneError.  Nothing here imports sympy.
"""
import itertools
import json
import math
import time
import re
import tomllib
from pathlib import Path

import gen.scene_keys as K

ROOT = Path(__file__).resolve().parent.parent
KERNEL_INDEX = ROOT / "out" / "kernels" / "index.json"
NAME_RE = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.-]{0,62}$")

ANALYSES = ("static", "dynamic", "modal")
MAX_ELEMENTS = 1000000          # per beam (the model file and the solver use int indices)
PLANNED_ANALYSES = ()

STATIC_DEFAULTS = {"load_steps": 10, "max_iterations": 25, "max_cutbacks": 12,
                   "rtol": 1e-8, "utol": 1e-10, "cycles": 0, "predictor": "secant", "stability": True, "stable_path": False}

# Ranges of material keys, whatever the law: (test, expectation text).
KEY_RANGES = {
    "E": (lambda v: v > 0, "a positive number (Pa)"),
    "nu": (lambda v: -1 < v < 0.5, "a number in (-1, 0.5)"),
    "mu": (lambda v: v > 0, "a positive number (Pa)"),
    "lambda": (lambda v: v > -1e300, "a number (Pa)"),
    "kappa": (lambda v: v > 0, "a positive number (Pa)"),
    "lambda_m": (lambda v: 1 < v <= 1e6, "a number in (1, 1e6]"),
    "rho": (lambda v: v > 0, "a positive number (kg/m^3)"),
    "kelvin_voigt": (lambda v: v >= 0, "a retardation time >= 0 (s)"),
}
DYNAMIC_DEFAULTS = {"rho_inf": 0.8, "tol": 0.0, "max_iterations": 25, "max_cutbacks": 12,
                    "output_every": 1, "rayleigh_alpha": 0.0, "rayleigh_beta": 0.0,
                    "rtol": 1e-8, "utol": 1e-8}


class SceneError(Exception):
    pass


class Ctx:
    """Error reporting with the file name."""

    def __init__(self, path):
        self.path = str(path)

    def fail(self, key, msg):
        raise SceneError(f"error: {self.path}: {key}: {msg}")


def _typename(v):
    if isinstance(v, bool):
        return "a boolean"
    if isinstance(v, int):
        return f"the integer {v}"
    if isinstance(v, float):
        return f"the number {v!r}"
    if isinstance(v, str):
        return f"the string {v!r}"
    if isinstance(v, list):
        return "an array"
    if isinstance(v, dict):
        return "a table"
    return type(v).__name__


def get_number(ctx, tbl, key, where, default=None, positive=False, nonneg=False, hi=None):
    if key not in tbl:
        if default is None:
            ctx.fail(f"{where}.{key}", "missing; expected a number")
        return default
    v = tbl[key]
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        ctx.fail(f"{where}.{key}", f"expected a number, found {_typename(v)}")
    v = float(v)
    if not math.isfinite(v):
        ctx.fail(f"{where}.{key}", f"expected a finite number, found {v}")
    if positive and not v > 0:
        ctx.fail(f"{where}.{key}", f"expected a positive number, found {v!r}")
    if nonneg and v < 0:
        ctx.fail(f"{where}.{key}", f"expected a number >= 0, found {v!r}")
    if hi is not None and v > hi:
        ctx.fail(f"{where}.{key}", f"expected a number <= {hi:g}, found {v!r}")
    return v


def get_int(ctx, tbl, key, where, default=None, lo=1, hi=10**7):
    if key not in tbl:
        if default is None:
            ctx.fail(f"{where}.{key}", "missing; expected an integer")
        return default
    v = tbl[key]
    if isinstance(v, bool) or not isinstance(v, int):
        ctx.fail(f"{where}.{key}", f"expected an integer, found {_typename(v)}")
    if not lo <= v <= hi:
        ctx.fail(f"{where}.{key}", f"expected an integer in [{lo}, {hi}], found {v}")
    return v


def get_str(ctx, tbl, key, where, default=None, choices=None):
    if key not in tbl:
        if default is None:
            ctx.fail(f"{where}.{key}", "missing; expected " +
                     (f"one of {', '.join(choices)}" if choices else "a string"))
        return default
    v = tbl[key]
    if not isinstance(v, str):
        ctx.fail(f"{where}.{key}", f"expected a string, found {_typename(v)}")
    if choices is not None and v not in choices:
        ctx.fail(f"{where}.{key}", f"expected one of {', '.join(choices)}, found {v!r}")
    return v


def get_bool(ctx, tbl, key, where, default):
    if key not in tbl:
        return default
    v = tbl[key]
    if not isinstance(v, bool):
        ctx.fail(f"{where}.{key}", f"expected true or false, found {_typename(v)}")
    return v


def get_name(ctx, tbl, key, where):
    v = get_str(ctx, tbl, key, where)
    if not NAME_RE.match(v):
        ctx.fail(f"{where}.{key}", f"expected a name of letters, digits, '_', '.', '-' "
                 f"(at most 63, not starting with '.' or '-'), found {v!r}")
    return v


def get_vec3(ctx, tbl, key, where, default=None, nonzero=False, bound=None):
    if key not in tbl:
        if default is None:
            ctx.fail(f"{where}.{key}", "missing; expected an array of 3 numbers")
        return list(default)
    v = tbl[key]
    if not isinstance(v, list) or len(v) != 3 or any(
            isinstance(x, bool) or not isinstance(x, (int, float)) for x in v):
        ctx.fail(f"{where}.{key}", f"expected an array of 3 numbers, found {_typename(v) if not isinstance(v, list) else f'{v!r}'}")
    v = [float(x) for x in v]
    if not all(math.isfinite(x) for x in v):
        ctx.fail(f"{where}.{key}", f"expected finite numbers, found {v!r}")
    if bound is not None and any(abs(x) > bound for x in v):
        ctx.fail(f"{where}.{key}", f"expected coordinates within +-{bound:g}, found {v!r}")
    if nonzero and math.sqrt(sum(x * x for x in v)) == 0.0:
        ctx.fail(f"{where}.{key}", "expected a nonzero vector")
    return v


def check_keys(ctx, tbl, allowed, where):
    if not isinstance(tbl, dict):
        ctx.fail(where, f"expected a table, found {_typename(tbl)}")
    for k in tbl:
        if k not in allowed:
            ctx.fail(f"{where}.{k}", f"unknown key; expected one of {', '.join(sorted(allowed))}")


def get_table(ctx, doc, key, where=None):
    v = doc.get(key, {})
    if not isinstance(v, dict):
        ctx.fail(where or key, f"expected a table, found {_typename(v)}")
    return v


def get_array_of_tables(ctx, doc, key):
    v = doc.get(key, [])
    if not isinstance(v, list) or any(not isinstance(x, dict) for x in v):
        ctx.fail(key, f"expected an array of tables ([[{key}]]), found {_typename(v)}")
    return v


# ----------------------------------------------------------------------------
# vectors

def _sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def _dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _norm(a):
    return math.sqrt(_dot(a, a))


def _skew(v):
    return [[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]]


def _scale(a, s):
    return [x * s for x in a]


# ----------------------------------------------------------------------------
# --set overrides

def apply_overrides(doc, sets, path):
    """Apply KEY=VALUE overrides (numbers only) to the parsed TOML document."""
    for item in sets:
        if "=" not in item:
            raise SceneError(f"error: --set {item}: expected KEY=VALUE")
        key, val = item.split("=", 1)
        parts = key.split(".")
        try:
            num = int(val) if re.fullmatch(r"[+-]?\d+", val.strip()) else float(val)
        except ValueError:
            num = None
        node = doc
        for depth, p in enumerate(parts[:-1]):
            if isinstance(node, dict):
                if p not in node and p in ("static", "dynamic", "modal", "output") and depth == 0:
                    node[p] = {}
                if p not in node:
                    raise SceneError(f"error: {path}: --set {key}: no table '{'.'.join(parts[:depth + 1])}' in the scene")
                node = node[p]
            elif isinstance(node, list):
                match = [t for t in node if isinstance(t, dict) and t.get("name") == p]
                if not match and p.isdigit() and int(p) < len(node):
                    match = [node[int(p)]]
                if len(match) != 1:
                    raise SceneError(f"error: {path}: --set {key}: no entry named or numbered '{p}' in "
                                     f"'{'.'.join(parts[:depth])}'")
                node = match[0]
        last = parts[-1]
        if isinstance(node, list) and last.isdigit():
            i = int(last)
            if i >= len(node) or isinstance(node[i], bool) or not isinstance(node[i], (int, float)):
                raise SceneError(f"error: {path}: --set {key}: no number at index {i} of "
                                 f"'{'.'.join(parts[:-1])}'")
            if num is None:
                raise SceneError(f"error: --set {key}: expected a numeric value, found {val!r}")
            node[i] = num
            continue
        if not isinstance(node, dict):
            raise SceneError(f"error: {path}: --set {key}: '{'.'.join(parts[:-1])}' is not a table")
        old = node.get(parts[-1])
        if val in ("true", "false") and (old is None or isinstance(old, bool)):
            node[parts[-1]] = val == "true"
            continue
        if isinstance(old, bool):
            raise SceneError(f"error: --set {key}: expected true or false, found {val!r}")
        if isinstance(old, str):
            node[parts[-1]] = val          # a string key (element, law, ...) takes the text
            continue
        if old is not None and (isinstance(old, bool) or not isinstance(old, (int, float))):
            raise SceneError(f"error: {path}: --set {key}: the scene's value is {_typename(old)}, not a number")
        if num is None and old is not None:
            raise SceneError(f"error: --set {key}: expected a numeric value, found {val!r}")
        node[parts[-1]] = val if num is None else num
    return doc


# ----------------------------------------------------------------------------
# the scene

def load_index():
    try:
        return json.loads(KERNEL_INDEX.read_text(encoding="utf-8"))
    except OSError:
        raise SceneError(f"error: {KERNEL_INDEX}: missing; run ./build.sh gen")


def read_toml(path):
    ctx = Ctx(path)
    try:
        data = Path(path).read_bytes()
    except OSError as e:
        raise SceneError(f"error: {path}: cannot read: {e.strerror}")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise SceneError(f"error: {path}: encoding: not UTF-8 text (byte {e.start}); expected a TOML scene file")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise SceneError(f"error: {path}: TOML syntax: {e}")


def law_eval(exprs, names, values):
    """Values of the generated expressions of a law (out/kernels/index.json
    "materials": Python expressions written by gen/generate.py, math only) for
    the variables `names` = `values`."""
    import keyword
    env = {"math": math, "__builtins__": {}}
    for n, v in zip(names, values):
        env[n + "_" if keyword.iskeyword(n) else n] = float(v)
    return [float(eval(e, env)) for e in exprs]      # noqa: S307 -- the project's own generated text


def small_strain(index, law, params):
    """(E, nu) of a law at small strain, or None if the law states none."""
    info = index["materials"][law]
    if "small_strain" not in info:
        return None
    return law_eval(info["small_strain"], info["params"], params)


def material_params(ctx, mname, mt, index):
    """(law, rho, params) of a [material.NAME] table; params is a function of the
    section for resultant laws given by E and nu.  Reads the law from the
    kernel index (no sympy)."""
    where = f"material.{mname}"
    laws = sorted(index["materials"])
    law = get_str(ctx, mt, "law", where, choices=laws)
    info = index["materials"][law]
    rho = get_number(ctx, mt, "rho", where)
    given = sorted(k for k in mt if k not in ("law", "rho", "kelvin_voigt"))
    for k in given:
        v = mt[k]
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(float(v)):
            ctx.fail(f"{where}.{k}", f"expected a finite number, found {_typename(v)}")
    for k in ["rho"] + given + (["kelvin_voigt"] if "kelvin_voigt" in mt else []):
        if k in KEY_RANGES:
            test, expect = KEY_RANGES[k]
            if not test(float(mt[k])):
                ctx.fail(f"{where}.{k}", f"expected {expect}, found {mt[k]!r}")
    kind = info["kind"]
    inputs = [(tuple(i["keys"]), i["params"]) for i in info["inputs"]]
    if kind == "resultant" and "section_stiffness" in info:
        # E, nu with the beam's section: stiffnesses from gen/materials/resultant.py (plain math)
        inputs.append((("E", "nu"), None))
    options = [" + ".join(keys) for keys, _ in inputs]
    for keys, exprs in inputs:
        if sorted(keys) == given:
            if exprs is None:
                import importlib
                mod = importlib.import_module(info["section_stiffness"])
                E, nu = float(mt["E"]), float(mt["nu"])
                return law, rho, (lambda sec, E=E, nu=nu: [float(x) for x in mod.section_stiffness(E, nu, *sec)])
            if "kelvin_voigt" in mt and "small_strain" not in info and kind != "resultant":
                ctx.fail(f"{where}.kelvin_voigt", f"law {law!r} states no small-strain E, nu (small_strain()), "
                         "which Kelvin-Voigt damping needs")
            try:
                vals = law_eval(exprs, keys, [mt[k] for k in keys])
            except (ZeroDivisionError, ValueError, OverflowError):
                vals = [math.nan]
            if not all(math.isfinite(v) for v in vals):
                ctx.fail(where, f"parameters {', '.join(keys)} give non-finite {law} constants")
            if kind == "resultant" and not all(v > 0 for v in vals):
                ctx.fail(where, f"stiffnesses {', '.join(keys)} must be positive")
            return law, rho, (lambda sec, vals=vals: [float(v) for v in vals])
    known = {k for keys, _ in inputs for k in keys}
    for k in given:
        if k not in known:
            ctx.fail(f"{where}.{k}", f"unknown key for law {law!r}; expected law, rho and one of: {'; '.join(options)}")
    ctx.fail(where, f"law {law!r} needs rho and one of: {'; '.join(options)}; found {', '.join(given) or 'none'}")


def parse_point(ctx, spec, key, beams):
    """'beam:start' | 'beam:end' | 'beam:<arc length in m>' -> (beam, s)."""
    if not isinstance(spec, str):
        ctx.fail(key, f"expected a string like 'arm:end', found {_typename(spec)}")
    if ":" not in spec:
        ctx.fail(key, f"expected BEAM:start, BEAM:end or BEAM:<arc length in m>, found {spec!r}")
    bname, where = spec.rsplit(":", 1)
    if bname not in beams:
        ctx.fail(key, f"no beam named {bname!r} (beams: {', '.join(beams) or 'none'})")
    beam = beams[bname]
    if where == "start":
        return beam, 0.0
    if where == "end":
        return beam, beam["length"]
    try:
        s = float(where)
    except ValueError:
        ctx.fail(key, f"expected start, end or an arc length in m after ':', found {where!r}")
    if not math.isfinite(s) or s < 0 or s > beam["length"] * (1 + 1e-12):
        ctx.fail(key, f"arc length {where} outside beam {bname!r} (0 to {beam['length']:.6g} m)")
    return beam, min(s, beam["length"])


# Element choices measured to lock (out/report/verification.md, README "What is
# there today"): (element, integrations, test on the small-strain nu, advice).
LOCKING = (
    ("ancf3243", ("full",), lambda nu: nu >= 0.1,
     "Poisson locking: bending too stiff (26 % at nu = 0.3, slender beam); use integration = \"sri\""),
    ("ancf3333", ("full",), lambda nu: nu >= 0.1,
     "locks in bending (19 % too stiff at nu = 0.3, 20 elements); use ancf3363 or ancf3243 with sri"),
    ("ancf3363", ("full",), lambda nu: nu > 0.495,
     "volumetric locking with kappa/mu > 100 (10 % too stiff at kappa = 1000 mu); use integration = \"reduced\""),
    ("ancf3273", ("full", "reduced"), lambda nu: nu > 0.495,
     "volumetric locking with kappa/mu > 100 (0.76 of beam theory at kappa = 1000 mu, 10 elements); "
     "use integration = \"sri\""),
)


def locking_warnings(where, ename, integ, law, params, index):
    ss = small_strain(index, law, params)
    if ss is None:
        return []
    _, nu = ss
    out = []
    for el, integs, test, advice in LOCKING:
        if el == ename and integ in integs and test(nu):
            kappa_mu = 2 * (1 + nu) / (3 * (1 - 2 * nu)) if nu < 0.5 else math.inf
            out.append(f"{where}: element {ename} with integration {integ!r} and law {law} (small-strain "
                       f"nu = {nu:.4g}, kappa/mu = {kappa_mu:.3g}): {advice}")
    return out


def element_lengths(ctx, bt, where, nel, length):
    """Element lengths of a beam: uniform, or graded by `grading` (ratio of the
    last element's length to the first's, geometric progression) or given by
    `element_lengths` (relative weights, scaled to the beam length)."""
    if "grading" in bt and "element_lengths" in bt:
        ctx.fail(f"{where}.grading", "give either grading or element_lengths, not both")
    if "element_lengths" in bt:
        v = bt["element_lengths"]
        if not isinstance(v, list) or len(v) != nel or any(
                isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(float(x)) or x <= 0
                for x in v):
            ctx.fail(f"{where}.element_lengths", f"expected an array of {nel} positive numbers (one per element, "
                     f"relative lengths), found {_typename(v) if not isinstance(v, list) else repr(v)}")
        w = [float(x) for x in v]
    elif "grading" in bt:
        r = get_number(ctx, bt, "grading", where, positive=True)
        if not 1e-3 <= r <= 1e3:
            ctx.fail(f"{where}.grading", f"expected a ratio last / first element length in [0.001, 1000], found {r!r}")
        w = [r ** (k / (nel - 1)) if nel > 1 else 1.0 for k in range(nel)]
    else:
        w = [1.0] * nel
    tot = sum(w)
    ls = [length * x / tot for x in w]
    if min(ls) < 1e-9 * length:
        ctx.fail(f"{where}.element_lengths", "an element is shorter than 1e-9 of the beam")
    return ls


def _key(s, length):
    """Dictionary key of an arc length on a beam (relative, rounded)."""
    return round(s / length * 1e9) / 1e9


def locate_node(beam, frac):
    """(element, xi) of the node at `frac` of the beam length."""
    return locate(beam, frac * beam["length"])


def locate(beam, s):
    """(global element index, xi) of arc length s on a beam."""
    import bisect
    starts = beam["elem_start"]
    n = beam["nelem"]
    k = min(max(bisect.bisect_right(starts, s + 1e-12 * beam["length"]) - 1, 0), n - 1)
    l = beam["elem_lens"][k]
    xi = min(max((s - starts[k]) / l, 0.0), 1.0)
    return beam["first_elem"] + k, xi


def _cost_check(ctx, doc, index, analysis, beams_doc, out_dir, log):
    """Memory, disk and time of the run estimated from the raw element counts
    (gen/estimate.py): refuse what cannot fit, say what is large."""
    from gen import estimate as est_mod
    beams = []
    for bi, bt in enumerate(beams_doc):
        name = bt.get("name") if isinstance(bt.get("name"), str) else f"[{bi}]"
        ename, nel = bt.get("element"), bt.get("elements")
        if isinstance(ename, str) and ename in index["elements"] and isinstance(nel, int) and not isinstance(nel, bool) \
                and 0 < nel <= MAX_ELEMENTS:        # beyond the limit the reader says so
            beams.append((f"beam.{name}", ename, nel))
    if not beams:
        return
    out = doc.get("output", {}) if isinstance(doc.get("output"), dict) else {}
    st = doc.get("static", {}) if isinstance(doc.get("static"), dict) else {}
    every = out.get("vtk_every", 1)
    every = every if isinstance(every, int) and not isinstance(every, bool) and every >= 0 else 1
    if every == 0:
        frames = 0
    elif analysis == "dynamic":
        frames = 101
    elif analysis == "modal":
        md = doc.get("modal", {}) if isinstance(doc.get("modal"), dict) else {}
        frames = (md.get("modes", 10) if isinstance(md.get("modes", 10), int) else 10) + 2
    else:
        ls = st.get("load_steps", 10)
        ls = ls if isinstance(ls, int) and not isinstance(ls, bool) and ls > 0 else 10
        frames = ls // every + 2
    e = est_mod.estimate(beams, index, frames)
    est_mod.check(e, beams, str(out_dir) if out_dir else str(ROOT / "out"), ctx.fail, log)


def build(path, sets=(), name=None, log=None, out_dir=None):
    """Validate the scene and return the model as a dict of plain data.  log: a
    function taking a line (cost estimates and meshing progress of large
    models); out_dir: where the results will go (disk space check)."""
    ctx = Ctx(path)
    doc = read_toml(path)
    if sets:
        apply_overrides(doc, sets, path)
    index = load_index()
    check_keys(ctx, doc, set(K.TOP), "(top level)")
    scene = get_table(ctx, doc, "scene")
    check_keys(ctx, scene, set(K.SCENE), "scene")
    analysis = get_str(ctx, scene, "analysis", "scene", default="static",
                       choices=ANALYSES + PLANNED_ANALYSES)
    if analysis not in ANALYSES:
        ctx.fail("scene.analysis", f"{analysis!r} analysis is not implemented yet; expected static")
    if "description" in scene:
        get_str(ctx, scene, "description", "scene")
    sname = name or (get_name(ctx, scene, "name", "scene") if "name" in scene else Path(path).stem)
    if not NAME_RE.match(sname):
        ctx.fail("scene.name", f"scene name {sname!r} must be letters, digits, '_', '.', '-'")

    mats_doc = get_table(ctx, doc, "material")
    materials = {}
    for mname, mt in mats_doc.items():
        if not NAME_RE.match(mname):
            ctx.fail(f"material.{mname}", "material names are letters, digits, '_', '.', '-'")
        check_keys(ctx, mt, set(mt) if isinstance(mt, dict) else set(), f"material.{mname}")
        materials[mname] = material_params(ctx, mname, mt, index)

    secs_doc = get_table(ctx, doc, "section")
    sections = {}
    for sn, st in secs_doc.items():
        where = f"section.{sn}"
        check_keys(ctx, st, set(K.union(K.SECTION)), where)
        shape = get_str(ctx, st, "shape", where, choices=("rectangle", "circle"))
        if shape == "rectangle":
            check_keys(ctx, st, set(K.SECTION["rectangle"]), where)
            sections[sn] = ("rectangle", get_number(ctx, st, "b", where, positive=True, hi=1e6),
                            get_number(ctx, st, "h", where, positive=True, hi=1e6))
        else:
            check_keys(ctx, st, set(K.SECTION["circle"]), where)
            r = get_number(ctx, st, "radius", where, positive=True, hi=1e6)
            sections[sn] = ("circle", 2 * r, 2 * r)

    beams_doc = get_array_of_tables(ctx, doc, "beam")
    if not beams_doc:
        ctx.fail("beam", "missing; expected at least one [[beam]]")
    _cost_check(ctx, doc, index, analysis, beams_doc, out_dir, log)
    n_total = sum(bt["elements"] for bt in beams_doc if isinstance(bt.get("elements"), int))
    t_progress = [time.monotonic(), 0]
    beams = {}
    warnings = []       # likely wrong results (printed, and in summary.json "warnings")
    nodes = []          # (position, t, d1, d2, vectors) per global node
    dof_of_node = []
    ndof = 0
    q0 = []
    elements = []
    pairs, geoms, mats_used = [], [], []
    geom_index = {}
    for bi, bt in enumerate(beams_doc):
        where = f"beam[{bi}]"
        bname = get_name(ctx, bt, "name", where) if isinstance(bt.get("name"), str) else None
        if bname is not None:
            where = f"beam.{bname}"
        check_keys(ctx, bt, set(K.BEAM), where)
        bname = get_name(ctx, bt, "name", where)
        if bname in beams:
            ctx.fail(f"{where}.name", f"duplicate beam name {bname!r}")
        ename = get_str(ctx, bt, "element", where, choices=sorted(index["elements"]))
        einfo = index["elements"][ename]
        mname = get_str(ctx, bt, "material", where)
        if mname not in materials:
            ctx.fail(f"{where}.material", f"no [material.{mname}] in the scene (materials: {', '.join(materials) or 'none'})")
        secname = get_str(ctx, bt, "section", where)
        if secname not in sections:
            ctx.fail(f"{where}.section", f"no [section.{secname}] in the scene (sections: {', '.join(sections) or 'none'})")
        integ = get_str(ctx, bt, "integration", where, default=einfo["default_integration"],
                        choices=sorted(einfo["integrations"]))
        law = materials[mname][0]
        mkind = index["materials"][law]["kind"]
        if mkind != einfo["material_kind"]:
            need = ("law = \"resultant\" (E, nu or the six stiffnesses)" if einfo["material_kind"] == "resultant"
                    else "a continuum law (" + ", ".join(k for k, v in sorted(index["materials"].items())
                                                         if v["kind"] == "continuum") + ")")
            ctx.fail(f"{where}.material", f"element {ename} needs {need}; material {mname!r} has law {law!r}")
        pair = f"{ename}_{law}_{integ}"
        if not any(p["element"] == ename and p["material"] == law and p["integration"] == integ
                   for p in index["pairs"]):
            ctx.fail(f"{where}.element", f"no generated kernel for element {ename!r} x law {law!r} "
                     f"x integration {integ!r}")
        sec = sections[secname]
        if einfo["section"] == "rectangle" and sec[0] != "rectangle":
            ctx.fail(f"{where}.section", f"element {ename} needs a rectangle section, found {sec[0]}")
        params = materials[mname][2](sec)
        if einfo["kind"] == "continuum":
            warnings += locking_warnings(where, ename, integ, law, params, index)
        if einfo["kind"] == "cable" and abs(params[4] - params[5]) > 1e-9 * max(params[4], params[5]):
            ctx.fail(f"{where}.section", f"element ancf_cable has no section orientation and needs equal "
                     f"bending stiffnesses, found EI1 = {params[4]:.6g}, EI2 = {params[5]:.6g}")
        start = get_vec3(ctx, bt, "start", where, bound=1e9)
        nel = get_int(ctx, bt, "elements", where, lo=1, hi=MAX_ELEMENTS)
        arc_keys = [k for k in ("arc_center", "arc_axis", "arc_angle") if k in bt]
        if arc_keys:
            if "end" in bt:
                ctx.fail(f"{where}.end", "give either end (straight beam) or arc_center, arc_axis, arc_angle")
            if not einfo["curved"]:
                ctx.fail(f"{where}.{arc_keys[0]}", f"element {ename} supports straight beams only; curved "
                         f"beams need gef, euler_bernoulli or kirchhoff")
            geo = arc_geometry(ctx, bt, where, start)
        else:
            end = get_vec3(ctx, bt, "end", where, bound=1e9)
            geo = line_geometry(ctx, bt, where, start, end)
        length = geo.length

        if pair not in pairs:
            pairs.append(pair)
        pidx = pairs.index(pair)
        visc = []
        tau = float(mats_doc[mname].get("kelvin_voigt", 0.0))
        if tau > 0 and einfo["kind"] != "continuum":
            ctx.fail(f"material.{mname}.kelvin_voigt", f"Kelvin-Voigt damping is offered by the ANCF continuum "
                     f"elements; for element {ename} use [dynamic] rayleigh_alpha / rayleigh_beta")
        if tau > 0:
            if mkind == "resultant":
                visc = [tau * v for v in params]
            else:
                E_, nu_ = small_strain(index, law, params)
                visc = [tau * E_ * nu_ / ((1 + nu_) * (1 - 2 * nu_)), tau * E_ / (2 * (1 + nu_))]
        mkey = (tuple(params), materials[mname][1], tuple(visc))
        if mkey not in mats_used:
            mats_used.append(mkey)
        midx = mats_used.index(mkey)
        lens = element_lengths(ctx, bt, where, nel, length)
        starts = [0.0] + list(itertools.accumulate(lens))[:-1]

        first_elem = len(elements)
        enodes = einfo["nodes"]
        prev_end = None
        node_ids_of_beam = {}
        for k in range(nel):
            if log and n_total > 100000 and k % 4096 == 0 and time.monotonic() - t_progress[0] > 2.0:
                t_progress[0] = time.monotonic()
                log(f"meshing: {t_progress[1] + k} of {n_total} elements")
            edofs = []
            end_node = None
            l = lens[k]
            for ni, nd in enumerate(enodes):
                xi = float(eval_fraction(nd["xi"]))
                fields = tuple((f, d) for f, d in nd["fields"])
                if xi == 0.0 and prev_end is not None:
                    gid = prev_end
                else:
                    X, t, d1, d2 = geo.at(starts[k] + xi * l)
                    gid = len(nodes)
                    nodes.append((X, t, d1, d2, fields))
                    dof_of_node.append(ndof)
                    for f, dim in fields:
                        q0.extend(reference_field(f, t, d1, d2, X))
                    ndof += sum(d for _, d in fields)
                    node_ids_of_beam[_key(starts[k] + xi * l, length)] = gid
                if nodes[gid][4] != fields:
                    ctx.fail(f"{where}.element", "inconsistent node layout between elements")
                base = dof_of_node[gid]
                edofs.extend(range(base, base + sum(d for _, d in fields)))
                if xi == 1.0:
                    end_node = gid
            # element-internal unknowns (multipliers of constrained theories)
            nint = einfo.get("internal", 0)
            edofs.extend(range(ndof, ndof + nint))
            q0.extend([0.0] * nint)
            ndof += nint
            prev_end = end_node
            gkey = (pidx, l, sec, geo.shape_key)     # congruent elements share a table
            if gkey not in geom_index:
                geom_index[gkey] = len(geoms)
                geoms.append((pidx, len(elements), section_geometry(sec, l)))
            elements.append((pidx, geom_index[gkey], midx, edofs))
        t_progress[1] += nel
        beams[bname] = {"name": bname, "element": ename, "length": length, "nelem": nel,
                        "first_elem": first_elem, "geo": geo, "elem_lens": lens, "elem_start": starts,
                        "node_at": node_ids_of_beam,
                        "kind": einfo["kind"], "moments": einfo["moments"]}

    # Constraints
    fixed = set()
    lincons = []

    def row(terms, r0=0.0, rc=0.0, rs=0.0, kappa=0.0, rate=0.0, amp=0.0, freq=0.0):
        """terms: [(dof, c0, cc, cs)].  A static single-DOF row is a fixed DOF."""
        terms = [t_ for t_ in terms if any(abs(c) > 1e-15 for c in t_[1:])]
        if not terms:
            return
        if len(terms) == 1 and terms[0][2] == 0 and terms[0][3] == 0 and rc == 0 and rs == 0 \
                and abs(r0 - terms[0][1] * q0[terms[0][0]]) <= 1e-12 * max(1.0, abs(r0)):
            fixed.add(terms[0][0])
            return
        lincons.append((terms, (r0, rc, rs), (kappa, rate, amp, freq)))

    def node_of(ctx_key, spec, what):
        beam, s_ = parse_point(ctx, spec, ctx_key, beams)
        gid = beam["node_at"].get(_key(s_, beam["length"]))
        if gid is None:
            near = min(beam["node_at"], key=lambda x: abs(x - s_ / beam["length"])) * beam["length"]
            ctx.fail(ctx_key, f"a {what} must be at a node of beam {beam['name']!r} (nearest node at arc "
                     f"length {near:.6g} m), found arc length {s_:.6g}")
        return beam, s_, gid

    def field_dofs(gid):
        out, base = {}, dof_of_node[gid]
        for f, dim in nodes[gid][4]:
            out[f] = list(range(base, base + dim))
            base += dim
        return out

    ctypes_ = tuple(K.CONSTRAINT)
    for ci, ct in enumerate(get_array_of_tables(ctx, doc, "constraint")):
        where = f"constraint[{ci}]"
        ctype = get_str(ctx, ct, "type", where, choices=ctypes_)
        check_keys(ctx, ct, set(K.CONSTRAINT[ctype]), where)
        if "a" not in ct:
            ctx.fail(f"{where}.a", "missing; expected a point like 'arm:start'")
        beam, s, gid = node_of(f"{where}.a", ct["a"], ctype)
        fd = field_dofs(gid)
        X = nodes[gid][0]
        if ctype == "clamp":
            mode = get_str(ctx, ct, "cross_section", where, default="rigid", choices=("rigid", "free"))
            if mode == "rigid":
                for dl in fd.values():
                    fixed.update(dl)
                continue
            _, t, d1, d2 = beam["geo"].at(s)
            normals = {"r_x": (d1, d2), "r_y": (t, d2), "r_z": (t, d1)}
            for f, dl in fd.items():
                if f == "r" or len(dl) != 3:
                    fixed.update(dl)                                  # position, rotations: held
                elif f in normals:
                    for nrm in normals[f]:
                        row([(dl[i], nrm[i], 0.0, 0.0) for i in range(3)])
                else:                   # r_yy, r_yz, r_zz: the section stays plane, free in its plane
                    row([(dl[i], t[i], 0.0, 0.0) for i in range(3)])
        elif ctype == "spherical":
            if "b" not in ct:
                fixed.update(fd["r"])                                 # to ground
                continue
            beam_b, s_b, gid_b = node_of(f"{where}.b", ct["b"], "spherical joint")
            if _norm(_sub(X, nodes[gid_b][0])) > 1e-9 * max(1.0, _norm(X)):
                ctx.fail(f"{where}.b", f"the points a and b must coincide in the reference configuration "
                         f"({ct['a']} at {X}, {ct['b']} at {nodes[gid_b][0]})")
            if gid_b == gid:
                ctx.fail(f"{where}.b", "a and b are the same node")
            fb = field_dofs(gid_b)
            for i in range(3):
                row([(fd["r"][i], 1.0, 0.0, 0.0), (fb["r"][i], -1.0, 0.0, 0.0)])
        else:
            axis = get_vec3(ctx, ct, "axis", where, nonzero=True)
            axis = _scale(axis, 1 / _norm(axis))
            n1 = _cross(axis, [1.0, 0.0, 0.0])
            if _norm(n1) < 0.5:
                n1 = _cross(axis, [0.0, 1.0, 0.0])
            n1 = _scale(n1, 1 / _norm(n1))
            n2 = _cross(axis, n1)
            _, t, d1, d2 = beam["geo"].at(s)
            fixed.update(fd["r"])                                     # the axis passes through the point
            if ctype == "revolute":
                if "p" in fd:                   # quaternion: vec(p conj(p0)) parallel to the axis
                    p0 = [q0[d] for d in fd["p"]]
                    s0, v0 = p0[0], p0[1:]
                    A = [[-v0[i]] + [(s0 if i == j else 0.0) + _skew(v0)[i][j] for j in range(3)] for i in range(3)]
                    for nrm in (n1, n2):
                        row([(fd["p"][k], sum(nrm[i] * A[i][k] for i in range(3)), 0.0, 0.0) for k in range(4)])
                else:                           # ANCF: the material fibre along the axis stays along it
                    comps = {"r_x": _dot(axis, t), "r_y": _dot(axis, d1), "r_z": _dot(axis, d2)}
                    for f, c in comps.items():
                        if abs(c) > 1e-12 and f not in fd:
                            ctx.fail(f"{where}.axis", f"element {beam['element']} has no nodal {f} at this "
                                     "point; a revolute axis there must lie in the cross-section plane")
                    for nrm in (n1, n2):
                        terms = []
                        for f, c in comps.items():
                            if abs(c) > 1e-12:
                                terms += [(fd[f][i], c * nrm[i], 0.0, 0.0) for i in range(3)]
                        row(terms)
            else:
                rate = get_number(ctx, ct, "rate", where, default=0.0)
                amp = get_number(ctx, ct, "amplitude", where, default=0.0)
                freq = get_number(ctx, ct, "frequency", where, default=0.0, nonneg=True)
                for f, dl in fd.items():
                    if f == "r":
                        continue
                    if f == "p":                # p(t) = (cos th/2, sin th/2 axis) p0
                        s0, v0 = q0[dl[0]], [q0[d] for d in dl[1:]]
                        av = _dot(axis, v0)
                        cr = _cross(axis, v0)
                        row([(dl[0], 1.0, 0.0, 0.0)], 0.0, s0, -av, 0.5, rate, amp, freq)
                        for i in range(3):
                            row([(dl[1 + i], 1.0, 0.0, 0.0)], 0.0, v0[i], s0 * axis[i] + cr[i], 0.5, rate, amp, freq)
                    elif len(dl) == 3:          # nodal vectors rotate rigidly
                        v0 = [q0[d] for d in dl]
                        par = _dot(axis, v0)
                        cr = _cross(axis, v0)
                        for i in range(3):
                            row([(dl[i], 1.0, 0.0, 0.0)], par * axis[i], v0[i] - par * axis[i], cr[i],
                                1.0, rate, amp, freq)
                    else:
                        fixed.update(dl)

    # Loads
    forces = []
    moments = []
    gravity = None
    for li, lt in enumerate(get_array_of_tables(ctx, doc, "load")):
        where = f"load[{li}]"
        ltype = get_str(ctx, lt, "type", where, choices=tuple(K.LOAD))
        if ltype in ("force", "moment"):
            check_keys(ctx, lt, set(K.LOAD[ltype]), where)
            if "at" not in lt:
                ctx.fail(f"{where}.at", "missing; expected a point like 'arm:end'")
            beam, s = parse_point(ctx, lt["at"], f"{where}.at", beams)
            val = get_vec3(ctx, lt, "value", where)
            e, xi = locate(beam, s)
            if ltype == "force":
                dist = get_str(ctx, lt, "distribution", where, default="point", choices=("point", "section"))
                forces.append((e, xi, 0.0, 0.0, 1 if dist == "section" else 0, val))
            else:
                if beam["moments"] == "nodes":
                    frac = s / beam["length"]
                    nodes_here = [x for x in beam["node_at"] if abs(x - frac) < 1e-9]
                    if not nodes_here:
                        near = min(beam["node_at"], key=lambda x: abs(x - frac)) * beam["length"]
                        ctx.fail(f"{where}.at", f"element {beam['element']} takes moments at nodes only "
                                 f"(nearest node of {beam['name']!r} at {near:.6g} m), found {s:.6g}")
                    e, xi = locate_node(beam, nodes_here[0])
                elif beam["moments"] == "no_torsion":
                    _, t, _, _ = beam["geo"].at(s)
                    mt = abs(_dot(val, t))
                    if mt > 1e-9 * max(_norm(val), 1e-300):
                        ctx.fail(f"{where}.value", f"element {beam['element']} cannot carry a torque about its "
                                 f"axis (moment component {mt:.6g} N m along the beam at {lt['at']!r})")
                moments.append((e, xi, val))
        else:
            check_keys(ctx, lt, set(K.LOAD["gravity"]), where)
            g = get_vec3(ctx, lt, "value", where)
            if gravity is not None:
                ctx.fail(f"{where}.type", "gravity given twice")
            gravity = g

    # Static options
    st = get_table(ctx, doc, "static")
    check_keys(ctx, st, set(K.STATIC), "static")
    stat = {
        "load_steps": get_int(ctx, st, "load_steps", "static", default=STATIC_DEFAULTS["load_steps"], lo=1, hi=10**7),
        "max_iterations": get_int(ctx, st, "max_iterations", "static", default=STATIC_DEFAULTS["max_iterations"], lo=1, hi=10000),
        "max_cutbacks": get_int(ctx, st, "max_cutbacks", "static", default=STATIC_DEFAULTS["max_cutbacks"], lo=0, hi=60),
        "cycles": get_int(ctx, st, "cycles", "static", default=0, lo=0, hi=1000),
        "rtol": get_number(ctx, st, "rtol", "static", default=STATIC_DEFAULTS["rtol"], positive=True),
        "utol": get_number(ctx, st, "utol", "static", default=STATIC_DEFAULTS["utol"], positive=True),
        "predictor": get_str(ctx, st, "predictor", "static", default=STATIC_DEFAULTS["predictor"],
                             choices=("none", "secant")),
        "stability": get_bool(ctx, st, "stability", "static", STATIC_DEFAULTS["stability"]),
        "stable_path": get_bool(ctx, st, "stable_path", "static", STATIC_DEFAULTS["stable_path"]),
    }
    dt = get_table(ctx, doc, "dynamic")
    check_keys(ctx, dt, set(K.DYNAMIC), "dynamic")
    dyn = {k: v for k, v in DYNAMIC_DEFAULTS.items()}
    if analysis == "dynamic":
        dyn["t_end"] = get_number(ctx, dt, "t_end", "dynamic", positive=True)
        dyn["dt"] = get_number(ctx, dt, "dt", "dynamic", positive=True)
        if dyn["dt"] > dyn["t_end"]:
            ctx.fail("dynamic.dt", f"expected a step no longer than t_end = {dyn['t_end']!r}, found {dyn['dt']!r}")
    else:
        dyn["t_end"], dyn["dt"] = 1.0, 1.0
    dyn["dt_min"] = get_number(ctx, dt, "dt_min", "dynamic", default=dyn["dt"] * 1e-6, positive=True)
    dyn["rho_inf"] = get_number(ctx, dt, "rho_inf", "dynamic", default=DYNAMIC_DEFAULTS["rho_inf"])
    if not 0.0 <= dyn["rho_inf"] <= 1.0:
        ctx.fail("dynamic.rho_inf", f"expected a spectral radius in [0, 1], found {dyn['rho_inf']!r}")
    for k in ("tol", "rayleigh_alpha", "rayleigh_beta"):
        dyn[k] = get_number(ctx, dt, k, "dynamic", default=DYNAMIC_DEFAULTS[k], nonneg=True)
    for k in ("rtol", "utol"):
        dyn[k] = get_number(ctx, dt, k, "dynamic", default=DYNAMIC_DEFAULTS[k], positive=True)
    dyn["max_iterations"] = get_int(ctx, dt, "max_iterations", "dynamic", default=25, lo=1, hi=10000)
    dyn["max_cutbacks"] = get_int(ctx, dt, "max_cutbacks", "dynamic", default=12, lo=0, hi=60)
    dyn["output_every"] = get_int(ctx, dt, "output_every", "dynamic", default=1, lo=1, hi=10**9)
    if analysis == "dynamic" and dyn["t_end"] / dyn["dt"] > 1e8:
        ctx.fail("dynamic.dt", f"t_end / dt = {dyn['t_end'] / dyn['dt']:.3g} steps: expected at most 1e8")

    ot = get_table(ctx, doc, "output")
    check_keys(ctx, ot, set(K.OUTPUT), "output")
    if analysis == "dynamic":
        n_out = dyn["t_end"] / (dyn["dt"] * dyn["output_every"])
        default_vtk = max(1, math.ceil(n_out / 100))
    else:
        default_vtk = 1
    vtk_every = get_int(ctx, ot, "vtk_every", "output", default=default_vtk, lo=0, hi=10**9)

    mt = get_table(ctx, doc, "modal")
    check_keys(ctx, mt, set(K.MODAL), "modal")
    modal = {"modes": get_int(ctx, mt, "modes", "modal", default=10, lo=1, hi=100000),
             "about": 1 if get_str(ctx, mt, "about", "modal", default="reference",
                                   choices=("reference", "static")) == "static" else 0}

    # Initial velocities: rigid translation + rotation, per beam or for all.
    qd0 = [0.0] * ndof
    for ii, iv in enumerate(get_array_of_tables(ctx, doc, "initial_velocity")):
        where = f"initial_velocity[{ii}]"
        check_keys(ctx, iv, set(K.INITIAL_VELOCITY), where)
        v = get_vec3(ctx, iv, "velocity", where, default=[0.0, 0.0, 0.0])
        w = get_vec3(ctx, iv, "angular_velocity", where, default=[0.0, 0.0, 0.0])
        c = get_vec3(ctx, iv, "center", where, default=[0.0, 0.0, 0.0])
        if "beam" in iv:
            bn = get_str(ctx, iv, "beam", where)
            if bn not in beams:
                ctx.fail(f"{where}.beam", f"no beam named {bn!r} (beams: {', '.join(beams)})")
            gids = sorted(set(beams[bn]["node_at"].values()))
        else:
            gids = range(len(nodes))
        for gid in gids:
            X = nodes[gid][0]
            base = dof_of_node[gid]
            for f, dim in nodes[gid][4]:
                vals = [q0[base + i] for i in range(dim)]
                if f == "r":
                    out = [v[i] + x for i, x in enumerate(_cross(w, _sub(X, c)))]
                elif f == "p":                     # p' = (0, w) p / 2
                    s0, v0 = vals[0], vals[1:]
                    out = [-0.5 * _dot(w, v0)] + [0.5 * (s0 * w[i] + _cross(w, v0)[i]) for i in range(3)]
                elif dim == 3:
                    out = _cross(w, vals)
                else:
                    out = [0.0] * dim
                for i in range(dim):
                    qd0[base + i] = out[i]
                base += dim

    sensors = []
    seen = set()
    for si, sd in enumerate(get_array_of_tables(ctx, doc, "sensor")):
        where = f"sensor[{si}]"
        check_keys(ctx, sd, set(K.SENSOR), where)
        sn = get_name(ctx, sd, "name", where)
        if sn in seen:
            ctx.fail(f"sensor.{sn}", f"duplicate sensor name {sn!r}")
        seen.add(sn)
        if "at" not in sd:
            ctx.fail(f"sensor.{sn}.at", "missing; expected a point like 'arm:end'")
        beam, s = parse_point(ctx, sd["at"], f"sensor.{sn}.at", beams)
        e, xi = locate(beam, s)
        sensors.append((sn, e, xi))

    if not fixed and not lincons:
        pass  # allowed: the solver reports the singular tangent with a hint

    return {
        "name": sname, "analysis": analysis, "ndof": ndof, "q0": q0,
        "length_scale": max(b["length"] for b in beams.values()),
        "pairs": pairs, "mats": mats_used, "geoms": geoms, "elements": elements,
        "fixed": sorted(fixed), "lincons": lincons, "forces": forces, "moments": moments,
        "gravity": gravity,
        "sensors": sensors, "static": stat, "beams": beams, "dynamic": dyn, "modal": modal, "qd0": qd0,
        "vtk_every": vtk_every, "warnings": warnings,
    }


class LineGeometry:
    """Straight beam: point and section frame (t, d1, d2) at arc length s."""

    def __init__(self, start, t, d1, d2, length):
        self.start, self.t, self.d1, self.d2, self.length = start, t, d1, d2, length
        self.shape_key = ("straight",)

    def at(self, s):
        return [self.start[i] + s * self.t[i] for i in range(3)], self.t, self.d1, self.d2


class ArcGeometry:
    """Circular arc about `axis` through `center`, from `start`, right-handed."""

    def __init__(self, center, axis, start, d1, d2, radius, angle):
        self.center, self.axis, self.start0 = center, axis, start
        self.d10, self.d20, self.radius = d1, d2, radius
        self.length = radius * angle
        self.shape_key = ("arc", round(radius, 12))

    def at(self, s):
        phi = s / self.radius
        rot = lambda v: _rotate(v, self.axis, phi)
        X = [self.center[i] + x for i, x in enumerate(rot(_sub(self.start0, self.center)))]
        d1, d2 = rot(self.d10), rot(self.d20)
        return X, _cross(d1, d2), d1, d2


def _rotate(v, k, phi):
    """Rodrigues rotation of v about the unit axis k by phi."""
    c, s_ = math.cos(phi), math.sin(phi)
    kv = _cross(k, v)
    kd = _dot(k, v)
    return [v[i] * c + kv[i] * s_ + k[i] * kd * (1 - c) for i in range(3)]


def line_geometry(ctx, bt, where, start, end):
    axis = _sub(end, start)
    length = _norm(axis)
    if not length > 0:
        ctx.fail(f"{where}.end", "expected an end point different from start (beam length must be positive)")
    t = _scale(axis, 1 / length)
    d1, d2 = section_axes(ctx, bt, where, t, [0.0, 0.0, 1.0])
    return LineGeometry(start, t, d1, d2, length)


def section_axes(ctx, bt, where, t, default_up):
    up = get_vec3(ctx, bt, "up", where, default=default_up, nonzero=True, bound=1e300)
    upn = _scale(up, 1 / _norm(up))
    d2 = _sub(upn, _scale(t, _dot(upn, t)))
    if _norm(d2) < 1e-6:
        ctx.fail(f"{where}.up", "expected a direction not parallel to the beam axis")
    d2 = _scale(d2, 1 / _norm(d2))
    return _cross(d2, t), d2


def arc_geometry(ctx, bt, where, start):
    for k in ("arc_center", "arc_axis", "arc_angle"):
        if k not in bt:
            ctx.fail(f"{where}.{k}", "missing; a curved beam needs arc_center, arc_axis and arc_angle")
    center = get_vec3(ctx, bt, "arc_center", where, bound=1e9)
    axis = get_vec3(ctx, bt, "arc_axis", where, nonzero=True, bound=1e300)
    axis = _scale(axis, 1 / _norm(axis))
    angle = get_number(ctx, bt, "arc_angle", where)
    if not 0 < angle <= 360:
        ctx.fail(f"{where}.arc_angle", f"expected an angle in (0, 360] degrees, found {angle!r}")
    rvec = _sub(start, center)
    radius = _norm(rvec)
    if radius == 0 or abs(_dot(rvec, axis)) > 1e-9 * radius:
        ctx.fail(f"{where}.arc_center", "expected the start point off the centre, in the plane normal to arc_axis")
    t = _cross(axis, _scale(rvec, 1 / radius))
    d1, d2 = section_axes(ctx, bt, where, t, axis)
    return ArcGeometry(center, axis, start, d1, d2, radius, math.radians(angle))


def eval_fraction(s):
    if "/" in s:
        a, b = s.split("/")
        return int(a) / int(b)
    return float(s)


def reference_field(name, t, d1, d2, x0):
    """Reference value of a nodal field for the section frame (t, d1, d2) at x0."""
    if name == "r":
        return list(x0)
    if name == "r_x":
        return list(t)
    if name == "r_y":
        return list(d1)
    if name == "r_z":
        return list(d2)
    if name == "p":
        return frame_quaternion(t, d1, d2)
    return [0.0, 0.0, 0.0]


def frame_quaternion(t, d1, d2):
    """Unit quaternion (s, x, y, z) of the rotation with columns (t, d1, d2)."""
    R = [[t[i], d1[i], d2[i]] for i in range(3)]
    tr = R[0][0] + R[1][1] + R[2][2]
    if tr > 0:
        w = math.sqrt(1 + tr) * 2
        q = [w / 4, (R[2][1] - R[1][2]) / w, (R[0][2] - R[2][0]) / w, (R[1][0] - R[0][1]) / w]
    elif R[0][0] > R[1][1] and R[0][0] > R[2][2]:
        w = math.sqrt(1 + R[0][0] - R[1][1] - R[2][2]) * 2
        q = [(R[2][1] - R[1][2]) / w, w / 4, (R[0][1] + R[1][0]) / w, (R[0][2] + R[2][0]) / w]
    elif R[1][1] > R[2][2]:
        w = math.sqrt(1 + R[1][1] - R[0][0] - R[2][2]) * 2
        q = [(R[0][2] - R[2][0]) / w, (R[0][1] + R[1][0]) / w, w / 4, (R[1][2] + R[2][1]) / w]
    else:
        w = math.sqrt(1 + R[2][2] - R[0][0] - R[1][1]) * 2
        q = [(R[1][0] - R[0][1]) / w, (R[0][2] + R[2][0]) / w, (R[1][2] + R[2][1]) / w, w / 4]
    n = math.sqrt(sum(x * x for x in q))
    return [x / n for x in q]


def section_geometry(sec, l):
    """geom[7] = {l, b, h, A, I1, I2, Ip} of a section (runtime/bk_kernel.h)."""
    shape, b, h = sec
    if shape == "rectangle":
        A, I1, I2 = b * h, b * h**3 / 12, h * b**3 / 12
    else:
        r = b / 2
        A, I1 = math.pi * r * r, math.pi * r**4 / 4
        I2 = I1
    return [l, b, h, A, I1, I2, I1 + I2]


def _f(x):
    return repr(float(x))


def write_model(model, path):
    """Write the model file read by runtime/model.c."""
    out = ["beamkit-model 1", f"name {model['name']}", f"analysis {model['analysis']}",
           f"length_scale {_f(model['length_scale'])}"]
    s = model["static"]
    out.append(f"static {s['load_steps']} {s['max_iterations']} {s['max_cutbacks']} {s['cycles']} "
               f"{_f(s['rtol'])} {_f(s['utol'])} {int(s['predictor'] == 'secant')} "
               f"{int(s['stability'] or s['stable_path'])} {int(s['stable_path'])}")
    d = model["dynamic"]
    out.append(f"dynamic {_f(d['t_end'])} {_f(d['dt'])} {_f(d['dt_min'])} {_f(d['rho_inf'])} {_f(d['tol'])} "
               f"{d['max_iterations']} {d['max_cutbacks']} {d['output_every']} {_f(d['rayleigh_alpha'])} "
               f"{_f(d['rayleigh_beta'])} {_f(d['rtol'])} {_f(d['utol'])}")
    out.append(f"output {model['vtk_every']}")
    out.append(f"modal {model['modal']['modes']} {model['modal']['about']}")
    out.append(f"ndof {model['ndof']}")
    out.append("q0")
    q0 = model["q0"]
    for i in range(0, len(q0), 6):
        out.append(" ".join(_f(v) for v in q0[i:i + 6]))
    out.append("qd0")
    qd = model["qd0"]
    for i in range(0, len(qd), 6):
        out.append(" ".join(_f(v) for v in qd[i:i + 6]))
    out.append(f"pairs {len(model['pairs'])}")
    out += [f"pair {p}" for p in model["pairs"]]
    out.append(f"mats {len(model['mats'])}")
    for params, rho, visc in model["mats"]:
        out.append(f"mat {_f(rho)} {len(params)} " + " ".join(_f(v) for v in params)
                   + f" {len(visc)} " + " ".join(_f(v) for v in visc))
    out.append(f"geoms {len(model['geoms'])}")
    for p, e, g in model["geoms"]:
        out.append(f"geom {p} {e} " + " ".join(_f(x) for x in g))
    out.append(f"elements {len(model['elements'])}")
    for p, g, m, dofs in model["elements"]:
        out.append(f"element {p} {g} {m} {len(dofs)} " + " ".join(map(str, dofs)))
    out.append(f"fixed {len(model['fixed'])}")
    for i in range(0, len(model["fixed"]), 24):
        out.append(" ".join(map(str, model["fixed"][i:i + 24])))
    out.append(f"lincons {len(model['lincons'])}")
    for terms, rhs, tf in model["lincons"]:
        out.append(f"lincon {len(terms)} " + " ".join(f"{d} {_f(a)} {_f(b)} {_f(c)}" for d, a, b, c in terms)
                   + " " + " ".join(_f(x) for x in rhs) + " " + " ".join(_f(x) for x in tf))
    out.append(f"forces {len(model['forces'])}")
    for e, xi, y, z, dist, v in model["forces"]:
        out.append(f"force {e} {_f(xi)} {_f(y)} {_f(z)} {dist} " + " ".join(_f(x) for x in v))
    out.append(f"moments {len(model['moments'])}")
    for e, xi, v in model["moments"]:
        out.append(f"moment {e} {_f(xi)} " + " ".join(_f(x) for x in v))
    g = model["gravity"]
    out.append("gravity 0" if g is None else "gravity 1 " + " ".join(_f(x) for x in g))
    out.append(f"sensors {len(model['sensors'])}")
    for n, e, xi in model["sensors"]:
        out.append(f"sensor {n} {e} {_f(xi)}")
    out.append("end")
    Path(path).write_text("\n".join(out) + "\n", encoding="utf-8")
