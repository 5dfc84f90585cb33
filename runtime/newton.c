/* newton.c -- load-stepped Newton iteration for statics. */
#include "newton.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "checks.h"
#include "interrupt.h"
#include "linsolve.h"
#include "norms.h"
#include "quaternion.h"
#include "stability.h"

typedef struct work {
    double *fint, *fext, *r, *dx, *Ax, *qsave, *nu, *nusave;
    double *qprev, *nuprev;          /* the equilibrium before the last one (predictor) */
    int *quat;                       /* first global DOF of each free nodal quaternion */
    int nquat;
    bk_norms norms;                  /* rotation-invariant measures */
} work;

/* One Newton solve: its outcome and counters. */
typedef struct attempt {
    int id;                          /* attempt number over the run (newton.csv)  */
    int iters;
    double rnorm, dnorm, ref;
    double rtol_abs;                 /* the residual tolerance of the last iteration */
    double rcond;                    /* KLU's pivot ratio of the last factorization  */
    int residual_met;                /* the residual met its tolerance at some iteration */
    int singular_at_start;           /* NEWTON_SINGULAR at iteration 0               */
    int signo;                       /* NEWTON_INTERRUPTED: the signal */
} attempt;

/* Below this pivot ratio the tangent is singular to working precision: Newton
 * increments are meaningless in its near-null directions. */
#define ILL_RCOND 1e-12

enum { NEWTON_OK = 0, NEWTON_MAXIT, NEWTON_NONFINITE, NEWTON_SINGULAR, NEWTON_DIVERGED, NEWTON_LINERR, NEWTON_UNSTABLE,
       NEWTON_INTERRUPTED };

static const char *why(int code)
{
    switch (code) {
    case NEWTON_MAXIT: return "no convergence within the iteration limit";
    case NEWTON_NONFINITE: return "non-finite internal force or increment";
    case NEWTON_SINGULAR: return "singular tangent: is the beam constrained against rigid motion?";
    case NEWTON_DIVERGED: return "residual grew without bound";
    case NEWTON_LINERR: return "linear solver error";
    case NEWTON_UNSTABLE: return "the equilibrium reached is unstable (more negative tangent eigenvalues)";
    case NEWTON_INTERRUPTED: return "interrupted";
    default: return "converged";
    }
}

/* What went wrong, for the failure message: a singular or numerically singular
 * tangent is named as such (with its likely causes) rather than as a missed
 * iteration limit. */
static void diagnose(char *buf, size_t n, int code, const attempt *a, int steps, int negative)
{
    if (code == NEWTON_SINGULAR || (isfinite(a->rcond) && a->rcond < ILL_RCOND)) {
        int exact = code == NEWTON_SINGULAR;
        int len = snprintf(buf, n, "%ssingular tangent (KLU pivot ratio %.1e)%s", exact ? "" : "numerically ",
                           a->rcond,
                           a->residual_met ? ": the residual met its tolerance but the increments did not settle"
                                           : "");
        if (len < 0 || (size_t)len >= n)
            return;
        snprintf(buf + len, n - (size_t)len,
                 "; likely cause: %s", steps == 0
                     ? "a rigid motion or mechanism left free: is every beam constrained against rigid motion? "
                       "(e.g. a beam held by nothing, or one that can spin about its own axis at a spherical joint)"
                     : negative > 0 ? "a bifurcation or limit point on the path (negative tangent eigenvalues): "
                                      "try static.stable_path with an imperfection"
                                    : "a mechanism that opened under the load, or a bifurcation point");
        return;
    }
    snprintf(buf, n, "%s", why(code));
}

/* Residual r(q, nu) at load factor lam into w->r, and the Newton matrix into
 * w->Ax when with_tangent.  Returns -1 on a non-finite internal force. */
static int residual(bk_system *s, work *w, const double *q, const double *nu, double lam, int with_tangent)
{
    const bk_model *m = s->m;
    double *Ax = with_tangent ? w->Ax : NULL;
    if (bk_assemble_internal(s, q, w->fint, Ax) != 0)
        return -1;
    bk_assemble_follower(s, q, lam, w->fint, Ax);
    for (int i = 0; i < m->ndof; ++i)
        if (s->eq[i] >= 0)
            w->r[s->eq[i]] = w->fint[i] - lam * w->fext[i];
    bk_assemble_constraints(s, q, nu, lam, w->r, Ax);
    return 0;
}

