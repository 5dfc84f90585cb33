"""C emission of an element x material pair of a continuum element:
<element>_<material>.h / .c with the energy, force and force + tangent kernels
per integration (one element a call, and over BK_LANES elements), the section
resultants function, the pair descriptors and the header that says what each
computes, its inputs' layout and its operation counts.  With gen/emit.py's
describe and element_source (the element's own file; re-exported here) it is
the continuum elements' emitter (gen/generate.py _emitter)."""
from pathlib import Path

from gen.continuum import lowered_body, rule_parts
from gen.descriptor import PairDesc, pair_descriptors, version_guard
from gen.emit import _kernel_fn, contraction_ops, describe, element_source  # noqa: F401
from gen.emit_sections import sections_function
from gen.lanes import _lane_kernel_fn, _vector_math_decls
from gen.program import Ops, count_lowered
from gen.provenance import BANNER, CORE_FILES, core_paths, input_hash


def pair_source(elem, elem_path, mat, mat_path):
    name = f"{elem.name}_{mat.NAME}"
    ndof = elem.ndof
    h = input_hash([elem_path, mat_path] + core_paths())
    sig = {
        "energy": f"double {name}_{{r}}_energy(const double *restrict q, const double *restrict tab, const double *restrict mat)",
        "force": f"void {name}_{{r}}_force(const double *restrict q, const double *restrict tab, const double *restrict mat, double *restrict f)",
        "tangent": f"void {name}_{{r}}_force_tangent(const double *restrict q, const double *restrict tab, const double *restrict mat, double *restrict f, double *restrict K)",
        "force_lanes": f"void {name}_{{r}}_force_lanes(const double *restrict q, const double *restrict tab, const double *restrict mat, double *restrict f)",
        "tangent_lanes": f"void {name}_{{r}}_force_tangent_lanes(const double *restrict q, const double *restrict tab, const double *restrict mat, double *restrict f, double *restrict K)",
    }
    c = ["/* " + BANNER + f" (see {name}.h) */", f'#include "{name}.h"', f'#include "{elem.name}.h"',
         "#include <math.h>"] + version_guard() + [""]
    summary = []
    descs = []
    decls = []
    for rname in elem.rule_names:
        slots, parts, ntab = rule_parts(elem, rname)
        nqp = sum(len(p.rule) for p in parts)
        counts = {}
        fns = {}
        for want in ("energy", "force", "tangent"):
            lows = [lowered_body(elem, mat, p.energy, want) for p in parts]
            per_call = Ops()
            per_qp = []
            for p, low in zip(parts, lows):
                pro, body = count_lowered(low)
                if want == "tangent":
                    body += contraction_ops(elem)
                per_call += pro
                for _ in range(len(p.rule)):
                    per_call += body
                per_qp.append(body.total())
            counts[want] = (per_qp, per_call)
            s = sig[want].format(r=rname)
            decls.append(s + ";")
            if want == "energy":
                lines = _kernel_fn(s, ndof, parts, lows, ["double e = 0.0;"], ["return e;"])
            elif want == "force":
                lines = _kernel_fn(s, ndof, parts, lows, [f"for (int i = 0; i < {ndof}; ++i) f[i] = 0.0;"], [])
            else:
                lines = _kernel_fn(s, ndof, parts, lows,
                                   [f"for (int i = 0; i < {ndof}; ++i) f[i] = 0.0;",
                                    f"for (int i = 0; i < {ndof * ndof}; ++i) K[i] = 0.0;"],
                                   [f"for (int r = 1; r < {ndof}; ++r)",
                                    f"    for (int c = 0; c < r; ++c) K[r * {ndof} + c] = K[c * {ndof} + r];"],
                                   contract_fn=f"{elem.name}_tangent_contract")
            c += lines
            fns[want] = s.split("(")[0].split()[-1]
            if want in ("force", "tangent"):
                s = sig[want + "_lanes" if want == "force" else "tangent_lanes"].format(r=rname)
                decls.append(s + ";")
                c += _lane_kernel_fn(s, ndof, parts, lows,
                                     contract_fn=f"{elem.name}_tangent_contract_lanes" if want == "tangent" else None)
                fns[want + "_lanes"] = s.split("(")[0].split()[-1]
        sname = f"{name}_{rname}_sections"
        slines, sxi, ssrc = sections_function(elem, mat, rname, sname)
        c += slines
        decls.append(slines[0] + ";")
        descs.append(PairDesc(
            element=elem.name, material=mat.NAME, integration=rname, ntab=ntab, nqp=nqp,
            ops_force=counts["force"][1].total(), ops_force_tangent=counts["tangent"][1].total(),
            functions={"tabulate": f"{elem.name}_{rname}_tabulate", "energy": fns["energy"], "force": fns["force"],
                       "force_tangent": fns["tangent"], "force_lanes": fns["force_lanes"],
                       "force_tangent_lanes": fns["tangent_lanes"], "viscous_force": f"{elem.name}_{rname}_viscous_force",
                       "viscous": f"{elem.name}_{rname}_viscous",
                       "viscous_force_lanes": f"{elem.name}_{rname}_viscous_force_lanes",
                       "viscous_lanes": f"{elem.name}_{rname}_viscous_lanes",
                       "invariants": f"{elem.name}_{rname}_invariants", "sections": sname},
            nvisc=2, green_strain_range=tuple(getattr(mat, "GREEN_STRAIN_RANGE", (0.0, 0.0))),
            sample_xi=sxi, sample_source=ssrc))
        parts_txt = " + ".join(f"{len(p.rule)} pts ({p.energy}, {'x'.join(map(str, rp.points))})"
                               for p, rp in zip(parts, elem.rule(rname)))
        summary.append((rname, parts_txt, ntab, counts))
    c += pair_descriptors(mat.PARAMS, descs)
    ng = len(version_guard())
    c[4 + ng:4 + ng] = _vector_math_decls(c)

    hdr = [f"/* {BANNER}",
           f" * pair: {elem.name} x {mat.NAME} -- {elem.title}; {mat.TITLE}",
           f" * generator inputs: gen/elements/{Path(elem_path).name}, gen/materials/{Path(mat_path).name}"
           f" + gen core ({', '.join(CORE_FILES)})",
           f" * input hash: sha256:{h}",
           " *",
           " * Computes for one element: U = sum over quadrature points of w W(I1, I2, J)",
           " * (strain energy, J), f = dU/dq (internal force) and K = df/dq (tangent).",
           f" * Inputs:  q[{ndof}] element coordinates ({elem.describe_layout()}), each xyz",
           f" *          tab[] from {elem.name}_<integration>_tabulate(geom)",
           f" *          mat[{len(mat.PARAMS)}] = {{{', '.join(mat.PARAMS)}}}",
           f" * Outputs: f[{ndof}] overwritten; K[{ndof}*{ndof}] row-major, upper triangle computed, mirrored.",
           " * Section resultants (<pair>_<integration>_sections, bk_pair.sections): at the axial Gauss",
           " * stations of the integration's first rule part, n = int P N0 dA0 and m = int (r - r_c) x P N0 dA0",
           " * over the reference section (N0 = e_x), from the points of every rule part (a part with one",
           " * axial station adds its section to every station), global axes.",
           " * Operations (add + mul + div + call; accumulation included):"]
    for rname, parts_txt, ntab, counts in summary:
        hdr.append(f" *   integration \"{rname}\": {parts_txt}; tab[{ntab}]")
        for want, label in (("energy", "energy"), ("force", "force"), ("tangent", "force + upper tangent")):
            per_qp, per_call = counts[want]
            hdr.append(f" *     {label:<22} per point {' / '.join(map(str, per_qp))}; per element {per_call}")
    hdr.append(f" * (force + tangent counts include {elem.name}_tangent_contract: {contraction_ops(elem).total()} per point)")
    hdr.append(" */")
    htxt = "\n".join(hdr) + f"""
#ifndef BK_GEN_{name.upper()}_H
#define BK_GEN_{name.upper()}_H
#include "bk_kernel.h"

""" + "\n".join(f"extern const bk_pair bk_pair_{name}_{r};" for r in elem.rule_names) + "\n" + \
        "\n".join(decls) + "\n\n#endif\n"
    return htxt, "\n".join(c), summary
