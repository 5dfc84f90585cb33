"""Lee's frame (models/lee_frame.toml, models/lee_frame_follower.toml) by a
second, independent method: a planar geometrically exact (Reissner) beam
solved as a boundary-value problem by shooting, the equilibrium path traced by
pseudo-arc-length continuation on the shooting unknowns.  No finite elements,
nothing shared with beamkit's elements.

The frame, in the x-z plane (x across, z up; angles counter-clockwise from +x
towards +z): a column from (0, 0) to (0, L), a beam from (0, L) to (L, L), the
corner rigid, both ends pinned, a point load P = lambda P0 at arc length a
from the corner (P0 = EI / L^2 in the scenes, so lambda = P L^2 / EI).  The
scenes' section: EA, GA1 (shear along d1, the in-plane normal), EI2 (bending
about d2 = y, the out-of-plane axis: the in-plane bending stiffness EI); the
out-of-plane stiffnesses (EI1, GA2, GJ) do not enter a planar path.

Equations (arc length s of each member; ' = d/ds):
  * the section turns by theta(s) from its reference direction phi0 (pi/2 in
    the column, 0 in the beam): a1 = (cos phi, sin phi), a2 = (-sin phi, cos phi),
    phi = phi0 + theta;
  * n: the force of the part beyond s on the part before it (constant between
    loads, n(a+) = n(a-) - F at the load), m: the moment likewise;
  * extensible, shear-deformable, linear: N = n.a1 = EA eps, Q = n.a2 = GA gam,
    m = EI theta', so r' = (1 + N/EA) a1 + (Q/GA) a2;
  * moment balance m' + r' x n = 0 (x: the planar cross product).
  * Dead load F = P (0, -1); follower load F = -P a2(theta(a)) (normal to the
    beam at the load point, turning with that section; -z before it turns).
  * s = 0 (column base): r = 0, m = 0, theta = theta0 and n = n0 unknown;
    corner: r, theta, m continuous (rigid, no moment applied);
    s = L on the beam: r = (L, L), m = 0.  Three unknowns (theta0, n0x, n0z),
    three conditions, at each load factor.
Integration: scipy solve_ivp DOP853 member by member (segments column, corner
to load, load to end), rtol = RTOL, atol = RTOL * 1e-2.  The shooting residual
is solved by Newton with a central-difference Jacobian.

Continuation: pseudo-arc-length on v = (theta0, n0x / 10 P0, n0z / 10 P0, lambda / 10):
tangent = null vector of the 3 x 4 Jacobian, predictor along it, corrector on
the hyperplane normal to it; step adapted to the iteration count.  The limit
load (the first maximum of lambda) is bracketed by the sign change of the
tangent's lambda component and refined by maximising lambda over solutions on
hyperplanes across the bracket (scipy minimize_scalar, bounded); the snap-back
(the first minimum of the load point's vertical displacement uz) and the next
minimum of lambda likewise.  The dead-load path is traced through both and back
to lambda = 0, the follower path until lambda is back to half its limit.

Tolerance check: the whole computation repeated with the ODE tolerances halved
(rtol / 2); the differences of the limit loads and of the path (lambda at the
path's uz samples) are recorded.  The result is committed as
references/data/lee_frame.json; regenerate it with

    /usr/bin/python3 -m references.lee_frame --write

(both load cases, both tolerances: a few minutes on one core).  The tests read
the data; tests/test_continuation.py re-solves the stored limit points (a few
seconds) to check that the data is current.
"""
import argparse
import json
import math
import sys
import time
import tomllib
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "references" / "data" / "lee_frame.json"
SCENES = {"dead": ROOT / "models" / "lee_frame.toml", "follower": ROOT / "models" / "lee_frame_follower.toml"}
RTOL = 1e-10
LAM_SCALE = 10.0


