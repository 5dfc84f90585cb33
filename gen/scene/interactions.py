"""The scene's interaction modules: each `[[TABLE]]` of a scene that becomes an
interaction of the solver (runtime/assembly/interaction.h) through a record of
the model file (runtime/model/records.c).

A module of gen/scene/ declares itself with a line that starts with
`INTERACTION = Interaction(`: its scene table and keys, the record's name
(the C module's `.record`), a function from the scene to the record's data
(None: the scene has none) and one from the data to the record's lines.  This
file finds the modules by that line, so adding an interaction touches no other
Python file: the scene key check (gen/scene_keys.py), the scene compiler
(build.py) and the model file (model_file.py) loop over `modules()`.
"""
import importlib
import re
from collections import namedtuple
from pathlib import Path

# A scene module's interaction: table (the scene's [[table]] name), keys (the
# keys a table may hold), record (the model record's name), build(ctx, doc,
# scene) -> data or None, lines(data, fmt) -> the record's lines (fmt
# formats a float), holds (True: it may hold the model against rigid motion,
# so statics of a model free to move is not refused; gen/scene/rigid_modes.py),
# order (the order of the records; the C modules sum in their own order).
Interaction = namedtuple("Interaction", "table keys record build lines holds order")

# What a module's build sees of the compiled scene: the meshed beams (by name)
# and bodies, the model length, the amplitudes, the analysis and its static
# options.
Scene = namedtuple("Scene", "beams bodies length_scale amps analysis stat")

_DECL = re.compile(r"^INTERACTION = Interaction\(", re.M)
_MODULES = None


def modules():
    """Every interaction module of gen/scene/, in their order (then by name)."""
    global _MODULES
    if _MODULES is None:
        here = Path(__file__).resolve().parent
        found = []
        for path in sorted(here.glob("*.py")):
            if path.name != "interactions.py" and _DECL.search(path.read_text(encoding="utf-8")):
                found.append(importlib.import_module(f"gen.scene.{path.stem}").INTERACTION)
        _MODULES = sorted(found, key=lambda it: (it.order, it.table))
    return _MODULES


def records(ctx, doc, scene):
    """[(module, data)] of the interactions the scene has, in their order."""
    out = []
    for it in modules():
        data = it.build(ctx, doc, scene)
        if data:
            out.append((it, data))
    return out
