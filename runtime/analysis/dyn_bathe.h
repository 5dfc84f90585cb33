/* dyn_bathe.h -- one step of Bathe's composite scheme (dyn_bathe.c), private
 * to analysis/. */
#ifndef BK_DYN_BATHE_H
#define BK_DYN_BATHE_H

#include "analysis/dynamics_impl.h"

/* The first sub-step's fraction of the step (the scheme holds for any in
 * (0, 1); 2 - sqrt(2), which makes both sub-steps' matrices equal, gave the
 * spinning hub at dt = 0.05 a larger lag, 13.6 mm against 8.3 mm at 1/2). */
#ifndef BK_BATHE_GAMMA
#define BK_BATHE_GAMMA 0.5
#endif

/* The mid state of a step (for the energy balance: its time, the applied and
 * damping powers, kinetic and strain energies) and the constraint scaling the
 * last sub-step left the multipliers in (0: none yet). */
typedef struct bk_dyn_mid {
    double t, P, Pd, T, U;
    double cscale_last;
} bk_dyn_mid;

/* The step from the state saved in dp->w (q_s, qd_s, qdd_s at t) to t + h into
 * dp->q, w->qd, w->qdd, w->nu: a trapezoidal sub-step to t + h/2 (Newton
 * matrix key h), then the three-point backward difference to t + h (key -h);
 * position: both predictors hold the position (else constant acceleration);
 * fresh: full Newton.  Returns the nonlinear solver's code (nonlinear.h),
 * res with the iterations of both sub-steps; on success dp->tn = t + h, and
 * dp->bp, dp->gp, s->cscale those of the second sub-step. */
int bk_dyn_bathe_step(dyn_problem *dp, bk_nl *nl, const bk_nl_opts *nlo, double t, double h, double mbar,
                      int fresh, int position, bk_dyn_mid *mid, bk_nl_result *res);

#endif
