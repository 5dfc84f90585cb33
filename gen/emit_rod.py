"""C emission for the geometrically exact rods' element and pair files (gef,
euler_bernoulli, kirchhoff; gen/rod.py): small files that call the shared
kinematics (gen/emit_rod_shared.py) and add the material law at the Gauss points."""
from dataclasses import replace
from pathlib import Path

import sympy as sp

from gen import rod, rod_energy
from gen.c_functions import _block, _function, _prologue
from gen.descriptor import ElementDesc, element_descriptor, pair_descriptors, version_guard
from gen.emit_resultant import FAMILY_FILES, _fields, _full_pair, _geom, _line_integrals, family_paths
from gen.emit_rod_shared import SHARED, shared_ops
from gen.program import Ops, Program, c_double, count_lowered, count_ops, lower, print_c
from gen.provenance import BANNER, CORE_FILES, core_paths, input_hash

ROD_CAPS = ("BK_CAP_SECTION_RECTANGLE", "BK_CAP_SECTION_CIRCLE", "BK_CAP_CURVED", "BK_CAP_MOMENT_NODES")


def describe(elem):
    """The descriptor of a rod element (gen/descriptor.py)."""
    return ElementDesc(name=elem.name, title=elem.title, node_xi=tuple(str(x) for x in rod.XI_NODES),
                       ndof=elem.ndof, caps=ROD_CAPS, fields=_fields(elem, 2),
                       shape_dof=tuple(rod.NODE_DOF * n for n in range(3)),
                       functions={"reference": "reference", "shape": "shape", "mass": "mass",
                                  "volume": "volume", "frame": "bk_rod_frame",
                                  "section_frame": "section_frame", "section_line": "section_line",
                                  "moment": "moment",
                                  "rotary": "rotary"})


def element_source(elem, elem_path):
    name = elem.name
    nd = elem.ndof
    h = input_hash([elem_path] + family_paths(elem) + core_paths())
    g = _geom()
    l, A = g["L"], g["A"]
    xi = sp.Symbol("xi", real=True)
    N = rod.lagrange(xi)
    shp = Program()
    for a in range(3):
        shp.output(f"N[{a}]", N[a], op="=")
    mass_low, vol_low = _line_integrals(list(N), xi, l, A)
    ref = Program()
    for n, xn in enumerate(rod.XI_NODES):
        b = rod.NODE_DOF * n
        for i, v in enumerate((xn * l, 0, 0, 1, 0, 0, 0)):
            ref.output(f"q0[{b + i}]", v, op="=")
    for i in range(elem.ninternal):
        ref.output(f"q0[{rod.NQ + i}]", 0, op="=")
    doc = (rod.__doc__ or "").strip().splitlines()
    hdr = [f"/* {BANNER}", f" * element: {name} -- {elem.title}", f" * source: {elem.source}",
           f" * generator inputs: gen/elements/{Path(elem_path).name}, "
           f"{', '.join('gen/' + f for f in FAMILY_FILES[elem.kind])} + gen core ({', '.join(CORE_FILES)})",
           f" * input hash: sha256:{h}", " *"]
    hdr += [" * " + x if x.strip() else " *" for x in doc]
    hdr += [" */"]
    ntab = rod.tab_layout()
    htxt = "\n".join(hdr) + f"""
#ifndef BK_GEN_{name.upper()}_H
#define BK_GEN_{name.upper()}_H
#include "bk_kernel.h"

extern const bk_element bk_element_{name};
/* tab[{ntab}] from the reference coordinates q0 (bk_rod_tabulate, {SHARED}.h) */
void {name}_full_tabulate(const double *restrict geom, const double *restrict q0, double *restrict tab);

#endif
"""
    c = [f"/* {BANNER} (see {name}.h) */", f'#include "{name}.h"', f'#include "{SHARED}.h"'] + version_guard() + [""]
    c += _function("static void shape(const double *restrict geom, double xi, double y, double z, double *restrict N)",
                   lower(shp, ()), ["(void)geom; (void)y; (void)z;"])
    c += _function("static void mass(const double *restrict geom, double *restrict m)", mass_low)
    c += _function("static void volume(const double *restrict geom, double *restrict v)", vol_low)
    c += ["static void section_frame(const double *restrict geom, double xi, const double *restrict q, "
          "double *restrict R, double *restrict dR)", "{",
          f"    bk_rod_section_frame({nd}, geom, xi, q, R, dR);", "}", ""]
    c += ["static void section_line(const double *restrict geom, double xi, const double *restrict q, "
          "const double *restrict a, const double *restrict u, double *restrict t, double *restrict dt, "
          "double *restrict H)", "{", f"    bk_rod_section_line({nd}, geom, xi, q, a, u, t, dt, H);", "}", ""]
    c += ["static void moment(const double *restrict geom, double xi, const double *restrict q, "
          "const double *restrict M, double *restrict Q, double *restrict dQ)", "{",
          "    (void)geom;", f"    bk_rod_moment({nd}, xi, q, M, Q, dQ);", "}", ""]
    c += _function("static void reference(const double *restrict geom, double *restrict q0)", lower(ref, ()),
                   ["(void)geom;"])
    c += ["static void rotary(const double *restrict geom, const double *restrict q, "
          "const double *restrict qd, const double *restrict qdd, double *restrict f, "
          "double *restrict Mq, double *restrict Cq, double *restrict Kq, double *restrict T)", "{",
          f"    bk_rod_rotary({nd}, geom, q, qd, qdd, f, Mq, Cq, Kq, T);", "}", ""]
    c += [f"void {name}_full_tabulate(const double *restrict geom, const double *restrict q0, "
          "double *restrict tab)", "{", "    bk_rod_tabulate(geom, q0, tab);", "}", ""]
    c += element_descriptor(describe(elem))
    return htxt, "\n".join(c)


