"""Read a beamkit scene for a solid (CalculiX) model and refuse what the deck
cannot represent.

The TOML reading, the `--set` override logic, the error format and the small
typed getters are gen/scene/'s (which imports no sympy); the material laws are
read here from the scene keys directly (gen/materials/ imports sympy).  Every
refusal is one line `error: FILE: KEY: ...` raised as SceneError.
"""
import math
from dataclasses import dataclass, field
from pathlib import Path

from gen.scene import (ROOT, Ctx, SceneError, apply_overrides, check_keys, get_array_of_tables,  # noqa: F401
                       get_int, get_number, get_str, get_table, get_vec3, read_toml, section_axes)

MODELS = ROOT / "models"

# Scene keys of the solver's numerics (Newton tolerances, step control, output):
# they do not change the mechanical problem, so the deck ignores them.
STATIC_NUMERICS = {"max_iterations", "max_cutbacks", "rtol", "utol", "predictor", "stability", "stable_path"}
DYNAMIC_NUMERICS = {"tol", "dt_min", "max_iterations", "max_cutbacks", "output_every", "rtol", "utol"}

# law -> accepted key sets (besides law, rho), as in gen/materials/*.py INPUTS
LAW_KEYS = {
    "svk": (("E", "nu"), ("lambda", "mu")),
    "neo_hookean": (("E", "nu"), ("lambda", "mu")),
    "mooney_rivlin": (("c10", "c01", "kappa"),),
    "arruda_boyce": (("mu", "lambda_m", "kappa"),),
}


@dataclass
class Material:
    law: str
    rho: float
    p: dict                       # svk, neo_hookean: lambda, mu, E, nu; mooney_rivlin: c10, c01, kappa;
    #                               arruda_boyce: mu, lambda_m, kappa

    def small_strain(self):
        """(E, nu) of the small-strain limit, as the material table of docs/explanation/elements.md."""
        p = self.p
        if self.law in ("svk", "neo_hookean"):
            return p["E"], p["nu"]
        if self.law == "mooney_rivlin":
            mu0, k = 2 * (p["c10"] + p["c01"]), p["kappa"]
        else:
            lm = p["lambda_m"]
            mu0 = p["mu"] * (1 + 3 / (5 * lm**2) + 99 / (175 * lm**4) + 513 / (875 * lm**6)
                             + 42039 / (67375 * lm**8))
            k = p["kappa"]
        return 9 * k * mu0 / (3 * k + mu0), (3 * k - 2 * mu0) / (2 * (3 * k + mu0))


@dataclass
class Problem:
    path: str
    name: str
    analysis: str                 # static | dynamic
    start: list
    t: list                       # unit axis
    d1: list                      # section's first axis (b)
    d2: list                      # section's second axis (h, "up")
    length: float
    b: float
    h: float
    material: Material
    clamps: list                  # [(end, mode)]: end 'start' | 'end', mode 'rigid' | 'free'
    forces: dict                  # end -> summed force vector (N), a uniform traction over that face
    gravity: list = None          # m/s^2 or None
    load_steps: int = 10
    t_end: float = 0.0
    dt: float = 0.0
    rho_inf: float = 0.8
    rayleigh_alpha: float = 0.0
    rayleigh_beta: float = 0.0
    velocity: list = field(default_factory=lambda: [0.0, 0.0, 0.0])
    angular_velocity: list = field(default_factory=lambda: [0.0, 0.0, 0.0])
    center: list = field(default_factory=lambda: [0.0, 0.0, 0.0])
    sensors: list = field(default_factory=list)    # [(name, arc length s)]
    layers: list = None           # beam.layers: [(Material, z0, z1)], fractions of h from the -d2 face; None: one
    arc: object = None            # a circular arc (gen.scene.geometry.ArcGeometry) instead of the straight axis

    def point(self, s, y=0.0, z=0.0):
        """Reference position of the section point (y along d1, z along d2) at arc length s
        (on an arc: the section frame carried along it, as the scene compiler does)."""
        if self.arc is not None:
            X, _, d1, d2 = self.arc.at(s)
            return [X[i] + y * d1[i] + z * d2[i] for i in range(3)]
        return [self.start[i] + s * self.t[i] + y * self.d1[i] + z * self.d2[i] for i in range(3)]


def resolve(scene):
    """A scene name in models/ or a path to a .toml file."""
    p = Path(scene)
    if p.suffix == ".toml" or p.exists():
        return p
    return MODELS / f"{scene}.toml"


