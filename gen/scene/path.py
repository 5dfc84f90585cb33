"""Beam centrelines through points (`beam.path`): a cubic spline through the
points (not-a-knot ends, chord-length parameter), taken by arc length, with a
section frame carried along it by parallel transport (the rotation-minimizing
frame, by double reflections on a fine subdivision) from the start's `up`."""
try:                                   # bisect's C half: importing bisect.py, the first module of the
    from _bisect import bisect_right   # standard library's folder a run needs, lists that folder
except ImportError:                    # (1 ms of every scene compile)  # pragma: no cover
    from bisect import bisect_right
import math

from gen.scene.values import _cross, _dot, _norm, _scale, _sub, _typename

SUBSTEPS = 64                   # subdivisions of each spline segment for arc length and transport
GAUSS5 = ((0.5 - 0.4530899229693320, 0.1184634425280945), (0.5 - 0.2692346550528415, 0.2393143352496832),
          (0.5, 0.2844444444444444), (0.5 + 0.2692346550528415, 0.2393143352496832),
          (0.5 + 0.4530899229693320, 0.1184634425280945))


def spline_second_derivatives(u, y):
    """Second derivatives at the knots of the not-a-knot cubic spline through (u_i, y_i)
    (n >= 3; three points: the parabola).  The end conditions are eliminated into
    the first and last interior equations, which leaves a tridiagonal system."""
    n = len(u)
    h = [u[i + 1] - u[i] for i in range(n - 1)]
    rhs = [6 * ((y[i + 1] - y[i]) / h[i] - (y[i] - y[i - 1]) / h[i - 1]) for i in range(1, n - 1)]
    if n == 3:
        m = rhs[0] / (3 * (h[0] + h[1]))
        return [m, m, m]
    m = n - 2                   # unknowns M_1 .. M_{n-2}
    lo, di, up = [0.0] * m, [0.0] * m, [0.0] * m
    for k in range(m):
        i = k + 1
        lo[k], di[k], up[k] = h[i - 1], 2 * (h[i - 1] + h[i]), h[i]
    # M_0 = ((h0 + h1) M_1 - h0 M_2) / h1, M_{n-1} likewise at the other end
    di[0] += h[0] * (h[0] + h[1]) / h[1]
    up[0] -= h[0] * h[0] / h[1]
    a, b = h[n - 3], h[n - 2]
    di[m - 1] += b * (a + b) / a
    lo[m - 1] -= b * b / a
    for k in range(1, m):       # Thomas algorithm
        w = lo[k] / di[k - 1]
        di[k] -= w * up[k - 1]
        rhs[k] -= w * rhs[k - 1]
    M = [0.0] * m
    M[m - 1] = rhs[m - 1] / di[m - 1]
    for k in range(m - 2, -1, -1):
        M[k] = (rhs[k] - up[k] * M[k + 1]) / di[k]
    M0 = ((h[0] + h[1]) * M[0] - h[0] * M[1]) / h[1]
    Mn = ((a + b) * M[m - 1] - b * M[m - 2]) / a
    return [M0] + M + [Mn]


class PathGeometry:
    """Spline centreline: point and section frame (t, d1, d2) at arc length s."""

    def __init__(self, pts):
        self.pts = pts
        u = [0.0]
        for i in range(1, len(pts)):
            u.append(u[-1] + _norm(_sub(pts[i], pts[i - 1])))
        self.u = u
        self.M = [spline_second_derivatives(u, [p[c] for p in pts]) for c in range(3)]
        # fine table: parameter, arc length, tangent and transported d2
        self.tu, self.ts = [0.0], [0.0]
        for i in range(len(u) - 1):
            for k in range(SUBSTEPS):
                a = u[i] + (u[i + 1] - u[i]) * k / SUBSTEPS
                b = u[i] + (u[i + 1] - u[i]) * (k + 1) / SUBSTEPS
                self.tu.append(b)
                self.ts.append(self.ts[-1] + self._length(a, b))
        self.length = self.ts[-1]
        self.shape_key = None
        self.td2 = []

    def transport(self, up):
        """The frame along the fine table from d2 = up (its part normal to the start's tangent)."""
        t0 = self.tangent(0.0)
        d2 = _sub(up, _scale(t0, _dot(up, t0)))
        self.td2 = [_scale(d2, 1 / _norm(d2))]
        for k in range(1, len(self.tu)):
            self.td2.append(self._transport(self.tu[k - 1], self.td2[-1], self.tu[k]))

    def element_key(self, k):
        return ("path", id(self), k)

    def _seg(self, v):
        i = min(max(bisect_right(self.u, v) - 1, 0), len(self.u) - 2)
        return i, v - self.u[i], self.u[i + 1] - self.u[i]

    def point(self, v):
        i, x, h = self._seg(v)
        out = []
        for c in range(3):
            y0, y1, M0, M1 = self.pts[i][c], self.pts[i + 1][c], self.M[c][i], self.M[c][i + 1]
            b = (y1 - y0) / h - h * (2 * M0 + M1) / 6
            out.append(y0 + x * (b + x * (M0 / 2 + x * (M1 - M0) / (6 * h))))
        return out

    def derivative(self, v):
        i, x, h = self._seg(v)
        out = []
        for c in range(3):
            y0, y1, M0, M1 = self.pts[i][c], self.pts[i + 1][c], self.M[c][i], self.M[c][i + 1]
            b = (y1 - y0) / h - h * (2 * M0 + M1) / 6
            out.append(b + x * (M0 + x * (M1 - M0) / (2 * h)))
        return out

    def tangent(self, v):
        d = self.derivative(v)
        return _scale(d, 1 / _norm(d))

    def _length(self, a, b):
        return sum(w * _norm(self.derivative(a + (b - a) * x)) for x, w in GAUSS5) * (b - a)

    def _transport(self, va, d, vb):
        """d (normal to the tangent at va) carried to vb by the double reflection of
        Wang, Juettler, Zheng and Liu (2008): fourth-order rotation-minimizing."""
        xa, xb = self.point(va), self.point(vb)
        ta, tb = self.tangent(va), self.tangent(vb)
        v1 = _sub(xb, xa)
        c1 = _dot(v1, v1)
        if c1 == 0.0:
            return d
        dl = _sub(d, _scale(v1, 2 * _dot(v1, d) / c1))
        tl = _sub(ta, _scale(v1, 2 * _dot(v1, ta) / c1))
        v2 = _sub(tb, tl)
        c2 = _dot(v2, v2)
        out = dl if c2 == 0.0 else _sub(dl, _scale(v2, 2 * _dot(v2, dl) / c2))
        out = _sub(out, _scale(tb, _dot(out, tb)))
        return _scale(out, 1 / _norm(out))

    def param(self, s):
        """Spline parameter at arc length s (Newton from the fine table)."""
        k = min(max(bisect_right(self.ts, s) - 1, 0), len(self.ts) - 2)
        v = self.tu[k] + (self.tu[k + 1] - self.tu[k]) * (s - self.ts[k]) / (self.ts[k + 1] - self.ts[k])
        for _ in range(8):
            r = self.ts[k] + self._length(self.tu[k], v) - s
            v -= r / _norm(self.derivative(v))
            if abs(r) <= 1e-15 * self.length:
                break
        return v, k

    def at(self, s):
        v, k = self.param(min(max(s, 0.0), self.length))
        t = self.tangent(v)
        d2 = self._transport(self.tu[k], self.td2[k], v)
        return self.point(v), t, _cross(d2, t), d2


