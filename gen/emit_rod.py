"""C emission for the resultant beam families: geometrically exact rods (gef,
euler_bernoulli, kirchhoff; gen/rod.py) and the ANCF cable (gen/cable.py)."""
from pathlib import Path

import sympy as sp

from gen import cable, rod
from gen.emit import BANNER, CORE_FILES, _block, _fields_c, _function, _prologue, core_paths, input_hash
from gen.loads import axis_moment, quaternion_moment
from gen.program import Ops, Program, count_lowered, lower

FAMILY_FILES = {"rod": ("rod.py", "chain.py", "emit_rod.py"), "cable": ("cable.py", "emit_rod.py")}
GEN_DIR = Path(__file__).resolve().parent


def family_paths(elem):
    return [GEN_DIR / f for f in FAMILY_FILES[elem.kind]]


def _geom():
    return [sp.Symbol(f"geom[{i}]", positive=True) for i in range(7)]


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


def _rod_parts(elem):
    """Element-level programs of a geometrically exact rod."""
    g = _geom()
    l, A = g[0], g[3]
    xi = sp.Symbol("xi", real=True)
    N = rod.lagrange(xi)
    shp = Program()
    for a in range(3):
        shp.output(f"N[{a}]", N[a], op="=")
    mass_low, vol_low = _line_integrals(list(N), xi, l, A)
    # frame: position and rotation at xi
    fr = Program()
    nodes, pc, psis, _ = rod.relative_rotation_vectors(fr, "q")
    pos, R = rod.frame_at(xi, [n[0] for n in nodes], pc, psis[0], psis[1])
    for i in range(3):
        fr.output(f"pos[{i}]", pos[i], op="=")
    for k, col in enumerate((1, 2, 0)):        # d1, d2 (section axes), d3 (axis)
        for i in range(3):
            fr.output(f"d[{3 * k + i}]", R[i, col], op="=")
    # moment on the quaternion of node n
    M = sp.Matrix([sp.Symbol(f"M[{i}]", real=True) for i in range(3)])
    mom = []
    for n in range(3):
        prog = Program()
        _, s, v = rod.node_syms("q", n)
        Q = quaternion_moment(s, v, M)
        pv = [s] + list(v)
        base = rod.NODE_DOF * n + 3
        for i in range(4):
            prog.output(f"Q[{base + i}]", Q[i], op="=")
            for j in range(4):
                d = sp.diff(Q[i], pv[j])
                if d != 0:
                    prog.output(f"dQ[{(base + i) * elem.ndof + base + j}]", d, op="=")
        mom.append(lower(prog, ()))
    ref = Program()
    for n, xn in enumerate(rod.XI_NODES):
        b = rod.NODE_DOF * n
        for i, v in enumerate((xn * l, 0, 0, 1, 0, 0, 0)):
            ref.output(f"q0[{b + i}]", v, op="=")
    for i in range(elem.ninternal):
        ref.output(f"q0[{3 * rod.NODE_DOF + i}]", 0, op="=")
    tab = lower(rod.tabulate_program(elem), ())
    return (lower(shp, ()), mass_low, vol_low, lower(fr, ()), mom, lower(ref, ()), tab,
            [rod.NODE_DOF * n for n in range(3)], rod.tab_layout(), lower(_rotary_program(elem), ()))


def _rotary_program(elem):
    """Rotary inertia lumped at the nodes (weights l/6, 2l/3, l/6), per unit density:
    T = sum_n 1/2 W_n^T J_n W_n with the body angular velocity W = 2 Im(conj(p) p')/|p|^2
    and J_n = w_n diag(Ip, I1, I2); f = d/dt dT/dp' - dT/dp and its derivatives."""
    g = _geom()
    l, I1, I2, Ip = g[0], g[4], g[5], g[6]
    nd = elem.ndof
    prog = Program()
    T = 0
    for n, wn in enumerate((sp.Rational(1, 6), sp.Rational(2, 3), sp.Rational(1, 6))):
        base = rod.NODE_DOF * n + 3
        p = [sp.Symbol(f"q[{base + k}]", real=True) for k in range(4)]
        pd = [sp.Symbol(f"qd[{base + k}]", real=True) for k in range(4)]
        pdd = [sp.Symbol(f"qdd[{base + k}]", real=True) for k in range(4)]
        n2 = sum(x * x for x in p)
        W = 2 * rod.qmul(rod.qconj((p[0], sp.Matrix(p[1:]))), (pd[0], sp.Matrix(pd[1:])))[1] / n2
        J = [Ip, I1, I2]
        Tn = wn * l * sum(J[k] * W[k]**2 for k in range(3)) / 2
        T += Tn
        dTdpd = [sp.diff(Tn, x) for x in pd]
        f = [sum(sp.diff(dTdpd[i], p[j]) * pd[j] + sp.diff(dTdpd[i], pd[j]) * pdd[j] for j in range(4))
             - sp.diff(Tn, p[i]) for i in range(4)]
        for i in range(4):
            prog.output(f"f[{base + i}]", f[i], op="=")
            for j in range(4):
                for arr, var in (("Mq", pdd), ("Cq", pd), ("Kq", p)):
                    d = sp.diff(f[i], var[j])
                    if d != 0:
                        prog.output(f"{arr}[{(base + i) * nd + base + j}]", d, op="=")
    prog.output("T[0]", T, op="=")
    return prog


