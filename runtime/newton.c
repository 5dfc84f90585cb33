/* newton.c -- load-stepped Newton iteration for statics. */
#include "newton.h"

#include <float.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>

#include "checks.h"
#include "clock.h"
#include "interrupt.h"
#include "linsolve.h"
#include "nonlinear.h"
#include "loads.h"
#include "norms.h"
#include "quaternion.h"
#include "stability.h"

typedef struct work {
    double *fint, *fext, *r, *dx, *Ax, *qsave, *nu, *nusave;
    double *qprev, *nuprev;          /* the equilibrium before the last one (predictor) */
    int *quat;                       /* first global DOF of each free nodal quaternion */
    int nquat;
    const bk_norms *norms;           /* rotation-invariant measures (the solver's) */
} work;

/* One Newton solve: its outcome and counters. */
typedef struct attempt {
    int id;                          /* attempt number over the run (newton.csv)  */
    int iters;
    double rnorm, dnorm, ref;
    double rtol_abs;                 /* the residual tolerance of the last iteration */
    double rcond;                    /* pivot ratio (min/max |u_jj|) of the last factorization */
    int residual_met;                /* the residual met its tolerance at some iteration */
    int singular_at_start;           /* NEWTON_SINGULAR at iteration 0               */
    int signo;                       /* NEWTON_INTERRUPTED: the signal */
} attempt;

/* Below this pivot ratio the tangent is singular to working precision: Newton
 * increments are meaningless in its near-null directions. */
#define ILL_RCOND BK_ILL_RCOND

enum { NEWTON_OK = BK_NL_OK, NEWTON_MAXIT = BK_NL_MAXIT, NEWTON_NONFINITE = BK_NL_NONFINITE,
       NEWTON_SINGULAR = BK_NL_SINGULAR, NEWTON_DIVERGED = BK_NL_DIVERGED, NEWTON_LINERR = BK_NL_LINERR,
       NEWTON_INTERRUPTED = BK_NL_INTERRUPTED, NEWTON_UNSTABLE = BK_NL_NCODES };

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
    bk_assemble_loads(s, q, lam, w->fint, Ax);
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

/* The stability check of the reference state made on the first Newton matrix
 * of the first load step, when that matrix is the reference state's
 * (matrix_free_of_load): one assembly fewer.  state: 1 pending, 3 its matrix
 * made (checked at the next residual, before the matrix is made again: after
 * the solver has factored it, so that the factorization, not the check, is
 * the first to touch the band LU's storage, which the check borrows as
 * scratch: stability.h), 2 made (res) and its matrix accepted at once (the
 * path starts there), its row and counts recorded after the step. */
typedef struct reference_probe {
    bk_stability *st;
    bk_stability_result res;
    int state;
} reference_probe;

/* The static problem for the nonlinear solver (nonlinear.h): the residual at
 * load factor lam, the update of q and the multipliers, the rotation trust
 * region.
 *
 * A line search on the energy slope s(alpha) = dx . r(x + alpha dx), tried as
 * a retry before cutting an increment back, rescued none of the hard cases
 * (report/hard.py: two-turn roll-ups, one-step cantilevers, silicone sag):
 * their failures are the alternation between membrane and bending residuals of
 * slender beams, which the rotation trust region below and the load increment
 * address.  It was removed rather than kept as an option that does nothing. */
typedef struct static_problem {
    bk_system *s;
    work *w;
    double *q;
    double lam, lam_last;            /* the load factor sought, the last equilibrium's */
    double lscale;
    reference_probe *ref;            /* NULL, or a pending check of the reference state at q */
} static_problem;

static int sp_residual(void *ctx, int matrix, double *r, double *Ax, bk_nl_eval *ev)
{
    static_problem *p = ctx;
    bk_system *s = p->s;
    work *w = p->w;
    const bk_model *m = s->m;
    (void)r, (void)Ax;               /* w->r, w->Ax are the solver's buffers */
    if (p->ref && p->ref->state == 3) {  /* w->Ax: still the reference state's matrix */
        bk_stability_check(p->ref->st, w->Ax, &p->ref->res);
        if (p->ref->res.ok)
            bk_stability_accept(p->ref->st);
        p->ref->state = 2;
    }
    if (residual(s, w, p->q, w->nu, p->lam, matrix) != 0)
        return -1;
    if (matrix && p->ref && p->ref->state == 1)
        p->ref->state = 3;
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

static void sp_update(void *ctx, const double *dx, double alpha)
{
    static_problem *p = ctx;
    step_to(p->s, p->w, p->q, p->w->nu, dx, alpha, p->q, p->w->nu);
}

/* Rotation trust region: quaternion increments are rotations only to first
 * order; a step that changes a unit quaternion by more than ROT_STEP
 * (Euclidean norm of the 4 components: a rotation of about 17 degrees) is
 * shortened to that.  With it the geometrically exact beams take the load
 * steps the ANCF elements take (two turns of roll-up in 4 steps instead of
 * 24). */
#define ROT_STEP 0.15
static double sp_step_limit(void *ctx, const double *dx)
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
    return dpmax > ROT_STEP ? ROT_STEP / dpmax : 1.0;
}

static bk_nl_opts static_nl_opts(const bk_static_opts *o)
{
    bk_nl_opts no = {.max_iter = o->max_iter, .rtol = o->rtol, .utol = o->utol, .ctol = 0.0,
                     .accept_far_below = 0, .stagnation = 1, .divergence = 1, .reuse = 0};
    return no;
}

/* Newton iteration at load factor lam, from the state in q, w->nu.  Returns
 * a NEWTON_* code; every iteration is recorded in newton.csv (alpha: the
 * fraction of the Newton step taken, below 1 when the rotation trust region
 * shortened it). */
static int newton(bk_system *s, bk_nl *nl, work *w, double *q, double lam, double lam_last, attempt *a,
                  const bk_static_opts *o, double lscale, int step, reference_probe *ref)
{
    static_problem sp = {.s = s, .w = w, .q = q, .lam = lam, .lam_last = lam_last, .lscale = lscale,
                         .ref = ref && (ref->state == 1 || ref->state == 3) ? ref : NULL};
    bk_nl_problem p = {.ctx = &sp, .q = q, .residual = sp_residual, .update = sp_update,
                       .step_limit = sp_step_limit};
    bk_nl_opts no = static_nl_opts(o);
    bk_nl_row row = {.attempt = a->id, .step = step, .lam = lam};
    bk_nl_result res;
    /* joints nonlinear in q: start from the multipliers that balance the loads
     * (their geometric stiffness holds mechanisms like a hanging pendulum) */
    if (s->m->nnlcon > 0 && residual(s, w, q, w->nu, lam, 0) == 0)
        bk_constraint_multipliers(s, q, lam, w->r, w->nu);
    bk_nl_solve(nl, &p, &no, 0.0, 1, &row, &res);
    a->iters = res.iters;
    a->rnorm = res.rnorm;
    a->dnorm = res.dnorm;
    a->ref = res.ref;
    a->rtol_abs = res.rtol_abs;
    a->rcond = res.rcond;
    a->residual_met = res.residual_met;
    a->singular_at_start = res.singular_at_start;
    a->signo = res.signo;
    return res.code;
}

