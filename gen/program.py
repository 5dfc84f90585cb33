"""Straight-line programs: named intermediate definitions plus outputs, reduced by
common-subexpression elimination over everything at once, ordered, split into a
prologue (what depends only on parameters) and a body, counted and printed as C.

The result is deterministic: symbols are ordered by their names, sympy's
canonical argument order does not depend on hashing, and the CSE symbols are
numbered in the order cse() meets them.
"""
import re

import sympy as sp
from sympy.printing.c import C99CodePrinter


class Program:
    """Definitions `sym = expr` (in any order that respects dependencies) and
    outputs `target op expr` (op is "=" or "+=")."""

    def __init__(self):
        self.defs = []          # (Symbol, expr)
        self.outputs = []       # (target string, op, expr)

    def define(self, name, expr):
        s = sp.Symbol(name, real=True)
        self.defs.append((s, sp.sympify(expr)))
        return s

    def output(self, target, expr, op="+="):
        self.outputs.append((target, op, sp.sympify(expr)))


def _sort_key(sym):
    m = re.match(r"([A-Za-z_]+)(\d*)$", sym.name)
    if m and m.group(2):
        return (m.group(1), int(m.group(2)), sym.name)
    return (sym.name, -1, sym.name)


def _free(expr):
    return sorted(expr.free_symbols, key=_sort_key)


class Lowered:
    """A program after CSE: prologue and body assignments and the outputs."""

    def __init__(self, prologue, body, outputs):
        self.prologue = prologue    # [(Symbol, expr)]
        self.body = body            # [(Symbol, expr)]
        self.outputs = outputs      # [(target, op, expr)]


def lower(prog, hoistable):
    """CSE over all definitions and outputs; order by dependency; drop what no
    output needs; move assignments whose inputs are all in `hoistable` (e.g. the
    material parameters) to the prologue."""
    exprs = [e for _, e in prog.defs] + [e for _, _, e in prog.outputs]
    # Powers b**(p/3) through one cube root per base, c = cbrt(b), then c**p as
    # products: a single libm call where cbrt(b*b), cbrt(b*b*b*b), ... were several.
    roots = {}

    def _root(e):
        b = e.base
        if b not in roots:
            roots[b] = sp.Symbol(f"cb{len(roots)}", real=True)
        return roots[b] ** int(e.exp.p)

    def _is_third(e):
        return e.is_Pow and e.exp.is_Rational and e.exp.q == 3

    exprs = [e.replace(_is_third, _root) if e.has(sp.Pow) else e for e in exprs]
    root_defs = [(c, sp.Pow(b, sp.Rational(1, 3), evaluate=False)) for b, c in roots.items()]
    # A base with several negative integer powers (b**-5, b**-8, ...) through
    # one reciprocal r = 1/b and products of r: one division where there were
    # several (a vector division costs as much as 20-30 multiplications).
    negs = {}
    for e in exprs:
        for f in e.atoms(sp.Pow):
            if f.exp.is_Integer and f.exp < 0:
                negs.setdefault(f.base, set()).add(int(f.exp))
    recips = {}
    for b in sorted((b for b, ns in negs.items() if len(ns) > 1), key=sp.default_sort_key):
        recips[b] = sp.Symbol(f"rc{len(recips)}", real=True)

    def _is_recip(e):
        return e.is_Pow and e.exp.is_Integer and e.exp < 0 and e.base in recips

    if recips:
        exprs = [e.replace(_is_recip, lambda e: recips[e.base] ** int(-e.exp)) for e in exprs]
        root_defs += [(r, sp.Pow(b, -1, evaluate=False)) for b, r in recips.items()]
    exprs = [e for _, e in root_defs] + exprs
    repl, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("x", real=True), order="none")
    nr = len(root_defs)
    repl = [(c, reduced[k]) for k, (c, _) in enumerate(root_defs)] + list(repl)
    reduced = reduced[nr:]
    nd = len(prog.defs)
    assign = {}                 # Symbol -> expr
    order_hint = {}
    for k, (s, e) in enumerate(repl):
        assign[s] = e
        order_hint[s] = ("x", k)
    for k, (s, _) in enumerate(prog.defs):
        assign[s] = reduced[k]
        order_hint[s] = ("d", k)
    outputs = [(t, op, reduced[nd + k]) for k, (t, op, _) in enumerate(prog.outputs)]

    # Post-order walk from the outputs: every assignment after its inputs.
    emitted, seq = set(), []

    def visit(s):
        if s in emitted or s not in assign:
            return
        stack = [(s, False)]
        while stack:
            node, done = stack.pop()
            if done:
                if node not in emitted:
                    emitted.add(node)
                    seq.append(node)
                continue
            if node in emitted:
                continue
            stack.append((node, True))
            for dep in reversed(_free(assign[node])):
                if dep in assign and dep not in emitted:
                    stack.append((dep, False))

    for _, _, e in outputs:
        for s in _free(e):
            visit(s)

    hoist = set(hoistable)
    prologue, body = [], []
    for s in seq:
        if all(d in hoist for d in assign[s].free_symbols):
            hoist.add(s)
            prologue.append((s, assign[s]))
        else:
            body.append((s, assign[s]))
    return Lowered(prologue, body, outputs)


# ----------------------------------------------------------------------------
# Operation counting (what the printed C does, per evaluation of the block)

