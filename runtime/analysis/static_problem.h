/* static_problem.h -- what the static analyses share (private to analysis/):
 * the work arrays of a static solve, one Newton attempt at a load factor (the
 * residual, the update, the rotation trust region), the stability probes of
 * equilibria, and the set-up and tear-down around a static path.  Load control
 * (static.c) and arc-length continuation (continuation.c) are built on it;
 * it calls the assembly, the nonlinear solver, the stability service and the
 * output. */
#ifndef BK_STATIC_PROBLEM_H
#define BK_STATIC_PROBLEM_H

#include <stdio.h>

#include "output/checks.h"
#include "output/output.h"
#include "solver/nonlinear.h"
#include "solver/stability.h"

typedef struct work {
    double *fint, *fext, *r, *dx, *Ax, *qsave, *nu, *nusave;
    double *qprev, *nuprev;          /* the equilibrium before the last one (predictor) */
    double *qtrial, *nutrial;        /* the trust region's trial state (NULL: static.globalization = none) */
    int *quat;                       /* first global DOF of each free nodal quaternion */
    int nquat;
    const bk_norms *norms;           /* rotation-invariant measures (the solver's) */
    FILE *newton_csv;                /* newton.csv: a row per Newton iteration (NULL: none) */
    FILE *stability_csv;             /* stability.csv: a row per stability check (NULL: none) */
    bk_output *out;                  /* where they are registered */
} work;

/* One Newton solve: its outcome and counters. */
typedef struct attempt {
    int id;                          /* attempt number over the run (newton.csv)  */
    int iters;
    double rnorm, dnorm, ref;
    double rtol_abs;                 /* the residual tolerance of the last iteration */
    double utol_abs;                 /* and the increment's */
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
       NEWTON_INTERRUPTED = BK_NL_INTERRUPTED, NEWTON_UNSTABLE = BK_NL_NCODES,
       NEWTON_INADMISSIBLE };         /* converged to a state bk_checks_admissible refuses */

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
    double mu;                       /* the trust region's shift of the tangent (static_trust.c) */
} static_problem;

/* static_trust.c: static.globalization = "trust_region".
 * bk_static_trust_refusal: 0 when the model's loads have a potential (dead
 *   forces, gravity) and no interaction or nonlinear joint; else 1 and why in msg.
 * bk_static_trust_shift: Ax[jj] += mu |Ax[jj]| on the free unknowns' diagonal.
 * bk_static_trust_step: the fraction of the correction dx to take (a, or 0:
 *   rejected), judged by the potential energy; adapts p->mu. */
int bk_static_trust_refusal(const bk_system *s, char *msg, size_t n);
void bk_static_trust_shift(const bk_system *s, double mu, double *Ax);
double bk_static_trust_step(static_problem *p, const double *dx, double a);

/* One static path's state between bk_static_begin and bk_static_end. */
typedef struct static_run {
    work w;
    bk_nl nl;
    int have_nl;
    bk_stability stab;
    int have_stab;
    bk_checks chk;
    double prev_lam;                 /* the load factor of the last stability check */
    bk_stability_result sres;
    reference_probe ref;             /* the reference state's check, made on the first Newton matrix */
    double ref_rnorm;                /* (static.stability) |r| at the reference state, load factor 0, no
                                      * multipliers: more than the first step's tolerance, and the reference is
                                      * no equilibrium (surfaces placed within a contact's reach, say) */
} static_run;

/* Allocates the work arrays, the nonlinear solver and (static.stability) the
 * stability checker; sets q to the reference state, the dead load, the
 * constraint scale; writes the reference state's output rows and checks its
 * stability (now, or on the first Newton matrix when reference_on_first and
 * that matrix is the reference state's); tables: newton.csv and (with
 * static.stability) stability.csv are opened and written.  Returns 0, or 1 with info->message
 * set (bk_static_end frees what was made). */
int bk_static_begin(static_run *R, bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log,
                    int reference_on_first, int tables);
/* Counters into info; frees what bk_static_begin made.  rc: the path's result. */
void bk_static_end(static_run *R, bk_run_info *info, int rc);

const char *bk_static_why(int code);
void bk_static_diagnose(char *buf, size_t n, int code, const attempt *a, int steps, int negative);
int bk_static_residual(bk_system *s, work *w, const double *q, const double *nu, double lam, int with_tangent);
void bk_static_step_to(const bk_system *s, const work *w, const double *q0, const double *nu0, const double *dx,
                       double alpha, double *q, double *nu);
int bk_sp_residual(void *ctx, int matrix, double *r, double *Ax, bk_nl_eval *ev);
void bk_sp_update(void *ctx, const double *dx, double alpha);
double bk_sp_step_limit(void *ctx, const double *dx);
bk_nl_opts bk_static_nl_opts(const bk_static_opts *o);
int bk_static_newton(bk_system *s, bk_nl *nl, work *w, double *q, double lam, double lam_last, attempt *a,
                     const bk_static_opts *o, double lscale, int step, reference_probe *ref);
int bk_static_matrix_free_of_load(const bk_system *s);
int bk_static_probe_stability(bk_stability *st, bk_system *s, work *w, const double *q, double lam,
                              int assembled, bk_stability_result *res);
void bk_static_accept_stability(bk_stability *st, const bk_stability_result *res, double lam, bk_output *out,
                                bk_run_info *info, FILE *log, double *prev_lam, int matrix, double refined,
                                FILE *table);

#endif