def _renamed(low, prefix):
    """The lowered program with its CSE temporaries x<k> renamed <prefix><k> (two
    programs inlined in one C scope)."""
    from gen.program import Lowered
    names = [s for s, _ in low.prologue + low.body if s.name.startswith("x") and s.name[1:].isdigit()]
    sub = {s: sp.Symbol(prefix + s.name[1:], real=True) for s in names}

    def r(pairs):
        return [(sub.get(s, s), e.xreplace(sub)) for s, e in pairs]
    return Lowered(r(low.prologue), r(low.body), [(t, op, e.xreplace(sub)) for t, op, e in low.outputs])


def pair_source(elem, elem_path, mat, mat_path):
    name = f"{elem.name}_{mat.NAME}"
    nd = elem.ndof
    nq = rod.NQ
    nc = len(elem.constrained)
    ng = len(rod.GAUSS)
    ntab = rod.tab_layout()
    h = input_hash([elem_path, mat_path] + family_paths(elem) + core_paths())
    progs, params = rod_energy.material_programs(elem, mat)
    force_only = Program()                        # without Gv = B^T sg: the force forms no B
    force_only.defs = list(progs["force"].defs)
    force_only.outputs = [o for o in progs["force"].outputs if not o[0].startswith("Gv[")]
    hoist = params.values()
    low = {"energy": lower(progs["energy"], hoist), "force": lower(force_only, hoist),
           "force_t": lower(progs["force"], hoist), "tangent": _renamed(lower(progs["tangent"], hoist), "y")}
    cg = print_c(rod_energy.gauge_coefficient(params))
    sh = shared_ops()

    def total(calls, mats):
        o = Ops()
        for fn, n in calls:
            for _ in range(n):
                o += sh[fn]
        for key, n in mats:
            pro, body = count_lowered(low[key])
            o += pro
            for _ in range(n):
                o += body
        return o

    gc = Ops(mul=1, div=3)                         # bk_rod_gauss_c
    cg_ops = count_ops(rod_energy.gauge_coefficient(params))
    ops = {
        "energy": total([("psi", 1), ("v", ng), ("strain", ng), ("gauge_energy", 1)], [("energy", ng)]),
        "force": total([("psi_j", 1), ("v", ng), ("strain", ng), ("strain_grad", ng), ("grad_v2z", ng), ("grad_z2q", 1),
                        ("gauge_force", 1)], [("force", ng)]),
        "tangent": total([("psi_j", 1), ("v", ng), ("strain_b", ng), ("strain_geo", ng), ("grad_v2z", ng * (1 + nc)),
                          ("hess_v2z", ng), ("grad_z2q", 1 + ng * nc), ("gauge_force", 1), ("psi_hc", 1),
                          ("hess_z2q", 1), ("gauge_tangent", 1)], [("force_t", ng), ("tangent", ng)]),
    }
    for o in ops.values():
        for _ in range(ng):
            o += gc
        o += cg_ops
    ops["energy"].add += ng                         # e += per point
    sig = {
        "energy": f"double {name}_full_energy(const double *restrict q, const double *restrict tab, const double *restrict mat)",
        "force": f"void {name}_full_force(const double *restrict q, const double *restrict tab, const double *restrict mat, double *restrict f)",
        "tangent": f"void {name}_full_force_tangent(const double *restrict q, const double *restrict tab, const double *restrict mat, double *restrict f, double *restrict K)",
    }

    def point(want, lows):
        """Loop over the Gauss points with the given material blocks inlined."""
        out = [f"    for (int g = 0; g < {ng}; ++g) {{"]
        decl = "double c[5], v[13], s[6]"
        if want != "energy":
            decl += ", sg[6], Gv[13]"
        if want == "tangent":
            decl += ", B[78], Hv[91]" + (f", C[{13 * nc}]" if nc else "")
        out += [f"        {decl};", "        const double w = bk_rod_gauss_c(g, l, c);"]
        if nc:
            out.append(f"        const double *restrict lam = q + {nq} + {nc} * g;")
            if want != "energy":
                out.append(f"        double *restrict fl = f + {nq} + {nc} * g;")
        out.append("        bk_rod_v(c, q, psi, v);")
        if want == "energy":
            out.append("        bk_rod_strain(v, tab + 1 + 6 * g, s);")
            out += _block(lows[0], "        ")
        elif want == "force":
            out.append("        bk_rod_strain(v, tab + 1 + 6 * g, s);")
            out += _block(lows[0], "        ")
            out += ["        bk_rod_strain_grad(v, sg, Gv);", "        bk_rod_grad_v2z(c, Gv, Gz);"]
        else:
            out.append("        bk_rod_strain_b(v, tab + 1 + 6 * g, s, B);")
            out += _block(lows[0], "        ")
            if want == "tangent":
                out.append("        bk_rod_strain_geo(v, sg, Hv);")
                out += _block(lows[1], "        ")
            out.append("        bk_rod_grad_v2z(c, Gv, Gz);")
            if want == "tangent":
                out.append("        bk_rod_hess_v2z(c, Hv, Hz);")
                if nc:
                    out += [f"        for (int j = 0; j < {nc}; ++j) {{",
                            f"            double Cz[{rod.NZ}] = {{0.0}}, Cq[{nq}];",
                            "            bk_rod_grad_v2z(c, C + 13 * j, Cz);",
                            "            bk_rod_grad_z2q(J, Cz, Cq);",
                            f"            for (int i = 0; i < {nq}; ++i) K[{nd} * i + {nq} + {nc} * g + j] = Cq[i];",
                            "        }"]
        return out + ["    }"]

    c = [f"/* {BANNER} (see {name}.h) */", f'#include "{name}.h"', f'#include "{elem.name}.h"',
         f'#include "{SHARED}.h"'] + version_guard() + [""]
    # energy
    c += [sig["energy"], "{", "    const double l = tab[0];", "    double e = 0.0, psi[6];"]
    c += _prologue(low["energy"], "    ") + ["    bk_rod_psi(q, psi);"]
    c += point("energy", [low["energy"]])
    c += [f"    e += bk_rod_gauge_energy(q, {cg});", "    return e;", "}", ""]
    # force
    c += [sig["force"], "{", "    const double l = tab[0];", f"    double psi[6], J[48], Gz[{rod.NZ}] = {{0.0}};"]
    c += _prologue(low["force"], "    ") + ["    bk_rod_psi_j(q, psi, J);"]
    c += point("force", [low["force"]])
    c += ["    bk_rod_grad_z2q(J, Gz, f);", f"    bk_rod_gauge_force(q, {cg}, f);", "}", ""]
    # force + tangent
    c += [sig["tangent"], "{", "    const double l = tab[0];", f"    const double cg = {cg};",
          f"    double psi[6], J[48], Hc[72], Gz[{rod.NZ}] = {{0.0}}, Hz[{len(rod.tri(rod.NZ))}] = {{0.0}};",
          f"    for (int i = 0; i < {nd * nd}; ++i) K[i] = 0.0;"]
    c += _prologue(low["force_t"], "    ") + _prologue(low["tangent"], "    ") + ["    bk_rod_psi_j(q, psi, J);"]
    c += point("tangent", [low["force_t"], low["tangent"]])
    c += ["    bk_rod_grad_z2q(J, Gz, f);", "    bk_rod_gauge_force(q, cg, f);",
          "    bk_rod_psi_hc(q, Gz, Hc);", f"    bk_rod_hess_z2q({nd}, J, Hc, Hz, K);",
          f"    bk_rod_gauge_tangent({nd}, q, cg, K);",
          f"    for (int r = 1; r < {nd}; ++r)",
          f"        for (int c = 0; c < r; ++c) K[r * {nd} + c] = K[c * {nd} + r];", "}", ""]
    # section resultants at the Gauss points
    sprog, _ = rod_energy.section_program(elem, mat)
    slow = lower(sprog, hoist)
    sig["sections"] = (f"void {name}_full_sections(const double *restrict geom, const double *restrict q, "
                       "const double *restrict tab, const double *restrict mat, double *restrict sec)")
    xg = [float(x) for x, _ in rod.GAUSS]
    c += [sig["sections"], "{", "    const double l = tab[0];",
          f"    static const double xg[{ng}] = {{{', '.join(c_double(x) for x in xg)}}};", "    double psi[6];"]
    c += _prologue(slow, "    ") + ["    bk_rod_psi(q, psi);", f"    for (int g = 0; g < {ng}; ++g) {{",
                                    "        double c[5], v[13], s[6], rs[6], d[9];",
                                    "        double *restrict o = sec + 9 * g;"]
    if nc:
        c.append(f"        const double *restrict lam = q + {nq} + {nc} * g;")
    c += ["        (void)bk_rod_gauss_c(g, l, c);", "        bk_rod_v(c, q, psi, v);",
          "        bk_rod_strain(v, tab + 1 + 6 * g, s);"]
    c += _block(slow, "        ")
    c += ["        bk_rod_frame(geom, xg[g], q, o, d);",
          "        for (int i = 0; i < 3; ++i) {",
          "            o[3 + i] = rs[0] * d[6 + i] + rs[1] * d[i] + rs[2] * d[3 + i];",
          "            o[6 + i] = rs[3] * d[6 + i] + rs[4] * d[i] + rs[5] * d[3 + i];",
          "        }", "    }", "}", ""]
    pd = _full_pair(elem, mat, ntab, ng, ops)
    pd = replace(pd, functions={**pd.functions, "sections": f"{name}_full_sections"}, sample_xi=tuple(xg),
                 sample_source=rod_energy.section_source_label(elem))
    c += pair_descriptors(mat.PARAMS, [pd])
    hdr = [f"/* {BANNER}", f" * pair: {elem.name} x {mat.NAME} -- {elem.title}; {mat.TITLE}",
           f" * generator inputs: gen/elements/{Path(elem_path).name}, gen/materials/{Path(mat_path).name}, "
           f"{', '.join('gen/' + f for f in FAMILY_FILES[elem.kind])} + gen core",
           f" * input hash: sha256:{h}", " *",
           " * Computes for one element: U (energy, J), f = dU/dq, K = df/dq: the material law as a",
           f" * function of the strains at each Gauss point, the kinematics from {SHARED}.c.",
           f" * Inputs:  q[{nd}] ({', '.join(f'{n}@{d}' for n, d, _ in elem.fields())})",
           f" *          tab[{ntab}] from {elem.name}_full_tabulate(geom, q0)",
           f" *          mat[{len(mat.PARAMS)}] = {{{', '.join(mat.PARAMS)}}}",
           f" * Outputs: f[{nd}]; K[{nd}*{nd}] row-major, upper triangle computed, mirrored.",
           f" * Operations per element call ({ng} Gauss points): energy {ops['energy']}; force {ops['force']};",
           f" *   force + upper tangent {ops['tangent']}",
           " * Section resultants (bk_pair.sections): n = R C Gamma, m = R D K at the Gauss points",
           f" *   ({rod_energy.section_source_label(elem)}; components held at zero: EA times their multiplier), global axes.",
           " */"]
    htxt = "\n".join(hdr) + f"""
#ifndef BK_GEN_{name.upper()}_H
#define BK_GEN_{name.upper()}_H
#include "bk_kernel.h"

extern const bk_pair bk_pair_{name}_full;
""" + "\n".join(s + ";" for s in sig.values()) + "\n\n#endif\n"
    return htxt, "\n".join(c), None
