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
"""
import sympy as sp


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