class Ops:
    __slots__ = ("add", "mul", "div", "call")

    def __init__(self, add=0, mul=0, div=0, call=0):
        self.add, self.mul, self.div, self.call = add, mul, div, call

    def __iadd__(self, o):
        self.add += o.add
        self.mul += o.mul
        self.div += o.div
        self.call += o.call
        return self

    def total(self):
        return self.add + self.mul + self.div + self.call

    def __str__(self):
        return f"{self.total()} ({self.add} add, {self.mul} mul, {self.div} div, {self.call} call)"


def _pow_ops(exp):
    """(mul, div, call) for x**exp as printed by CPrinter below."""
    if exp.is_Integer:
        n = int(exp)
        if n > 0:
            return (n - 1, 0, 0)
        return (-n - 1, 1, 0)
    if exp.is_Rational and exp.q in (2, 3):
        n = abs(int(exp.p))
        return (max(n - 1, 0), 1 if exp < 0 else 0, 1)
    return (0, 0, 1)


def count_ops(expr, ops=None, in_add=False):
    ops = ops if ops is not None else Ops()
    if expr.is_Atom:
        return ops
    if expr.is_Add:
        ops.add += len(expr.args) - 1
        for a in expr.args:
            count_ops(a, ops, in_add=True)
        return ops
    if expr.is_Mul:
        coeff, factors = expr.as_coeff_mul()
        nf = len(factors)
        mults = nf - 1
        if coeff not in (1, -1):
            mults += 1
        elif coeff == -1 and not in_add:
            mults += 1          # negation
        for f in factors:
            if f.is_Pow and f.exp.is_Integer and f.exp < 0:
                # a/b**n: the division replaces a multiplication
                m, d, c = _pow_ops(f.exp)
                ops.mul += m
                ops.div += d
                mults -= 1 if nf > 1 or coeff not in (1, -1) else 0
                count_ops(f.base, ops)
            else:
                count_ops(f, ops)
        ops.mul += max(mults, 0)
        return ops
    if expr.is_Pow:
        m, d, c = _pow_ops(expr.exp)
        ops.mul += m
        ops.div += d
        ops.call += c
        count_ops(expr.base, ops)
        return ops
    if isinstance(expr, sp.Function):
        ops.call += 1
        for a in expr.args:
            count_ops(a, ops)
        return ops
    for a in expr.args:
        count_ops(a, ops)
    return ops


def count_lowered(low):
    """(prologue ops, body ops) of a lowered program, output accumulations included."""
    pro, body = Ops(), Ops()
    for _, e in low.prologue:
        count_ops(e, pro)
    for _, e in low.body:
        count_ops(e, body)
    for _, op, e in low.outputs:
        count_ops(e, body)
        if op == "+=":
            body.add += 1
    return pro, body


# ----------------------------------------------------------------------------
# C printing

def c_double(x):
    """Shortest literal that round-trips to the same double."""
    v = float(x)
    s = repr(v)
    if "e" not in s and "." not in s and "inf" not in s and "nan" not in s:
        s += ".0"
    return s


class CPrinter(C99CodePrinter):
    """C99 printer with integer powers as products, rational powers through
    sqrt/cbrt, and every number as a round-tripping double literal."""

    def _print_Rational(self, expr):
        return c_double(expr)

    def _print_Integer(self, expr):
        return c_double(expr)

    def _print_Float(self, expr):
        return c_double(expr)

    def _print_Pow(self, expr):
        base, exp = expr.base, expr.exp
        b = self.parenthesize(base, 50)  # tighter than * (precedence of Mul is 50)
        if exp.is_Integer:
            n = int(exp)
            if n == 0:
                return "1.0"
            prod = "*".join([b] * abs(n))
            if n > 0:
                return prod if abs(n) == 1 else f"({prod})"
            return f"(1.0/{prod})" if abs(n) == 1 else f"(1.0/({prod}))"
        if exp.is_Rational and exp.q in (2, 3):
            n = abs(int(exp.p))
            if exp.q == 2:
                root = f"sqrt({self._print(base)})"
                val = "*".join([root] * n)
            else:
                arg = "*".join([b] * n)
                val = f"cbrt({arg})"
            return f"({val})" if exp > 0 else f"(1.0/({val}))"
        return f"pow({self._print(base)}, {self._print(exp)})"

    def _print_Symbol(self, expr):
        return expr.name

    def _print_Function(self, expr):
        name = getattr(expr.func, "c_name", None)
        if name:
            return f"{name}({', '.join(self._print(a) for a in expr.args)})"
        return super()._print_Function(expr)

    def _print_Mul(self, expr):
        coeff, rest = expr.as_coeff_Mul()
        if coeff < 0:
            inner = self._print_Mul_abs(-coeff, rest)
            return "-" + inner
        return self._print_Mul_abs(coeff, rest)

    def _print_Mul_abs(self, coeff, rest):
        num, den = [], []
        for f in sp.Mul.make_args(rest):
            if f.is_Pow and f.exp.is_Rational and f.exp.is_negative:
                den.append(sp.Pow(f.base, -f.exp, evaluate=False) if f.exp != -1 else f.base)
            elif f != 1:
                num.append(f)
        parts = [] if coeff == 1 else [c_double(coeff)]
        parts += [self.parenthesize(f, 50) for f in num]
        s = "*".join(parts) if parts else "1.0"
        if den:
            d = "*".join(self.parenthesize(f, 50) for f in den)
            s = f"{s}/{d}" if len(den) == 1 and not den[0].is_Pow else f"{s}/({d})"
        return s if (len(parts) + len(den)) <= 1 else f"({s})" if den else s


def print_c(expr):
    return CPrinter().doprint(expr)
