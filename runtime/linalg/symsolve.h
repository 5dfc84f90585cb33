/* symsolve.h -- the symmetric solver object: L D L^T without pivoting of the
 * symmetric part of a matrix, for its inertia (by Sylvester's law the
 * negative entries of D are its negative eigenvalues), solves and products
 * with it.  Two backends, chosen at set-up:
 *   band    (bandlu.h bk_bandsym) when the matrix is a narrow band in the
 *           order of the Newton solver's band LU (that linear solver object's
 *           plan, given to bk_sym_init) or in its own reverse Cuthill-McKee
 *           order; when the band LU's storage holds them, the factor and the
 *           values now are placed there (borrowed), so a factorization touches
 *           no fresh memory (the band LU must then factor anew after any of
 *           these calls: bk_sym_begin tells it); a band of BK_BANDSPLIT_MIN
 *           unknowns and more is factored in two halves and a separator on
 *           two threads (symsplit.h: in the split band LU's order and cut,
 *           its blocks' storage borrowed for the halves' factors, when the
 *           Newton solver uses it; the same bits for any thread count);
 *   sparse  SuiteSparse LDL on the symmetric pattern with AMD ordering, the
 *           unknowns marked `first` eliminated first (each in its AMD rank).
 *
 * Values.  A matrix's values live in an array of bk_sym_nvalues doubles in the
 * backend's layout (band, or the symmetric pattern's); the object owns the
 * array of the values now (bk_sym_now) and a scratch one (bk_sym_scratch: for
 * the band, the factor's own storage, factored in place); the caller may keep
 * others (e.g. the values of an earlier matrix) and interpolate between them
 * entry by entry.
 *
 * Sizes and directions: n the unknowns; Ap[n+1], Ai[nnz] a CSC pattern (the
 * caller's, outlives the object), Ax[nnz] values on it; x, y [n] in the
 * pattern's order.  No allocation after bk_sym_init.
 */
#ifndef BK_SYMSOLVE_H
#define BK_SYMSOLVE_H

#include "linalg/linsolve.h"
#include "linalg/symsplit.h"

typedef struct bk_symsolver {
    int n, use_band, use_split;      /* use_split: the band in two halves (symsplit.h) */
    long nval;                       /* doubles in a values array */
    double *now;                     /* [nval] the values now (owned, or the band LU's) */
    double *scratch;                 /* [nval] (sparse: owned; band: the factor, band.ab) */
    bk_band *lender;                 /* NULL, or the band LU whose storage holds now and the factor */
    const int *Ap, *Ai;              /* the matrix's pattern (not owned) */
    bk_bandsym band;
    bk_symsplit split;
    /* sparse: the symmetric pattern with every diagonal, and for each of its
     * entries the positions of (i,j) and (j,i) in the matrix's values */
    int *Bp, *Bi, *src, *srct;
    int *Lp, *Parent, *Lnz, *Flag, *Pattern, *P, *Pinv, *Li;
    double *Lx, *D, *Y, *z;
} bk_symsolver;

/* Plans the object for the pattern (Ap, Ai) of n unknowns, first[n] (1: an
 * unknown to eliminate first in the sparse order; may be NULL), ls the linear
 * solver object of the same pattern (its band plan's order and width serve
 * the band backend, its storage is borrowed; NULL, or another pattern's:
 * none).  0, or -1 when out of memory. */
int bk_sym_init(bk_symsolver *f, int n, const int *Ap, const int *Ai, const char *first, bk_linsolver *ls);
void bk_sym_free(bk_symsolver *f);
/* Call before using the object: the band LU whose storage it borrows must
 * factor from scratch next time. */
void bk_sym_begin(bk_symsolver *f);
/* vals = (A + A^T) / 2 of Ax; the diagonal of each unknown marked reg (may be
 * NULL: none) replaced by -1e-8 b2 / kmax, b2 the sum of the squares of its
 * column's off-diagonal entries (or kmax when there are none), kmax the
 * largest magnitude of the other diagonals (a saddle point's multipliers,
 * regularized: stability.h). */
void bk_sym_fill(const bk_symsolver *f, const double *Ax, const char *reg, double *vals);
/* L D L^T of vals (may be bk_sym_scratch: factored in place): 0, or -1 at a
 * zero or non-finite pivot. */
int bk_sym_factor(bk_symsolver *f, const double *vals);
/* The last factorization's pivots D[n] (in the backend's order). */
const double *bk_sym_pivots(const bk_symsolver *f);
/* The number of negative pivots of the last factorization. */
int bk_sym_negative(const bk_symsolver *f);
/* y = A^-1 x with the last factors (x may be y). */
void bk_sym_solve(bk_symsolver *f, const double *x, double *y);
/* y = A x for the values vals. */
void bk_sym_matvec(bk_symsolver *f, const double *vals, const double *x, double *y);
/* Keeps the values now: into keep[nval] when they are borrowed, else by
 * swapping the arrays (*keep gets the values now, now the old *keep). */
void bk_sym_keep_now(bk_symsolver *f, double **keep);

#endif
