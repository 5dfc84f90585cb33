"""C emission for the ANCF cable (gen/cable.py): its element file (shape, mass,
frame, moment, tabulate) and its element x material pair files."""
from dataclasses import replace
from pathlib import Path

import sympy as sp

from gen import cable
from gen.c_functions import _block, _function, _prologue
from gen.descriptor import ElementDesc, element_descriptor, pair_descriptors, version_guard
from gen.emit_resultant import FAMILY_FILES, _fields, _full_pair, _geom, _line_integrals, family_paths
from gen.loads import axis_moment
from gen.program import Program, count_lowered, lower
from gen.provenance import BANNER, CORE_FILES, core_paths, input_hash

CABLE_CAPS = ("BK_CAP_SECTION_RECTANGLE", "BK_CAP_SECTION_CIRCLE", "BK_CAP_CURVED", "BK_CAP_MOMENT_NO_TORSION")


def describe(elem):
    """The descriptor of the cable element (gen/descriptor.py)."""
    return ElementDesc(name=elem.name, title=elem.title, node_xi=("0", "1"), ndof=elem.ndof, caps=CABLE_CAPS,
                       fields=_fields(elem, 2), shape_dof=(0, 3, 6, 9),
                       functions={k: k for k in ("reference", "shape", "mass", "volume", "frame", "moment")})


def _cable_parts(elem):
    g = _geom()
    l, A = g["L"], g["A"]
    xi = sp.Symbol("xi", real=True)
    from gen.element import XI, L
    Nh, d1h, _ = cable.hermite()
    sub = {XI: xi, L: l}
    N = [n.subs(sub) for n in Nh]
    dN = [n.subs(sub) for n in d1h]
    shp = Program()
    for a in range(4):
        shp.output(f"N[{a}]", N[a], op="=")
    mass_low, vol_low = _line_integrals(N, xi, l, A)
    q = [sp.Symbol(f"q[{i}]", real=True) for i in range(12)]
    fr = Program()
    for i in range(3):
        fr.output(f"pos[{i}]", sum(N[a] * q[3 * a + i] for a in range(4)), op="=")
        fr.output(f"d[{i}]", sp.nan, op="=")
        fr.output(f"d[{3 + i}]", sp.nan, op="=")
        fr.output(f"d[{6 + i}]", sum(dN[a] * q[3 * a + i] for a in range(4)), op="=")
    mo = Program()
    rx = sp.Matrix([mo.define(f"rx{i}", sum(dN[a] * q[3 * a + i] for a in range(4))) for i in range(3)])
    M = sp.Matrix([sp.Symbol(f"M[{i}]", real=True) for i in range(3)])
    Qr = axis_moment(rx, M)
    Qs = [mo.define(f"Qs{i}", Qr[i]) for i in range(3)]
    dQs = [[mo.define(f"dQs{i}_{j}", sp.diff(Qr[i], rx[j])) for j in range(3)] for i in range(3)]
    for a in range(4):
        for i in range(3):
            mo.output(f"Q[{3 * a + i}]", dN[a] * Qs[i], op="=")
            for b in range(4):
                for k in range(3):
                    mo.output(f"dQ[{(3 * a + i) * 12 + 3 * b + k}]", dN[a] * dN[b] * dQs[i][k], op="=")
    ref = Program()
    for i, v in enumerate((0, 0, 0, 1, 0, 0, l, 0, 0, 1, 0, 0)):
        ref.output(f"q0[{i}]", v, op="=")
    tab = lower(cable.tabulate_program(), ())
    return (lower(shp, ()), mass_low, vol_low, lower(fr, ()), [lower(mo, ())], lower(ref, ()), tab,
            [0, 3, 6, 9], cable.tab_layout())


def element_source(elem, elem_path):
    name = elem.name
    nd = elem.ndof
    h = input_hash([elem_path] + family_paths(elem) + core_paths())
    shp, mass_low, vol_low, fr, mom, ref, tab, shape_dof, ntab = _cable_parts(elem)
    doc = (cable.__doc__ or "").strip().splitlines()
    hdr = [f"/* {BANNER}", f" * element: {name} -- {elem.title}", f" * source: {elem.source}",
           f" * generator inputs: gen/elements/{Path(elem_path).name}, "
           f"{', '.join('gen/' + f for f in FAMILY_FILES[elem.kind])} + gen core ({', '.join(CORE_FILES)})",
           f" * input hash: sha256:{h}", " *"]
    hdr += [" * " + x if x.strip() else " *" for x in doc]
    hdr += [" */"]
    htxt = "\n".join(hdr) + f"""
#ifndef BK_GEN_{name.upper()}_H
#define BK_GEN_{name.upper()}_H
#include "bk_kernel.h"

extern const bk_element bk_element_{name};
/* tab[{ntab}] from the reference coordinates q0 */
void {name}_full_tabulate(const double *restrict geom, const double *restrict q0, double *restrict tab);

#endif
"""
    c = [f"/* {BANNER} (see {name}.h) */", f'#include "{name}.h"', "#include <math.h>",
         '#include "rod_math.h"'] + version_guard() + [""]
    c += _function("static void shape(const double *restrict geom, double xi, double y, double z, double *restrict N)",
                   shp, ["(void)geom; (void)y; (void)z;"])
    c += _function("static void mass(const double *restrict geom, double *restrict m)", mass_low)
    c += _function("static void volume(const double *restrict geom, double *restrict v)", vol_low)
    c += _function("static void frame(const double *restrict geom, double xi, const double *restrict q, "
                   "double *restrict pos, double *restrict d)", fr, ["(void)geom; (void)xi;"])
    msig = ("static void moment(const double *restrict geom, double xi, const double *restrict q, "
            "const double *restrict M, double *restrict Q, double *restrict dQ)")
    pre = ["(void)geom; (void)xi;", f"for (int i = 0; i < {nd}; ++i) Q[i] = 0.0;",
           f"for (int i = 0; i < {nd * nd}; ++i) dQ[i] = 0.0;"]
    c += _function(msig, mom[0], pre)
    c += _function("static void reference(const double *restrict geom, double *restrict q0)", ref, ["(void)geom;"])
    c += [f"/* 1 where the reference turns by at least {cable.STRAIGHT:g} rad over the element (kappa0 l), else 0 */",
          "static double curved_flag(double turn) { return turn >= " + repr(cable.STRAIGHT) + " ? 1.0 : 0.0; }", ""]
    c += _function(f"void {name}_full_tabulate(const double *restrict geom, const double *restrict q0, "
                   "double *restrict tab)", tab)
    desc = describe(elem)
    assert list(desc.shape_dof) == list(shape_dof)
    c += element_descriptor(desc)
    return htxt, "\n".join(c)