def path_points(ctx, bt, where):
    """The points of `path`: an inline array [[x, y, z], ...] or a CSV file of x, y, z
    rows (a header line allowed; path relative to the scene file)."""
    key = f"{where}.path"
    v = bt["path"]
    if isinstance(v, str):
        p = ctx.data_path(key, v)
        try:
            text = p.read_text(encoding="utf-8")
        except OSError as e:
            ctx.fail(key, f"cannot read {str(p)!r}: {e.strerror}")
        ctx.inputs.append(str(p))
        import csv                         # only for paths from a file
        pts = []
        for ln, rec in enumerate(csv.reader(text.splitlines()), 1):
            rec = [c.strip() for c in rec]
            if not rec or not any(rec) or rec[0].startswith("#"):
                continue
            try:
                vals = [float(c) for c in rec]
            except ValueError:
                if not pts:
                    continue                # a header line
                ctx.fail(key, f"{p.name} line {ln}: expected three numbers x, y, z, found {','.join(rec)!r}")
            if len(vals) != 3:
                ctx.fail(key, f"{p.name} line {ln}: expected three columns x, y, z, found {len(vals)}")
            pts.append(vals)
    elif isinstance(v, list):
        pts = []
        for i, p in enumerate(v):
            if (not isinstance(p, list) or len(p) != 3
                    or any(isinstance(c, bool) or not isinstance(c, (int, float)) for c in p)):
                ctx.fail(key, f"point {i}: expected [x, y, z] (three numbers), found {p!r}")
            pts.append([float(c) for c in p])
    else:
        ctx.fail(key, f"expected an array of points [[x, y, z], ...] or a CSV file name, found {_typename(v)}")
    if len(pts) < 3:
        ctx.fail(key, f"expected at least 3 points for a spline, found {len(pts)}")
    for i, p in enumerate(pts):
        if not all(math.isfinite(c) and abs(c) <= 1e9 for c in p):
            ctx.fail(key, f"point {i}: expected finite coordinates within 1e9 m, found {p!r}")
    span = max(_norm(_sub(p, pts[0])) for p in pts)
    for i in range(1, len(pts)):
        if _norm(_sub(pts[i], pts[i - 1])) <= 1e-9 * span:
            ctx.fail(key, f"points {i - 1} and {i} coincide ({pts[i]!r}); expected distinct consecutive points")
    return pts


def path_geometry(ctx, bt, where):
    from gen.scene.values import get_vec3
    pts = path_points(ctx, bt, where)
    up = get_vec3(ctx, bt, "up", where, default=[0.0, 0.0, 1.0], nonzero=True, bound=1e300)
    up = _scale(up, 1 / _norm(up))
    geo = PathGeometry(pts)
    t0 = geo.tangent(0.0)
    if _norm(_sub(up, _scale(t0, _dot(up, t0)))) < 1e-6:
        ctx.fail(f"{where}.up", "expected a direction not parallel to the path's first tangent")
    for k in range(1, len(geo.tu)):
        if _dot(geo.tangent(geo.tu[k - 1]), geo.tangent(geo.tu[k])) < 0.5:
            ctx.fail(f"{where}.path", f"the spline through the points turns by more than 60 degrees within "
                     f"1/{SUBSTEPS} of a segment near {geo.point(geo.tu[k])!r} (a cusp or a kink); "
                     "expected a smooth centreline (more points, or points farther apart)")
    geo.transport(up)
    return geo
