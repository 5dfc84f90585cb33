/* stability.h -- stability of a static equilibrium: the inertia of the tangent
 * restricted to the constraints, its smallest-magnitude eigenvalue and an
 * estimate of its largest (for the condition number).
 *
 * Method.  The Newton matrix is the saddle-point (KKT) matrix
 *     A = [ K  B^T ]     B: the scaled constraint rows, and the rows of the
 *         [ B  0   ]     element-internal multipliers (fields of role
 *                        BK_FIELD_MULTIPLIER: the Euler-Bernoulli and
 *                        Kirchhoff beams)
 * with m multiplier unknowns.  Its symmetric part, regularized with -delta_i on
 * the multiplier diagonals (delta_i = 1e-8 |b_i|^2 / kmax), is factored as
 * L D L^T (the symmetric solver object, linalg/symsolve.h: a band, or
 * SuiteSparse LDL with the multipliers eliminated first and AMD ordering for
 * the rest).  Eliminating the multipliers first leaves K + B^T
 * delta^-1 B, so by Sylvester's law of inertia
 *     negative pivots of D = m + negative eigenvalues of (K + B^T delta^-1 B),
 * and for small delta the latter are the negative eigenvalues of K on the
 * tangent space of the constraints (the directions B moves are penalized by
 * about 1e8 kmax).  A change of that count between two equilibria is a
 * bifurcation or a limit point between them.  The smallest-magnitude
 * eigenvalue comes from inverse iteration with the factor, the largest from
 * power iteration with the matrix (both in the Euclidean metric of the
 * unknowns).
 *
 * The critical load between two equilibria with different counts is found by
 * bisection on the inertia of the linearly interpolated matrix.
 *
 * Storage: the symmetric solver object (linalg/symsolve.h) holds the
 * matrix now and the factor (for a narrow band in the Newton solver's band LU
 * storage, borrowed, so that a check touches no fresh memory but the
 * accepted matrix; a check then makes the band LU factor from scratch next
 * time, which the static solver does anyway: it factors every Newton matrix
 * it makes, nonlinear.h opts.reuse = 0; a long band's halves are factored on
 * two threads in the split band LU's block storage: symsplit.h); the checker
 * keeps the values at the last accepted check.
 *
 * Ownership: the checker owns every array it allocates and its symmetric
 * solver (bk_stability_free); it keeps a pointer to the system, which must
 * outlive it, and the symmetric solver borrows the linear solver's storage,
 * which must outlive it too.  No allocation after bk_stability_init.
 */
#ifndef BK_STABILITY_H
#define BK_STABILITY_H

#include "linalg/symsolve.h"
#include "assembly/system.h"

typedef struct bk_stability {
    const bk_system *s;
    double t_spent;                 /* wall time in this analysis so far (s; set-up, checks, crossings) */
    int n, nmult;
    char *ismult;                   /* [n] 1 for multiplier unknowns           */
    int have_prev;                  /* a check was accepted (prev holds its values) */
    bk_symsolver sym;               /* L D L^T of the symmetric part: inertia, solves, products */
    double *prev;                   /* [sym.nval] the values at the last accepted check */
    /* eigenvalue iterations (static.eigenvalues) */
    double *x, *y, *z;              /* iteration vectors                        */
    double *dcross;                 /* [2 n] the pivots at the ends of the crossing's bracket */
    double *dchk, *dacc;            /* [n] each: the pivots of the last check and of the last
                                     * accepted one (the crossing's ends t = 1 and t = 0) */
    int count_chk, ok_chk, ok_acc;  /* the last check's count; whether dchk, dacc hold pivots */
    double *xmax;                   /* the last power-iteration vector          */
    int have_vec;                   /* x holds the last eigenvector             */
    int have_vmax;                  /* xmax holds one                           */
} bk_stability;

typedef struct bk_stability_result {
    int negative;                   /* negative eigenvalues on the constraint tangent space */
    double eig_min;                 /* smallest-magnitude eigenvalue (Rayleigh quotient)    */
    double eig_max;                 /* largest-magnitude eigenvalue estimate                */
    int ok;                         /* 0: the factorization broke down (zero pivot)         */
} bk_stability_result;

/* ls: the Newton solver's linear solver object of the system's pattern (a
 * band LU plan's order and half bandwidths serve the band L D L^T and save
 * its own reverse Cuthill-McKee search; its storage is borrowed as the
 * checks' scratch: symsolve.h), or NULL.  Returns 0, or -1 when out of
 * memory. */
int bk_stability_init(bk_stability *st, const bk_system *s, bk_linsolver *ls);
/* Analyses the Newton matrix with values Ax (as assembled by newton.c).
 * Overwrites the band LU's factors (see Storage). */
void bk_stability_check(bk_stability *st, const double *Ax, bk_stability_result *res);
/* Makes the last checked matrix the reference of the next crossing search
 * (call when its state is accepted as an equilibrium of the path, before
 * the band LU factors anything again). */
void bk_stability_accept(bk_stability *st);
/* After a check whose count differs from the previous one: the fraction
 * t in (0, 1) between the last accepted and the current state at which the matrix
 * interpolated linearly between the two, (1 - t) A_prev + t A, first has a
 * negative-eigenvalue count different from the previous one: the inertia
 * narrows a bracket (lo: the previous count, hi: another) to 2^-BK_CROSSING_BISECTIONS
 * wide, then the zero of the k-th root of the determinant (the product of
 * the pivots; k eigenvalues crossing) is interpolated linearly across it
 * (within about the squared width, so exact to round-off for a tangent linear
 * in the load, as on a straight pre-buckling path), or the bracket's middle
 * when the determinant's sign does not fit k.  Each narrowing factors the
 * matrix at two points BK_CROSSING_GUESS_WIDTH of the bracket either side of
 * that interpolated zero, which brackets it tightly when it is good; after a
 * guess that missed, or without one, it bisects.  Off such a path the linear
 * interpolation's own error, of the order of the squared step, is far larger.
 * NaN when unavailable. */
#define BK_CROSSING_BISECTIONS 20
#define BK_CROSSING_GUESS_WIDTH (1.0 / 64.0)
double bk_stability_crossing(bk_stability *st, int count_before);
void bk_stability_free(bk_stability *st);

#endif
