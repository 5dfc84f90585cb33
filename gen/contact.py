"""Contact kernels, derived with sympy: the gap between a point of a beam's
centreline and a rigid primitive with its first and second derivatives in the
point's position, the barrier that keeps gaps positive, and the smoothed
Coulomb friction profile (out/kernels/contact.{h,c}).

Gaps (g > 0: apart, the beam's own section radius not included; x the point):
  half-space  n . x - d                    (prm: unit normal n, offset d)
  sphere      |x - c| - R                  (prm: centre c, radius R)
  segment     |x - a - t (b - a)| - R,     t = (x - a).(b - a) / |b - a|^2
              the distance to the segment's line; the ends (t <= 0, t >= 1) of
              a capsule are spheres (prm: a, b, R; out: t after the
              derivatives, for the caller's choice of branch)
Each gap kernel writes out[0] = g, out[1..3] = dg/dx, out[4..12] = d2g/dx2
(row-major).

Barrier (incremental potential contact, Li et al. 2020): for a distance
0 < s < shat, b(s) = -(s - shat)^2 ln(s / shat), zero beyond; C2 at s = shat,
growing without bound as s -> 0, so an iterate that keeps s > 0 (the step
limiter's job) feels a force that grows as it approaches.  out[0..2] = b, b',
b''.

Primitives of rigid bodies: a primitive is given in the reference
configuration; a point y of a beam is taken to the body's reference
coordinates, z = X + R0 R(p)^T (y - r), with (r, p) the body's centre and
quaternion (R(p) the rotation of p/|p|), X and R0 its reference centre and
rotation (prm[12]: X, then R0 row-major), and the gap is the reference
primitive's at z.  bk_contact_body_frame writes z (out[0..2]), dz/dv
(out[3..32], 3 x 10 row-major, v = (y, r, p)) and d2z_k/dv2 (out[33 + 100 k
..], 10 x 10 row-major): the chain rule then gives the gap's derivatives in v.
Friction is measured in z too, so it acts on the slip relative to the body.

Rolling (a section that carries a rotation, a node's quaternion p): friction
acts on the section's surface, at the material point y + R(p) a with a the
lever arm in the node's frame (fixed over a step: the arm -r n of the last
accepted state taken back by R(p)^T).  bk_contact_lever writes w = R(p) a
(out[0..2]), dw/dp (out[3..14], 3 x 4 row-major) and the second-derivative
term sum_i f_i d2 w_i/dp2 (out[15..30], 4 x 4 row-major) for the force f on
the point, so the point's force f on the quaternion, (dw/dp)^T f (the moment
w x f), and its Jacobian are exact.  The same kernel takes a point of a rigid
body's reference (a body's box corner, a sphere's surface point) to where it
is: y = r + R(p) a with a = R0^T (Z - X).

Friction (the same paper's smoothed slip function): for a slip magnitude
y >= 0 and tolerance eps, f1(y) = 2 y/eps - y^2/eps^2 below eps, 1 beyond, so
the friction force mu N f1(y) t/|t| is exact Coulomb past eps and a stiff
linear spring below it (static friction up to the tolerance).  out[0..3] =
f1, f1', f1(y)/y, d(f1(y)/y)/dy, the last two regular at y = 0 (the force is
mu N (f1/y) u for the slip vector u)."""
import sympy as sp

from gen.c_functions import _function
from gen.program import Program, count_lowered, lower
from gen.rod import rotation

_D = "const double *restrict"
_W = "double *restrict"


def _vec(name, k=0, n=3):
    return sp.Matrix([sp.Symbol(f"{name}[{k + i}]", real=True) for i in range(n)])


def _gap_program(g, x, extra=()):
    """g, dg/dx, d2g/dx2 of a gap expression g(x) into out[0..12] (and extra
    outputs after them)."""
    p = Program()
    p.output("out[0]", g, op="=")
    dg = [sp.diff(g, xi) for xi in x]
    for i in range(3):
        p.output(f"out[{1 + i}]", dg[i], op="=")
    for i in range(3):
        for j in range(3):
            p.output(f"out[{4 + 3 * i + j}]", sp.diff(dg[i], x[j]), op="=")
    for k, e in enumerate(extra):
        p.output(f"out[{13 + k}]", e, op="=")
    return lower(p, ())


def half_space():
    x, n, d = _vec("x"), _vec("prm"), sp.Symbol("prm[3]", real=True)
    return _gap_program(n.dot(x) - d, x)


def sphere():
    x, c, R = _vec("x"), _vec("prm"), sp.Symbol("prm[3]", real=True)
    r = x - c
    return _gap_program(sp.sqrt(r.dot(r)) - R, x)


def segment():
    x, a, b, R = _vec("x"), _vec("prm"), _vec("prm", 3), sp.Symbol("prm[6]", real=True)
    e = b - a
    t = (x - a).dot(e) / e.dot(e)
    r = x - a - t * e
    return _gap_program(sp.sqrt(r.dot(r)) - R, x, extra=(t,))


def body_frame():
    y, r = _vec("y"), _vec("qb")
    s, v = sp.Symbol("qb[3]", real=True), _vec("qb", 4)
    X = _vec("prm")
    R0 = sp.Matrix(3, 3, [sp.Symbol(f"prm[{3 + k}]", real=True) for k in range(9)])
    z = X + R0 * rotation(s, v).T * (y - r)
    var = list(y) + list(r) + [s] + list(v)
    p = Program()
    for k in range(3):
        p.output(f"out[{k}]", z[k], op="=")
    for k in range(3):
        dk = [sp.diff(z[k], a) for a in var]
        for i in range(10):
            p.output(f"out[{3 + 10 * k + i}]", dk[i], op="=")
            for j in range(10):
                p.output(f"out[{33 + 100 * k + 10 * i + j}]", sp.diff(dk[i], var[j]), op="=")
    return lower(p, ())


