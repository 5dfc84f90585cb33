/* step_control.c -- the time-step controller with memory (step_control.h). */
#include "solver/step_control.h"

#include <math.h>

void bk_step_ctl_init(bk_step_ctl *c, double h_max)
{
    c->h_max = h_max;
    c->h_fail = INFINITY;
    c->calm = 0;
    c->hold = 0;
    c->failures = 0;
}

double bk_step_ctl_failed(bk_step_ctl *c, double h)
{
    /* a failure while the last one is still remembered, or soon after: the
     * regrowth came too soon (a second cut in the same step keeps the hold) */
    if (c->calm == 0 && isfinite(c->h_fail))
        ;
    else if (isfinite(c->h_fail) || (c->hold > 0 && c->calm < 4 * c->hold))
        c->hold = c->hold > 0 ? (2 * c->hold < BK_STEP_HOLD_MAX ? 2 * c->hold : BK_STEP_HOLD_MAX) : BK_STEP_HOLD0;
    else
        c->hold = BK_STEP_HOLD0;
    c->h_fail = isfinite(c->h_fail) ? fmin(c->h_fail, h) : h;
    c->calm = 0;
    c->failures++;
    return 0.5 * h;
}

double bk_step_ctl_accepted(bk_step_ctl *c, double h, int iters, double err_ratio)
{
    c->calm++;
    if (isfinite(c->h_fail) && c->calm >= 2 * c->hold)
        c->h_fail = INFINITY;                    /* the memory is dropped: dt may be tried again */
    double f = 2.0;
    if (err_ratio > 0.0)
        f = fmin(2.0, fmax(0.2, 0.9 * cbrt(1.0 / err_ratio)));
    if (f > 1.0 && (c->calm < c->hold || iters > BK_STEP_TARGET_ITERS))
        f = 1.0;                                 /* no growth right after a failure, nor on a slow Newton */
    double hn = h * f;
    if (isfinite(c->h_fail) && hn > h) {
        /* adaptive: up to 0.9 of the size that failed; fixed: doubling only, and
         * not back to the size that failed (the steps stay dt / 2^k) */
        if (err_ratio > 0.0)
            hn = fmax(h, fmin(hn, 0.9 * c->h_fail));
        else if (hn >= c->h_fail * (1.0 - 1e-12))
            hn = h;
    }
    return fmin(hn, c->h_max);
}

double bk_step_ctl_error_reject(const bk_step_ctl *c, double h, double err_ratio)
{
    (void)c;
    return h * fmax(0.2, fmin(0.9, 0.9 * cbrt(1.0 / err_ratio)));
}
