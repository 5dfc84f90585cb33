"""Reading and checking scene values: one error line naming the file, the key
and what was expected (SceneError)."""
import math

_NAME_FIRST = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_")
_NAME_REST = _NAME_FIRST | frozenset(".-")


class _NameRule:
    """Names of scenes, beams, materials, ...: 1 to 63 of letters, digits, '_', '.',
    '-', not starting with '.' or '-' (the regular expression
    ^[A-Za-z0-9_][A-Za-z0-9_.-]{0,62}$, checked without importing re)."""

    @staticmethod
    def match(s):
        return (isinstance(s, str) and 0 < len(s) <= 63 and s[0] in _NAME_FIRST
                and all(c in _NAME_REST for c in s))


NAME_RE = _NameRule()


def plain_name(s):
    """A joint's or an actuator's name: 1 to 63 letters, digits, '_', '.' or '-'
    (any of them first; the regular expression [A-Za-z0-9_.-]{1,63})."""
    return 0 < len(s) <= 63 and all(c in _NAME_REST for c in s)


class SceneError(Exception):
    pass


class Ctx:
    """Error reporting with the file name; base: the directory of the scene's
    relative data paths (default the scene file's; a scene given as a dict to
    the Python API, whose label is "<dict scene NAME>", has none)."""

    def __init__(self, path, base=None):
        self.path = str(path)
        self.base = base
        self.inputs = []        # data files the scene reads (paths from CSV files)

    def fail(self, key, msg):
        raise SceneError(f"error: {self.path}: {key}: {msg}")

    def data_path(self, key, fname):
        """The path of a data file named in the scene (key: where)."""
        from pathlib import Path           # only for data files
        p = Path(fname)
        if p.is_absolute():
            return p
        if self.base is not None:
            return Path(self.base) / p
        if self.path.startswith("<"):
            self.fail(key, f"the relative path {fname!r} in a scene given as a dict has no directory to start "
                           "from: give an absolute path, or the directory as Scene(..., base=DIR)")
        return Path(self.path).resolve().parent / p


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
