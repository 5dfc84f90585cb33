/* band_test_util.h -- what the band solvers' C checks share (band_check.c,
 * bandsplit_check.c, symsplit_check.c): their random numbers, the random
 * matrices shaped like the Newton systems of beams (chains of node blocks in
 * a scrambled numbering, as a dense row-major matrix with its pattern), the
 * dense matrix's compressed columns, and its product with a vector.  The
 * references each check solves against (dense eliminations, eigenvalue
 * counts) stay in the checks: they are what differs between them. */
#ifndef BAND_TEST_UTIL_H
#define BAND_TEST_UTIL_H

#include <stdlib.h>

/* Uniform in [0, 1) from the xorshift state *s (a check's own seed). */
static inline double bt_urand(unsigned long long *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return (double)(*s >> 11) / 9007199254740992.0;
}

/* A random permutation of 0 .. n-1 (Fisher-Yates), malloc'ed: the scrambled
 * numbering the band orderings must undo. */
static inline int *bt_scramble(int n, unsigned long long *s)
{
    int *scr = malloc((size_t)n * sizeof *scr);
    if (!scr)
        return NULL;
    for (int i = 0; i < n; ++i)
        scr[i] = i;
    for (int i = n - 1; i > 0; --i) {
        int j = (int)(bt_urand(s) * (i + 1)), t = scr[i];
        scr[i] = scr[j];
        scr[j] = t;
    }
    return scr;
}

/* How bt_chain draws a neighbours' block: */
enum {
    BT_UNSYMMETRIC,          /* every entry drawn and added */
    BT_SYMMETRIC,            /* every entry drawn, those of the upper triangle with its diagonal added to
                              * (i, j) and (j, i) */
    BT_SYMMETRIC_SET         /* the strictly lower triangle drawn, set (not added) at (i, j) and (j, i) */
};

/* The chain of `nodes` nodes of bs unknowns: each two neighbours' 2 bs x 2 bs
 * block, values uniform in [-0.5, 0.5) (drawn in row order of the block), put
 * into D[n n] (row-major) and its pattern mask[n n] at the scrambled rows and
 * columns scr[] (unknown k of node e is e bs + k before scrambling). */
static inline void bt_chain(double *D, char *mask, int n, const int *scr, int nodes, int bs, int how,
                            unsigned long long *s)
{
    for (int e = 0; e + 1 < nodes; ++e)
        for (int a = 0; a < 2 * bs; ++a)
            for (int c = 0; c < 2 * bs; ++c) {
                if (how == BT_SYMMETRIC_SET && c >= a)
                    continue;
                const double v = bt_urand(s) - 0.5;
                if (how == BT_SYMMETRIC && c < a)
                    continue;
                const long i = scr[e * bs + a], j = scr[e * bs + c];
                if (how == BT_SYMMETRIC_SET) {
                    D[i * n + j] = D[j * n + i] = v;
                } else {
                    D[i * n + j] += v;
                    if (how == BT_SYMMETRIC && i != j)
                        D[j * n + i] += v;
                }
                mask[i * n + j] = 1;
                if (how != BT_UNSYMMETRIC)
                    mask[j * n + i] = 1;
            }
}

/* The entries of D where mask is set, as compressed columns into Ap[n + 1],
 * Ai, Ax (room for every set entry; columns and rows ascending). */
static inline void bt_to_csc(int n, const double *D, const char *mask, int *Ap, int *Ai, double *Ax)
{
    int k = 0;
    for (int j = 0; j < n; ++j) {
        Ap[j] = k;
        for (int i = 0; i < n; ++i)
            if (mask[(long)i * n + j]) {
                Ai[k] = i;
                Ax[k++] = D[(long)i * n + j];
            }
    }
    Ap[n] = k;
}

/* The same, allocated (*Ap, *Ai, *Ax malloc'ed); returns the entries' count. */
static inline int bt_csc(int n, const double *D, const char *mask, int **Ap, int **Ai, double **Ax)
{
    int nnz = 0;
    for (long k = 0; k < (long)n * n; ++k)
        nnz += mask[k];
    *Ap = malloc((size_t)(n + 1) * sizeof **Ap);
    *Ai = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof **Ai);
    *Ax = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof **Ax);
    if (*Ap && *Ai && *Ax)
        bt_to_csc(n, D, mask, *Ap, *Ai, *Ax);
    return nnz;
}

/* y[n] = D x (D row-major n x n). */
static inline void bt_matvec(int n, const double *D, const double *x, double *y)
{
    for (int i = 0; i < n; ++i) {
        y[i] = 0.0;
        for (int j = 0; j < n; ++j)
            y[i] += D[(long)i * n + j] * x[j];
    }
}

#endif
