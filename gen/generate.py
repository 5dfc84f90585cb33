"""Generate out/kernels/: every element, every element x material pair, and index.json;
from the options schema out/kernels/bk_options.h and docs/reference/options.md
(gen/options_emit.py); from the result tables' registrations in runtime/ the
table of CSV files of docs/reference/outputs.md (gen/outputs_emit.py).

Incremental: a file whose header carries the hash of its current generator
inputs is not re-derived.  `check` re-derives everything in memory and compares
byte for byte with what is on disk.
"""
import json
import os
import re
import sys
import time
from pathlib import Path

from gen.elements import all_elements
from gen.provenance import core_paths, input_hash
from gen.materials import all_materials

HASH_RE = re.compile(r"input hash: sha256:([0-9a-f]{64})")


def _existing_hash(path):
    try:
        with open(path, encoding="utf-8") as fh:
            head = fh.read(4096)
    except OSError:
        return None
    m = HASH_RE.search(head)
    return m.group(1) if m else None


def plan(elements=None, materials=None):
    """All (kind, name, input paths) units of generation, in fixed order."""
    elements = elements or all_elements()
    materials = materials or all_materials()
    here = Path(__file__).resolve().parent
    units = [("header", "rod_math", [here / "rodmath.py", here / "program.py"])]
    if any(e.kind == "rod" for e, _ in elements.values()):
        from gen.emit_rod_shared import SHARED_UNITS, shared_paths
        units += [("shared", u, shared_paths()) for u in SHARED_UNITS]
    from gen.emit_body import UNITS as BODY_UNITS, paths as body_paths
    units += [("body", u, body_paths()) for u in BODY_UNITS]
    for mod in runtime_units():
        units.append(("runtime", mod.UNIT, mod.paths()))
    for ename, (elem, epath) in elements.items():
        fam = family_paths(elem)
        units.append(("element", ename, [epath] + fam))
        for mname, (mat, mpath) in materials.items():
            if compatible(elem, mat):
                units.append(("pair", f"{ename}_{mname}", [epath, mpath] + fam))
    return units


_RUNTIME_UNIT = re.compile(r"^RUNTIME_UNIT = True", re.M)


def runtime_units():
    """The emitters of kernels that the runtime's own modules call (contact
    gaps, segment distances, ...): every gen/emit_*.py with a line
    `RUNTIME_UNIT = True`, sorted by name; each gives UNIT (the file name),
    paths() (its inputs) and unit_source() (header and source text).  Every
    solver links them, so a new one needs no edit here."""
    import importlib
    here = Path(__file__).resolve().parent
    return [importlib.import_module(f"gen.{p.stem}") for p in sorted(here.glob("emit_*.py"))
            if _RUNTIME_UNIT.search(p.read_text(encoding="utf-8"))]


def compatible(elem, mat):
    return getattr(mat, "KIND", "continuum") == elem.material_kind


def family_paths(elem):
    if elem.kind == "continuum":
        return []
    from gen.emit_resultant import family_paths as fp
    return fp(elem)


def kernel_files(elem):
    """Shared generated files an element family's pairs link (besides their own)."""
    if elem.kind == "continuum":
        return []
    from gen.emit_rod_shared import kernel_files as kf
    return kf(elem)


def _emitter(elem):
    """The module that writes an element family's files: describe,
    element_source, pair_source."""
    if elem.kind == "continuum":
        import gen.emit_pair as m
    elif elem.kind == "cable":
        import gen.emit_cable as m
    else:
        import gen.emit_rod as m
    return m


def produce(unit):
    """(header text, source text, seconds) of one unit; runs in a worker process."""
    kind, name, inputs = unit
    t0 = time.time()
    if kind == "header":
        from gen.provenance import BANNER
        from gen.rodmath import rod_math_header
        h, c = rod_math_header(BANNER, input_hash(inputs)), None
    elif kind == "shared":
        from gen.emit_rod_shared import shared_source
        h, c = shared_source(name)
    elif kind == "body":
        from gen.emit_body import unit_source
        h, c = unit_source(name)
    elif kind == "runtime":
        h, c = next(m for m in runtime_units() if m.UNIT == name).unit_source()
    elif kind == "element":
        elem, epath = all_elements()[name]
        h, c = _emitter(elem).element_source(elem, epath)[:2]
    else:
        elements = all_elements()
        ename = max((e for e in elements if name.startswith(e + "_")), key=len)
        elem, epath = elements[ename]
        mat, mpath = all_materials()[name[len(ename) + 1:]]
        h, c = _emitter(elem).pair_source(elem, epath, mat, mpath)[:2]
    return h, c, time.time() - t0


