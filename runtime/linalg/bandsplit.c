/* bandsplit.c -- the band LU of a long band in two halves and a separator,
 * the halves on two threads (see bandsplit.h). */
#include "linalg/bandsplit.h"
#include "base/bigalloc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/band_impl.h"
#include "linalg/bandlu.h"

/* Where new index g lies: 0 block 1, 1 block 2, 2 the separator; *k its
 * index there (block 2 counts from the end). */
static inline int place(const bk_bandsplit *b, int g, int *k)
{
    if (g < b->m) {
        *k = g;
        return 0;
    }
    if (g < b->m + b->s) {
        *k = g - b->m;
        return 2;
    }
    *k = b->n - 1 - g;
    return 1;
}

static int block_plan(bk_bandsplit_block *x, int nb, int kl, int ku, int first, int step, int s)
{
    memset(x, 0, sizeof *x);
    x->nb = nb;
    x->kl = kl;
    x->ku = ku;
    x->first = first;
    x->step = step;
    x->klp = (kl + BK_BAND_LANES - 1) / BK_BAND_LANES * BK_BAND_LANES;
    x->ldab = kl + ku + x->klp + 1;
    x->j0 = nb - ku - kl > 0 ? nb - ku - kl : 0;
    x->t = nb - x->j0;
    size_t S = (size_t)s, L = (size_t)(kl > 0 ? kl : 1), U = (size_t)(ku > 0 ? ku : 1);
    x->ab = bk_big_malloc((size_t)x->ldab * (size_t)nb * sizeof *x->ab);
    x->ipiv = malloc((size_t)nb * sizeof *x->ipiv);
    x->E = malloc(S * U * sizeof *x->E);
    x->F = malloc(S * L * sizeof *x->F);
    x->W = malloc(S * (size_t)x->t * sizeof *x->W);
    x->Z = malloc(S * L * sizeof *x->Z);
    x->C = malloc(S * S * sizeof *x->C);
    x->z = malloc(L * sizeof *x->z);
    x->y = malloc((size_t)nb * sizeof *x->y);
    return x->ab && x->ipiv && x->E && x->F && x->W && x->Z && x->C && x->z && x->y ? 0 : -1;
}

static void block_free(bk_bandsplit_block *x)
{
    free(x->ab);
    free(x->ipiv);
    free(x->E);
    free(x->F);
    free(x->W);
    free(x->Z);
    free(x->C);
    free(x->z);
    free(x->y);
    memset(x, 0, sizeof *x);
}

int bk_bandsplit_plan(bk_bandsplit *b, int n, const int *Ap, const int *Ai, const int *perm, int kl, int ku)
{
    memset(b, 0, sizeof *b);
    const int s = kl > ku ? kl : ku;
    if (s < 1 || n < 2 * s + 4)
        return -1;
    b->n = n;
    b->kl = kl;
    b->ku = ku;
    b->s = s;
    b->m = (n - s) / 2;
    b->Ap = Ap;
    b->Ai = Ai;
    size_t N = (size_t)n, S = (size_t)s;
    b->perm = malloc(N * sizeof *b->perm);
    b->iperm = malloc(N * sizeof *b->iperm);
    b->rs = malloc(N * sizeof *b->rs);
    b->D = malloc(S * S * sizeof *b->D);
    b->dpiv = malloc(S * sizeof *b->dpiv);
    b->sep = malloc(3 * S * sizeof *b->sep);
    if (!b->perm || !b->iperm || !b->rs || !b->D || !b->dpiv || !b->sep ||
        block_plan(&b->blk[0], b->m, kl, ku, 0, 1, s) != 0 ||
        block_plan(&b->blk[1], n - b->m - s, ku, kl, n - 1, -1, s) != 0) {
        bk_bandsplit_free(b);
        return -1;
    }
    memcpy(b->perm, perm, N * sizeof *perm);
    for (int i = 0; i < n; ++i)
        b->iperm[perm[i]] = i;
    b->rcond = NAN;
    return 0;
}

void bk_bandsplit_free(bk_bandsplit *b)
{
    free(b->perm);
    free(b->iperm);
    free(b->rs);
    free(b->D);
    free(b->dpiv);
    free(b->sep);
    block_free(&b->blk[0]);
    block_free(&b->blk[1]);
    memset(b, 0, sizeof *b);
}

/* ---- the factorization ---- */

/* Largest |entry| of block X's rows (final: they have entries only in the
 * block's and the separator's columns) and, in smax[s], of the separator's
 * rows within the block's columns; 2 on a non-finite value. */