def pair_source(elem, elem_path, mat, mat_path):
    name = f"{elem.name}_{mat.NAME}"
    nd = elem.ndof
    h = input_hash([elem_path, mat_path] + family_paths(elem) + core_paths())
    mod = cable
    ntab = mod.tab_layout()
    sig = {
        "energy": f"double {name}_full_energy(const double *restrict q, const double *restrict tab, const double *restrict mat)",
        "force": f"void {name}_full_force(const double *restrict q, const double *restrict tab, const double *restrict mat, double *restrict f)",
        "tangent": f"void {name}_full_force_tangent(const double *restrict q, const double *restrict tab, const double *restrict mat, double *restrict f, double *restrict K)",
    }
    c = [f"/* {BANNER} (see {name}.h) */", f'#include "{name}.h"', f'#include "{elem.name}.h"',
         "#include <math.h>", '#include "rod_math.h"'] + version_guard() + [""]
    ops = {}
    for want in ("energy", "force", "tangent"):
        prog, params = mod.body_program(elem, mat, want)
        low = lower(prog, params.values())
        pro, body = count_lowered(low)
        body += pro
        ops[want] = body
        if want == "energy":
            c += [sig[want], "{", "    double e;"] + _prologue(low, "    ") + _block(low, "    ") + ["    return e;", "}", ""]
        elif want == "force":
            c += _function(sig[want], low, [f"for (int i = 0; i < {nd}; ++i) f[i] = 0.0;"])
        else:
            c += _function(sig[want], low, [f"for (int i = 0; i < {nd}; ++i) f[i] = 0.0;",
                                            f"for (int i = 0; i < {nd * nd}; ++i) K[i] = 0.0;"])
            c[-2:-2] = [f"    for (int r = 1; r < {nd}; ++r)",
                        f"        for (int c = 0; c < r; ++c) K[r * {nd} + c] = K[c * {nd} + r];"]
    nqp = cable.NGAUSS
    sprog, sparams = cable.section_program(elem, mat)
    sig["sections"] = (f"void {name}_full_sections(const double *restrict geom, const double *restrict q, "
                       "const double *restrict tab, const double *restrict mat, double *restrict sec)")
    c += _function(sig["sections"], lower(sprog, sparams.values()), ["(void)geom;"])
    pd = _full_pair(elem, mat, ntab, nqp, ops)
    pd = replace(pd, functions={**pd.functions, "sections": f"{name}_full_sections"}, sample_xi=cable.sample_xi(),
                 sample_source="law+dM/ds")
    c += pair_descriptors(mat.PARAMS, [pd])
    hdr = [f"/* {BANNER}", f" * pair: {elem.name} x {mat.NAME} -- {elem.title}; {mat.TITLE}",
           f" * generator inputs: gen/elements/{Path(elem_path).name}, gen/materials/{Path(mat_path).name}, "
           f"{', '.join('gen/' + f for f in FAMILY_FILES[elem.kind])} + gen core",
           f" * input hash: sha256:{h}", " *",
           " * Computes for one element: U (energy, J), f = dU/dq, K = df/dq.",
           f" * Inputs:  q[{nd}] ({', '.join(f'{n}@{d}' for n, d, _ in elem.fields())})",
           f" *          tab[{ntab}] from {elem.name}_full_tabulate(geom, q0)",
           f" *          mat[{len(mat.PARAMS)}] = {{{', '.join(mat.PARAMS)}}}",
           f" * Outputs: f[{nd}]; K[{nd}*{nd}] row-major, upper triangle computed, mirrored.",
           f" * Operations per element call ({nqp} Gauss points): energy {ops['energy']}; force {ops['force']};",
           f" *   force + upper tangent {ops['tangent']}",
           " * Section resultants (bk_pair.sections) at the Gauss points: n = G W_a - d/dx (G W_b),",
           " *   m = r' x G W_b (a = r', b = r'', G = |r0'|; gen/cable.py section_program), global axes.", " */"]
    htxt = "\n".join(hdr) + f"""
#ifndef BK_GEN_{name.upper()}_H
#define BK_GEN_{name.upper()}_H
#include "bk_kernel.h"

extern const bk_pair bk_pair_{name}_full;
""" + "\n".join(s + ";" for s in sig.values()) + "\n\n#endif\n"
    return htxt, "\n".join(c), None
