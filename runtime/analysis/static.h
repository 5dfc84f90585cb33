/* static.h -- static equilibrium: load control (static.c) and arc-length
 * continuation (continuation.c).
 *
 * Load control: the load factor goes from 0 to 1 in model->stat.load_steps
 * equal increments.  An increment whose Newton iteration diverges (too many
 * iterations, a non-finite value, a singular matrix, a residual blow-up) is
 * retried from the last converged state with half the increment, at most
 * max_cutbacks times in a row; after an easy increment the step grows back
 * towards its initial size.  Every converged increment is written to the
 * output as it is reached.
 */
#ifndef BK_STATIC_H
#define BK_STATIC_H

#include <stdio.h>

#include "assembly/system.h"
#include "output/output.h"

/* Both solve in place: q holds the reference configuration on entry and the
 * last converged configuration on return.  Return 0 when the full load (the
 * path's end) was reached, 1 otherwise (info->message says where and why). */
int bk_run_static(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log);
int bk_solve_continuation(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log);

/* Load control as another analysis's first stage (modal about a loaded state):
 * no newton.csv, no stability.csv. */
int bk_solve_static(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log);

#endif