def scene_params(path):
    """The frame's data from a scene file: L, a, EA, GA, EI, P0 and the load kind.
    Checks the geometry is the one modelled here (column up the z axis from the
    origin, beam along +x from its top, equal lengths, load on the beam)."""
    sc = tomllib.loads(Path(path).read_text(encoding="utf-8"))
    beams = {b["name"]: b for b in sc["beam"]}
    col, bm = beams["column"], beams["beam"]
    L = col["end"][2]
    if (col["start"] != [0.0, 0.0, 0.0] or col["end"] != [0.0, 0.0, L] or bm["start"] != [0.0, 0.0, L]
            or bm["end"] != [L, 0.0, L]):
        raise ValueError(f"{path}: not the frame modelled by references/lee_frame.py")
    mat = sc["material"][col["material"]]
    if sc["material"][bm["material"]] != mat:
        raise ValueError(f"{path}: the column and the beam must share one material")
    (load,) = sc["load"]
    where, a = load["at"].split(":")
    if where != "beam":
        raise ValueError(f"{path}: the load must be on the beam")
    follower = bool(load.get("follower", False))
    v = load["value"]
    # dead: the value is (0, 0, -P0); follower: (P0, 0, 0) along d1 (-z before the frame deforms)
    P0 = abs(v[0]) if follower else abs(v[2])
    return dict(L=float(L), a=float(a), EA=float(mat["EA"]), GA=float(mat["GA1"]), EI=float(mat["EI2"]),
                P0=float(P0), follower=follower)


class Frame:
    def __init__(self, p, rtol=RTOL):
        self.p = dict(p)
        self.rtol = rtol
        self.nfev = 0

    def _rhs(self, phi0, nx, nz):
        EA, GA, EI = self.p["EA"], self.p["GA"], self.p["EI"]

        def f(s, y):
            ph = phi0 + y[2]
            c, sn = math.cos(ph), math.sin(ph)
            N = nx * c + nz * sn
            Q = -nx * sn + nz * c
            e, g = 1.0 + N / EA, Q / GA
            rx, rz = e * c - g * sn, e * sn + g * c
            return [rx, rz, y[3] / EI, -(rx * nz - rz * nx)]
        return f

    def _seg(self, y0, length, phi0, n):
        sol = solve_ivp(self._rhs(phi0, n[0], n[1]), (0.0, length), y0, method="DOP853", rtol=self.rtol,
                        atol=self.rtol * 1e-2)
        self.nfev += sol.nfev
        if not sol.success:
            raise RuntimeError(f"solve_ivp: {sol.message}")
        return sol.y[:, -1]

    def shoot(self, v):
        """Residual (3) at v = (theta0, n0x, n0z, lambda) / (1, S P0, S P0, S), S = LAM_SCALE, and the
        load point's state (x, z, theta, m) and the load force."""
        p = self.p
        L, a, P0 = p["L"], p["a"], p["P0"]
        th0, nx, nz, lam = v[0], v[1] * P0 * LAM_SCALE, v[2] * P0 * LAM_SCALE, v[3] * LAM_SCALE
        n0 = (nx, nz)
        y = self._seg([0.0, 0.0, th0, 0.0], L, 0.5 * math.pi, n0)       # column, base to corner
        yF = self._seg(y, a, 0.0, n0)                                     # beam, corner to load
        P = lam * P0
        if p["follower"]:
            F = (P * math.sin(yF[2]), -P * math.cos(yF[2]))
        else:
            F = (0.0, -P)
        yE = self._seg(yF, L - a, 0.0, (nx - F[0], nz - F[1]))            # load to the far pin
        R = np.array([(yE[0] - L) / L, (yE[1] - L) / L, yE[3] / (P0 * L * L)])
        return R, yF

    def residual(self, v):
        return self.shoot(v)[0]

    def jacobian(self, v, h=1e-6):
        J = np.zeros((3, 4))
        for j in range(4):
            e = np.zeros(4)
            e[j] = h
            J[:, j] = (self.residual(v + e) - self.residual(v - e)) / (2 * h)
        return J

    def load_point(self, v):
        """(ux, uz, theta) of the load point and lambda at v."""
        _, yF = self.shoot(v)
        return yF[0] - self.p["a"], yF[1] - self.p["L"], yF[2], v[3] * LAM_SCALE


def tangent(J, prev=None):
    t = np.linalg.svd(J)[2][-1]
    if prev is None:
        return t if t[3] > 0 else -t
    return t if t @ prev > 0 else -t


