/* arc_step.c -- one step of arc-length continuation: the load derivative of
 * the residual, the bordered Newton correction, the tangent, the bisection of
 * a limit point and the direction of a branch switch (see continuation.h). */
#include "analysis/continuation.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/linsolve.h"

/* dr/dlam at (q, nu, lam) into rl[neq]: the dead loads and the interactions'
 * rate along the path (interaction.h bk_interactions_path_rate: exact for
 * loads proportional to the factor, by central differences for those with
 * amplitudes), and, by central differences in lam, the load-factor
 * dependence of rheonomic constraints. */
void bk_load_derivative(bk_system *s, work *w, const double *q, double lam, double *rl, double *fol,
                            double *tmp)
{
    bk_interactions_path_rate(s, q, lam, w->fext, rl, fol);
    if (s->ncon > 0) {
        double d = 1e-6 * fmax(1.0, fabs(lam));
        memset(tmp, 0, (size_t)s->neq * sizeof *tmp);
        bk_assemble_constraints(s, q, w->nu, lam + d, tmp, NULL);
        for (int j = 0; j < s->neq; ++j)
            rl[j] += tmp[j] / (2.0 * d);
        memset(tmp, 0, (size_t)s->neq * sizeof *tmp);
        bk_assemble_constraints(s, q, w->nu, lam - d, tmp, NULL);
        for (int j = 0; j < s->neq; ++j)
            rl[j] -= tmp[j] / (2.0 * d);
    }
}

int bk_arc_augment(void *ctx, bk_linsolver *ls, double *dx)
{
    arc_ctx *c = ctx;
    bk_system *s = c->sp.s;
    const double *q = c->sp.q, *q0 = c->w->qsave;
    bk_load_derivative(s, c->w, q, c->sp.lam, c->rl, c->fol, c->tmp);
    for (int j = 0; j < s->neq; ++j)
        c->t[j] = -c->rl[j];
    if (bk_lin_solve(ls, c->t) != BK_LIN_OK)
        return -1;
    double dlam = c->sp.lam - c->lam0;
    double A = c->psi2, B = 2.0 * c->psi2 * dlam, C = c->psi2 * dlam * dlam - c->dl * c->dl, D1 = c->psi2 * dlam;
    for (int j = 0; j < s->nfree; ++j) {
        double wj = c->W[j], a = q[c->fdof[j]] - q0[c->fdof[j]], u = a + dx[j], tj = c->t[j];
        A += wj * tj * tj;
        B += 2.0 * wj * u * tj;
        C += wj * u * u;
        D1 += wj * a * tj;
    }
    if (!(A > 0.0))
        return -1;
    double disc = B * B - 4.0 * A * C, r;
    if (disc < 0.0)
        r = -B / (2.0 * A);          /* no root: the closest to the constraint */
    else {
        double sq = sqrt(disc), r1 = (-B + sq) / (2.0 * A), r2 = (-B - sq) / (2.0 * A);
        r = D1 >= 0.0 ? fmax(r1, r2) : fmin(r1, r2);   /* the acute angle with the increment */
    }
    for (int j = 0; j < s->neq; ++j)
        dx[j] += r * c->t[j];
    c->pending = r;
    return 0;
}

void bk_arc_update(void *ctx, const double *dx, double alpha)
{
    arc_ctx *c = ctx;
    bk_sp_update(&c->sp, dx, alpha);
    c->sp.lam += alpha * c->pending;
}

double bk_arc_step_limit(void *ctx, const double *dx)
{
    arc_ctx *c = ctx;
    return bk_sp_step_limit(&c->sp, dx);
}

/* The tangent at the equilibrium (q, w->nu, lam): t = -K^-1 dr/dlam into c->t;
 * its weighted square length into *tWt.  Returns 0, or a BK_NL_* code. */
int bk_arc_tangent(bk_system *s, bk_nl *nl, arc_ctx *c, double *q, double lam, int assembled, double *tWt)
{
    if (!assembled && bk_static_residual(s, c->w, q, c->w->nu, lam, 1) != 0)
        return BK_NL_NONFINITE;
    int st = bk_lin_factor(&nl->ls, nl->Ax);
    if (st != BK_LIN_OK)
        return st == BK_LIN_SINGULAR ? BK_NL_SINGULAR : BK_NL_LINERR;
    bk_load_derivative(s, c->w, q, lam, c->rl, c->fol, c->tmp);
    for (int j = 0; j < s->neq; ++j)
        c->t[j] = -c->rl[j];
    if (bk_lin_solve(&nl->ls, c->t) != BK_LIN_OK)
        return BK_NL_LINERR;
    double ss = 0.0;
    for (int j = 0; j < s->nfree; ++j)
        ss += c->W[j] * c->t[j] * c->t[j];
    if (!isfinite(ss))
        return BK_NL_NONFINITE;
    *tWt = ss;
    return BK_NL_OK;
}

