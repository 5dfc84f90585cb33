"""C emission for continuum elements and element x material pairs.

Files written (see runtime/bk_kernel.h for the contract):
  <element>.h / .c            shape functions, mass and volume integrals,
                              quadrature tables (one tabulate() per integration)
  <element>_<material>.h / .c energy, force, force + tangent per integration
                              (gen/emit_pair.py)
The lane kernels' loops are gen/lanes.py, the section resultants function
gen/emit_sections.py, the banner and input hash gen/provenance.py.
"""
from functools import lru_cache
from pathlib import Path

import sympy as sp

from gen.c_functions import _block, _function, _prologue, section_frame_function
from gen.continuum import (A_INDEX, SKEW_INDEX, contraction_programs, invariants_program, rule_parts,
                           skew_contraction_programs, tabulate_program, viscous_body_program)
from gen.descriptor import ElementDesc, Field, element_descriptor, version_guard
from gen.element import B, H, HI, L, LO, XI, Y, Z, band_subs, geom_subs, shape_functions, shape_gradients
from gen.lanes import _lane_kernel_fn, _lane_loop, lanes
from gen.program import Program, count_lowered, lower, Ops
from gen.provenance import BANNER, CORE_FILES, core_paths, input_hash

# The lane kernels' definitions carry BK_LANE_TARGET (defined in the element
# header): gcc's tuning for recent Intel CPUs prefers 256-bit vectors, which
# splits every operation of the 8 lanes in two; in whole AVX-512 registers the
# continuum force + tangent lane kernels take 20-35 % less time.  The
# one-element kernels keep the default: with 512-bit vectors their scalar code
# ran up to 1.7x slower.  No effect where the target has no AVX-512 (the
# memcheck build, other CPUs).
LANE_TARGET = """
/* The lane kernels in whole 512-bit registers where the target has them (gen/emit.py). */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define BK_LANE_TARGET __attribute__((target("prefer-vector-width=512")))
#else
#define BK_LANE_TARGET
#endif
"""


# ----------------------------------------------------------------------------
# Element file

VISC_ARGS = ("const double *restrict q, const double *restrict qd, const double *restrict tab, "
             "const double *restrict visc")

CAPS = ("BK_CAP_SECTION_RECTANGLE", "BK_CAP_SECTION_FIELD", "BK_CAP_CURVED", "BK_CAP_MOMENT_ANYWHERE")


def describe(elem):
    """The descriptor of a continuum element (gen/descriptor.py): the box section is
    the element's own field, moments anywhere along the axis."""
    fields = tuple(Field(vec, 3 * a, 3, node) for a, (node, vec) in enumerate(elem.shape_labels()))
    return ElementDesc(name=elem.name, title=elem.title, node_xi=tuple(str(n.xi) for n in elem.nodes),
                       ndof=elem.ndof, caps=CAPS, fields=fields, shape_dof=tuple(3 * a for a in range(elem.nshape)),
                       functions={k: k for k in ("reference", "shape", "mass", "volume", "frame", "section_frame",
                                                 "moment")})