static int block_scales(const bk_bandsplit *b, int X, const double *Ax, double *smax)
{
    const bk_bandsplit_block *x = &b->blk[X];
    double *rs = b->rs;
    for (int c = 0; c < x->nb; ++c)
        rs[x->first + x->step * c] = 0.0;
    for (int k = 0; k < b->s; ++k)
        smax[k] = 0.0;
    for (int c = -b->s; c < x->nb; ++c) {            /* the separator's columns, then the block's */
        const int jo = b->perm[c < 0 ? b->m + b->s + c : x->first + x->step * c];
        for (int p = b->Ap[jo]; p < b->Ap[jo + 1]; ++p) {
            const double a = fabs(Ax[p]);
            const int g = b->iperm[b->Ai[p]];
            int k;
            const int where = place(b, g, &k);
            if (!(a <= INFINITY))
                return 2;
            if (where == X) {
                if (a > rs[g])
                    rs[g] = a;
            } else if (where == 2 && c >= 0 && a > smax[k])
                smax[k] = a;
        }
    }
    for (int c = 0; c < x->nb; ++c) {
        const int g = x->first + x->step * c;
        if (!(rs[g] > 0.0))
            return 1;
        rs[g] = 1.0 / rs[g];
    }
    return 0;
}

/* z[kl] = the last kl rows of U_X^-1 w, w[i - w0] row i (rows below i only:
 * the back substitution of the block's tail). */
static void tail_back(const bk_bandsplit_block *x, const double *w, int w0, double *z)
{
    const int nb = x->nb, kl = x->kl, kv = x->kl + x->ku, ldab = x->ldab;
    const double *ab = x->ab;
    for (int i = nb - 1; i >= nb - kl && i >= 0; --i) {
        double sum = w[i - w0];
        const int kend = i + x->kvu < nb - 1 ? i + x->kvu : nb - 1;
        for (int k = i + 1; k <= kend; ++k)
            sum -= ab[(kv + i - k) + (long)k * ldab] * z[k - (nb - kl)];
        z[i - (nb - kl)] = sum / ab[kv + (long)i * ldab];
    }
}

/* Block X's band, E and F, scaled; then its LU, W, Z and C (bandsplit.h). */
static int block_factor(bk_bandsplit *b, int X, const double *Ax)
{
    bk_bandsplit_block *x = &b->blk[X];
    const int nb = x->nb, kl = x->kl, ku = x->ku, kv = kl + ku, ldab = x->ldab, s = b->s;
    const int Lk = kl > 0 ? kl : 1, Uk = ku > 0 ? ku : 1;
    const double *rs = b->rs;
    double *ab = x->ab;
    memset(x->E, 0, (size_t)s * (size_t)Uk * sizeof *x->E);
    memset(x->F, 0, (size_t)s * (size_t)Lk * sizeof *x->F);
    for (int c = 0; c < nb; ++c) {
        double *bc = ab + (long)c * ldab, *at = bc + kv - c;
        memset(bc, 0, (size_t)ldab * sizeof *bc);
        const int jo = b->perm[x->first + x->step * c];
        for (int p = b->Ap[jo]; p < b->Ap[jo + 1]; ++p) {
            const int g = b->iperm[b->Ai[p]];
            int k;
            const int where = place(b, g, &k);
            if (where == X)
                at[k] += Ax[p] * rs[g];
            else if (where == 2 && c >= nb - kl)
                x->F[(long)k * Lk + (c - (nb - kl))] += Ax[p] * rs[g];
        }
    }
    for (int k = 0; k < s; ++k) {                    /* E: the separator's columns, the block's rows */
        const int jo = b->perm[b->m + k];
        for (int p = b->Ap[jo]; p < b->Ap[jo + 1]; ++p) {
            const int g = b->iperm[b->Ai[p]];
            int r;
            if (place(b, g, &r) == X && r >= nb - ku)
                x->E[(long)k * Uk + (r - (nb - ku))] += Ax[p] * rs[g];
        }
    }
    /* the elimination (bandlu.c's, pivots from the block's rows only) */
    double umin = INFINITY, umax = 0.0;
    int ju = 0, kvu = 0;
    for (int j = 0; j < nb; ++j) {
        const int km = kl < nb - 1 - j ? kl : nb - 1 - j;
        double *col = ab + kv + (long)j * ldab;
        double amax = 0.0;
        for (int r = 0; r <= km; ++r) {
            const double a = fabs(col[r]);
            amax = a > amax ? a : amax;
        }
        if (!(amax > 0.0))
            return 1;
        int piv = 0;
        if (!(fabs(col[0]) >= BK_BAND_PIVOT_TOL * amax))
            for (int r = 1; r <= km; ++r)
                if (fabs(col[r]) == amax) {
                    piv = r;
                    break;
                }
        x->ipiv[j] = j + piv;
        int last = j + ku + piv < nb - 1 ? j + ku + piv : nb - 1;
        if (last > ju)
            ju = last;
        if (piv != 0)
            for (int c = j; c <= ju; ++c) {
                double *u = ab + (kv + j - c) + (long)c * ldab, *v = u + piv, t = *u;
                *u = *v;
                *v = t;
            }
        const double d = col[0], inv = 1.0 / d;
        for (int r = 1; r <= km; ++r)
            col[r] *= inv;
        if (ju - j > kvu)
            kvu = ju - j;
        const int kp = km == kl ? x->klp : km;
        for (int c = j + 1; c <= ju; ++c) {
            double *cc = ab + (kv + j - c) + (long)c * ldab;
            const double a = cc[0];
            if (a != 0.0)
                axpy_sub(kp, a, col + 1, cc + 1);
        }
        const double u = fabs(d);
        umin = u < umin ? u : umin;
        umax = u > umax ? u : umax;
    }
    x->kvu = kvu;
    x->umin = umin;
    x->umax = umax;
    /* W = L^-1 P E on rows j0..nb-1 (above them E is zero and stays so) */
    const int j0 = x->j0, t = x->t;
    for (int c = 0; c < s; ++c) {
        double *w = x->W + (long)c * t;
        for (int i = 0; i < t; ++i) {
            const int r = j0 + i;
            w[i] = r >= nb - ku ? x->E[(long)c * Uk + (r - (nb - ku))] : 0.0;
        }
        for (int j = j0; j < nb; ++j) {
            const int p = x->ipiv[j];
            if (p != j) {
                const double tw = w[j - j0];
                w[j - j0] = w[p - j0];
                w[p - j0] = tw;
            }
            const int km = kl < nb - 1 - j ? kl : nb - 1 - j;
            const double a = w[j - j0];
            if (a != 0.0)
                axpy_sub(km, a, ab + kv + 1 + (long)j * ldab, w + j - j0 + 1);
        }
        tail_back(x, w, j0, x->Z + (long)c * Lk);     /* Z: the last kl rows of U^-1 W */
    }
    /* C = F Z (s x s) */
    for (int c = 0; c < s; ++c)
        for (int a = 0; a < s; ++a) {
            double sum = 0.0;
            for (int r = 0; r < kl; ++r)
                sum += x->F[(long)a * Lk + r] * x->Z[(long)c * Lk + r];
            x->C[a + (long)c * s] = sum;
        }
    return 0;
}

