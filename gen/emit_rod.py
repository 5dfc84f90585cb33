"""C emission for the resultant beam families: geometrically exact rods (gef,
euler_bernoulli, kirchhoff; gen/rod.py) and the ANCF cable (gen/cable.py)."""
from functools import lru_cache
from pathlib import Path

import sympy as sp

from gen import cable, contract, rod
from gen.descriptor import ElementDesc, Field, PairDesc, element_descriptor, pair_descriptors, version_guard
from gen.element import geom_symbol
from gen.emit import BANNER, CORE_FILES, _block, _function, _prologue, core_paths, input_hash
from gen.loads import axis_moment
from gen.program import Ops, Program, c_double, count_lowered, count_ops, lower, print_c

FAMILY_FILES = {"rod": ("rod.py", "chain.py", "emit_rod.py"), "cable": ("cable.py", "emit_rod.py")}
GEN_DIR = Path(__file__).resolve().parent


def family_paths(elem):
    return [GEN_DIR / f for f in FAMILY_FILES[elem.kind]]


def _geom():
    """{slot name: symbol geom[BK_GEOM_<slot>]}."""
    return {k: geom_symbol(k) for k in contract.geom_slots()}


CABLE_CAPS = ("BK_CAP_SECTION_RECTANGLE", "BK_CAP_SECTION_CIRCLE", "BK_CAP_MOMENT_NO_TORSION")
ROD_CAPS = ("BK_CAP_SECTION_RECTANGLE", "BK_CAP_SECTION_CIRCLE", "BK_CAP_CURVED", "BK_CAP_MOMENT_NODES")


def _fields(elem, per_node):
    """Field descriptors from elem.fields() [(name, dof, dim)]: the first
    per_node * nnode are nodal, the rest element-internal."""
    return tuple(Field(n, d, k, i // per_node if i < per_node * elem.nnode else -1)
                 for i, (n, d, k) in enumerate(elem.fields()))


def describe(elem):
    """The descriptor of a cable or rod element (gen/descriptor.py)."""
    if elem.kind == "rod":
        return ElementDesc(name=elem.name, title=elem.title, node_xi=tuple(str(x) for x in rod.XI_NODES),
                           ndof=elem.ndof, caps=ROD_CAPS, fields=_fields(elem, 2),
                           shape_dof=tuple(rod.NODE_DOF * n for n in range(3)),
                           functions={"reference": "reference", "shape": "shape", "mass": "mass",
                                      "volume": "volume", "frame": "bk_rod_frame",
                                      "section_frame": "section_frame", "moment": "moment",
                                      "rotary": "rotary"})
    return ElementDesc(name=elem.name, title=elem.title, node_xi=("0", "1"), ndof=elem.ndof, caps=CABLE_CAPS,
                       fields=_fields(elem, 2), shape_dof=(0, 3, 6, 9),
                       functions={k: k for k in ("reference", "shape", "mass", "volume", "frame", "moment")})


def _line_integrals(N, xi, l, A):
    """mass and volume programs for position shape functions N(xi) on a line of
    length l with cross-section area A."""
    n = len(N)
    mass, vol = Program(), Program()
    for a in range(n):
        for b in range(a, n):
            e = sp.factor(A * l * sp.integrate(sp.expand(N[a] * N[b]), (xi, 0, 1)))
            mass.output(f"m[{a * n + b}]", e, op="=")
            if b != a:
                mass.output(f"m[{b * n + a}]", e, op="=")
        vol.output(f"v[{a}]", sp.factor(A * l * sp.integrate(N[a], (xi, 0, 1))), op="=")
    return lower(mass, ()), lower(vol, ())


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
    if elem.kind == "rod":
        return _rod_element_source(elem, elem_path)
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
    c += _function(f"void {name}_full_tabulate(const double *restrict geom, const double *restrict q0, "
                   "double *restrict tab)", tab, ["(void)q0;"])
    desc = describe(elem)
    assert list(desc.shape_dof) == list(shape_dof)
    c += element_descriptor(desc)
    return htxt, "\n".join(c)


def pair_source(elem, elem_path, mat, mat_path):
    if elem.kind == "rod":
        return _rod_pair_source(elem, elem_path, mat, mat_path)
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
    from dataclasses import replace
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
           " * Section resultants (bk_pair.sections) at the Gauss points: n = W_a - d/dx W_b, m = r' x W_b",
           " *   (a = r', b = r''; gen/cable.py section_program), global axes.", " */"]
    htxt = "\n".join(hdr) + f"""
#ifndef BK_GEN_{name.upper()}_H
#define BK_GEN_{name.upper()}_H
#include "bk_kernel.h"

extern const bk_pair bk_pair_{name}_full;
""" + "\n".join(s + ";" for s in sig.values()) + "\n\n#endif\n"
    return htxt, "\n".join(c), None


