/* buckling.h -- linear (eigen)buckling: critical load factors and mode shapes
 * of the scene's loads (scene.analysis = "buckling"; see buckling.c). */
#ifndef BK_BUCKLING_H
#define BK_BUCKLING_H

#include <stdio.h>

#include "assembly/system.h"
#include "output/output.h"

/* Writes the base state (the reference as step 0, or the static load steps to
 * the preloaded equilibrium) to sensors.csv and step_*.vtu, and each buckling
 * mode to modes.csv (mode, load factor, display scale), mode_sensors.csv and
 * mode_NN.vtu (bk_output_mode).  q holds the base state on return.  Returns 0
 * on success, else 1 with info->message. */
int bk_solve_buckling(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log);

#endif
