"""Derivation of continuum (ANCF) element kernels: element x material x rule.

At a quadrature point the deformation gradient is linear in the element
coordinates, F = sum_a q_a g_a^T M, with g_a = grad N_a over the element box (x
along the axis, y, z across; tabulated once per element geometry, only the
entries that are not identically zero, equal or opposite entries sharing one
slot) and M = J0^-1 Q0 the point's reference map: J0 = sum_a q0_a g_a^T the
gradient of the reference configuration over the box and Q0 its orthonormal
frame (Gram-Schmidt of J0's columns: the reference tangent first), so that
J0 = Q0 R and M = R^-1 is upper triangular (6 table entries).  F is thus
the deformation gradient from the reference configuration, whatever its shape,
in the local frame (tangent, d1, d2) there: a curved element is stress free in
its curved reference, and C11 is the stretch along the reference tangent.  The
point weight carries det J0.  A straight reference gives M = I exactly (the
products by 1 and 0 round nothing).  For an isotropic energy W(I1, I2, J):

  P = dW/dF  = sum_m W_m dI_m/dF
  A = d2W/dF2 = sum_mn W_mn dI_m/dF (x) dI_n/dF + sum_m W_m d2I_m/dF2
  f_a   = sum_qp w (P M^T) g_a                   (internal force, 3 per node)
  K_ab  = sum_qp w sum_JL g_aJ g_bL A'[:,J,:,L]  (tangent block, 3x3 per pair)

with A' = A transformed by M on its second and fourth index.

with the invariant derivatives of gen/invariants.py.  Only the upper triangle of
K is computed; the kernel mirrors it.  The material part A is a 3x3x3x3 tensor
(45 distinct entries) contracted with per-node gradient vectors, so the cost per
point grows with the number of node pairs, not with ndof^2 x (terms of W).
"""
from dataclasses import dataclass

import sympy as sp

from gen.element import AX, B, H, HI, L, LO, XI, Y, Z, band_subs, geom_subs, shape_gradients
from gen.invariants import (COMPONENTS, cofactor, component_first, component_second,
                            first_derivatives, second_derivatives)
from gen.program import Program, lower
from gen.quadrature import box_rule

INVARIANTS = ("I1", "I2", "J")
MAP_ENTRIES = ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))   # upper triangle of M
NMAP = len(MAP_ENTRIES)   # table entries of the reference map M per point, after the gradient slots


@dataclass
class GradientSlots:
    exprs: list        # canonical gradient expressions, one per table slot
    ref: dict          # (a, J) -> (slot, sign)


def gradient_slots(elem):
    """Assign table slots to the structurally nonzero shape-function gradients."""
    exprs, ref = [], {}
    for a, grad in enumerate(shape_gradients(elem)):
        for J, g in enumerate(grad):
            if g == 0:
                continue
            for k, e in enumerate(exprs):
                if sp.expand(g - e) == 0:
                    ref[(a, J)] = (k, 1)
                    break
                if sp.expand(g + e) == 0:
                    ref[(a, J)] = (k, -1)
                    break
            else:
                ref[(a, J)] = (len(exprs), 1)
                exprs.append(g)
    return GradientSlots(exprs, ref)


def qp_coords(s, band=False):
    """Unit-cube rule point -> (xi, y, z) of the element box (band: of the layer's
    band z in [(lo - 1/2) h, (1/2 - hi) h] of it; "axis": at the height of the
    layered section's neutral axis, s[2] being the middle)."""
    if band == "axis":
        return {XI: s[0], Y: (s[1] - 0.5) * B, Z: AX * H}
    if band:
        return {XI: s[0], Y: (s[1] - 0.5) * B, Z: (LO - sp.Rational(1, 2) + s[2] * (1 - LO - HI)) * H}
    return {XI: s[0], Y: (s[1] - 0.5) * B, Z: (s[2] - 0.5) * H}


@dataclass
class PartSpec:
    energy: str        # energy part ("all" or a material part name)
    rule: list         # [((sx, sy, sz), weight on the unit cube)]
    tab_offset: int    # first table entry of this part
    stride: int        # table entries per point: weight, then gradient slots


def rule_parts(elem, integration):
    slots = gradient_slots(elem)
    parts, off = [], 0
    for rp in elem.rule(integration):
        rule = box_rule(rp.points)
        stride = 1 + len(slots.exprs) + NMAP
        parts.append(PartSpec(rp.energy, rule, off, stride))
        off += stride * len(rule)
    return slots, parts, off


