"""Soft seed pendulum by a second, independent implementation: a planar
geometrically exact (Reissner / Simo) beam in numpy, integrated by scipy.

The scene (models/pendulum_soft_*.toml): a rod of length L = 1 m, square
section b = h = 0.01 m, E = 3e7 Pa, nu = 0.3, rho = 2700 kg/m^3, pinned at
x = 0 (a spherical joint: position fixed, rotation free), straight and at rest
along +x at t = 0, gravity -9.81 m/s^2 along z.  The motion stays in the x-z
plane.

Model (written from the theory, sharing nothing with beamkit's elements):
  * unknowns per node: the centreline position (x, z) and the section angle
    theta (the section's axis a1 = (cos theta, sin theta), its normal
    a2 = (-sin theta, cos theta) in the x-z plane);
  * strains: extension eps = r'.a1 - 1, shear gam = r'.a2, curvature kap = theta'
    (' the derivative in the reference arc length);
  * energy 1/2 int (EA eps^2 + k G A gam^2 + EI kap^2) ds with G = E / (2 (1 + nu))
    and Cowper's shear factor of a rectangle k = 10 (1 + nu) / (12 + 11 nu);
  * kinetic energy 1/2 int (rho A |r_t|^2 + rho I theta_t^2) ds: in the plane the
    rotary inertia is exactly rho I theta_t^2, so the mass matrix is constant
    (consistent, exact Gauss quadrature);
  * quadratic Lagrange elements (3 nodes), internal forces with 2-point Gauss
    (reduced: no shear locking), analytic tangent (material + geometric parts);
  * M q'' + f_int(q) = f_grav as a first-order system, scipy.integrate.solve_ivp
    (Radau, rtol = atol-scale 1e-10) with the analytic Jacobian; dense output at
    the requested times.

The reference is the mesh study N = 16, 32, 64 elements extrapolated point
by point (Richardson with the observed order, as calculix/extrapolate.py; the
error estimate 1.25 |extrapolated - finest|; see richardson3 for the points where
the differences are not monotone), plus the time-integration
tolerance check: |finest(rtol 1e-10) - finest(rtol 1e-9)|, an upper bound of the
finest run's integration error (which shrinks with the tolerance).  The result is
committed as references/data/pendulum_reissner.json (tip position x, z and
error estimates at t = 0.01, 0.02, ... 1 s); regenerate it with

    /usr/bin/python3 -m references.pendulum_reissner --write

(16, 32 and 64 elements: about 40 minutes on one busy core; the runs are
cached in out/pendulum_reissner/).  The bench and the tests read the data only.
"""
import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "references" / "data" / "pendulum_reissner.json"

SCENE = dict(L=1.0, b=0.01, h=0.01, E=3.0e7, nu=0.3, rho=2700.0, g=9.81)


def sections(p):
    """(EA, kGA, EI, rhoA, rhoI) of the rectangle."""
    A = p["b"] * p["h"]
    I = p["b"] * p["h"] ** 3 / 12.0
    G = p["E"] / (2.0 * (1.0 + p["nu"]))
    k = 10.0 * (1.0 + p["nu"]) / (12.0 + 11.0 * p["nu"])
    return p["E"] * A, k * G * A, p["E"] * I, p["rho"] * A, p["rho"] * I


def _shape(xi):
    """Quadratic Lagrange shape functions on [-1, 1] (nodes -1, 0, 1) and d/dxi."""
    xi = np.asarray(xi, dtype=float)
    N = np.stack([0.5 * xi * (xi - 1.0), 1.0 - xi * xi, 0.5 * xi * (xi + 1.0)], axis=-1)
    dN = np.stack([xi - 0.5, -2.0 * xi, xi + 0.5], axis=-1)
    return N, dN


