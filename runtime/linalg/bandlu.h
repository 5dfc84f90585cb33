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
 *                  out: the plan (permutation, band widths; an entry's place
 *                  in the band follows from the permutation, which the fill
 *                  reads anyway for the row scale: no map of nnz places in the
 *                  stream the factorization reads).  Returns 0, 1 when the band would be
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
    int dirty;               /* superdiagonals of ab that may hold non-zeros (the next
                              * factorization zeroes those above ku) */
    int *perm, *iperm;       /* [n] new -> old, old -> new */
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
/* The storage ab was used as scratch (stability.c borrows it): the next
 * factorization zeroes all of it, not only the band and the rows the last
 * factorization's interchanges filled. */
void bk_band_clobbered(bk_band *b);
void bk_band_free(bk_band *b);


/* bandsym: LDL^T without pivoting of a symmetric matrix stored as a band
 * (lower triangle) after the same reverse Cuthill-McKee ordering: for the
 * inertia of a symmetric matrix (the negative entries of D, by Sylvester's law
 * the negative eigenvalues) and solves with it.
 *   bk_bandsym_plan   in: n, the CSC pattern Ap[n+1], Ai[nnz], order[n] (a
 *                     symmetric order to use, new -> old: e.g. the band LU's of
 *                     the same pattern) or NULL (reverse Cuthill-McKee of the
 *                     pattern), kd: the half bandwidth of the pattern in
 *                     `order` when the caller knows it (the band LU's
 *                     max(kl, ku)), else -1 (found here), the largest band
 *                     storage allowed (doubles); out: perm, iperm, kd.  0, 1
 *                     (band larger than allowed), -1 (out of memory).  The
 *                     pattern stays the caller's.
 *   bk_bandsym_fill   in: a CSC pattern Ap[n+1], Ai[nnz] (the plan's, or one
 *                     within its band) and values Ax[nnz] on it; out:
 *                     band[ldab n], its symmetric part (A + A^T) / 2 in the
 *                     band layout (column c of the new order at band + c ldab,
 *                     row c + r at [r]); an entry without its transpose counts
 *                     half.  Each entry's place from iperm (no map of nnz
 *                     places: reading one costs as much as the look-up, and its
 *                     pages are memory a small model's check would touch the
 *                     first time, at 1-10 us a page).
 *   bk_bandsym_factor in: band[ldab n] as filled (band may be b->ab: factored in
 *                     place); 0, or -1 on a zero or non-finite pivot (D[j], new
 *                     order, holds the pivots); no allocation;
 *   bk_bandsym_solve  x[n] overwritten with A^-1 x (w[n] of the plan as scratch).
 *   bk_bandsym_matvec y[n] = A x for the band values `band` (as filled), x and y
 *                     in the original order (w[n] of the plan as scratch). */
typedef struct bk_bandsym {
    int n, kd, ldab;         /* half bandwidth; ldab: kd + 1 rounded up to BK_BAND_LANES */
    int *perm, *iperm;       /* [n] new -> old, old -> new */
    double *ab, *D, *w;      /* [ldab n] the factor; [n] pivots; [n] scratch */
    double *piv;             /* [ldab + BK_BAND_LANES] the factor's pivot column (scratch) */
} bk_bandsym;

int bk_bandsym_plan(bk_bandsym *b, int n, const int *Ap, const int *Ai, const int *order, int kd, long max_storage);
void bk_bandsym_fill(const bk_bandsym *b, const int *Ap, const int *Ai, const double *Ax, double *band);
int bk_bandsym_factor(bk_bandsym *b, const double *band);
void bk_bandsym_solve(bk_bandsym *b, double *x);
void bk_bandsym_matvec(bk_bandsym *b, const double *band, const double *x, double *y);
void bk_bandsym_free(bk_bandsym *b);

#endif
