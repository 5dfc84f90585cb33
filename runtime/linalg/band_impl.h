/* band_impl.h -- what the band LU (bandlu.c) and the band LDL^T (bandsym.c)
 * share (private to linalg/): the inner loop of their eliminations, the
 * reverse Cuthill-McKee ordering and the half bandwidths of an ordering. */
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

/* A reverse Cuthill-McKee ordering of the pattern (n columns Ap, Ai): perm[n];
 * 0, or -1 when out of memory. */
int bk_band_rcm(int n, const int *Ap, const int *Ai, int *perm);
/* The lower and upper half bandwidths of the pattern under iperm (the new
 * index of each old one). */
void bk_band_widths(int n, const int *Ap, const int *Ai, const int *iperm, int *kl, int *ku);

#endif
