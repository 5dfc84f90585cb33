/* band_impl.h -- what the band LU (bandlu.c) and the band LDL^T (bandsym.c)
 * share (private to linalg/): the inner loop of their eliminations, the
 * symmetric band elimination (with symsplit.c), the reverse Cuthill-McKee ordering and the half bandwidths of an ordering. */
#ifndef BK_BAND_IMPL_H
#define BK_BAND_IMPL_H

/* y[0..m) -= a x[0..m): the inner loop of the factorization and the solves
 * (contiguous, vectorized). */
static inline void axpy_sub(int m, double a, const double *restrict x, double *restrict y)
{
#pragma omp simd
    for (int r = 0; r < m; ++r)
        y[r] -= a * x[r];
}

/* L D L^T without pivoting of the symmetric band ab[ldab n] (lower triangle,
 * column c at ab + c ldab, row c + r at [r]; half bandwidth kd; ldab a
 * multiple of BK_BAND_LANES above kd), in place: L below the diagonal, D[n]
 * the pivots; l[ldab + BK_BAND_LANES] scratch.  0, or -1 at a zero or
 * non-finite pivot (D holds the pivots up to it). */
int bk_band_ldlt(double *ab, int n, int kd, int ldab, double *D, double *l);

/* A reverse Cuthill-McKee ordering of the pattern (n columns Ap, Ai): perm[n];
 * 0, or -1 when out of memory. */
int bk_band_rcm(int n, const int *Ap, const int *Ai, int *perm);
/* The lower and upper half bandwidths of the pattern under iperm (the new
 * index of each old one). */
void bk_band_widths(int n, const int *Ap, const int *Ai, const int *iperm, int *kl, int *ku);

#endif
