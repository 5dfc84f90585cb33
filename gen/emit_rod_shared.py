"""C emission of the geometrically exact rods' shared kinematics (gen/rod.py):
out/kernels/rod_strain, rod_common and rod_inertia (.h, .c), one object for the
three elements (gef, euler_bernoulli, kirchhoff) and every material, which their
element and pair files (gen/emit_rod.py) call."""
from functools import lru_cache
from pathlib import Path

import sympy as sp

from gen import rod, rod_energy, rod_frame, rod_inertia, rod_kinematics
from gen.c_functions import _block, _prologue
from gen.descriptor import version_guard
from gen.program import c_double, count_lowered, lower, print_c
from gen.provenance import BANNER, CORE_FILES, core_paths, input_hash

GEN_DIR = Path(__file__).resolve().parent

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
#   rod_line     a line fixed in the sections (tendons, chambers): its tangent
#                and derivatives (bk_element.section_line)
SHARED = "rod_common"
SHARED_UNITS = ("rod_strain", "rod_inertia", "rod_common", "rod_line")
# The generator inputs of the three files (and, with the element and pair
# emitters, of every rod kernel: gen/emit_resultant.py FAMILY_FILES).
SHARED_FILES = ("rod.py", "rod_kinematics.py", "rod_energy.py", "rod_frame.py", "rod_inertia.py", "chain.py",
                "emit_rod_shared.py")
