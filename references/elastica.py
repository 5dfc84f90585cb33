"""Closed-form and ODE references for planar elasticae (inextensible, unshearable,
linear moment-curvature EI), used by tests and reports."""
import math


def heavy_cantilever(L, q, EI, n=4000):
    """Cantilever clamped horizontally at s = 0 under its own weight q (N/m), free end.
    theta'' = -q (L - s) cos(theta) / EI, theta(0) = 0, theta'(L) = 0, solved by
    shooting on theta'(0) with RK4 on n steps.  Returns (tip x, tip deflection down)."""
    def shoot(k0):
        h = L / n
        th, k, x, z, s = 0.0, k0, 0.0, 0.0, 0.0
        f = lambda s, th, k: (k, -q * (L - s) * math.cos(th) / EI, math.cos(th), math.sin(th))
        for _ in range(n):
            a = f(s, th, k)
            b = f(s + h / 2, th + h / 2 * a[0], k + h / 2 * a[1])
            c = f(s + h / 2, th + h / 2 * b[0], k + h / 2 * b[1])
            d = f(s + h, th + h * c[0], k + h * c[1])
            th += h / 6 * (a[0] + 2 * b[0] + 2 * c[0] + d[0])
            k += h / 6 * (a[1] + 2 * b[1] + 2 * c[1] + d[1])
            x += h / 6 * (a[2] + 2 * b[2] + 2 * c[2] + d[2])
            z += h / 6 * (a[3] + 2 * b[3] + 2 * c[3] + d[3])
            s += h
        return k, x, z
    lo, hi = 0.0, q * L**2 / (2 * EI)      # the root curvature lies below the linear one
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if shoot(mid)[0] > 0:
            hi = mid
        else:
            lo = mid
    _, x, z = shoot(0.5 * (lo + hi))
    return x, z


def tip_load_cantilever(L, P, EI, n=4000):
    """Cantilever clamped horizontally at s = 0 with a tip load P perpendicular to the
    undeformed axis (fixed direction): theta'' = -P cos(theta)/EI, theta(0) = 0,
    theta'(L) = 0 (inextensible elastica), by shooting with RK4.  Returns
    (u, w): tip displacement along the axis and along the load."""
    def shoot(k0):
        h = L / n
        th, k, x, z = 0.0, k0, 0.0, 0.0
        f = lambda th, k: (k, -P * math.cos(th) / EI, math.cos(th), math.sin(th))
        for _ in range(n):
            a = f(th, k)
            b = f(th + h / 2 * a[0], k + h / 2 * a[1])
            c = f(th + h / 2 * b[0], k + h / 2 * b[1])
            d = f(th + h * c[0], k + h * c[1])
            th += h / 6 * (a[0] + 2 * b[0] + 2 * c[0] + d[0])
            k += h / 6 * (a[1] + 2 * b[1] + 2 * c[1] + d[1])
            x += h / 6 * (a[2] + 2 * b[2] + 2 * c[2] + d[2])
            z += h / 6 * (a[3] + 2 * b[3] + 2 * c[3] + d[3])
        return k, x, z
    lo, hi = 0.0, P * L / EI
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if shoot(mid)[0] > 0:
            hi = mid
        else:
            lo = mid
    _, x, z = shoot(0.5 * (lo + hi))
    return x - L, z
