"""Joint actuators, derived with sympy (emitted into out/kernels/joints.c by
gen/emit_body.py): the joint coordinate s(x) of a joint with an axis, its
gradient and Hessian, from which the runtime (runtime/assembly/actuators.c)
makes a motor's generalized force Q = tau ds/dx and its exact Jacobian.

Coordinates and parameters are the joints' (gen/body.py): x[14] = (r_a, p_a,
r_b, p_b), prm[0..23] = (c_a, c_b, A_a, A_b); o = r + R c, d = o_b - o_a,
u_k = R_a a_k, v_k = R_b b_k; the joint axis is the third.
  rotation     th = atan2(Y, X), X = v_1.u_1, Y = v_2.u_1: the angle of frame a
               relative to frame b about the axis (that of joints.csv and of a
               prescribed_rotation); the kernel gives X, Y, and
               dth/dx = (X dY - Y dX)/(X^2 + Y^2) and its Hessian (the value
               itself, unwrapped, is the runtime's atan2);
  translation  s = -d.u_3: frame a's displacement along the axis relative to b.
A torque tau acting on a about the axis and -tau on b does the virtual work
tau dth, a force F along the axis on a and -F on b the work F ds: Q = tau ds/dx.
"""
import sympy as sp

from gen.body import NX, _frames
from gen.program import Program
from gen.rod import _syms

KINDS = ("rotation", "translation")


def _coordinate(kind, x, prm):
    """(value outputs [(name, expr)], gradient, Hessian as nested lists) of the joint coordinate."""
    d, u, v = _frames(x, prm)
    n = len(x)
    if kind == "rotation":
        X, Y = v[0].dot(u[0]), v[1].dot(u[0])
        gX, gY = [sp.diff(X, xi) for xi in x], [sp.diff(Y, xi) for xi in x]
        n2 = X * X + Y * Y
        grad = [(X * gY[i] - Y * gX[i]) / n2 for i in range(n)]
        hess = [[(gX[j] * gY[i] + X * sp.diff(gY[i], x[j]) - gY[j] * gX[i] - Y * sp.diff(gX[i], x[j])) / n2
                 - grad[i] * 2 * (X * gX[j] + Y * gY[j]) / n2 for j in range(n)] for i in range(n)]
        return [("val[0]", X), ("val[1]", Y)], grad, hess
    s = -d.dot(u[2])
    grad = [sp.diff(s, xi) for xi in x]
    return [("val[0]", s), ("val[1]", sp.Integer(0))], grad, [[sp.diff(g, xj) for xj in x] for g in grad]


def actuator_program(kind):
    """val[2] (rotation: X, Y; translation: s, 0), grad[14] = ds/dx and
    H[14 i + j] (i <= j) = d2s/dx_i dx_j."""
    x, prm = _syms("x", NX), _syms("prm", 24)
    vals, grad, hess = _coordinate(kind, x, prm)
    prog = Program()
    for name, e in vals:
        prog.output(name, e, op="=")
    for i in range(NX):
        prog.output(f"grad[{i}]", grad[i], op="=")
    for i in range(NX):
        for j in range(i, NX):
            prog.output(f"H[{NX * i + j}]", hess[i][j], op="=")
    return prog
