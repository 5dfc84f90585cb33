/* newton.h -- static equilibrium by Newton's method with load stepping.
 *
 * The load factor goes from 0 to 1 in model->stat.load_steps equal increments.
 * An increment whose Newton iteration diverges (too many iterations, a
 * non-finite value, a singular matrix, a residual blow-up) is retried from the
 * last converged state with half the increment, at most max_cutbacks times in a
 * row; after an easy increment the step grows back towards its initial size.
 * Every converged increment is written to the output as it is reached.
 */
#ifndef BK_NEWTON_H
#define BK_NEWTON_H

#include <stdio.h>

#include "output/output.h"
#include "assembly/system.h"

/* Solves in place: q holds the reference configuration on entry and the last
 * converged configuration on return.  Returns 0 when the full load was
 * reached, 1 otherwise (info->message says where and why). */
int bk_solve_static(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log);

#endif