/* Whether the Newton matrix depends on neither the load factor nor the
 * multipliers: no load with a stiffness or a varying factor (moments, follower,
 * distributed and tendon loads, gravity with an amplitude, forces with one), no
 * joint nonlinear in q, no constraint coefficient that changes with the load
 * factor.  The matrix at q0 of the first load step's first Newton iteration is
 * then, to the bit, the reference state's. */
static int matrix_free_of_load(const bk_system *s)
{
    const bk_model *m = s->m;
    if (m->nmoment > 0 || m->ndload > 0 || m->ntendon > 0 || m->nnlcon > 0 || (m->has_gravity && m->gravity_amp))
        return 0;
    for (int i = 0; i < m->nforce; ++i)
        if (m->forces[i].amp >= 0 || m->forces[i].follower)
            return 0;
    for (int c = 0; c < m->nlincon; ++c) {
        const bk_lincon *lc = &m->lincons[c];
        if (lc->kappa == 0.0 || (lc->rate == 0.0 && lc->amp == 0.0 && !lc->ampl))
            continue;                    /* the angle is constant: so are the coefficients */
        for (int k = 0; k < lc->nterm; ++k)
            if (lc->cc[k] != 0.0 || lc->cs[k] != 0.0)
                return 0;
    }
    return 1;
}

/* Stability of the equilibrium q at load factor lam (not yet accepted):
 * the number of negative eigenvalues of the constrained tangent.  assembled:
 * w->Ax already holds the Newton matrix at q (a converged Newton solve ends
 * on the assembly of its last iterate), else it is assembled here. */
static int probe_stability(bk_stability *st, bk_system *s, work *w, const double *q, double lam,
                           int assembled, bk_stability_result *res)
{
    double t0 = bk_clock_s();
    int bad = !assembled && residual(s, w, q, w->nu, lam, 1) != 0;
    st->t_spent += bk_clock_s() - t0;
    if (bad) {
        memset(res, 0, sizeof *res);
        return -1;
    }
    bk_stability_check(st, w->Ax, res);
    return res->ok ? res->negative : -1;
}

/* Accepts the probed equilibrium: when the count changed since the previous
 * one, records the event with the critical load factor `refined` or, when it
 * is NaN, the interpolated one.  matrix: the checker accepts the probed matrix
 * too (0: it did already). */
