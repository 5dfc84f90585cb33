"""Scene files: reading the TOML, `--set` overrides, the kernel index."""
import os

from gen.derived import derived
from gen.scene.values import SceneError, _typename

# The repository and the kernel index as str (the run of a built scene imports
# no pathlib); ROOT and KERNEL_INDEX, as pathlib.Path, for the other modules.
ROOT_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
KERNEL_INDEX_FILE = os.path.join(ROOT_DIR, "out", "kernels", "index.json")


def __getattr__(name):
    if name in ("ROOT", "KERNEL_INDEX"):
        from pathlib import Path
        return Path(ROOT_DIR if name == "ROOT" else KERNEL_INDEX_FILE)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def apply_overrides(doc, sets, path, touched=None):
    """Apply KEY=VALUE overrides to the parsed TOML document: numbers, booleans,
    strings where the scene has a string, TOML arrays and inline tables; arrays of
    tables are addressed by an entry's `name` or its index.  touched (a list):
    gets (the --set string, the forms of its key the scene's messages may use:
    an array entry as NAME, N and [N]) for blame_set."""
    for item in sets:
        if "=" not in item:
            raise SceneError(f"error: --set {item}: expected KEY=VALUE")
        key, val = item.split("=", 1)
        parts = key.split(".")
        forms = [""]                                 # the key's forms so far
        try:
            digits = val.strip()
            digits = digits[1:] if digits[:1] in "+-" else digits
            num = int(val) if digits.isdigit() and digits.isascii() else float(val)
        except ValueError:
            num = None
        node = doc
        for depth, p in enumerate(parts[:-1]):
            if isinstance(node, dict):
                if p not in node and depth == 0:
                    from gen.options_schema import TABLES      # an options table the scene may leave out
                    if p in TABLES and p != "scene":
                        node[p] = {}
                if p not in node:
                    raise SceneError(f"error: {path}: --set {key}: no table '{'.'.join(parts[:depth + 1])}' in the scene")
                node = node[p]
                forms = [f"{f}.{p}" if f else p for f in forms]
            elif isinstance(node, list):
                match = [t for t in node if isinstance(t, dict) and t.get("name") == p]
                if not match and p.isdigit() and int(p) < len(node):
                    match = [node[int(p)]]
                if len(match) != 1:
                    have = [t["name"] if isinstance(t, dict) and isinstance(t.get("name"), str) else str(k)
                            for k, t in enumerate(node)]
                    raise SceneError(f"error: {path}: --set {key}: no entry named or numbered '{p}' in "
                                     f"'{'.'.join(parts[:depth])}' (it has: {', '.join(have) or 'none'})")
                i = next(k for k, t in enumerate(node) if t is match[0])
                names = {str(i)} | ({match[0]["name"]} if isinstance(match[0].get("name"), str) else set())
                forms = [g for f in forms for g in [f"{f}[{i}]"] + [f"{f}.{n}" for n in sorted(names)]]
                node = match[0]
        if touched is not None:
            touched.append((item, [f"{f}.{parts[-1]}" if f else parts[-1] for f in forms]
                            + ([f"{f}[{parts[-1]}]" for f in forms if f] if parts[-1].isdigit() else [])))
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
        if val.lstrip()[:1] in ("[", "{"):           # an array or an inline table, in TOML
            if old is not None and not isinstance(old, (list, dict)):
                raise SceneError(f"error: {path}: --set {key}: the scene's value is {_typename(old)}, "
                                 f"not an array or a table")
            node[parts[-1]] = _toml_value(key, val)
            continue
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


def blame_set(msg, path, touched):
    """A scene message "error: PATH: KEY...: ..." about a value a --set gave
    (touched: from apply_overrides) names the --set instead of the file,
    which does not hold that value; any other message is returned as it is."""
    head = f"error: {path}: "
    if not msg.startswith(head):
        return msg
    rest = msg[len(head):]
    for item, forms in reversed(touched):           # the last --set of a key wins
        for f in forms:
            if rest.startswith(f) and rest[len(f):len(f) + 1] in (":", ".", "[", " "):
                return f"error: --set {item}: {rest}"
    return msg


def _toml_value(key, val):
    """The value of `--set KEY=VAL` when VAL is a TOML array or inline table."""
    import tomllib
    try:
        return tomllib.loads("v = " + val)["v"]
    except tomllib.TOMLDecodeError as e:
        raise SceneError(f"error: --set {key}: expected a TOML array [..] or inline table {{..}}: {e}")


def _parse_json(data):
    import json
    return json.loads(data.decode("utf-8"))


def load_index():
    try:
        with open(KERNEL_INDEX_FILE, "rb") as fh:
            data = fh.read()
    except OSError:
        raise SceneError(f"error: {KERNEL_INDEX_FILE}: missing; run ./build.sh gen")
    return derived("index", data, _parse_json)


def _parse_toml(data, path):
    import tomllib
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise SceneError(f"error: {path}: encoding: not UTF-8 text (byte {e.start}); expected a TOML scene file")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise SceneError(f"error: {path}: TOML syntax: {e}")


def read_toml(path):
    """The parsed scene file (through gen/derived.py: a file parsed before is not parsed again)."""
    try:
        with open(path, "rb") as fh:
            data = fh.read()
    except OSError as e:
        raise SceneError(f"error: {path}: cannot read: {e.strerror}")
    return derived("toml", data, lambda d: _parse_toml(d, path))
