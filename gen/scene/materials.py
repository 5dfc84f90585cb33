"""[material.NAME] and [section.NAME] tables: laws as data from the kernel index
(no sympy), small-strain moduli, element choices known to lock."""
import math

import gen.scene_keys as K
from gen.scene.values import _typename, check_keys, get_number, get_str, get_table

# Ranges of the material keys of every law (the law's own keys: its RANGES,
# in out/kernels/index.json): (test, expectation text).
KEY_RANGES = {
    "rho": (lambda v: v > 0, "a positive number (kg/m^3)"),
    "kelvin_voigt": (lambda v: v >= 0, "a retardation time >= 0 (s)"),
}


def law_range(lo, hi, unit):
    """(test, expectation text) of a law's range lo < v < hi (None: unbounded)."""
    def test(v, lo=lo, hi=hi):
        return (lo is None or v > lo) and (hi is None or v < hi)
    text = ("a number" if lo is None and hi is None else "a positive number" if lo == 0 and hi is None
            else f"a number > {lo:g}" if hi is None else f"a number < {hi:g}" if lo is None
            else f"a number in ({lo:g}, {hi:g})")
    return test, text + (f" ({unit})" if unit else "")


def _is_keyword(name):
    """keyword.iskeyword(name) (the printer writes lambda_ for lambda), without
    importing keyword: the first module of the standard library's folder a run
    imports lists that folder, 1 ms of every scene compile."""
    try:
        compile(name + " = 0", "<name>", "exec")
        return False
    except SyntaxError:
        return name.isidentifier()


def law_eval(exprs, names, values):
    """Values of the generated expressions of a law (out/kernels/index.json
    "materials": Python expressions written by gen/generate.py, math only) for
    the variables `names` = `values`."""
    env = {"math": math, "__builtins__": {}}
    for n, v in zip(names, values):
        env[n + "_" if _is_keyword(n) else n] = float(v)
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
    ranges = dict(KEY_RANGES)
    ranges.update({k: law_range(*r) for k, r in info.get("ranges", {}).items()})
    for k in ["rho"] + given + (["kelvin_voigt"] if "kelvin_voigt" in mt else []):
        if k in ranges:
            test, expect = ranges[k]
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
    # a resultant law given some of its stiffnesses: the rest are NaN, and an
    # element that uses one of them is refused where the material meets it
    # (gen/scene/mesh.py: the cable uses EA and EI only)
    if kind == "resultant" and inputs and "EA" in given and set(given) < set(inputs[0][0]):
        keys, exprs = inputs[0]
        if tuple(keys) == tuple(info["params"]) and all(mt[k] > 0 for k in given):
            vals = [float(mt[k]) if k in mt else math.nan for k in keys]
            return law, rho, (lambda sec, vals=vals: list(vals))
    known = {k for keys, _ in inputs for k in keys}
    for k in given:
        if k not in known:
            ctx.fail(f"{where}.{k}", f"unknown key for law {law!r}; expected law, rho and one of: {'; '.join(options)}")
    ctx.fail(where, f"law {law!r} needs rho and one of: {'; '.join(options)}; found {', '.join(given) or 'none'}")


# Element choices measured to lock (out/report/verification.md, docs/explanation/elements.md,
# "The elements"): (element, integrations, test on the small-strain nu, advice).
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


def sections(ctx, doc):
    """{name: (shape, b, h)} of the [section.NAME] tables (a circle as b = h = 2 r)."""
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

    return sections
