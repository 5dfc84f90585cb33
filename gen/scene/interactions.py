"""The scene's interaction modules: each `[[TABLE]]` of a scene that becomes an
interaction of the solver (runtime/assembly/interaction.h) through a record of
the model file (runtime/model/records.c).

A module of gen/scene/ declares itself with a line that starts with
`INTERACTION = Interaction(`: its scene table and keys, the record's name
(the C module's `.record`), a function from the scene to the record's data
(None: the scene has none) and one from the data to the record's lines.  This
file finds the modules by that line, so adding an interaction touches no other
Python file: the scene key check (gen/scene_keys.py), the scene compiler
(build.py) and the model file (model_file.py) loop over `modules()`.  Write
the table as `table="NAME"` in the declaration: a scene compile then imports
only the modules of the tables the scene has (`tables()` reads the names from
the declarations).
"""
import os
import sys

# A scene module's interaction: table (the scene's [[table]] name), keys (the
# keys a table may hold; () for a part of a table whose keys another module
# checks and documents: body_loads.py's forces at body points in [[load]]),
# record (the model record's name), build(ctx, doc, scene) -> data or None,
# lines(data, fmt) -> the record's lines (fmt formats a float), holds (True: it
# may hold the model against rigid motion, so statics of a model free to move is
# not refused; gen/scene/rigid_modes.py),
# order (the order of the records; the C modules sum in their own order),
# doc (the key reference: rows (keys, unit, default, meaning), markdown, links
# relative to the repository) and title (a line saying what the table is).
class Interaction:
    __slots__ = ("table", "keys", "record", "build", "lines", "holds", "order", "doc", "title")

    def __init__(self, table, keys, record, build, lines, holds, order, doc=(), title=""):
        self.table, self.keys, self.record, self.build, self.lines = table, keys, record, build, lines
        self.holds, self.order, self.doc, self.title = holds, order, doc, title


# (plain classes and strings, no collections, importlib, re or pathlib: every
# scene compile imports this file, and those imports were 13 ms of a run with
# a new --set value)
_HERE = os.path.dirname(os.path.realpath(__file__))
REFERENCE = os.path.join(os.path.dirname(os.path.dirname(_HERE)), "docs", "reference", "interactions.md")

# What a module's build sees of the compiled scene: the meshed beams (by name)
# and bodies, the model length, the amplitudes, the analysis and its static
# options, the constraints' rows (gen/scene/joints.py constraints: reactions,
# joints nonlinear in q).
class Scene:
    __slots__ = ("beams", "bodies", "length_scale", "amps", "analysis", "stat", "joints")

    def __init__(self, beams, bodies, length_scale, amps, analysis, stat, joints):
        self.beams, self.bodies, self.length_scale, self.amps = beams, bodies, length_scale, amps
        self.analysis, self.stat, self.joints = analysis, stat, joints

_DECL = "INTERACTION = Interaction("       # at the start of a line
_DECLARED = None


def _declares(text):
    return text.startswith(_DECL) or "\n" + _DECL in text


def _declaring(listing):
    """[module, table] of each module of gen/scene/ that declares an interaction
    (by name), from their sources: the table is the declaration's `table="..."`
    (None when it is not written so: then the module is always imported).
    listing: the folder's "name size mtime_ns" lines."""
    found = []
    for line in listing.decode().split("\n"):
        name = line.partition(" ")[0]
        with open(os.path.join(_HERE, name), encoding="utf-8") as f:
            text = f.read()
        if _declares(text):
            decl = text[text.index(_DECL):]
            table = decl.partition('table="')[2].partition('"')[0] if 'table="' in decl[:200] else None
            found.append([name[:-3], table or None])
    return found


def _declared():
    """_declaring() of the folder now.  Kept by the state (name, size, time) of
    the folder's files (gen/derived.py): reading all 31 of them was 1.2 ms of
    every scene compile."""
    global _DECLARED
    if _DECLARED is None:
        from gen.derived import derived
        with os.scandir(_HERE) as it:
            listing = sorted(f"{e.name} {e.stat().st_size} {e.stat().st_mtime_ns}" for e in it
                             if e.name.endswith(".py") and not e.name.startswith(".")
                             and e.name != "interactions.py" and e.is_file())
        _DECLARED = derived("interaction_tables", "\n".join(listing).encode(), _declaring)
    return _DECLARED


def _module(name):
    """The interaction of the module gen/scene/NAME.py (imported when not yet)."""
    mod = f"gen.scene.{name}"
    if mod not in sys.modules:
        __import__(mod)
    return sys.modules[mod].INTERACTION


def tables():
    """The scene tables of every interaction module (a module is imported only
    when its declaration does not write its table as a literal)."""
    return {table or _module(name).table for name, table in _declared()}


def modules(doc=None):
    """Every interaction module of gen/scene/, in their order (then by name).
    doc: only those whose table the scene has (each module's build finds
    nothing without its table, so the others need not be imported: 1.5 ms of a
    scene compile)."""
    found = [_module(name) for name, table in _declared() if doc is None or not table or table in doc]
    return sorted(found, key=lambda it: (it.order, it.table))


def records(ctx, doc, scene):
    """[(module, data)] of the interactions the scene has, in their order."""
    out = []
    for it in modules(doc):
        data = it.build(ctx, doc, scene)
        if data:
            out.append((it, data))
    return out


def reference():
    """Text of docs/reference/interactions.md: each interaction table's keys,
    from the modules' doc rows (tests/test_docs.py checks they are the keys
    the module accepts)."""
    out = ["# Interaction keys", "",
           "<!-- generated by gen/scene/interactions.py from the interaction modules of gen/scene/: "
           "edit those, then ./build.sh gen -->", "",
           "The keys of the scene tables that become interactions of the solver (the other keys: the "
           "[scene reference](scene.md#scene-reference) and [options.md](options.md)).  Each table's keys and this reference live in its "
           "scene module (`gen/scene/*.py`, `INTERACTION = Interaction(...)`).", ""]
    for it in modules():
        if not it.doc:
            continue
        out += [f"## `[[{it.table}]]`: {it.title}" if it.title else f"## `[[{it.table}]]`", "",
                "| key | unit | default | meaning |", "|---|---|---|---|"]
        for keys, unit, default, meaning in it.doc:
            first = f"`{it.table}.{keys[0]}`" + "".join(f", `.{k}`" for k in keys[1:])
            out.append(f"| {first} | {unit} | {default} | {meaning.replace('](docs/', '](../')} |")
        out.append("")
    return "\n".join(out)


def files():
    """{path: text} of the files generated from the interaction modules."""
    from pathlib import Path
    return {Path(REFERENCE): reference()}