/* One arc step of length dl from the equilibrium in q, w->nu at lam0 along
 * the tangent c->t oriented by sigma: the predictor, then the bordered Newton
 * iteration (a predictor the contact's step limiter cut: load control at its
 * uncut load factor first).  On success q, w->nu, c->sp.lam hold the new equilibrium; on
 * failure the start is restored.  w->qsave, w->nusave: the start. */
int bk_arc_step(bk_system *s, bk_nl *nl, arc_ctx *c, double *q, double lam0, double sigma, double tWt,
                    double dl, const bk_static_opts *o, attempt *a, int step, bk_run_info *info, double lam_scale)
{
    work *w = c->w;
    const bk_model *m = s->m;
    memcpy(w->qsave, q, (size_t)m->ndof * sizeof *q);
    memcpy(w->nusave, w->nu, (size_t)(s->ncon > 0 ? s->ncon : 1) * sizeof *q);
    double dlp = sigma * dl / sqrt(tWt + lam_scale * c->psi2);
    for (int j = 0; j < s->neq; ++j)       /* a predictor that keeps the interactions' states admissible */
        c->tmp[j] = dlp * c->t[j];
    if (bk_interactions_prepare(s, q) != 0)  /* (the broad phase of beam contact where q is) */
        return BK_NL_LINERR;
    const double cut = bk_interactions_step_limit(s, q, c->tmp);   /* (contact: no point through a surface) */
    bk_static_step_to(s, w, q, w->nu, c->t, cut * dlp, q, w->nu);
    c->lam0 = lam0;
    c->dl = dl;
    if (cut < 1.0 && lam_scale > 0.0) {
        /* The contact cut the predictor: the tangent did not see it (a pair
         * just beyond the barrier's reach, or running into it).  The arc's
         * Newton iteration would start from a state whose increment is
         * dominated by the barrier's correction, and its root choice (the
         * acute angle with that increment) then takes the path's other root,
         * backwards.  This step is solved in load control instead, at the
         * uncut predictor's load factor from the cut predictor (the path's
         * direction is that load factor's sign); the arc length goes on from
         * its equilibrium with a tangent that sees the contact.  When that
         * fails, the arc iteration below, as before. */
        const double lt = lam0 + lam_scale * dlp;
        a->id++;
        int lst = bk_static_newton(s, nl, w, q, lt, lam0, a, o, m->length_scale, step, NULL);
        info->newton_iterations += a->iters;
        if (lst == NEWTON_OK) {
            c->sp.lam = lt;
            return BK_NL_OK;
        }
        memcpy(q, w->qsave, (size_t)m->ndof * sizeof *q);
        memcpy(w->nu, w->nusave, (size_t)(s->ncon > 0 ? s->ncon : 1) * sizeof *q);
        bk_static_step_to(s, w, q, w->nu, c->t, cut * dlp, q, w->nu);
    }
    dlp *= cut;
    c->sp.lam = lam0 + lam_scale * dlp;
    c->sp.lam_last = lam0;
    c->pending = 0.0;
    bk_nl_problem p = {.ctx = c, .q = q, .residual = bk_sp_residual, .augment = bk_arc_augment, .update = bk_arc_update,
                       .step_limit = bk_arc_step_limit};
    /* bk_sp_residual reads the static_problem at the start of the context */
    bk_nl_opts no = bk_static_nl_opts(o);
    a->id++;
    bk_nl_row row = {.attempt = a->id, .step = step, .lam = lam0 + dlp};
    bk_nl_result res;
    int st = bk_nl_solve(nl, &p, &no, 0.0, 1, &row, &res);
    info->newton_iterations += res.iters;
    a->iters = res.iters, a->rnorm = res.rnorm, a->dnorm = res.dnorm, a->ref = res.ref;
    a->rtol_abs = res.rtol_abs, a->rcond = res.rcond, a->residual_met = res.residual_met;
    a->singular_at_start = res.singular_at_start, a->signo = res.signo;
    if (st != BK_NL_OK) {
        memcpy(q, w->qsave, (size_t)m->ndof * sizeof *q);
        memcpy(w->nu, w->nusave, (size_t)(s->ncon > 0 ? s->ncon : 1) * sizeof *q);
    }
    return st;
}

/* Displacements of the first sensors at q into cp. */
void bk_sensor_displacements(const bk_model *m, const double *q, bk_critical_point *cp)
{
    cp->nsensor = m->nsensor < BK_CRIT_SENSORS ? m->nsensor : BK_CRIT_SENSORS;
    for (int k = 0; k < cp->nsensor; ++k) {
        double p[3], p0[3];
        bk_eval_sensor(m, q, &m->sensors[k], p, NULL);
        bk_eval_sensor(m, m->q0, &m->sensors[k], p0, NULL);
        for (int i = 0; i < 3; ++i)
            cp->u[k][i] = p[i] - p0[i];
    }
}

