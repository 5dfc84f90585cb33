"""What the Python side knows of runtime/bk_kernel.h, read from the header itself
(no sympy: the scene compiler may import it): the kernel version, the slots of
geom[], the section shapes, the field roles and the element capabilities.

The header is the one definition; this module only parses it, so a slot, role
or capability added there is known here without a second list.
"""
import os

from gen.derived import derived

HEADER = os.path.join(os.path.dirname(os.path.dirname(os.path.realpath(__file__))), "runtime", "bk_kernel.h")

# Nodal vector names of the generator (gen/element.py, gen/rod.py) -> field role.
_ROLE_OF_NAME = {"r": "BK_FIELD_POSITION", "r_x": "BK_FIELD_R_X", "r_y": "BK_FIELD_R_Y",
                 "r_z": "BK_FIELD_R_Z", "r_yy": "BK_FIELD_R_YY", "r_yz": "BK_FIELD_R_YZ",
                 "r_zz": "BK_FIELD_R_ZZ", "p": "BK_FIELD_QUATERNION", "lambda": "BK_FIELD_MULTIPLIER"}


def _parse(data):
    """{"define:NAME": int} of every `#define NAME <integer>` and
    {"enum:NAME": ((constant, value), ...)} of every `enum NAME { ... }`, values
    as C gives them (explicit, shifted, or previous + 1)."""
    import re
    text = data.decode("utf-8")
    out = {f"define:{m.group(1)}": int(m.group(2))
           for m in re.finditer(r"^#define\s+(\w+)\s+(\d+)\s*$", text, re.M)}
    src = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    for m in re.finditer(r"enum\s+(\w+)\s*\{(.*?)\}", src, re.S):
        items, nxt = [], 0
        for item in m.group(2).split(","):
            item = item.strip()
            if not item:
                continue
            if "=" in item:
                k, v = (x.strip() for x in item.split("=", 1))
                sh = re.fullmatch(r"(\d+)\s*<<\s*(\d+)", v)
                val = int(sh.group(1)) << int(sh.group(2)) if sh else int(v)
            else:
                k, val = item, nxt
            items.append((k, val))
            nxt = val + 1
        out.setdefault(f"enum:{m.group(1)}", tuple(items))
    return out


_PARSED = []                           # the header's definitions, once per process


def _parsed():
    """What _parse finds in the header, through gen/derived.py (a run does not
    parse an unchanged header again).  Memoized by hand: functools (lru_cache)
    would import collections, 4 ms of a run that only changes numbers."""
    if not _PARSED:
        with open(HEADER, "rb") as fh:
            _PARSED.append(derived("contract", fh.read(), _parse))
    return _PARSED[0]


def _define(name):
    try:
        return _parsed()[f"define:{name}"]
    except KeyError:
        raise RuntimeError(f"{HEADER}: no '#define {name} <n>'") from None


def version():
    """BK_KERNEL_VERSION of the header."""
    return _define("BK_KERNEL_VERSION")


def lanes():
    """BK_LANES of the header: elements per call of a lane kernel."""
    return _define("BK_LANES")


def _enum(name):
    """[(constant, value)] of `enum name { ... }` or `typedef enum name { ... }`."""
    try:
        return _parsed()[f"enum:{name}"]
    except KeyError:
        raise RuntimeError(f"{HEADER}: no enum {name}") from None


def geom_slots():
    """Slot names of geom[] in order, without the prefix: ("L", "B", "H", "A", ...)."""
    slots = [(k, v) for k, v in _enum("bk_geom_slot") if k != "BK_NGEOM"]
    names = [k[len("BK_GEOM_"):] for k, v in sorted(slots, key=lambda kv: kv[1])]
    assert [v for _, v in sorted(slots, key=lambda kv: kv[1])] == list(range(len(names))), slots
    return tuple(names)


def ngeom():
    return dict(_enum("bk_geom_slot"))["BK_NGEOM"]


def geom_slot(name):
    """Index of a geom[] slot ("L", "B", ...)."""
    return geom_slots().index(name)


def geom_vector(**values):
    """geom[] in slot order from values named by slot ("L", "B", ...; missing ones 0)."""
    slots = geom_slots()
    unknown = set(values) - set(slots)
    if unknown:
        raise KeyError(f"no geom[] slot {sorted(unknown)} in {HEADER}")
    return [float(values.get(k, 0.0)) for k in slots]


def section_shapes():
    """{"rectangle": 1, "circle": 2, ...}."""
    return {k[len("BK_SECTION_"):].lower(): v for k, v in _enum("bk_section_shape")}


def field_roles():
    """{role constant: value}."""
    return dict(_enum("bk_field_role"))


def capabilities():
    """{capability constant: bit}."""
    return dict(_enum("bk_element_cap"))


def role_of(field_name):
    """Role constant of a field name of the generator ("r", "r_x", "p", "lambda", ...)."""
    try:
        role = _ROLE_OF_NAME[field_name]
    except KeyError:
        raise ValueError(f"field {field_name!r} has no role in {os.path.basename(HEADER)} (bk_field_role): "
                         "add one there and here") from None
    if role not in field_roles():
        raise RuntimeError(f"{HEADER}: bk_field_role lacks {role}")
    return role


def max_sizes():
    """(BK_MAX_ELEMENT_DOF, BK_MAX_SHAPE)."""
    return _define("BK_MAX_ELEMENT_DOF"), _define("BK_MAX_SHAPE")
