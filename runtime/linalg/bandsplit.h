/* bandsplit.h -- the band LU of a long band split in two halves that two
 * threads factor at once: nested dissection with one separator.
 *
 * In the band LU's reverse Cuthill-McKee order (bandlu.h) the unknowns are
 * cut into block 1 = [0, m), the separator S = [m, m + s) with s = max(kl, ku)
 * and block 2 = [m + s, n): no entry couples the two blocks.  Block 2 is taken
 * in reverse order (its half bandwidths swap), so that each block meets the
 * separator in its last rows and columns:
 *
 *     [ B1  0   E1 ]        B_X = P_X L_X U_X   band LU with interchanges
 *     [ 0   B2  E2 ]        inside the block only (threshold pivoting as
 *     [ F1  F2  D  ]        bandlu.h), each block on its own thread;
 *
 *     D' = D - F1 B1^-1 E1 - F2 B2^-1 E2   (s x s, dense LU with partial
 *     pivoting).  E_X is non-zero in the block's last ku_X rows, F_X in its
 *     last kl_X columns, so W_X = L_X^-1 P_X E_X is non-zero only in its last
 *     kl_X + ku_X rows and F_X U_X^-1 W_X needs only the last kl_X rows of
 *     U_X^-1 W_X: the back substitution of the block's tail.  The separator
 *     costs O(s^2 (kl + ku)), not a pass over the blocks.
 *
 * A solve: forward substitution in both blocks (two threads), the separator's
 * right-hand side from the blocks' tails, the separator's solve, then the
 * blocks' back substitutions (two threads).  The operations do not depend on
 * the number of threads: the same bits with 1 or 2.  Rows are scaled by the
 * inverse of their largest entry first, as in bandlu.h.
 *
 * Sizes and directions (n unknowns, CSC pattern Ap[n+1], Ai[nnz]; perm[n] the
 * band order new -> old, kl, ku its half bandwidths, e.g. a bk_band plan's):
 *   bk_bandsplit_plan   out: the plan (owns every array; the pattern and perm
 *                       are copied or referenced: Ap, Ai must outlive it).
 *                       0, or -1 out of memory.
 *   bk_bandsplit_factor in: Ax[nnz].  0, 1 singular (a block column without a
 *                       non-zero candidate pivot, or a zero separator pivot),
 *                       2 a non-finite value.  No allocation.
 *   bk_bandsplit_solve  in/out: x[n] (b in, the solution out).  No allocation.
 *   rcond               after a factorization: min |u_jj| / max |u_jj| over the
 *                       blocks' and the separator's pivots (scaled matrix). */
#ifndef BK_BANDSPLIT_H
#define BK_BANDSPLIT_H

/* Fewer unknowns than this: one band (bandlu.h).  Above, a half takes more
 * than the fork and join of two threads and the separator's O(s^3). */
#define BK_BANDSPLIT_MIN 20000

typedef struct bk_bandblock {
    int nb, kl, ku, klp, ldab, kvu;  /* size, half bandwidths (local order), storage as bandlu.h */
    int first, step;                 /* local index i is new index first + step i */
    double *ab;                      /* [ldab nb] the band, column-major */
    int *ipiv;                       /* [nb] */
    int j0, t;                       /* W's rows are [j0, nb): t = nb - j0 */
    double *E;                       /* [s (ku)]: E_X's last ku rows, column c at E + c ku */
    double *F;                       /* [s (kl)]: F_X's last kl columns, row a at F + a kl */
    double *W;                       /* [s t]: W_X rows j0..nb-1, column c at W + c t */
    double *Z;                       /* [s kl]: the last kl rows of U_X^-1 W_X, column c at Z + c kl */
    double *C;                       /* [s s]: F_X U_X^-1 W_X, column-major */
    double *y;                       /* [nb] scratch of a solve: the block's unknowns, local order */
    double *z;                       /* [kl] scratch of a solve: the tail of U_X^-1 y */
    double umin, umax;
    int status;
} bk_bandsplit_block;

typedef struct bk_bandsplit {
    int n, kl, ku, s, m;
    const int *Ap, *Ai;
    int *perm, *iperm;               /* [n] new -> old, old -> new */
    double *rs;                      /* [n] row scales, new order */
    double *sep;                     /* [3 s] scratch: the separator rows' maxima in each block; its unknowns */
    double *D;                       /* [s s] the separator, then its LU (column-major) */
    int *dpiv;                       /* [s] */
    bk_bandsplit_block blk[2];
    double rcond;
} bk_bandsplit;

int bk_bandsplit_plan(bk_bandsplit *b, int n, const int *Ap, const int *Ai, const int *perm, int kl, int ku);
int bk_bandsplit_factor(bk_bandsplit *b, const double *Ax);
void bk_bandsplit_solve(bk_bandsplit *b, double *x);
void bk_bandsplit_free(bk_bandsplit *b);

#endif
