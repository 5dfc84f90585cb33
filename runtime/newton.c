/* newton.c -- load-stepped Newton iteration for statics. */
#include "newton.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linsolve.h"

typedef struct work {
    double *fint, *fext, *r, *dx, *Ax, *qsave, *nu, *nusave;
} work;

static double norm2(const double *v, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; ++i)
        s += v[i] * v[i];
    return sqrt(s);
}

enum { NEWTON_OK = 0, NEWTON_MAXIT, NEWTON_NONFINITE, NEWTON_SINGULAR, NEWTON_DIVERGED, NEWTON_LINERR };

static const char *why(int code)
{
    switch (code) {
    case NEWTON_MAXIT: return "no convergence within the iteration limit";
    case NEWTON_NONFINITE: return "non-finite internal force or increment";
    case NEWTON_SINGULAR: return "singular tangent: is the beam constrained against rigid motion?";
    case NEWTON_DIVERGED: return "residual grew without bound";
    case NEWTON_LINERR: return "linear solver error";
    default: return "converged";
    }
}

/* Newton iteration at load factor lam.  Returns a NEWTON_* code; iterations,
 * final residual and increment norms are reported through the pointers. */
static int newton(bk_system *s, bk_linsolver *ls, work *w, double *q, double lam, int *iters,
                  double *rnorm_out, double *dnorm_out, const bk_static_opts *o, double lscale)
{
    const bk_model *m = s->m;
    double dnorm = INFINITY, r0 = -1.0;
    for (int it = 0;; ++it) {
        if (bk_assemble_internal(s, q, w->fint, w->Ax) != 0)
            return NEWTON_NONFINITE;
        bk_assemble_follower(s, q, lam, w->fint, w->Ax);
        for (int i = 0; i < m->ndof; ++i)
            if (s->eq[i] >= 0)
                w->r[s->eq[i]] = w->fint[i] - lam * w->fext[i];
        bk_assemble_constraints(s, q, w->nu, lam, w->r, w->Ax);
        double rnorm = norm2(w->r, s->neq);
        double ref = fmax(fabs(lam) * norm2(w->fext, m->ndof), norm2(w->fint, m->ndof));
        double uscale = 0.0, qmax = 0.0, kmax = 0.0;
        for (int i = 0; i < m->ndof; ++i) {
            uscale = fmax(uscale, fabs(q[i] - m->q0[i]));
            qmax = fmax(qmax, fabs(q[i]));
        }
        for (int j = 0; j < s->nfree; ++j)
            if (s->diag[j] >= 0)
                kmax = fmax(kmax, fabs(w->Ax[s->diag[j]]));
        uscale = fmax(uscale, 1e-6 * lscale);
        /* Round-off floors: forces of the size of K times a last-bit change of
         * q, and increments of a few ulps of q. */
        double rfloor = 100.0 * DBL_EPSILON * kmax * qmax;
        double dfloor = 64.0 * DBL_EPSILON * qmax;
        *rnorm_out = rnorm;
        *dnorm_out = dnorm;
        *iters = it;
        if (!isfinite(rnorm))
            return NEWTON_NONFINITE;
        if (rnorm == 0.0)
            return NEWTON_OK;
        if (it > 0 && rnorm <= fmax(o->rtol * ref, rfloor) && dnorm <= fmax(o->utol * uscale, dfloor))
            return NEWTON_OK;
        if (r0 < 0.0)
            r0 = fmax(rnorm, 1e-300);
        else if (rnorm > 1e12 * r0)
            return NEWTON_DIVERGED;
        if (it >= o->max_iter)
            return NEWTON_MAXIT;
        int st = bk_lin_factor(ls, w->Ax);
        if (st == BK_LIN_SINGULAR)
            return NEWTON_SINGULAR;
        if (st != BK_LIN_OK)
            return NEWTON_LINERR;
        for (int i = 0; i < s->neq; ++i)
            w->dx[i] = -w->r[i];
        if (bk_lin_solve(ls, w->dx) != BK_LIN_OK)
            return NEWTON_LINERR;
        dnorm = 0.0;
        for (int i = 0; i < m->ndof; ++i)
            if (s->eq[i] >= 0) {
                double d = w->dx[s->eq[i]];
                if (!isfinite(d))
                    return NEWTON_NONFINITE;
                q[i] += d;
                dnorm = fmax(dnorm, fabs(d));
            }
        for (int c = 0; c < s->ncon; ++c)
            w->nu[c] += w->dx[s->nfree + c];
    }
}