class Beam:
    """n quadratic elements on [0, L]; DOFs (x, z, theta) per node, 2 n + 1 nodes;
    node 0's x and z held (the pin)."""

    def __init__(self, n, p=SCENE):
        self.n, self.p = n, dict(p)
        self.EA, self.GAs, self.EI, self.rhoA, self.rhoI = sections(self.p)
        L = self.p["L"]
        self.nn = 2 * n + 1
        self.le = L / n
        self.X = np.linspace(0.0, L, self.nn)
        self.conn = np.array([[2 * e, 2 * e + 1, 2 * e + 2] for e in range(n)])
        # element DOF indices: node a, component c (x, z, theta) -> 3 * node + c
        self.edofs = (3 * self.conn[:, :, None] + np.arange(3)[None, None, :]).reshape(n, 9)
        g = 1.0 / math.sqrt(3.0)
        self.Nr, dNr = _shape(np.array([-g, g]))          # reduced: 2 points, weights 1
        self.dNr = dNr * (2.0 / self.le)
        self.wr = np.array([1.0, 1.0]) * self.le / 2.0
        self.free = np.array([i for i in range(3 * self.nn) if i not in (0, 1)])
        self._mass()
        self._gravity()

    def _mass(self):
        xg, wg = np.polynomial.legendre.leggauss(3)       # exact for N_a N_b
        N, _ = _shape(xg)
        me = np.einsum("g,ga,gb->ab", wg * self.le / 2.0, N, N)
        M = np.zeros((3 * self.nn, 3 * self.nn))
        for e in range(self.n):
            for a in range(3):
                for b in range(3):
                    ia, ib = 3 * self.conn[e, a], 3 * self.conn[e, b]
                    M[ia, ib] += self.rhoA * me[a, b]
                    M[ia + 1, ib + 1] += self.rhoA * me[a, b]
                    M[ia + 2, ib + 2] += self.rhoI * me[a, b]
        Mf = M[np.ix_(self.free, self.free)]
        self.Minv = np.linalg.inv(Mf)

    def _gravity(self):
        xg, wg = np.polynomial.legendre.leggauss(3)
        N, _ = _shape(xg)
        fe = np.einsum("g,ga->a", wg * self.le / 2.0, N)
        f = np.zeros(3 * self.nn)
        for e in range(self.n):
            for a in range(3):
                f[3 * self.conn[e, a] + 1] -= self.rhoA * self.p["g"] * fe[a]
        self.fg = f[self.free]

    def initial(self):
        q = np.zeros(3 * self.nn)
        q[0::3] = self.X
        return q

    def internal(self, q, tangent=False):
        """f_int (all DOFs) and, with tangent, the stiffness matrix (all DOFs)."""
        qe = q[self.edofs].reshape(self.n, 3, 3)          # element, node, (x, z, theta)
        rp = np.einsum("ga,eac->egc", self.dNr, qe[:, :, :2])      # r' at the points
        th = np.einsum("ga,ea->eg", self.Nr, qe[:, :, 2])
        kap = np.einsum("ga,ea->eg", self.dNr, qe[:, :, 2])
        c, s = np.cos(th), np.sin(th)
        a1 = np.stack([c, s], axis=-1)
        a2 = np.stack([-s, c], axis=-1)
        eps = np.einsum("egc,egc->eg", rp, a1) - 1.0
        gam = np.einsum("egc,egc->eg", rp, a2)
        Nf, Qf, Mf = self.EA * eps, self.GAs * gam, self.EI * kap
        n, G = self.n, 2
        dN = np.broadcast_to(self.dNr, (n, G, 3))
        Nn = np.broadcast_to(self.Nr, (n, G, 3))
        # B rows per point: (element, point, node, component)
        Be = np.zeros((n, G, 3, 3))
        Bg = np.zeros((n, G, 3, 3))
        Bk = np.zeros((n, G, 3, 3))
        Be[..., :2] = dN[..., None] * a1[:, :, None, :]
        Be[..., 2] = Nn * gam[:, :, None]
        Bg[..., :2] = dN[..., None] * a2[:, :, None, :]
        Bg[..., 2] = -Nn * (1.0 + eps)[:, :, None]
        Bk[..., 2] = dN
        w = self.wr[None, :]
        fe = (np.einsum("eg,egac->eac", w * Nf, Be) + np.einsum("eg,egac->eac", w * Qf, Bg)
              + np.einsum("eg,egac->eac", w * Mf, Bk)).reshape(n, 9)
        f = np.zeros(3 * self.nn)
        np.add.at(f, self.edofs, fe)
        if not tangent:
            return f, None
        Be2, Bg2, Bk2 = (B.reshape(n, G, 9) for B in (Be, Bg, Bk))
        Ke = (self.EA * np.einsum("eg,egi,egj->eij", w, Be2, Be2)
              + self.GAs * np.einsum("eg,egi,egj->eij", w, Bg2, Bg2)
              + self.EI * np.einsum("eg,egi,egj->eij", w, Bk2, Bk2))
        # geometric part: N d(d eps) + Q d(d gam)
        Kg = np.zeros((n, G, 3, 3, 3, 3))          # (e, g, a, c, b, d)
        # r-theta coupling: d eps: dN_a a2_c N_b ; d gam: -dN_a a1_c N_b
        rt = (Nf[:, :, None] * a2 - Qf[:, :, None] * a1)           # (e, g, c)
        Kg[:, :, :, :2, :, 2] += np.einsum("ega,egc,egb->egacb", dN, rt, Nn)
        Kg[:, :, :, 2, :, :2] += np.einsum("ega,egd,egb->egabd", Nn, rt, dN)
        tt = -(Nf * (1.0 + eps) + Qf * gam)                         # theta-theta
        Kg[:, :, :, 2, :, 2] += tt[:, :, None, None] * Nn[:, :, :, None] * Nn[:, :, None, :]
        Ke += np.einsum("eg,egij->eij", w, Kg.reshape(n, G, 9, 9))
        K = np.zeros((3 * self.nn, 3 * self.nn))
        idx = self.edofs
        np.add.at(K, (idx[:, :, None], idx[:, None, :]), Ke)
        return f, K

    def solve(self, times, rtol=1e-10, method="Radau"):
        """Tip (x, z) at `times` (s) and solver statistics."""
        fr = self.free
        nf = len(fr)
        q0 = self.initial()[fr]
        y0 = np.concatenate([q0, np.zeros(nf)])
        full = self.initial()

        def unpack(y):
            q = full.copy()
            q[fr] = y[:nf]
            return q

        def rhs(t, y):
            f, _ = self.internal(unpack(y))
            return np.concatenate([y[nf:], self.Minv @ (self.fg - f[fr])])

        def jac(t, y):
            _, K = self.internal(unpack(y), tangent=True)
            J = np.zeros((2 * nf, 2 * nf))
            J[:nf, nf:] = np.eye(nf)
            J[nf:, :nf] = -self.Minv @ K[np.ix_(fr, fr)]
            return J

        # absolute tolerances: positions rtol (m), their velocities 10 rtol (m/s); the section
        # angles 1e-4 rad and their rates 1 rad/s only: the release excites the section-rotation
        # (shear) mode, sqrt(k G A / (rho I)) = 2.1e4 rad/s, whose resolution would need ~1e5
        # steps; Radau (L-stable) damps it instead, and the tip positions, controlled at rtol,
        # do not feel it (the tolerance check in study() measures what remains)
        ang = (fr % 3) == 2
        atol = np.concatenate([np.where(ang, 1e-4, rtol), np.where(ang, 1.0, 10.0 * rtol)])
        t0 = time.perf_counter()
        sol = solve_ivp(rhs, (0.0, float(times[-1])), y0, method=method, t_eval=times, rtol=rtol,
                        atol=atol, jac=jac)
        wall = time.perf_counter() - t0
        if not sol.success:
            raise RuntimeError(f"solve_ivp ({method}, {self.n} elements): {sol.message}")
        tip = 3 * (self.nn - 1)
        xs = sol.y[np.where(fr == tip)[0][0]]
        zs = sol.y[np.where(fr == tip + 1)[0][0]]
        return np.stack([xs, zs], axis=1), {"elements": self.n, "nfev": int(sol.nfev), "njev": int(sol.njev),
                                            "nlu": int(sol.nlu), "wall_s": round(wall, 1), "rtol": rtol}