def tabulate_program(elem, integration, band=False):
    """Program filling tab[] from geom[BK_GEOM_L, _B, _H] and the reference
    coordinates q0: per point w*l*b*h*det J0, the gradient slots, then the
    reference map M = J0^-1 Q0 = R^-1 (its upper triangle, MAP_ENTRIES).
    band: the element's rule mapped onto the band of a layer (geom[BK_GEOM_BAND_LO,
    _HI]), its weights times the band's share 1 - lo - hi of the height; a rule
    part with one point through the height puts it at the layered section's
    neutral axis (the centreline part of selective reduced integration: at the
    band's middle the element's lateral fields would lock as in full integration,
    at the geometric middle a layer's lateral response would meet the stretch
    there)."""
    slots, parts, ntab = rule_parts(elem, integration)
    geom = {**geom_subs(), **band_subs()} if band else geom_subs()
    share = (1 - LO - HI) if band else 1
    section_points = [rp.points[2] for rp in elem.rule(integration)]
    nsh = elem.nshape
    q0 = [sp.Symbol(f"q0[{i}]", real=True) for i in range(elem.ndof)]
    grads = shape_gradients(elem)
    prog = Program()
    for ip, part in enumerate(parts):
        for p, (s, w) in enumerate(part.rule):
            base = part.tab_offset + p * part.stride
            # a part with one point through the height (the centreline part of
            # selective reduced integration) is evaluated for every layer at the
            # layered section's neutral axis (geom[BK_GEOM_BAND_AXIS]): where bending
            # strains nothing, as the middle of a one-material section
            sub = qp_coords(s, band if section_points[ip] > 1 or not band else "axis")
            gp = [[sp.expand(grads[a][J].subs(sub)).subs(geom) for J in range(3)] for a in range(nsh)]
            J0 = sp.Matrix(3, 3, lambda i, J: prog.define(
                f"J{ip}_{p}_{i}{J}", sum(q0[3 * a + i] * gp[a][J] for a in range(nsh))))
            det, Mmap = reference_map(prog, J0, f"{ip}_{p}")
            prog.output(f"tab[{base}]", (sp.Float(w) * L * B * H * share).subs(geom) * det, op="=")
            for k, e in enumerate(slots.exprs):
                prog.output(f"tab[{base + 1 + k}]", sp.expand(e.subs(sub)).subs(geom), op="=")
            for k, m in enumerate(Mmap):
                prog.output(f"tab[{base + 1 + len(slots.exprs) + k}]", m, op="=")
    return prog, ntab


def reference_map(prog, J0, tag):
    """(det J0, the entries MAP_ENTRIES of M = R^-1), J0 = Q0 R the Gram-Schmidt
    (QR) factorization of J0's columns, e1 along the first (the reference tangent)."""
    c = [J0[:, j] for j in range(3)]
    R00 = prog.define(f"R00_{tag}", sp.sqrt(c[0].dot(c[0])))
    e1 = sp.Matrix([prog.define(f"e1{i}_{tag}", c[0][i] / R00) for i in range(3)])
    R01 = prog.define(f"R01_{tag}", e1.dot(c[1]))
    u = c[1] - e1 * R01
    R11 = prog.define(f"R11_{tag}", sp.sqrt(u.dot(u)))
    e2 = sp.Matrix([prog.define(f"e2{i}_{tag}", u[i] / R11) for i in range(3)])
    e3 = e1.cross(e2)
    R02, R12, R22 = (prog.define(f"R{k}2_{tag}", e.dot(c[2])) for k, e in enumerate((e1, e2, e3)))
    Rm = sp.Matrix([[R00, R01, R02], [0, R11, R12], [0, 0, R22]])
    Mi = Rm.inv()
    return R00 * R11 * R22, [sp.simplify(Mi[J, K]) for J, K in MAP_ENTRIES]