def index_data(elements=None, materials=None):
    """out/kernels/index.json: the kernel header version the kernels were generated
    for, per element what the scene compiler needs (from the same descriptor the
    C file is written from, gen/descriptor.py), per material its data, per pair
    its symbol and the files a solver links."""
    from gen import contract
    from gen.continuum import rule_parts
    from gen.descriptor import index_entry
    elements = elements or all_elements()
    materials = materials or all_materials()
    out = {"kernel_version": contract.version(), "elements": {}, "materials": {}, "pairs": []}
    for ename, (elem, _) in elements.items():
        if elem.kind == "continuum":
            rules = {}
            for r in elem.rule_names:
                _, parts, ntab = rule_parts(elem, r)
                rules[r] = {"ntab": ntab, "points": [len(p.rule) for p in parts]}
        else:
            from gen import cable, rod
            rules = {"full": {"ntab": (rod if elem.kind == "rod" else cable).tab_layout()}}
        d = _emitter(elem).describe(elem)
        out["elements"][ename] = {
            "kind": elem.kind, "material_kind": elem.material_kind, "title": elem.title,
            "ndof": elem.ndof, "integrations": rules, "default_integration": elem.default_rule,
            **index_entry(d),
        }
        for mname, (mat, _) in materials.items():
            if not compatible(elem, mat):
                continue
            for r in elem.rule_names:
                out["pairs"].append({"element": ename, "material": mname, "integration": r,
                                     "symbol": f"bk_pair_{ename}_{mname}_{r}",
                                     "files": kernel_files(elem) + [f"{ename}.c", f"{ename}_{mname}.c"]})
    for mname, (mat, mpath) in materials.items():
        out["materials"][mname] = material_data(mat, mpath)
    from gen.emit_body import index_entries
    out["body"], out["joints"] = index_entries()
    # every solver links the kernels of the runtime's own modules (contact, ...)
    out["runtime"] = {"files": [f"{m.UNIT}.c" for m in runtime_units()]}
    return out


def material_data(mat, mpath):
    """What the scene compiler needs of a material, as data (no sympy at run
    time): its scene key sets with the kernel parameters as Python expressions
    of those keys, the small-strain E and nu as expressions of the parameters,
    the Green strain range, and for resultant laws the module whose
    section_stiffness(E, nu, shape, b, h) turns E, nu and a section into the
    six stiffnesses (plain math)."""
    import sympy as sp
    from sympy.printing.pycode import pycode

    def code(e):
        e = sp.sympify(e)
        return pycode(sp.nsimplify(e) if e.is_Number else e, fully_qualified_modules=True)
    inputs = []
    ranges = getattr(mat, "RANGES", None)
    missing = [k for keys, _ in mat.INPUTS for k in keys if not ranges or k not in ranges]
    if getattr(mat, "KIND", "continuum") == "resultant" and hasattr(mat, "section_stiffness"):
        missing += [k for k in ("E", "nu") if not ranges or k not in ranges]
    if missing:
        raise ValueError(f"{mpath}: RANGES gives no (lo, hi, unit) for {', '.join(dict.fromkeys(missing))} "
                         "(every scene key of INPUTS needs its range: docs/howto/add-material.md)")
    for keys, fn in mat.INPUTS:
        syms = [sp.Symbol(k, positive=True) for k in keys]
        inputs.append({"keys": list(keys), "params": [code(v) for v in fn(*syms)]})
    d = {"title": mat.TITLE, "params": list(mat.PARAMS), "kind": getattr(mat, "KIND", "continuum"),
         "inputs": inputs, "ranges": {k: [None if lo is None else float(lo), None if hi is None else float(hi), u]
                                      for k, (lo, hi, u) in ranges.items()}}
    if hasattr(mat, "small_strain"):
        syms = [sp.Symbol(k, positive=True) for k in mat.PARAMS]
        d["small_strain"] = [code(sp.simplify(v)) for v in mat.small_strain(*syms)]
    if hasattr(mat, "GREEN_STRAIN_RANGE"):
        d["green_strain_range"] = [float(x) for x in mat.GREEN_STRAIN_RANGE]
    if hasattr(mat, "section_stiffness"):
        d["section_stiffness"] = f"gen.materials.{Path(mpath).stem}"
    return d


