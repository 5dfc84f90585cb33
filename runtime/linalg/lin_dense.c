/* lin_dense.c -- the dense LU backend of the linear solver object: the
 * matrix scattered into n x n column-major storage, LU with partial (row)
 * pivoting, the pivot ratio min |u_jj| / max |u_jj| as the condition
 * estimate, as the band LU reports it (see linsolve.h).  O(n^2) storage and
 * O(n^3) work: for small systems and as an independent check of the sparse
 * backends; it allocates its storage once, at init. */
#include "linalg/linsolve.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int dense_factor(bk_linsolver *s, double *Ax)
{
    const int n = s->n;
    double *A = s->dense;
    memset(A, 0, (size_t)n * (size_t)n * sizeof *A);
    for (int j = 0; j < n; ++j)
        for (int k = s->Ap[j]; k < s->Ap[j + 1]; ++k)
            A[(size_t)j * n + s->Ai[k]] += Ax[k];
    s->nfactor++;
    s->nfull++;
    double umin = INFINITY, umax = 0.0;
    int singular = 0;
    for (int j = 0; j < n; ++j) {
        double *cj = A + (size_t)j * n;
        int p = j;                       /* the pivot: the largest magnitude in column j at or below j */
        for (int i = j + 1; i < n; ++i)
            if (fabs(cj[i]) > fabs(cj[p]))
                p = i;
        s->dpiv[j] = p;
        if (p != j)
            for (int c = 0; c < n; ++c) {
                double *col = A + (size_t)c * n, t = col[j];
                col[j] = col[p];
                col[p] = t;
            }
        const double d = cj[j];
        if (!isfinite(d)) {
            s->rcond = 0.0;
            return BK_LIN_ERROR;
        }
        umin = fmin(umin, fabs(d));
        umax = fmax(umax, fabs(d));
        if (d == 0.0) {
            singular = 1;
            continue;
        }
        for (int i = j + 1; i < n; ++i)
            cj[i] /= d;
        for (int c = j + 1; c < n; ++c) {
            double *col = A + (size_t)c * n;
            const double f = col[j];
            if (f != 0.0)
                for (int i = j + 1; i < n; ++i)
                    col[i] -= f * cj[i];
        }
    }
    s->rcond = singular || !(umax > 0.0) ? 0.0 : umin / umax;
    s->rcond_factor = s->rcond;
    return !(s->rcond > 1e-300) ? BK_LIN_SINGULAR : BK_LIN_OK;
}

static int dense_solve(bk_linsolver *s, double *b)
{
    if (!(s->rcond > 1e-300))
        return BK_LIN_ERROR;
    const int n = s->n;
    const double *A = s->dense;
    for (int j = 0; j < n; ++j) {        /* P b, then L y = P b (unit diagonal) */
        int p = s->dpiv[j];
        if (p != j) {
            double t = b[j];
            b[j] = b[p];
            b[p] = t;
        }
    }
    for (int j = 0; j < n; ++j) {
        const double *cj = A + (size_t)j * n;
        for (int i = j + 1; i < n; ++i)
            b[i] -= cj[i] * b[j];
    }
    for (int j = n - 1; j >= 0; --j) {   /* U x = y */
        const double *cj = A + (size_t)j * n;
        b[j] /= cj[j];
        for (int i = 0; i < j; ++i)
            b[i] -= cj[i] * b[j];
    }
    return BK_LIN_OK;
}

static int dense_factor_solve(bk_linsolver *s, double *Ax, double *b)
{
    int st = dense_factor(s, Ax);
    return st != BK_LIN_OK ? st : dense_solve(s, b);
}

static void dense_free(bk_linsolver *s)
{
    free(s->dense);
    free(s->dpiv);
    s->dense = NULL;
    s->dpiv = NULL;
}

const bk_lin_ops bk_lin_dense_ops = {"dense LU", dense_factor, dense_solve, dense_factor_solve, dense_free};

int bk_lin_dense_init(bk_linsolver *s)
{
    const size_t n = (size_t)(s->n > 0 ? s->n : 1);
    s->dense = malloc(n * n * sizeof *s->dense);
    s->dpiv = malloc(n * sizeof *s->dpiv);
    s->ops = &bk_lin_dense_ops;          /* (freed by bk_lin_free also on failure) */
    if (!s->dense || !s->dpiv)
        return BK_LIN_ERROR;
    s->nanalyze = 1;
    return BK_LIN_OK;
}
