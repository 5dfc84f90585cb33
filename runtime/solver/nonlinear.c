/* nonlinear.c -- the one Newton solver of every analysis (see nonlinear.h). */
#include "solver/nonlinear.h"
#include "base/bigalloc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/interrupt.h"

const char *bk_nl_why(int code)
{
    switch (code) {
    case BK_NL_MAXIT: return "no convergence within the iteration limit";
    case BK_NL_NONFINITE: return "non-finite internal force or increment";
    case BK_NL_SINGULAR: return "singular Newton matrix";
    case BK_NL_DIVERGED: return "residual grew without bound";
    case BK_NL_LINERR: return "linear solver error";
    case BK_NL_INTERRUPTED: return "interrupted";
    default: return "converged";
    }
}

int bk_nl_init(bk_nl *nl, bk_system *s, char *msg, size_t nmsg)
{
    memset(nl, 0, sizeof *nl);
    nl->s = s;
    nl->t_poll = -INFINITY;                        /* the first iteration polls */
    size_t ne = (size_t)(s->neq > 0 ? s->neq : 1), nnz = (size_t)(s->nnz > 0 ? s->nnz : 1);
    nl->r = calloc(ne, sizeof(double));
    nl->dx = calloc(ne, sizeof(double));
    nl->Ax = bk_big_calloc(nnz, sizeof(double));
    if (!nl->r || !nl->dx || !nl->Ax || bk_norms_init(&nl->norms, s) != 0) {
        snprintf(msg, nmsg, "out of memory");
        return -1;
    }
    if (s->neq > 0 && bk_lin_init(&nl->ls, s->neq, s->Ap, s->Ai) != BK_LIN_OK) {
        snprintf(msg, nmsg, "linear-solver set-up (ordering, band plan or KLU analysis) failed");
        return -1;
    }
    nl->pattern_gen = s->pattern_gen;
    return 0;
}

/* The interactions' prepare at q, and, when the pattern grew, the matrix
 * values and the linear solver's plan for the new one (no factors kept).
 * 0, or -1 when out of memory or the plan failed. */
static int prepare(bk_nl *nl, const double *q)
{
    bk_system *s = nl->s;
    if (bk_interactions_prepare(s, q) != 0)
        return -1;
    if (nl->pattern_gen == s->pattern_gen)
        return 0;
    double *Ax = bk_big_realloc(nl->Ax, (size_t)(s->nnz > 0 ? s->nnz : 1) * sizeof *Ax);
    if (!Ax)
        return -1;
    nl->Ax = Ax;
    memset(Ax, 0, (size_t)(s->nnz > 0 ? s->nnz : 1) * sizeof *Ax);
    bk_lin_free(&nl->ls);
    nl->have_factors = 0;
    nl->pattern_gen = s->pattern_gen;
    return bk_lin_init(&nl->ls, s->neq, s->Ap, s->Ai) == BK_LIN_OK ? 0 : -1;
}

void bk_nl_free(bk_nl *nl)
{
    bk_lin_free(&nl->ls);
    bk_norms_free(&nl->norms);
    free(nl->r);
    free(nl->dx);
    free(nl->Ax);
    nl->r = nl->dx = nl->Ax = NULL;
}

