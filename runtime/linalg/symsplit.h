/* symsplit.h -- the symmetric band L D L^T (no pivoting) of a long band in
 * two halves and a separator, the halves on two threads: the stability
 * checks' inertia of a band of BK_BANDSPLIT_MIN unknowns and more, split as
 * the band LU splits it (bandsplit.h).
 *
 * The values are a bk_bandsym band (bandlu.h: lower triangle, column c of the
 * band order at band + c ldab, half bandwidth kd).  The band order's unknowns
 * are cut into block 1 = [0, m), the separator S = [m, m + s), s = kd, and
 * block 2 = [m + s, n), taken in reverse order so that both blocks meet the
 * separator in their last kd rows; no entry couples the blocks.  With the
 * unknowns ordered (block 1, block 2, S) the matrix is congruent to
 *
 *     diag(A11, A22, S),   S = A_SS - W1^T D1^-1 W1 - W2^T D2^-1 W2,
 *
 * A_XX = L_X D_X L_X^T (band L D L^T of block X, one thread each) and
 * W_X = L_X^-1 A_XS, non-zero in the block's last kd rows only.  S (s x s) is
 * factored densely without pivoting.  By Sylvester's law of inertia the
 * negative pivots of D1, D2 and D_S together are the negative eigenvalues of
 * the matrix, and their product is its determinant.  The operations do not
 * depend on the number of threads: the same bits with 1 or 2.
 *
 * Sizes and directions (n unknowns, kd, ldab as the bk_bandsym's):
 *   bk_symsplit_plan   in: n, kd, ldab, m (the first separator unknown: the
 *                      band LU's split, or (n - kd) / 2), storage: NULL, or
 *                      two arrays of store_len[X] doubles that block X's
 *                      factor uses when it fits (borrowed: the split band
 *                      LU's blocks, bandsplit.h, which refill them at every
 *                      factorization; its factors are lost).  0, or -1 (out of memory, or a band
 *                      too short: n < 2 kd + 4).
 *   bk_symsplit_factor in: band[ldab n] as filled.  0, or -1 at a zero or
 *                      non-finite pivot.  D[n] holds the pivots in the
 *                      factorization's order (block 1, block 2, S).  No
 *                      allocation.
 *   bk_symsplit_solve  in/out: x[n], in the order of the band's perm (the
 *                      caller permutes): b in, A^-1 b out.  No allocation. */
#ifndef BK_SYMSPLIT_H
#define BK_SYMSPLIT_H

typedef struct bk_symsplit_block {
    int nb, t;                       /* size; the tail rows coupled to S: t = kd (nb > kd) */
    int first, step;                 /* local index i is band index first + step i */
    double *ab;                      /* [ldab nb] the block's band, then its L (unit diagonal implied) */
    int borrowed;                    /* ab is the split band LU's */
    double *D;                       /* [nb] its pivots (in the object's D) */
    double *W;                       /* [s t] A_XS's tail rows, then W = L^-1 A_XS; column c at W + c t */
    double *V;                       /* [s t] D^-1 W */
    double *C;                       /* [s s] W^T D^-1 W, column-major */
    double *l;                       /* [ldab + BK_BAND_LANES] the factor's pivot column */
    double *y;                       /* [nb] scratch of a solve */
} bk_symsplit_block;

typedef struct bk_symsplit {
    int n, kd, ldab, m, s;
    double *D;                       /* [n] pivots: block 1, block 2, S */
    double *S;                       /* [s s] the separator, then its L (column-major, lower) */
    double *xs;                      /* [s] scratch of a solve */
    bk_symsplit_block blk[2];
} bk_symsplit;

int bk_symsplit_plan(bk_symsplit *b, int n, int kd, int ldab, int m, double *const storage[2], const long store_len[2]);
int bk_symsplit_factor(bk_symsplit *b, const double *band);
void bk_symsplit_solve(bk_symsplit *b, double *x);
void bk_symsplit_free(bk_symsplit *b);

#endif