def richardson3(f1, f2, f3, r=2.0, tiny=1e-12):
    """Point-wise Richardson of three arrays (coarse to fine): (value, error, order).
    Where the differences are below `tiny` or not monotone (a point of the history
    where the coarsest mesh's error changes sign): the finest value with twice the
    difference of the two finest meshes as the error (a bound when the finer pair
    converges at order 0.6 or more; the median observed order is ~3), no order."""
    e21, e32 = f2 - f1, f3 - f2
    ok = (e21 * e32 > 0) & (np.abs(e32) < np.abs(e21)) & (np.abs(e32) > tiny)
    with np.errstate(divide="ignore", invalid="ignore"):
        p = np.where(ok, np.log(np.abs(e21 / np.where(e32 == 0, 1, e32))) / math.log(r), np.nan)
        val = np.where(ok, f3 + e32 / (r ** p - 1.0), f3)
    err = np.where(ok, 1.25 * np.abs(val - f3), 2.0 * np.abs(e32))
    return val, err, p


CACHE = ROOT / "out" / "pendulum_reissner"


def cached(n, times, rtol):
    """Beam(n).solve(times, rtol), kept in out/pendulum_reissner/ (a study re-run
    with other meshes re-uses the runs it shares)."""
    key = CACHE / f"n{n}_rtol{rtol:g}_t{len(times)}_{float(times[-1]):g}.json"
    if key.exists():
        d = json.loads(key.read_text())
        if np.allclose(d["times"], times, rtol=0, atol=1e-12):
            return np.array(d["tip"]), d["info"]
    tip, info = Beam(n).solve(times, rtol=rtol)
    CACHE.mkdir(parents=True, exist_ok=True)
    key.write_text(json.dumps({"times": [float(t) for t in times], "tip": tip.tolist(), "info": info}))
    return tip, info