int bk_nl_solve(bk_nl *nl, const bk_nl_problem *p, const bk_nl_opts *o, double key, int fresh_all,
                const bk_nl_row *row, bk_nl_result *res)
{
    bk_system *s = nl->s;
    const int neq = s->neq;
    double *r = nl->r, *dx = nl->dx, *Ax = nl->Ax;
    double dnorm = INFINITY, enorm = INFINITY, eref = 0.0, alpha = 1.0;
    double r0 = -1.0, rprev = INFINITY;          /* divergence and stagnation (tested rows) */
    double rall = 0.0, rprev_all = INFINITY;     /* contraction rate of kept factors (every row) */
    double dnorm_prev = INFINITY, enorm_prev = INFINITY;
    int eref_it = -1;                            /* the correction whose energy is eref */
    int prev_reused = 0;                         /* the last correction was made with kept factors */
    int it, code = BK_NL_MAXIT;
    bk_nl_eval ev = {0};
    memset(res, 0, sizeof *res);
    res->rcond = NAN;
    res->dnorm = INFINITY;
    for (it = 0;; ++it) {
        const double now = bk_clock_s();           /* (a clock read costs ~25 ns; the poll, a system call) */
        if (now - nl->t_poll >= BK_INTERRUPT_POLL_S) {
            nl->t_poll = now;
            if ((res->signo = bk_interrupt_poll()) != 0) {
                code = BK_NL_INTERRUPTED;
                break;
            }
        }
        if (prepare(nl, p->q) != 0) {
            code = BK_NL_LINERR;
            break;
        }
        Ax = nl->Ax;
        const int want = !o->reuse || fresh_all || !nl->have_factors || nl->factors_key != key ||
                         nl->krate > BK_REUSE_MAX_RATE;
        int fresh = want && !(o->lazy_matrix && it > 0);
        int rs = p->residual(p->ctx, fresh, r, Ax, &ev);
        rall = rs == 0 ? bk_norm2(r, neq) : INFINITY;
        if (prev_reused && rs == 0)
            nl->krate = rall / rprev_all;        /* contraction rate of the last kept-factor correction */
        if (prev_reused && (rs != 0 || rall > BK_REUSE_DIVERGED * rprev_all)) {
            /* a kept-factor correction that led to a non-finite force or
             * diverged is taken back and this iteration redone from the
             * previous point with a new matrix */
            p->update(p->ctx, dx, -alpha);
            dnorm = dnorm_prev, enorm = enorm_prev;
            if (eref_it == it - 1)
                eref_it = -1;                    /* the energy scale came from the undone one */
            nl->krate = INFINITY;
            fresh = 1;
            rs = p->residual(p->ctx, 1, r, Ax, &ev);
            rall = rs == 0 ? bk_norm2(r, neq) : INFINITY;
        }
        if (rs != 0) {
            code = BK_NL_NONFINITE;
            break;
        }
        double rnorm = ev.rnorm;
        /* rotation-invariant floors (norms.h), from the last assembled matrix */
        if (fresh)
            nl->fl = bk_round_off_floors(&nl->norms, s, p->q, Ax);
        const bk_floors fl = nl->fl;
        res->rnorm = rnorm;
        res->dnorm = dnorm;
        res->ref = ev.ref;
        res->iters = it;
        if (row && nl->on_iteration)
            nl->on_iteration(nl->iteration_ctx, row, it, rnorm, ev.ref, it ? dnorm : NAN, it ? alpha : NAN,
                             nl->ls.rcond);
        if (!isfinite(rnorm)) {
            code = BK_NL_NONFINITE;
            break;
        }
        int con_ok = o->ctol <= 0.0 || ev.cres <= o->ctol;
        if (rnorm == 0.0 && con_ok) {
            code = BK_NL_OK;
            break;
        }
        double rtol_abs = fmax(o->rtol * ev.ref, fl.force), utol_abs = fmax(o->utol * ev.uscale, fl.increment);
        res->rtol_abs = rtol_abs, res->utol_abs = utol_abs;
        if (rnorm <= rtol_abs)
            res->residual_met = 1;
        /* converged: residual (and constraints) within tolerance, and the last
         * correction small in length or in energy (BK_ENERGY_TOL), or the
         * residual far below its tolerance; the energy scale is the first
         * correction or the provider's, whichever is larger (a good predictor
         * must not make the test stricter) */
        double escale = fmax(eref, ev.escale);
        if (it > 0 && con_ok && rnorm <= rtol_abs &&
            (dnorm <= utol_abs || (o->accept_far_below && rnorm <= 1e-3 * rtol_abs) ||
             enorm <= fmax(BK_ENERGY_TOL * escale, fl.energy))) {
            code = BK_NL_OK;
            break;
        }
        /* Stagnation at round-off: on ill-conditioned matrices (slender
         * higher-order elements) the residual stops decreasing a little above
         * its floor while the increments are already at noise level; accept
         * within a factor 1e3 (residual) and 1e2 (increment) of the
         * tolerances once an iteration no longer halves the residual. */
        if (o->stagnation && it > 1 && rnorm > 0.5 * rprev && rnorm <= 1e3 * rtol_abs && dnorm <= 1e2 * utol_abs) {
            code = BK_NL_OK;
            break;
        }
        rprev = rnorm;
        if (o->divergence) {
            if (r0 < 0.0)
                r0 = fmax(rnorm, 1e-300);
            else if (rnorm > 1e12 * r0) {
                code = BK_NL_DIVERGED;
                break;
            }
        }
        if (it >= o->max_iter) {
            code = BK_NL_MAXIT;
            break;
        }
        /* kept factors must reach the tolerance within BK_REUSE_ITERATIONS
         * more corrections at their last measured rate, else this iteration
         * takes a new matrix (the residual is the same, only the matrix is
         * added); so does a lazy iteration that wanted one */
        double kp = nl->krate > 0.0 ? pow(nl->krate, BK_REUSE_ITERATIONS) : 0.0;
        if (!fresh && (want || (kp > 0.0 && (rnorm * kp > rtol_abs || (o->ctol > 0.0 && ev.cres * kp > o->ctol))))) {
            fresh = 1;
            bk_nl_eval ev2;
            if (p->residual(p->ctx, 1, r, Ax, &ev2) != 0) {
                code = BK_NL_NONFINITE;
                break;
            }
            res->rnorm = ev2.rnorm;
            nl->fl = bk_round_off_floors(&nl->norms, s, p->q, Ax);
        }
        for (int i = 0; i < neq; ++i)
            dx[i] = -r[i];
        if (fresh) {
            int fs = bk_lin_factor_solve(&nl->ls, Ax, dx);
            nl->have_factors = fs == BK_LIN_OK;
            nl->factors_key = key;
            nl->krate = 0.0;                     /* rate of the new factors: not yet measured */
            res->rcond = fs == BK_LIN_SINGULAR ? 0.0 : nl->ls.rcond;
            if (fs == BK_LIN_SINGULAR) {
                res->singular_at_start = it == 0;
                code = BK_NL_SINGULAR;
                break;
            }
            if (fs != BK_LIN_OK) {
                code = BK_NL_LINERR;
                break;
            }
        } else if (bk_lin_solve(&nl->ls, dx) != BK_LIN_OK) {
            code = BK_NL_LINERR;
            break;
        }
        prev_reused = !fresh;
        res->reused |= !fresh;
        rprev_all = rall;
        dnorm_prev = dnorm, enorm_prev = enorm;
        if (p->augment && p->augment(p->ctx, &nl->ls, dx) != 0) {
            code = BK_NL_LINERR;
            break;
        }
        double work = 0.0;
        int finite = 1;
        for (int i = 0; i < neq; ++i) {
            finite &= isfinite(dx[i]) != 0;
            work += dx[i] * r[i];
        }
        if (!finite) {
            code = BK_NL_NONFINITE;
            break;
        }
        dnorm = bk_norm_free_max(&nl->norms, s, dx);
        enorm = sqrt(fabs(work));
        if (eref_it < 0)
            eref = enorm, eref_it = it;
        alpha = p->step_limit ? p->step_limit(p->ctx, dx) : 1.0;
        dnorm *= alpha;
        p->update(p->ctx, dx, alpha);
    }
    res->code = code;
    res->iters = it;
    if (code != BK_NL_OK)
        nl->have_factors = 0;                    /* a retry starts from a fresh matrix */
    return code;
}