int bk_bandsplit_factor(bk_bandsplit *b, const double *Ax)
{
    const int s = b->s, m = b->m;
    double *smax = b->sep;                           /* [2 s]: the separator rows' maxima in each block */
    int st[2] = {0, 0};
#pragma omp parallel for schedule(static, 1)
    for (int X = 0; X < 2; ++X)
        st[X] = block_scales(b, X, Ax, smax + (long)X * s);
    if (st[0] || st[1])
        return st[0] == 2 || st[1] == 2 ? 2 : 1;
    /* the separator's rows: the two blocks' maxima and the separator's columns */
    for (int k = 0; k < s; ++k)
        b->rs[m + k] = smax[k] > smax[s + k] ? smax[k] : smax[s + k];
    double *D = b->D;
    for (int k = 0; k < s; ++k) {
        const int jo = b->perm[m + k];
        for (int p = b->Ap[jo]; p < b->Ap[jo + 1]; ++p) {
            const int g = b->iperm[b->Ai[p]], r = g - m;
            const double a = fabs(Ax[p]);
            if (!(a <= INFINITY))
                return 2;
            if (r >= 0 && r < s && a > b->rs[g])
                b->rs[g] = a;
        }
    }
    for (int k = 0; k < s; ++k) {
        if (!(b->rs[m + k] > 0.0))
            return 1;
        b->rs[m + k] = 1.0 / b->rs[m + k];
    }
#pragma omp parallel for schedule(static, 1)
    for (int X = 0; X < 2; ++X)
        st[X] = block_factor(b, X, Ax);
    if (st[0] || st[1])
        return 1;
    /* D' = D - C1 - C2, then its LU with partial pivoting */
    memset(D, 0, (size_t)s * (size_t)s * sizeof *D);
    for (int k = 0; k < s; ++k) {
        const int jo = b->perm[m + k];
        for (int p = b->Ap[jo]; p < b->Ap[jo + 1]; ++p) {
            const int g = b->iperm[b->Ai[p]], r = g - m;
            if (r >= 0 && r < s)
                D[r + (long)k * s] += Ax[p] * b->rs[g];
        }
    }
    for (long e = 0; e < (long)s * s; ++e)
        D[e] -= b->blk[0].C[e] + b->blk[1].C[e];
    double umin = fmin(b->blk[0].umin, b->blk[1].umin), umax = fmax(b->blk[0].umax, b->blk[1].umax);
    for (int j = 0; j < s; ++j) {
        double *col = D + (long)j * s;
        int piv = j;
        for (int r = j + 1; r < s; ++r)
            if (fabs(col[r]) > fabs(col[piv]))
                piv = r;
        b->dpiv[j] = piv;
        if (!(fabs(col[piv]) > 0.0))
            return 1;
        if (piv != j)                                /* (columns j on: L keeps its rows, as bandlu.c) */
            for (int c = j; c < s; ++c) {
                double *u = D + (long)c * s, t = u[j];
                u[j] = u[piv];
                u[piv] = t;
            }
        const double inv = 1.0 / col[j];
        for (int r = j + 1; r < s; ++r)
            col[r] *= inv;
        for (int c = j + 1; c < s; ++c) {
            double *cc = D + (long)c * s;
            const double a = cc[j];
            if (a != 0.0)
                axpy_sub(s - j - 1, a, col + j + 1, cc + j + 1);
        }
        const double u = fabs(col[j]);
        umin = u < umin ? u : umin;
        umax = u > umax ? u : umax;
    }
    b->rcond = umin / umax;
    return 0;
}