def _full_pair(elem, mat, ntab, nqp, ops):
    """The one pair ("full" integration) of a cable or rod element file."""
    name = f"{elem.name}_{mat.NAME}"
    return PairDesc(element=elem.name, material=mat.NAME, integration="full", ntab=ntab, nqp=nqp,
                    ops_force=ops["force"].total(), ops_force_tangent=ops["tangent"].total(),
                    functions={"tabulate": f"{elem.name}_full_tabulate", "energy": f"{name}_full_energy",
                               "force": f"{name}_full_force", "force_tangent": f"{name}_full_force_tangent"})


# ----------------------------------------------------------------------------
# Geometrically exact rods: one shared kinematics file for the three elements,
# small element and pair files that call it.

# The shared code is split in three files of similar compile time so that the two
# compile jobs of a solver build (gen/solver_build.py) run side by side on a
# first use:
#   rod_strain   the Gauss point: v from z, strains, B = ds/dv, the geometric
#                term, the pull-back v -> z
#   rod_common   the nodes: psi = log(conj(p_c) p_i) and its derivatives, the
#                pull-back z -> q, the gauge penalty, tabulate, frame, moments
#                (its header includes the other two: the one the element and
#                pair files include)
#   rod_inertia  rotary inertia lumped at the nodes
SHARED = "rod_common"
SHARED_UNITS = ("rod_strain", "rod_inertia", "rod_common")
SHARED_FILES = ("rod.py", "chain.py", "emit_rod.py")
_STRAIN_FNS = ("v", "strain", "strain_b", "strain_grad", "strain_geo", "grad_v2z", "hess_v2z")

_D = "const double *restrict"
_W = "double *restrict"


def shared_paths():
    return [GEN_DIR / f for f in SHARED_FILES]


def kernel_files(elem):
    """Generated C files a pair of this element family links besides its own
    element and pair files (index.json "files")."""
    return [f"{u}.c" for u in SHARED_UNITS] if elem.kind == "rod" else []


