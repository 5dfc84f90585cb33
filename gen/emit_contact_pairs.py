"""C emission of the beam-to-beam contact kernels (out/kernels/
contact_pairs.{h,c}) from gen/contact_pairs.py: the point-point,
point-edge and edge-edge distances with their gradients and Hessians, each a
flat function whose header line gives its layout and operation count."""
from pathlib import Path

from gen import contact_pairs
from gen.descriptor import version_guard
from gen.provenance import BANNER, CORE_FILES, core_paths, input_hash

GEN_DIR = Path(__file__).resolve().parent
FILES = ("contact_pairs.py", "emit_contact_pairs.py")
UNIT = "contact_pairs"
RUNTIME_UNIT = True             # linked into every solver (gen/generate.py runtime_units)


def paths():
    return [GEN_DIR / f for f in FILES]


def unit_source():
    """(header text, source text) of out/kernels/contact_pairs.{h,c}."""
    digest = input_hash(paths() + core_paths())
    funcs = contact_pairs.functions()
    top = [f"/* {BANNER}", f" * {UNIT}: distances between segments of two centrelines, with derivatives",
           f" * generator inputs: {', '.join('gen/' + f for f in FILES)} + gen core ({', '.join(CORE_FILES)})",
           f" * input hash: sha256:{digest}", " *"]
    doc = [" * " + x if x.strip() else " *" for x in (contact_pairs.__doc__ or "").strip().splitlines()]
    header = "\n".join(top + doc + [" */"]) + "\n#ifndef BK_GEN_CONTACT_PAIRS_H\n#define BK_GEN_CONTACT_PAIRS_H\n\n"
    header += "".join(f"/* {name}: {d}. */\n{sig};\n" for name, sig, d, _ in funcs) + "\n#endif\n"
    source = "\n".join(top[:4] + [" */"]) + '\n#include <math.h>\n\n#include "contact_pairs.h"\n'
    source += "\n".join(version_guard()) + "\n\n" + "".join("\n".join(lines) + "\n" for *_, lines in funcs)
    return header, source