/* ---- the solve ---- */

/* y = L^-1 P (scaled b) of block X, and z = the last kl rows of U^-1 y. */
static void block_forward(bk_bandsplit *b, int X, const double *x_in)
{
    bk_bandsplit_block *x = &b->blk[X];
    const int nb = x->nb, kl = x->kl, kv = x->kl + x->ku, ldab = x->ldab;
    const double *ab = x->ab;
    double *y = x->y;
    for (int i = 0; i < nb; ++i) {
        const int g = x->first + x->step * i;
        y[i] = x_in[b->perm[g]] * b->rs[g];
    }
    for (int j = 0; j < nb; ++j) {
        const int p = x->ipiv[j];
        if (p != j) {
            const double t = y[j];
            y[j] = y[p];
            y[p] = t;
        }
        const int km = kl < nb - 1 - j ? kl : nb - 1 - j;
        if (y[j] != 0.0)
            axpy_sub(km, y[j], ab + kv + 1 + (long)j * ldab, y + j + 1);
    }
    tail_back(x, y, 0, x->z);
}

/* y -= W xs, then U^-1 y into x (old order). */
static void block_back(bk_bandsplit *b, int X, const double *xs, double *x_out)
{
    bk_bandsplit_block *x = &b->blk[X];
    const int nb = x->nb, kv = x->kl + x->ku, kvu = x->kvu, ldab = x->ldab, t = x->t;
    const double *ab = x->ab;
    double *y = x->y;
    for (int c = 0; c < b->s; ++c)
        if (xs[c] != 0.0)
            axpy_sub(t, xs[c], x->W + (long)c * t, y + x->j0);
    for (int j = nb - 1; j >= 0; --j) {
        const double *col = ab + kv + (long)j * ldab;
        y[j] /= col[0];
        const int i0 = j - kvu > 0 ? j - kvu : 0;
        if (y[j] != 0.0)
            axpy_sub(j - i0, y[j], col - (j - i0), y + i0);
    }
    for (int i = 0; i < nb; ++i)
        x_out[b->perm[x->first + x->step * i]] = y[i];
}

void bk_bandsplit_solve(bk_bandsplit *b, double *x)
{
    const int s = b->s, m = b->m;
#pragma omp parallel for schedule(static, 1)
    for (int X = 0; X < 2; ++X)
        block_forward(b, X, x);
    double *xs = b->sep + 2L * s;
    for (int k = 0; k < s; ++k) {                   /* the separator's right-hand side */
        double v = x[b->perm[m + k]] * b->rs[m + k];
        for (int X = 0; X < 2; ++X) {
            const bk_bandsplit_block *bl = &b->blk[X];
            const int Lk = bl->kl > 0 ? bl->kl : 1;
            for (int r = 0; r < bl->kl; ++r)
                v -= bl->F[(long)k * Lk + r] * bl->z[r];
        }
        xs[k] = v;
    }
    const double *D = b->D;
    for (int j = 0; j < s; ++j) {                   /* L, with the interchanges */
        const int p = b->dpiv[j];
        if (p != j) {
            const double t = xs[j];
            xs[j] = xs[p];
            xs[p] = t;
        }
        if (xs[j] != 0.0)
            axpy_sub(s - j - 1, xs[j], D + j + 1 + (long)j * s, xs + j + 1);
    }
    for (int j = s - 1; j >= 0; --j) {              /* U */
        xs[j] /= D[j + (long)j * s];
        if (xs[j] != 0.0)
            axpy_sub(j, xs[j], D + (long)j * s, xs);
    }
#pragma omp parallel for schedule(static, 1)
    for (int X = 0; X < 2; ++X)
        block_back(b, X, xs, x);
    for (int k = 0; k < s; ++k)
        x[b->perm[m + k]] = xs[k];
}