def _cable_parts(elem):
    g = _geom()
    l, A = g[0], g[3]
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
    parts = _rod_parts(elem) if elem.kind == "rod" else _cable_parts(elem) + (None,)
    shp, mass_low, vol_low, fr, mom, ref, tab, shape_dof, ntab, rot = parts
    nsh = len(shape_dof)
    mod = rod if elem.kind == "rod" else cable
    doc = (mod.__doc__ or "").strip().splitlines()
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
    fields = elem.fields()
    c = [f"/* {BANNER} (see {name}.h) */", f'#include "{name}.h"', "#include <math.h>",
         '#include "rod_math.h"', "",
         f"static const double node_xi[{elem.nnode}] = {{{', '.join(repr(float(x)) for x in (rod.XI_NODES if elem.kind == 'rod' else (0, 1)))}}};",
         f"static const int shape_dof[{nsh}] = {{{', '.join(map(str, shape_dof))}}};"]
    c += _fields_c(name, fields) + [""]
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
    if len(mom) == 1:
        c += _function(msig, mom[0], pre)
    else:   # moments act on the nodal quaternion of the node at xi
        c += [msig, "{"] + [f"    {x}" for x in pre]
        for n, low in enumerate(mom):
            cond = ("if (xi < 0.25) {" if n == 0 else "} else if (xi < 0.75) {" if n == 1 else "} else {")
            c += [f"    {cond}"] + _prologue(low, "        ") + _block(low, "        ")
        c += ["    }", "}", ""]
    c += _function("static void reference(const double *restrict geom, double *restrict q0)", ref, ["(void)geom;"])
    if rot is not None:
        c += _function("static void rotary(const double *restrict geom, const double *restrict q, "
                       "const double *restrict qd, const double *restrict qdd, double *restrict f, "
                       "double *restrict Mq, double *restrict Cq, double *restrict Kq, double *restrict T)", rot,
                       [f"for (int i = 0; i < {nd}; ++i) f[i] = 0.0;",
                        f"for (int i = 0; i < {nd * nd}; ++i) Mq[i] = Cq[i] = Kq[i] = 0.0;"])
    c += _function(f"void {name}_full_tabulate(const double *restrict geom, const double *restrict q0, "
                   "double *restrict tab)", tab, ["(void)q0;"] if elem.kind == "cable" else [])
    c += [f"const bk_element bk_element_{name} = {{",
          f'    "{name}", "{elem.title}", {elem.nnode}, {nd}, node_xi,',
          f"    {len(fields)}, field_name, field_dof, field_dim, reference,",
          f"    {nsh}, shape_dof, shape, mass, volume, frame, moment, {'rotary' if rot is not None else '0'}",
          "};", ""]
    return htxt, "\n".join(c)


def pair_source(elem, elem_path, mat, mat_path):
    name = f"{elem.name}_{mat.NAME}"
    nd = elem.ndof
    h = input_hash([elem_path, mat_path] + family_paths(elem) + core_paths())
    mod = rod if elem.kind == "rod" else cable
    ntab = mod.tab_layout()
    sig = {
        "energy": f"double {name}_full_energy(const double *restrict q, const double *restrict tab, const double *restrict mat)",
        "force": f"void {name}_full_force(const double *restrict q, const double *restrict tab, const double *restrict mat, double *restrict f)",
        "tangent": f"void {name}_full_force_tangent(const double *restrict q, const double *restrict tab, const double *restrict mat, double *restrict f, double *restrict K)",
    }
    c = [f"/* {BANNER} (see {name}.h) */", f'#include "{name}.h"', f'#include "{elem.name}.h"',
         "#include <math.h>", '#include "rod_math.h"', "",
         f"static const char *const param_names[{len(mat.PARAMS)}] = "
         f"{{{', '.join(chr(34) + p + chr(34) for p in mat.PARAMS)}}};", ""]
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
    nqp = len(rod.GAUSS) if elem.kind == "rod" else cable.NGAUSS
    c += [f"const bk_pair bk_pair_{name}_full = {{",
          f'    &bk_element_{elem.name}, "{mat.NAME}", "full", {len(mat.PARAMS)}, param_names,',
          f"    {ntab}, {nqp}, {ops['force'].total()}L, {ops['tangent'].total()}L,",
          f"    {elem.name}_full_tabulate, {name}_full_energy, {name}_full_force, {name}_full_force_tangent,",
          "    0, 0",
          "};", ""]
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
           f" *   force + upper tangent {ops['tangent']}", " */"]
    htxt = "\n".join(hdr) + f"""
#ifndef BK_GEN_{name.upper()}_H
#define BK_GEN_{name.upper()}_H
#include "bk_kernel.h"

extern const bk_pair bk_pair_{name}_full;
""" + "\n".join(s + ";" for s in sig.values()) + "\n\n#endif\n"
    return htxt, "\n".join(c), None