/* x = x0 + alpha dx on the free DOFs and multipliers, quaternions rescaled. */
static void step_to(const bk_system *s, const work *w, const double *q0, const double *nu0, const double *dx,
                    double alpha, double *q, double *nu)
{
    const bk_model *m = s->m;
    for (int i = 0; i < m->ndof; ++i)
        q[i] = s->eq[i] >= 0 ? q0[i] + alpha * dx[s->eq[i]] : q0[i];
    for (int c = 0; c < s->ncon; ++c)
        nu[c] = nu0[c] + alpha * dx[s->nfree + c];
    bk_quat_normalize(w->quat, w->nquat, q, NULL, 0);
}

/* Newton iteration at load factor lam, from the state in q, w->nu.  Returns
 * a NEWTON_* code; every iteration is recorded in newton.csv (alpha: the
 * fraction of the Newton step taken, below 1 when the rotation trust region
 * shortened it).
 *
 * A line search on the energy slope s(alpha) = dx . r(x + alpha dx), tried as
 * a retry before cutting an increment back, rescued none of the hard cases
 * (report/hard.py: two-turn roll-ups, one-step cantilevers, silicone sag):
 * their failures are the alternation between membrane and bending residuals of
 * slender beams, which the rotation trust region below and the load increment
 * address.  It was removed rather than kept as an option that does nothing. */
