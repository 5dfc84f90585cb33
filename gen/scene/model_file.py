"""The model file the C solver reads (runtime/model/model.c)."""

from gen import options_schema as S


def _f(x):
    return repr(float(x))


# Model file format: versioned; the option records are named fields `key=value`
# in the order of the options schema (gen/options_schema.py), which
# runtime/model/options.c reads by its generated descriptor table (a model file
# of another version, or with a field renamed, is refused naming the record and
# field).  Choices are written by name, booleans as 0 or 1.
VERSION = S.MODEL_VERSION
RECORDS = S.records()


def _value(v):
    if isinstance(v, bool):
        return str(int(v))
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return _f(v)
    return str(v)


def _line(text):
    """text on one line: backslash and newline escaped (runtime/model/extras.c reads it back)."""
    return text.replace("\\", "\\\\").replace("\n", "\\n")


def _option_records(model):
    """The option records, each `record key=value ...`, from the model's values
    (scene and output keys at its top level, the others in model[table])."""
    out = []
    for rec in S.RECORD_ORDER:
        fields = []
        for o in S.record_fields(rec):
            values = model if o.table in ("scene", "output") else model[o.table]
            rule = S.RECORD_VALUE_RULES.get(o.name)
            if rule:
                v = rule(values)
            elif o.key not in values and not callable(o.default) and o.default is not S.REQUIRED:
                v = o.default          # a record another analysis writes in part (buckling: modal)
            else:
                v = values[o.key]
            if o.type == "float":
                v = float(v)
            elif o.type == "bool":
                v = bool(v)
            fields.append(f"{o.key}={_value(v)}")
        out.append(rec + " " + " ".join(fields))
    return out


def write_model(model, path):
    """Write the model file read by runtime/model/model.c."""
    out = [f"beamkit-model {VERSION}"] + _option_records(model)
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
    for params, rho, visc, names in model["mats"]:
        out.append(f"mat rho={_f(rho)} params={len(params)} " + " ".join(f"{n}={_f(v)}" for n, v in zip(names, params))
                   + f" visc={len(visc)} " + " ".join(_f(v) for v in visc))
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
    nl = model.get("nlcons", [])
    out.append(f"nlcons {len(nl)}")
    for jtype, dofs, x0, prm, drive in nl:
        out.append(f"nlcon {jtype} " + " ".join(map(str, dofs)) + " " + " ".join(_f(x) for x in x0)
                   + " " + " ".join(_f(x) for x in prm) + " " + " ".join(_f(x) for x in drive[:4])
                   + f" {drive[4]}")
    out.append(f"forces {len(model['forces'])}")
    for e, xi, y, z, dist, v, amp, fol in model["forces"]:
        out.append(f"force {e} {_f(xi)} {_f(y)} {_f(z)} {dist} " + " ".join(_f(x) for x in v) + f" {amp} {fol}")
    out.append(f"moments {len(model['moments'])}")
    for e, xi, v, amp, fol in model["moments"]:
        out.append(f"moment {e} {_f(xi)} " + " ".join(_f(x) for x in v) + f" {amp} {fol}")
    g = model["gravity"]
    out.append("gravity 0" if g is None else "gravity 1 " + " ".join(_f(x) for x in g[0]) + f" {g[1]}")
    out.append(f"sensors {len(model['sensors'])}")
    for n, e, xi, off in model["sensors"]:
        out.append(f"sensor {n} {e} {_f(xi)} " + " ".join(_f(x) for x in off))
    out.append(f"amplitudes {len(model['amplitudes'])}")
    for atype, params in model["amplitudes"]:
        out.append(f"amplitude {atype} {len(params)} " + " ".join(_f(x) for x in params))
    out.append(f"dloads {len(model['dloads'])}")
    for e, x0, x1, fol, amp, v in model["dloads"]:
        out.append(f"dload {e} {_f(x0)} {_f(x1)} {fol} {amp} " + " ".join(_f(x) for x in v))
    out.append(f"tendons {len(model['tendons'])}")
    for amp, T, pieces in model["tendons"]:
        out.append(f"tendon {amp} {_f(T)} {len(pieces)}")
        out += [f"piece {e} {_f(x0)} {_f(x1)} {_f(dy)} {_f(dz)}" for e, x0, x1, dy, dz in pieces]
    out.append(f"reactions {len(model['reactions'])}")
    for ci, ctype, at, e, xi, fixed, lins, side, nlcon, name, njoint in model["reactions"]:
        side = side or []
        out.append(f"reaction {ci} {ctype} {name} {at} {e} {_f(xi)} {len(fixed)} " + " ".join(map(str, fixed))
                   + f" {len(lins)} " + " ".join(map(str, lins)) + f" {len(side)} " + " ".join(map(str, side))
                   + f" {nlcon} {njoint}")
    out.append(f"sections {len(model['sections'])}")
    for bname, e, s0, s1, r, group in model["sections"]:
        out.append(f"section {bname} {e} {_f(s0)} {_f(s1)} {_f(r)} {group}")
    from gen.scene.point_masses import point_mass_records
    out += point_mass_records(model.get("point_masses", []), _f)
    records = model.get("records", [])       # the interaction modules' (gen/scene/interactions.py)
    out.append(f"records {len(records)}")
    for name, lines in records:
        out += [f"record {name}"] + lines + ["end_record"]
    warnings = model.get("warnings", [])     # the scene reader's: the solver lists them first in summary.json
    out.append(f"warnings {len(warnings)}")
    out += ["warning " + _line(w) for w in warnings]
    out.append("end")
    with open(path, "w", encoding="utf-8") as fh:
        fh.write("\n".join(out) + "\n")