def _shared_programs():
    """[(name, signature, program builder, doc)] of the generated shared functions."""
    t8 = len(rod.tri(rod.NX))
    items = [
        ("psi", f"void bk_rod_psi({_D} q, {_W} psi)", lambda: rod.psi_program(0),
         "psi[6] = (psi_0, psi_2), psi_i = log(conj(p_c) p_i), from the element coordinates q."),
        ("psi_j", f"void bk_rod_psi_j({_D} q, {_W} psi, {_W} J)", lambda: rod.psi_program(1),
         f"psi[6] and J[{6 * rod.NX}]: J[8 (3a + k) + b] = d psi_a,k / d x_b, x = q at "
         f"PSI_Q[a] = {{{', '.join(map(str, rod.PSI_Q[0]))}}} (a = 0), {{{', '.join(map(str, rod.PSI_Q[1]))}}} (a = 1)."),
        ("psi_hc", f"void bk_rod_psi_hc({_D} q, {_D} Gz, {_W} Hc)", lambda: rod.psi_hessian_program(),
         f"Hc[{2 * t8}]: Hc[{t8} a + tri8(b, c)] = sum_k Gz[13 + 3a + k] d2 psi_a,k / dx_b dx_c."),
        ("v", f"void bk_rod_v({_D} c, {_D} q, {_D} psi, {_W} v)", lambda: rod.v_program(),
         "v[13] = (r', p_c, psi, psi') at a Gauss point with coefficients c[5] (bk_rod_gauss_c)."),
        ("strain", f"void bk_rod_strain({_D} v, {_D} t0, {_W} s)", lambda: rod.strain_program(0),
         "s[6] = (Gamma, K) - t0 at a Gauss point."),
        ("strain_b", f"void bk_rod_strain_b({_D} v, {_D} t0, {_W} s, {_W} B)", lambda: rod.strain_program(1),
         f"s[6] and B[78] = ds/dv (row-major 6 x 13; {len(rod.b_pattern())} structural nonzeros, zeros written)."),
        ("strain_grad", f"void bk_rod_strain_grad({_D} v, {_D} sg, {_W} Gv)", lambda: rod.strain_gradient_program(),
         "Gv[13] = sum_k sg[k] ds_k/dv (= B^T sg, without forming B)."),
        ("strain_geo", f"void bk_rod_strain_geo({_D} v, {_D} sg, {_W} Hv)", lambda: rod.geometric_program(),
         "Hv[91] = sum_k sg[k] d2 s_k / dv2 (upper triangle of 13 x 13, packed by rows)."),
        ("grad_v2z", f"void bk_rod_grad_v2z({_D} c, {_D} Gv, {_W} Gz)", lambda: rod.grad_v2z_program(),
         "Gz[19] += P^T Gv: a gradient in v (13) accumulated in z (19), v = P(c) z."),
        ("hess_v2z", f"void bk_rod_hess_v2z({_D} c, {_D} Hv, {_W} Hz)", lambda: rod.hess_v2z_program(),
         "Hz[190] += P^T Hv P (upper triangles: 13 x 13 packed into 19 x 19 packed)."),
        ("grad_z2q", f"void bk_rod_grad_z2q({_D} J, {_D} Gz, {_W} g)", lambda: rod.grad_z2q_program(),
         "g[21] = dz/dq^T Gz (J from bk_rod_psi_j)."),
        ("hess_z2q", f"void bk_rod_hess_z2q(int nd, {_D} J, {_D} Hc, {_D} Hz, {_W} K)", lambda: rod.hess_z2q_program(),
         "K[nd i + j] = (dz/dq^T Hz dz/dq)_ij + Hc, 0 <= i <= j < 21 (the rest of K untouched)."),
        ("gauge_energy", f"double bk_rod_gauge_energy({_D} q, double cg)", lambda: rod.gauge_program(0),
         "Quaternion gauge penalty sum_n w_n cg/4 (|p_n|^2 - 1)^2, w = (1/2, 1, 1/2)."),
        ("gauge_force", f"void bk_rod_gauge_force({_D} q, double cg, {_W} f)", lambda: rod.gauge_program(1),
         "f[21] += its gradient."),
        ("gauge_tangent", f"void bk_rod_gauge_tangent(int nd, {_D} q, double cg, {_W} K)", lambda: rod.gauge_program(2),
         "K[nd i + j] += its Hessian, i <= j < 21."),
    ]
    return items


@lru_cache(maxsize=None)
def _lowered(name):
    builder = next(b for n, _, b, _ in _shared_programs() if n == name)
    return lower(builder(), ())


def _shared_list(names=None):
    """[(name, signature, lowered, doc)], all or those in names."""
    return [(n, sig, _lowered(n), doc) for n, sig, _, doc in _shared_programs() if names is None or n in names]


def _ops(low):
    pro, body = count_lowered(low)
    body += pro
    return body


def _gen_fn(sig, low, pre=(), post=(), ret=None):
    out = [sig, "{"] + [f"    {x}" for x in pre]
    if ret:
        out.append(f"    double {ret};")
    out += _prologue(low, "    ") + _block(low, "    ") + [f"    {x}" for x in post]
    if ret:
        out.append(f"    return {ret};")
    return out + ["}", ""]


def shared_ops():
    """{function name: Ops} of the generated shared functions."""
    return {n: _ops(low) for n, _, low, _ in _shared_list()}


