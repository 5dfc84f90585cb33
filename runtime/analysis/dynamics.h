/* dynamics.h -- time integration with generalized-alpha for index-3 systems
 * (see dynamics.c for the scheme, scaling and step control). */
#ifndef BK_DYNAMICS_H
#define BK_DYNAMICS_H

#include <stdio.h>

#include "output/output.h"
#include "assembly/system.h"

/* Integrates from the model's reference state and initial velocities to
 * dynamic.t_end.  q holds the last accepted configuration on return.  Returns
 * 0 when t_end was reached, 1 otherwise (info->message says where and why). */
int bk_solve_dynamic(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log);

#endif