def _material(ctx, mname, mt):
    where = f"material.{mname}"
    if not isinstance(mt, dict):
        ctx.fail(where, "expected a table")
    law = get_str(ctx, mt, "law", where)
    if law not in LAW_KEYS:
        ctx.fail(f"{where}.law", f"the CalculiX deck takes the continuum laws {', '.join(LAW_KEYS)}; found {law!r}")
    rho = get_number(ctx, mt, "rho", where, positive=True)
    if float(mt.get("kelvin_voigt", 0.0)) != 0.0:
        ctx.fail(f"{where}.kelvin_voigt", "CalculiX has no Kelvin-Voigt viscosity for hyperelastic solids; "
                 "compare with stiffness-proportional Rayleigh damping instead "
                 f"(--set {where}.kelvin_voigt=0 --set dynamic.rayleigh_beta=TAU in both codes)")
    given = sorted(k for k in mt if k not in ("law", "rho", "kelvin_voigt"))
    for keys in LAW_KEYS[law]:
        if sorted(keys) == given:
            v = {k: get_number(ctx, mt, k, where) for k in keys}
            break
    else:
        opts = "; ".join(" + ".join(k) for k in LAW_KEYS[law])
        ctx.fail(where, f"law {law!r} needs rho and one of: {opts}; found {', '.join(given) or 'none'}")
    if law in ("svk", "neo_hookean"):
        if "E" in v:
            E, nu = v["E"], v["nu"]
            if not (E > 0 and -1 < nu < 0.5):
                ctx.fail(where, f"expected E > 0 and -1 < nu < 0.5, found E = {E!r}, nu = {nu!r}")
            v["lambda"], v["mu"] = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
        else:
            lam, mu = v["lambda"], v["mu"]
            if not (mu > 0 and 3 * lam + 2 * mu > 0):
                ctx.fail(where, f"expected mu > 0 and a positive bulk modulus, found lambda = {lam!r}, mu = {mu!r}")
            v["E"], v["nu"] = mu * (3 * lam + 2 * mu) / (lam + mu), lam / (2 * (lam + mu))
    elif law == "mooney_rivlin":
        if not (v["kappa"] > 0 and v["c10"] + v["c01"] > 0):
            ctx.fail(where, "expected kappa > 0 and c10 + c01 > 0")
    else:
        if not (v["mu"] > 0 and v["kappa"] > 0 and v["lambda_m"] > 1):
            ctx.fail(where, "expected mu > 0, kappa > 0 and lambda_m > 1")
    return Material(law, rho, v)


def _layers(ctx, bt, where, mats, default, h):
    """beam.layers as [(Material, z0, z1)] (fractions of h from the -d2 face), or
    None; the keys are checked as the scene compiler does (gen/scene/layers.py),
    which refuses anything else before a deck is written."""
    if "layers" not in bt:
        return None
    v = bt["layers"]
    if not isinstance(v, list) or not v or not all(isinstance(x, dict) for x in v):
        ctx.fail(f"{where}.layers", "expected an array of inline tables {material = NAME, thickness = m}")
    rows = []
    for i, lt in enumerate(v):
        w = f"{where}.layers[{i}]"
        check_keys(ctx, lt, {"material", "thickness"}, w)
        mname = get_str(ctx, lt, "material", w, default=default)
        if mname not in mats:
            ctx.fail(f"{w}.material", f"no [material.{mname}] in the scene")
        t = get_number(ctx, lt, "thickness", w, positive=True) if "thickness" in lt else None
        rows.append((_material(ctx, mname, mats[mname]), t))
    fixed = sum(t for _, t in rows if t is not None)
    if sum(t is None for _, t in rows) > 1 or fixed > h * (1 + 1e-9):
        ctx.fail(f"{where}.layers", "expected at most one layer without a thickness, the others within the height")
    out, z = [], 0.0
    for m, t in rows:
        dz = (h - fixed) / h if t is None else t / h
        out.append((m, z, min(1.0, z + dz)))
        z += dz
    return out


def _end_of(ctx, spec, key, bname, length):
    """'B:start' | 'B:end' | 'B:<arc length>' -> arc length s."""
    if not isinstance(spec, str) or ":" not in spec:
        ctx.fail(key, f"expected a point like '{bname}:end', found {spec!r}")
    b, where = spec.rsplit(":", 1)
    if b != bname:
        ctx.fail(key, f"no beam named {b!r} (beams: {bname})")
    if where == "start":
        return 0.0
    if where == "end":
        return length
    try:
        s = float(where)
    except ValueError:
        ctx.fail(key, f"expected start, end or an arc length in m after ':', found {where!r}")
    if not (math.isfinite(s) and 0 <= s <= length * (1 + 1e-12)):
        ctx.fail(key, f"arc length {where} outside beam {bname!r} (0 to {length:.6g} m)")
    return min(s, length)


