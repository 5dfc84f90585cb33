"""Rigid bodies and joints, derived with sympy (emitted by gen/emit_body.py).

Rigid body (element `rigid_body`, 7 DOFs: the centre of mass r and a quaternion
p; the rotation is that of p/|p|, its columns the body axes e1, e2, e3, which
are the principal axes of the inertia tensor):
  kinetic energy  T = 1/2 M |r'|^2 + 1/2 W^T diag(J1, J2, J3) W,
                  W = 2 Im(conj(p) p')/|p|^2 (body angular velocity);
  the translational part is the constant mass of the one position shape
  function (N = 1), the rotational part with its gyroscopic terms is the rods'
  nodal rotary inertia (gen/rod.py rotary_node_program) with the body's
  principal moments; gravity acts on r (volume = M); a gauge penalty
  cg/4 (|p|^2 - 1)^2 fixes the free scale of p without doing work.

Joints between two frames a and b (a beam node with a rotation, a rigid body,
or the ground: constants), coordinates x[14] = (r_a, p_a, r_b, p_b) and
parameters prm[24] = (c_a, c_b, A_a, A_b): c the joint point in the node's
frame, A (3 x 3, columns a_1, a_2, a_3, column-major in prm) the joint axes in
the node's frame, such that in the reference configuration both sides give
the same point and axes (the joint axis is the third).  With R = R(p/|p|):
  o = r + R c,  d = o_b - o_a,  u_k = R_a a_k,  v_k = R_b b_k;
  spherical   d = 0                                        (3 rows)
  revolute    d = 0, u_1.v_3 = 0, u_2.v_3 = 0              (5): turns about axis 3
  universal   d = 0, u_1.v_2 = 0                           (4): cross arms a_1 in a, b_2 in b
  fixed       d = 0, u_2.v_3 = u_3.v_1 = u_1.v_2 = 0       (6): a weld at any angle
  prismatic   u_2.v_3 = u_3.v_1 = u_1.v_2 = 0,
              d.u_1 = d.u_2 = 0                            (5): slides along axis 3
(the orientation rows hold the relative rotation at its reference value, to
first order exactly; they are gauge invariant in p).  Each type gives g(x), its
Jacobian G = dg/dx and the Hessian term H = sum_k nu_k d2 g_k / dx2.

Driven joints: frame a moved relative to frame b by a prescribed function of
time; prm[24], prm[25] = (c, s) are filled by the runtime at each time, and the
last row is linear and homogeneous in them, so that its k-th time derivative
is the same row with (c, s) replaced by their k-th derivatives:
  prescribed_rotation     d = 0, u_1.v_3 = u_2.v_3 = 0,
                          c (v_2.u_1) - s (v_1.u_1) = 0          (6), c, s = cos th, sin th:
                          a turned about axis 3 by th relative to b (sin(phi - th) = 0)
  prescribed_translation  u_2.v_3 = u_3.v_1 = u_1.v_2 = 0, d.u_1 = d.u_2 = 0,
                          -c d.u_3 - s = 0                       (6), c, s = 1, x:
                          a moved along axis 3 by x relative to b (d = o_b - o_a)

Welds of an ANCF node to a frame b (gen/scene/weld.py): the joint's position
rows are a spherical joint's (side a the ANCF node's r with a constant
identity quaternion, c_a = 0); the section rows read x[0..5] as nodal vectors
u, v of the ANCF node and x[10..13] as p_b (x[6..9] unused), with w_1 =
prm[6..8], w_2 = prm[9..11] their reference directions in b's frame
(R_b0^T u_0, R_b0^T v_0):
  weld_vectors  R_b w_1 - u = 0, R_b w_2 - v = 0           (6): two section vectors turn with b
  weld_vector   R_b w_1 - u = 0                            (3): one
  weld_tangent  (R_b w_1).u = (R_b w_2).u = 0              (2): a cable's r_x = u stays along b's
                rotated reference tangent (w_1, w_2 across it), its length free
"""
import sympy as sp

from gen.program import Program
from gen.rod import _sym, _syms, rotation
from gen.rod_inertia import rotary_node_program

NX = 14
NPARAM = 26
NDRIVE = 2          # prm[24], prm[25]: the drive's (c, s) at the time (driven joints)


def _frames(x, prm):
    ra, rb = sp.Matrix(x[0:3]), sp.Matrix(x[7:10])
    Ra = rotation(x[3], sp.Matrix(x[4:7]))
    Rb = rotation(x[10], sp.Matrix(x[11:14]))
    ca, cb = sp.Matrix(prm[0:3]), sp.Matrix(prm[3:6])
    A = [sp.Matrix(prm[6 + 3 * k: 9 + 3 * k]) for k in range(3)]
    B = [sp.Matrix(prm[15 + 3 * k: 18 + 3 * k]) for k in range(3)]
    d = rb + Rb * cb - ra - Ra * ca
    u = [Ra * a for a in A]
    v = [Rb * b for b in B]
    return d, u, v


def _orientation(u, v):
    return [u[1].dot(v[2]), u[2].dot(v[0]), u[0].dot(v[1])]


