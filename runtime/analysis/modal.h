/* modal.h -- natural frequencies and mode shapes (see modal.c). */
#ifndef BK_MODAL_H
#define BK_MODAL_H

#include <stdio.h>

#include "output/output.h"
#include "assembly/system.h"

/* Writes modes.csv and one sensors.csv row per mode (step = mode number,
 * time = frequency in Hz, the configuration displaced along the mode).  q
 * holds the linearization state on return.  Returns 0 on success. */
int bk_solve_modal(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log);

#endif