def correct(fr, vp, t, J, tol=1e-12, maxit=12):
    """Solve R(v) = 0, t.(v - vp) = 0 from vp (chord iterations with J, refreshed
    when slow).  Returns (v, iterations, J) or None."""
    v = vp.copy()
    A = np.vstack([J, t])
    last = None
    for it in range(1, maxit + 1):
        R = fr.residual(v)
        g = np.concatenate([R, [t @ (v - vp)]])
        dv = np.linalg.solve(A, -g)
        v = v + dv
        nrm = float(np.max(np.abs(dv)))
        if nrm < tol:
            if float(np.max(np.abs(fr.residual(v)))) < 1e-11:
                return v, it, A[:3]
        if last is not None and nrm > 0.3 * last:
            A = np.vstack([fr.jacobian(v), t])
        last = nrm
    return None


def on_plane(fr, v0, t0, sigma):
    """The equilibrium on the hyperplane t0.(v - v0) = sigma (near v0 + sigma t0)."""
    r = correct(fr, v0 + sigma * t0, t0, fr.jacobian(v0 + sigma * t0))
    if r is None:
        raise RuntimeError(f"no equilibrium on the hyperplane sigma = {sigma:g}")
    return r[0]


def refine_extremum(fr, va, ta, vb, f, sign):
    """Extremum of f(v) (sign = +1: maximum) between the path points va, vb:
    maximise sign * f over the equilibria on the hyperplanes normal to ta."""
    sb = float(ta @ (vb - va))
    cache = {}

    def obj(s):
        v = on_plane(fr, va, ta, s)
        cache[s] = v
        return -sign * f(v)

    r = minimize_scalar(obj, bounds=(0.0, sb), method="bounded", options={"xatol": 1e-9 * max(sb, 1e-12)})
    v = cache.get(r.x)
    if v is None:
        v = on_plane(fr, va, ta, r.x)
    return v


def trace(p, rtol=RTOL, h0=0.02, hmax=0.05, max_steps=600, log=None, stop=None):
    """The path from the unloaded frame: (Frame, list of v (shooting unknowns),
    the limit point, for the dead load the snap-back (first minimum of uz), the
    first minimum of lambda after the limit point, or None where not reached)."""
    fr = Frame(p, rtol)
    v = np.zeros(4)
    J = fr.jacobian(v)
    t = tangent(J)
    path = [v]
    h = h0
    lim = snap = lmin = None
    uz_prev, dir_uz = 0.0, -1.0
    steps = 0
    while steps < max_steps:
        res = correct(fr, v + h * t, t, J)
        if res is None:
            h *= 0.5
            if h < 1e-6:
                raise RuntimeError("continuation stalled")
            continue
        vn, it, _ = res
        Jn = fr.jacobian(vn)
        tn = tangent(Jn, t)
        if lim is None and t[3] > 0 and tn[3] <= 0:
            vl = refine_extremum(fr, v, t, vn, lambda w: w[3], +1)
            lim = vl
            if log:
                log(f"  limit point: lambda = {vl[3] * LAM_SCALE:.9f}")
        if lim is not None and lmin is None and t[3] < 0 and tn[3] >= 0:
            lmin = refine_extremum(fr, v, t, vn, lambda w: w[3], -1)
            if log:
                log(f"  minimum of the load factor: lambda = {lmin[3] * LAM_SCALE:.9f}")
        uz = fr.load_point(vn)[1]
        if snap is None and lim is not None and not p["follower"] and uz > uz_prev and dir_uz < 0:
            vs = refine_extremum(fr, v, t, vn, lambda w: fr.load_point(w)[1], -1)
            snap = vs
            if log:
                ux_, uz_, _, lam_ = fr.load_point(vs)
                log(f"  snap-back: uz = {uz_:.9f} at lambda = {lam_:.9f}")
        dir_uz = math.copysign(1.0, uz - uz_prev)
        uz_prev = uz
        path.append(vn)
        v, t, J = vn, tn, Jn
        steps += 1
        h = min(hmax, h * (1.4 if it <= 6 else (1.0 if it <= 8 else 0.6)))
        if stop is not None and stop(fr, path, lim, snap):
            break
    return fr, path, lim, snap, lmin


def _stop_dead(fr, path, lim, snap):
    # past the snap-back, through the load factor's minimum and back up to zero
    if snap is None or len(path) < 3:
        return False
    lams = [w[3] for w in path]
    return min(lams) < 0 and lams[-1] > lams[-2] and lams[-1] * LAM_SCALE > 0.0


