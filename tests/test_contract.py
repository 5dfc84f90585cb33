"""runtime/bk_kernel.h is the only contract between the generated kernels and the
runtime: a version every generated file and every solver's kernel table is
checked against when compiled, field roles and capabilities instead of names,
named geometry slots, descriptors written by one emitter."""
import json
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

from gen import contract
from gen.solver_build import CC, INCLUDES, WARN, kernel_table_source
from util import ROOT

RUNTIME = ROOT / "runtime"
KERNELS = ROOT / "out" / "kernels"
CMP_RE = re.compile(r"\b(strn?cmp|strn?casecmp|memcmp|strstr)\s*\(")


def _call_args(text, start):
    """The argument text of the call whose '(' is at text[start]."""
    depth, i = 0, start
    while True:
        c = text[i]
        depth += c == "("
        depth -= c == ")"
        if depth == 0:
            return text[start + 1:i]
        i += 1


def _names():
    """Every field name and material parameter name the kernels have."""
    idx = json.loads((KERNELS / "index.json").read_text())
    fields = {f for e in idx["elements"].values() for n in e["nodes"] for f, _ in n["fields"]}
    fields |= {"p", "lambda"}
    params = {p for m in idx["materials"].values() for p in m["params"]}
    return fields | params


def test_no_runtime_file_compares_field_or_parameter_names():
    """No runtime .c file names a field or a material parameter in a string
    comparison, nor compares field names at all: the runtime knows fields by
    bk_field_role and elements by their capabilities.  (Checking a model file's
    parameter names against a kernel's param_names generically is matching by
    name, not naming one, and stays allowed.)"""
    names = _names()
    bad = []
    for path in sorted(RUNTIME.rglob("*.c")):
        text = re.sub(r"/\*.*?\*/", lambda c: "\n" * c.group(0).count("\n"), path.read_text(), flags=re.S)
        for m in CMP_RE.finditer(text):
            args = _call_args(text, m.end() - 1)
            literals = set(re.findall(r'"((?:[^"\\]|\\.)*)"', args))
            if "field_name" in args or literals & names:
                line = text[:m.start()].count("\n") + 1
                bad.append(f"{path.name}:{line}: {m.group(1)}({args})")
    assert not bad, "runtime compares names:\n" + "\n".join(bad)


def test_header_constants_as_the_generator_reads_them():
    assert contract.version() >= 2
    assert contract.geom_slots() == ("L", "B", "H", "A", "I1", "I2", "IP", "SHAPE", "BAND_LO", "BAND_HI", "BAND_AXIS",
                                     "EIGENSTRAIN")
    assert contract.ngeom() == len(contract.geom_slots())
    assert contract.section_shapes() == {"rectangle": 1, "circle": 2}
    roles = contract.field_roles()
    assert 0 not in roles.values() and len(set(roles.values())) == len(roles)
    caps = contract.capabilities()
    assert all(v & (v - 1) == 0 for v in caps.values()) and len(set(caps.values())) == len(caps)


def test_every_continuum_pair_has_lane_kernels():
    """BK_LANES as the generator reads it, and every continuum element x material
    pair descriptor offers force_lanes and force_tangent_lanes (bk_kernel.h,
    "Lane kernels"); the rods do not (NULL: one element per call)."""
    assert contract.lanes() == 8
    idx = json.loads((KERNELS / "index.json").read_text())
    n = 0
    for p in idx["pairs"]:
        text = (KERNELS / f"{p['element']}_{p['material']}.c").read_text()
        sym = f"bk_pair_{p['element']}_{p['material']}_{p['integration']}"
        body = re.search(r"^const bk_pair " + sym + r" = \{\n(.*?)^\};", text, re.M | re.S).group(1)
        has = ".force_lanes = " in body and ".force_tangent_lanes = " in body
        assert has == (p["material"] != "resultant"), f"{sym}: lane kernels {'missing' if not has else 'unexpected'}"
        n += has
    assert n >= 30, n


def test_generated_files_state_the_header_version():
    """Every generated C file (elements, pairs, shared rod files) carries the
    version guard of the current header, index.json the version, and every
    descriptor is written with designated initializers and field roles."""
    v = contract.version()
    guard = f"#if !defined(BK_KERNEL_VERSION) || BK_KERNEL_VERSION != {v}\n#error"
    files = sorted(KERNELS.glob("*.c"))
    assert len(files) > 20
    for f in files:
        text = f.read_text()
        assert guard in text, f"{f.name} has no version guard for version {v}"
        for m in re.finditer(r"^const bk_(element|pair) \w+ = \{\n(.*?)^\};", text, re.M | re.S):
            body = m.group(2).rstrip().splitlines()
            assert body and all(re.match(r"\s+\.\w+ = ", ln) for ln in body), f"{f.name}: positional initializer"
            if m.group(1) == "element":
                assert ".field_role = field_role," in m.group(2) and ".caps = " in m.group(2), f.name
    assert json.loads((KERNELS / "index.json").read_text())["kernel_version"] == v


def _compile(src, include_first=None):
    inc = ([f"-I{include_first}"] if include_first else []) + INCLUDES
    return subprocess.run([CC] + WARN + ["-fsyntax-only"] + inc + [str(src)], capture_output=True, text=True)


def test_kernels_and_kernel_table_refuse_another_header_version():
    """A generated file compiled against a header of another version, and a
    solver's kernel table made for kernels of another version, fail to compile
    with a message that says to regenerate."""
    v = contract.version()
    tmp = Path(tempfile.mkdtemp(prefix="bk-version-"))
    try:
        hdr = (RUNTIME / "bk_kernel.h").read_text()
        (tmp / "bk_kernel.h").write_text(hdr.replace(f"#define BK_KERNEL_VERSION {v}",
                                                     f"#define BK_KERNEL_VERSION {v + 1}"))
        assert _compile(KERNELS / "gef.c").returncode == 0
        r = _compile(KERNELS / "gef.c", include_first=tmp)
        assert r.returncode != 0 and f"generated for runtime/bk_kernel.h version {v}" in r.stderr, r.stderr
        (tmp / "tables").mkdir()
        for version, ok in ((v, True), (v - 1, False)):
            t = tmp / "tables" / f"table_{version}.c"
            t.write_text(kernel_table_source(["gef_resultant_full"], version))
            r = _compile(t)
            assert (r.returncode == 0) == ok, r.stderr
            if not ok:
                assert "regenerate with ./build.sh gen" in r.stderr, r.stderr
    finally:
        shutil.rmtree(tmp)


def test_every_element_descriptor_comes_from_the_one_emitter():
    """index.json's element entries and the C descriptors come from the same
    description (gen/descriptor.py): nodes, fields, section, moments, curved."""
    from gen.descriptor import index_entry
    from gen.elements import all_elements
    from gen.generate import _emitter
    idx = json.loads((KERNELS / "index.json").read_text())
    for name, (elem, _) in all_elements().items():
        d = _emitter(elem).describe(elem)
        e = idx["elements"][name]
        for k, v in index_entry(d).items():
            assert e[k] == v, (name, k)
        text = (KERNELS / f"{name}.c").read_text()
        roles = re.search(r"field_role\[\d+\] = \{(.*?)\};", text).group(1).split(", ")
        assert roles == [contract.role_of(f.name) for f in d.fields], name
        assert f".caps = {' | '.join(d.caps)}," in text, name
