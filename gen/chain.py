"""Symbolic reverse chain rule through layers of named intermediates.

Given the gradient G and Hessian H of a scalar with respect to outer variables
a, and a map a = a(b) to inner variables b, `pull_back` defines, in a
Program, the gradient and Hessian with respect to b:

    G_b  = sum_a G_a da/db
    H_bc = sum_aa' da/db H_aa' da'/dc + sum_a G_a d2a/db dc

Each layer is differentiated on its own (small) expressions, so deeply nested
kinematics (rotations of rotations) cost a sum over layers instead of the
product sympy's diff would build on the composite.  Hessians are kept as upper
triangles in the order of the inner variable list.
"""
import sympy as sp


def _named(prog, name, expr):
    expr = sp.sympify(expr)
    if expr.is_Atom:
        return expr
    return prog.define(name, expr)


def pull_back(prog, tag, G, H, mapping, inner, second=True):
    """G: {outer symbol: expr}; H: {(a, a'): expr} upper triangle in the order of
    `outer_order` (the keys of mapping plus pass-through symbols); mapping:
    {outer symbol: expr of inner symbols}; outer symbols not in mapping are
    inner symbols themselves.  Returns (G_in, H_in) with H_in keyed by inner
    index pairs (i <= j)."""
    index = {s: i for i, s in enumerate(inner)}
    outer = list(G.keys() | {a for pair in H for a in pair})
    J, Hs = {}, {}
    for a in outer:
        if a in mapping:
            e = mapping[a]
            J[a] = {}
            for b in sorted(e.free_symbols & set(inner), key=lambda s: index[s]):
                d = sp.diff(e, b)
                if d != 0:
                    J[a][b] = d
        else:
            J[a] = {a: sp.Integer(1)}
    Gin = {}
    for a, g in G.items():
        if g == 0:
            continue
        for b, d in J[a].items():
            Gin[b] = Gin.get(b, 0) + g * d
    Gin = {b: _named(prog, f"{tag}G_{index[b]}", v) for b, v in sorted(Gin.items(), key=lambda kv: index[kv[0]])}
    if not second:
        return Gin, {}
    Hin = {}

    def add(i, j, v):
        if i > j:
            i, j = j, i
        Hin[(i, j)] = Hin.get((i, j), 0) + v

    for (a, a2), h in H.items():
        if h == 0:
            continue
        for b, db in J[a].items():
            for c, dc in J[a2].items():
                i, j = index[b], index[c]
                v = h * db * dc
                if a == a2:
                    if i <= j:
                        add(i, j, v)
                elif i == j:
                    add(i, i, 2 * v)
                else:
                    add(i, j, v)
    for a, g in G.items():
        if g == 0 or a not in mapping:
            continue
        items = list(J[a].items())
        for x, (b, db) in enumerate(items):
            for c, _ in items[x:]:
                d2 = sp.diff(db, c)
                if d2 != 0:
                    add(index[b], index[c], g * d2)
    Hin = {k: _named(prog, f"{tag}H_{k[0]}_{k[1]}", v) for k, v in sorted(Hin.items())}
    return Gin, Hin
