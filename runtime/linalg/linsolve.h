/* linsolve.h -- the linear solver of the Newton systems as an object: one
 * interface (init, factor, solve, factor_solve, free; counters and a pivot
 * ratio) over swappable backends, each in its own file:
 *   band LU  (lin_band.c, bandlu.h) for a matrix that is a narrow band in
 *            reverse Cuthill-McKee order (beams, chains of beams): planned
 *            once, every factorization pivots within the band in place, no
 *            allocation;
 *   KLU      (lin_klu.c, SuiteSparse) otherwise: the symbolic analysis
 *            (fill-reducing ordering, block triangular form) once per
 *            pattern; the first numeric factorization chooses pivots and
 *            allocates, later ones refactor in place (klu_refactor) and fall
 *            back to a full factorization when the refactored matrix looks
 *            much worse conditioned;
 *   split band LU (lin_bandsplit.c, bandsplit.h) for such a band of at least
 *            BK_BANDSPLIT_MIN unknowns: two halves factored on two threads
 *            and a separator;
 *   dense LU (lin_dense.c) with partial pivoting on the n x n matrix, for
 *            small systems and as an independent check of the others.
 * BK_LIN_AUTO picks the band when its storage stays within
 * BK_BAND_MAX_STORAGE and its width kl + ku within BK_BAND_MAX_WIDTH
 * (bandlu.h), else KLU.  The pattern arrays (CSC, n columns) stay owned by the
 * caller and must outlive the solver; the solver owns everything else.
 *
 * Sizes and directions: Ax[nnz] values on the pattern (in; a factorization
 * may keep pointers to nothing of it after it returns); b[n] right-hand side
 * in, solution out.  Results: BK_LIN_OK, BK_LIN_SINGULAR (zero or
 * numerically zero pivot: rcond not above 1e-300), BK_LIN_ERROR (out of
 * memory, no factors).
 */
#ifndef BK_LINSOLVE_H
#define BK_LINSOLVE_H

#include <klu.h>

#include "linalg/bandlu.h"
#include "linalg/bandsplit.h"

enum { BK_LIN_OK = 0, BK_LIN_SINGULAR = 1, BK_LIN_ERROR = 2 };
typedef enum bk_lin_kind { BK_LIN_AUTO = 0, BK_LIN_BAND, BK_LIN_KLU, BK_LIN_DENSE } bk_lin_kind;

struct bk_linsolver;

/* A backend: what the interface's calls do (lin_band.c, lin_klu.c, lin_dense.c). */
typedef struct bk_lin_ops {
    const char *name;
    int (*factor)(struct bk_linsolver *s, double *Ax);
    int (*solve)(struct bk_linsolver *s, double *b);
    int (*factor_solve)(struct bk_linsolver *s, double *Ax, double *b);
    void (*free)(struct bk_linsolver *s);
} bk_lin_ops;

typedef struct bk_linsolver {
    const bk_lin_ops *ops;   /* the backend */
    int n;
    const int *Ap, *Ai;      /* the pattern (not owned) */
    int nanalyze, nfactor;   /* counters, for the summary: analyses, numeric factorizations */
    int nfull;               /* of the nfactor: full factorizations (new pivots, allocating) */
    double rcond;            /* crude reciprocal condition estimate (pivot ratio) of the last factorization */
    double rcond_factor;     /* the same, of the last full factorization */
    /* the backends' state: only the chosen one's is used */
    bk_band band;
    bk_bandsplit split;
    klu_common common;
    klu_symbolic *sym;
    klu_numeric *num;
    double *dense;           /* [n n] column-major LU factors (dense backend) */
    int *dpiv;               /* [n] its row interchanges */
} bk_linsolver;

/* Plans the solver for the pattern with the backend `kind`. */
int bk_lin_init_kind(bk_linsolver *s, int n, const int *Ap, const int *Ai, bk_lin_kind kind);
/* bk_lin_init_kind with BK_LIN_AUTO. */
int bk_lin_init(bk_linsolver *s, int n, const int *Ap, const int *Ai);
/* Factors the matrix with values Ax on the planned pattern. */
int bk_lin_factor(bk_linsolver *s, double *Ax);
/* Solves A x = b in place with the last factors. */
int bk_lin_solve(bk_linsolver *s, double *b);
/* bk_lin_factor then bk_lin_solve (the same results; the band backend does
 * the forward substitution during the elimination).  b is unspecified unless
 * BK_LIN_OK is returned. */
int bk_lin_factor_solve(bk_linsolver *s, double *Ax, double *b);
void bk_lin_free(bk_linsolver *s);
/* The backend's name ("band LU", "KLU", "dense LU"). */
const char *bk_lin_name(const bk_linsolver *s);
/* The band LU's plan when the band backend was chosen, else NULL: the
 * stability service takes its ordering and borrows its storage between
 * factorizations (stability.h). */
bk_band *bk_lin_band(bk_linsolver *s);
/* The split band LU when that backend was chosen, else NULL: the stability
 * service takes its order and cut and borrows its blocks' storage. */
bk_bandsplit *bk_lin_split(bk_linsolver *s);

/* The backends (used by bk_lin_init_kind). */
extern const bk_lin_ops bk_lin_band_ops, bk_lin_bandsplit_ops, bk_lin_klu_ops, bk_lin_dense_ops;
/* required: 0 (auto) answers -1 when the matrix is no narrow band (nothing
 * kept); 1 plans the band whatever its width. */
int bk_lin_band_init(bk_linsolver *s, int required);
/* After a band plan in s->band: the split band LU in its order (the plan's
 * storage freed); BK_LIN_OK, or -1 (out of memory, or too short to split:
 * s->band kept). */
int bk_lin_bandsplit_init(bk_linsolver *s);
/* The band backends' counters and status after a factorization that returned
 * rc (0, 1 singular, 2 non-finite; bandlu.h, bandsplit.h) with pivot ratio rcond. */
int bk_lin_band_status(bk_linsolver *s, int rc, double rcond);
int bk_lin_klu_init(bk_linsolver *s);
int bk_lin_dense_init(bk_linsolver *s);

#endif
