"""The rotary inertia of a rod node as a program (out/kernels/rod_inertia.c, and
the rigid body's through gen/body.py): the Lagrange equations of the kinetic
energy of a quaternion's rotation and their Jacobians."""
import sympy as sp

from gen.program import Program
from gen.rod import _syms, qconj, qmul


def rotary_node_program():
    """Rotary inertia of one node with inertia Jn[3] = w_n l (Ip, I1, I2) per unit
    density: T = 1/2 W^T diag(Jn) W with the body angular velocity
    W = 2 g / |p|^2, g = Im(conj(p) p'); f[4] = d/dt dT/dp' - dT/dp, Mq = df/dp'',
    Cq = df/dp', Kq = df/dp (4 x 4 row-major), T[0].

    Written in the intermediates ni = 1/|p|^2, n2' = 2 p.p', g and
    g' = Im(conj(p) p'') (conj(p')p' is real): with dg/dp' = G(p), dg/dp = -G(p'),
        dT/dp' = 2 ni G(p)^T J W,   dT/dp = 2 ni (-G(p')^T J W) - 4 ni^2 p (g . J W),
    the time derivative of the first by the product rule; the Jacobians of f by
    the chain rule through the intermediates (gen/chain.py)."""
    from gen.chain import pull_back
    prog = Program()
    Jn = _syms("Jn", 3)
    p, pd, pdd = _syms("p", 4), _syms("pd", 4), _syms("pdd", 4)

    def im(a, b):
        return list(qmul(qconj((a[0], sp.Matrix(a[1:]))), (b[0], sp.Matrix(b[1:])))[1])
    ni, n2d = sp.symbols("ni n2d", real=True)
    g = sp.symbols("g0:3", real=True)
    gd = sp.symbols("gd0:3", real=True)
    umap = {ni: 1 / sum(x * x for x in p), n2d: 2 * sum(a * b for a, b in zip(p, pd))}
    umap.update(dict(zip(g, im(p, pd))))
    umap.update(dict(zip(gd, im(p, pdd))))
    for x, e in umap.items():
        prog.defs.append((x, e))
    W = [2 * g[k] * ni for k in range(3)]
    Wd = [2 * (gd[k] * ni - g[k] * n2d * ni**2) for k in range(3)]
    gexpr = im(p, pd)
    G = [[sp.diff(gexpr[k], pd[i]) for i in range(4)] for k in range(3)]      # G(p), linear in p
    Gd = [[sp.diff(gexpr[k], p[i]) for i in range(4)] for k in range(3)]      # -G(p')
    to_pd = dict(zip(p, pd))
    JW = [Jn[k] * W[k] for k in range(3)]
    JWd = [Jn[k] * Wd[k] for k in range(3)]
    nid = -n2d * ni**2
    y = list(p) + list(pd) + list(pdd)
    for i in range(4):
        dpi = sum(2 * (nid * JW[k] * G[k][i] + ni * JWd[k] * G[k][i]
                       + ni * JW[k] * G[k][i].xreplace(to_pd)) for k in range(3))
        dTdp = sum(JW[k] * (2 * Gd[k][i] * ni - 4 * g[k] * p[i] * ni**2) for k in range(3))
        fi = dpi - dTdp
        prog.output(f"f[{i}]", fi, op="=")
        outer = sorted(fi.free_symbols & (set(y) | set(umap)), key=lambda x: x.name)
        Gy, _ = pull_back(prog, f"f{i}", {x: sp.diff(fi, x) for x in outer}, {}, umap, y, False)
        for arr, var in (("Mq", pdd), ("Cq", pd), ("Kq", p)):
            for j in range(4):
                prog.output(f"{arr}[{4 * i + j}]", Gy.get(var[j], 0), op="=")
    prog.output("T[0]", sum(Jn[k] * W[k]**2 for k in range(3)) / 2, op="=")
    return prog
