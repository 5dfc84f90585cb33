/* static_problem.c -- one static Newton attempt, the stability probes of
 * equilibria, and the set-up and tear-down of a static path (see
 * static_problem.h). */
#include "analysis/static_problem.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/quaternion.h"
#include "base/clock.h"
#include "solver/norms.h"

const char *bk_static_why(int code)
{
    switch (code) {
    case NEWTON_MAXIT: return "no convergence within the iteration limit";
    case NEWTON_NONFINITE: return "non-finite internal force or increment";
    case NEWTON_SINGULAR: return "singular tangent: is the beam constrained against rigid motion?";
    case NEWTON_DIVERGED: return "residual grew without bound";
    case NEWTON_LINERR: return "linear solver error";
    case NEWTON_UNSTABLE: return "the equilibrium reached is unstable (more negative tangent eigenvalues)";
    case NEWTON_INADMISSIBLE: return "the equilibrium reached is not physical (an element turned inside out)";
    case NEWTON_INTERRUPTED: return "interrupted";
    default: return "converged";
    }
}

/* What went wrong, for the failure message: a singular or numerically singular
 * tangent is named as such (with its likely causes) rather than as a missed
 * iteration limit. */
void bk_static_diagnose(char *buf, size_t n, int code, const attempt *a, int steps, int negative)
{
    if (code == NEWTON_SINGULAR || (isfinite(a->rcond) && a->rcond < ILL_RCOND)) {
        int exact = code == NEWTON_SINGULAR;
        int len = snprintf(buf, n, "%ssingular tangent (pivot ratio %.1e)%s", exact ? "" : "numerically ",
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
    snprintf(buf, n, "%s", bk_static_why(code));
}

/* Residual r(q, nu) at load factor lam into w->r, and the Newton matrix into
 * w->Ax when with_tangent.  Returns -1 on a non-finite internal force. */
int bk_static_residual(bk_system *s, work *w, const double *q, const double *nu, double lam, int with_tangent)
{
    const bk_model *m = s->m;
    double *Ax = with_tangent ? w->Ax : NULL;
    if (bk_assemble_internal(s, q, w->fint, Ax) != 0)
        return -1;
    const bk_path path = {.factor = lam, .x = lam};
    if (bk_assemble_interactions(s, q, &path, w->fint, Ax) != 0)
        return -1;
    for (int i = 0; i < m->ndof; ++i)
        if (s->eq[i] >= 0)
            w->r[s->eq[i]] = w->fint[i] - lam * w->fext[i];
    bk_assemble_constraints(s, q, nu, lam, w->r, Ax);
    return 0;
}

/* x = x0 + alpha dx on the free DOFs and multipliers, quaternions rescaled. */
void bk_static_step_to(const bk_system *s, const work *w, const double *q0, const double *nu0, const double *dx,
                    double alpha, double *q, double *nu)
{
    const bk_model *m = s->m;
    for (int i = 0; i < m->ndof; ++i)
        q[i] = s->eq[i] >= 0 ? q0[i] + alpha * dx[s->eq[i]] : q0[i];
    for (int c = 0; c < s->ncon; ++c)
        nu[c] = nu0[c] + alpha * dx[s->nfree + c];
    bk_quat_normalize(w->quat, w->nquat, q, NULL, 0);
}

int bk_sp_residual(void *ctx, int matrix, double *r, double *Ax, bk_nl_eval *ev)
{
    static_problem *p = ctx;
    bk_system *s = p->s;
    work *w = p->w;
    const bk_model *m = s->m;
    (void)r;                         /* w->r is the solver's buffer */
    w->Ax = Ax;                      /* the solver's, made anew when the pattern grew (nonlinear.h) */
    if (p->ref && p->ref->state == 3) {  /* w->Ax: still the reference state's matrix */
        bk_stability_check(p->ref->st, w->Ax, &p->ref->res);
        if (p->ref->res.ok)
            bk_stability_accept(p->ref->st);
        p->ref->state = 2;
    }
    if (bk_static_residual(s, w, p->q, w->nu, p->lam, matrix) != 0)
        return -1;
    if (matrix && p->ref && p->ref->state == 1)
        p->ref->state = 3;
    if (matrix && w->qtrial)
        bk_static_trust_shift(s, p->mu, Ax);          /* (after the reference state's check) */
    /* Every measure is invariant under a rigid rotation of the scene: field
     * norms, column-block norms, scalar products (norms.h). */
    ev->rnorm = bk_norm2(w->r, s->neq);
    ev->ref = fmax(fabs(p->lam) * bk_norm2(w->fext, m->ndof), bk_norm2(w->fint, m->ndof));
    ev->uscale = fmax(bk_norm_dof_max(w->norms, s, p->q, m->q0), 1e-6 * p->lscale);
    /* the energy scale of the increment besides its first correction: the
     * work of the load increment on the motion from the last equilibrium
     * (w->qsave) */
    double wload = 0.0;
    for (int i = 0; i < m->ndof; ++i)
        wload += (p->lam - p->lam_last) * w->fext[i] * (p->q[i] - w->qsave[i]);
    ev->escale = sqrt(fabs(wload));
    ev->cres = 0.0;
    return 0;
}

void bk_sp_update(void *ctx, const double *dx, double alpha)
{
    static_problem *p = ctx;
    bk_static_step_to(p->s, p->w, p->q, p->w->nu, dx, alpha, p->q, p->w->nu);
}

/* Rotation trust region: quaternion increments are rotations only to first
 * order; a step that changes a unit quaternion by more than ROT_STEP
 * (Euclidean norm of the 4 components: a rotation of about 17 degrees) is
 * shortened to that.  With it the geometrically exact beams take the load
 * steps the ANCF elements take (two turns of roll-up in 4 steps instead of
 * 24). */
#define ROT_STEP 0.15
double bk_sp_step_limit(void *ctx, const double *dx)
{
    static_problem *p = ctx;
    const bk_system *s = p->s;
    const work *w = p->w;
    double dpmax = 0.0;
    for (int k = 0; k < w->nquat; ++k) {
        double ss = 0.0;
        for (int i = 0; i < 4; ++i)
            ss += dx[s->eq[w->quat[k] + i]] * dx[s->eq[w->quat[k] + i]];
        dpmax = fmax(dpmax, sqrt(ss));
    }
    double a = dpmax > ROT_STEP ? ROT_STEP / dpmax : 1.0;
    double b = bk_interactions_step_limit(s, p->q, dx);     /* e.g. no contact gap crosses zero */
    a = b < a ? b : a;
    return w->qtrial ? bk_static_trust_step(p, dx, a) : a;
}

bk_nl_opts bk_static_nl_opts(const bk_static_opts *o)
{
    bk_nl_opts no = {.max_iter = o->max_iterations, .rtol = o->rtol, .utol = o->utol, .ctol = 0.0,
                     .accept_far_below = 0, .stagnation = 1, .divergence = 1, .reuse = 0};
    return no;
}

/* Newton iteration at load factor lam, from the state in q, w->nu.  Returns
 * a NEWTON_* code; every iteration is recorded in newton.csv (alpha: the
 * fraction of the Newton step taken, below 1 when the rotation trust region
 * shortened it). */
int bk_static_newton(bk_system *s, bk_nl *nl, work *w, double *q, double lam, double lam_last, attempt *a,
                  const bk_static_opts *o, double lscale, int step, reference_probe *ref)
{
    static_problem sp = {.s = s, .w = w, .q = q, .lam = lam, .lam_last = lam_last, .lscale = lscale,
                         .ref = ref && (ref->state == 1 || ref->state == 3) ? ref : NULL};
    bk_nl_problem p = {.ctx = &sp, .q = q, .residual = bk_sp_residual, .update = bk_sp_update,
                       .step_limit = bk_sp_step_limit};
    bk_nl_opts no = bk_static_nl_opts(o);
    bk_nl_row row = {.attempt = a->id, .step = step, .lam = lam};
    bk_nl_result res;
    /* joints nonlinear in q: start from the multipliers that balance the loads
     * (their geometric stiffness holds mechanisms like a hanging pendulum) */
    if (bk_constraints_nonlinear(s) > 0 && bk_static_residual(s, w, q, w->nu, lam, 0) == 0)
        bk_constraint_multipliers(s, q, lam, w->r, w->nu);
    bk_nl_solve(nl, &p, &no, 0.0, 1, &row, &res);
    a->iters = res.iters;
    a->rnorm = res.rnorm;
    a->dnorm = res.dnorm;
    a->ref = res.ref;
    a->rtol_abs = res.rtol_abs;
    a->utol_abs = res.utol_abs;
    a->rcond = res.rcond;
    a->residual_met = res.residual_met;
    a->singular_at_start = res.singular_at_start;
    a->signo = res.signo;
    return res.code;
}

/* Whether the Newton matrix depends on neither the load factor nor the
 * multipliers: no interaction whose Jacobian changes along the path (moments,
 * follower, distributed and tendon loads, loads with amplitudes, moving
 * contact, ...: interaction.h), no joint nonlinear in q, no constraint
 * coefficient that changes with the load factor.  The matrix at q0 of the
 * first load step's first Newton iteration is then, to the bit, the
 * reference state's. */
int bk_static_matrix_free_of_load(const bk_system *s)
{
    return !bk_interactions_tangent_on_path(s) && bk_constraints_nonlinear(s) == 0 && !bk_constraints_on_path(s);
}

/* Stability of the equilibrium q at load factor lam (not yet accepted):
 * the number of negative eigenvalues of the constrained tangent.  assembled:
 * w->Ax already holds the Newton matrix at q (a converged Newton solve ends
 * on the assembly of its last iterate), else it is assembled here. */
int bk_static_probe_stability(bk_stability *st, bk_system *s, work *w, const double *q, double lam,
                           int assembled, bk_stability_result *res)
{
    double t0 = bk_clock_s();
    int bad = !assembled && bk_static_residual(s, w, q, w->nu, lam, 1) != 0;
    st->t_spent += bk_clock_s() - t0;
    if (bad) {
        memset(res, 0, sizeof *res);
        return -1;
    }
    bk_stability_check(st, w->Ax, res);
    return res->ok ? res->negative : -1;
}

/* Accepts the probed equilibrium: when the count changed since the previous
 * one, records the event with the interpolated critical load factor.
 * matrix: the checker accepts the probed matrix too (0: it did already). */
void bk_static_accept_stability(bk_stability *st, const bk_stability_result *res, double lam, bk_output *out,
                             bk_run_info *info, FILE *log, double *prev_lam, int matrix, double refined,
                             FILE *table)
{
    const char *s_name = out->m->name;
    int before = info->negative_eigenvalues;
    info->negative_eigenvalues = res->ok ? res->negative : before;
    info->eig_min = res->eig_min;
    info->eig_max = res->eig_max;
    bk_stability_event *ev;
    if (res->ok && res->negative != before && info->steps >= 1 && (ev = bk_run_add_stability(info)) != NULL) {
        double t = isnan(refined) ? bk_stability_crossing(st, before) : 0.0;
        ev->step = info->steps;
        ev->lam_before = *prev_lam;
        ev->lam_after = lam;
        ev->neg_before = before;
        ev->neg_after = res->negative;
        ev->lam_critical = isnan(refined) ? *prev_lam + t * (lam - *prev_lam) : refined;
        if (out->m->stat.method != BK_METHOD_ARC_LENGTH)    /* arc-length: reported as critical points */
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
    if (res->ok && matrix)
        bk_stability_accept(st);
    *prev_lam = lam;
    if (table) {
        double t0 = bk_clock_s();
        bk_row r;                    /* step,load_factor,negative_eigenvalues,eig_min,eig_max */
        bk_output_row(out, &r, table);
        bk_row_int(&r, info->steps);
        bk_row_num(&r, lam);
        bk_row_int(&r, res->ok ? res->negative : -1);
        bk_row_e(&r, res->eig_min, 9);
        bk_row_e(&r, res->eig_max, 6);
        bk_output_row_end(out, &r, t0, 1);
    }
}


/* A row of newton.csv (the nonlinear solver's record of an iteration). */
static void newton_row(void *ctx, const bk_nl_row *row, int iter, double rnorm, double ref, double increment,
                       double alpha, double rcond)
{
    const work *w = ctx;
    double t0 = bk_clock_s();
    bk_row r;                        /* attempt,step,load_factor,iteration,residual,reference,increment,alpha,rcond */
    bk_output_row(w->out, &r, w->newton_csv);
    bk_row_int(&r, row->attempt);
    bk_row_int(&r, row->step);
    bk_row_num(&r, row->lam);
    bk_row_int(&r, iter);
    bk_row_e(&r, rnorm, 6);
    bk_row_e(&r, ref, 6);
    bk_row_e(&r, increment, 6);
    bk_row_g(&r, alpha, 6);
    bk_row_e(&r, rcond, 3);
    bk_output_row_end(w->out, &r, t0, 0);
}

static const bk_table_spec newton_csv =
    BK_TABLE("newton.csv", "statics", "attempt,step,load_factor,iteration,residual,reference,increment,alpha,rcond\n");
static const bk_table_spec stability_csv =
    BK_TABLE("stability.csv", "statics with `static.stability` (the default)",
             "step,load_factor,negative_eigenvalues,eig_min,eig_max\n");

int bk_static_begin(static_run *R, bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log,
                    int reference_on_first, int tables)
{
    const bk_model *m = s->m;
    const bk_static_opts *o = &m->stat;
    work *w = &R->w;
    int nd = m->ndof, nc = s->ncon > 0 ? s->ncon : 1;
    memset(R, 0, sizeof *R);
    R->ref.st = &R->stab;
    w->out = out;
    if (tables) {
        if (!(w->newton_csv = bk_output_table(out, &newton_csv, stderr))) {
            snprintf(info->message, sizeof info->message, "cannot write newton.csv");
            return 1;
        }
        if (o->stability &&
            !(w->stability_csv = bk_output_table(out, &stability_csv, stderr))) {
            snprintf(info->message, sizeof info->message, "cannot write stability.csv");
            return 1;
        }
    }
    w->fint = calloc((size_t)nd, sizeof(double));
    w->fext = calloc((size_t)nd, sizeof(double));
    w->qsave = calloc((size_t)nd, sizeof(double));
    w->qprev = calloc((size_t)nd, sizeof(double));
    w->nu = calloc((size_t)nc, sizeof(double));
    w->nusave = calloc((size_t)nc, sizeof(double));
    w->nuprev = calloc((size_t)nc, sizeof(double));
    if (!w->fint || !w->fext || !w->qsave || !w->qprev || !w->nu || !w->nusave || !w->nuprev) {
        snprintf(info->message, sizeof info->message, "out of memory");
        return 1;
    }
    if (s->neq == 0) {
        snprintf(info->message, sizeof info->message, "every DOF is fixed: nothing to solve");
        return 1;
    }
    R->have_nl = 1;
    if (bk_nl_init(&R->nl, s, info->message, sizeof info->message) != 0)
        return 1;
    if (w->newton_csv) {
        R->nl.on_iteration = newton_row;
        R->nl.iteration_ctx = w;
    }
    w->r = R->nl.r, w->dx = R->nl.dx, w->Ax = R->nl.Ax, w->norms = &R->nl.norms;
    w->quat = bk_quat_list(s, &w->nquat);
    if (w->nquat < 0 || bk_checks_init(&R->chk, s) != 0) {
        snprintf(info->message, sizeof info->message, "out of memory");
        return 1;
    }
    if (o->stability) {
        if (bk_stability_init(&R->stab, s, &R->nl.ls) != 0) {
            snprintf(info->message, sizeof info->message, "out of memory (stability analysis)");
            return 1;
        }
        R->have_stab = 1;
    }
    if (o->globalization == BK_GLOBALIZATION_TRUST_REGION) {
        if (bk_static_trust_refusal(s, info->message, sizeof info->message))
            return 1;
        w->qtrial = calloc((size_t)nd, sizeof(double));
        w->nutrial = calloc((size_t)nc, sizeof(double));
        if (!w->qtrial || !w->nutrial) {
            snprintf(info->message, sizeof info->message, "out of memory");
            return 1;
        }
    }
    memcpy(q, m->q0, (size_t)nd * sizeof *q);
    bk_external_load(s, w->fext);

    /* Constraint scaling: the mean magnitude of the tangent's diagonal at the
     * reference state (no allocation: reuses Ax). */
    if (s->ncon > 0) {
        bk_assemble_internal(s, q, w->fint, w->Ax);
        double sum = 0.0;
        int cnt = 0;
        for (int j = 0; j < s->nfree; ++j)
            for (int k = s->Ap[j]; k < s->Ap[j + 1]; ++k)
                if (s->Ai[k] == j) {
                    sum += fabs(w->Ax[k]);
                    cnt++;
                }
        s->cscale = cnt && sum > 0.0 ? sum / cnt : 1.0;
    }

    if (R->have_stab) {
        double t0 = bk_clock_s();
        R->ref_rnorm = bk_static_residual(s, w, q, w->nu, 0.0, 0) == 0 ? bk_norm2(w->r, s->neq) : 0.0;
        R->stab.t_spent += bk_clock_s() - t0;
    }
    bk_interactions_accept(s, q, &(bk_path){.factor = 0.0, .x = 0.0});   /* the lagged states (friction) */
    bk_output_forces(out, s, 0, 0.0, q, NULL, NULL, w->nu);
    bk_output_step(out, 0, 0.0, q);
    R->prev_lam = 0.0;
    if (R->have_stab && reference_on_first && bk_static_matrix_free_of_load(s))
        R->ref.state = 1;                /* on the first Newton matrix (at q0) */
    else if (R->have_stab) {
        bk_static_probe_stability(&R->stab, s, w, q, 0.0, 0, &R->sres);
        bk_static_accept_stability(&R->stab, &R->sres, 0.0, out, info, log, &R->prev_lam, 1, NAN, w->stability_csv);
    }
    return 0;
}

void bk_static_end(static_run *R, bk_run_info *info, int rc)
{
    work *w = &R->w;
    info->converged = rc == 0;
    info->factorizations = R->nl.ls.nfactor;
    info->analyses = R->nl.ls.nanalyze;
    info->stability_checked = R->have_stab;
    if (R->have_nl)
        bk_nl_free(&R->nl);
    if (R->have_stab) {
        info->stability_s = R->stab.t_spent;
        bk_stability_free(&R->stab);
    }
    free(w->fint);
    free(w->fext);
    free(w->qsave);
    free(w->qprev);
    free(w->nu);
    free(w->nusave);
    free(w->nuprev);
    free(w->qtrial);
    free(w->nutrial);
    free(w->quat);
    bk_checks_free(&R->chk);
}