def deformation_gradient(prog, elem, q, t, name="F"):
    """F = (sum_a q_a g_a^T) M at a point (t: its table row); returns (F, M, g)
    with g(a, J) the gradient slot of shape function a."""
    slots = gradient_slots(elem)
    nsl, nsh = len(slots.exprs), elem.nshape

    def g(a, J):
        r = slots.ref.get((a, J))
        return 0 if r is None else r[1] * t[1 + r[0]]

    M = sp.zeros(3, 3)
    for k, (J, K) in enumerate(MAP_ENTRIES):
        M[J, K] = t[1 + nsl + k]
    Fp = sp.zeros(3, 3)
    for i in range(3):
        for J in range(3):
            Fp[i, J] = prog.define(f"{name}p{i}{J}", sp.collect(
                sp.expand(sum(q[3 * a + i] * g(a, J) for a in range(nsh))), t[1:1 + nsl]))
    F = sp.Matrix(3, 3, lambda i, J: prog.define(f"{name}{i}{J}", sum(Fp[i, K] * M[K, J] for K in range(3))))
    return F, M, g


def table_symbols(elem):
    return [sp.Symbol(f"t[{i}]", real=True) for i in range(1 + len(gradient_slots(elem).exprs) + NMAP)]


def mapped_tangent(prog, A, M, prefix="A", index=None):
    """Outputs prefix[x] = A'[iJkL] = sum_PQ M_JP M_LQ A[i,P,k,Q] for (iJkL) the
    x-th of `index` (default A_INDEX); A(i, P, k, Q) gives the untransformed entries."""
    index = A_INDEX if index is None else index
    Bt = {}
    for i in range(3):
        for J in range(3):
            for k in range(3):
                for Q in range(3):
                    Bt[(i, J, k, Q)] = prog.define(f"{prefix}m{i}{J}{k}{Q}",
                                                   sum(M[J, P] * A(i, P, k, Q) for P in range(3)))
    for x, (i, J, k, Ll) in enumerate(index):
        prog.output(f"{prefix}[{x}]", sum(M[Ll, Q] * Bt[(i, J, k, Q)] for Q in range(3)), op="=")


def sri_split(mat, I1, I2, J, C, params):
    """(W_full_order, W_centreline) of a material for selective reduced integration.

    At full order: the material's own uniaxial-stress energy of the axial stretch
    (the lateral stretches chosen so that the lateral stresses vanish, derived
    from W in gen/uniaxial.py) and the transverse shears with the small-strain
    shear modulus, U(C11) + mu0/2 (C12^2 + C13^2): bending and stretching see the
    material's uniaxial response whatever the element's lateral fields can do,
    torsion and transverse shear their full stiffness.  At the centreline points:
    the rest, W - W_full, which holds the lateral (Poisson, volumetric) response.
    For St. Venant-Kirchhoff this is E/2 E11^2 + 2 mu (E12^2 + E13^2), the split
    used before for that law alone."""
    from gen.uniaxial import full_order_energy
    W = mat.energy(I1, I2, J, params)
    W_full = full_order_energy(mat, params, C)
    return W_full, W - W_full


def material_energy(mat, part, I1, I2, J, C, params):
    if part == "all":
        return mat.energy(I1, I2, J, params)
    full, centre = sri_split(mat, I1, I2, J, C, params)
    if part == "full_order":
        return full
    if part == "centreline":
        return centre
    raise ValueError(f"unknown energy part {part!r}")


