"""Amplitudes: the time (dynamics) or load-factor (statics) history a load or a
prescribed motion is multiplied by.  [amplitude.NAME] tables, or an inline
table in the load, referenced by a load's `amplitude` key (a constraint's
`angle_amplitude`).

Types (gen/scene_keys.py AMPLITUDE), x the time or the load factor:
  ramp   0 before t0, linear to 1 at t1, 1 after (t0 = 0, t1 = 1)
  step   0 before t0, 1 from t0 on
  sine   offset + amplitude sin(2 pi frequency x + phase)
  table  piecewise linear through points [[x, a], ...] (x strictly increasing),
         inline or from a CSV file of two columns (path relative to the scene),
         constant beyond the first and last point
  cycloidal  rest to rest from 0 at t0 to 1 at t1: u - sin(2 pi u)/(2 pi), u = (x - t0)/(t1 - t0)
  quintic    rest to rest: 10 u^3 - 15 u^4 + 6 u^5
  spline     the natural cubic spline through points (as table; at least 2), constant
             beyond its ends; its second derivatives at the knots are solved here
Model-file form: (type, [parameters]) -- runtime/model/amplitude.c evaluates it
(and its first two derivatives, exactly).
"""
import math

import gen.scene_keys as K
from gen.scene.values import _typename, check_keys, get_number, get_str

TYPES = tuple(K.AMPLITUDE)


class Amplitudes:
    """The scene's amplitudes as they are referenced, numbered in order of use."""

    def __init__(self, ctx, doc):
        self.ctx = ctx
        self.named = doc.get("amplitude", {})
        if not isinstance(self.named, dict):
            ctx.fail("amplitude", f"expected tables [amplitude.NAME], found {_typename(self.named)}")
        self.rows = []          # (type, params) per amplitude
        self.index = {}         # name -> row
        for name, tbl in self.named.items():
            self.index[name] = self._parse(tbl, f"amplitude.{name}")

    def ref(self, tbl, key, where):
        """Index of the amplitude tbl[key] (a name or an inline table), -1 when absent."""
        if key not in tbl:
            return -1
        v = tbl[key]
        if isinstance(v, str):
            if v not in self.index:
                self.ctx.fail(f"{where}.{key}", f"no [amplitude.{v}] table (amplitudes: "
                              f"{', '.join(self.index) or 'none'})")
            return self.index[v]
        if isinstance(v, dict):
            return self._parse(v, f"{where}.{key}")
        self.ctx.fail(f"{where}.{key}", f"expected the name of an [amplitude.NAME] table or an inline "
                      f"table, found {_typename(v)}")

    def _parse(self, tbl, where):
        ctx = self.ctx
        if not isinstance(tbl, dict):
            ctx.fail(where, f"expected a table, found {_typename(tbl)}")
        atype = get_str(ctx, tbl, "type", where, choices=TYPES)
        check_keys(ctx, tbl, set(K.AMPLITUDE[atype]), where)
        if atype in ("ramp", "cycloidal", "quintic"):
            t0 = get_number(ctx, tbl, "t0", where, default=0.0)
            t1 = get_number(ctx, tbl, "t1", where, default=1.0)
            if not t1 > t0:
                ctx.fail(f"{where}.t1", f"expected t1 > t0 = {t0:g}, found {t1:g}")
            params = [t0, t1]
        elif atype == "step":
            params = [get_number(ctx, tbl, "t0", where, default=0.0)]
        elif atype == "sine":
            params = [get_number(ctx, tbl, "amplitude", where, default=1.0),
                      get_number(ctx, tbl, "frequency", where, nonneg=True),
                      get_number(ctx, tbl, "phase", where, default=0.0),
                      get_number(ctx, tbl, "offset", where, default=0.0)]
        elif atype == "spline":
            params = _spline(ctx, self._table(tbl, where), where)
        else:
            params = self._table(tbl, where)
        self.rows.append((atype, params))
        return len(self.rows) - 1

    def _table(self, tbl, where):
        ctx = self.ctx
        if ("points" in tbl) == ("file" in tbl):
            ctx.fail(where, "a table amplitude needs exactly one of `points` (inline [[x, a], ...]) and `file` "
                     "(a CSV file of x, a rows)")
        if "points" in tbl:
            key = f"{where}.points"
            pts = tbl["points"]
            if not isinstance(pts, list):
                ctx.fail(key, f"expected an array of [x, a] pairs, found {_typename(pts)}")
            rows = []
            for i, p in enumerate(pts):
                if (not isinstance(p, list) or len(p) != 2
                        or any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in p)):
                    ctx.fail(key, f"entry {i}: expected a pair [x, a] of numbers, found {p!r}")
                rows.append((float(p[0]), float(p[1])))
        else:
            key = f"{where}.file"
            fname = tbl["file"]
            if not isinstance(fname, str):
                ctx.fail(key, f"expected a path to a CSV file, found {_typename(fname)}")
            path = ctx.data_path(key, fname)
            try:
                text = path.read_text(encoding="utf-8")
            except OSError as e:
                ctx.fail(key, f"cannot read {str(path)!r}: {e.strerror}")
            ctx.inputs.append(str(path))
            rows = []
            import csv                 # only for table amplitudes from a file
            for ln, rec in enumerate(csv.reader(text.splitlines()), 1):
                rec = [c.strip() for c in rec]
                if not rec or not any(rec) or rec[0].startswith("#"):
                    continue
                try:
                    vals = [float(c) for c in rec]
                except ValueError:
                    if not rows:
                        continue                    # a header line
                    ctx.fail(key, f"{path.name} line {ln}: expected two numbers x, a, found {','.join(rec)!r}")
                if len(vals) != 2:
                    ctx.fail(key, f"{path.name} line {ln}: expected two columns x, a, found {len(vals)}")
                rows.append((vals[0], vals[1]))
        if not rows:
            ctx.fail(key, "expected at least one point")
        for i, (x, a) in enumerate(rows):
            if not (math.isfinite(x) and math.isfinite(a)):
                ctx.fail(key, f"point {i}: expected finite numbers, found {x!r}, {a!r}")
            if i and not x > rows[i - 1][0]:
                ctx.fail(key, f"points out of time order: x = {x:g} (point {i}) after x = {rows[i - 1][0]:g}; "
                         "expected strictly increasing x")
        return [v for p in rows for v in p]


def _spline(ctx, flat, where):
    """x, a, m per knot of the natural cubic spline through (x, a) (m = a'' at the
    knot, zero at both ends): the tridiagonal system solved by elimination."""
    x, a = flat[0::2], flat[1::2]
    n = len(x)
    if n < 2:
        ctx.fail(f"{where}.points", f"a spline needs at least 2 points, found {n}")
    m = [0.0] * n
    if n > 2:
        h = [x[i + 1] - x[i] for i in range(n - 1)]
        diag = [2.0 * (h[i - 1] + h[i]) for i in range(1, n - 1)]
        rhs = [6.0 * ((a[i + 1] - a[i]) / h[i] - (a[i] - a[i - 1]) / h[i - 1]) for i in range(1, n - 1)]
        for i in range(1, n - 2):               # forward elimination (sub- and superdiagonal h[i])
            f = h[i] / diag[i - 1]
            diag[i] -= f * h[i]
            rhs[i] -= f * rhs[i - 1]
        for i in range(n - 3, -1, -1):
            m[i + 1] = (rhs[i] - (h[i + 1] * m[i + 2] if i + 1 < n - 2 else 0.0)) / diag[i]
    return [v for i in range(n) for v in (x[i], a[i], m[i])]