def lever():
    p, a, f = _vec("p", 0, 4), _vec("a"), _vec("f")
    w = rotation(p[0], sp.Matrix(p[1:])) * a
    prog = Program()
    for i in range(3):
        prog.output(f"out[{i}]", w[i], op="=")
    dw = [[sp.diff(w[i], p[j]) for j in range(4)] for i in range(3)]
    for i in range(3):
        for j in range(4):
            prog.output(f"out[{3 + 4 * i + j}]", dw[i][j], op="=")
    g = [sum(f[i] * dw[i][j] for i in range(3)) for j in range(4)]
    for j in range(4):
        for k in range(4):
            prog.output(f"out[{15 + 4 * j + k}]", sp.diff(g[j], p[k]), op="=")
    return lower(prog, ())


def barrier():
    s, shat = sp.symbols("s shat", positive=True)
    b = -(s - shat) ** 2 * sp.log(s / shat)
    p = Program()
    p.output("out[0]", b, op="=")
    p.output("out[1]", sp.diff(b, s), op="=")
    p.output("out[2]", sp.diff(b, s, 2), op="=")
    return lower(p, ())


def friction():
    y, eps = sp.symbols("y eps", nonnegative=True)
    f1 = 2 * y / eps - y ** 2 / eps ** 2
    f1y = sp.simplify(f1 / y)                   # 2/eps - y/eps^2: regular at y = 0
    p = Program()
    p.output("out[0]", f1, op="=")
    p.output("out[1]", sp.diff(f1, y), op="=")
    p.output("out[2]", f1y, op="=")
    p.output("out[3]", sp.diff(f1y, y), op="=")
    return lower(p, ())


def transition():
    y, eps = sp.symbols("y eps", positive=True)
    z = (y - eps) / eps
    h = 3 * z ** 2 - 2 * z ** 3
    p = Program()
    p.output("out[0]", h, op="=")
    p.output("out[1]", sp.diff(h, y), op="=")
    return lower(p, ())


def _ops(low):
    pro, bod = count_lowered(low)
    return pro.total() + bod.total()


def _guarded(name, args, low, guard, doc):
    """(name, signature, doc, C lines) of bk_contact_NAME(a, b, out): the C
    lines `guard` (the closed-form ranges), else the generated NAME_inside."""
    a, b = args
    inner = f"static void {name}_inside(double {a}, double {b}, double *restrict out)"
    wrap = [f"void bk_contact_{name}(double {a}, double {b}, double *restrict out)", "{"]
    wrap += ["    " + line for line in guard] + [f"    {name}_inside({a}, {b}, out);", "}", ""]
    return f"bk_contact_{name}", wrap[0], f"{doc}; {_ops(low)} operations", _function(inner, low) + wrap


def functions():
    """(name, signature, doc, C lines) of every contact kernel, in file order."""
    out = []
    for name, make, nprm, nout, doc in (
            ("half_space", half_space, 4, 13, "gap to the half-space n . x >= d"),
            ("sphere", sphere, 4, 13, "gap to the sphere |x - c| = R"),
            ("segment", segment, 7, 14, "gap to the line of the segment a b (radius R), then t")):
        low = make()
        sig = (f"void bk_contact_gap_{name}({_D} x, {_D} prm, {_W} out)")
        out.append((f"bk_contact_gap_{name}", sig,
                    f"{doc}: x[3], prm[{nprm}] in; out[{nout}]; {_ops(low)} operations", _function(sig, low)))
    low = body_frame()
    sig = f"void bk_contact_body_frame({_D} y, {_D} qb, {_D} prm, {_W} out)"
    out.append(("bk_contact_body_frame", sig,
                f"reference coordinates z of y on a body (r, p) and their derivatives: y[3], qb[7], prm[12] in; "
                f"out[333]; {_ops(low)} operations", _function(sig, low)))
    low = lever()
    sig = f"void bk_contact_lever({_D} p, {_D} a, {_D} f, {_W} out)"
    out.append(("bk_contact_lever", sig,
                f"lever arm w = R(p) a of a section's surface point, dw/dp and sum f_i d2w_i/dp2: p[4], a[3], f[3] "
                f"in; out[31]; {_ops(low)} operations", _function(sig, low)))
    out.append(_guarded("barrier", ("s", "shat"), barrier(),
                        ["if (s >= shat) {", "    out[0] = out[1] = out[2] = 0.0;", "    return;", "}"],
                        "barrier b, b', b'' at the distance s (0 < s; zero from shat on)"))
    out.append(_guarded("friction", ("y", "eps"), friction(),
                        ["if (y >= eps) {", "    out[0] = 1.0;", "    out[1] = 0.0;", "    out[2] = 1.0 / y;",
                         "    out[3] = -1.0 / (y * y);", "    return;", "}"],
                        "slip function f1, f1', f1/y, (f1/y)' at the slip y >= 0 (tolerance eps)"))
    out.append(_guarded("transition", ("y", "eps"), transition(),
                        ["if (y <= eps || y >= 2.0 * eps) {", "    out[0] = y <= eps ? 0.0 : 1.0;", "    out[1] = 0.0;",
                         "    return;", "}"],
                        "static-to-kinetic step h, h' at the slip y >= 0 (tolerance eps)"))
    return out