def shared_source(unit=SHARED):
    """(header, source) of out/kernels/<unit>.{h,c}, unit in SHARED_UNITS."""
    h = input_hash(shared_paths() + core_paths())
    if unit == "rod_inertia":
        return _inertia_source(h, lower(rod.rotary_node_program(), ()))
    strain = unit == "rod_strain"
    progs = _shared_list(
        [n for n, _, _, _ in _shared_programs() if (n in _STRAIN_FNS) == strain])
    gt = rod.gauss_table()
    ng = len(gt)
    what = ("Gauss-point strain kinematics" if strain else
            "nodal rotations, pull-back to q, element-level functions")
    hdr = [f"/* {BANNER}",
           f" * shared kinematics of the geometrically exact rods (gef, euler_bernoulli, kirchhoff): {what}",
           f" * generator inputs: {', '.join('gen/' + f for f in SHARED_FILES)} + gen core ({', '.join(CORE_FILES)})",
           f" * input hash: sha256:{h}", " *",
           " * One object for all three elements and every material: their element and pair",
           " * kernels (out/kernels/<element>.c, <element>_<material>.c) call these functions;",
           " * rod_strain.c, rod_common.c, rod_inertia.c are three files so that they compile in parallel.",
           " * Layouts (gen/rod.py):",
           " *   q[21+]   element coordinates, node n: r at 7n, quaternion p at 7n + 3 (p_c = node 1)",
           " *   z[19]    (r_0, r_1, r_2, p_c, psi_0, psi_2), psi_i = log(conj(p_c) p_i)",
           " *   v[13]    (r', p_c, psi, psi') at a Gauss point: v = P(c) z",
           " *   s[6]     (Gamma - Gamma0, K - K0), material components",
           " *   t0[6]    (Gamma0, K0) of the point, tab + 1 + 6 g of bk_rod_tabulate",
           " *   tri_n    upper triangles packed by rows: (i, j), i <= j, at i n - i (i - 1)/2 + j - i",
           " * Operations per call (add + mul + div + call):"]
    for n, _, low, _ in progs:
        hdr.append(f" *   bk_rod_{n:<14} {_ops(low)}")
    hdr += [" */", f"#ifndef BK_GEN_{unit.upper()}_H", f"#define BK_GEN_{unit.upper()}_H", ""]
    if strain:
        hdr += [f"/* Gauss points g = 0..{ng - 1}: (N_0, N_2, N_0', N_1', N_2', weight) at xi_g (Lagrange, d/dxi) */",
                f"extern const double bk_rod_gauss[{ng}][6];", "",
                "/* c[5] = (N_0, N_2, N_0'/l, N_1'/l, N_2'/l) of Gauss point g for length l; returns weight x l */",
                f"static inline double bk_rod_gauss_c(int g, double l, {_W} c)", "{",
                "    const double *t = bk_rod_gauss[g];",
                "    c[0] = t[0];", "    c[1] = t[1];", "    c[2] = t[2] / l;", "    c[3] = t[3] / l;",
                "    c[4] = t[4] / l;", "    return t[5] * l;", "}", ""]
    else:
        hdr += ['#include "rod_strain.h"', '#include "rod_inertia.h"', ""]
    for n, sig, low, doc in progs:
        hdr += [f"/* {doc} */", sig + ";"]
    if not strain:
        hdr += ["/* tab[13] = (l, then per Gauss point Gamma0[3], K0[3]) of the reference coordinates q0 */",
                f"void bk_rod_tabulate({_D} geom, {_D} q0, {_W} tab);",
                "/* Centreline position pos[3] and section frame d[9] = (d1, d2, d3) at xi */",
                f"void bk_rod_frame({_D} geom, double xi, {_D} q, {_W} pos, {_W} d);",
                "/* Section frame R[9] = (d1, d2, d3) of bk_rod_frame at xi and, when dR is not NULL, its",
                " * Jacobian dR[9*nd], dR[nd k + j] = dR_k/dq_j (bk_element.section_frame) */",
                f"void bk_rod_section_frame(int nd, {_D} geom, double xi, {_D} q, {_W} R, {_W} dR);",
                "/* Moment M[3] fixed in space on the quaternion of the node nearest xi: Q[nd], dQ[nd*nd] */",
                f"void bk_rod_moment(int nd, double xi, {_D} q, {_D} M, {_W} Q, {_W} dQ);"]
    hdr += ["", "#endif", ""]
    c = [f"/* {BANNER} (see {unit}.h) */", f'#include "{unit}.h"', "#include <math.h>",
         '#include "rod_math.h"'] + version_guard() + [""]
    if strain:
        c += [f"const double bk_rod_gauss[{ng}][6] = {{"]
        c += [f"    {{{', '.join(c_double(x) for x in row)}}}," for row in gt]
        c += ["};", ""]
    for n, sig, low, _ in progs:
        c += _gen_fn(sig, low, ret="ge" if sig.startswith("double") else None)
    if strain:
        return "\n".join(hdr), "\n".join(c)
    c += [f"void bk_rod_tabulate({_D} geom, {_D} q0, {_W} tab)", "{",
          "    const double zero[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};",
          "    double psi[6];",
          "    tab[0] = geom[BK_GEOM_L];",
          "    bk_rod_psi(q0, psi);",
          f"    for (int g = 0; g < {ng}; ++g) {{",
          "        double c[5], v[13];",
          "        (void)bk_rod_gauss_c(g, geom[BK_GEOM_L], c);",
          "        bk_rod_v(c, q0, psi, v);",
          "        bk_rod_strain(v, zero, tab + 1 + 6 * g);",
          "    }", "}", ""]
    fr, mom = lower(rod.frame_program(), ()), lower(rod.moment_node_program(), ())
    c += _gen_fn(f"void bk_rod_frame({_D} geom, double xi, {_D} q, {_W} pos, {_W} d)", fr,
                 ["(void)geom;", "double psi[6];", "bk_rod_psi(q, psi);"])
    sf_r, sf_j = (lower(rod.section_frame_program(j), ()) for j in (False, True))
    c += [f"void bk_rod_section_frame(int nd, {_D} geom, double xi, {_D} q, {_W} R, {_W} dR)", "{",
          "    (void)geom;", "    double psi[6], J[48];", "    if (!dR) {", "        bk_rod_psi(q, psi);"]
    c += _prologue(sf_r, "        ") + _block(sf_r, "        ") + ["        return;", "    }"]
    c += ["    bk_rod_psi_j(q, psi, J);", "    for (int i = 0; i < 9 * nd; ++i) dR[i] = 0.0;"]
    c += _prologue(sf_j, "    ") + _block(sf_j, "    ") + ["}", ""]
    c += _gen_fn(f"static void moment_node({_D} p, {_D} M, {_W} Q, {_W} dQ)", mom)
    c += [f"void bk_rod_moment(int nd, double xi, {_D} q, {_D} M, {_W} Q, {_W} dQ)", "{",
          "    double Qn[4], dQn[16];",
          "    const int b = 7 * (xi < 0.25 ? 0 : xi < 0.75 ? 1 : 2) + 3;",
          "    for (int i = 0; i < nd; ++i) Q[i] = 0.0;",
          "    for (int i = 0; i < nd * nd; ++i) dQ[i] = 0.0;",
          "    moment_node(q + b, M, Qn, dQn);",
          "    for (int i = 0; i < 4; ++i) {",
          "        Q[b + i] = Qn[i];",
          "        for (int j = 0; j < 4; ++j) dQ[(b + i) * nd + b + j] = dQn[4 * i + j];",
          "    }", "}", ""]
    return "\n".join(hdr), "\n".join(c)


