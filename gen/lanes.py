"""The loops of the lane kernels (runtime/bk_kernel.h, "Lane kernels"): BK_LANES
elements per call, every array in structure-of-arrays order, entry k of lane l at
[k * BK_LANES + l].  The body of the one-element kernel is printed inside
`#pragma omp simd` over the lanes, so that the compiler vectorizes across
elements."""
import re

from gen import contract
from gen.c_functions import _block, _prologue
from gen.continuum import A_INDEX

_LANE_ARRAYS = re.compile(r"\b(q|qd|t|mat|visc|f|K|A|Ask)\[(\d+)\]")


def lanes():
    return contract.lanes()


def _lane(line):
    w = lanes()
    return _LANE_ARRAYS.sub(lambda m: f"{m.group(1)}[{int(m.group(2)) * w} + l]", line)


# libm functions the lane kernels may call, with their arity: glibc's libmvec has
# vector variants of them (x86-64), which `declare simd` lets the compiler use.
_VECTOR_MATH = {"log": 1, "exp": 1, "cbrt": 1, "pow": 2}


def _vector_math_decls(lines):
    """Declarations that make the libm calls in `lines` vectorizable (libmvec);
    sqrt needs none (an instruction, with -fno-math-errno)."""
    used = sorted({m.group(1) for x in lines for m in re.finditer(r"\b(\w+)\(", x)} & set(_VECTOR_MATH))
    if not used:
        return []
    out = ["", "/* Vector variants (glibc libmvec) of the libm functions the lane kernels call. */",
           "#if defined(__GLIBC__) && defined(__x86_64__)"]
    for fn in used:
        out += ["#pragma omp declare simd notinbranch",
                f"double {fn}({', '.join(['double'] * _VECTOR_MATH[fn])});"]
    return out + ["#endif"]


def _lane_loop(lines, indent):
    """Lines of one element's straight-line code as a loop over the lanes."""
    return ([f"{indent}#pragma omp simd", f"{indent}for (int l = 0; l < {lanes()}; ++l) {{"] +
            [_lane(x) for x in lines] + [f"{indent}}}"])


def _lane_kernel_fn(signature, ndof, parts, lows, contract_fn=None):
    """One lane kernel: per quadrature point the one-element body in a loop over
    the lanes (the prologue inside it: the parameters are per lane), then the
    tangent contraction over the lanes."""
    w = lanes()
    lines = ["BK_LANE_TARGET " + signature, "{", f"    for (int i = 0; i < {ndof * w}; ++i) f[i] = 0.0;"]
    if contract_fn:
        lines += [f"    for (int r = 0; r < {ndof}; ++r)",
                  f"        for (int i = r * {ndof + 1} * {w}; i < (r + 1) * {ndof} * {w}; ++i) K[i] = 0.0;"]
    for part, low in zip(parts, lows):
        lines.append(f"    {{   /* energy part \"{part.energy}\": {len(part.rule)} quadrature points */")
        lines.append(f"        for (int p = 0; p < {len(part.rule)}; ++p) {{")
        lines.append(f"            const double *restrict t = tab + ({part.tab_offset} + {part.stride} * p) * {w};")
        if contract_fn:
            lines.append(f"            double A[{len(A_INDEX) * w}];")
        lines += _lane_loop(_prologue(low, "                ") + _block(low, "                "), "            ")
        if contract_fn:
            lines.append(f"            {contract_fn}(A, t, K);")
        lines += ["        }", "    }"]
    if contract_fn:
        lines += [f"    for (int r = 1; r < {ndof}; ++r)",
                  "        for (int c = 0; c < r; ++c)",
                  f"            for (int l = 0; l < {w}; ++l) K[(r * {ndof} + c) * {w} + l] = K[(c * {ndof} + r) * {w} + l];"]
    lines += ["}", ""]
    return lines
