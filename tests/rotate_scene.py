"""Rigidly rotated copies of scene files (tests of rotation invariance).

rotated(path, R) returns the scene's TOML text with every point, direction and
vector value (beam ends, `up`, arc centre and axis, joint axes, loads, gravity,
initial velocities and their centre) turned by the rotation matrix R about the
origin; everything else is kept."""
import math
import tomllib

VECTOR_KEYS = {
    "beam": ("start", "end", "up", "arc_center", "arc_axis"),
    "constraint": ("axis",),
    "load": ("value",),
    "initial_velocity": ("velocity", "angular_velocity", "center"),
}


def rotation(axis, angle):
    """Rotation matrix about `axis` by `angle` (rad), Rodrigues' formula."""
    n = math.sqrt(sum(a * a for a in axis))
    k = [a / n for a in axis]
    c, s = math.cos(angle), math.sin(angle)
    K = [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]]
    return [[(1.0 if i == j else 0.0) + s * K[i][j] + (1 - c) * sum(K[i][m] * K[m][j] for m in range(3))
             for j in range(3)] for i in range(3)]


def apply(R, v):
    return [sum(R[i][j] * v[j] for j in range(3)) for i in range(3)]


def _value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    raise TypeError(type(v))


def dumps(doc):
    """A TOML text for a scene document (tables of scalars and arrays, arrays of tables)."""
    out = []
    for key, val in doc.items():
        if isinstance(val, dict) and all(isinstance(x, dict) for x in val.values()) and val:
            for sub, tbl in val.items():
                out.append(f"[{key}.{sub}]")
                out += [f"{k} = {_value(v)}" for k, v in tbl.items()]
                out.append("")
        elif isinstance(val, dict):
            out.append(f"[{key}]")
            out += [f"{k} = {_value(v)}" for k, v in val.items()]
            out.append("")
        elif isinstance(val, list) and val and all(isinstance(x, dict) for x in val):
            for tbl in val:
                out.append(f"[[{key}]]")
                out += [f"{k} = {_value(v)}" for k, v in tbl.items()]
                out.append("")
        else:
            out.insert(0, f"{key} = {_value(val)}")
    return "\n".join(out) + "\n"


def rotated(path, R):
    with open(path, "rb") as fh:
        doc = tomllib.load(fh)
    for table, keys in VECTOR_KEYS.items():
        for entry in doc.get(table, []):
            if table == "beam" and "up" not in entry and "arc_axis" not in entry:
                entry["up"] = [0.0, 0.0, 1.0]        # the default, turned with the rest
            for k in keys:
                if k in entry:
                    entry[k] = apply(R, entry[k])
    return dumps(doc)
