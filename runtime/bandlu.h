/* bandlu.h -- LU factorization with partial pivoting of a sparse matrix stored
 * as a band after a bandwidth-reducing symmetric permutation.
 *
 * Beam models are chains: with their unknowns in Cuthill-McKee order the
 * Newton matrix is a narrow band (a node couples to its neighbours only), and
 * a dense band factorization with short contiguous inner loops costs a
 * fraction of a general sparse one.  The band is factored like LAPACK's
 * unblocked band LU (row interchanges within the band, so U gets kl extra
 * superdiagonals), after scaling every row by the inverse of its largest
 * entry (as KLU does by default), with threshold pivoting: the diagonal is
 * kept when it is at least BK_BAND_PIVOT_TOL of the largest candidate.
 *
 * Sizes and directions (n unknowns, CSC pattern Ap[n+1], Ai[nnz]):
 *   bk_band_plan   in: n, Ap, Ai, the largest band storage allowed (doubles);
 *                  out: the plan (permutation, band widths, map of every CSC
 *                  entry into the band).  Returns 0, 1 when the band would be
 *                  larger than allowed (use a general sparse solver), -1 when
 *                  out of memory.  The plan owns its arrays; the pattern stays
 *                  the caller's.
 *   bk_band_factor in: Ax[nnz] values on the pattern.  Returns 0, 1 when a
 *                  column has no nonzero candidate pivot (singular), 2 on a
 *                  non-finite value.  No allocation.
 *   bk_band_solve  in/out: b[n], overwritten with the solution of A x = b.
 *                  Uses w[n] of the plan as scratch.  No allocation.
 *   rcond          after a factorization: min |u_jj| / max |u_jj| of the
 *                  scaled matrix (the same crude estimate as klu_rcond).
 */
#ifndef BK_BANDLU_H
#define BK_BANDLU_H

#define BK_BAND_PIVOT_TOL 1e-3
#define BK_BAND_LANES 8          /* doubles per vector register (AVX-512; two AVX2 registers) */

/* Limits of the band solvers' use (linsolve.c, stability.c): storage in
 * doubles, and the width kl + ku (a wider band does more work per column than
 * a sparse factorization's fill). */
#define BK_BAND_MAX_STORAGE (1L << 28)
#define BK_BAND_MAX_WIDTH 240

typedef struct bk_band {
    int n, kl, ku, ldab;     /* ldab = kl + ku + klp + 1 */
    int klp;                 /* kl rounded up to a multiple of BK_BAND_LANES */
    int kvu;                 /* superdiagonals of the last U (ku, up to kl + ku with interchanges) */
    int *perm, *iperm;       /* [n] new -> old, old -> new */
    long *map;               /* [nnz] position of each CSC entry in ab */
    const int *Ap, *Ai;
    double *ab;              /* [ldab n] the band, column-major (LAPACK layout) */
    double *rs;              /* [n] row scale factors (1 / largest entry), new order */
    int *ipiv;               /* [n] row interchanged with row j at step j */
    double *w;               /* [n] scratch of the solve */
    double rcond;
} bk_band;

int bk_band_plan(bk_band *b, int n, const int *Ap, const int *Ai, long max_storage);
int bk_band_factor(bk_band *b, const double *Ax);
void bk_band_solve(bk_band *b, double *x);
/* bk_band_factor, then bk_band_solve of x[n] (in: b, out: the solution), the
 * forward substitution done during the elimination: the same bits as the two
 * calls.  On a non-zero return x is unspecified. */
int bk_band_factor_solve(bk_band *b, const double *Ax, double *x);
void bk_band_free(bk_band *b);


/* bandsym: LDL^T without pivoting of a symmetric matrix stored as a band
 * (lower triangle) after the same reverse Cuthill-McKee ordering: for the
 * inertia of a symmetric matrix (the negative entries of D, by Sylvester's law
 * the negative eigenvalues) and solves with it.  Same sizes and directions as
 * above; the values are read from the entries (i, j) with i at or below j in
 * the new order (the matrix must be symmetric).
 *   bk_bandsym_plan   order[n]: a symmetric order to use instead (new -> old; e.g.
 *                     the band LU's of the same pattern), or NULL;
 *                     0, 1 (band larger than allowed), -1 (out of memory);
 *   bk_bandsym_factor 0, or -1 on a zero or non-finite pivot (D[j], new order,
 *                     holds the pivots); no allocation;
 *   bk_bandsym_solve  x[n] overwritten with A^-1 x (w[n] of the plan as scratch). */
typedef struct bk_bandsym {
    int n, kd, ldab;         /* half bandwidth, ldab = kd + 1 */
    int *perm, *iperm;
    long *map;               /* [nnz] position in ab, -1: the upper triangle (ignored) */
    const int *Ap, *Ai;
    double *ab, *D, *w;
} bk_bandsym;

int bk_bandsym_plan(bk_bandsym *b, int n, const int *Ap, const int *Ai, const int *order, long max_storage);
int bk_bandsym_factor(bk_bandsym *b, const double *Ax);
void bk_bandsym_solve(bk_bandsym *b, double *x);
void bk_bandsym_free(bk_bandsym *b);

#endif