int bk_solve_static(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log)
{
    const bk_model *m = s->m;
    const bk_static_opts *o = &m->stat;
    work w = {0};
    int nd = m->ndof, ne = s->neq > 0 ? s->neq : 1, nc = s->ncon > 0 ? s->ncon : 1;
    w.fint = calloc((size_t)nd, sizeof(double));
    w.fext = calloc((size_t)nd, sizeof(double));
    w.qsave = calloc((size_t)nd, sizeof(double));
    w.r = calloc((size_t)ne, sizeof(double));
    w.dx = calloc((size_t)ne, sizeof(double));
    w.nu = calloc((size_t)nc, sizeof(double));
    w.nusave = calloc((size_t)nc, sizeof(double));
    w.Ax = calloc((size_t)(s->nnz ? s->nnz : 1), sizeof(double));
    bk_linsolver ls = {0};
    int rc = 1;
    if (!w.fint || !w.fext || !w.qsave || !w.r || !w.dx || !w.nu || !w.nusave || !w.Ax) {
        snprintf(info->message, sizeof info->message, "out of memory");
        goto done;
    }
    if (s->neq == 0) {
        snprintf(info->message, sizeof info->message, "every DOF is fixed: nothing to solve");
        goto done;
    }
    if (bk_lin_init(&ls, s->neq, s->Ap, s->Ai) != BK_LIN_OK) {
        snprintf(info->message, sizeof info->message, "sparse analysis (KLU) failed");
        goto done;
    }
    memcpy(q, m->q0, (size_t)nd * sizeof *q);
    bk_external_load(s, w.fext);

    /* Constraint scaling: the mean magnitude of the tangent's diagonal at the
     * reference state (no allocation: reuses Ax). */
    if (s->ncon > 0) {
        bk_assemble_internal(s, q, w.fint, w.Ax);
        double sum = 0.0;
        int cnt = 0;
        for (int j = 0; j < s->nfree; ++j)
            for (int k = s->Ap[j]; k < s->Ap[j + 1]; ++k)
                if (s->Ai[k] == j) {
                    sum += fabs(w.Ax[k]);
                    cnt++;
                }
        s->cscale = cnt && sum > 0.0 ? sum / cnt : 1.0;
    }

    bk_output_step(out, 0, 0.0, q);
    /* Load path: 0 -> 1, then `cycles` times 1 -> 0 -> 1 (load-unload cycles, to
     * show path independence); each leg in load_steps increments. */
    double lam = 0.0, dlam0 = 1.0 / o->load_steps, dlam = dlam0;
    int cuts_in_row = 0, nleg = 1 + 2 * o->cycles;
    for (int leg = 0; leg < nleg; ++leg) {
        double goal = leg % 2 == 0 ? 1.0 : 0.0, dir = goal > lam ? 1.0 : -1.0;
        dlam = dlam0;
        while (dir * (goal - lam) > 0.0) {
            double target = lam + dir * dlam;
            if (dir * (goal - target) < 1e-12)
                target = goal;
            memcpy(w.qsave, q, (size_t)nd * sizeof *q);
            memcpy(w.nusave, w.nu, (size_t)nc * sizeof *w.nu);
            int iters = 0;
            double rnorm = 0.0, dnorm = 0.0;
            int st = newton(s, &ls, &w, q, target, &iters, &rnorm, &dnorm, o, m->length_scale);
            info->newton_iterations += iters;
            if (st == NEWTON_OK) {
                lam = target;
                info->steps++;
                info->load_factor = lam;
                bk_output_step(out, info->steps, lam, q);
                cuts_in_row = 0;
                if (iters <= 6 && dlam < dlam0)
                    dlam = fmin(2.0 * dlam, dlam0);
                if (log)
                    fprintf(log, "  step %d: load factor %.6g, %d iterations, residual %.3e\n",
                            info->steps, lam, iters, rnorm);
                bk_output_progress(out, (leg + (goal > 0.5 ? lam : 1.0 - lam)) / nleg, info->steps, lam,
                                   iters, rnorm);
                continue;
            }
            memcpy(q, w.qsave, (size_t)nd * sizeof *q);
            memcpy(w.nu, w.nusave, (size_t)nc * sizeof *w.nu);
            if (cuts_in_row >= o->max_cutbacks) {
                snprintf(info->message, sizeof info->message,
                         "static solve failed at step %d, load factor %.6g (last converged %.6g): %s; "
                         "residual %.3e, last increment %.3e after %d iterations, %d cut-backs",
                         info->steps + 1, target, lam, why(st), rnorm, dnorm, iters, cuts_in_row);
                goto done;
            }
            cuts_in_row++;
            info->cutbacks++;
            dlam *= 0.5;
            if (log)
                fprintf(log, "  cut-back at load factor %.6g (%s): new increment %.3g\n", target, why(st), dlam);
        }
    }
    rc = 0;
done:
    info->converged = rc == 0;
    info->factorizations = ls.nfactor;
    info->analyses = ls.nanalyze;
    bk_lin_free(&ls);
    free(w.fint);
    free(w.fext);
    free(w.qsave);
    free(w.r);
    free(w.dx);
    free(w.nu);
    free(w.nusave);
    free(w.Ax);
    return rc;
}