def element_source(elem, elem_path):
    """Element file of a continuum (ANCF) element."""
    from gen.loads import section_frame_programs, section_moment
    name = elem.name
    nsh, ndof = elem.nshape, elem.ndof
    h = input_hash([elem_path] + core_paths())
    geom = geom_subs()
    xi_s, y_s, z_s = (sp.Symbol(n, real=True) for n in ("xi", "y", "z"))
    sub = {XI: xi_s, Y: y_s, Z: z_s, **geom}
    line = {XI: xi_s, Y: 0, Z: 0, **geom}
    Ns = shape_functions(elem)
    grads = shape_gradients(elem)
    q = [sp.Symbol(f"q[{i}]", real=True) for i in range(ndof)]

    shp = Program()
    for a, N in enumerate(Ns):
        shp.output(f"N[{a}]", N.subs(sub), op="=")
    shp_low = lower(shp, ())

    # Exact integrals over the box x in [0,l], y in [-b/2,b/2], z in [-h/2,h/2]
    # (band: z in [(lo - 1/2) h, (1/2 - hi) h], a layer's band of the height).
    def integrate(expr, band=False):
        z0, z1 = ((LO - sp.Rational(1, 2)) * H, (sp.Rational(1, 2) - HI) * H) if band else (-H / 2, H / 2)
        e = sp.integrate(sp.expand(expr), (Y, -B / 2, B / 2), (Z, z0, z1), (XI, 0, 1))
        return sp.factor(e * L)

    def mass_program(band):
        gs = {**geom, **band_subs()} if band else geom
        mass = Program()
        for a in range(nsh):
            for b in range(a, nsh):
                e = integrate(Ns[a] * Ns[b], band).subs(gs)
                mass.output(f"m[{a * nsh + b}]", e, op="=")
                if b != a:
                    mass.output(f"m[{b * nsh + a}]", e, op="=")
        return lower(mass, ())

    def volume_program(band):
        gs = {**geom, **band_subs()} if band else geom
        vol = Program()
        for a in range(nsh):
            vol.output(f"v[{a}]", integrate(Ns[a], band).subs(gs), op="=")
        return lower(vol, ())
    mass_low, mass_band_low = mass_program(False), mass_program(True)
    vol_low, vol_band_low = volume_program(False), volume_program(True)

    # Centreline frame: position and the gradients r_y, r_z, r_x.
    def field(fn):
        return [sum(fn(a) * q[3 * a + i] for a in range(nsh)) for i in range(3)]
    fr = Program()
    for i, e in enumerate(field(lambda a: Ns[a].subs(line))):
        fr.output(f"pos[{i}]", e, op="=")
    for k, J in enumerate((1, 2, 0)):
        for i, e in enumerate(field(lambda a: grads[a][J].subs(line))):
            fr.output(f"d[{3 * k + i}]", e, op="=")
    fr_low = lower(fr, ())
    # Orthonormal section frame of d1 = r_y, d3 = r_x and its Jacobian (follower loads).
    sf_low = [lower(pr, ()) for pr in section_frame_programs(
        sp.Matrix(field(lambda a: grads[a][1].subs(line))), sp.Matrix(field(lambda a: grads[a][0].subs(line))),
        q, ndof)]

    # Moment through the section slopes r_y, r_z at (xi, 0, 0).
    mo = Program()
    Ny = [grads[a][1].subs(line) for a in range(nsh)]
    Nz = [grads[a][2].subs(line) for a in range(nsh)]
    ry = sp.Matrix([mo.define(f"ry{i}", sum(Ny[a] * q[3 * a + i] for a in range(nsh))) for i in range(3)])
    rz = sp.Matrix([mo.define(f"rz{i}", sum(Nz[a] * q[3 * a + i] for a in range(nsh))) for i in range(3)])
    M = sp.Matrix([sp.Symbol(f"M[{i}]", real=True) for i in range(3)])
    Qs_expr = section_moment(ry, rz, M)
    rr = list(ry) + list(rz)
    Qs = [mo.define(f"Qs{i}", Qs_expr[i]) for i in range(6)]
    dQs = [[mo.define(f"dQs{i}_{j}", sp.diff(Qs_expr[i], rr[j])) for j in range(6)] for i in range(6)]
    for a in range(nsh):
        if Ny[a] == 0 and Nz[a] == 0:
            continue
        for i in range(3):
            mo.output(f"Q[{3 * a + i}]", Ny[a] * Qs[i] + Nz[a] * Qs[3 + i], op="=")
            for b in range(nsh):
                if Ny[b] == 0 and Nz[b] == 0:
                    continue
                for k in range(3):
                    e = (Ny[a] * Ny[b] * dQs[i][k] + Ny[a] * Nz[b] * dQs[i][3 + k]
                         + Nz[a] * Ny[b] * dQs[3 + i][k] + Nz[a] * Nz[b] * dQs[3 + i][3 + k])
                    mo.output(f"dQ[{(3 * a + i) * ndof + 3 * b + k}]", e, op="=")
    mo_low = lower(mo, ())

    # Reference coordinates of the straight element.
    ref = Program()
    labels = elem.shape_labels()
    for a, (ni, vec) in enumerate(labels):
        val = {"r": (elem.nodes[ni].xi * L, 0, 0), "r_x": (1, 0, 0), "r_y": (0, 1, 0),
               "r_z": (0, 0, 1)}.get(vec, (0, 0, 0))
        for i in range(3):
            ref.output(f"q0[{3 * a + i}]", sp.sympify(val[i]).subs(geom), op="=")
    ref_low = lower(ref, ())

    hdr = [f"/* {BANNER}",
           f" * element: {name} -- {elem.title}",
           f" * source: {elem.source}",
           f" * generator inputs: gen/elements/{Path(elem_path).name} + gen core ({', '.join(CORE_FILES)})",
           f" * input hash: sha256:{h}",
           " *",
           f" * Nodal layout ({len(elem.nodes)} nodes, {nsh} vectors, {ndof} DOF):",
           f" *   {elem.describe_layout()}",
           " * Reference box: x in [0,l] (xi = x/l), y in [-b/2,b/2], z in [-h/2,h/2];"
           " l, b, h = geom[BK_GEOM_L, _B, _H].",
           " * Shape functions N_a (r = sum_a N_a q_a, S = N (x) I3):"]
    for a, N in enumerate(Ns):
        hdr.append(f" *   N{a} [{labels[a][1]} @ node {labels[a][0]}] = {sp.sstr(N)}")
    hdr += [" * frame(): d1 = r_y, d2 = r_z, d3 = r_x at (xi, 0, 0).",
            " * section_frame(): e3 = r_x/|r_x|, e1 = the part of r_y normal to it, normalised, e2 = e3 x e1,",
            " *   and dR/dq (gen/loads.py, section_frame_programs).",
            " * moment(): through the section slopes r_y, r_z (gen/loads.py, section_moment).", " */"]

    htxt = "\n".join(hdr) + f"""
#ifndef BK_GEN_{name.upper()}_H
#define BK_GEN_{name.upper()}_H
#include "bk_kernel.h"

extern const bk_element bk_element_{name};
"""
    for rname in elem.rule_names:
        _, parts, ntab = rule_parts(elem, rname)
        htxt += (f"/* integration \"{rname}\": {', '.join(f'{len(p.rule)} points ({p.energy})' for p in parts)};"
                 f" tab[{ntab}] */\n")
        htxt += f"void {name}_{rname}_tabulate(const double *restrict geom, const double *restrict q0, double *restrict tab);\n"
        nqp_r = sum(len(p.rule) for p in parts)
        htxt += (f"/* J, I1, I2 of C = F^T F at the {nqp_r} points of \"{rname}\" (all parts, in order): "
                 f"inv[3 p + 0..2] */\n"
                 f"void {name}_{rname}_invariants(const double *restrict q, const double *restrict tab, "
                 "double *restrict inv);\n")
        htxt += (f"/* Kelvin-Voigt damping of \"{rname}\" (bk_pair.viscous_force, viscous, and their lane\n"
                 " * kernels): the force (and the Rayleigh dissipation function), and the force with\n"
                 " * K = gc C + gk K_q (C = df/dqd, K_q = df/dq): per point one contraction of its\n"
                 " * symmetric part and one of its antisymmetric part. */\n"
                 f"double {name}_{rname}_viscous_force(" + VISC_ARGS + ", double *restrict f);\n"
                 f"void {name}_{rname}_viscous(" + VISC_ARGS + ", double gc, double gk, "
                 "double *restrict f, double *restrict K);\n"
                 f"void {name}_{rname}_viscous_force_lanes(" + VISC_ARGS + ", double *restrict f);\n"
                 f"void {name}_{rname}_viscous_lanes(" + VISC_ARGS + ", double gc, double gk, "
                 "double *restrict f, double *restrict K);\n")
    htxt += (f"/* K (upper triangle) += sum over node pairs of g_a g_b : A for one quadrature point;\n"
             f" * A[{len(A_INDEX)}] = the weighted dP/dF entries (iJ) <= (kL), t = the point's table row.\n"
             f" * {contraction_ops(elem)} operations. */\n"
             f"void {name}_tangent_contract(const double *restrict A, const double *restrict t, double *restrict K);\n")
    htxt += (f"/* The same for BK_LANES = {lanes()} elements, every array in lane order "
             "(runtime/bk_kernel.h, \"Lane kernels\"). */\n"
             f"void {name}_tangent_contract_lanes(const double *restrict A, const double *restrict t, "
             "double *restrict K);\n")
    htxt += (f"/* Antisymmetric part: K[c, r] += sum over node pairs of g_a g_b : B for r < c (the lower\n"
             f" * triangle), B[{len(SKEW_INDEX)}] the entries (iJ) < (kL) of an antisymmetric tensor; and over\n"
             " * BK_LANES elements. */\n"
             f"void {name}_contract_skew(const double *restrict Ask, const double *restrict t, double *restrict K);\n"
             f"void {name}_contract_skew_lanes(const double *restrict Ask, const double *restrict t, "
             "double *restrict K);\n")
    htxt += LANE_TARGET
    htxt += "\n#endif\n"

    c = ["/* " + BANNER + f" (see {name}.h) */", f'#include "{name}.h"', "#include <math.h>"]
    c += version_guard() + ["",
         "#if defined(__GNUC__)", "#define BK_NOINLINE __attribute__((noinline))", "#else",
         "#define BK_NOINLINE", "#endif", ""]
    c += _function(f"static void shape(const double *restrict geom, double xi, double y, double z, double *restrict N)",
                   shp_low, ["(void)geom; (void)xi; (void)y; (void)z;"])
    c += _function("static void mass_band(const double *restrict geom, double *restrict m)", mass_band_low)
    c += _banded("static void mass(const double *restrict geom, double *restrict m)", mass_low, "mass_band(geom, m)")
    c += _function("static void volume_band(const double *restrict geom, double *restrict v)", vol_band_low)
    c += _banded("static void volume(const double *restrict geom, double *restrict v)", vol_low,
                 "volume_band(geom, v)")
    c += _function("static void frame(const double *restrict geom, double xi, const double *restrict q, "
                   "double *restrict pos, double *restrict d)", fr_low, ["(void)geom; (void)xi;"])
    c += section_frame_function(*sf_low)
    c += _function("static void moment(const double *restrict geom, double xi, const double *restrict q, "
                   "const double *restrict M, double *restrict Q, double *restrict dQ)", mo_low,
                   ["(void)geom; (void)xi;", f"for (int i = 0; i < {ndof}; ++i) Q[i] = 0.0;",
                    f"for (int i = 0; i < {ndof * ndof}; ++i) dQ[i] = 0.0;"])
    c += _function("static void reference(const double *restrict geom, double *restrict q0)", ref_low,
                   ["(void)geom;"])
    for rname in elem.rule_names:
        tprog, ntab = tabulate_program(elem, rname)
        bprog, _ = tabulate_program(elem, rname, band=True)
        c += _function(f"static void {name}_{rname}_tabulate_band(const double *restrict geom, "
                       "const double *restrict q0, double *restrict tab)", lower(bprog, ()))
        c += _banded(f"void {name}_{rname}_tabulate(const double *restrict geom, const double *restrict q0, "
                     "double *restrict tab)", lower(tprog, ()),
                     f"{name}_{rname}_tabulate_band(geom, q0, tab)")[:-2] + snap_map_lines(elem, rname)
    # Strain invariants at every point of each integration (state checks).
    ilow = lower(invariants_program(elem), ())
    for rname in elem.rule_names:
        _, parts, _ = rule_parts(elem, rname)
        c += [f"void {name}_{rname}_invariants(const double *restrict q, const double *restrict tab, "
              "double *restrict out)", "{"]
        first = 0
        for part in parts:
            c += [f"    for (int p = 0; p < {len(part.rule)}; ++p) {{",
                  f"        const double *restrict t = tab + {part.tab_offset} + {part.stride} * p;",
                  f"        double *restrict inv = out + 3 * ({first} + p);"]
            c += _prologue(ilow, "        ") + _block(ilow, "        ")
            c += ["    }"]
            first += len(part.rule)
        c += ["}", ""]
    # Kelvin-Voigt damping per integration (at the points of its first rule part):
    # the force alone for residual-only evaluations (the one-element kernel also
    # returns the Rayleigh dissipation function), and the force with gc C + gk K_q
    # (K_q = df/dq) from one symmetric and one antisymmetric contraction per point; each also over BK_LANES elements.
    vlow = {want: lower(viscous_body_program(elem, want), ())
            for want in ("force", "dissipation", "tangent")}
    for rname in elem.rule_names:
        _, parts, _ = rule_parts(elem, rname)
        part = parts[0]
        point = [f"    for (int p = 0; p < {len(part.rule)}; ++p) {{",
                 f"        const double *restrict t = tab + {part.tab_offset} + {part.stride} * p;"]
        low = vlow["dissipation"]
        c += [f"double {name}_{rname}_viscous_force(" + VISC_ARGS + ", double *restrict f)", "{",
              f"    for (int i = 0; i < {ndof}; ++i) f[i] = 0.0;", "    double D = 0.0;"] + point
        c += _prologue(low, "        ") + _block(low, "        ")
        c += ["    }", "    return D;", "}", ""]
        # the matrix: the symmetric part's upper triangle, the antisymmetric part's
        # into the lower one (X_rc at [c, r]); then K[r, c] = U + X, K[c, r] = U - X
        low = vlow["tangent"]
        c += [f"void {name}_{rname}_viscous(" + VISC_ARGS + ", double gc, double gk, double *restrict f, "
              "double *restrict K)", "{",
              f"    for (int i = 0; i < {ndof}; ++i) f[i] = 0.0;",
              f"    for (int i = 0; i < {ndof * ndof}; ++i) K[i] = 0.0;"] + point
        c += [f"        double A[{len(A_INDEX)}], Ask[{len(SKEW_INDEX)}];"]
        c += _prologue(low, "        ") + _block(low, "        ")
        c += [f"        {name}_tangent_contract(A, t, K);", f"        {name}_contract_skew(Ask, t, K);", "    }",
              f"    for (int r = 1; r < {ndof}; ++r)",
              "        for (int c = 0; c < r; ++c) {",
              f"            const double u = K[c * {ndof} + r], x = K[r * {ndof} + c];",
              f"            K[c * {ndof} + r] = u + x;",
              f"            K[r * {ndof} + c] = u - x;",
              "        }", "}", ""]
        c += _lane_kernel_fn(f"void {name}_{rname}_viscous_force_lanes(" + VISC_ARGS + ", double *restrict f)",
                             ndof, [part], [vlow["force"]])
        w = lanes()
        c += ["BK_LANE_TARGET void " + f"{name}_{rname}_viscous_lanes(" + VISC_ARGS + ", double gc, double gk, "
              "double *restrict f, double *restrict K)", "{",
              f"    for (int i = 0; i < {ndof * w}; ++i) f[i] = 0.0;",
              f"    for (int i = 0; i < {ndof * ndof * w}; ++i) K[i] = 0.0;",
              f"    for (int p = 0; p < {len(part.rule)}; ++p) {{",
              f"        const double *restrict t = tab + ({part.tab_offset} + {part.stride} * p) * {w};",
              f"        double A[{len(A_INDEX) * w}], Ask[{len(SKEW_INDEX) * w}];"]
        c += _lane_loop(_prologue(low, "            ") + _block(low, "            "), "        ")
        c += [f"        {name}_tangent_contract_lanes(A, t, K);", f"        {name}_contract_skew_lanes(Ask, t, K);",
              "    }",
              f"    for (int r = 1; r < {ndof}; ++r)",
              "        for (int c = 0; c < r; ++c)",
              f"            for (int l = 0; l < {w}; ++l) {{",
              f"                const double u = K[(c * {ndof} + r) * {w} + l], x = K[(r * {ndof} + c) * {w} + l];",
              f"                K[(c * {ndof} + r) * {w} + l] = u + x;",
              f"                K[(r * {ndof} + c) * {w} + l] = u - x;",
              "            }", "}", ""]
    # The tangent contraction, one function per row node (keeps compile time linear).
    lows = contraction_lowered(elem)
    for a, low in enumerate(lows):
        if not low.outputs:
            continue
        c += _function(f"static BK_NOINLINE void {name}_contract_row{a}(const double *restrict A, "
                       "const double *restrict t, double *restrict K)", low)
    c += [f"void {name}_tangent_contract(const double *restrict A, const double *restrict t, double *restrict K)",
          "{"]
    c += [f"    {name}_contract_row{a}(A, t, K);" for a, low in enumerate(lows) if low.outputs]
    c += ["}", ""]
    # The same over BK_LANES elements (lane kernels: A, t, K in lane order).
    for a, low in enumerate(lows):
        if not low.outputs:
            continue
        c += [f"static BK_NOINLINE BK_LANE_TARGET void {name}_contract_lanes_row{a}(const double *restrict A, "
              "const double *restrict t, double *restrict K)", "{"]
        c += _lane_loop(_prologue(low, "        ") + _block(low, "        "), "    ")
        c += ["}", ""]
    c += [f"BK_LANE_TARGET void {name}_tangent_contract_lanes(const double *restrict A, const double *restrict t, "
          "double *restrict K)", "{"]
    c += [f"    {name}_contract_lanes_row{a}(A, t, K);" for a, low in enumerate(lows) if low.outputs]
    c += ["}", ""]
    # The antisymmetric contraction (the viscous tangent's part), the same way.
    slows = [lower(p, ()) for p in skew_contraction_programs(elem)]
    for a, low in enumerate(slows):
        if not low.outputs:
            continue
        c += _function(f"static BK_NOINLINE void {name}_skew_row{a}(const double *restrict Ask, "
                       "const double *restrict t, double *restrict K)", low)
        c += [f"static BK_NOINLINE BK_LANE_TARGET void {name}_skew_lanes_row{a}(const double *restrict Ask, "
              "const double *restrict t, double *restrict K)", "{"]
        c += _lane_loop(_prologue(low, "        ") + _block(low, "        "), "    ")
        c += ["}", ""]
    c += [f"void {name}_contract_skew(const double *restrict Ask, const double *restrict t, double *restrict K)",
          "{"] + [f"    {name}_skew_row{a}(Ask, t, K);" for a, low in enumerate(slows) if low.outputs] + ["}", ""]
    c += [f"BK_LANE_TARGET void {name}_contract_skew_lanes(const double *restrict Ask, const double *restrict t, "
          "double *restrict K)", "{"]
    c += [f"    {name}_skew_lanes_row{a}(Ask, t, K);" for a, low in enumerate(slows) if low.outputs] + ["}", ""]
    c += element_descriptor(describe(elem))
    return htxt, "\n".join(c)