def _inertia_source(h, rot):
    hdr = [f"/* {BANNER}",
           " * shared rotary inertia of the geometrically exact rods (gef, euler_bernoulli, kirchhoff)",
           f" * generator inputs: {', '.join('gen/' + f for f in SHARED_FILES)} + gen core ({', '.join(CORE_FILES)})",
           f" * input hash: sha256:{h}", " *",
           " * Per node n (quaternion p at 7n + 3, weight w_n = 1/6, 2/3, 1/6), per unit density:",
           " *   T = 1/2 W^T diag(Jn) W, W = 2 Im(conj(p) p')/|p|^2 (body angular velocity),",
           " *   Jn = w_n l (Ip, I1, I2) = w_n geom[BK_GEOM_L] (geom[BK_GEOM_IP], geom[BK_GEOM_I1], geom[BK_GEOM_I2]);",
           " *   f = d/dt dT/dp' - dT/dp, Mq = df/dp'', Cq = df/dp', Kq = df/dp.",
           f" * Operations per node: {_ops(rot)}",
           " */", "#ifndef BK_GEN_ROD_INERTIA_H", "#define BK_GEN_ROD_INERTIA_H", "",
           "/* Rotary inertia lumped at the nodes (weights l/6, 2l/3, l/6) per unit density, see",
           " * bk_element.rotary: f[nd], Mq, Cq, Kq [nd*nd], T[1] */",
           f"void bk_rod_rotary(int nd, {_D} geom, {_D} q, {_D} qd, {_D} qdd, {_W} f, {_W} Mq, "
           f"{_W} Cq, {_W} Kq, {_W} T);", "", "#endif", ""]
    c = [f"/* {BANNER} (see rod_inertia.h) */", '#include "rod_inertia.h"'] + version_guard() + [""]
    c += _gen_fn(f"static void rotary_node({_D} Jn, {_D} p, {_D} pd, {_D} pdd, {_W} f, {_W} Mq, "
                 f"{_W} Cq, {_W} Kq, {_W} T)", rot)
    c += [f"void bk_rod_rotary(int nd, {_D} geom, {_D} q, {_D} qd, {_D} qdd, {_W} f, {_W} Mq, "
          f"{_W} Cq, {_W} Kq, {_W} T)", "{",
          "    static const double wn[3] = {1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0};",
          "    for (int i = 0; i < nd; ++i) f[i] = 0.0;",
          "    for (int i = 0; i < nd * nd; ++i) Mq[i] = Cq[i] = Kq[i] = 0.0;",
          "    T[0] = 0.0;",
          "    for (int n = 0; n < 3; ++n) {",
          "        const int b = 7 * n + 3;",
          "        const double wl = wn[n] * geom[BK_GEOM_L];",
          "        const double Jn[3] = {wl * geom[BK_GEOM_IP], wl * geom[BK_GEOM_I1], wl * geom[BK_GEOM_I2]};",
          "        double fn[4], Mn[16], Cn[16], Kn[16], Tn;",
          "        rotary_node(Jn, q + b, qd + b, qdd + b, fn, Mn, Cn, Kn, &Tn);",
          "        T[0] += Tn;",
          "        for (int i = 0; i < 4; ++i) {",
          "            f[b + i] = fn[i];",
          "            for (int j = 0; j < 4; ++j) {",
          "                Mq[(b + i) * nd + b + j] = Mn[4 * i + j];",
          "                Cq[(b + i) * nd + b + j] = Cn[4 * i + j];",
          "                Kq[(b + i) * nd + b + j] = Kn[4 * i + j];",
          "            }", "        }", "    }", "}", ""]
    return "\n".join(hdr), "\n".join(c)


