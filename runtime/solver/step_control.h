/* step_control.h -- the time-step controller with memory of the dynamic analysis.
 *
 * A step that failed (Newton, an inadmissible state) is halved, and the size that
 * failed is remembered: for the next `hold` accepted steps the step does not grow
 * at all, and until `2 hold` accepted steps it grows at most to 0.9 of the size
 * that failed (with dynamic.tol = 0, by doublings that stay below it: the steps
 * remain dt / 2^k); then the memory is dropped and the step may return to dt.  A new
 * failure within that time (the regrowth came too soon) doubles `hold` (8, 16,
 * ... up to BK_STEP_HOLD_MAX accepted steps), so that a transient that cannot be
 * passed at dt (a stiff mode excited by a sudden load, a fast spin) is crossed
 * at a step that works instead of being halved again and again.  Growth is by at
 * most 2 a step, and only when the last Newton solve took at most
 * BK_STEP_TARGET_ITERS iterations and (with dynamic.tol > 0) the local error
 * allows it; with dynamic.tol > 0 the error estimate also shrinks the step.
 * Never above dt (`h_max`).
 */
#ifndef BK_STEP_CONTROL_H
#define BK_STEP_CONTROL_H

#define BK_STEP_HOLD0 8
#define BK_STEP_HOLD_MAX 1024
#define BK_STEP_TARGET_ITERS 6

typedef struct bk_step_ctl {
    double h_max;     /* dt: the step never exceeds it                               */
    double h_fail;    /* the size that failed last (remembered while calm < 2 hold)  */
    int calm;         /* accepted steps since the last failure                        */
    int hold;         /* accepted steps without growth after a failure               */
    int failures;     /* failures counted by the controller (statistics)             */
} bk_step_ctl;

void bk_step_ctl_init(bk_step_ctl *c, double h_max);
/* A step of size h failed: the size to retry with (h / 2). */
double bk_step_ctl_failed(bk_step_ctl *c, double h);
/* A step of size h was accepted after `iters` Newton iterations; err_ratio is
 * the local error over its tolerance (0 when the step is fixed, dynamic.tol =
 * 0): the size of the next step. */
double bk_step_ctl_accepted(bk_step_ctl *c, double h, int iters, double err_ratio);
/* A step of size h rejected by the local error estimate alone (err_ratio > 1):
 * the size to retry with (not a failure: no memory). */
double bk_step_ctl_error_reject(const bk_step_ctl *c, double h, double err_ratio);

#endif