def _banded(sig, low, band_call):
    """C lines of a function computing low over the whole section, or calling
    band_call when geom[] names a band of it (a layer: bk_kernel.h)."""
    return ([sig, "{", "    if (geom[BK_GEOM_BAND_LO] != 0.0 || geom[BK_GEOM_BAND_HI] != 0.0) {",
             f"        {band_call};", "    } else {"]
            + _prologue(low, "        ") + _block(low, "        ") + ["    }", "}", ""])


def snap_map_lines(elem, rname):
    """The end of a tabulate(): reference-map entries within 1e-12 of the identity's
    are the identity's, so that a straight element's map is exactly I (the sums that
    make J0 round; off the diagonal that noise would couple directions a symmetric
    problem keeps apart); then a layer's free isotropic strain e
    (geom[BK_GEOM_EIGENSTRAIN]) scales the map by 1/(1 + e), the weights by (1 + e)^3."""
    from gen.continuum import MAP_ENTRIES, gradient_slots
    nsl = len(gradient_slots(elem).exprs)
    _, parts, _ = rule_parts(elem, rname)
    from gen.program import c_double
    lines = ["    /* a reference map within round-off of the identity is the identity, and the weight",
             "     * of a point whose det J0 is within round-off of 1 that of the straight box */",
             "    const double box = geom[BK_GEOM_L] * geom[BK_GEOM_B] * geom[BK_GEOM_H]"
             " * (1.0 - geom[BK_GEOM_BAND_LO] - geom[BK_GEOM_BAND_HI]);"]
    for part in parts:
        lines += [f"    for (int p = 0; p < {len(part.rule)}; ++p) {{",
                  f"        static const double wq[{len(part.rule)}] = {{{', '.join(c_double(w) for _, w in part.rule)}}};",
                  f"        double *restrict wt = tab + {part.tab_offset} + {part.stride} * p;",
                  f"        double *restrict m = wt + {1 + nsl};",
                  "        if (fabs(*wt - wq[p] * box) <= 1e-12 * wq[p] * box) *wt = wq[p] * box;"]
        for k, (J, K) in enumerate(MAP_ENTRIES):
            ref = "1.0" if J == K else "0.0"
            lines.append(f"        if (fabs(m[{k}] - {ref}) <= 1e-12) m[{k}] = {ref};")
        # a free isotropic strain e (BK_GEOM_EIGENSTRAIN): F_e = F F_theta^-1 with
        # F_theta = (1 + e) I, the energy per stress-free volume times det F_theta
        lines += ["        if (geom[BK_GEOM_EIGENSTRAIN] != 0.0) {",
                  "            const double s = 1.0 + geom[BK_GEOM_EIGENSTRAIN];",
                  "            *wt *= s * s * s;",
                  f"            for (int k = 0; k < {len(MAP_ENTRIES)}; ++k) m[k] /= s;",
                  "        }", "    }"]
    return lines + ["}", ""]


@lru_cache(maxsize=None)
def contraction_lowered(elem):
    return tuple(lower(p, ()) for p in contraction_programs(elem))


def contraction_ops(elem):
    tot = Ops()
    for low in contraction_lowered(elem):
        tot += count_lowered(low)[1]
    return tot


# ----------------------------------------------------------------------------
# Pair file

def _kernel_fn(signature, ndof, parts, lows, zero, finish, contract_fn=None):
    lines = [signature, "{"]
    lines += [f"    {z}" for z in zero]
    for part, low in zip(parts, lows):
        lines.append(f"    {{   /* energy part \"{part.energy}\": {len(part.rule)} quadrature points */")
        lines += _prologue(low, "        ")
        lines.append(f"        for (int p = 0; p < {len(part.rule)}; ++p) {{")
        lines.append(f"            const double *restrict t = tab + {part.tab_offset} + {part.stride} * p;")
        if contract_fn:
            lines.append(f"            double A[{len(A_INDEX)}];")
        lines += _block(low, "            ")
        if contract_fn:
            lines.append(f"            {contract_fn}(A, t, K);")
        lines += ["        }", "    }"]
    lines += [f"    {x}" for x in finish]
    lines += ["}", ""]
    return lines