double bk_max_sensor_displacement(const bk_model *m, const double *q)
{
    bk_critical_point cp;
    double d = 0.0;
    bk_sensor_displacements(m, q, &cp);
    for (int k = 0; k < cp.nsensor; ++k)
        d = fmax(d, sqrt(cp.u[k][0] * cp.u[k][0] + cp.u[k][1] * cp.u[k][1] + cp.u[k][2] * cp.u[k][2]));
    return d;
}


void bk_arc_save(const bk_system *s, const work *w, const double *q, double lam, arc_point *p)
{
    memcpy(p->q, q, (size_t)s->m->ndof * sizeof *q);
    memcpy(p->nu, w->nu, (size_t)(s->ncon > 0 ? s->ncon : 1) * sizeof *q);
    p->lam = lam;
}

void bk_arc_restore(const bk_system *s, work *w, double *q, double *lam, const arc_point *p)
{
    memcpy(q, p->q, (size_t)s->m->ndof * sizeof *q);
    memcpy(w->nu, p->nu, (size_t)(s->ncon > 0 ? s->ncon : 1) * sizeof *q);
    *lam = p->lam;
}

/* Orientation of the tangent c->t at the equilibrium q (lam) along the path
 * coming from (q_from, lam_from): +1 when the load factor grows along it. */
double bk_arc_orientation(const bk_system *s, const arc_ctx *c, const double *q, double lam,
                              const double *q_from, double lam_from)
{
    double d = c->psi2 * (lam - lam_from);
    for (int j = 0; j < s->nfree; ++j)
        d += c->W[j] * (q[c->fdof[j]] - q_from[c->fdof[j]]) * c->t[j];
    return d >= 0.0 ? 1.0 : -1.0;
}

/* Bisection on the arc length from the equilibrium A (orientation sigma_a,
 * the load factor growing when sigma_a > 0) for the limit point within the
 * number of bisection solves in *nsolve. */
double bk_arc_bisect_limit(bk_system *s, bk_nl *nl, arc_ctx *c, double *q, const arc_point *A,
                               double sigma_a, double dl, const bk_static_opts *o, attempt *a, int step,
                               bk_run_info *info, arc_point *best, double lam_b)
{
    double lo = 0.0, hi = dl, lam_best = sigma_a > 0.0 ? fmax(A->lam, lam_b) : fmin(A->lam, lam_b);
    int have_best = 0;
    for (int k = 0; k < ARC_BISECTIONS; ++k) {
        double mid = 0.5 * (lo + hi), lam = A->lam, tWt;
        bk_arc_restore(s, c->w, q, &lam, A);
        if (bk_arc_tangent(s, nl, c, q, lam, 0, &tWt) != BK_NL_OK)
            break;
        if (bk_arc_step(s, nl, c, q, lam, sigma_a, tWt, mid, o, a, step, info, 1.0) != BK_NL_OK)
            break;
        double lam_m = c->sp.lam;
        if (sigma_a > 0.0 ? lam_m >= lam_best : lam_m <= lam_best) {
            lam_best = lam_m;
            bk_arc_save(s, c->w, q, lam_m, best);
            have_best = 1;
        }
        if (bk_arc_tangent(s, nl, c, q, lam_m, 0, &tWt) != BK_NL_OK)
            break;
        double sg = bk_arc_orientation(s, c, q, lam_m, A->q, A->lam);
        if (sg == sigma_a)
            lo = mid;
        else
            hi = mid;
    }
    if (!have_best)
        best->lam = NAN;
    return lam_best;
}

/* The direction of a branch switch into c->t: the eigenvector of the
 * smallest-magnitude eigenvalue of the last stability check (the null vector
 * at the bifurcation), its free part, the sign of its largest weighted
 * component positive; its weighted square length into *tWt. */
void bk_branch_direction(const bk_system *s, const bk_stability *st, arc_ctx *c, double *tWt)
{
    double ss = 0.0, big = 0.0;
    for (int j = 0; j < s->neq; ++j) {
        c->t[j] = j < s->nfree ? st->x[j] : 0.0;
        ss += c->W[j] * c->t[j] * c->t[j];
        if (sqrt(c->W[j]) * fabs(c->t[j]) > fabs(big))
            big = sqrt(c->W[j]) * c->t[j];
    }
    if (big < 0.0)
        for (int j = 0; j < s->nfree; ++j)
            c->t[j] = -c->t[j];
    *tWt = ss;
}

