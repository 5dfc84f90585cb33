"""Moments fixed in space, applied through the kinematics an element has.

section_moment (continuum elements, through the section slope vectors r_y, r_z):
with e1 = r_y/|r_y|, e2 = r_z/|r_z| and the section normal t = e1 x e2/|e1 x e2|,
the virtual rotation of a rigidly rotating section is
    dtheta = t (e2 . de1 - e1 . de2)/2 + e1 (t . de2) - e2 (t . de1),
so M . dtheta = Q_ry . dr_y + Q_rz . dr_z with
    Q_ry = (M_t e2 / 2 - M_2 t) / |r_y|,   Q_rz = (-M_t e1 / 2 + M_1 t) / |r_z|,
M_t = M . t, M_1 = M . e1, M_2 = M . e2.  For a deformed section this is the
couple a rigid rotation of its frame would feel.

axis_moment (gradient-deficient cable, through the axis slope r_x): the tangent
t = r_x/|r_x| turns by dtheta_perp = t x dr_x / |r_x|, so Q_rx = M x r_x / |r_x|^2;
the component of M along the axis does no work (the cable has no torsion).

quaternion_moment (beams with nodal rotations, quaternion p = (s, v), not
necessarily unit): the spatial virtual rotation is dtheta = 2 (s dv - v ds +
v x dv)/|p|^2, so Q_s = -2 M.v/|p|^2, Q_v = 2 (s M + M x v)/|p|^2.

section_frame (follower loads, elements without a rotation of their own): the
orthonormal frame of the section vectors an element's frame() gives, e3 = d3/|d3|,
e1 = d1 - (d1 . e3) e3 normalised, e2 = e3 x e1; section_frame_programs emits it
with its Jacobian in the element coordinates, dR/dq = dR/dd dd/dq (a follower
load c1 e1 + c2 e2 + c3 e3 has the Jacobian c1 de1/dq + c2 de2/dq + c3 de3/dq).
"""
import sympy as sp

from gen.program import Program


def _vec(name):
    return sp.Matrix([sp.Symbol(f"{name}[{i}]", real=True) for i in range(3)])


def section_moment(ry, rz, M):
    """Generalized forces (Q_ry, Q_rz) as a list of 6 expressions."""
    ny, nz = sp.sqrt(ry.dot(ry)), sp.sqrt(rz.dot(rz))
    e1, e2 = ry / ny, rz / nz
    c = e1.cross(e2)
    t = c / sp.sqrt(c.dot(c))
    Mt, M1, M2 = M.dot(t), M.dot(e1), M.dot(e2)
    return list((Mt * e2 / 2 - M2 * t) / ny) + list((-Mt * e1 / 2 + M1 * t) / nz)


def axis_moment(rx, M):
    return list(M.cross(rx) / rx.dot(rx))


def quaternion_moment(s, v, M):
    n2 = s**2 + v.dot(v)
    return [-2 * M.dot(v) / n2] + list(2 * (s * M + M.cross(v)) / n2)


def _named(prog, name, expr):
    """expr as a defined symbol of prog (atoms, e.g. 0, as they are)."""
    expr = sp.sympify(expr)
    return expr if expr.is_Atom else prog.define(name, expr)


def section_frame(d1, d3):
    """Rows (e1, e2, e3) of the orthonormal frame of d1, d3 (3x1 Matrices) as a
    list of 9 expressions."""
    e3 = d3 / sp.sqrt(d3.dot(d3))
    w = d1 - d1.dot(e3) * e3
    e1 = w / sp.sqrt(w.dot(w))
    return list(e1) + list(e3.cross(e1)) + list(e3)


def section_frame_programs(d1, d3, q, nd):
    """(R only, R and Jacobian) Programs of the section frame of d1, d3 (3x1
    Matrices of expressions in the coordinate symbols q[nd]): R[9] = e1, e2, e3
    and dR[k nd + j] = dR_k/dq_j (every entry written), through d."""
    dexpr = list(d1) + list(d3)
    progs = []
    for jac in (False, True):
        prog = Program()
        ds = [prog.define(f"fd{m}", e) for m, e in enumerate(dexpr)]
        R = section_frame(sp.Matrix(ds[:3]), sp.Matrix(ds[3:]))
        for k in range(9):
            prog.output(f"R[{k}]", R[k], op="=")
        if jac:
            G = [[_named(prog, f"fg{k}_{m}", sp.diff(R[k], ds[m])) for m in range(6)] for k in range(9)]
            D = [[sp.diff(e, q[j]) for j in range(nd)] for e in dexpr]
            for k in range(9):
                for j in range(nd):
                    prog.output(f"dR[{k * nd + j}]", sum(G[k][m] * D[m][j] for m in range(6)), op="=")
        progs.append(prog)
    return progs
