/* dyn_bathe.c -- one step of Bathe's composite scheme (dynamic.integrator =
 * "bathe"; Bathe and Baig 2005, Bathe 2007): of length h from t_n, in two
 * sub-steps whose equations of motion hold exactly at their ends, as in the
 * generalized-alpha steps (the same residual, dyn_residual.c):
 *   1. the trapezoidal rule over g h to t_m = t_n + g h (Newmark beta = 1/4,
 *      gamma = 1/2: q' and q'' of the mid state linear in its q, with
 *      dq'/dq = 2/(g h) and dq''/dq = 4/(g h)^2);
 *   2. the three-point backward difference over the whole step,
 *      q'_{n+1}  = c1 q_n  + c2 q_m  + c3 q_{n+1},
 *      q''_{n+1} = c1 q'_n + c2 q'_m + c3 q'_{n+1},
 *      c1 = (1 - g)/(g h), c2 = -1/((1 - g) g h), c3 = (2 - g)/((1 - g) h)
 *      (g = 1/2: 1/h, -4/h, 3/h; dq'/dq = c3, dq''/dq = c3^2).
 * Second order, unconditionally stable for linear systems, and dissipating the
 * modes far above 1/h completely (spectral radius 0 at infinity) while those
 * resolved by the step keep their energy to O(h^3) per period: the sub-step
 * with the backward difference takes out the energy the trapezoidal rule
 * lets a nonlinear system (large rotations) build up in its unresolved modes.
 * The constraint rows are scaled by each sub-step's dq''/dq times the mean
 * mass as in dynamics.c, the multipliers carried across by the ratio. */
#include "analysis/dyn_bathe.h"

#include <string.h>

#include "assembly/system.h"

int bk_dyn_bathe_step(dyn_problem *dp, bk_nl *nl, const bk_nl_opts *nlo, double t, double h, double mbar,
                      int fresh, int position, bk_dyn_mid *mid, bk_nl_result *res)
{
    bk_system *s = dp->s;
    dyn_work *w = dp->w;
    double *q = dp->q;
    const int nd = s->m->ndof;
    const double g = BK_BATHE_GAMMA, h1 = g * h;
    bk_nl_problem prob = {.ctx = dp, .q = q, .residual = bk_dyn_problem_residual, .update = bk_dyn_problem_update,
                          .step_limit = bk_dyn_problem_step_limit};
    /* 1: trapezoidal to t + h/2 */
    const double bp1 = 4.0 / (h1 * h1), gp1 = 2.0 / h1;
    for (int c = 0; c < w->nc; ++c)       /* the multipliers were scaled by the last sub-step's c3^2 */
        w->nu[c] *= mid->cscale_last > 0.0 ? mid->cscale_last / (bp1 * mbar) : 1.0;
    s->cscale = bp1 * mbar;
    bk_dyn_predict(s, w, q, h1, 0.0, 0.0, 0.25, 0.5, position);
    dp->tn = t + h1, dp->bp = bp1, dp->gp = gp1;
    bk_nl_result r1;
    int st = bk_nl_solve(nl, &prob, nlo, h, fresh, NULL, &r1);
    if (st != BK_NL_OK) {
        *res = r1;
        return st;
    }
    /* the mid state's powers (the last residual was at the converged state) */
    mid->t = t + h1;
    mid->P = bk_dyn_dot_free(s, dp->fdof, w->fext, bk_dyn_power_velocity(s, w, q, mid->t)) - w->p_inter - w->p_con;
    mid->Pd = w->p_damp;
    mid->T = bk_dyn_kinetic(s, w, dp->fdof, q, mid->t);
    mid->U = bk_strain_energy(s, q);
    memcpy(w->q_m, q, (size_t)nd * sizeof *q);
    memcpy(w->qd_m, w->qd, (size_t)nd * sizeof *q);
    /* 2: the three-point backward difference to t + h, from the constant
     * acceleration of the mid state (or its position held) */
    const double c1 = (1.0 - g) / (g * h), c2 = -1.0 / ((1.0 - g) * g * h), c3 = (2.0 - g) / ((1.0 - g) * h);
    for (int i = 0; i < nd; ++i) {
        if (s->eq[i] < 0)
            continue;
        if (!position)
            q[i] = w->q_m[i] + h1 * w->qd_m[i] + 0.5 * h1 * h1 * w->qdd[i];
        w->qd[i] = c1 * w->q_s[i] + c2 * w->q_m[i] + c3 * q[i];
        w->qdd[i] = c1 * w->qd_s[i] + c2 * w->qd_m[i] + c3 * w->qd[i];
    }
    const double bp2 = c3 * c3, gp2 = c3;
    for (int c = 0; c < w->nc; ++c)
        w->nu[c] *= bp1 / bp2;
    s->cscale = bp2 * mbar;
    mid->cscale_last = s->cscale;
    dp->tn = t + h, dp->bp = bp2, dp->gp = gp2;
    st = bk_nl_solve(nl, &prob, nlo, -h, fresh, NULL, res);
    res->iters += r1.iters;
    res->reused |= r1.reused;
    return st;
}
