/* static.c -- statics by load control: the load factor from 0 to 1 (and
 * static.cycles times back and forth) in increments that adapt to the Newton
 * iterations and are cut back on failure; the analysis module "static" (see
 * analysis.h) unless static.method = "arc_length" (continuation.c). */
#include "analysis/static.h"
#include "solver/null_motion.h"

#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/analysis.h"
#include "analysis/static_problem.h"
#include "assembly/quaternion.h"
#include "base/interrupt.h"

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
    if (o->step_control != BK_STEP_CONTROL_ADAPTIVE || o->max_cutbacks == 0)
        return iters <= 6 && dlam < dlam0 ? fmin(2.0 * dlam, dlam0) : dlam;
    double f = iters <= 3 ? 2.0 : iters <= TARGET_ITERS ? 1.5 : 1.0;
    if (calm < 2)
        f = fmin(f, dlam < dlam0 ? 2.0 : 1.0);      /* after a cut-back: back to dlam0 at most */
    return fmin(fmin(dlam * f, calm < 2 ? fmax(dlam0, dlam) : 1.0), 1.0);
}

/* Load control passed a critical point inside the increment from lam_lo
 * (the equilibrium w->qprev, w->nuprev, `before` negative eigenvalues) to
 * lam_hi (q, w->nu, the checker's last check): the load factor where the
 * count first changes, by bisection on equilibria re-solved from the last one
 * below it, to BK_REFINE_TOL of the load factor.  The interpolation of
 * bk_static_accept_stability assumes a tangent linear in the load: across a large
 * increment off a straight prebuckling path it misplaces the point (the
 * gef cantilever strip of tests/test_buckling.py, 8 steps to 15 N: 11.72 N
 * interpolated from 5.6 N and 13.1 N, 11.4927 N refined; 60 fixed steps
 * 11.4928 N interpolated, 11.4927 N refined).  Leaves q, w->nu and
 * the checker as they were (the last check repeated at q, the eigenvalue
 * iterations' vectors restored); returns the bracket's middle, or NaN when no
 * equilibrium inside converged.  Allocates its buffers per event (rare). */
#define BK_REFINE_TOL 1e-7
#define BK_REFINE_MAX 40
static double refine_critical(bk_system *s, bk_nl *nl, work *w, bk_stability *st, const double *q,
                              double lam_lo, double lam_hi, int before, const bk_static_opts *o, attempt *a,
                              bk_run_info *info)
{
    const bk_model *m = s->m;
    size_t nd = (size_t)m->ndof, nc = (size_t)(s->ncon > 0 ? s->ncon : 1), n = (size_t)st->n;
    double *ql = malloc(nd * sizeof *ql), *qt = malloc(nd * sizeof *qt);
    double *nul = malloc(2 * nc * sizeof *nul), *xs = st->x ? malloc(2 * n * sizeof *xs) : NULL;
    double lo = lam_lo, hi = lam_hi, crit = NAN;
    int have_vec = st->have_vec, have_vmax = st->have_vmax;
    if (!ql || !qt || !nul || (st->x && !xs))
        goto done;
    double *nuh = nul + nc;
    memcpy(ql, w->qprev, nd * sizeof *ql);
    memcpy(nul, w->nuprev, nc * sizeof *nul);
    memcpy(nuh, w->nu, nc * sizeof *nuh);
    if (xs) {
        memcpy(xs, st->x, n * sizeof *xs);
        memcpy(xs + n, st->xmax, n * sizeof *xs);
    }
    attempt b = *a;
    for (int k = 0; k < BK_REFINE_MAX && fabs(hi - lo) > BK_REFINE_TOL * fmax(fabs(hi), fabs(lo)); ++k) {
        double mid = 0.5 * (lo + hi);
        memcpy(qt, ql, nd * sizeof *qt);
        memcpy(w->nu, nul, nc * sizeof *nul);
        b.id++;
        int rc = bk_static_newton(s, nl, w, qt, mid, lo, &b, o, m->length_scale, info->steps, NULL);
        info->newton_iterations += b.iters;
        if (rc == NEWTON_INTERRUPTED)
            raise(b.signo);              /* pending again (blocked): the load loop stops on it */
        bk_stability_result r;
        if (rc != NEWTON_OK || bk_static_probe_stability(st, s, w, qt, mid, 1, &r) < 0)
            break;
        if (r.negative == before) {
            lo = mid;
            memcpy(ql, qt, nd * sizeof *ql);
            memcpy(nul, w->nu, nc * sizeof *nul);
        } else {
            hi = mid;
        }
        crit = 0.5 * (lo + hi);
    }
    a->id = b.id;
    memcpy(w->nu, nuh, nc * sizeof *nuh);
    bk_stability_result r;
    bk_static_probe_stability(st, s, w, q, lam_hi, 0, &r);
    if (xs) {
        memcpy(st->x, xs, n * sizeof *xs);
        memcpy(st->xmax, xs + n, n * sizeof *xs);
    }
    st->have_vec = have_vec, st->have_vmax = have_vmax;
done:
    free(ql), free(qt), free(nul), free(xs);
    return crit;
}