def study(n0=16, times=None, rtol=1e-10, log=None):
    """Mesh study n0, 2 n0, 4 n0 elements and the tolerance check; a dict as stored."""
    if times is None:
        times = np.round(np.arange(1, 101) * 0.01, 10)
    runs, tips = [], []
    for n in (n0, 2 * n0, 4 * n0):
        tip, info = cached(n, times, rtol)
        runs.append(info)
        tips.append(tip)
        if log:
            log(f"  {n} elements: tip at 1 s ({tip[-1, 0]:.9f}, {tip[-1, 1]:.9f}) m, {info['wall_s']} s")
    val, err, p = richardson3(*tips)
    tipc, infoc = cached(4 * n0, times, rtol * 10.0)
    tol_diff = np.abs(tipc - tips[-1])
    err = err + tol_diff
    if log:
        log(f"  tolerance check (rtol {rtol * 10:g}): largest difference {tol_diff.max():.1e} m")
    sec = dict(zip(("EA", "kGA", "EI", "rhoA", "rhoI"), sections(SCENE)))
    ordr = p[np.isfinite(p)]
    return {
        "about": "Soft seed pendulum (models/pendulum_soft_*.toml) by references/pendulum_reissner.py: a planar "
                 "geometrically exact (Reissner/Simo) beam, quadratic elements (x, z, theta per node), 2-point "
                 "reduced integration, consistent translational and rotary inertia, pinned at x = 0, released "
                 "from the horizontal under gravity; scipy solve_ivp Radau with the analytic Jacobian.  Tip "
                 "position (x, z) in m, Richardson-extrapolated over the meshes point by point, error = 1.25 "
                 "|extrapolated - finest| (where the differences are not monotone: the finest value, error 2 "
                 "|finest - second finest|) + |finest(rtol) - finest(10 rtol)|.",
        "command": "/usr/bin/python3 -m references.pendulum_reissner --write",
        "scene": dict(SCENE), "sections": sec,
        "meshes": [r["elements"] for r in runs], "runs": runs + [infoc],
        "order_median": None if not len(ordr) else round(float(np.median(ordr)), 2),
        "tolerance_check_max": float(f"{tol_diff.max():.3e}"),
        "columns": ["t", "x", "z", "err_x", "err_z", "x_finest", "z_finest"],
        "rows": [[float(t), float(f"{v[0]:.10e}"), float(f"{v[1]:.10e}"), float(f"{e[0]:.3e}"),
                  float(f"{e[1]:.3e}"), float(f"{w[0]:.10e}"), float(f"{w[1]:.10e}")]
                 for t, v, e, w in zip(times, val, err, tips[-1])],
    }


def load(path=DATA):
    """The committed reference: {t: ((x, y, z), err)} with err the distance bound
    sqrt(err_x^2 + err_z^2) (m); y = 0."""
    d = json.loads(Path(path).read_text(encoding="utf-8"))
    return {round(r[0], 10): ((r[1], 0.0, r[2]), math.hypot(r[3], r[4])) for r in d["rows"]}


def meshes(path=DATA):
    """The element counts of the committed mesh study."""
    return json.loads(Path(path).read_text(encoding="utf-8"))["meshes"]


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python3 -m references.pendulum_reissner",
                                 description="Soft seed pendulum by a planar Reissner beam (scipy).")
    ap.add_argument("--n0", type=int, default=16, help="coarsest mesh (elements); the study uses n0, 2 n0, 4 n0")
    ap.add_argument("--rtol", type=float, default=1e-10)
    ap.add_argument("--write", action="store_true", help=f"write {DATA.relative_to(ROOT)}")
    a = ap.parse_args(argv)
    log = lambda s: print(s, file=sys.stderr, flush=True)    # noqa: E731
    d = study(a.n0, rtol=a.rtol, log=log)
    last = d["rows"][-1]
    print(f"tip at t = 1 s: x = {last[1]:.9f} +- {last[3]:.1e} m, z = {last[2]:.9f} +- {last[4]:.1e} m "
          f"(median observed order {d['order_median']})")
    print("largest error estimate over t: x %.1e m, z %.1e m" % (max(r[3] for r in d["rows"]),
                                                                 max(r[4] for r in d["rows"])))
    if a.write:
        DATA.write_text(json.dumps(d, indent=1) + "\n", encoding="utf-8")
        print(f"wrote {DATA}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
