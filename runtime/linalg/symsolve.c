/* symsolve.c -- the symmetric solver object's calls: the regularized
 * symmetric part, factorization, pivots, solves and products, for both
 * backends (see symsolve.h; set-up in sym_setup.c). */
#include "linalg/symsolve.h"

#include <ldl.h>
#include <math.h>
#include <string.h>

/* The regularization -delta_i of an unknown marked reg: b2 the sum of the
 * squares of its column's off-diagonal entries, kmax the largest diagonal
 * magnitude of the other unknowns. */
static double regularization(double b2, double kmax)
{
    return -1e-8 * (b2 > 0.0 ? b2 / kmax : kmax);
}

static void fill_band(const bk_symsolver *f, const double *Ax, const char *reg, double *band)
{
    const bk_bandsym *b = &f->band;
    const int n = f->n, ldab = b->ldab, *iperm = b->iperm;
    bk_bandsym_fill(b, f->Ap, f->Ai, Ax, band);
    int any = 0;
    for (int j = 0; reg && j < n; ++j)
        any |= reg[j];
    if (!any)
        return;
    double kmax = 0.0;
    for (int j = 0; j < n; ++j)
        if (!reg[j])
            kmax = fmax(kmax, fabs(band[(long)iperm[j] * ldab]));
    if (!(kmax > 0.0))
        kmax = 1.0;
    for (int j = 0; j < n; ++j) {
        if (!reg[j])
            continue;
        const int c = iperm[j];
        double b2 = 0.0;
        for (int k = f->Ap[j]; k < f->Ap[j + 1]; ++k) {
            const int r = iperm[f->Ai[k]];
            if (r == c)
                continue;
            const double v = r > c ? band[(r - c) + (long)c * ldab] : band[(c - r) + (long)r * ldab];
            b2 += v * v;
        }
        band[(long)c * ldab] = regularization(b2, kmax);
    }
}

void bk_sym_fill(const bk_symsolver *f, const double *Ax, const char *reg, double *vals)
{
    if (f->use_band) {
        fill_band(f, Ax, reg, vals);
        return;
    }
    const int n = f->n;
    double kmax = 0.0;
    for (int j = 0; j < n; ++j) {
        for (int k = f->Bp[j]; k < f->Bp[j + 1]; ++k) {
            double a = f->src[k] >= 0 ? Ax[f->src[k]] : 0.0;
            double b = f->srct[k] >= 0 ? Ax[f->srct[k]] : 0.0;
            vals[k] = 0.5 * (a + b);
            if (f->Bi[k] == j && !(reg && reg[j]))
                kmax = fmax(kmax, fabs(vals[k]));
        }
    }
    if (!(kmax > 0.0))
        kmax = 1.0;
    for (int j = 0; reg && j < n; ++j) {
        if (!reg[j])
            continue;
        double b2 = 0.0;
        long dk = -1;
        for (int k = f->Bp[j]; k < f->Bp[j + 1]; ++k) {
            if (f->Bi[k] == j)
                dk = k;
            else
                b2 += vals[k] * vals[k];
        }
        vals[dk] = regularization(b2, kmax);
    }
}

int bk_sym_factor(bk_symsolver *f, const double *vals)
{
    if (f->use_split)
        return bk_symsplit_factor(&f->split, vals);
    if (f->use_band)
        return bk_bandsym_factor(&f->band, vals) != 0 ? -1 : 0;
    const int n = f->n;
    int d = ldl_numeric(n, f->Bp, f->Bi, (double *)vals, f->Lp, f->Parent, f->Lnz, f->Li, f->Lx, f->D, f->Y,
                        f->Pattern, f->Flag, f->P, f->Pinv);
    return d == n ? 0 : -1;
}

const double *bk_sym_pivots(const bk_symsolver *f)
{
    return f->use_split ? f->split.D : f->use_band ? f->band.D : f->D;
}

int bk_sym_negative(const bk_symsolver *f)
{
    const double *D = bk_sym_pivots(f);
    int neg = 0;
    for (int i = 0; i < f->n; ++i)
        neg += D[i] < 0.0;
    return neg;
}

void bk_sym_solve(bk_symsolver *f, const double *x, double *y)
{
    const int n = f->n;
    if (f->use_split) {                  /* (in the band's order: its scratch w) */
        double *w = f->band.w;
        for (int i = 0; i < n; ++i)
            w[i] = x[f->band.perm[i]];
        bk_symsplit_solve(&f->split, w);
        for (int i = 0; i < n; ++i)
            y[f->band.perm[i]] = w[i];
        return;
    }
    if (f->use_band) {
        if (y != x)
            memcpy(y, x, (size_t)n * sizeof *y);
        bk_bandsym_solve(&f->band, y);
        return;
    }
    ldl_perm(n, f->z, (double *)x, f->P);
    ldl_lsolve(n, f->z, f->Lp, f->Li, f->Lx);
    ldl_dsolve(n, f->z, f->D);
    ldl_ltsolve(n, f->z, f->Lp, f->Li, f->Lx);
    ldl_permt(n, y, f->z, f->P);
}

void bk_sym_matvec(bk_symsolver *f, const double *vals, const double *x, double *y)
{
    if (f->use_band) {
        bk_bandsym_matvec(&f->band, vals, x, y);
        return;
    }
    memset(y, 0, (size_t)f->n * sizeof *y);
    for (int j = 0; j < f->n; ++j)
        for (int k = f->Bp[j]; k < f->Bp[j + 1]; ++k)
            y[f->Bi[k]] += vals[k] * x[j];
}

void bk_sym_begin(bk_symsolver *f)
{
    if (f->lender)
        bk_band_clobbered(f->lender);
}

void bk_sym_keep_now(bk_symsolver *f, double **keep)
{
    if (f->lender) {
        memcpy(*keep, f->now, (size_t)f->nval * sizeof **keep);
        return;
    }
    double *t = *keep;
    *keep = f->now;
    f->now = t;
}