/* The secant predictor q (from w->qsave, w->nusave) taken only as far as the
 * interactions' step limit allows (beam-to-beam contact: two beams have no
 * signed distance to tell that an extrapolation put one through the other). */
static void cut_predictor(bk_system *s, work *w, double *q)
{
    const int nd = s->m->ndof;
    memset(w->dx, 0, (size_t)(s->neq > 0 ? s->neq : 1) * sizeof *w->dx);
    for (int i = 0; i < nd; ++i)
        if (s->eq[i] >= 0 && s->eq[i] < s->nfree)
            w->dx[s->eq[i]] = q[i] - w->qsave[i];
    const double alpha = bk_interactions_prepare(s, w->qsave) == 0 ? bk_interactions_step_limit(s, w->qsave, w->dx)
                                                                   : 0.0;
    if (alpha >= 1.0)
        return;
    for (int i = 0; i < nd; ++i)
        q[i] = w->qsave[i] + alpha * (q[i] - w->qsave[i]);
    for (int k = 0; k < s->ncon; ++k)
        w->nu[k] = w->nusave[k] + alpha * (w->nu[k] - w->nusave[k]);
}

static int load_control(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log, int tables)
{
    const bk_model *m = s->m;
    const bk_static_opts *o = &m->stat;
    int nd = m->ndof, nc = s->ncon > 0 ? s->ncon : 1;
    static_run R;
    int rc = 1;
    if (bk_static_begin(&R, s, q, out, info, log, 1, tables) != 0)
        goto done;
    work *w = &R.w;
    /* Load path: 0 -> 1, then `cycles` times 1 -> 0 -> 1 (load-unload cycles, to
     * show path independence); each leg in load_steps increments. */
    double lam = 0.0, lam_prev = 0.0, dlam0 = 1.0 / o->load_steps, dlam = dlam0;
    int cuts_in_row = 0, nleg = 1 + 2 * o->cycles, have_prev = 0, max_negative = 0, warned_singular = 0;
    int cuts_since_growth_ok = 2;      /* converged increments since the last cut-back (at most 2) */
    attempt a = {0};
    char inadm[320] = "";              /* why the last inadmissible state was refused */
    for (int leg = 0; leg < nleg; ++leg) {
        double goal = leg % 2 == 0 ? 1.0 : 0.0, dir = goal > lam ? 1.0 : -1.0;
        dlam = dlam0;
        have_prev = 0;
        while (dir * (goal - lam) > 0.0) {
            double target = lam + dir * dlam;
            if (dir * (goal - target) < 1e-12)
                target = goal;
            memcpy(w->qsave, q, (size_t)nd * sizeof *q);
            memcpy(w->nusave, w->nu, (size_t)nc * sizeof *w->nu);
            /* Secant predictor: extrapolate the last two equilibria of this
             * leg to the target load. */
            if (o->predictor == BK_PREDICTOR_SECANT && have_prev && lam != lam_prev) {
                double c = (target - lam) / (lam - lam_prev);
                for (int i = 0; i < nd; ++i)
                    q[i] += c * (q[i] - w->qprev[i]);
                for (int k = 0; k < s->ncon; ++k)
                    w->nu[k] += c * (w->nu[k] - w->nuprev[k]);
                if (bk_interactions_cut_predictors(s))   /* e.g. no beam carried through another */
                    cut_predictor(s, w, q);
                bk_quat_normalize(w->quat, w->nquat, q, NULL, 0);
            }
            /* Attempts: Newton from the predicted state, then from the last
             * equilibrium; then the increment is cut back. */
            int st = NEWTON_MAXIT;
            for (int k = 0; k < 2 && st != NEWTON_OK && st != NEWTON_INTERRUPTED; ++k) {
                int predicted = k == 0 && o->predictor == BK_PREDICTOR_SECANT && have_prev;
                if (k == 0 && !predicted)
                    continue;
                if (k > 0) {
                    memcpy(q, w->qsave, (size_t)nd * sizeof *q);
                    memcpy(w->nu, w->nusave, (size_t)nc * sizeof *w->nu);
                }
                a.id++;
                st = bk_static_newton(s, &R.nl, w, q, target, lam, &a, o, m->length_scale, info->steps + 1, &R.ref);
                info->newton_iterations += a.iters;
            }
            /* an increment is accepted only at an admissible state (finite,
             * no element inverted): else it is cut back like a failed one */
            if (st == NEWTON_OK && !bk_checks_admissible(&R.chk, s, q, inadm, sizeof inadm))
                st = NEWTON_INADMISSIBLE;
            int assembled = 1;           /* w->Ax: the matrix at q (a converged solve ends on it) */
            if (R.ref.state != 0) {         /* the reference state's check, before this step's */
                const int probe = R.ref.state != 2;   /* no Newton matrix was made at it, or not checked */
                if (probe) {
                    bk_static_probe_stability(&R.stab, s, w, m->q0, 0.0, 0, &R.ref.res);
                    assembled = 0;
                }
                bk_static_accept_stability(&R.stab, &R.ref.res, 0.0, out, info, log, &R.prev_lam, probe, NAN,
                                           w->stability_csv);
                R.ref.state = 0;
            }
            /* On a stable path (static.stable_path), an increment that ends
             * at an equilibrium with more negative eigenvalues than the last
             * one is cut back while cut-backs remain: with an imperfection
             * the stable branch is reached with smaller increments; without,
             * the bifurcation is bracketed as closely as the cut-backs allow
             * and then passed (and reported). */
            if (st == NEWTON_OK && R.have_stab) {
                int c = bk_static_probe_stability(&R.stab, s, w, q, target, assembled, &R.sres);
                /* not for an eigenvalue at round-off level (the count is
                 * uncertain there) nor below a millionth of the increment */
                if (o->stable_path && c > max_negative && cuts_in_row < o->max_cutbacks &&
                    dlam > 1e-6 * dlam0)
                    st = NEWTON_UNSTABLE;
            }
            if (st == NEWTON_OK) {
                if (isfinite(a.rcond) && a.rcond < ILL_RCOND && !warned_singular++)
                    bk_warn(info, out->console, m->name,
                            "numerically singular tangent at the equilibrium of load factor %.6g (pivot "
                            "ratio %.1e): the solution is not unique; likely cause: a rigid motion or "
                            "mechanism the constraints leave free (e.g. the rotation of a beam about its own "
                            "axis at a spherical joint), or a bifurcation point", target, a.rcond);
                memcpy(w->qprev, w->qsave, (size_t)nd * sizeof *q);
                memcpy(w->nuprev, w->nusave, (size_t)nc * sizeof *w->nu);
                lam_prev = lam;
                have_prev = 1;
                lam = target;
                info->steps++;
                info->load_factor = lam;
                bk_output_forces(out, s, info->steps, lam, q, NULL, NULL, w->nu);
                bk_output_step(out, info->steps, lam, q);
                bk_interactions_accept(s, q, &(bk_path){.factor = lam, .x = lam});
                bk_checks_state(&R.chk, s, q, "load factor", lam, info, out->console);
                cuts_in_row = 0;
                if (cuts_since_growth_ok < 2)
                    cuts_since_growth_ok++;
                dlam = next_increment(o, dlam, dlam0, a.iters, cuts_since_growth_ok);
                if (log)
                    fprintf(log, "  step %d: load factor %.6g, %d iterations, residual %.3e\n",
                            info->steps, lam, a.iters, a.rnorm);
                if (R.have_stab) {
                    double refined = NAN;
                    /* a reference that is no equilibrium (its residual at load factor 0 above this
                     * step's tolerance) has a count of no path: no change is drawn from it */
                    if (info->steps == 1 && R.sres.ok && R.ref_rnorm > a.rtol_abs) {
                        if (log && R.sres.negative != info->negative_eigenvalues)
                            fprintf(log, "  stability: the reference state is no equilibrium (residual %.3e at "
                                         "load factor 0): its %d negative eigenvalues are not compared\n",
                                    R.ref_rnorm, info->negative_eigenvalues);
                        info->negative_eigenvalues = R.sres.negative;
                    }
                    if (R.sres.ok && R.sres.negative != info->negative_eigenvalues)
                        refined = refine_critical(s, &R.nl, w, &R.stab, q, R.prev_lam, lam,
                                                  info->negative_eigenvalues, o, &a, info);
                    bk_static_accept_stability(&R.stab, &R.sres, lam, out, info, log, &R.prev_lam, 1, refined,
                                               w->stability_csv);
                    /* the count may flicker at a nearly singular state: only
                     * a count above every one accepted so far is a new loss
                     * of stability */
                    if (info->negative_eigenvalues > max_negative)
                        max_negative = info->negative_eigenvalues;
                }
                bk_output_progress(out, (leg + (goal > 0.5 ? lam : 1.0 - lam)) / nleg, info->steps, lam,
                                   fabs(lam - lam_prev), a.iters, a.rnorm);
                continue;
            }
            memcpy(q, w->qsave, (size_t)nd * sizeof *q);
            memcpy(w->nu, w->nusave, (size_t)nc * sizeof *w->nu);
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
            int hopeless = st == NEWTON_SINGULAR && a.singular_at_start &&
                           !(o->predictor == BK_PREDICTOR_SECANT && have_prev);
            if (cuts_in_row >= o->max_cutbacks || hopeless) {
                char what[1000], incr[64];
                if (st == NEWTON_INADMISSIBLE)
                    snprintf(what, sizeof what, "the equilibrium reached is not physical: %s", inadm);
                else
                    bk_static_diagnose(what, sizeof what, st, &a, info->steps, info->negative_eigenvalues);
                char fm[400];
                size_t wl = strlen(what);
                /* the free motion, from the matrix at the last equilibrium */
                if ((st == NEWTON_SINGULAR || (isfinite(a.rcond) && a.rcond < ILL_RCOND)) &&
                    bk_static_residual(s, w, w->qsave, w->nusave, lam, 1) == 0 &&
                    bk_null_motion(s, w->Ax, w->qsave, &R.nl.ls, fm, sizeof fm) == 0)
                    snprintf(what + wl, sizeof what - wl, "; %s", fm);
                /* a near-mechanism (slack cable, rope, chain) under loads with a
                 * potential: the trust region may converge where Newton cannot */
                char why_not[8];
                /* the iteration limit reached with the last residual met: the increments had not
                 * settled yet (a low static.max_iterations), no sign of a mechanism */
                const int settling = st == NEWTON_MAXIT && a.rnorm <= a.rtol_abs;
                const char *hint = settling
                    ? "; the residual met its tolerance, the increments had not settled: raise "
                      "static.max_iterations"
                    : o->globalization == BK_GLOBALIZATION_NONE && st != NEWTON_INADMISSIBLE && !hopeless &&
                              !bk_static_trust_refusal(s, why_not, sizeof why_not)
                    ? "; for a near-mechanism (a slack cable, rope or chain) try [static] globalization = "
                      "\"trust_region\" with max_iterations = 2000" : "";
                if (a.iters > 0 && isfinite(a.dnorm))
                    snprintf(incr, sizeof incr, ", last increment %.3e (tolerance %.3e)", a.dnorm, a.utol_abs);
                else
                    incr[0] = 0;
                const int len = snprintf(info->message, sizeof info->message,
                         "static solve failed at step %d, load factor %.6g (last converged %.6g): %s; "
                         "residual %.3e (tolerance %.3e)%s after %d iteration%s, %d cut-back%s%s%s",
                         info->steps + 1, target, lam, what, a.rnorm, a.rtol_abs, incr, a.iters,
                         a.iters == 1 ? "" : "s", cuts_in_row, cuts_in_row == 1 ? "" : "s",
                         hopeless ? " (a tangent singular at the last equilibrium does not improve with smaller "
                                    "increments)"
                         : info->negative_eigenvalues > 0 && info->steps > 0
                             ? "; the last equilibrium was unstable (negative tangent eigenvalues): "
                               "a bifurcation or limit point was passed"
                             : "", hint);
                if (len >= (int)sizeof info->message)   /* (cut: said so) */
                    memcpy(info->message + sizeof info->message - 4, "...", 4);
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
                         "last increment %.3e after %d iterations%s",
                         info->steps + 1, target, lam, st == NEWTON_INADMISSIBLE ? inadm : bk_static_why(st),
                         a.rnorm, a.dnorm, a.iters,
                         info->negative_eigenvalues > 0 && info->steps > 0
                             ? "; the last equilibrium was unstable (negative tangent eigenvalues): the structure "
                               "buckles or snaps there (follow it with static.stable_path = true and an imperfection, "
                               "or run the scene as dynamic)" : "");
                goto done;
            }
            if (log)
                fprintf(log, "  cut-back at load factor %.6g (%s): new increment %.3g\n", target, bk_static_why(st), dlam);
        }
    }
    /* an equilibrium is not a result a structure reaches when it is unstable:
     * the events above say the path lost stability, this says the answer did */
    if (R.have_stab && info->negative_eigenvalues > 0) {
        double lc = NAN;
        for (int k = 0; k < info->nstability && !isfinite(lc); ++k)
            if (info->stability[k].neg_after > info->stability[k].neg_before)
                lc = info->stability[k].lam_critical;
        bk_warn(info, out->console, m->name, "the final equilibrium (load factor %.6g) is unstable: %d negative "
                "tangent eigenvalue%s (stability lost near load factor %.6g); the structure would buckle or snap "
                "away from it (e.g. a compressed branch), so it is not the state the loads lead to: follow the "
                "stable branch with static.stable_path = true and an imperfection, or run the scene as dynamic",
                lam, info->negative_eigenvalues, info->negative_eigenvalues == 1 ? "" : "s", lc);
    }
    rc = 0;
done:
    bk_static_end(&R, info, rc);
    return rc;
}

int bk_solve_static(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log)
{
    return load_control(s, q, out, info, log, 0);
}

int bk_run_static(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log)
{
    return load_control(s, q, out, info, log, 1);
}

static int runs_static(const bk_model *m)
{
    return m->analysis == BK_ANALYSIS_STATIC && m->stat.method == BK_METHOD_LOAD_CONTROL;
}

/* The load factor runs 0 -> 1 (load cycles: back and forth); a frame per load
 * step, which the step control may change. */
static void plan_static(const bk_model *m, bk_output_plan *p)
{
    p->end = m->stat.cycles == 0 ? 1.0 : 0.0;
    p->stability = m->stat.stability;
    p->room = m->stat.load_steps * (1 + 2 * m->stat.cycles) + 4;
}

const bk_analysis_module bk_analysis_static = {"static", runs_static, bk_run_static, plan_static};
