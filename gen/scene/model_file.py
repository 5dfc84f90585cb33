"""The model file the C solver reads (runtime/model.c)."""
from pathlib import Path

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
