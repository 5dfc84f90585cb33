/* nonlinear.h -- the one Newton solver of every analysis.
 *
 * An analysis (static load stepping, arc-length continuation, generalized-
 * alpha) is a residual provider and a step controller: it supplies the
 * residual and the Newton matrix of its unknowns (free DOFs, then scaled
 * multipliers: system.h) through callbacks, the update of its state by a
 * correction (quaternions, velocities, a load factor) and, for rotation DOFs,
 * a limit on the step.  The solver owns the iteration, the convergence tests
 * (rotation-invariant measures and round-off floors of norms.h), the
 * factorizations (KLU, linsolve.h), the Jacobian-reuse policy across solves,
 * the diagnostics of a failure and the record of every iteration (on_iteration).
 *
 * Convergence: the residual within max(rtol ref, force floor), the constraint
 * rows within ctol (when ctol > 0), and the last correction small in length
 * (max(utol uscale, increment floor)) or in energy (BK_ENERGY_TOL times the
 * energy scale: the first correction of the solve or the provider's escale,
 * whichever is larger), or the residual far below its tolerance
 * (accept_far_below).  Optional: acceptance of stagnation at round-off
 * (stagnation) and a divergence test (divergence).
 *
 * Jacobian reuse (opts.reuse, modified Newton across solves): a solve starts
 * with the factors of an earlier matrix of the same key (the provider's step
 * size) and keeps them while their measured contraction rate (residual after /
 * before a correction made with them) is at most BK_REUSE_MAX_RATE and
 * predicts convergence within BK_REUSE_ITERATIONS more corrections; else the
 * matrix is assembled and factorized anew.  A kept-factor correction that led
 * to a non-finite force or raised the residual more than BK_REUSE_DIVERGED
 * times is taken back and redone with a new matrix.
 *
 * Ownership: the solver owns its buffers (r, dx, Ax), the linear solver and
 * the norms; the provider may read and write them between solves (e.g. for a
 * stability probe or a predictor solve with nl->ls).  No allocation in
 * bk_nl_solve, but when an interaction's prepare (interaction.h: beam-to-beam
 * contact) grew the system's pattern before an iteration: then Ax is made
 * anew for it and the linear solver planned again (the providers take Ax
 * from the residual callback's argument, never from an earlier copy).
 */
#ifndef BK_NONLINEAR_H
#define BK_NONLINEAR_H

#include "linalg/linsolve.h"
#include "solver/norms.h"
#include "assembly/system.h"

#define BK_REUSE_MAX_RATE 0.5
#define BK_REUSE_ITERATIONS 5
#define BK_REUSE_DIVERGED 10.0

/* Pending SIGINT / SIGTERM are polled (interrupt.h; a system call) before a
 * Newton iteration at most this often (s of wall time): a small model's
 * iteration costs a few microseconds, the poll as much as a tenth of it. */
#define BK_INTERRUPT_POLL_S 0.002

/* Below this pivot ratio the Newton matrix is singular to working precision. */
#define BK_ILL_RCOND 1e-12

enum { BK_NL_OK = 0, BK_NL_MAXIT, BK_NL_NONFINITE, BK_NL_SINGULAR, BK_NL_DIVERGED, BK_NL_LINERR,
       BK_NL_INTERRUPTED, BK_NL_NCODES };

/* What a residual evaluation tells the convergence tests. */
typedef struct bk_nl_eval {
    double rnorm;      /* norm of the rows tested against rtol ref               */
    double ref;        /* force scale of the residual                            */
    double uscale;     /* motion scale of the increment test                     */
    double escale;     /* an energy scale of the solve besides its first correction (0: none) */
    double cres;       /* constraint-row residual (tested when ctol > 0)         */
} bk_nl_eval;

typedef struct bk_nl_problem {
    void *ctx;
    double *q;         /* DOF-indexed configuration, changed in place by update (floors) */
    /* Residual at the current state into r[neq] and, when matrix, the Newton
     * matrix into Ax; fills ev.  Returns 0, or nonzero on a non-finite value. */
    int (*residual)(void *ctx, int matrix, double *r, double *Ax, bk_nl_eval *ev);
    /* After a linear solve: may change the correction dx (bordered systems
     * solve more with ls); NULL: none.  Returns 0, nonzero on failure
     * (BK_NL_LINERR). */
    int (*augment)(void *ctx, bk_linsolver *ls, double *dx);
    /* State += alpha dx (alpha = -1: take a correction back). */
    void (*update)(void *ctx, const double *dx, double alpha);
    /* The fraction in (0, 1] of the correction dx to take; NULL: 1. */
    double (*step_limit)(void *ctx, const double *dx);
} bk_nl_problem;

typedef struct bk_nl_opts {
    int max_iter;
    double rtol, utol;
    double ctol;          /* > 0: the constraint rows (ev.cres) within ctol */
    int accept_far_below; /* converged when the residual is below 1e-3 of its tolerance */
    int stagnation;       /* accept stagnation near round-off */
    int divergence;       /* residual above 1e12 times the first: diverged */
    int reuse;            /* Jacobian reuse across solves (see above) */
    int lazy_matrix;      /* after the first iteration: the residual alone first, and the matrix
                           * only when that residual is not converged (for solves that mostly
                           * converge after one or two corrections: time steps) */
} bk_nl_opts;

/* The label of the newton.csv rows of one solve (row == NULL: none). */
typedef struct bk_nl_row {
    int attempt, step;
    double lam;
} bk_nl_row;

typedef struct bk_nl_result {
    int code;
    int iters;            /* corrections made */
    double rnorm, dnorm, ref, rtol_abs;
    double utol_abs;      /* the increment tolerance of the last iteration */
    double rcond;         /* KLU's pivot ratio of the last factorization (NaN: none) */
    int residual_met;     /* the residual met its tolerance at some iteration */
    int singular_at_start;
    int reused;           /* some correction used kept factors */
    int signo;            /* BK_NL_INTERRUPTED: the signal */
} bk_nl_result;

typedef struct bk_nl {
    bk_system *s;
    bk_linsolver ls;
    bk_norms norms;
    double *r, *dx, *Ax;  /* [neq], [neq], [nnz] */
    int have_factors;     /* ls holds factors of a matrix of key factors_key */
    double factors_key;
    double krate;         /* last measured contraction rate of kept factors */
    bk_floors fl;         /* round-off floors of the last assembled matrix */
    /* The record of each iteration of a solve given a row label (bk_nl_solve's
     * row): the residual norm, its reference force, the increment (max norm,
     * NaN at iteration 0), the step length taken and the pivot ratio of the
     * last factorization.  NULL: none (an analysis writes them to a table). */
    void (*on_iteration)(void *ctx, const struct bk_nl_row *row, int iter, double rnorm, double ref,
                         double increment, double alpha, double rcond);
    void *iteration_ctx;
    double t_poll;        /* when SIGINT / SIGTERM were last polled (bk_clock_s) */
    int pattern_gen;      /* the system's pattern version Ax and ls were made for (system.h) */
} bk_nl;

/* Returns 0, or -1 with a message in msg. */
int bk_nl_init(bk_nl *nl, bk_system *s, char *msg, size_t nmsg);
void bk_nl_free(bk_nl *nl);

/* One Newton solve from the provider's current state.  key: the matrix key of
 * the reuse policy; fresh: a new matrix at every iteration of this solve. */
int bk_nl_solve(bk_nl *nl, const bk_nl_problem *p, const bk_nl_opts *o, double key, int fresh,
                const bk_nl_row *row, bk_nl_result *res);

/* A short text for a BK_NL_* code. */
const char *bk_nl_why(int code);

#endif