def body_program(elem, mat, part, want):
    """Per-quadrature-point program for one rule part.

    want: "energy" (output e), "force" (f), "tangent" (f and upper K) or
    "traction" (tr[3] = w P N0 with N0 = e_x, the reference section normal:
    the point's weighted first Piola-Kirchhoff traction, for the section
    resultants)."""
    ndof, nsh = elem.ndof, elem.nshape
    prog = Program()
    q = [sp.Symbol(f"q[{i}]", real=True) for i in range(ndof)]
    t = table_symbols(elem)
    params = {name: sp.Symbol(f"mat[{k}]", real=True) for k, name in enumerate(mat.PARAMS)}
    w = t[0]
    # Deformation gradient in the local reference frame (box gradient, then the map M).
    Fm, Mm, g = deformation_gradient(prog, elem, q, t)
    Cm = sp.zeros(3, 3)
    bm = sp.zeros(3, 3)
    for I in range(3):
        for Jj in range(I, 3):
            Cm[I, Jj] = Cm[Jj, I] = prog.define(f"C{I}{Jj}", sum(Fm[k, I] * Fm[k, Jj] for k in range(3)))
            bm[I, Jj] = bm[Jj, I] = prog.define(f"b{I}{Jj}", sum(Fm[I, k] * Fm[Jj, k] for k in range(3)))
    cof_expr = cofactor(Fm)
    cof = sp.Matrix(3, 3, lambda i, j: prog.define(f"cof{i}{j}", cof_expr[i, j]))
    I1 = prog.define("I1", Cm[0, 0] + Cm[1, 1] + Cm[2, 2])
    I2 = prog.define("I2", Cm[0, 0] * Cm[1, 1] + Cm[1, 1] * Cm[2, 2] + Cm[0, 0] * Cm[2, 2]
                     - Cm[0, 1]**2 - Cm[1, 2]**2 - Cm[0, 2]**2)
    Jdet = prog.define("J", sum(Fm[i, 0] * cof[i, 0] for i in range(3)))
    inv = {"I1": I1, "I2": I2, "J": Jdet}

    W = material_energy(mat, part, I1, I2, Jdet, Cm, params)
    # The uniaxial energy of the SRI split (gen/uniaxial.py) is a function of C11
    # whose value and derivatives the program computes.
    from gen.uniaxial import U0, define_uniaxial
    urepl = define_uniaxial(prog, mat, params, Cm[0, 0]) if W.has(U0) else {}
    # Variables W depends on: invariants, and components of C (element frame).
    dvar = {m: first_derivatives(Fm, Cm, I1, cof)[m] for m in INVARIANTS}
    d2var = dict(second_derivatives(Fm, Cm, bm, I1))
    for (I, Jc) in COMPONENTS:
        name = f"C{I}{Jc}"
        inv[name] = Cm[I, Jc]
        dvar[name] = component_first(Fm, I, Jc)
        d2var[name] = component_second(I, Jc)
    names = list(inv)
    if want == "energy":
        prog.output("e", w * W.xreplace(urepl))
        return prog, params

    # Material derivatives (times the point weight) as named scalars.
    Wm = {}
    for m in names:
        d = sp.diff(W, inv[m]).xreplace(urepl)
        if d != 0:
            Wm[m] = prog.define(f"W_{m}", w * d)
    Wmn = {}
    if want == "tangent":
        for x, m in enumerate(names):
            for n in names[x:]:
                d = sp.diff(W, inv[m], inv[n]).xreplace(urepl)
                if d != 0:
                    Wmn[(m, n)] = Wmn[(n, m)] = prog.define(f"W_{m}_{n}", w * d)

    dI = dvar
    P = sp.Matrix(3, 3, lambda i, J: prog.define(
        f"P{i}{J}", sum(Wm[m] * dI[m][i, J] for m in Wm)))
    if want == "traction":          # the weighted traction P N0 on the reference section x = const
        for i in range(3):
            prog.output(f"tr[{i}]", P[i, 0], op="=")
        return prog, params
    Pb = sp.Matrix(3, 3, lambda i, J: prog.define(f"Pb{i}{J}", sum(P[i, K] * Mm[J, K] for K in range(3))))
    for a in range(nsh):
        for i in range(3):
            prog.output(f"f[{3 * a + i}]", sum(Pb[i, J] * g(a, J) for J in range(3)))
    if want == "force":
        return prog, params

    d2I = d2var
    At = {}
    for x, (i, J, k, Ll) in enumerate(A_INDEX):
        expr = sum(Wmn[(m, n)] * dI[m][i, J] * dI[n][k, Ll] for (m, n) in Wmn)
        expr += sum(Wm[m] * d2I[m](i, J, k, Ll) for m in Wm)
        At[(i, J, k, Ll)] = At[(k, Ll, i, J)] = prog.define(f"At{x}", sp.expand(expr))
    mapped_tangent(prog, lambda i, P_, k, Q: At[(i, P_, k, Q)], Mm)
    return prog, params


# The 45 distinct entries of the symmetric 3x3x3x3 tangent dP/dF, (iJ) <= (kL).
A_INDEX = tuple((i, J, k, L) for i in range(3) for J in range(3) for k in range(3) for L in range(3)
                if 3 * i + J <= 3 * k + L)
# The 36 distinct entries of an antisymmetric one (B[iJkL] = -B[kLiJ]), (iJ) < (kL).
SKEW_INDEX = tuple(x for x in A_INDEX if 3 * x[0] + x[1] < 3 * x[2] + x[3])


