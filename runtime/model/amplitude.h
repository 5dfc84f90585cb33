/* amplitude.h -- the histories loads and prescribed angles are multiplied by
 * (model.h bk_amplitude), as functions of x: the time in dynamics, the load
 * factor in statics (and in the static solve of a modal analysis). */
#ifndef BK_AMPLITUDE_H
#define BK_AMPLITUDE_H

#include "model/model.h"

/* k-th derivative (k = 0, 1, 2) of the amplitude at x.  Steps and the kinks of
 * ramps and tables have zero derivatives (their impulses are not represented). */
double bk_amp_eval(const bk_amplitude *a, double x, int k);

/* The factor of a load with amplitude index amp at x: the amplitude's value,
 * or for amp < 0 the default, x in statics and 1 in dynamics. */
double bk_load_factor(const bk_model *m, int amp, double x);

#endif
