"""Analysis options ([static], [dynamic], [modal], [output]) with their
defaults and ranges, initial velocities and sensors."""
import math

import gen.scene_keys as K
from gen.scene.mesh import locate, parse_point
from gen.scene.values import (_cross, _dot, _sub, check_keys, get_array_of_tables, get_bool, get_int, get_name,
                              get_number, get_str, get_table, get_vec3)

# ParaView frames of a dynamic run by default (every ceil(output steps / this)-th
# output step, and the last): enough to play the motion, few enough that writing
# them stays a small part of the run (the speed issue's output target).
DYNAMIC_FRAMES = 50

STATIC_DEFAULTS = {"load_steps": 1, "max_iterations": 25, "max_cutbacks": 12,
                   "rtol": 1e-8, "utol": 1e-10, "cycles": 0, "predictor": "secant", "stability": True,
                   "eigenvalues": False, "stable_path": False, "step_control": "adaptive", "method": "load_control",
                   "arc_constraint": "cylindrical", "target_load_factor": 1.0, "max_steps": 1000,
                   "max_displacement": 0.0, "arc_iterations": 5, "branch_switch": False}
DYNAMIC_DEFAULTS = {"rho_inf": 0.8, "tol": 0.0, "max_iterations": 25, "max_cutbacks": 12,
                    "output_every": 1, "rayleigh_alpha": 0.0, "rayleigh_beta": 0.0,
                    "rtol": 1e-8, "utol": 1e-8, "jacobian": "reuse"}


def continuation_options(ctx, st, stat):
    """The arc-length keys of [static] (checked also when load control ignores them)."""
    d = STATIC_DEFAULTS
    c = {"method": get_str(ctx, st, "method", "static", default=d["method"], choices=("load_control", "arc_length")),
         "arc_constraint": get_str(ctx, st, "arc_constraint", "static", default=d["arc_constraint"],
                                   choices=("cylindrical", "spherical")),
         "target_load_factor": get_number(ctx, st, "target_load_factor", "static", default=d["target_load_factor"],
                                          positive=True),
         "max_steps": get_int(ctx, st, "max_steps", "static", default=d["max_steps"], lo=1, hi=10**7),
         "max_displacement": get_number(ctx, st, "max_displacement", "static", default=d["max_displacement"],
                                        nonneg=True),
         "arc_iterations": get_int(ctx, st, "arc_iterations", "static", default=d["arc_iterations"], lo=1,
                                   hi=stat["max_iterations"]),
         "branch_switch": get_bool(ctx, st, "branch_switch", "static", d["branch_switch"])}
    if c["method"] == "arc_length":
        if stat["cycles"]:
            ctx.fail("static.cycles", f"expected 0 with method = \"arc_length\" (the path is followed, not "
                                      f"cycled), found {stat['cycles']!r}")
        if c["branch_switch"] and not stat["stability"]:
            ctx.fail("static.branch_switch", "expected static.stability = true (the switch follows the null vector "
                                             "of the stability check)")
        if stat["stable_path"]:
            ctx.fail("static.stable_path", "expected false with method = \"arc_length\" (arc-length follows "
                                           "the path through limit points; stable_path is for load control)")
    else:
        for k in ("arc_constraint", "target_load_factor", "max_steps", "max_displacement", "arc_iterations",
                  "branch_switch"):
            if k in st:
                ctx.fail("static." + k, 'expected only with method = "arc_length" (load control ignores it)')
    return c


def options(ctx, doc, analysis):
    """(static, dynamic, modal, vtk_every) options."""
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
        "eigenvalues": get_bool(ctx, st, "eigenvalues", "static", STATIC_DEFAULTS["eigenvalues"]),
        "stable_path": get_bool(ctx, st, "stable_path", "static", STATIC_DEFAULTS["stable_path"]),
        "step_control": get_str(ctx, st, "step_control", "static", default=STATIC_DEFAULTS["step_control"],
                                choices=("adaptive", "fixed")),
    }
    stat.update(continuation_options(ctx, st, stat))
    if stat["branch_switch"]:
        stat["eigenvalues"] = True     # the switch follows the eigenvector of the eigenvalue nearest zero
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
    dyn["jacobian"] = get_str(ctx, dt, "jacobian", "dynamic", default=DYNAMIC_DEFAULTS["jacobian"],
                              choices=("reuse", "every_iteration"))
    dyn["output_every"] = get_int(ctx, dt, "output_every", "dynamic", default=1, lo=1, hi=10**9)
    if analysis == "dynamic" and dyn["t_end"] / dyn["dt"] > 1e8:
        ctx.fail("dynamic.dt", f"t_end / dt = {dyn['t_end'] / dyn['dt']:.3g} steps: expected at most 1e8")

    ot = get_table(ctx, doc, "output")
    check_keys(ctx, ot, set(K.OUTPUT), "output")
    if analysis == "dynamic":
        n_out = dyn["t_end"] / (dyn["dt"] * dyn["output_every"])
        default_vtk = max(1, math.ceil(n_out / DYNAMIC_FRAMES))
    else:
        default_vtk = 1
    vtk_every = get_int(ctx, ot, "vtk_every", "output", default=default_vtk, lo=0, hi=10**9)

    mt = get_table(ctx, doc, "modal")
    check_keys(ctx, mt, set(K.MODAL), "modal")
    modal = {"modes": get_int(ctx, mt, "modes", "modal", default=10, lo=1, hi=100000),
             "about": 1 if get_str(ctx, mt, "about", "modal", default="reference",
                                   choices=("reference", "static")) == "static" else 0}

    return stat, dyn, modal, vtk_every


def initial_velocities(ctx, doc, mesh):
    """Initial velocities: rigid translation + rotation, per beam or for all."""
    beams, nodes, dof_of_node, q0, ndof = mesh.beams, mesh.nodes, mesh.dof_of_node, mesh.q0, mesh.ndof
    qd0 = [0.0] * ndof
    for ii, iv in enumerate(get_array_of_tables(ctx, doc, "initial_velocity")):
        where = f"initial_velocity[{ii}]"
        check_keys(ctx, iv, set(K.INITIAL_VELOCITY), where)
        v = get_vec3(ctx, iv, "velocity", where, default=[0.0, 0.0, 0.0])
        w = get_vec3(ctx, iv, "angular_velocity", where, default=[0.0, 0.0, 0.0])
        c = get_vec3(ctx, iv, "center", where, default=[0.0, 0.0, 0.0])
        if "body" in iv:
            if "beam" in iv:
                ctx.fail(f"{where}.body", "give either beam or body, not both")
            bn = get_str(ctx, iv, "body", where)
            if bn not in mesh.bodies:
                ctx.fail(f"{where}.body", f"no body named {bn!r} (bodies: {', '.join(mesh.bodies) or 'none'})")
            gids = [mesh.bodies[bn]["gid"]]
        elif "beam" in iv:
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

    return qd0


def sensors(ctx, doc, beams, bodies=None):
    """[(name, element, xi)] of the [[sensor]] tables (a body: its centre of mass, xi = 1/2)."""
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
        if bodies and isinstance(sd["at"], str) and sd["at"] in bodies:
            sensors.append((sn, bodies[sd["at"]]["elem"], 0.5))
            continue
        beam, s = parse_point(ctx, sd["at"], f"sensor.{sn}.at", beams)
        e, xi = locate(beam, s)
        sensors.append((sn, e, xi))

    return sensors
