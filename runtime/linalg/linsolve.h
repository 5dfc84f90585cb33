/* linsolve.h -- sparse direct solves: a band LU (bandlu.h) when the matrix is
 * a narrow band in reverse Cuthill-McKee order (beams, chains of beams), else
 * KLU (SuiteSparse).
 *
 * Band: the ordering and the band layout are planned once by bk_lin_init();
 * every factorization chooses its pivots (partial pivoting within the band)
 * in place, with no allocation.  KLU: the symbolic analysis (fill-reducing ordering, block triangular form) is
 * computed once for a pattern by bk_lin_init() and reused by every numeric
 * factorization.  The first numeric factorization chooses the pivots and
 * allocates the factors; later ones refactor in place with those pivots
 * (klu_refactor, no allocation) and fall back to a full factorization only
 * when the refactored matrix looks much worse conditioned.  The solver owns
 * its KLU objects; the pattern arrays stay owned by the caller and must
 * outlive the solver.
 */
#ifndef BK_LINSOLVE_H
#define BK_LINSOLVE_H

#include <klu.h>

#include "linalg/bandlu.h"

/* The band solver is used when its storage stays within BK_BAND_MAX_STORAGE
 * and its width kl + ku within BK_BAND_MAX_WIDTH (bandlu.h). */

typedef struct bk_linsolver {
    int n;
    int use_band;            /* 1: the band LU below, 0: KLU */
    bk_band band;
    const int *Ap, *Ai;
    klu_common common;
    klu_symbolic *sym;
    klu_numeric *num;
    int nanalyze, nfactor;   /* counters, for the summary: analyses, numeric factorizations */
    int nfull;               /* of the nfactor: full factorizations (new pivots, allocating) */
    double rcond;            /* crude reciprocal condition estimate of the last factorization */
    double rcond_factor;     /* the same, of the last full factorization */
} bk_linsolver;

enum { BK_LIN_OK = 0, BK_LIN_SINGULAR = 1, BK_LIN_ERROR = 2 };

int bk_lin_init(bk_linsolver *s, int n, const int *Ap, const int *Ai);
/* Factors the matrix with values Ax on the analysed pattern. */
int bk_lin_factor(bk_linsolver *s, double *Ax);
/* Solves A x = b in place (b has n entries). */
int bk_lin_solve(bk_linsolver *s, double *b);
/* bk_lin_factor then bk_lin_solve (the same results): the band solver does the
 * forward substitution during the elimination.  b is unspecified unless
 * BK_LIN_OK is returned. */
int bk_lin_factor_solve(bk_linsolver *s, double *Ax, double *b);
void bk_lin_free(bk_linsolver *s);

#endif
