/* symsplit.c -- the symmetric band L D L^T of a long band in two halves and a
 * separator, the halves on two threads (see symsplit.h). */
#include "linalg/symsplit.h"
#include "base/bigalloc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/band_impl.h"
#include "linalg/bandlu.h"

static int block_plan(bk_symsplit_block *x, int nb, int first, int step, int s, int ldab, double *D, double *store,
                      long store_len)
{
    memset(x, 0, sizeof *x);
    x->nb = nb;
    x->t = s;
    x->first = first;
    x->step = step;
    x->D = D;
    const size_t S = (size_t)s, len = (size_t)ldab * (size_t)nb;
    if (store && (long)len <= store_len) {
        x->ab = store;
        x->borrowed = 1;
    } else
        x->ab = bk_big_malloc(len * sizeof *x->ab);
    x->W = malloc(S * S * sizeof *x->W);
    x->V = malloc(S * S * sizeof *x->V);
    x->C = malloc(S * S * sizeof *x->C);
    x->l = malloc(((size_t)ldab + BK_BAND_LANES) * sizeof *x->l);
    x->y = malloc((size_t)nb * sizeof *x->y);
    return x->ab && x->W && x->V && x->C && x->l && x->y ? 0 : -1;
}

static void block_free(bk_symsplit_block *x)
{
    if (!x->borrowed)
        free(x->ab);
    free(x->W);
    free(x->V);
    free(x->C);
    free(x->l);
    free(x->y);
    memset(x, 0, sizeof *x);
}

int bk_symsplit_plan(bk_symsplit *b, int n, int kd, int ldab, int m, double *const storage[2], const long store_len[2])
{
    memset(b, 0, sizeof *b);
    if (kd < 1 || n < 2 * kd + 4 || m < kd + 1 || n - m - kd < kd + 1)
        return -1;
    b->n = n;
    b->kd = kd;
    b->ldab = ldab;
    b->m = m;
    b->s = kd;
    const size_t S = (size_t)kd;
    b->D = malloc((size_t)n * sizeof *b->D);
    b->S = malloc(S * S * sizeof *b->S);
    b->xs = malloc(S * sizeof *b->xs);
    if (!b->D || !b->S || !b->xs ||
        block_plan(&b->blk[0], m, 0, 1, kd, ldab, b->D, storage ? storage[0] : NULL, storage ? store_len[0] : 0) != 0 ||
        block_plan(&b->blk[1], n - m - kd, n - 1, -1, kd, ldab, b->D ? b->D + m : NULL,
                   storage ? storage[1] : NULL, storage ? store_len[1] : 0) != 0) {
        bk_symsplit_free(b);
        return -1;
    }
    return 0;
}

void bk_symsplit_free(bk_symsplit *b)
{
    free(b->D);
    free(b->S);
    free(b->xs);
    block_free(&b->blk[0]);
    block_free(&b->blk[1]);
    memset(b, 0, sizeof *b);
}

/* ---- the factorization ---- */

/* Block X's band and its coupling to the separator (the tail rows of A_XS)
 * from the whole band; its L D L^T; W = L^-1 A_XS, V = D^-1 W and
 * C = W^T D^-1 W.  0, or -1 at a zero or non-finite pivot. */
static int block_factor(bk_symsplit *b, int X, const double *band)
{
    bk_symsplit_block *x = &b->blk[X];
    const int nb = x->nb, kd = b->kd, ldab = b->ldab, s = b->s, m = b->m, t = x->t, n = b->n;
    double *ab = x->ab;
    if (X == 0) {                                    /* block 1: the band's first m columns, cut at m */
        memcpy(ab, band, (size_t)ldab * (size_t)nb * sizeof *ab);
        for (int c = nb - kd; c < nb; ++c)
            for (int r = nb - c; r <= kd; ++r)
                ab[r + (long)c * ldab] = 0.0;
    } else {                                         /* block 2, reversed: local (i + d, i) is the */
        for (int i = 0; i < nb; ++i) {               /* band's (g - d, g) with g = n - 1 - i: the */
            double *col = ab + (long)i * ldab;       /* lower entry d of column g - d */
            const int km = kd < nb - 1 - i ? kd : nb - 1 - i;
            for (int d = 0; d <= km; ++d)
                col[d] = band[d + (long)(n - 1 - i - d) * ldab];
            for (int d = km + 1; d < ldab; ++d)
                col[d] = 0.0;
        }
    }
    /* W: rows nb - t ... nb - 1 of A_XS (the band row g of separator column m + c) */
    for (int c = 0; c < s; ++c)
        for (int i = nb - t; i < nb; ++i) {
            const int g = x->first + x->step * i, lo = g < m + c ? g : m + c, d = abs(g - (m + c));
            x->W[(long)c * t + (i - (nb - t))] = d <= kd ? band[d + (long)lo * ldab] : 0.0;
        }
    if (bk_band_ldlt(ab, nb, kd, ldab, x->D, x->l) != 0)
        return -1;
    for (int c = 0; c < s; ++c) {                    /* W = L^-1 A_XS on the tail rows */
        double *w = x->W + (long)c * t;
        for (int j = nb - t; j < nb; ++j) {
            const int km = kd < nb - 1 - j ? kd : nb - 1 - j;
            const double a = w[j - (nb - t)];
            if (a != 0.0)
                axpy_sub(km, a, ab + 1 + (long)j * ldab, w + j - (nb - t) + 1);
        }
        for (int i = 0; i < t; ++i)
            x->V[(long)c * t + i] = w[i] / x->D[nb - t + i];
    }
    for (int c = 0; c < s; ++c)                      /* C = W^T V */
        for (int a = 0; a < s; ++a) {
            double sum = 0.0;
            for (int i = 0; i < t; ++i)
                sum += x->W[(long)a * t + i] * x->V[(long)c * t + i];
            x->C[a + (long)c * s] = sum;
        }
    return 0;
}