def read_scene(scene, sets=()):
    """Problem of a scene (name or path) with `--set` overrides, or SceneError."""
    path = resolve(scene)
    ctx = Ctx(path)
    doc = read_toml(path)
    if sets:
        apply_overrides(doc, list(sets), path)
    check_keys(ctx, doc, {"scene", "material", "section", "beam", "constraint", "load", "static",
                          "dynamic", "modal", "initial_velocity", "sensor", "output"}, "(top level)")
    sc = get_table(ctx, doc, "scene")
    analysis = get_str(ctx, sc, "analysis", "scene", default="static")
    if analysis not in ("static", "dynamic"):
        ctx.fail("scene.analysis", f"the CalculiX deck does static and dynamic analyses; found {analysis!r}")
    name = sc["name"] if isinstance(sc.get("name"), str) else path.stem

    beams = get_array_of_tables(ctx, doc, "beam")
    if len(beams) != 1:
        ctx.fail("beam", f"the CalculiX deck takes exactly one straight beam; found {len(beams)}")
    bt = beams[0]
    bname = bt.get("name") if isinstance(bt.get("name"), str) else "beam"
    where = f"beam.{bname}"
    for k in ("path", "section_end", "sections"):
        if k in bt:
            ctx.fail(f"{where}.{k}", "the CalculiX deck takes straight beams and circular arcs of one section")
    start = get_vec3(ctx, bt, "start", where)
    arc = None
    if any(k in bt for k in ("arc_center", "arc_axis", "arc_angle")):
        from gen.scene.geometry import arc_geometry
        if "end" in bt:
            ctx.fail(f"{where}.end", "give either end (a straight beam) or an arc")
        arc = arc_geometry(ctx, bt, where, start)
        length = arc.length
        _, t, d1, d2 = arc.at(0.0)
    else:
        end = get_vec3(ctx, bt, "end", where)
        axis = [end[i] - start[i] for i in range(3)]
        length = math.sqrt(sum(a * a for a in axis))
        if not length > 0:
            ctx.fail(f"{where}.end", "expected an end point different from start")
        t = [a / length for a in axis]
        d1, d2 = section_axes(ctx, bt, where, t, [0.0, 0.0, 1.0])

    secs = get_table(ctx, doc, "section")
    sname = get_str(ctx, bt, "section", where)
    if sname not in secs or not isinstance(secs[sname], dict):
        ctx.fail(f"{where}.section", f"no [section.{sname}] in the scene")
    st = secs[sname]
    if get_str(ctx, st, "shape", f"section.{sname}") != "rectangle":
        ctx.fail(f"section.{sname}.shape", f"the CalculiX deck takes rectangular sections; found {st['shape']!r}")
    b = get_number(ctx, st, "b", f"section.{sname}", positive=True)
    h = get_number(ctx, st, "h", f"section.{sname}", positive=True)

    mats = get_table(ctx, doc, "material")
    mname = get_str(ctx, bt, "material", where)
    if mname not in mats:
        ctx.fail(f"{where}.material", f"no [material.{mname}] in the scene")
    material = _material(ctx, mname, mats[mname])
    layers = _layers(ctx, bt, where, mats, mname, h)

    clamps = []
    for ci, ct in enumerate(get_array_of_tables(ctx, doc, "constraint")):
        cw = f"constraint[{ci}]"
        ctype = get_str(ctx, ct, "type", cw)
        if ctype != "clamp":
            ctx.fail(f"{cw}.type", f"the CalculiX deck represents clamps only; found {ctype!r}")
        check_keys(ctx, ct, {"type", "a", "cross_section"}, cw)
        s = _end_of(ctx, ct.get("a"), f"{cw}.a", bname, length)
        if s not in (0.0, length):
            ctx.fail(f"{cw}.a", f"the CalculiX deck clamps an end face ({bname}:start or {bname}:end); found {ct['a']!r}")
        mode = get_str(ctx, ct, "cross_section", cw, default="rigid")
        if mode not in ("rigid", "free"):
            ctx.fail(f"{cw}.cross_section", f"expected rigid or free, found {mode!r}")
        side = "start" if s == 0.0 else "end"
        if any(c[0] == side for c in clamps):
            ctx.fail(f"{cw}.a", f"the {side} face is clamped twice")
        clamps.append((side, mode))
    if not clamps:
        ctx.fail("constraint", "the CalculiX deck needs a clamp (a free solid has rigid-body modes)")

    forces, gravity = {}, None
    for li, lt in enumerate(get_array_of_tables(ctx, doc, "load")):
        lw = f"load[{li}]"
        ltype = get_str(ctx, lt, "type", lw)
        if ltype == "force":
            check_keys(ctx, lt, {"type", "at", "value", "distribution"}, lw)
            s = _end_of(ctx, lt.get("at"), f"{lw}.at", bname, length)
            if s not in (0.0, length):
                ctx.fail(f"{lw}.at", "the CalculiX deck takes forces on an end face (spread as a uniform "
                         f"traction); found {lt['at']!r}")
            v = get_vec3(ctx, lt, "value", lw)
            side = "start" if s == 0.0 else "end"
            old = forces.get(side, [0.0, 0.0, 0.0])
            forces[side] = [old[i] + v[i] for i in range(3)]
        elif ltype == "gravity":
            check_keys(ctx, lt, {"type", "value"}, lw)
            if gravity is not None:
                ctx.fail(f"{lw}.type", "gravity given twice")
            gravity = get_vec3(ctx, lt, "value", lw)
        else:
            ctx.fail(f"{lw}.type", f"the CalculiX deck takes force and gravity loads; found {ltype!r}")
    for side in forces:
        if any(c[0] == side for c in clamps):
            ctx.fail("load", f"a force on the clamped {side} face does nothing")

    prob = Problem(str(path), name, analysis, start, t, d1, d2, length, b, h, material, clamps, forces, gravity,
                   layers=layers, arc=arc)
    if arc is not None and any(side == "end" and mode == "free" for side, mode in clamps):
        ctx.fail("constraint", "the CalculiX deck's free clamp of an arc is at its start (the section axes there)")

    stt = get_table(ctx, doc, "static")
    check_keys(ctx, stt, STATIC_NUMERICS | {"load_steps", "cycles"}, "static")
    if int(stt.get("cycles", 0)) != 0:
        ctx.fail("static.cycles", "the CalculiX deck does one loading (cycles = 0)")
    prob.load_steps = get_int(ctx, stt, "load_steps", "static", default=10, lo=1, hi=10**6)

    dyn = get_table(ctx, doc, "dynamic")
    check_keys(ctx, dyn, DYNAMIC_NUMERICS | {"t_end", "dt", "rho_inf", "rayleigh_alpha", "rayleigh_beta"}, "dynamic")
    if analysis == "dynamic":
        prob.t_end = get_number(ctx, dyn, "t_end", "dynamic", positive=True)
        prob.dt = get_number(ctx, dyn, "dt", "dynamic", positive=True)
        if prob.dt > prob.t_end:
            ctx.fail("dynamic.dt", f"expected a step no longer than t_end = {prob.t_end!r}")
        prob.rho_inf = get_number(ctx, dyn, "rho_inf", "dynamic", default=0.8)
        if not 0.5 <= prob.rho_inf <= 1.0:
            ctx.fail("dynamic.rho_inf", "CalculiX's HHT-alpha reaches spectral radii in [0.5, 1] "
                     f"(alpha in [-1/3, 0]); found {prob.rho_inf!r}")
        prob.rayleigh_alpha = get_number(ctx, dyn, "rayleigh_alpha", "dynamic", default=0.0, nonneg=True)
        prob.rayleigh_beta = get_number(ctx, dyn, "rayleigh_beta", "dynamic", default=0.0, nonneg=True)
        ivs = get_array_of_tables(ctx, doc, "initial_velocity")
        if len(ivs) > 1:
            ctx.fail("initial_velocity", "the CalculiX deck takes one rigid initial velocity field")
        for iv in ivs:
            check_keys(ctx, iv, {"beam", "velocity", "angular_velocity", "center"}, "initial_velocity[0]")
            prob.velocity = get_vec3(ctx, iv, "velocity", "initial_velocity[0]", default=[0.0, 0.0, 0.0])
            prob.angular_velocity = get_vec3(ctx, iv, "angular_velocity", "initial_velocity[0]",
                                             default=[0.0, 0.0, 0.0])
            prob.center = get_vec3(ctx, iv, "center", "initial_velocity[0]", default=[0.0, 0.0, 0.0])

    for si, sd in enumerate(get_array_of_tables(ctx, doc, "sensor")):
        sw = f"sensor[{si}]"
        check_keys(ctx, sd, {"name", "at"}, sw)
        sname_ = get_str(ctx, sd, "name", sw)
        prob.sensors.append((sname_, _end_of(ctx, sd.get("at"), f"sensor.{sname_}.at", bname, length)))
    if not prob.sensors:
        ctx.fail("sensor", "the CalculiX reference reports sensor displacements; the scene has no [[sensor]]")
    return prob