def _node_row_programs(nsh, ndof, g, tensor, skip, place):
    """One Program per row node a: for r = 3a + i and c = 3b + k from r + skip
    on, sum_JL g_aJ g_bL tensor(i, J, k, L) into K[place(r, c)] (the
    symmetric part's upper triangle, the antisymmetric part's lower)."""
    progs = []
    for a in range(nsh):
        prog = Program()
        for i in range(3):
            r = 3 * a + i
            for c in range(r + skip, ndof):
                b, k = divmod(c, 3)
                expr = 0
                for J in range(3):
                    gaJ = g(a, J)
                    if gaJ == 0:
                        continue
                    for Ll in range(3):
                        gbL = g(b, Ll)
                        if gbL != 0:
                            expr += gaJ * gbL * tensor(i, J, k, Ll)
                if expr != 0:
                    prog.output(f"K[{place(r, c)}]", expr)
        progs.append(prog)
    return progs


def contraction_programs(elem):
    """Per row node a: K[(3a+i), (3b+k)] += sum_JL g_aJ g_bL A[i,J,k,L] for the upper
    triangle, with A[45] (weighted dP/dF) and the table slots t[] as inputs.  This
    part depends on the element only, so all materials share it."""
    slots = gradient_slots(elem)
    ndof, nsh = elem.ndof, elem.nshape
    t = [sp.Symbol(f"t[{i}]", real=True) for i in range(1 + len(slots.exprs))]
    Asym = [sp.Symbol(f"A[{x}]", real=True) for x in range(len(A_INDEX))]
    pos = {key: x for x, key in enumerate(A_INDEX)}

    def g(a, J):
        r = slots.ref.get((a, J))
        return 0 if r is None else r[1] * t[1 + r[0]]

    def Aget(i, J, k, Ll):
        return Asym[pos[(i, J, k, Ll)]] if 3 * i + J <= 3 * k + Ll else Asym[pos[(k, Ll, i, J)]]

    return _node_row_programs(nsh, ndof, g, Aget, 0, lambda r, c: r * ndof + c)


def skew_contraction_programs(elem):
    """The antisymmetric part of a tangent: per row node a, X_rc = sum_JL g_aJ g_bL
    B[i,J,k,L] for r = 3a+i < c = 3b+k, with B[36] (SKEW_INDEX) the antisymmetric
    tensor's entries, added into the lower triangle K[c, r] (the kernel then makes
    K[r, c] = upper + X, K[c, r] = upper - X; the diagonal of an antisymmetric part
    is zero)."""
    slots = gradient_slots(elem)
    ndof, nsh = elem.ndof, elem.nshape
    t = [sp.Symbol(f"t[{i}]", real=True) for i in range(1 + len(slots.exprs))]
    Bsym = [sp.Symbol(f"Ask[{x}]", real=True) for x in range(len(SKEW_INDEX))]
    pos = {key: x for x, key in enumerate(SKEW_INDEX)}

    def g(a, J):
        r = slots.ref.get((a, J))
        return 0 if r is None else r[1] * t[1 + r[0]]

    def Bget(i, J, k, Ll):
        if 3 * i + J < 3 * k + Ll:
            return Bsym[pos[(i, J, k, Ll)]]
        if 3 * i + J > 3 * k + Ll:
            return -Bsym[pos[(k, Ll, i, J)]]
        return 0

    return _node_row_programs(nsh, ndof, g, Bget, 1, lambda r, c: c * ndof + r)


def invariants_program(elem):
    """J = det F, I1 = tr C, I2 of C = F^T F at one quadrature point (t: its table
    row), into inv[0..2]: what the runtime checks a state against (inverted or
    over-compressed elements, strains beyond the range of a law)."""
    prog = Program()
    q = [sp.Symbol(f"q[{i}]", real=True) for i in range(elem.ndof)]
    F, _, _ = deformation_gradient(prog, elem, q, table_symbols(elem))
    C = sp.zeros(3, 3)
    for I in range(3):
        for Jj in range(I, 3):
            C[I, Jj] = C[Jj, I] = prog.define(f"C{I}{Jj}", sum(F[k, I] * F[k, Jj] for k in range(3)))
    cof = cofactor(F)
    prog.output("inv[0]", sum(F[i, 0] * cof[i, 0] for i in range(3)), op="=")
    prog.output("inv[1]", C[0, 0] + C[1, 1] + C[2, 2], op="=")
    prog.output("inv[2]", C[0, 0] * C[1, 1] + C[1, 1] * C[2, 2] + C[0, 0] * C[2, 2]
                - C[0, 1]**2 - C[1, 2]**2 - C[0, 2]**2, op="=")
    return prog


