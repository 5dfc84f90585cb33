"""C text of lowered programs (gen/program.py): the statements of a program's
prologue and body, a C function around them, and a section_frame() function
(runtime/bk_kernel.h) from its two programs; every emitter prints through these."""
from gen.program import print_c


def _block(low, indent):
    out = []
    for s, e in low.body:
        out.append(f"{indent}const double {s.name} = {print_c(e)};")
    for target, op, e in low.outputs:
        out.append(f"{indent}{target} {op} {print_c(e)};")
    return out


def _prologue(low, indent):
    return [f"{indent}const double {s.name} = {print_c(e)};" for s, e in low.prologue]


def _function(sig, low, pre=()):
    return [sig, "{"] + [f"    {x}" for x in pre] + _prologue(low, "    ") + _block(low, "    ") + ["}", ""]


SECTION_FRAME_SIG = ("static void section_frame(const double *restrict geom, double xi, const double *restrict q, "
                     "double *restrict R, double *restrict dR)")


def section_frame_function(r_low, j_low, sig=SECTION_FRAME_SIG, pre=("(void)geom; (void)xi;",)):
    """C lines of a section_frame() (runtime/bk_kernel.h): R only when dR is NULL,
    else R and dR, from the two lowered programs."""
    out = [sig, "{"] + [f"    {x}" for x in pre] + ["    if (!dR) {"]
    out += _prologue(r_low, "        ") + _block(r_low, "        ") + ["        return;", "    }"]
    return out + _prologue(j_low, "    ") + _block(j_low, "    ") + ["}", ""]