#define ROT_STEP 0.15
static int newton(bk_system *s, bk_linsolver *ls, work *w, double *q, double lam, double lam_last, attempt *a,
                  const bk_static_opts *o, double lscale, bk_output *out, int step)
{
    const bk_model *m = s->m;
    double dnorm = INFINITY, r0 = -1.0, alpha = 1.0, rprev = INFINITY, enorm = INFINITY, eref = 0.0;
    a->iters = 0;
    a->residual_met = 0;
    a->singular_at_start = 0;
    a->rcond = NAN;
    for (int it = 0;; ++it) {
        if ((a->signo = bk_interrupt_poll()) != 0)
            return NEWTON_INTERRUPTED;
        if (residual(s, w, q, w->nu, lam, 1) != 0)
            return NEWTON_NONFINITE;
        /* joints nonlinear in q: start from the multipliers that balance the loads
         * (their geometric stiffness holds mechanisms like a hanging pendulum) */
        if (it == 0 && m->nnlcon > 0 && bk_constraint_multipliers(s, q, lam, w->r, w->nu) == 0 &&
            residual(s, w, q, w->nu, lam, 1) != 0)
            return NEWTON_NONFINITE;
        double rnorm = bk_norm2(w->r, s->neq);
        double ref = fmax(fabs(lam) * bk_norm2(w->fext, m->ndof), bk_norm2(w->fint, m->ndof));
        /* Every measure is invariant under a rigid rotation of the scene:
         * field norms, column-block norms, scalar products (norms.h).  The
         * round-off floors use the stiffest column block of the Newton matrix:
         * with multipliers (constraint rows, the internal multipliers of the
         * constrained beams) the stiffest couplings can sit off the diagonal. */
        double uscale = fmax(bk_norm_dof_max(&w->norms, s, q, m->q0), 1e-6 * lscale);
        bk_floors fl = bk_round_off_floors(&w->norms, s, q, w->Ax);
        a->rnorm = rnorm;
        a->dnorm = dnorm;
        a->ref = ref;
        a->iters = it;
        bk_output_iteration(out, a->id, step, lam, it, rnorm, ref, it ? dnorm : NAN, it ? alpha : NAN, ls->rcond);
        if (!isfinite(rnorm))
            return NEWTON_NONFINITE;
        if (rnorm == 0.0)
            return NEWTON_OK;
        double rtol_abs = fmax(o->rtol * ref, fl.force), utol_abs = fmax(o->utol * uscale, fl.increment);
        a->rtol_abs = rtol_abs;
        if (rnorm <= rtol_abs)
            a->residual_met = 1;
        /* converged: the residual within its tolerance, and the last
         * correction small, in length (field norm) or in energy (see
         * BK_ENERGY_TOL, norms.h) */
        /* the energy scale of the increment: its first correction, or the
         * work of the load increment on the motion from the last equilibrium
         * (w->qsave), whichever is larger -- a good predictor must not make
         * the test stricter */
        double wload = 0.0;
        for (int i = 0; i < m->ndof; ++i)
            wload += (lam - lam_last) * w->fext[i] * (q[i] - w->qsave[i]);
        double escale = fmax(eref, sqrt(fabs(wload)));
        if (it > 0 && rnorm <= rtol_abs &&
            (dnorm <= utol_abs || enorm <= fmax(BK_ENERGY_TOL * escale, fl.energy)))
            return NEWTON_OK;
        /* Stagnation at round-off: on ill-conditioned tangents (slender
         * higher-order elements) the residual stops decreasing a little above
         * its floor while the increments are already at noise level; accept
         * within a factor 1e3 (residual) and 1e2 (increment) of the
         * tolerances once an iteration no longer halves the residual. */
        if (it > 1 && rnorm > 0.5 * rprev && rnorm <= 1e3 * rtol_abs && dnorm <= 1e2 * utol_abs)
            return NEWTON_OK;
        rprev = rnorm;
        if (r0 < 0.0)
            r0 = fmax(rnorm, 1e-300);
        else if (rnorm > 1e12 * r0)
            return NEWTON_DIVERGED;
        if (it >= o->max_iter)
            return NEWTON_MAXIT;
        int st = bk_lin_factor(ls, w->Ax);
        a->rcond = st == BK_LIN_SINGULAR ? 0.0 : ls->rcond;
        if (st == BK_LIN_SINGULAR) {
            a->singular_at_start = it == 0;
            return NEWTON_SINGULAR;
        }
        if (st != BK_LIN_OK)
            return NEWTON_LINERR;
        for (int i = 0; i < s->neq; ++i)
            w->dx[i] = -w->r[i];
        if (bk_lin_solve(ls, w->dx) != BK_LIN_OK)
            return NEWTON_LINERR;
        double work_ = 0.0;
        for (int i = 0; i < s->neq; ++i) {
            if (!isfinite(w->dx[i]))
                return NEWTON_NONFINITE;
            work_ += w->dx[i] * w->r[i];
        }
        dnorm = bk_norm_free_max(&w->norms, s, w->dx);
        enorm = sqrt(fabs(work_));
        if (it == 0)
            eref = enorm;
        alpha = 1.0;
        /* Rotation trust region: quaternion increments are rotations only to
         * first order; a step that changes a unit quaternion by more than
         * ROT_STEP (Euclidean norm of the 4 components: a rotation of about 17
         * degrees) is shortened to that.  With it the geometrically exact beams take the load steps the
         * ANCF elements take (two turns of roll-up in 4 steps instead of 24). */
        double dpmax = 0.0;
        for (int k = 0; k < w->nquat; ++k) {
            double ss = 0.0;
            for (int i = 0; i < 4; ++i)
                ss += w->dx[s->eq[w->quat[k] + i]] * w->dx[s->eq[w->quat[k] + i]];
            dpmax = fmax(dpmax, sqrt(ss));
        }
        if (dpmax > ROT_STEP)
            alpha = ROT_STEP / dpmax;
        dnorm *= alpha;
        step_to(s, w, q, w->nu, w->dx, alpha, q, w->nu);
    }
}

/* Stability of the equilibrium q at load factor lam (not yet accepted):
 * the number of negative eigenvalues of the constrained tangent.  assembled:
 * w->Ax already holds the Newton matrix at q (a converged Newton solve ends
 * on the assembly of its last iterate), else it is assembled here. */
static int probe_stability(bk_stability *st, bk_system *s, work *w, const double *q, double lam,
                           int assembled, bk_stability_result *res)
{
    if (!assembled && residual(s, w, q, w->nu, lam, 1) != 0) {
        memset(res, 0, sizeof *res);
        return -1;
    }
    bk_stability_check(st, w->Ax, res);
    return res->ok ? res->negative : -1;
}

/* Accepts the probed equilibrium: when the count changed since the previous
 * one, records the event with the interpolated critical load factor. */