def _rod_element_source(elem, elem_path):
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


def _rod_pair_source(elem, elem_path, mat, mat_path):
    name = f"{elem.name}_{mat.NAME}"
    nd = elem.ndof
    nq = rod.NQ
    nc = len(elem.constrained)
    ng = len(rod.GAUSS)
    ntab = rod.tab_layout()
    h = input_hash([elem_path, mat_path] + family_paths(elem) + core_paths())
    progs, params = rod.material_programs(elem, mat)
    force_only = Program()                        # without Gv = B^T sg: the force forms no B
    force_only.defs = list(progs["force"].defs)
    force_only.outputs = [o for o in progs["force"].outputs if not o[0].startswith("Gv[")]
    hoist = params.values()
    low = {"energy": lower(progs["energy"], hoist), "force": lower(force_only, hoist),
           "force_t": lower(progs["force"], hoist), "tangent": _renamed(lower(progs["tangent"], hoist), "y")}
    cg = print_c(rod.gauge_coefficient(params))
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
    cg_ops = count_ops(rod.gauge_coefficient(params))
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
    sprog, _ = rod.section_program(elem, mat)
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
    from dataclasses import replace
    pd = replace(pd, functions={**pd.functions, "sections": f"{name}_full_sections"}, sample_xi=tuple(xg),
                 sample_source=rod.section_source_label(elem))
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
           f" *   ({rod.section_source_label(elem)}; components held at zero: EA times their multiplier), global axes.",
           " */"]
    htxt = "\n".join(hdr) + f"""
#ifndef BK_GEN_{name.upper()}_H
#define BK_GEN_{name.upper()}_H
#include "bk_kernel.h"

extern const bk_pair bk_pair_{name}_full;
""" + "\n".join(s + ";" for s in sig.values()) + "\n\n#endif\n"
    return htxt, "\n".join(c), None