def joint_rows(name, x, prm):
    d, u, v = _frames(x, prm)
    if name == "spherical":
        return list(d)
    if name == "revolute":
        return list(d) + [u[0].dot(v[2]), u[1].dot(v[2])]
    if name == "universal":
        return list(d) + [u[0].dot(v[1])]
    if name == "fixed":
        return list(d) + _orientation(u, v)
    if name == "prismatic":
        return _orientation(u, v) + [d.dot(u[0]), d.dot(u[1])]
    if name in WELD_TYPES:
        Rb = rotation(x[10], sp.Matrix(x[11:14]))
        w1, w2 = Rb * sp.Matrix(prm[6:9]), Rb * sp.Matrix(prm[9:12])
        a, b = sp.Matrix(x[0:3]), sp.Matrix(x[3:6])
        if name == "weld_tangent":
            return [w1.dot(a), w2.dot(a)]
        return list(w1 - a) + (list(w2 - b) if name == "weld_vectors" else [])
    c, s = prm[24], prm[25]
    if name == "prescribed_rotation":
        return list(d) + [u[0].dot(v[2]), u[1].dot(v[2]), c * v[1].dot(u[0]) - s * v[0].dot(u[0])]
    if name == "prescribed_translation":
        return _orientation(u, v) + [d.dot(u[0]), d.dot(u[1]), -c * d.dot(u[2]) - s]
    raise KeyError(name)


WELD_TYPES = ("weld_vectors", "weld_vector", "weld_tangent")
JOINT_TYPES = ("spherical", "revolute", "universal", "fixed", "prismatic", "prescribed_rotation",
               "prescribed_translation") + WELD_TYPES
DRIVEN = {"prescribed_rotation": 1, "prescribed_translation": 2}   # bk_joint_kind.driven


def joint_nrow(name):
    return {"spherical": 3, "revolute": 5, "universal": 4, "fixed": 6, "prismatic": 5,
            "prescribed_rotation": 6, "prescribed_translation": 6, "weld_vectors": 6, "weld_vector": 3,
            "weld_tangent": 2}[name]


def joint_program(name, order):
    """order 1: g[k] and G[14 k + j]; order 2: H[14 i + j] (i <= j) = sum_k nu[k] d2 g_k/dx_i dx_j."""
    x, prm = _syms("x", NX), _syms("prm", NPARAM)
    rows = joint_rows(name, x, prm)
    prog = Program()
    if order == 1:
        for k, gk in enumerate(rows):
            prog.output(f"g[{k}]", gk, op="=")
            for j in range(NX):
                prog.output(f"G[{NX * k + j}]", sp.diff(gk, x[j]), op="=")
    else:
        nu = _syms("nu", len(rows))
        L = sum(n * gk for n, gk in zip(nu, rows))
        grad = [sp.diff(L, xi) for xi in x]
        for i in range(NX):
            for j in range(i, NX):
                prog.output(f"H[{NX * i + j}]", sp.diff(grad[i], x[j]), op="=")
    return prog


# ----------------------------------------------------------------------------
# Rigid body element

def body_rotary_program():
    """The nodal rotary inertia of gen/rod_inertia.py with Jn = (J1, J2, J3) about the
    body axes (the columns of R(p))."""
    return rotary_node_program()


def body_gauge_program(order):
    """q[7] = (r, p), cg = mat[0]: order 0: e = U; 1: f[i] = dU/dq_i; 2: K[7 i + j] = d2U (full)."""
    q = _syms("q", 7)
    cg = _sym("mat", 0)
    U = cg / 4 * (sum(x * x for x in q[3:7]) - 1)**2
    prog = Program()
    if order == 0:
        prog.output("e", U, op="=")
    elif order == 1:
        for i in range(7):
            prog.output(f"f[{i}]", sp.diff(U, q[i]), op="=")
    else:
        for i in range(7):
            for j in range(7):
                prog.output(f"K[{7 * i + j}]", sp.diff(U, q[i], q[j]), op="=")
    return prog


def body_frame_program():
    """pos[3] = r + (xi - 1/2) l e3 (xi = 1/2: the centre of mass; the rest draws the body
    as a cube of edge l = geom[BK_GEOM_L] along e3), d[9] = (e1, e2, e3)."""
    from gen.element import geom_symbol
    q = _syms("q", 7)
    xi = sp.Symbol("xi", real=True)
    R = rotation(q[3], sp.Matrix(q[4:7]))
    prog = Program()
    for i in range(3):
        prog.output(f"pos[{i}]", q[i] + (xi - sp.Rational(1, 2)) * geom_symbol("L") * R[i, 2], op="=")
    for k in range(3):
        for i in range(3):
            prog.output(f"d[{3 * k + i}]", R[i, k], op="=")
    return prog


def body_section_frame_programs():
    """(R only, R and dR[7 k + j] = dR_k/dq_j) of the body's section frame
    (bk_element.section_frame): its own rotation's axes, rows e1, e2, e3 (the
    d of body_frame_program: orthonormal, no Gram-Schmidt)."""
    q = _syms("q", 7)
    R = rotation(q[3], sp.Matrix(q[4:7]))
    rows = [R[i, k] for k in range(3) for i in range(3)]
    progs = []
    for jac in (False, True):
        prog = Program()
        for k in range(9):
            prog.output(f"R[{k}]", rows[k], op="=")
            if jac:
                for j in range(7):
                    prog.output(f"dR[{7 * k + j}]", sp.diff(rows[k], q[j]), op="=")
        progs.append(prog)
    return progs
