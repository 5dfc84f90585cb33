/* bandsym.c -- the symmetric band L D L^T (no pivoting) of the stability
 * checks: plan, fill from the sparse matrix, factor, solve, product (see
 * bandlu.h). */
#include "linalg/bandlu.h"
#include "base/bigalloc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/band_impl.h"
#include "linalg/bandsplit.h"

int bk_bandsym_plan(bk_bandsym *b, int n, const int *Ap, const int *Ai, const int *order, int kd, long max_storage)
{
    memset(b, 0, sizeof *b);
    b->n = n;
    size_t N = (size_t)(n > 0 ? n : 1);
    b->perm = malloc(N * sizeof *b->perm);
    b->iperm = malloc(N * sizeof *b->iperm);
    if (!b->perm || !b->iperm || (!order && bk_band_rcm(n, Ap, Ai, b->perm) != 0)) {
        bk_bandsym_free(b);
        return -1;
    }
    if (order)
        memcpy(b->perm, order, (size_t)n * sizeof *b->perm);
    for (int i = 0; i < n; ++i)
        b->iperm[b->perm[i]] = i;
    if (!order || kd < 0) {
        int kl, ku;
        bk_band_widths(n, Ap, Ai, b->iperm, &kl, &ku);
        kd = kl > ku ? kl : ku;
    }
    b->kd = kd;
    /* kd + 1 rounded up to whole vectors: the factor's updates are whole vectors */
    b->ldab = (kd + BK_BAND_LANES) / BK_BAND_LANES * BK_BAND_LANES;
    if ((double)b->ldab * n > (double)max_storage) {
        bk_bandsym_free(b);
        return 1;
    }
    b->ab = bk_big_advise(aligned_alloc(64, (size_t)b->ldab * N * sizeof *b->ab), (size_t)b->ldab * N * sizeof *b->ab);
    b->D = malloc(N * sizeof *b->D);
    b->w = malloc(N * sizeof *b->w);
    b->piv = aligned_alloc(64, (size_t)(b->ldab + BK_BAND_LANES) * sizeof *b->piv);
    if (!b->ab || !b->D || !b->w || !b->piv) {
        bk_bandsym_free(b);
        return -1;
    }
    return 0;
}

/* Halves the off-diagonal entries of band column c: each holds a + a^T (or a
 * alone); the diagonal is its own transpose. */
static void halve_column(double *col, int ldab)
{
    const double d = col[0];
#pragma omp simd
    for (int r = 0; r < ldab; ++r)
        col[r] *= 0.5;
    col[0] = d;
}

void bk_bandsym_fill(const bk_bandsym *b, const int *Ap, const int *Ai, const double *Ax, double *band)
{
    const int n = b->n, ldab = b->ldab, *restrict iperm = b->iperm, *restrict perm = b->perm;
    if (n < BK_BANDSPLIT_MIN) {
        memset(band, 0, (size_t)ldab * (size_t)n * sizeof *band);
        for (int j = 0; j < n; ++j) {
            const int c = iperm[j];
            for (int p = Ap[j]; p < Ap[j + 1]; ++p) {
                /* (r, c) and (c, r) share the lower entry */
                const int r = iperm[Ai[p]], lo = r < c ? r : c, hi = r < c ? c : r;
                band[(hi - lo) + (long)lo * ldab] += Ax[p];
            }
        }
        for (int c = 0; c < n; ++c)
            halve_column(band + (long)c * ldab, ldab);
        return;
    }
    /* a long band on the threads, by band column c (the pattern's column
     * perm[c]): first its entries on and below the diagonal into column c,
     * then those above into the column of their row; each place gets at most
     * one entry in each pass, and a sum of two is the same whatever their
     * order: the same bits as above, on any number of threads */
#pragma omp parallel
    {
#pragma omp for schedule(static)
        for (int c = 0; c < n; ++c) {
            double *col = band + (long)c * ldab;
            memset(col, 0, (size_t)ldab * sizeof *col);
            const int j = perm[c];
            for (int p = Ap[j]; p < Ap[j + 1]; ++p) {
                const int r = iperm[Ai[p]];
                if (r >= c)
                    col[r - c] += Ax[p];
            }
        }
#pragma omp for schedule(static)
        for (int c = 0; c < n; ++c) {
            const int j = perm[c];
            for (int p = Ap[j]; p < Ap[j + 1]; ++p) {
                const int r = iperm[Ai[p]];
                if (r < c)
                    band[(c - r) + (long)r * ldab] += Ax[p];
            }
        }
#pragma omp for schedule(static)
        for (int c = 0; c < n; ++c)
            halve_column(band + (long)c * ldab, ldab);
    }
}