def generate(outdir, check=False, force=False, log=print, only=None):
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    stale = []
    todo = []
    for kind, name, inputs in plan():
        if only and not any(o in name for o in only.split(",")):
            continue
        h = input_hash(list(inputs) + (core_paths() if kind != "header" else []))
        hpath, cpath = outdir / f"{name}.h", outdir / f"{name}.c"
        if not check and not force and _existing_hash(hpath) == h and (kind == "header" or cpath.exists()):
            log(f"  {name}: up to date")
            continue
        todo.append((kind, name, inputs))
    # Units are independent: derive them in parallel worker processes; results
    # are written in plan order, so the output does not depend on scheduling.
    workers = max(1, min(len(todo), os.cpu_count() or 1, int(os.environ.get("BK_JOBS", "2"))))
    if workers > 1:
        import multiprocessing as mp
        from concurrent.futures import ProcessPoolExecutor
        with ProcessPoolExecutor(max_workers=workers, mp_context=mp.get_context("fork")) as ex:
            results = list(ex.map(produce, todo))
    else:
        results = [produce(u) for u in todo]
    for (kind, name, inputs), (htxt, ctxt, dt) in zip(todo, results):
        hpath, cpath = outdir / f"{name}.h", outdir / f"{name}.c"
        files = [(hpath, htxt)] + ([(cpath, ctxt)] if ctxt is not None else [])
        if check:
            for p, txt in files:
                if not p.exists() or p.read_text(encoding="utf-8") != txt:
                    stale.append(str(p))
            log(f"  {name}: checked ({dt:.1f} s)")
        else:
            for p, txt in files:
                p.write_text(txt, encoding="utf-8")
            log(f"  {name}: generated ({dt:.1f} s)")
    if only:
        return stale
    from gen.options_emit import files as option_files   # the options schema's header and key reference
    from gen.outputs_emit import files as output_files   # the outputs reference's tables, from their registrations
    for p, txt in {**option_files(outdir), **output_files()}.items():
        if check:
            if not p.exists() or p.read_text(encoding="utf-8") != txt:
                stale.append(str(p))
        elif not p.exists() or p.read_text(encoding="utf-8") != txt:     # unchanged: keep its time
            p.parent.mkdir(parents=True, exist_ok=True)
            p.write_text(txt, encoding="utf-8")
            log(f"  {p.name}: generated")
    idx = json.dumps(index_data(), indent=1, sort_keys=True) + "\n"
    ipath = outdir / "index.json"
    if check:
        if not ipath.exists() or ipath.read_text(encoding="utf-8") != idx:
            stale.append(str(ipath))
    else:
        ipath.write_text(idx, encoding="utf-8")
    # Files on disk that the generator no longer produces.
    expected = {f"{n}.{x}" for k, n, _ in plan() for x in (("h",) if k == "header" else ("h", "c"))} | {"index.json", "bk_options.h"}
    extra = sorted(p.name for p in outdir.iterdir() if p.name not in expected)
    if check:
        stale += [str(outdir / e) for e in extra]
    else:
        for e in extra:
            (outdir / e).unlink()
            log(f"  removed stale {e}")
    return stale


def main(argv):
    import argparse
    ap = argparse.ArgumentParser(prog="build.sh gen", description="Regenerate the C kernels in out/kernels/.")
    ap.add_argument("--check", action="store_true", help="fail if the committed kernels differ from a fresh generation")
    ap.add_argument("--force", action="store_true", help="re-derive every kernel even if its input hash is unchanged")
    ap.add_argument("--only", metavar="NAMES", help="only the units whose name contains one of these "
                    "comma-separated substrings (no index, no stale-file cleanup)")
    ap.add_argument("--out", default=str(Path(__file__).resolve().parent.parent / "out" / "kernels"))
    a = ap.parse_args(argv)
    stale = generate(a.out, check=a.check, force=a.force, only=a.only)
    if a.check:
        if stale:
            print("gen --check: generated kernels are stale:", file=sys.stderr)
            for s in stale:
                print(f"  {s}", file=sys.stderr)
            print("run ./build.sh gen and commit out/kernels/", file=sys.stderr)
            return 1
        print("gen --check: out/kernels/ is up to date")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