def _stop_follower(fr, path, lim, snap):
    return lim is not None and path[-1][3] < 0.5 * lim[3]


def point_record(fr, v):
    ux, uz, th, lam = fr.load_point(v)
    return [float(f"{lam:.12g}"), float(f"{ux:.12g}"), float(f"{uz:.12g}"), float(f"{th:.12g}"),
            float(f"{v[0]:.12g}"), float(f"{v[1] * LAM_SCALE:.12g}"), float(f"{v[2] * LAM_SCALE:.12g}")]


def study(case, rtol=RTOL, log=None):
    p = scene_params(SCENES[case])
    stop = _stop_follower if p["follower"] else _stop_dead
    t0 = time.perf_counter()
    fr, path, lim, snap, lmin = trace(p, rtol, log=log, stop=stop)
    wall = time.perf_counter() - t0
    if lim is None:
        raise RuntimeError(f"{case}: no limit point on the traced path")
    rec = dict(scene=str(SCENES[case].relative_to(ROOT)), params=p, rtol=rtol, steps=len(path) - 1,
               nfev=fr.nfev, wall_s=round(wall, 1),
               limit=point_record(fr, lim),
               path=[point_record(fr, v) for v in path])
    if snap is not None:
        rec["snap_back"] = point_record(fr, snap)
    if lmin is not None:
        rec["load_minimum"] = point_record(fr, lmin)
    return rec


def _path_lambda_at(path, uz, lo, hi):
    """lambda at load-point displacement uz on the stretch of the path (rows)
    between the indices lo and hi where uz is monotone (linear interpolation)."""
    zs = np.array([r[2] for r in path[lo:hi + 1]])
    ls = np.array([r[0] for r in path[lo:hi + 1]])
    if zs[-1] < zs[0]:
        zs, ls = zs[::-1], ls[::-1]
    return float(np.interp(uz, zs, ls))


def compare(rec_a, rec_b):
    """Differences between two studies (tolerance check): limit loads, snap-back."""
    d = {"limit_lambda": abs(rec_a["limit"][0] - rec_b["limit"][0]),
         "limit_uz": abs(rec_a["limit"][2] - rec_b["limit"][2])}
    if "snap_back" in rec_a and "snap_back" in rec_b:
        d["snap_back_uz"] = abs(rec_a["snap_back"][2] - rec_b["snap_back"][2])
        d["snap_back_lambda"] = abs(rec_a["snap_back"][0] - rec_b["snap_back"][0])
    if "load_minimum" in rec_a and "load_minimum" in rec_b:
        d["load_minimum_lambda"] = abs(rec_a["load_minimum"][0] - rec_b["load_minimum"][0])
    return {k: float(f"{x:.3e}") for k, x in d.items()}


COLUMNS = ["lambda", "ux", "uz", "theta_load", "theta0", "n0x_over_P0", "n0z_over_P0"]


def build(log=None):
    out = {
        "about": "Lee's frame (models/lee_frame.toml dead load, models/lee_frame_follower.toml follower load) "
                 "by references/lee_frame.py: a planar geometrically exact (Reissner) beam, extensible and "
                 "shear-deformable (EA, GA1, EI2 of the scene), rigid corner, pinned ends, point load at arc "
                 "length a from the corner; shooting on (theta0, n0x, n0z) at the column base with scipy "
                 "solve_ivp DOP853, pseudo-arc-length continuation on the shooting unknowns, the limit load "
                 "(first maximum of lambda) and the snap-back (first minimum of the load point's uz) refined "
                 "by maximising over equilibria on hyperplanes across the bracketing step (load_minimum: the "
                 "next minimum of lambda, likewise).  Rows: [lambda, ux, uz, theta_load, theta0, n0x/P0, "
                 "n0z/P0]; lambda = P L^2 / EI "
                 "(the scenes' load factor); ux, uz: displacement of the load point (m); theta_load: turn of its "
                 "section (rad, counter-clockwise in the x-z plane from +x to +z); theta0: turn at the column "
                 "base; n0: force at the base over P0 = EI / L^2.",
        "command": "/usr/bin/python3 -m references.lee_frame --write",
        "columns": COLUMNS,
    }
    for case in ("dead", "follower"):
        if log:
            log(f"{case}: rtol {RTOL:g}")
        a = study(case, RTOL, log)
        if log:
            log(f"{case}: rtol {RTOL / 2:g} (tolerance check)")
        b = study(case, RTOL / 2, log)
        a["tolerance_check"] = dict(rtol=RTOL / 2, **compare(a, b))
        out[case] = a
    return out