int bk_symsplit_factor(bk_symsplit *b, const double *band)
{
    const int s = b->s, m = b->m, kd = b->kd, ldab = b->ldab;
    int st[2] = {0, 0};
#pragma omp parallel for schedule(static, 1)
    for (int X = 0; X < 2; ++X)
        st[X] = block_factor(b, X, band);
    if (st[0] || st[1])
        return -1;
    /* S = A_SS - C1 - C2 (lower triangle), then its L D L^T */
    double *S = b->S, *DS = b->D + (b->n - s);
    for (int c = 0; c < s; ++c)
        for (int a = c; a < s; ++a)
            S[a + (long)c * s] = (a - c <= kd ? band[(a - c) + (long)(m + c) * ldab] : 0.0) -
                                 b->blk[0].C[a + (long)c * s] - b->blk[1].C[a + (long)c * s];
    for (int j = 0; j < s; ++j) {
        double *col = S + (long)j * s;
        const double d = col[j];
        DS[j] = d;
        if (d == 0.0 || !isfinite(d))
            return -1;
        for (int k = j + 1; k < s; ++k) {            /* column k, rows k ... s - 1 */
            const double f = col[k] / d;
            if (f != 0.0)
                axpy_sub(s - k, f, col + k, S + k + (long)k * s);
        }
        for (int r = j + 1; r < s; ++r)
            col[r] /= d;
    }
    return 0;
}

/* ---- the solve ---- */

/* y = L_X^-1 (block X's part of x). */
static void block_forward(bk_symsplit *b, int X, const double *x_in)
{
    bk_symsplit_block *x = &b->blk[X];
    const int nb = x->nb, kd = b->kd, ldab = b->ldab;
    double *y = x->y;
    for (int i = 0; i < nb; ++i)
        y[i] = x_in[x->first + x->step * i];
    for (int j = 0; j < nb; ++j) {
        const int km = kd < nb - 1 - j ? kd : nb - 1 - j;
        if (y[j] != 0.0)
            axpy_sub(km, y[j], x->ab + 1 + (long)j * ldab, y + j + 1);
    }
}

/* y = L_X^-T (D_X^-1 y - V xs) into block X's part of x. */
static void block_back(bk_symsplit *b, int X, double *x_out)
{
    bk_symsplit_block *x = &b->blk[X];
    const int nb = x->nb, kd = b->kd, ldab = b->ldab, t = x->t;
    double *y = x->y;
    for (int i = 0; i < nb; ++i)
        y[i] /= x->D[i];
    for (int c = 0; c < b->s; ++c)
        if (b->xs[c] != 0.0)
            axpy_sub(t, b->xs[c], x->V + (long)c * t, y + nb - t);
    for (int j = nb - 1; j >= 0; --j) {
        const int km = kd < nb - 1 - j ? kd : nb - 1 - j;
        const double *col = x->ab + 1 + (long)j * ldab;
        double sum = 0.0;
        for (int r = 0; r < km; ++r)
            sum += col[r] * y[j + 1 + r];
        y[j] -= sum;
    }
    for (int i = 0; i < nb; ++i)
        x_out[x->first + x->step * i] = y[i];
}

void bk_symsplit_solve(bk_symsplit *b, double *x)
{
    const int s = b->s, m = b->m;
#pragma omp parallel for schedule(static, 1)
    for (int X = 0; X < 2; ++X)
        block_forward(b, X, x);
    double *xs = b->xs;
    const double *S = b->S, *DS = b->D + (b->n - s);
    for (int k = 0; k < s; ++k) {                   /* the separator's right-hand side: b_S - V^T z */
        double v = x[m + k];
        for (int X = 0; X < 2; ++X) {
            const bk_symsplit_block *bl = &b->blk[X];
            const double *vk = bl->V + (long)k * bl->t, *z = bl->y + (bl->nb - bl->t);
            for (int i = 0; i < bl->t; ++i)
                v -= vk[i] * z[i];
        }
        xs[k] = v;
    }
    for (int j = 0; j < s; ++j)                     /* L_S, D_S, L_S^T */
        if (xs[j] != 0.0)
            axpy_sub(s - j - 1, xs[j], S + j + 1 + (long)j * s, xs + j + 1);
    for (int j = 0; j < s; ++j)
        xs[j] /= DS[j];
    for (int j = s - 1; j >= 0; --j) {
        double sum = 0.0;
        for (int r = j + 1; r < s; ++r)
            sum += S[r + (long)j * s] * xs[r];
        xs[j] -= sum;
    }
#pragma omp parallel for schedule(static, 1)
    for (int X = 0; X < 2; ++X)
        block_back(b, X, x);
    for (int k = 0; k < s; ++k)
        x[m + k] = xs[k];
}
