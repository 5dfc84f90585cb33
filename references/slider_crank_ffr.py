"""Slider-crank with a flexible connecting rod by a floating frame of reference
(assumed modes) model in numpy/scipy, sharing nothing with beamkit's elements.

The scene (models/slider_crank.toml): the crank pin A(t) = r (cos wt, sin wt),
r = 0.15 m, w = 4 pi rad/s (the crank, E = 2.1e13 Pa, is taken as rigid: its
bending under the rod force is ~1e-7 m); the connecting rod of length l = 0.5 m,
a circle of radius 6 mm, E = 1e9 Pa, nu = 0.3, rho = 100 kg/m^3, pinned at A
(the universal joint leaves the in-plane rotation free) and at the slider pin
B = (s, 0) (spherical joint); the slider M = 0.5 kg on the x axis; no gravity.
Started on the head-end dead centre (s = l + r) with the velocities of the
rigid mechanism; Rayleigh damping beta = 1.5 ms.  The motion is planar (x-y).

Model (written from the theory):
  * the chord frame: e1 = (B - A)/c, c = |B - A|, e2 = z x e1;
  * the rod's material point at reference arc length xi in [0, l] is at
        R(xi) = A + (xi + u(xi)) e1 + w(xi) e2,
        u(xi) = (xi / l)(c - l) + sum_k a_k sin(k pi xi / l)   (axial),
        w(xi) = sum_i eta_i sin(i pi xi / l)                   (transverse),
    generalized coordinates q = (s, a_1..a_Na, eta_1..eta_Nb): the chord
    stretch c - l follows from s, the internal axial modes and the pinned-pinned
    transverse modes vanish at both pins;
  * kinetic energy 1/2 int rho A |dR/dt|^2 dxi + 1/2 M s'^2: Lagrange's equations
    int rho A (dR/dq)^T R'' dxi + M s'' e_s = Q, with R'' = J q'' + gamma and
    gamma holding every rigid-motion and coupling term (the transverse and axial
    accelerations of the chord points, centrifugal, Coriolis: from the exact
    first and second derivatives of c(s, t) and e1(s, t));
  * strain energy 1/2 int EA eps^2 dxi + 1/2 sum_i k_i eta_i^2 with the
    moderate-rotation axial strain eps = u' + w'^2 / 2: its eta-derivative
    int EA eps w' phi_i' is the geometric stiffness of the axial force
    distribution N(xi) = EA eps(xi), which the axial coordinates (the slider's
    and the rod's own axial inertia, centrifugal included) determine; the
    bending stiffness of the sine mode i, k_i = EI (i pi/l)^4 (l/2) / (1 +
    EI (i pi/l)^2 / (k G A)), is the Euler-Bernoulli value with the shear
    compliance of a Timoshenko beam condensed (exact for a sine mode of a pinned
    beam; 0.1 % for mode 1 here; Cowper's circle k = 6(1+nu)/(7+6nu));
  * Rayleigh damping as beamkit defines it, C = beta K_t (the tangent stiffness
    at the current state), in three parts: (1) on the elastic coordinates
    e = (c - l, a, eta), K_t(e) e' = int EA eps' d eps/de + int N w_t' phi_i'
    + k_i eta_i' (the Hessian of the strain energy: the viscous axial force
    beta EA times the full strain rate, and the geometric part beta N w_t');
    (2) on the rigid rotation of the stressed rod at the chord's rate phi'
    (objectivity: the internal forces of the rotated state are the rotated
    ones): K_t v_rot . dq = phi' int (z x n) . dR' dxi with the resultant
    n ~ N R' (its shear part, V/N < 1 %, left out).  damping="rotation" (the
    default) has both; "tangent" only (1); "elastic" only the linear K on e
    (int EA u_t' d u'/de + k_i eta_i'): the differences show how much the
    definition of the damping matters (see `study`);
  * Gauss-Legendre quadrature in xi (exact enough: checked by doubling), the
    first-order system by scipy.integrate.solve_ivp (Radau, finite-difference
    Jacobian), dense output at the requested times.

Assumptions: small elastic deflection relative to the chord frame (w' ~ 1e-3),
moderate-rotation strain (error O(w'^2 u', w'^4)), Euler-Bernoulli kinematics
for the inertia (the rotary inertia of the section, (r/2l)^2 ~ 4e-5 of the
translational, is left out), shear only through the modal stiffness, modal
truncation (Na axial, Nb transverse modes), the crank rigid.

The reference is the run Na = 3, Nb = 7, rtol 1e-9, 32 Gauss points; its
error is estimated from the differences to Nb = 5, Na = 2, to rtol 1e-8 and to
48 Gauss points (`study`).  Measured over t >= 0.1 s: Nb 5 against 7 differ by
7.1e-9 m in the midpoint deflection (largest 1.07e-4 m), Na 2 against 3 by
5.6e-9 m, rtol 1e-8 against 1e-9 by 4e-14 m, 48 against 32 Gauss points by
6e-15 m: error estimate 1.3e-8 m (slider 6e-12 m).  Without the internal axial
modes (Na = 0, a uniform axial force) the deflection at t = 0.2 s is 1.0e-6 m
off: the axial force distribution matters.  The model's sensitivity to the
damping's definition: "tangent" 1.3e-6 m, "elastic" 9.7e-7 m; to the shear
compliance 1.15e-7 m.  Committed as references/data/slider_crank_ffr.json
(t, midpoint deflection w(l/2) along e2 and slider position s every 1 ms to
0.75 s); regenerate it with

    /usr/bin/python3 -m references.slider_crank_ffr --write

(eight runs, about 10 minutes on one busy core).  tests/test_slider_crank.py
reads the data and recomputes a short coarse run as a check that the data match
the code.
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
DATA = ROOT / "references" / "data" / "slider_crank_ffr.json"

SCENE = dict(r=0.15, l=0.5, radius=0.006, E=1.0e9, nu=0.3, rho=100.0, M=0.5,
             omega=4.0 * math.pi, beta=1.5e-3, t_end=0.75)


def sections(p):
    """(EA, EI, kGA, rhoA) of the circular rod."""
    A = math.pi * p["radius"] ** 2
    I = math.pi * p["radius"] ** 4 / 4.0
    G = p["E"] / (2.0 * (1.0 + p["nu"]))
    k = 6.0 * (1.0 + p["nu"]) / (7.0 + 6.0 * p["nu"])
    return p["E"] * A, p["E"] * I, k * G * A, p["rho"] * A


class SliderCrank:
    """The FFR model: q = (s, a_1..a_na, eta_1..eta_nb)."""

    def __init__(self, na=3, nb=7, ngauss=32, p=SCENE, damping="rotation", shear=True):
        if damping not in ("rotation", "tangent", "elastic"):
            raise ValueError(f"damping: expected 'rotation', 'tangent' or 'elastic', got {damping!r}")
        self.p, self.na, self.nb, self.damping = dict(p), na, nb, damping
        self.n = 1 + na + nb
        self.EA, self.EI, self.kGA, self.rhoA = sections(self.p)
        l = self.p["l"]
        x, wq = np.polynomial.legendre.leggauss(ngauss)
        self.xi = 0.5 * l * (x + 1.0)
        self.wq = 0.5 * l * wq
        ka = np.arange(1, na + 1)[:, None] * math.pi / l
        kb = np.arange(1, nb + 1)[:, None] * math.pi / l
        self.Sa, self.dSa = np.sin(ka * self.xi), ka * np.cos(ka * self.xi)        # (na, ng)
        self.Sb, self.dSb = np.sin(kb * self.xi), kb * np.cos(kb * self.xi)        # (nb, ng)
        kk = kb[:, 0]
        shear_fac = 1.0 + (self.EI * kk**2 / self.kGA if shear else 0.0)
        self.kbend = self.EI * kk**4 * (l / 2.0) / shear_fac
        self.mid = np.sin(np.arange(1, nb + 1) * math.pi / 2.0)                  # w(l/2) = mid . eta

    # chord kinematics: c(s, t), e1(s, t) and their partial derivatives
    def chord(self, s, t):
        r, w = self.p["r"], self.p["omega"]
        ct, st = math.cos(w * t), math.sin(w * t)
        A = np.array([r * ct, r * st])
        At = np.array([-r * w * st, r * w * ct])
        Att = -w * w * A
        d = np.array([s, 0.0]) - A
        c = math.hypot(d[0], d[1])
        e1 = d / c
        # derivatives of d: d_s = (1, 0), d_t = -A', d_tt = -A'', d_ss = d_st = 0
        ds, dt, dtt = np.array([1.0, 0.0]), -At, -Att
        c_s, c_t = e1 @ ds, e1 @ dt
        e1_s = (ds - c_s * e1) / c
        e1_t = (dt - c_t * e1) / c
        c_ss = ds @ e1_s
        c_st = ds @ e1_t
        c_tt = dtt @ e1 + dt @ e1_t
        # e1 = d / c: e1_ab = (d_ab - c_ab e1 - c_a e1_b - c_b e1_a) / c
        e1_ss = (-c_ss * e1 - 2.0 * c_s * e1_s) / c
        e1_st = (-c_st * e1 - c_s * e1_t - c_t * e1_s) / c
        e1_tt = (dtt - c_tt * e1 - 2.0 * c_t * e1_t) / c
        return dict(A=A, Att=Att, c=c, e1=e1, c_s=c_s, c_t=c_t, c_ss=c_ss, c_st=c_st, c_tt=c_tt,
                    e1_s=e1_s, e1_t=e1_t, e1_ss=e1_ss, e1_st=e1_st, e1_tt=e1_tt)

    @staticmethod
    def _perp(v):
        """z x v for v of shape (..., 2) or (2,)."""
        return np.stack([-v[..., 1], v[..., 0]], axis=-1)

    def rhs(self, t, y):
        n, na, nb, l = self.n, self.na, self.nb, self.p["l"]
        q, qd = y[:n], y[n:]
        s, sd = q[0], qd[0]
        a, ad = q[1:1 + na], qd[1:1 + na]
        eta, etad = q[1 + na:], qd[1 + na:]
        k = self.chord(s, t)
        e1, c = k["e1"], k["c"]
        e2 = self._perp(e1)
        xi = self.xi
        X = xi + xi / l * (c - l) + a @ self.Sa                    # (ng,)
        W = eta @ self.Sb
        cdot = k["c_s"] * sd + k["c_t"]
        Xd = xi / l * cdot + ad @ self.Sa
        Wd = etad @ self.Sb
        e1d = k["e1_s"] * sd + k["e1_t"]
        e2d = self._perp(e1d)
        e1dd_v = k["e1_ss"] * sd * sd + 2.0 * k["e1_st"] * sd + k["e1_tt"]   # without the s'' part
        e2dd_v = self._perp(e1dd_v)
        cdd_v = k["c_ss"] * sd * sd + 2.0 * k["c_st"] * sd + k["c_tt"]
        # J: (ng, 2, n)
        ng = xi.size
        J = np.empty((ng, 2, n))
        J[:, :, 0] = (xi / l * k["c_s"])[:, None] * e1 + X[:, None] * k["e1_s"] + W[:, None] * self._perp(k["e1_s"])
        J[:, :, 1:1 + na] = self.Sa.T[:, None, :] * e1[None, :, None]
        J[:, :, 1 + na:] = self.Sb.T[:, None, :] * e2[None, :, None]
        gam = (k["Att"][None, :] + (xi / l * cdd_v)[:, None] * e1 + 2.0 * Xd[:, None] * e1d
               + X[:, None] * e1dd_v + 2.0 * Wd[:, None] * e2d + W[:, None] * e2dd_v)   # (ng, 2)
        wr = self.wq * self.rhoA
        Mq = np.einsum("g,gia,gib->ab", wr, J, J)
        Mq[0, 0] += self.p["M"]
        F = -np.einsum("g,gia,gi->a", wr, J, gam)
        # elastic forces
        up = (c - l) / l + a @ self.dSa
        wp = eta @ self.dSb
        eps = up + 0.5 * wp * wp
        N = self.EA * eps
        F[0] -= np.sum(self.wq * N) * k["c_s"] / l
        F[1:1 + na] -= self.dSa @ (self.wq * N)
        F[1 + na:] -= self.dSb @ (self.wq * N * wp) + self.kbend * eta
        # Rayleigh damping, beta K on the elastic coordinates
        beta = self.p["beta"]
        # (elastic coordinates e = (c - l, a, eta); K_t(e) = int EA g g^T + N d2eps/de2 + diag(k),
        # g = d eps/de, so K_t(e) e' = int EA eps' g + int N w_t' phi' + k eta')
        upd = cdot / l + ad @ self.dSa
        wpd = etad @ self.dSb
        if self.damping == "elastic":
            Nd = self.EA * upd
        else:
            Nd = self.EA * (upd + wp * wpd)
        F[0] -= beta * np.sum(self.wq * Nd) * k["c_s"] / l
        F[1:1 + na] -= beta * (self.dSa @ (self.wq * Nd))
        F[1 + na:] -= beta * self.kbend * etad
        if self.damping != "elastic":
            F[1 + na:] -= beta * (self.dSb @ (self.wq * (N * wpd + Nd * wp)))
        if self.damping == "rotation":
            # beta K_t applied to the rigid rotation (rate phi' of the chord) of the stressed
            # rod: K_t v_rot . dq = phi' int (z x n) . dR' dxi with the resultant n ~ N R'
            # (objectivity: f_int of the rotated state is the rotated f_int)
            phid = e2 @ e1d
            Xp = 1.0 + (c - l) / l + a @ self.dSa
            zxn = N[:, None] * (Xp[:, None] * e2[None, :] - wp[:, None] * e1[None, :])   # (ng, 2)
            Rp_s = ((k["c_s"] / l) * e1)[None, :] + Xp[:, None] * k["e1_s"][None, :] \
                + wp[:, None] * self._perp(k["e1_s"])[None, :]
            F[0] -= beta * phid * np.sum(self.wq * np.einsum("gi,gi->g", zxn, Rp_s))
            F[1:1 + na] -= beta * phid * (self.dSa @ (self.wq * (zxn @ e1)))
            F[1 + na:] -= beta * phid * (self.dSb @ (self.wq * (zxn @ e2)))
        return np.concatenate([qd, np.linalg.solve(Mq, F)])

    def y0(self):
        """Straight rod at the head-end dead centre, moving with the rigid mechanism
        (the chord frame carries the rigid motion: every elastic rate zero)."""
        y = np.zeros(2 * self.n)
        y[0] = self.p["l"] + self.p["r"]
        return y

    def run(self, times, rtol=1e-9, atol=None):
        """(w_mid, s) at the times; atol scaled to the coordinates' sizes."""
        if atol is None:
            sc = np.concatenate([[1.0], np.full(self.na, 1e-4), np.full(self.nb, 1e-4)])
            atol = rtol * np.concatenate([sc, 10.0 * sc])
        t0 = time.time()
        sol = solve_ivp(self.rhs, (0.0, float(times[-1])), self.y0(), method="Radau", t_eval=times,
                        rtol=rtol, atol=atol, dense_output=False)
        if not sol.success:
            raise RuntimeError(f"solve_ivp failed: {sol.message}")
        eta = sol.y[1 + self.na:self.n]
        return dict(w_mid=self.mid @ eta, s=sol.y[0], nfev=int(sol.nfev),
                    wall_s=round(time.time() - t0, 1))