def resolve_limit(case, data=None, rtol=RTOL):
    """Re-solve the stored limit point of `case` from its stored unknowns: the
    maximum of lambda along the path through it (three equilibria on hyperplanes
    close to it, a parabola through their load factors).  Cheap (a few seconds):
    the tests' check that the committed data matches the scene and this code."""
    data = data or json.loads(DATA.read_text(encoding="utf-8"))
    rec = data[case]
    p = scene_params(SCENES[case])
    fr = Frame(p, rtol)
    l = rec["limit"]
    v0 = np.array([l[4], l[5] / LAM_SCALE, l[6] / LAM_SCALE, l[0] / LAM_SCALE])
    v0 = correct(fr, v0, np.array([1.0, 0.0, 0.0, 0.0]), fr.jacobian(v0))     # theta0 held: lambda is free
    if v0 is None:
        raise RuntimeError(f"{case}: the stored limit point is not an equilibrium of the scene")
    v0 = v0[0]
    t0 = tangent(fr.jacobian(v0))
    h = 2e-3
    lam = [on_plane(fr, v0, t0, s)[3] * LAM_SCALE for s in (-h, 0.0, h)]
    # parabola through (-h, l0), (0, l1), (h, l2): maximum l1 + (l2 - l0)^2 / (8 (2 l1 - l0 - l2))
    curv = 2 * lam[1] - lam[0] - lam[2]
    return lam[1] + (lam[2] - lam[0]) ** 2 / (8.0 * curv), p


def check_path_points(case, rows, data=None, rtol=RTOL):
    """Re-evaluate stored path points (indices `rows`) from their stored unknowns:
    the largest shooting residual and the largest difference of the recomputed
    load-point displacement and load factor from the stored ones."""
    data = data or json.loads(DATA.read_text(encoding="utf-8"))
    fr = Frame(scene_params(SCENES[case]), rtol)
    res = dev = 0.0
    for i in rows:
        r = data[case]["path"][i]
        v = np.array([r[4], r[5] / LAM_SCALE, r[6] / LAM_SCALE, r[0] / LAM_SCALE])
        res = max(res, float(np.max(np.abs(fr.residual(v)))))
        ux, uz, th, lam = fr.load_point(v)
        dev = max(dev, abs(ux - r[1]), abs(uz - r[2]), abs(th - r[3]))
    return res, dev


def load(path=DATA):
    return json.loads(Path(path).read_text(encoding="utf-8"))


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python3 -m references.lee_frame",
                                 description="Lee's frame by a planar Reissner beam, shooting + continuation.")
    ap.add_argument("--write", action="store_true", help=f"write {DATA.relative_to(ROOT)}")
    ap.add_argument("--case", choices=("dead", "follower"), help="one load case only, no tolerance check, no write")
    a = ap.parse_args(argv)
    log = lambda s: print(s, file=sys.stderr, flush=True)    # noqa: E731
    if a.case:
        r = study(a.case, RTOL, log)
        print(f"{a.case}: limit lambda = {r['limit'][0]:.9f} at uz = {r['limit'][2]:.6f}, {r['steps']} steps, "
              f"{r['wall_s']} s")
        return 0
    d = build(log)
    for case in ("dead", "follower"):
        r = d[case]
        print(f"{case}: limit P L^2/EI = {r['limit'][0]:.9f} (load point ux {r['limit'][1]:.6f}, uz "
              f"{r['limit'][2]:.6f} m); tolerance check {r['tolerance_check']}")
        if "snap_back" in r:
            print(f"{case}: snap-back at uz = {r['snap_back'][2]:.9f} m, lambda {r['snap_back'][0]:.6f}")
        if "load_minimum" in r:
            print(f"{case}: minimum load factor {r['load_minimum'][0]:.9f} at uz = {r['load_minimum'][2]:.6f} m")
    if a.write:
        DATA.write_text(json.dumps(d, indent=1) + "\n", encoding="utf-8")
        print(f"wrote {DATA}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
