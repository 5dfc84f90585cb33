"""Reference for the pendulum tests and the hard-case report: a uniform rigid
rod pinned at one end, released from the horizontal,
theta'' = 3 g / (2 L) cos(theta) (theta below the horizontal), by RK4."""
import math


def rigid_pendulum(t_end, n=40000, g=9.81, L=1.0):
    """Returns lists (times, tip x, tip z) at n + 1 equally spaced times."""
    h = t_end / n
    th, w = 0.0, 0.0
    ts, xs, zs = [0.0], [L], [0.0]

    def f(th, w):
        return w, 1.5 * g / L * math.cos(th)
    for i in range(n):
        a = f(th, w)
        b = f(th + h / 2 * a[0], w + h / 2 * a[1])
        c = f(th + h / 2 * b[0], w + h / 2 * b[1])
        d = f(th + h * c[0], w + h * c[1])
        th += h / 6 * (a[0] + 2 * b[0] + 2 * c[0] + d[0])
        w += h / 6 * (a[1] + 2 * b[1] + 2 * c[1] + d[1])
        ts.append((i + 1) * h)
        xs.append(L * math.cos(th))
        zs.append(-L * math.sin(th))
    return ts, xs, zs