def lowered_body(elem, mat, part, want):
    prog, params = body_program(elem, mat, part, want)
    return lower(prog, hoistable=params.values())


def viscous_body_program(elem, want="tangent"):
    """Kelvin-Voigt damping at one quadrature point: viscous second Piola-Kirchhoff
    stress S_v = lam_v tr(dE/dt) I + 2 mu_v dE/dt (visc = {lam_v, mu_v}: the
    retardation time times the small-strain Lame constants), dE/dt = sym(F^T dF/dt).

    want: "force" (f += w F S_v g_a only: residual-only evaluations), "dissipation"
    (the same and D += w S_v : dE/dt / 2, the Rayleigh dissipation function, whose
    derivative by qd is f), or "tangent" (f and, for the Newton matrix gc C + gk K
    with C = df/dqd and K = df/dq, the tensors A[45] = gc w dP_v/d(dF/dt) + gk (the
    symmetric part of w dP_v/dF) and Ask[36] = gk (its antisymmetric part), contracted
    by <element>_tangent_contract and _contract_skew).  w dP_v/dF at fixed dF/dt is
    delta_ik S_v,JL (the stress part) + w (lam F_iJ Fd_kL + mu (F_iL Fd_kJ +
    (F Fd^T)_ik delta_JL)) (the variation of dE/dt with F), not symmetric.  gc, gk
    are the kernel's scalar arguments (the analysis' factors, e.g. gamma' and 1)."""
    ndof, nsh = elem.ndof, elem.nshape
    prog = Program()
    q = [sp.Symbol(f"q[{i}]", real=True) for i in range(ndof)]
    qd = [sp.Symbol(f"qd[{i}]", real=True) for i in range(ndof)]
    t = table_symbols(elem)
    lam, mu = sp.Symbol("visc[0]", real=True), sp.Symbol("visc[1]", real=True)
    w = t[0]
    F, Mm, g = deformation_gradient(prog, elem, q, t)
    Fd, _, _ = deformation_gradient(prog, elem, qd, t, name="Fd")
    Ed = (F.T * Fd + Fd.T * F) / 2
    Ed = sp.Matrix(3, 3, lambda I, J: prog.define(f"Ed{min(I, J)}{max(I, J)}", Ed[min(I, J), max(I, J)]))
    tr = Ed[0, 0] + Ed[1, 1] + Ed[2, 2]
    S = sp.Matrix(3, 3, lambda I, J: prog.define(f"Sv{min(I, J)}{max(I, J)}",
                                                 w * (lam * tr * (1 if I == J else 0) + 2 * mu * Ed[min(I, J), max(I, J)])))
    P = F * S * Mm.T
    for a in range(nsh):
        for i in range(3):
            prog.output(f"f[{3 * a + i}]", sum(P[i, J] * g(a, J) for J in range(3)))
    if want == "dissipation":
        prog.output("D", sum(S[I, J] * Ed[I, J] for I in range(3) for J in range(3)) / 2)
    if want != "tangent":
        return prog
    gc, gk = sp.Symbol("gc", real=True), sp.Symbol("gk", real=True)
    b = F * F.T
    bd = sp.Matrix(3, 3, lambda i, k: prog.define(f"bd{i}{k}", sum(F[i, m] * Fd[k, m] for m in range(3))))
    d = lambda u, v: 1 if u == v else 0

    def T(i, J, k, L_):               # w dP_v/dF_kL through dE/dt
        return w * (lam * F[i, J] * Fd[k, L_] + mu * (F[i, L_] * Fd[k, J] + bd[i, k] * d(J, L_)))
    mapped_tangent(prog, lambda i, J, k, L_: gc * w * (lam * F[i, J] * F[k, L_] + mu * (F[i, L_] * F[k, J]
                                                                                        + b[i, k] * d(J, L_)))
                   + gk * (d(i, k) * S[J, L_] + (T(i, J, k, L_) + T(k, L_, i, J)) / 2), Mm)
    mapped_tangent(prog, lambda i, J, k, L_: gk * (T(i, J, k, L_) - T(k, L_, i, J)) / 2, Mm, prefix="Ask",
                   index=SKEW_INDEX)
    return prog
