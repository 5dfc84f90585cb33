"""C emission of the contact kernels (out/kernels/contact.{h,c}) from
gen/contact.py: the gaps to rigid primitives with their derivatives, the
barrier and the friction profile, each a flat function with its inputs'
layout and operation count in the header."""
from pathlib import Path

from gen import contact
from gen.descriptor import version_guard
from gen.provenance import BANNER, CORE_FILES, core_paths, input_hash

GEN_DIR = Path(__file__).resolve().parent
CONTACT_FILES = ("contact.py", "emit_contact.py", "rod.py", "rodmath.py")
UNIT = "contact"
RUNTIME_UNIT = True             # linked into every solver (gen/generate.py runtime_units)


def paths():
    return [GEN_DIR / f for f in CONTACT_FILES]


def unit_source():
    """(header text, source text) of out/kernels/contact.{h,c}."""
    h = input_hash(paths() + core_paths())
    funcs = contact.functions()
    head = [f"/* {BANNER}", f" * {UNIT}: gaps to rigid primitives, barrier, friction profile",
            f" * generator inputs: {', '.join('gen/' + f for f in CONTACT_FILES)} + gen core ({', '.join(CORE_FILES)})",
            f" * input hash: sha256:{h}", " *"]
    head += [" * " + x if x.strip() else " *" for x in (contact.__doc__ or "").strip().splitlines()]
    head.append(" */")
    htxt = "\n".join(head) + "\n#ifndef BK_GEN_CONTACT_H\n#define BK_GEN_CONTACT_H\n\n"
    for name, sig, doc, _ in funcs:
        htxt += f"/* {name}: {doc}. */\n{sig};\n"
    htxt += "\n#endif\n"
    ctxt = ("\n".join(head[:4] + [" */"]) + '\n#include <math.h>\n\n#include "contact.h"\n' +
            "\n".join(version_guard()) + "\n\n")
    for _, _, _, lines in funcs:
        ctxt += "\n".join(lines) + "\n"
    return htxt, ctxt