static void accept_stability(bk_stability *st, const bk_stability_result *res, double lam, bk_output *out,
                             bk_run_info *info, FILE *log, double *prev_lam, int matrix, double refined)
{
    const char *s_name = out->m->name;
    int before = info->negative_eigenvalues;
    info->negative_eigenvalues = res->ok ? res->negative : before;
    info->eig_min = res->eig_min;
    info->eig_max = res->eig_max;
    if (res->ok && res->negative != before && info->steps >= 1 && info->nstability < BK_MAX_EVENTS) {
        double t = isnan(refined) ? bk_stability_crossing(st, before) : 0.0;
        bk_stability_event *ev = &info->stability[info->nstability++];
        ev->step = info->steps;
        ev->lam_before = *prev_lam;
        ev->lam_after = lam;
        ev->neg_before = before;
        ev->neg_after = res->negative;
        ev->lam_critical = isnan(refined) ? *prev_lam + t * (lam - *prev_lam) : refined;
        if (!out->m->stat.arc_length)    /* arc-length: reported as critical points */
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
    bk_output_stability(out, info->steps, lam, res->ok ? res->negative : -1, res->eig_min, res->eig_max);
}

/* Load control passed a critical point inside the increment from lam_lo
 * (the equilibrium w->qprev, w->nuprev, `before` negative eigenvalues) to
 * lam_hi (q, w->nu, the checker's last check): the load factor where the
 * count first changes, by bisection on equilibria re-solved from the last one
 * below it, to BK_REFINE_TOL of the load factor.  The interpolation of
 * accept_stability assumes a tangent linear in the load: across a large
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
        int rc = newton(s, nl, w, qt, mid, lo, &b, o, m->length_scale, info->steps, NULL);
        info->newton_iterations += b.iters;
        if (rc == NEWTON_INTERRUPTED)
            raise(b.signo);              /* pending again (blocked): the load loop stops on it */
        bk_stability_result r;
        if (rc != NEWTON_OK || probe_stability(st, s, w, qt, mid, 1, &r) < 0)
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
    probe_stability(st, s, w, q, lam_hi, 0, &r);
    if (xs) {
        memcpy(st->x, xs, n * sizeof *xs);
        memcpy(st->xmax, xs + n, n * sizeof *xs);
    }
    st->have_vec = have_vec, st->have_vmax = have_vmax;
done:
    free(ql), free(qt), free(nul), free(xs);
    return crit;
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

/* ---- Arc-length continuation (static.method = "arc_length") ----
 *
 * The unknowns x (free DOFs and multipliers) and the load factor lam follow
 * the equilibrium path r(x, lam) = 0 in steps of arc length dl:
 *     |x - x_n|_W^2 + psi^2 (lam - lam_n)^2 = dl^2
 * (Crisfield).  W weighs the free DOFs: 1 for positions, L^2 for the
 * dimensionless fields (position gradients, quaternions; L the model's length
 * scale), so that a rotation counts as the motion it causes over the model, 0
 * for multipliers; psi = 0 (cylindrical) or psi^2 = t0' W t0 (spherical: a
 * unit load factor counts as the linear displacement at full load, t0 the
 * tangent at the start).  Each Newton correction is bordered: with
 * K dx_r = -r and K t = -dr/dlam, dx = dx_r + dlam t with dlam from the
 * constraint (the root nearer the current increment; where the quadratic has
 * none, the dlam closest to satisfying it).  The predictor goes along the
 * tangent, oriented so that it makes an acute angle with the last increment:
 * the path never turns back, and the load factor may exceed 1 and go down.
 * The arc length follows the iteration count (sqrt(arc_iterations / iters),
 * in [0.5, 2], at most 8 times the first or 0.05 of the model length), is
 * halved on failure, and the first is the arc of a load increment
 * target / load_steps along the tangent.  With static.branch_switch the step
 * after the first bifurcation starts along the null vector of the tangent
 * (the eigenvector of its eigenvalue nearest zero) with the load factor kept:
 * the arc-length sphere about the equilibrium past the bifurcation meets the
 * secondary branch, and the path follows it from there. */
typedef struct arc_ctx {
    static_problem sp;               /* the residual, the update of q and nu; sp.lam: the iterate's */
    work *w;
    const double *W;                 /* [neq] weights of the constraint */
    const int *fdof;                 /* [nfree] equation -> DOF */
    double *rl, *t, *tmp, *fol;      /* [neq] x 3, [ndof] */
    double lam0;                     /* the load factor at the start of the step (x_n: w->qsave) */
    double dl, psi2;
    double pending;                  /* the load-factor part of the last correction */
} arc_ctx;

/* dr/dlam at (q, nu, lam) into rl[neq]: the dead and follower loads, and, by
 * central differences in lam, the loads of loads.c (amplitudes, follower and
 * distributed loads, tendons) and the load-factor dependence of rheonomic
 * constraints. */
static void load_derivative(bk_system *s, work *w, const double *q, double lam, double *rl, double *fol,
                            double *tmp)
{
    const bk_model *m = s->m;
    memset(fol, 0, (size_t)m->ndof * sizeof *fol);
    bk_assemble_follower(s, q, 1.0, fol, NULL);
    for (int i = 0; i < m->ndof; ++i)
        if (s->eq[i] >= 0)
            rl[s->eq[i]] = fol[i] - w->fext[i];
    for (int c = 0; c < s->ncon; ++c)
        rl[s->nfree + c] = 0.0;
    {
        double d = 1e-6 * fmax(1.0, fabs(lam));
        for (int sgn = 1; sgn >= -1; sgn -= 2) {
            memset(fol, 0, (size_t)m->ndof * sizeof *fol);
            bk_assemble_loads(s, q, lam + sgn * d, fol, NULL);
            for (int i = 0; i < m->ndof; ++i)
                if (s->eq[i] >= 0)
                    rl[s->eq[i]] += sgn * fol[i] / (2.0 * d);
        }
    }
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

static int arc_augment(void *ctx, bk_linsolver *ls, double *dx)
{
    arc_ctx *c = ctx;
    bk_system *s = c->sp.s;
    const double *q = c->sp.q, *q0 = c->w->qsave;
    load_derivative(s, c->w, q, c->sp.lam, c->rl, c->fol, c->tmp);
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

static void arc_update(void *ctx, const double *dx, double alpha)
{
    arc_ctx *c = ctx;
    sp_update(&c->sp, dx, alpha);
    c->sp.lam += alpha * c->pending;
}

static double arc_step_limit(void *ctx, const double *dx)
{
    arc_ctx *c = ctx;
    return sp_step_limit(&c->sp, dx);
}

/* The tangent at the equilibrium (q, w->nu, lam): t = -K^-1 dr/dlam into c->t;
 * its weighted square length into *tWt.  Returns 0, or a BK_NL_* code. */
static int arc_tangent(bk_system *s, bk_nl *nl, arc_ctx *c, double *q, double lam, double *tWt)
{
    if (residual(s, c->w, q, c->w->nu, lam, 1) != 0)
        return BK_NL_NONFINITE;
    int st = bk_lin_factor(&nl->ls, nl->Ax);
    if (st != BK_LIN_OK)
        return st == BK_LIN_SINGULAR ? BK_NL_SINGULAR : BK_NL_LINERR;
    load_derivative(s, c->w, q, lam, c->rl, c->fol, c->tmp);
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
 * iteration.  On success q, w->nu, c->sp.lam hold the new equilibrium; on
 * failure the start is restored.  w->qsave, w->nusave: the start. */
static int arc_step(bk_system *s, bk_nl *nl, arc_ctx *c, double *q, double lam0, double sigma, double tWt,
                    double dl, const bk_static_opts *o, attempt *a, int step, bk_run_info *info, double lam_scale)
{
    work *w = c->w;
    const bk_model *m = s->m;
    memcpy(w->qsave, q, (size_t)m->ndof * sizeof *q);
    memcpy(w->nusave, w->nu, (size_t)(s->ncon > 0 ? s->ncon : 1) * sizeof *q);
    double dlp = sigma * dl / sqrt(tWt + lam_scale * c->psi2);
    step_to(s, w, q, w->nu, c->t, dlp, q, w->nu);
    c->lam0 = lam0;
    c->dl = dl;
    c->sp.lam = lam0 + lam_scale * dlp;
    c->sp.lam_last = lam0;
    c->pending = 0.0;
    bk_nl_problem p = {.ctx = c, .q = q, .residual = sp_residual, .augment = arc_augment, .update = arc_update,
                       .step_limit = arc_step_limit};
    /* sp_residual reads the static_problem at the start of the context */
    bk_nl_opts no = static_nl_opts(o);
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
static void sensor_displacements(const bk_model *m, const double *q, bk_critical_point *cp)
{
    cp->nsensor = m->nsensor < BK_CRIT_SENSORS ? m->nsensor : BK_CRIT_SENSORS;
    for (int k = 0; k < cp->nsensor; ++k) {
        double p[3], p0[3];
        bk_eval_point(m, q, m->sensors[k].elem, m->sensors[k].xi, p, NULL);
        bk_eval_point(m, m->q0, m->sensors[k].elem, m->sensors[k].xi, p0, NULL);
        for (int i = 0; i < 3; ++i)
            cp->u[k][i] = p[i] - p0[i];
    }
}

static double max_sensor_displacement(const bk_model *m, const double *q)
{
    bk_critical_point cp;
    double d = 0.0;
    sensor_displacements(m, q, &cp);
    for (int k = 0; k < cp.nsensor; ++k)
        d = fmax(d, sqrt(cp.u[k][0] * cp.u[k][0] + cp.u[k][1] * cp.u[k][1] + cp.u[k][2] * cp.u[k][2]));
    return d;
}

/* The path state of one equilibrium (for the bisection of a limit point). */
typedef struct arc_point {
    double *q, *nu;
    double lam;
} arc_point;

static void arc_save(const bk_system *s, const work *w, const double *q, double lam, arc_point *p)
{
    memcpy(p->q, q, (size_t)s->m->ndof * sizeof *q);
    memcpy(p->nu, w->nu, (size_t)(s->ncon > 0 ? s->ncon : 1) * sizeof *q);
    p->lam = lam;
}

static void arc_restore(const bk_system *s, work *w, double *q, double *lam, const arc_point *p)
{
    memcpy(q, p->q, (size_t)s->m->ndof * sizeof *q);
    memcpy(w->nu, p->nu, (size_t)(s->ncon > 0 ? s->ncon : 1) * sizeof *q);
    *lam = p->lam;
}

/* Orientation of the tangent c->t at the equilibrium q (lam) along the path
 * coming from (q_from, lam_from): +1 when the load factor grows along it. */
static double arc_orientation(const bk_system *s, const arc_ctx *c, const double *q, double lam,
                              const double *q_from, double lam_from)
{
    double d = c->psi2 * (lam - lam_from);
    for (int j = 0; j < s->nfree; ++j)
        d += c->W[j] * (q[c->fdof[j]] - q_from[c->fdof[j]]) * c->t[j];
    return d >= 0.0 ? 1.0 : -1.0;
}

/* Bisection on the arc length from the equilibrium A (orientation sigma_a,
 * the load factor growing when sigma_a > 0) for the limit point within the
 * arc dl: the arc s at which the orientation of the load factor turns.
 * Returns the extreme load factor found (the state there in best), the
 * number of bisection solves in *nsolve. */
#define ARC_BISECTIONS 14
#define ARC_NEAR 3
static double arc_bisect_limit(bk_system *s, bk_nl *nl, arc_ctx *c, double *q, const arc_point *A,
                               double sigma_a, double dl, const bk_static_opts *o, attempt *a, int step,
                               bk_run_info *info, arc_point *best, double lam_b)
{
    double lo = 0.0, hi = dl, lam_best = sigma_a > 0.0 ? fmax(A->lam, lam_b) : fmin(A->lam, lam_b);
    int have_best = 0;
    for (int k = 0; k < ARC_BISECTIONS; ++k) {
        double mid = 0.5 * (lo + hi), lam = A->lam, tWt;
        arc_restore(s, c->w, q, &lam, A);
        if (arc_tangent(s, nl, c, q, lam, &tWt) != BK_NL_OK)
            break;
        if (arc_step(s, nl, c, q, lam, sigma_a, tWt, mid, o, a, step, info, 1.0) != BK_NL_OK)
            break;
        double lam_m = c->sp.lam;
        if (sigma_a > 0.0 ? lam_m >= lam_best : lam_m <= lam_best) {
            lam_best = lam_m;
            arc_save(s, c->w, q, lam_m, best);
            have_best = 1;
        }
        if (arc_tangent(s, nl, c, q, lam_m, &tWt) != BK_NL_OK)
            break;
        double sg = arc_orientation(s, c, q, lam_m, A->q, A->lam);
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
static void branch_direction(const bk_system *s, const bk_stability *st, arc_ctx *c, double *tWt)
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

/* ---- Closed loops: a return to a visited point of the path ----
 * Every accepted equilibrium is kept: its load factor, the displacements of
 * the first sensors and, while the kept states fit in ARC_PATH_BUDGET doubles,
 * the full state q.  After each step the new point is compared with every
 * kept segment [k, k+1] of the path that ends at least two steps and four
 * tolerances (below) of arc length before it.
 * First cheaply: the load factor and each sensor's displacement inside the
 * segment's range widened by a quarter of the change over the last step and
 * over the segment.  Then, for those candidates, the full state: the distance
 * from the new point to the segment in the metric of the arc-length
 * constraint (W, psi), quaternions compared as the rotations they stand for
 * (normalised, p and -p alike).  Below a quarter of the larger of the last
 * arc and the segment's length, the path is back where it was: a closed
 * loop, reported with the segment and stopped. */
#define ARC_PATH_BUDGET (1L << 24)
typedef struct arc_path {
    int n, cap, ns, nd, nquat;       /* points, capacity, sensors, DOFs, quaternion nodes */
    double *lam, *arc, *u, *q;       /* [cap], [cap] (arc length from the start), [cap][3 ns], [cap][nd] (the first nq) */
    int nq, qcap;                    /* points whose state is kept, room for them */
    int *quat;                       /* [nquat][4] DOFs of each quaternion node */
    char *isq;                       /* [nd] 1: a DOF of a quaternion */
} arc_path;

static void arc_path_free(arc_path *p)
{
    free(p->lam), free(p->arc), free(p->u), free(p->q), free(p->quat), free(p->isq);
}

/* Keep the point (q, lam) at the arc length arc from the start; 0, or -1 when out of memory. */
static int arc_path_push(arc_path *p, const bk_model *m, const double *q, double lam, double arc)
{
    if (p->n == p->cap) {
        int cap = p->cap ? 2 * p->cap : 64;
        double *l = realloc(p->lam, (size_t)cap * sizeof *l);
        if (!l)
            return -1;
        p->lam = l;
        double *ar = realloc(p->arc, (size_t)cap * sizeof *ar);
        if (!ar)
            return -1;
        p->arc = ar;
        double *u = realloc(p->u, (size_t)cap * 3 * (size_t)(p->ns > 0 ? p->ns : 1) * sizeof *u);
        if (!u)
            return -1;
        p->u = u;
        p->cap = cap;
    }
    if (p->nq == p->n && (long)(p->nq + 1) * p->nd <= ARC_PATH_BUDGET) {
        if (p->nq == p->qcap) {      /* doubling, within the budget; out of memory: no more states kept */
            long cap = p->qcap ? 2L * p->qcap : 64;
            if (cap * p->nd > ARC_PATH_BUDGET)
                cap = ARC_PATH_BUDGET / (p->nd > 0 ? p->nd : 1);
            double *s = realloc(p->q, (size_t)cap * (size_t)p->nd * sizeof *s);
            if (s)
                p->q = s, p->qcap = (int)cap;
        }
        if (p->nq < p->qcap) {
            memcpy(p->q + (size_t)p->nq * p->nd, q, (size_t)p->nd * sizeof *q);
            p->nq++;
        }
    }
    bk_critical_point cp;
    sensor_displacements(m, q, &cp);
    for (int k = 0; k < p->ns; ++k)
        for (int i = 0; i < 3; ++i)
            p->u[(size_t)p->n * 3 * p->ns + 3 * k + i] = cp.u[k][i];
    p->arc[p->n] = arc;
    p->lam[p->n++] = lam;
    return 0;
}

/* The cheap test of the point (u: its sensor displacements, lam) against the
 * segment [k, k+1]; du, dlam: the change over the last step. */
static int arc_path_near(const arc_path *p, int k, const double *u, double lam, const double *du, double dlam)
{
    double l0 = p->lam[k], l1 = p->lam[k + 1], tl = 0.25 * (fabs(dlam) + fabs(l1 - l0)) + 1e-12 * fabs(lam);
    if (lam < fmin(l0, l1) - tl || lam > fmax(l0, l1) + tl)
        return 0;
    const double *u0 = p->u + (size_t)k * 3 * p->ns, *u1 = u0 + 3 * p->ns;
    for (int s = 0; s < p->ns; ++s) {
        double dn = 0.0, ds = 0.0;
        for (int i = 0; i < 3; ++i) {
            double d = u1[3 * s + i] - u0[3 * s + i];
            dn += du[3 * s + i] * du[3 * s + i], ds += d * d;
        }
        double tu = 0.25 * (sqrt(dn) + sqrt(ds)) + 1e-12;
        for (int i = 0; i < 3; ++i) {
            double a = u0[3 * s + i], b = u1[3 * s + i], x = u[3 * s + i];
            if (x < fmin(a, b) - tu || x > fmax(a, b) + tu)
                return 0;
        }
    }
    return 1;
}

/* The full test: the weighted distance of (q, lam) from the segment [k, k+1]
 * of kept states (k + 1 < p->nq) into *dist, the segment's length into *len. */
static void arc_path_distance(const arc_path *p, const bk_system *s, const arc_ctx *c, double L2, int k,
                              const double *q, double lam, double *dist, double *len)
{
    const double *a = p->q + (size_t)k * p->nd, *b = a + p->nd;
    double xa = c->psi2 * (lam - p->lam[k]) * (lam - p->lam[k]);
    double ba = c->psi2 * (p->lam[k + 1] - p->lam[k]) * (p->lam[k + 1] - p->lam[k]);
    double xb = c->psi2 * (lam - p->lam[k]) * (p->lam[k + 1] - p->lam[k]);
    for (int j = 0; j < s->nfree; ++j) {
        int i = c->fdof[j];
        if (p->isq[i] || c->W[j] == 0.0)
            continue;
        double dx = q[i] - a[i], db = b[i] - a[i];
        xa += c->W[j] * dx * dx, ba += c->W[j] * db * db, xb += c->W[j] * dx * db;
    }
    for (int g = 0; g < p->nquat; ++g) {
        const int *d = p->quat + 4 * g;
        double nx = 0.0, na = 0.0, nb = 0.0, sa = 0.0;
        for (int i = 0; i < 4; ++i)
            nx += q[d[i]] * q[d[i]], na += a[d[i]] * a[d[i]], nb += b[d[i]] * b[d[i]], sa += q[d[i]] * a[d[i]];
        nx = 1.0 / sqrt(nx), na = (sa < 0.0 ? -1.0 : 1.0) / sqrt(na), nb = (sa < 0.0 ? -1.0 : 1.0) / sqrt(nb);
        for (int i = 0; i < 4; ++i) {
            double dx = q[d[i]] * nx - a[d[i]] * na, db = b[d[i]] * nb - a[d[i]] * na;
            xa += L2 * dx * dx, ba += L2 * db * db, xb += L2 * dx * db;
        }
    }
    double t = ba > 0.0 ? fmin(fmax(xb / ba, 0.0), 1.0) : 0.0;
    *dist = sqrt(fmax(xa - 2.0 * t * xb + t * t * ba, 0.0));
    *len = sqrt(ba);
}

static int arc_length(bk_system *s, bk_nl *nl, work *w, double *q, bk_output *out, bk_run_info *info, FILE *log,
                      bk_stability *stab, int have_stab, bk_checks *chk)
{
    const bk_model *m = s->m;
    const bk_static_opts *o = &m->stat;
    int nd = m->ndof, ne = s->neq, nc = s->ncon > 0 ? s->ncon : 1, rc = 1;
    bk_critical_point cand[BK_MAX_EVENTS];          /* bifurcation candidates */
    int cand_neg[BK_MAX_EVENTS][2], ncand = 0;
    arc_ctx c = {.sp = {.s = s, .w = w, .q = q, .lscale = m->length_scale}, .w = w};
    double *W = calloc((size_t)ne, sizeof *W);
    int *fdof = calloc((size_t)(s->nfree > 0 ? s->nfree : 1), sizeof *fdof);
    c.rl = calloc((size_t)ne, sizeof *c.rl), c.t = calloc((size_t)ne, sizeof *c.t);
    c.tmp = calloc((size_t)ne, sizeof *c.tmp), c.fol = calloc((size_t)nd, sizeof *c.fol);
    arc_point A = {calloc((size_t)nd, sizeof(double)), calloc((size_t)nc, sizeof(double)), 0.0};
    arc_point B = {calloc((size_t)nd, sizeof(double)), calloc((size_t)nc, sizeof(double)), 0.0};
    arc_point best = {calloc((size_t)nd, sizeof(double)), calloc((size_t)nc, sizeof(double)), 0.0};
    double *tprim = calloc((size_t)ne, sizeof(double));
    arc_path path = {.ns = m->nsensor < BK_CRIT_SENSORS ? m->nsensor : BK_CRIT_SENSORS, .nd = nd};
    path.isq = calloc((size_t)nd, 1), path.quat = malloc((size_t)(nd / 4 + 1) * 4 * sizeof *path.quat);
    double pu[3 * BK_CRIT_SENSORS], pdu[3 * BK_CRIT_SENSORS];
    info->continuation = 1;
    if (!W || !fdof || !c.rl || !c.t || !c.tmp || !c.fol || !A.q || !A.nu || !B.q || !B.nu || !best.q ||
        !best.nu || !tprim || !path.isq || !path.quat) {
        snprintf(info->message, sizeof info->message, "out of memory");
        goto done;
    }
    c.W = W, c.fdof = fdof;
    for (int i = 0; i < nd; ++i)
        if (s->eq[i] >= 0 && s->eq[i] < s->nfree)
            fdof[s->eq[i]] = i;
    {
        const double L2 = m->length_scale * m->length_scale;
        for (int e = 0; e < m->nelem; ++e) {
            const bk_elem *el = &m->elems[e];
            const bk_element *et = m->pairs[el->pair]->element;
            for (int f = 0; f < et->nfield; ++f) {
                bk_field_role role = et->field_role[f];
                double wt = role == BK_FIELD_POSITION ? 1.0
                            : bk_field_is_gradient(role) || role == BK_FIELD_QUATERNION ? L2 : 0.0;
                for (int i = 0; i < et->field_dim[f]; ++i) {
                    int eqn = s->eq[el->dofs[et->field_dof[f] + i]];
                    if (eqn >= 0 && eqn < s->nfree)
                        W[eqn] = wt;
                }
                const int *d = el->dofs + et->field_dof[f];
                if (role == BK_FIELD_QUATERNION && et->field_dim[f] == 4 && !path.isq[d[0]]) {
                    for (int i = 0; i < 4; ++i)
                        path.isq[d[i]] = 1, path.quat[4 * path.nquat + i] = d[i];
                    path.nquat++;
                }
            }
        }
    }
    if (arc_path_push(&path, m, q, 0.0, 0.0) != 0) {
        snprintf(info->message, sizeof info->message, "out of memory");
        goto done;
    }
    double lam = 0.0, target = o->target, dl = 0.0, dl0 = 0.0, sigma_prev = 1.0, dl_prev = 0.0;
    double prev_lam = 0.0;
    int have_dir = 0, calm = 2, claimed = -1;    /* claimed: the step of the last critical point */
    int switching = 0, switched = 0, after_switch = 0;   /* static.branch_switch: pending, done, last step */
    int switch_mult = 0;                                 /* eigenvalues crossing at the switched bifurcation */
    attempt a = {0};
    bk_stability_result sres;
    if (bk_norm2(w->fext, nd) == 0.0 && m->nmoment == 0 && s->ncon == 0) {
        snprintf(info->message, sizeof info->message,
                 "static.method = \"arc_length\": the scene has no load to scale (expected a force, moment or "
                 "gravity load)");
        goto done;
    }
    for (;;) {
        double tWt;
        int st = arc_tangent(s, nl, &c, q, lam, &tWt);
        if (st != BK_NL_OK || !(tWt > 0.0)) {
            snprintf(info->message, sizeof info->message,
                     "arc-length: no tangent at the equilibrium of step %d, load factor %.6g (%s): the tangent "
                     "is singular there (a bifurcation point hit exactly, or a mechanism)", info->steps, lam,
                     st != BK_NL_OK ? bk_nl_why(st) : "the load moves nothing");
            goto done;
        }
        if (info->steps == 0) {
            c.psi2 = o->arc_spherical ? tWt : 0.0;
            dl = dl0 = target / o->load_steps * sqrt(tWt + c.psi2);
        }
        double sigma = have_dir ? arc_orientation(s, &c, q, lam, A.q, A.lam) : 1.0;
        /* a limit point between the last two equilibria: the load factor turned */
        if (have_dir && sigma != sigma_prev && !after_switch && info->ncritical < BK_MAX_EVENTS) {
            arc_save(s, w, q, lam, &B);
            int step = info->steps;
            double lc = arc_bisect_limit(s, nl, &c, q, &A, sigma_prev, dl_prev, o, &a, step, info, &best, lam);
            bk_critical_point *cp = &info->critical[info->ncritical++];
            cp->limit = 1;
            cp->step = step;
            cp->lam = lc;
            sensor_displacements(m, isfinite(best.lam) ? best.q : B.q, cp);
            if (out->console) {
                fprintf(out->console, "%s: limit point at load factor %.6g (between steps %d and %d)", m->name, lc,
                        step - 1, step);
                if (cp->nsensor)
                    fprintf(out->console, ", sensor %s displacement [%.6g, %.6g, %.6g] m", m->sensors[0].name,
                            cp->u[0][0], cp->u[0][1], cp->u[0][2]);
                fprintf(out->console, "\n");
            }
            if (log)
                fprintf(log, "  limit point: load factor %.6g between steps %d and %d\n", lc, step - 1, step);
            /* a stability event of the same step is this limit point */
            if (info->nstability > 0 && info->stability[info->nstability - 1].step == step)
                info->stability[info->nstability - 1].lam_critical = lc;
            claimed = step;
            arc_restore(s, w, q, &lam, &B);
            if ((st = arc_tangent(s, nl, &c, q, lam, &tWt)) != BK_NL_OK) {
                snprintf(info->message, sizeof info->message, "arc-length: no tangent at step %d (%s)", info->steps,
                         bk_nl_why(st));
                goto done;
            }
        }
        after_switch = 0;
        if (info->steps >= o->max_steps) {
            snprintf(info->message, sizeof info->message,
                     "arc-length: the load-factor target %.6g was not reached within static.max_steps = %d steps; "
                     "the path is kept up to step %d, load factor %.6g, largest sensor displacement %.6g m",
                     target, o->max_steps, info->steps, lam, max_sensor_displacement(m, q));
            goto done;
        }
        /* the step: predictor along the oriented tangent, bordered Newton, cut-backs */
        arc_save(s, w, q, lam, &A);
        int cuts = 0;
        for (;;) {
            double dls = dl;
            if (switching) {
                /* branch switch: the predictor along the null vector of the
                 * tangent past the bifurcation, the load factor kept; the
                 * sphere about the last equilibrium meets the secondary branch */
                memcpy(tprim, c.t, (size_t)ne * sizeof *tprim);
                branch_direction(s, stab, &c, &tWt);
                dls = fmax(dl, 1e-2 * m->length_scale);
            }
            st = arc_step(s, nl, &c, q, lam, switching ? 1.0 : sigma, tWt, dls, o, &a, info->steps + 1, info,
                          switching ? 0.0 : 1.0);
            if (switching && st == BK_NL_OK) {
                /* on the secondary branch the step is across the primary tangent */
                double tt = 0.0, dd = 0.0, td = 0.0;
                for (int j = 0; j < s->nfree; ++j) {
                    double dj = q[fdof[j]] - A.q[fdof[j]];
                    tt += W[j] * tprim[j] * tprim[j], dd += W[j] * dj * dj, td += W[j] * tprim[j] * dj;
                }
                if (tt > 0.0 && dd > 0.0 && fabs(td) > 0.9 * sqrt(tt * dd))
                    bk_warn(info, out->console, m->name, "the branch switch at step %d (load factor %.6g) came back "
                            "to the primary branch (the eigenvector nearest zero is not the buckling mode?)",
                            info->steps, lam);
                dl = dls;
                if (out->console)
                    fprintf(out->console, "%s: branch switch at step %d (load factor %.6g) onto the secondary branch "
                            "along the null vector of the tangent\n", m->name, info->steps, lam);
            }
            if (switching && st != BK_NL_OK && st != BK_NL_INTERRUPTED) {
                if (switch_mult > 1)
                    bk_warn(info, out->console, m->name, "the branch switch at step %d (load factor %.6g) failed (%s): "
                            "the path goes on along the primary branch; the bifurcation is multiple (%d eigenvalues "
                            "crossed zero together, e.g. a section symmetric in both bending planes), so its "
                            "secondary branches form a family and the switch has no single branch to follow: break "
                            "the symmetry (e.g. a rectangle with b != h)", info->steps, lam, bk_nl_why(st),
                            switch_mult);
                else
                    bk_warn(info, out->console, m->name, "the branch switch at step %d (load factor %.6g) failed (%s): "
                            "the path goes on along the primary branch", info->steps, lam, bk_nl_why(st));
                switching = 0;
                if ((st = arc_tangent(s, nl, &c, q, lam, &tWt)) != BK_NL_OK) {
                    snprintf(info->message, sizeof info->message, "arc-length: no tangent at step %d (%s)",
                             info->steps, bk_nl_why(st));
                    goto done;
                }
                continue;
            }
            if (st == BK_NL_OK || st == BK_NL_INTERRUPTED)
                break;
            if (cuts >= o->max_cutbacks) {
                char what[600];
                diagnose(what, sizeof what, st, &a, info->steps, info->negative_eigenvalues);
                snprintf(info->message, sizeof info->message,
                         "arc-length failed at step %d from load factor %.6g (arc length %.3e): %s; residual %.3e "
                         "(tolerance %.3e) after %d iterations, %d cut-backs; the path is kept up to step %d",
                         info->steps + 1, lam, dl, what, a.rnorm, a.rtol_abs, a.iters, cuts, info->steps);
                goto done;
            }
            cuts++;
            info->cutbacks++;
            calm = 0;
            dl *= 0.5;
            if (log)
                fprintf(log, "  cut-back at load factor %.6g (%s): new arc length %.3g\n", lam, bk_nl_why(st), dl);
            if ((st = arc_tangent(s, nl, &c, q, lam, &tWt)) != BK_NL_OK) {
                snprintf(info->message, sizeof info->message, "arc-length: no tangent at step %d (%s)",
                         info->steps, bk_nl_why(st));
                goto done;
            }
        }
        if (st == BK_NL_INTERRUPTED) {
            info->interrupted = a.signo;
            snprintf(info->message, sizeof info->message,
                     "interrupted by %s during step %d from load factor %.6g; the %d converged steps are kept",
                     bk_interrupt_name(a.signo), info->steps + 1, lam, info->steps);
            goto done;
        }
        if (switching) {
            switching = 0;
            switched = 1;
            after_switch = 1;           /* no limit point between the branches */
        }
        double lam_new = c.sp.lam;
        int reached = (lam - target) * (lam_new - target) <= 0.0 && lam_new > lam;
        if (reached && lam_new != target) {
            /* land on the target by load control from the arc point */
            arc_save(s, w, q, lam_new, &B);
            memcpy(w->qsave, A.q, (size_t)nd * sizeof *q);
            a.id++;
            int lst = newton(s, nl, w, q, target, lam, &a, o, m->length_scale, info->steps + 1, NULL);
            info->newton_iterations += a.iters;
            if (lst == NEWTON_OK)
                lam_new = target;
            else
                arc_restore(s, w, q, &lam_new, &B);
        }
        dl_prev = dl;
        sigma_prev = sigma;
        have_dir = 1;
        lam = lam_new;
        info->steps++;
        info->load_factor = lam;
        bk_output_forces(out, s, info->steps, lam, q, NULL, NULL, w->nu);
        bk_output_step(out, info->steps, lam, q);
        bk_checks_state(chk, s, q, "load factor", lam, info, out->console);
        if (log)
            fprintf(log, "  step %d: load factor %.6g, arc length %.3g, %d iterations, residual %.3e\n", info->steps,
                    lam, dl, a.iters, a.rnorm);
        if (have_stab) {
            probe_stability(stab, s, w, q, lam, 0, &sres);
            accept_stability(stab, &sres, lam, out, info, log, &prev_lam, 1, NAN);
        }
        /* a change of the negative-eigenvalue count in the last step without
         * a limit point: a bifurcation candidate (its load factor from the
         * bisection on the inertia of the interpolated tangent, sensors
         * interpolated); kept unless a limit point is within ARC_NEAR steps
         * (the count flickers while the smallest eigenvalue hovers about zero
         * on the flat top of a limit point); not the change of a branch switch */
        if (info->nstability > 0 && info->stability[info->nstability - 1].step == info->steps &&
            claimed != info->steps && !after_switch && ncand < BK_MAX_EVENTS) {
            const bk_stability_event *ev = &info->stability[info->nstability - 1];
            bk_critical_point *cp = &cand[ncand++], ca, cb;
            double f = isfinite(ev->lam_critical) && lam != A.lam ? (ev->lam_critical - A.lam) / (lam - A.lam) : 1.0;
            sensor_displacements(m, A.q, &ca);
            sensor_displacements(m, q, &cb);
            cp->limit = 0;
            cp->step = info->steps;
            cp->lam = ev->lam_critical;
            cp->nsensor = cb.nsensor;
            for (int k = 0; k < cb.nsensor; ++k)
                for (int i = 0; i < 3; ++i)
                    cp->u[k][i] = ca.u[k][i] + f * (cb.u[k][i] - ca.u[k][i]);
            cand_neg[ncand - 1][0] = ev->neg_before, cand_neg[ncand - 1][1] = ev->neg_after;
            claimed = info->steps;
            if (o->branch_switch && !switched && ev->neg_after > ev->neg_before) {
                switching = 1;          /* the next step switches branch */
                switch_mult = ev->neg_after - ev->neg_before;
            }
        }
        bk_output_progress(out, fmin(fabs(lam / target), 1.0), info->steps, lam, a.iters, a.rnorm);
        if (reached && !switching) {    /* (a pending branch switch goes on from the target) */
            rc = 0;
            goto done;
        }
        if (o->max_displacement > 0.0 && max_sensor_displacement(m, q) >= o->max_displacement) {
            if (out->console)
                fprintf(out->console, "%s: arc-length stopped at the displacement limit %.6g m (step %d, load "
                        "factor %.6g)\n", m->name, o->max_displacement, info->steps, lam);
            rc = 0;
            goto done;
        }
        /* a closed loop: back at a visited point of the path (arc_path) */
        {
            bk_critical_point cp;
            sensor_displacements(m, q, &cp);
            const double *ul = path.u + (size_t)(path.n - 1) * 3 * path.ns;
            for (int k = 0; k < 3 * path.ns; ++k)
                pu[k] = cp.u[k / 3][k % 3], pdu[k] = pu[k] - ul[k];
            int kb = -1;
            double db = INFINITY;
            for (int k = 0; k + 1 < path.n - 1; ++k) {
                double dist, len;
                if (k + 1 >= path.nq || !arc_path_near(&path, k, pu, lam, pdu, lam - path.lam[path.n - 1]))
                    continue;
                arc_path_distance(&path, s, &c, m->length_scale * m->length_scale, k, q, lam, &dist, &len);
                double tol = 0.25 * fmax(dl, len), went = path.arc[path.n - 1] + dl - path.arc[k + 1];
                if (dist < tol && went > 4.0 * tol && dist < db)
                    kb = k, db = dist;
            }
            if (kb >= 0) {
                int o2 = snprintf(info->message, sizeof info->message,
                                  "arc-length: a closed loop: at step %d (load factor %.6g) the path came back to "
                                  "where it was between steps %d and %d (load factor %.6g to %.6g",
                                  info->steps, lam, kb, kb + 1, path.lam[kb], path.lam[kb + 1]);
                if (path.ns > 0 && o2 > 0 && (size_t)o2 < sizeof info->message)
                    o2 += snprintf(info->message + o2, sizeof info->message - (size_t)o2,
                                   ", sensor %s displacement [%.6g, %.6g, %.6g] m", m->sensors[0].name, pu[0], pu[1],
                                   pu[2]);
                if (o2 > 0 && (size_t)o2 < sizeof info->message)
                    snprintf(info->message + o2, sizeof info->message - (size_t)o2,
                             "; distance %.3e, arc length %.3e); the target %.6g is not on this path", db, dl, target);
                goto done;
            }
            if (arc_path_push(&path, m, q, lam, path.arc[path.n - 1] + dl) != 0) {
                snprintf(info->message, sizeof info->message, "out of memory");
                goto done;
            }
        }
        /* the next arc length from the iteration count */
        double f = sqrt((double)o->arc_iters / (a.iters > 1 ? a.iters : 1));
        f = fmin(fmax(f, 0.5), 2.0);
        if (calm < 2) {
            f = fmin(f, 1.0);
            calm++;
        }
        dl = fmin(dl * f, fmax(8.0 * dl0, 0.05 * m->length_scale));
    }
done:
    /* the bifurcations: candidates away from every limit point, merged by
     * step; a change taken back within ARC_NEAR steps (0 -> 1 -> 0) is the
     * flicker of an eigenvalue about zero and no bifurcation */
    char gone[BK_MAX_EVENTS] = {0};
    for (int k = 0; k + 1 < ncand; ++k)
        if (!gone[k] && cand_neg[k][0] == cand_neg[k + 1][1] && cand_neg[k][1] == cand_neg[k + 1][0] &&
            cand[k + 1].step - cand[k].step <= ARC_NEAR)
            gone[k] = gone[k + 1] = 1;
    for (int k = 0; k < ncand; ++k) {
        int near = gone[k];
        for (int j = 0; j < info->ncritical; ++j)
            near |= info->critical[j].limit && abs(info->critical[j].step - cand[k].step) <= ARC_NEAR;
        if (near || info->ncritical >= BK_MAX_EVENTS)
            continue;
        int at = info->ncritical;
        while (at > 0 && info->critical[at - 1].step > cand[k].step) {
            info->critical[at] = info->critical[at - 1];
            at--;
        }
        info->critical[at] = cand[k];
        info->ncritical++;
        if (out->console)
            fprintf(out->console, "%s: bifurcation at load factor %.6g (between steps %d and %d: negative tangent "
                    "eigenvalues %d -> %d)\n", m->name, cand[k].lam, cand[k].step - 1, cand[k].step, cand_neg[k][0],
                    cand_neg[k][1]);
    }
    free(W), free(fdof), free(c.rl), free(c.t), free(c.tmp), free(c.fol), free(tprim);
    arc_path_free(&path);
    free(A.q), free(A.nu), free(B.q), free(B.nu), free(best.q), free(best.nu);
    return rc;
}

int bk_solve_static(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log)
{
    const bk_model *m = s->m;
    const bk_static_opts *o = &m->stat;
    work w = {0};
    int nd = m->ndof, nc = s->ncon > 0 ? s->ncon : 1;
    w.fint = calloc((size_t)nd, sizeof(double));
    w.fext = calloc((size_t)nd, sizeof(double));
    w.qsave = calloc((size_t)nd, sizeof(double));
    w.qprev = calloc((size_t)nd, sizeof(double));
    w.nu = calloc((size_t)nc, sizeof(double));
    w.nusave = calloc((size_t)nc, sizeof(double));
    w.nuprev = calloc((size_t)nc, sizeof(double));
    bk_nl nl = {0};
    int have_nl = 0;
    bk_stability stab = {0};
    bk_checks chk = {0};
    int rc = 1, have_stab = 0;
    if (!w.fint || !w.fext || !w.qsave || !w.qprev || !w.nu || !w.nusave || !w.nuprev) {
        snprintf(info->message, sizeof info->message, "out of memory");
        goto done;
    }
    if (s->neq == 0) {
        snprintf(info->message, sizeof info->message, "every DOF is fixed: nothing to solve");
        goto done;
    }
    have_nl = 1;
    if (bk_nl_init(&nl, s, out, info->message, sizeof info->message) != 0)
        goto done;
    w.r = nl.r, w.dx = nl.dx, w.Ax = nl.Ax, w.norms = &nl.norms;
    w.quat = bk_quat_list(s, &w.nquat);
    if (w.nquat < 0 || bk_checks_init(&chk, s) != 0) {
        snprintf(info->message, sizeof info->message, "out of memory");
        goto done;
    }
    if (o->stability) {
        if (bk_stability_init(&stab, s, nl.ls.use_band ? &nl.ls.band : NULL) != 0) {
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

    bk_output_forces(out, s, 0, 0.0, q, NULL, NULL, w.nu);
    bk_output_step(out, 0, 0.0, q);
    double prev_lam = 0.0;
    bk_stability_result sres;
    reference_probe ref = {.st = &stab};
    if (have_stab && !o->arc_length && matrix_free_of_load(s))
        ref.state = 1;                   /* on the first Newton matrix (at q0) */
    else if (have_stab) {
        probe_stability(&stab, s, &w, q, 0.0, 0, &sres);
        accept_stability(&stab, &sres, 0.0, out, info, log, &prev_lam, 1, NAN);
    }
    if (o->arc_length) {
        rc = arc_length(s, &nl, &w, q, out, info, log, &stab, have_stab, &chk);
        goto done;
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
                st = newton(s, &nl, &w, q, target, lam, &a, o, m->length_scale, info->steps + 1, &ref);
                info->newton_iterations += a.iters;
            }
            int assembled = 1;           /* w.Ax: the matrix at q (a converged solve ends on it) */
            if (ref.state != 0) {         /* the reference state's check, before this step's */
                const int probe = ref.state != 2;   /* no Newton matrix was made at it, or not checked */
                if (probe) {
                    probe_stability(&stab, s, &w, m->q0, 0.0, 0, &ref.res);
                    assembled = 0;
                }
                accept_stability(&stab, &ref.res, 0.0, out, info, log, &prev_lam, probe, NAN);
                ref.state = 0;
            }
            /* On a stable path (static.stable_path), an increment that ends
             * at an equilibrium with more negative eigenvalues than the last
             * one is cut back while cut-backs remain: with an imperfection
             * the stable branch is reached with smaller increments; without,
             * the bifurcation is bracketed as closely as the cut-backs allow
             * and then passed (and reported). */
            if (st == NEWTON_OK && have_stab) {
                int c = probe_stability(&stab, s, &w, q, target, assembled, &sres);
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
                memcpy(w.qprev, w.qsave, (size_t)nd * sizeof *q);
                memcpy(w.nuprev, w.nusave, (size_t)nc * sizeof *w.nu);
                lam_prev = lam;
                have_prev = 1;
                lam = target;
                info->steps++;
                info->load_factor = lam;
                bk_output_forces(out, s, info->steps, lam, q, NULL, NULL, w.nu);
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
                    double refined = NAN;
                    if (sres.ok && sres.negative != info->negative_eigenvalues && info->nstability < BK_MAX_EVENTS)
                        refined = refine_critical(s, &nl, &w, &stab, q, prev_lam, lam, info->negative_eigenvalues,
                                                  o, &a, info);
                    accept_stability(&stab, &sres, lam, out, info, log, &prev_lam, 1, refined);
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
    info->factorizations = nl.ls.nfactor;
    info->analyses = nl.ls.nanalyze;
    info->stability_checked = have_stab;
    if (have_nl)
        bk_nl_free(&nl);
    if (have_stab) {
        info->stability_s = stab.t_spent;
        bk_stability_free(&stab);
    }
    free(w.fint);
    free(w.fext);
    free(w.qsave);
    free(w.qprev);
    free(w.nu);
    free(w.nusave);
    free(w.nuprev);
    free(w.quat);
    bk_checks_free(&chk);
    return rc;
}
