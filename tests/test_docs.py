"""The scene reference (docs/reference/scene.md) and the generated option reference
(docs/reference/options.md) list exactly the keys the scene reader accepts
(gen/scene_keys.py and the laws' parameter keys), so a key is never undocumented
or documented but refused; the files generated from the options schema are
fresh, and so is its table of CSV files, made from the tables' registrations."""
import re

import pytest

from gen import scene_keys as K
from gen.materials import all_materials
from util import ROOT


def documented_keys():
    return _table_keys((ROOT / "docs" / "reference" / "scene.md").read_text(), "## Scene reference") | \
        _table_keys((ROOT / "docs" / "reference" / "options.md").read_text(), "# Analysis options") | \
        _interaction_keys((ROOT / "docs" / "reference" / "interactions.md").read_text())


def _interaction_keys(text):
    """The keys of every table of docs/reference/interactions.md."""
    out = set()
    for part in text.split("\n## ")[1:]:
        out |= _table_keys("## " + part + "\n\n", "## ")
    return out


def _table_keys(text, heading):
    start = text.index("| key |", text.index(heading))
    table = text[start:text.index("\n\n", start)]
    keys = set()
    for row in table.splitlines()[2:]:       # below the header and its rule
        first = row.split("|")[1]
        prefix = None
        for tok in re.findall(r"`([^`]+)`", first):
            if tok.startswith("."):
                keys.add(prefix + tok)
            else:
                keys.add(tok)
                prefix = tok.rsplit(".", 1)[0]
    out = set()
    for k in keys:
        parts = k.split(".")
        if parts[0] in ("material", "section", "amplitude") and len(parts) == 3:
            parts = [parts[0], parts[2]]
        out.add(".".join(parts))
    return out


def accepted_keys():
    out = {f"{t}.{k}" for t, ks in K.all_keys().items() for k in ks}
    from gen.scene.interactions import modules
    out |= {f"{it.table}.{k}" for it in modules() for k in it.keys}
    for mod, _ in all_materials().values():
        for keys, _fn in mod.INPUTS:
            out |= {f"material.{k}" for k in keys}
        if getattr(mod, "KIND", "continuum") == "resultant":
            out |= {"material.E", "material.nu"}
    return out


def test_readme_scene_reference_matches_the_reader():
    doc, acc = documented_keys(), accepted_keys()
    assert not acc - doc, f"accepted but not in the scene reference (docs/reference/scene.md): {sorted(acc - doc)}"
    assert not doc - acc, f"in the scene reference (docs/reference/scene.md) but refused by the reader: {sorted(doc - acc)}"


def test_option_header_and_reference_are_generated_from_the_schema():
    """out/kernels/bk_options.h and docs/reference/options.md as the schema makes
    them (what `./build.sh gen --check` checks, without the kernels)."""
    from gen.options_emit import files
    for path, text in files(ROOT / "out" / "kernels").items():
        assert path.read_text(encoding="utf-8") == text, f"{path} is stale: run ./build.sh gen"


def test_output_reference_mentions_outputs_and_limits():
    text = "".join((ROOT / "docs" / "reference" / f).read_text() for f in ("outputs.md", "scene.md"))
    for needle in ("results.pvd", "step_NNNNNN.vtu", "vtk_every", "[[initial_velocity]]", "1,000,000",
                   "about 50 frames"):
        assert needle in text, needle


def test_output_tables_are_generated_from_their_registrations():
    """The CSV files of docs/reference/outputs.md as `./build.sh gen` makes
    them from the tables' BK_TABLE registrations (what `--check` checks); the
    reader takes adjacent literals, skips comments and the macro's #define,
    and refuses anything but string literals; every table spec of runtime/ is
    a BK_TABLE (so the page sees every table a run can open)."""
    from gen.outputs_emit import SpecError, files, specs_in
    for path, text in files().items():
        assert path.read_text(encoding="utf-8") == text, f"{path} is stale: run ./build.sh gen"
    src = ('#define BK_TABLE(a, b, c) {a, b, c}\n/* BK_TABLE("no.csv", "x", "y\\n") */\n'
           'static const bk_table_spec t = BK_TABLE("a.csv", "runs " "with `[[x]]`", "step,"\n'
           '    "time\\n"); // BK_TABLE(\n')
    assert specs_in(src) == [("a.csv", "runs with `[[x]]`", "step,time", 3)]
    for bad in ('BK_TABLE(NAME, "x", "y\\n")', 'BK_TABLE("a.csv", "x")', 'BK_TABLE("a.csv", "x", "no newline")'):
        with pytest.raises(SpecError):
            specs_in(bad)
    made = []
    for p in sorted((ROOT / "runtime").rglob("*.[ch]")):
        text = re.sub(r"/\*.*?\*/", "", p.read_text(), flags=re.S)
        for m in re.finditer(r"\bbk_table_spec\s+(\w+)\s*=\s*(\w+)", text):
            assert m.group(2) == "BK_TABLE", f"{p}: table spec {m.group(1)} not written with BK_TABLE"
            made.append(m.group(1))
    assert len(made) >= 15, made