_STRAIN_FNS = ("v", "strain", "strain_b", "strain_grad", "strain_geo", "grad_v2z", "hess_v2z")
_LINE_FNS = ("line", "line_hess0", "line_hess1")

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
        ("psi", f"void bk_rod_psi({_D} q, {_W} psi)", lambda: rod_kinematics.psi_program(0),
         "psi[6] = (psi_0, psi_2), psi_i = log(conj(p_c) p_i), from the element coordinates q."),
        ("psi_j", f"void bk_rod_psi_j({_D} q, {_W} psi, {_W} J)", lambda: rod_kinematics.psi_program(1),
         f"psi[6] and J[{6 * rod.NX}]: J[8 (3a + k) + b] = d psi_a,k / d x_b, x = q at "
         f"PSI_Q[a] = {{{', '.join(map(str, rod.PSI_Q[0]))}}} (a = 0), {{{', '.join(map(str, rod.PSI_Q[1]))}}} (a = 1)."),
        ("psi_hc", f"void bk_rod_psi_hc({_D} q, {_D} Gz, {_W} Hc)", lambda: rod_kinematics.psi_hessian_program(),
         f"Hc[{2 * t8}]: Hc[{t8} a + tri8(b, c)] = sum_k Gz[13 + 3a + k] d2 psi_a,k / dx_b dx_c."),
        ("v", f"void bk_rod_v({_D} c, {_D} q, {_D} psi, {_W} v)", lambda: rod_kinematics.v_program(),
         "v[13] = (r', p_c, psi, psi') at a Gauss point with coefficients c[5] (bk_rod_gauss_c)."),
        ("strain", f"void bk_rod_strain({_D} v, {_D} t0, {_W} s)", lambda: rod_kinematics.strain_program(0),
         "s[6] = (Gamma, K) - t0 at a Gauss point."),
        ("strain_b", f"void bk_rod_strain_b({_D} v, {_D} t0, {_W} s, {_W} B)", lambda: rod_kinematics.strain_program(1),
         f"s[6] and B[78] = ds/dv (row-major 6 x 13; {len(rod_kinematics.b_pattern())} structural nonzeros, zeros written)."),
        ("strain_grad", f"void bk_rod_strain_grad({_D} v, {_D} sg, {_W} Gv)", lambda: rod_kinematics.strain_gradient_program(),
         "Gv[13] = sum_k sg[k] ds_k/dv (= B^T sg, without forming B)."),
        ("strain_geo", f"void bk_rod_strain_geo({_D} v, {_D} sg, {_W} Hv)", lambda: rod_kinematics.geometric_program(),
         "Hv[91] = sum_k sg[k] d2 s_k / dv2 (upper triangle of 13 x 13, packed by rows)."),
        ("grad_v2z", f"void bk_rod_grad_v2z({_D} c, {_D} Gv, {_W} Gz)", lambda: rod_kinematics.grad_v2z_program(),
         "Gz[19] += P^T Gv: a gradient in v (13) accumulated in z (19), v = P(c) z."),
        ("hess_v2z", f"void bk_rod_hess_v2z({_D} c, {_D} Hv, {_W} Hz)", lambda: rod_kinematics.hess_v2z_program(),
         "Hz[190] += P^T Hv P (upper triangles: 13 x 13 packed into 19 x 19 packed)."),
        ("grad_z2q", f"void bk_rod_grad_z2q({_D} J, {_D} Gz, {_W} g)", lambda: rod_kinematics.grad_z2q_program(),
         "g[21] = dz/dq^T Gz (J from bk_rod_psi_j)."),
        ("hess_z2q", f"void bk_rod_hess_z2q(int nd, {_D} J, {_D} Hc, {_D} Hz, {_W} K)", lambda: rod_kinematics.hess_z2q_program(),
         "K[nd i + j] = (dz/dq^T Hz dz/dq)_ij + Hc, 0 <= i <= j < 21 (the rest of K untouched)."),
        ("line", f"void bk_rod_line({_D} v, {_D} a, {_W} t, {_W} Dv)", lambda: rod_frame.line_program(),
         "t[3] = dP/dxi of the line P = r + a[0] d1 + a[1] d2 and Dv[39] = dt/dv (row-major 3 x 13) from "
         "v[13] of bk_rod_v with c = (N_0, N_2, N_0', N_1', N_2') at xi."),
        ("line_hess0", f"void bk_rod_line_hess0({_D} v, {_D} a, {_D} u, {_W} Hv)",
         lambda: rod_frame.line_hessian_program(0),
         "Hv[91] = d2(u . t)/dv2 of bk_rod_line's tangent (upper triangle of 13 x 13, packed by rows): "
         f"rows 0..{rod_frame.LINE_HESS_SPLIT - 1}."),
        ("line_hess1", f"void bk_rod_line_hess1({_D} v, {_D} a, {_D} u, {_W} Hv)",
         lambda: rod_frame.line_hessian_program(1),
         f"The same, rows {rod_frame.LINE_HESS_SPLIT}..12."),
        ("gauge_energy", f"double bk_rod_gauge_energy({_D} q, double cg)", lambda: rod_energy.gauge_program(0),
         "Quaternion gauge penalty sum_n w_n cg/4 (|p_n|^2 - 1)^2, w = (1/2, 1, 1/2)."),
        ("gauge_force", f"void bk_rod_gauge_force({_D} q, double cg, {_W} f)", lambda: rod_energy.gauge_program(1),
         "f[21] += its gradient."),
        ("gauge_tangent", f"void bk_rod_gauge_tangent(int nd, {_D} q, double cg, {_W} K)", lambda: rod_energy.gauge_program(2),
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
        return _inertia_source(h, lower(rod_inertia.rotary_node_program(), ()))
    if unit == "rod_line":
        return _line_unit(h)
    strain = unit == "rod_strain"
    progs = _shared_list(
        [n for n, _, _, _ in _shared_programs() if (n in _STRAIN_FNS) == strain and n not in _LINE_FNS])
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
           " * rod_strain.c, rod_common.c, rod_inertia.c, rod_line.c are four files so that they compile in parallel.",
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
        hdr += ['#include "rod_strain.h"', '#include "rod_inertia.h"', '#include "rod_line.h"', ""]
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
    fr, mom = lower(rod_frame.frame_program(), ()), lower(rod_frame.moment_node_program(), ())
    c += _gen_fn(f"void bk_rod_frame({_D} geom, double xi, {_D} q, {_W} pos, {_W} d)", fr,
                 ["(void)geom;", "double psi[6];", "bk_rod_psi(q, psi);"])
    sf_r, sf_j = (lower(rod_frame.section_frame_program(j), ()) for j in (False, True))
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


def _line_unit(h):
    """(header, source) of out/kernels/rod_line.{h,c}: the line fixed in the
    sections (bk_rod_line, bk_rod_line_hess at v; bk_rod_section_line at xi)."""
    progs = _shared_list(list(_LINE_FNS))
    hdr = [f"/* {BANNER}",
           " * shared kinematics of the geometrically exact rods (gef, euler_bernoulli, kirchhoff): a line",
           " * P = r + a[0] d1 + a[1] d2 fixed in the sections (tendons, chambers)",
           f" * generator inputs: {', '.join('gen/' + f for f in SHARED_FILES)} + gen core ({', '.join(CORE_FILES)})",
           f" * input hash: sha256:{h}", " *",
           " * Layouts as rod_common.h (gen/rod.py).  Operations per call (add + mul + div + call):"]
    for n, _, low, _ in progs:
        hdr.append(f" *   bk_rod_{n:<14} {_ops(low)}")
    hdr += [" */", "#ifndef BK_GEN_ROD_LINE_H", "#define BK_GEN_ROD_LINE_H", ""]
    for n, sig, low, doc in progs:
        hdr += [f"/* {doc} */", sig + ";"]
    hdr += ["/* Tangent t[3] = dP/dxi of the line P = r + a[0] d1 + a[1] d2 fixed in the sections,",
            " * dt[3*nd] = dt/dq when dt is not NULL and H[nd*nd] = d2(u . t)/dq2 (full) when u",
            " * and H are not NULL (bk_element.section_line) */",
            f"void bk_rod_section_line(int nd, {_D} geom, double xi, {_D} q, {_D} a, {_D} u, {_W} t, "
            f"{_W} dt, {_W} H);", "", "#endif", ""]
    c = [f"/* {BANNER} (see rod_line.h) */", '#include "rod_common.h"', "#include <math.h>",
         '#include "rod_math.h"'] + version_guard() + [""]
    for n, sig, low, _ in progs:
        c += _gen_fn(sig, low, ret="ge" if sig.startswith("double") else None)
    c += _line_source()
    return "\n".join(hdr), "\n".join(c)


def _line_source():
    """C lines of bk_rod_section_line: c at xi (Lagrange values and xi-derivatives),
    bk_rod_line's t and dt/dv pulled back to q row by row, and the contracted
    Hessian through v -> z -> q like the element's tangent."""
    N, dN = rod.lagrange(sp.Symbol("xi")), rod.lagrange_d(sp.Symbol("xi"))
    cs = [N[0], N[2], dN[0], dN[1], dN[2]]
    return [f"void bk_rod_section_line(int nd, {_D} geom, double xi, {_D} q, {_D} a, {_D} u, {_W} t, "
            f"{_W} dt, {_W} H)", "{",
            "    (void)geom;",
            f"    const double c[5] = {{{', '.join(print_c(x) for x in cs)}}};",
            "    double psi[6], J[48], v[13], Dv[39];",
            "    bk_rod_psi_j(q, psi, J);",
            "    bk_rod_v(c, q, psi, v);",
            "    bk_rod_line(v, a, t, Dv);",
            "    if (!dt)",
            "        return;",
            "    for (int k = 0; k < 3; ++k) {",
            f"        double Gz[{rod.NZ}] = {{0.0}}, g[{rod.NQ}];",
            "        bk_rod_grad_v2z(c, Dv + 13 * k, Gz);",
            "        bk_rod_grad_z2q(J, Gz, g);",
            f"        for (int j = 0; j < nd; ++j) dt[k * nd + j] = j < {rod.NQ} ? g[j] : 0.0;",
            "    }",
            "    if (!u || !H)",
            "        return;",
            f"    double Gv[13], Hv[91], Hc[72], Gz[{rod.NZ}] = {{0.0}}, Hz[{len(rod.tri(rod.NZ))}] = {{0.0}};",
            "    for (int b = 0; b < 13; ++b) Gv[b] = u[0] * Dv[b] + u[1] * Dv[13 + b] + u[2] * Dv[26 + b];",
            "    bk_rod_line_hess0(v, a, u, Hv);",
            "    bk_rod_line_hess1(v, a, u, Hv);",
            "    bk_rod_grad_v2z(c, Gv, Gz);",
            "    bk_rod_hess_v2z(c, Hv, Hz);",
            "    bk_rod_psi_hc(q, Gz, Hc);",
            "    for (int i = 0; i < nd * nd; ++i) H[i] = 0.0;",
            "    bk_rod_hess_z2q(nd, J, Hc, Hz, H);",
            f"    for (int r = 1; r < {rod.NQ}; ++r)",
            "        for (int s = 0; s < r; ++s) H[r * nd + s] = H[s * nd + r];",
            "}", ""]


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