static void accept_stability(bk_stability *st, const bk_stability_result *res, double lam, bk_output *out,
                             bk_run_info *info, FILE *log, double *prev_lam)
{
    const char *s_name = out->m->name;
    int before = info->negative_eigenvalues;
    info->negative_eigenvalues = res->ok ? res->negative : before;
    info->eig_min = res->eig_min;
    info->eig_max = res->eig_max;
    if (res->ok && res->negative != before && info->steps >= 1 && info->nstability < BK_MAX_EVENTS) {
        double t = bk_stability_crossing(st, before);
        bk_stability_event *ev = &info->stability[info->nstability++];
        ev->step = info->steps;
        ev->lam_before = *prev_lam;
        ev->lam_after = lam;
        ev->neg_before = before;
        ev->neg_after = res->negative;
        ev->lam_critical = *prev_lam + t * (lam - *prev_lam);
        bk_warn(info, out->console, s_name,
                "the number of negative tangent eigenvalues went from %d to %d between load factors %.6g and "
                "%.6g (critical load factor %.6g): a %s was passed%s", before, res->negative, *prev_lam, lam,
                ev->lam_critical, res->negative > before ? "bifurcation or limit point" : "point of regained stability",
                res->negative > before ? "; the path beyond may be unstable (static.stable_path with an "
                                         "imperfection follows the stable branch)" : "");
        if (log)
            fprintf(log, "  stability: negative eigenvalues of the tangent %d -> %d between load factors "
                         "%.6g and %.6g (first change at load factor %.6g)\n",
                    before, res->negative, *prev_lam, lam, ev->lam_critical);
    }
    if (res->ok)
        bk_stability_accept(st);
    *prev_lam = lam;
    bk_output_stability(out, info->steps, lam, res->ok ? res->negative : -1, res->eig_min, res->eig_max);
}

/* The next load increment after one that converged in `iters` iterations.
 * Fixed control (static.step_control = "fixed", or no cut-backs allowed):
 * back towards the initial increment after easy steps.  Adaptive control (the
 * default): grow by 2 after an increment of at most 3 iterations, by 1.5 after
 * one of at most TARGET_ITERS, not right after a cut-back (two converged
 * increments first), never beyond the leg; an increment that needs many
 * iterations is kept (slowly converging problems need them at any size) and
 * one that fails is cut back. */
