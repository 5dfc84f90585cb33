"""The energy terms of a rod element x material kernel as programs: the
quaternion gauge penalty and its derivatives, the material law as a function of
the strains (with the multipliers of the constrained components) and the section
resultants it gives."""
import sympy as sp

from gen.program import Program
from gen.rod import NODE_DOF, NQ, NS, NV, STRAIN_NAMES, _named, _sym, _syms, tri
from gen.rod_kinematics import b_pattern


# ----------------------------------------------------------------------------
# Quaternion gauge penalty  sum_n w_n cg/4 (|p_n|^2 - 1)^2,  w = (1/2, 1, 1/2)

def _gauge():
    q = _syms("q", NQ)
    cg = sp.Symbol("cg", real=True)
    U = 0
    for n, wn in zip(range(3), (sp.Rational(1, 2), 1, sp.Rational(1, 2))):
        p = q[NODE_DOF * n + 3: NODE_DOF * n + 7]
        U += wn * cg / 4 * (sum(x * x for x in p) - 1)**2
    return q, U


def gauge_program(order):
    """order 0: ge = U; 1: f[i] += dU/dq_i; 2: K[nd*i + j] += d2U/dq_i dq_j (i <= j)."""
    q, U = _gauge()
    prog = Program()
    if order == 0:
        prog.output("ge", U, op="=")
    elif order == 1:
        for i in range(NQ):
            d = sp.diff(U, q[i])
            if d != 0:
                prog.output(f"f[{i}]", d, op="+=")
    else:
        for i in range(NQ):
            for j in range(i, NQ):
                d = sp.diff(U, q[i], q[j])
                if d != 0:
                    prog.output(f"K[nd*{i} + {j}]", d, op="+=")
    return prog


def gauge_coefficient(params):
    """cg of the gauge penalty from the material parameters and l = tab[0]."""
    return (params["GJ"] + params["EI1"] + params["EI2"]) / _sym("tab", 0)


# ----------------------------------------------------------------------------
# Element x material: the energy as a function of the strains

def material_programs(elem, mat):
    """Programs of one Gauss point of an element x material kernel, in the symbols
    s[6], B[...], lam[nc] (the point's multipliers), w (weight x l), mat[...]:
      "energy":  e += w (W(s) + c_l sum_j lam_j s_cj)
      "force":   sg[6] = dL/ds; Gv[13] = B^T sg (tangent path only); fl[j] = dL/dlam_j
      "tangent": Hv[tri13] += B^T D B (D = d2L/ds2); C[13 j + a] = d fl_j / dv_a
    (c_l = EA scales the multipliers), and the parameter symbols."""
    params = {name: _sym("mat", k) for k, name in enumerate(mat.PARAMS)}
    s = _syms("s", NS)
    lam = _syms("lam", len(elem.constrained))
    w = sp.Symbol("w", real=True)
    gs = dict(zip(STRAIN_NAMES, s))
    W = mat.energy([gs["g1"], gs["g2"], gs["g3"]], [gs["k1"], gs["k2"], gs["k3"]], params)
    W = W.subs({gs[c]: 0 for c in elem.constrained})
    cl = params["EA"]
    L = w * (W + cl * sum(lam[j] * gs[c] for j, c in enumerate(elem.constrained)))
    pattern = b_pattern()
    Bs = {(k, a): _sym("B", k * NV + a) for k, a in pattern}

    pe = Program()
    pe.output("e", L, op="+=")

    pf = Program()
    sg = []
    for k in range(NS):
        sg.append(_named(pf, f"sig{k}", sp.diff(L, s[k])))
        pf.output(f"sg[{k}]", sg[k], op="=")
    for a in range(NV):
        pf.output(f"Gv[{a}]", sum(sg[k] * Bs[(k, a)] for k in range(NS) if (k, a) in Bs), op="=")
    for j, c in enumerate(elem.constrained):
        pf.output(f"fl[{j}]", sp.diff(L, lam[j]), op="=")

    pk = Program()
    D = {(k, l): sp.diff(L, s[k], s[l]) for k in range(NS) for l in range(NS)}
    DB = {}
    for k in range(NS):
        for b in range(NV):
            e = sum(D[(k, l)] * Bs[(l, b)] for l in range(NS) if (l, b) in Bs and D[(k, l)] != 0)
            if e != 0:
                DB[(k, b)] = _named(pk, f"DB{k}_{b}", e)
    for (a, b), i in tri(NV).items():
        e = sum(Bs[(k, a)] * DB[(k, b)] for k in range(NS) if (k, a) in Bs and (k, b) in DB)
        if e != 0:
            pk.output(f"Hv[{i}]", e, op="+=")
    for j, c in enumerate(elem.constrained):
        k = STRAIN_NAMES.index(c)
        g = sp.diff(L, lam[j], s[k])
        for a in range(NV):
            pk.output(f"C[{NV * j + a}]", g * Bs[(k, a)] if (k, a) in Bs else 0, op="=")
    return {"energy": pe, "force": pf, "tangent": pk}, params


def section_program(elem, mat):
    """The stress resultants at a Gauss point in the material frame, rs[6] =
    (n1, n2, n3, m1, m2, m3) (components along d3, d1, d2: N, Q2, Q3, T, M2,
    M3), from s[6], lam[nc] and mat[...]: dW/ds of the law for the free strain
    components, EA lam_j (the force the multiplier of Gamma_j = 0 exerts, the
    resultant conjugate to that component in the constrained energy) for the
    components held at zero.  Returns (program, parameter symbols)."""
    params = {name: _sym("mat", k) for k, name in enumerate(mat.PARAMS)}
    s = _syms("s", NS)
    lam = _syms("lam", len(elem.constrained))
    gs = dict(zip(STRAIN_NAMES, s))
    W = mat.energy([gs["g1"], gs["g2"], gs["g3"]], [gs["k1"], gs["k2"], gs["k3"]], params)
    W = W.subs({gs[c]: 0 for c in elem.constrained})
    prog = Program()
    for k, name in enumerate(STRAIN_NAMES):
        if name in elem.constrained:
            e = params["EA"] * lam[elem.constrained.index(name)]
        else:
            e = sp.diff(W, s[k])
        prog.output(f"rs[{k}]", e, op="=")
    return prog, params


def section_source_label(elem):
    """What the rows of sections.csv from sections() hold: "law" (n = C Gamma,
    m = D K), with the components held at zero by multipliers named."""
    names = dict(zip(STRAIN_NAMES, ("N", "Q2", "Q3")))
    if not elem.constrained:
        return "law"
    return "law;multiplier:" + " ".join(names[c] for c in elem.constrained)
