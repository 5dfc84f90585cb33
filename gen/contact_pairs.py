"""Beam-to-beam contact kernels, derived with sympy: the distances between
the pieces of two centrelines (out/kernels/contact_pairs.{h,c}), each with its
gradient and Hessian in the coordinates of the points it takes.

A beam's centreline is taken as the polyline of its contact sample points
(runtime/assembly/contact_pairs.c); two of its segments, a0 a1 and b0 b1, are
at the distance of their closest points, which is one of three smooth
functions depending on where those points lie (the runtime classifies):
  point-point  |p - q|                               x = (p, q): 6 coordinates
  point-edge   |p - e0 - t (e1 - e0)|,               x = (p, e0, e1): 9
               t = (p - e0).(e1 - e0) / |e1 - e0|^2  (the distance to the line)
  edge-edge    (b0 - a0).n / |n|, n = (a1 - a0) x (b1 - b0)
                                                     x = (a0, a1, b0, b1): 12
               the signed distance between the two lines (the caller takes
               its magnitude; undefined for parallel lines, where the runtime
               uses the point-edge distances instead)
Each kernel writes out[0] = d, out[1..n] = dd/dx, out[n+1..n+n^2] = d2d/dx2
(row-major), n its coordinate count.  One more, of the same layout, measures
how parallel two segments are (the runtime blends a crossing's energy into
that of segments lying along each other by it):
  cos2         ((a1 - a0).(b1 - b0))^2 / (|a1 - a0|^2 |b1 - b0|^2)
                                                     x = (a0, a1, b0, b1): 12  The barrier and the friction profile
are those of out/kernels/contact.h (the same energy as beam-to-primitive
contact)."""
import sympy as sp

from gen.c_functions import _function
from gen.program import Program, count_lowered, lower

_D = "const double *restrict"
_W = "double *restrict"


def _points(n):
    x = [sp.Symbol(f"x[{k}]", real=True) for k in range(3 * n)]
    return x, [sp.Matrix(x[3 * i:3 * i + 3]) for i in range(n)]


def _program(d, x):
    """d, its gradient and Hessian in x into out[...]."""
    n = len(x)
    p = Program()
    p.output("out[0]", d, op="=")
    g = [sp.diff(d, xi) for xi in x]
    for i in range(n):
        p.output(f"out[{1 + i}]", g[i], op="=")
    for i in range(n):
        for j in range(n):
            # the Hessian is symmetric: the lower triangle repeats the upper's expressions (CSE shares them)
            p.output(f"out[{1 + n + n * i + j}]", sp.diff(g[min(i, j)], x[max(i, j)]), op="=")
    return lower(p, ())


def point_point():
    x, (p, q) = _points(2)
    r = p - q
    return _program(sp.sqrt(r.dot(r)), x)


def point_edge():
    x, (p, e0, e1) = _points(3)
    e = e1 - e0
    t = (p - e0).dot(e) / e.dot(e)
    r = p - e0 - t * e
    return _program(sp.sqrt(r.dot(r)), x)


def edge_edge():
    x, (a0, a1, b0, b1) = _points(4)
    n = (a1 - a0).cross(b1 - b0)
    return _program((b0 - a0).dot(n) / sp.sqrt(n.dot(n)), x)


def cos2():
    x, (a0, a1, b0, b1) = _points(4)
    u, v = a1 - a0, b1 - b0
    return _program(u.dot(v) ** 2 / (u.dot(u) * v.dot(v)), x)


def _ops(low):
    pro, bod = count_lowered(low)
    return pro.total() + bod.total()


def functions():
    """(name, signature, doc, C lines) of every pair kernel, in file order."""
    out = []
    for name, make, npt, doc in (
            ("point_point", point_point, 2, "distance |p - q| of two points"),
            ("point_edge", point_edge, 3, "distance of the point p to the line of e0 e1"),
            ("edge_edge", edge_edge, 4, "signed distance of the lines of a0 a1 and b0 b1"),
            ("cos2", cos2, 4, "squared cosine of the angle between a1 - a0 and b1 - b0")):
        low = make()
        n = 3 * npt
        sig = f"void bk_pair_dist_{name}({_D} x, {_W} out)"
        out.append((f"bk_pair_dist_{name}", sig,
                    f"{doc}: x[{n}] in; out[{1 + n + n * n}]; {_ops(low)} operations", _function(sig, low)))
    return out
