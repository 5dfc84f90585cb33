"""Generated load kernels shared by all continuum elements.

bk_section_moment: a moment vector M (fixed in space) applied to a cross-section
through its slope vectors r_y, r_z.  With e1 = r_y/|r_y|, e2 = r_z/|r_z| and the
section normal t = e1 x e2 / |e1 x e2|, the virtual rotation of a rigidly
rotating section is
    dtheta = t (e2 . de1 - e1 . de2)/2 + e1 (t . de2) - e2 (t . de1),
so M . dtheta = Q_ry . dr_y + Q_rz . dr_z with
    Q_ry = (M_t e2 / 2 - M_2 t) / |r_y|,   Q_rz = (-M_t e1 / 2 + M_1 t) / |r_z|,
M_t = M . t, M_1 = M . e1, M_2 = M . e2.  For a deformed section this is the
couple a rigid rotation of its frame would feel.  The kernel also gives the
6 x 6 Jacobian d(Q_ry, Q_rz)/d(r_y, r_z) (the load stiffness, not symmetric).
"""
import sympy as sp

from gen.emit import BANNER, _block, _prologue, input_hash
from gen.program import Program, count_lowered, lower

FILES = ("loads.py", "program.py", "emit.py")


def section_moment_program():
    ry = sp.Matrix([sp.Symbol(f"ry[{i}]", real=True) for i in range(3)])
    rz = sp.Matrix([sp.Symbol(f"rz[{i}]", real=True) for i in range(3)])
    M = sp.Matrix([sp.Symbol(f"M[{i}]", real=True) for i in range(3)])
    ny, nz = sp.sqrt(ry.dot(ry)), sp.sqrt(rz.dot(rz))
    e1, e2 = ry / ny, rz / nz
    c = e1.cross(e2)
    t = c / sp.sqrt(c.dot(c))
    Mt, M1, M2 = M.dot(t), M.dot(e1), M.dot(e2)
    Qy = (Mt * e2 / 2 - M2 * t) / ny
    Qz = (-Mt * e1 / 2 + M1 * t) / nz
    Q = list(Qy) + list(Qz)
    r = list(ry) + list(rz)
    prog = Program()
    for i in range(6):
        prog.output(f"Q[{i}]", Q[i], op="=")
    for i in range(6):
        for j in range(6):
            prog.output(f"dQ[{6 * i + j}]", sp.diff(Q[i], r[j]), op="=")
    return prog


def loads_source():
    from pathlib import Path
    here = Path(__file__).resolve().parent
    h = input_hash([here / f for f in FILES])
    low = lower(section_moment_program(), ())
    _, ops = count_lowered(low)
    doc = __doc__.strip().splitlines()
    hdr = [f"/* {BANNER}", " * generator: gen/loads.py", f" * input hash: sha256:{h}", " *"]
    hdr += [" * " + l if l else " *" for l in doc]
    hdr += [f" * Operations: {ops}", " */"]
    htxt = "\n".join(hdr) + """
#ifndef BK_GEN_LOADS_H
#define BK_GEN_LOADS_H

/* ry[3], rz[3]: section slope vectors; M[3]: moment (N m).
 * Q[6] = (Q_ry, Q_rz) (N m per unit slope); dQ[36] row-major d(Q)/d(ry, rz). */
void bk_section_moment(const double *restrict ry, const double *restrict rz,
                       const double *restrict M, double *restrict Q, double *restrict dQ);

#endif
"""
    c = [f"/* {BANNER} (see loads.h) */", '#include "loads.h"', "#include <math.h>", "",
         "void bk_section_moment(const double *restrict ry, const double *restrict rz,",
         "                       const double *restrict M, double *restrict Q, double *restrict dQ)",
         "{"]
    c += _prologue(low, "    ") + _block(low, "    ") + ["}", ""]
    return htxt, "\n".join(c), h
