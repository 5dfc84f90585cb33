"""Symbolic reverse chain rule through layers of named intermediates.

Given the gradient G and Hessian H of a scalar with respect to outer variables
a, and a map a = a(b) to inner variables b, `pull_back` defines, in a
Program, the gradient and Hessian with respect to b:

    G_b  = sum_a G_a da/db
    H_bc = sum_aa' da/db H_aa' da'/dc + sum_a G_a d2a/db dc

Each layer is differentiated on its own (small) expressions, so deeply nested
kinematics (rotations of rotations) cost a sum over layers instead of the
product sympy's diff would build on the composite.  The Gauss-Newton part
J^T H J is formed as J^T (H J) with the columns of H J named once.  Hessians are
kept as upper triangles in the order of the inner variable list.
"""
import re

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
    # J^T H J, factored as J^T (H J): T[a][c] = sum_a' H_aa' da'/dc is named once
    # and reused by every b, instead of expanding sum_aa' da/db H_aa' da'/dc.
    Hrow = {}
    for (a, a2), h in H.items():
        if h == 0:
            continue
        Hrow.setdefault(a, {})
        Hrow[a][a2] = Hrow[a].get(a2, 0) + h
        if a2 != a:
            Hrow.setdefault(a2, {})
            Hrow[a2][a] = Hrow[a2].get(a, 0) + h
    names = {a: re.sub(r"\W", "_", a.name) for a in outer}
    users = {}                                   # inner symbol -> outer symbols whose map has it
    for a in sorted(outer, key=lambda s: s.name):
        for b in J[a]:
            users.setdefault(b, []).append(a)
    T = {}

    def t(a, c):
        if (a, c) not in T:
            T[(a, c)] = _named(prog, f"{tag}T_{names[a]}_{index[c]}",
                               sum(h * J[a2][c] for a2, h in Hrow.get(a, {}).items() if c in J[a2]))
        return T[(a, c)]

    Hin = {}

    def add(i, j, v):
        if i > j:
            i, j = j, i
        Hin[(i, j)] = Hin.get((i, j), 0) + v

    for b in sorted(users, key=lambda s: index[s]):
        for c in sorted(users, key=lambda s: index[s]):
            if index[c] < index[b]:
                continue
            v = sum(J[a][b] * t(a, c) for a in users[b] if a in Hrow and any(c in J[a2] for a2 in Hrow[a]))
            if v != 0:
                add(index[b], index[c], v)
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