int bk_band_ldlt(double *ab, int n, int kd, int ldab, double *D, double *restrict l)
{
    for (int r = 0; r < ldab + BK_BAND_LANES; ++r)
        l[r] = 0.0;
    for (int j = 0; j < n; ++j) {
        double *col = ab + (long)j * ldab;           /* col[r] = A(j + r, j) */
        const double d = col[0];
        D[j] = d;
        if (d == 0.0 || !isfinite(d))
            return -1;
        const int km = kd < n - 1 - j ? kd : n - 1 - j;
        const double inv = 1.0 / d;
        /* l: column j below the pivot, zero beyond its last row, so that every
         * update below is whole vectors (the rows past km stay unchanged) */
        for (int r = 1; r <= km; ++r)
            l[r] = col[r];
        for (int c = 1; c <= km; ++c) {              /* column j + c, rows j + c ... j + km */
            const double f = col[c] * inv;
            if (f == 0.0)
                continue;
            double *restrict y = ab + (long)(j + c) * ldab;
            const double *restrict x = l + c;
            for (int r0 = 0; r0 <= km - c; r0 += BK_BAND_LANES) {
#pragma omp simd
                for (int r = 0; r < BK_BAND_LANES; ++r)
                    y[r0 + r] -= f * x[r0 + r];
            }
        }
        for (int r = 1; r <= km; ++r) {
            col[r] *= inv;
            l[r] = 0.0;
        }
    }
    return 0;
}

int bk_bandsym_factor(bk_bandsym *b, const double *band)
{
    if (band != b->ab)
        memcpy(b->ab, band, (size_t)b->ldab * (size_t)b->n * sizeof *b->ab);
    return bk_band_ldlt(b->ab, b->n, b->kd, b->ldab, b->D, b->piv);
}

void bk_bandsym_solve(bk_bandsym *b, double *x)
{
    const int n = b->n, kd = b->kd, ldab = b->ldab;
    const double *ab = b->ab;
    double *w = b->w;
    for (int i = 0; i < n; ++i)
        w[i] = x[b->perm[i]];
    for (int j = 0; j < n; ++j) {                    /* L */
        const int km = kd < n - 1 - j ? kd : n - 1 - j;
        if (w[j] != 0.0)
            axpy_sub(km, w[j], ab + (long)j * ldab + 1, w + j + 1);
    }
    for (int j = 0; j < n; ++j)                      /* D */
        w[j] /= b->D[j];
    for (int j = n - 1; j >= 0; --j) {               /* L^T */
        const int km = kd < n - 1 - j ? kd : n - 1 - j;
        const double *col = ab + (long)j * ldab + 1;
        double s = 0.0;
        for (int r = 0; r < km; ++r)
            s += col[r] * w[j + 1 + r];
        w[j] -= s;
    }
    for (int i = 0; i < n; ++i)
        x[b->perm[i]] = w[i];
}

void bk_bandsym_matvec(bk_bandsym *b, const double *band, const double *x, double *y)
{
    const int n = b->n, kd = b->kd, ldab = b->ldab;
    double *w = b->w;
    for (int i = 0; i < n; ++i)
        w[i] = 0.0;
    for (int c = 0; c < n; ++c) {
        const int km = kd < n - 1 - c ? kd : n - 1 - c;
        const double *col = band + (long)c * ldab, xc = x[b->perm[c]];
        double s = col[0] * xc;
        for (int r = 1; r <= km; ++r) {
            const double xr = x[b->perm[c + r]];
            w[c + r] += col[r] * xc;
            s += col[r] * xr;
        }
        w[c] += s;
    }
    for (int i = 0; i < n; ++i)
        y[b->perm[i]] = w[i];
}

void bk_bandsym_free(bk_bandsym *b)
{
    free(b->perm);
    free(b->iperm);
    free(b->piv);
    free(b->ab);
    free(b->D);
    free(b->w);
    memset(b, 0, sizeof *b);
}