def rigid_slider(t, p=SCENE):
    th = p["omega"] * np.asarray(t)
    return p["r"] * np.cos(th) + np.sqrt(p["l"] ** 2 - (p["r"] * np.sin(th)) ** 2)


def study(times=None, log=None):
    """The reference run and its convergence checks; a dict as stored."""
    if times is None:
        times = np.round(np.arange(0, 751) * 1e-3, 10)
    base = dict(na=3, nb=7, ngauss=32, rtol=1e-9)
    variants = {"reference": {}, "nb5": dict(nb=5), "na2": dict(na=2), "rtol1e-8": dict(rtol=1e-8),
                "gauss48": dict(ngauss=48), "damping_tangent": dict(damping="tangent"),
                "damping_elastic": dict(damping="elastic"), "no_shear": dict(shear=False)}
    out = {}
    for name, v in variants.items():
        cfg = dict(base, **v)
        rtol = cfg.pop("rtol")
        res = SliderCrank(**cfg).run(times, rtol=rtol)
        out[name] = res
        if log:
            log(f"  {name}: max |w_mid| {np.abs(res['w_mid']).max():.6e} m, {res['nfev']} rhs, {res['wall_s']} s")
    ref = out["reference"]
    late = times >= 0.1
    diffs = {}
    for name, res in out.items():
        if name == "reference":
            continue
        diffs[name] = dict(w_mid=float(f"{np.abs(res['w_mid'] - ref['w_mid'])[late].max():.3e}"),
                           s=float(f"{np.abs(res['s'] - ref['s'])[late].max():.3e}"))
        if log:
            log(f"  |{name} - reference| for t >= 0.1 s: w_mid {diffs[name]['w_mid']:.2e} m, "
                f"s {diffs[name]['s']:.2e} m")
    numerics = ("nb5", "na2", "rtol1e-8", "gauss48")
    err_w = sum(diffs[k]["w_mid"] for k in numerics)
    err_s = sum(diffs[k]["s"] for k in numerics)
    return {
        "about": "Slider-crank with a flexible connecting rod (models/slider_crank.toml) by "
                 "references/slider_crank_ffr.py: floating frame of reference on the chord between the "
                 "crank pin and the slider pin, the chord stretch plus Na = 3 internal axial sine modes, "
                 "Nb = 7 pinned-pinned transverse sine modes, moderate-rotation axial strain (geometric "
                 "stiffness of the axial force distribution), Euler-Bernoulli inertia, Timoshenko shear "
                 "compliance condensed per mode, slider mass, Rayleigh damping beta K_t (on the elastic "
                 "coordinates and on the rigid rotation of the stressed rod); scipy Radau rtol 1e-9, 32 "
                 "Gauss points.  w_mid: the rod's midpoint (reference arc length l/2) from the chord line "
                 "along e2 = z x (B - A)/|B - A| (m); s: slider x (m).  err_*: the sum of the largest "
                 "differences (t >= 0.1 s) to Nb = 5, Na = 2, rtol 1e-8 and 48 Gauss points (each an "
                 "over-estimate of the reference's error in that respect).  The damping_* and no_shear "
                 "entries show the model's sensitivity, not its error.",
        "command": "/usr/bin/python3 -m references.slider_crank_ffr --write",
        "scene": dict(SCENE), "sections": dict(zip(("EA", "EI", "kGA", "rhoA"), sections(SCENE))),
        "reference": dict(base, damping="rotation", shear=True),
        "differences_t_ge_0.1": diffs,
        "err_w_mid": float(f"{err_w:.3e}"), "err_s": float(f"{err_s:.3e}"),
        "runs": {k: dict(nfev=v["nfev"], wall_s=v["wall_s"]) for k, v in out.items()},
        "columns": ["t", "w_mid", "s"],
        "rows": [[float(t), float(f"{w:.10e}"), float(f"{s:.12e}")]
                 for t, w, s in zip(times, ref["w_mid"], ref["s"])],
    }


def load(path=DATA):
    """The committed reference: (data dict, t, w_mid, s) as arrays."""
    d = json.loads(Path(path).read_text(encoding="utf-8"))
    a = np.array(d["rows"])
    return d, a[:, 0], a[:, 1], a[:, 2]


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python3 -m references.slider_crank_ffr",
                                 description="Flexible slider-crank by a floating-frame assumed-modes model (scipy).")
    ap.add_argument("--write", action="store_true", help=f"write {DATA.relative_to(ROOT)}")
    a = ap.parse_args(argv)
    log = lambda s: print(s, file=sys.stderr, flush=True)    # noqa: E731
    d = study(log=log)
    w = np.array(d["rows"])[:, 1]
    print(f"largest |w_mid| {np.abs(w).max():.6e} m; estimated error w_mid {d['err_w_mid']:.1e} m, "
          f"s {d['err_s']:.1e} m")
    if a.write:
        DATA.write_text(json.dumps(d, indent=1) + "\n", encoding="utf-8")
        print(f"wrote {DATA}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