#define TARGET_ITERS 6
static double next_increment(const bk_static_opts *o, double dlam, double dlam0, int iters, int calm)
{
    if (!o->adaptive || o->max_cutbacks == 0)
        return iters <= 6 && dlam < dlam0 ? fmin(2.0 * dlam, dlam0) : dlam;
    double f = iters <= 3 ? 2.0 : iters <= TARGET_ITERS ? 1.5 : 1.0;
    if (calm < 2)
        f = fmin(f, dlam < dlam0 ? 2.0 : 1.0);      /* after a cut-back: back to dlam0 at most */
    return fmin(fmin(dlam * f, calm < 2 ? fmax(dlam0, dlam) : 1.0), 1.0);
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
    w.qprev = calloc((size_t)nd, sizeof(double));
    w.r = calloc((size_t)ne, sizeof(double));
    w.dx = calloc((size_t)ne, sizeof(double));
    w.nu = calloc((size_t)nc, sizeof(double));
    w.nusave = calloc((size_t)nc, sizeof(double));
    w.nuprev = calloc((size_t)nc, sizeof(double));
    w.Ax = calloc((size_t)(s->nnz ? s->nnz : 1), sizeof(double));
    bk_linsolver ls = {0};
    bk_stability stab = {0};
    bk_checks chk = {0};
    int rc = 1, have_stab = 0;
    if (!w.fint || !w.fext || !w.qsave || !w.qprev || !w.r || !w.dx || !w.nu || !w.nusave ||
        !w.nuprev || !w.Ax) {
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
    w.quat = bk_quat_list(s, &w.nquat);
    if (w.nquat < 0 || bk_norms_init(&w.norms, s) != 0 || bk_checks_init(&chk, s) != 0) {
        snprintf(info->message, sizeof info->message, "out of memory");
        goto done;
    }
    if (o->stability) {
        if (bk_stability_init(&stab, s) != 0) {
            snprintf(info->message, sizeof info->message, "out of memory (stability analysis)");
            goto done;
        }
        have_stab = 1;
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
    double prev_lam = 0.0;
    bk_stability_result sres;
    if (have_stab) {
        probe_stability(&stab, s, &w, q, 0.0, 0, &sres);
        accept_stability(&stab, &sres, 0.0, out, info, log, &prev_lam);
    }
    /* Load path: 0 -> 1, then `cycles` times 1 -> 0 -> 1 (load-unload cycles, to
     * show path independence); each leg in load_steps increments. */
    double lam = 0.0, lam_prev = 0.0, dlam0 = 1.0 / o->load_steps, dlam = dlam0;
    int cuts_in_row = 0, nleg = 1 + 2 * o->cycles, have_prev = 0, max_negative = 0, warned_singular = 0;
    int cuts_since_growth_ok = 2;      /* converged increments since the last cut-back (at most 2) */
    attempt a = {0};
    for (int leg = 0; leg < nleg; ++leg) {
        double goal = leg % 2 == 0 ? 1.0 : 0.0, dir = goal > lam ? 1.0 : -1.0;
        dlam = dlam0;
        have_prev = 0;
        while (dir * (goal - lam) > 0.0) {
            double target = lam + dir * dlam;
            if (dir * (goal - target) < 1e-12)
                target = goal;
            memcpy(w.qsave, q, (size_t)nd * sizeof *q);
            memcpy(w.nusave, w.nu, (size_t)nc * sizeof *w.nu);
            /* Secant predictor: extrapolate the last two equilibria of this
             * leg to the target load. */
            if (o->predictor && have_prev && lam != lam_prev) {
                double c = (target - lam) / (lam - lam_prev);
                for (int i = 0; i < nd; ++i)
                    q[i] += c * (q[i] - w.qprev[i]);
                for (int k = 0; k < s->ncon; ++k)
                    w.nu[k] += c * (w.nu[k] - w.nuprev[k]);
                bk_quat_normalize(w.quat, w.nquat, q, NULL, 0);
            }
            /* Attempts: Newton from the predicted state, then from the last
             * equilibrium; then the increment is cut back. */
            int st = NEWTON_MAXIT;
            for (int k = 0; k < 2 && st != NEWTON_OK && st != NEWTON_INTERRUPTED; ++k) {
                int predicted = k == 0 && o->predictor && have_prev;
                if (k == 0 && !predicted)
                    continue;
                if (k > 0) {
                    memcpy(q, w.qsave, (size_t)nd * sizeof *q);
                    memcpy(w.nu, w.nusave, (size_t)nc * sizeof *w.nu);
                }
                a.id++;
                st = newton(s, &ls, &w, q, target, lam, &a, o, m->length_scale, out, info->steps + 1);
                info->newton_iterations += a.iters;
            }
            /* On a stable path (static.stable_path), an increment that ends
             * at an equilibrium with more negative eigenvalues than the last
             * one is cut back while cut-backs remain: with an imperfection
             * the stable branch is reached with smaller increments; without,
             * the bifurcation is bracketed as closely as the cut-backs allow
             * and then passed (and reported). */
            if (st == NEWTON_OK && have_stab) {
                int c = probe_stability(&stab, s, &w, q, target, 1, &sres);
                /* not for an eigenvalue at round-off level (the count is
                 * uncertain there) nor below a millionth of the increment */
                if (o->stable_path && c > max_negative && cuts_in_row < o->max_cutbacks &&
                    dlam > 1e-6 * dlam0)
                    st = NEWTON_UNSTABLE;
            }
            if (st == NEWTON_OK) {
                if (isfinite(a.rcond) && a.rcond < ILL_RCOND && !warned_singular++)
                    bk_warn(info, out->console, m->name,
                            "numerically singular tangent at the equilibrium of load factor %.6g (KLU "
                            "pivot ratio %.1e): the solution is not unique; likely cause: a rigid motion or "
                            "mechanism the constraints leave free (e.g. the rotation of a beam about its own "
                            "axis at a spherical joint), or a bifurcation point", target, a.rcond);
                memcpy(w.qprev, w.qsave, (size_t)nd * sizeof *q);
                memcpy(w.nuprev, w.nusave, (size_t)nc * sizeof *w.nu);
                lam_prev = lam;
                have_prev = 1;
                lam = target;
                info->steps++;
                info->load_factor = lam;
                bk_output_step(out, info->steps, lam, q);
                bk_checks_state(&chk, s, q, "load factor", lam, info, out->console);
                cuts_in_row = 0;
                if (cuts_since_growth_ok < 2)
                    cuts_since_growth_ok++;
                dlam = next_increment(o, dlam, dlam0, a.iters, cuts_since_growth_ok);
                if (log)
                    fprintf(log, "  step %d: load factor %.6g, %d iterations, residual %.3e\n",
                            info->steps, lam, a.iters, a.rnorm);
                if (have_stab) {
                    accept_stability(&stab, &sres, lam, out, info, log, &prev_lam);
                    /* the count may flicker at a nearly singular state: only
                     * a count above every one accepted so far is a new loss
                     * of stability */
                    if (info->negative_eigenvalues > max_negative)
                        max_negative = info->negative_eigenvalues;
                }
                bk_output_progress(out, (leg + (goal > 0.5 ? lam : 1.0 - lam)) / nleg, info->steps, lam,
                                   a.iters, a.rnorm);
                continue;
            }
            memcpy(q, w.qsave, (size_t)nd * sizeof *q);
            memcpy(w.nu, w.nusave, (size_t)nc * sizeof *w.nu);
            if (st == NEWTON_INTERRUPTED) {
                info->interrupted = a.signo;
                snprintf(info->message, sizeof info->message,
                         "interrupted by %s during step %d at load factor %.6g; the %d converged steps (last "
                         "load factor %.6g) are kept", bk_interrupt_name(a.signo), info->steps + 1, target,
                         info->steps, lam);
                goto done;
            }
            /* A tangent singular at the last equilibrium itself (iteration 0
             * without predictor) does not depend on the increment: cutting
             * back cannot help. */
            int hopeless = st == NEWTON_SINGULAR && a.singular_at_start && !(o->predictor && have_prev);
            if (cuts_in_row >= o->max_cutbacks || hopeless) {
                char what[600], incr[64];
                diagnose(what, sizeof what, st, &a, info->steps, info->negative_eigenvalues);
                if (a.iters > 0 && isfinite(a.dnorm))
                    snprintf(incr, sizeof incr, ", last increment %.3e", a.dnorm);
                else
                    incr[0] = 0;
                snprintf(info->message, sizeof info->message,
                         "static solve failed at step %d, load factor %.6g (last converged %.6g): %s; "
                         "residual %.3e (tolerance %.3e)%s after %d iteration%s, %d cut-back%s%s",
                         info->steps + 1, target, lam, what, a.rnorm, a.rtol_abs, incr, a.iters,
                         a.iters == 1 ? "" : "s", cuts_in_row, cuts_in_row == 1 ? "" : "s",
                         hopeless ? " (a tangent singular at the last equilibrium does not improve with smaller "
                                    "increments)"
                         : info->negative_eigenvalues > 0 && info->steps > 0
                             ? "; the last equilibrium was unstable (negative tangent eigenvalues): "
                               "a bifurcation or limit point was passed"
                             : "");
                goto done;
            }
            cuts_in_row++;
            info->cutbacks++;
            dlam *= 0.5;
            cuts_since_growth_ok = 0;
            if (dlam <= 1e-14 * fmax(fabs(lam), 1.0)) {
                snprintf(info->message, sizeof info->message,
                         "static solve failed at step %d, load factor %.6g (last converged %.6g): the load "
                         "increment fell below round-off after repeated cut-backs (last: %s); residual %.3e, "
                         "last increment %.3e after %d iterations",
                         info->steps + 1, target, lam, why(st), a.rnorm, a.dnorm, a.iters);
                goto done;
            }
            if (log)
                fprintf(log, "  cut-back at load factor %.6g (%s): new increment %.3g\n", target, why(st), dlam);
        }
    }
    rc = 0;
done:
    info->converged = rc == 0;
    info->factorizations = ls.nfactor;
    info->analyses = ls.nanalyze;
    info->stability_checked = have_stab;
    bk_lin_free(&ls);
    if (have_stab)
        bk_stability_free(&stab);
    free(w.fint);
    free(w.fext);
    free(w.qsave);
    free(w.qprev);
    free(w.r);
    free(w.dx);
    free(w.nu);
    free(w.nusave);
    free(w.nuprev);
    free(w.Ax);
    free(w.quat);
    bk_norms_free(&w.norms);
    bk_checks_free(&chk);
    return rc;
}
