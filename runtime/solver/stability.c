/* stability.c -- the checks: inertia and extreme eigenvalues of the
 * constrained tangent, the crossing search between two checks (method in
 * stability.h; set-up in stability_setup.c). */
#include "solver/stability.h"

#include <ldl.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"

#define INV_ITERS 30
#define POW_ITERS 40


/* The multipliers' regularization -delta_i of the method (stability.h):
 * b2[j] is the sum of the squares of column j's off-diagonal entries, kmax
 * the largest diagonal magnitude of the other unknowns. */
static double regularization(double b2, double kmax)
{
    return -1e-8 * (b2 > 0.0 ? b2 / kmax : kmax);
}

/* Symmetric part of the Newton matrix, multiplier diagonals regularized: in
 * the band (bnow) or on the symmetric pattern (Bx). */
static void fill_band(bk_stability *st, const double *Ax)
{
    const bk_system *s = st->s;
    const bk_bandsym *b = &st->band;
    const int n = st->n, ldab = b->ldab, *iperm = b->iperm;
    double *band = st->bnow;
    bk_bandsym_fill(b, s->Ap, s->Ai, Ax, band);
    if (st->nmult == 0)
        return;
    double kmax = 0.0;
    for (int j = 0; j < n; ++j)
        if (!st->ismult[j])
            kmax = fmax(kmax, fabs(band[(long)iperm[j] * ldab]));
    if (!(kmax > 0.0))
        kmax = 1.0;
    for (int j = 0; j < n; ++j) {
        if (!st->ismult[j])
            continue;
        const int c = iperm[j];
        double b2 = 0.0;
        for (int k = s->Ap[j]; k < s->Ap[j + 1]; ++k) {
            const int r = iperm[s->Ai[k]];
            if (r == c)
                continue;
            const double v = r > c ? band[(r - c) + (long)c * ldab] : band[(c - r) + (long)r * ldab];
            b2 += v * v;
        }
        band[(long)c * ldab] = regularization(b2, kmax);
    }
}

static void fill(bk_stability *st, const double *Ax)
{
    if (st->use_band) {
        fill_band(st, Ax);
        return;
    }
    int n = st->n;
    double kmax = 0.0;
    for (int j = 0; j < n; ++j) {
        for (int k = st->Bp[j]; k < st->Bp[j + 1]; ++k) {
            double a = st->src[k] >= 0 ? Ax[st->src[k]] : 0.0;
            double b = st->srct[k] >= 0 ? Ax[st->srct[k]] : 0.0;
            st->Bx[k] = 0.5 * (a + b);
            if (st->Bi[k] == j && !st->ismult[j])
                kmax = fmax(kmax, fabs(st->Bx[k]));
        }
    }
    if (!(kmax > 0.0))
        kmax = 1.0;
    for (int j = 0; j < n; ++j) {
        if (!st->ismult[j])
            continue;
        double b2 = 0.0;
        long dk = -1;
        for (int k = st->Bp[j]; k < st->Bp[j + 1]; ++k) {
            if (st->Bi[k] == j)
                dk = k;
            else
                b2 += st->Bx[k] * st->Bx[k];
        }
        st->Bx[dk] = regularization(b2, kmax);
    }
}

static void matvec(bk_stability *st, const double *x, double *y)
{
    if (st->use_band) {
        bk_bandsym_matvec(&st->band, st->bnow, x, y);
        return;
    }
    memset(y, 0, (size_t)st->n * sizeof *y);
    for (int j = 0; j < st->n; ++j)
        for (int k = st->Bp[j]; k < st->Bp[j + 1]; ++k)
            y[st->Bi[k]] += st->Bx[k] * x[j];
}

static double dot(const double *a, const double *b, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; ++i)
        s += a[i] * b[i];
    return s;
}

static void normalize(double *x, int n)
{
    double s = sqrt(dot(x, x, n));
    for (int i = 0; i < n; ++i)
        x[i] /= s > 0.0 ? s : 1.0;
}

static void start_vector(double *x, int n)
{
    unsigned long long r = 88172645463325252ULL;
    for (int i = 0; i < n; ++i) {
        r ^= r << 13;
        r ^= r >> 7;
        r ^= r << 17;
        x[i] = (double)(r >> 11) / 9007199254740992.0 - 0.5;
    }
    normalize(x, n);
}

/* Negative pivots minus multipliers of the matrix in band (the band values:
 * bnow, or the factor's own array filled in place) or in Bx; -1 on a zero
 * pivot. */
static int inertia(bk_stability *st, const double *band)
{
    int n = st->n;
    const double *D = st->D;
    if (st->use_band) {
        if (bk_bandsym_factor(&st->band, band) != 0)
            return -1;
        D = st->band.D;
    } else {
        int d = ldl_numeric(n, st->Bp, st->Bi, st->Bx, st->Lp, st->Parent, st->Lnz, st->Li, st->Lx, st->D,
                            st->Y, st->Pattern, st->Flag, st->P, st->Pinv);
        if (d != n)
            return -1;
    }
    int neg = 0;
    for (int i = 0; i < n; ++i)
        neg += D[i] < 0.0;
    neg -= st->nmult;
    return neg < 0 ? 0 : neg;
}

/* The count of the matrix interpolated at t between the accepted and the
 * current one, (1 - t) A_prev + t A; its pivots in st->band.D or st->D. */
static int count_at(bk_stability *st, double t, int first)
{
    if (st->use_band) {
        long len = (long)st->band.ldab * st->n;
        double *ab = st->band.ab;
        for (long k = 0; k < len; ++k)
            ab[k] = (1.0 - t) * st->bprev[k] + t * st->bnow[k];
        return inertia(st, ab);
    }
    long nz = st->Bp[st->n];
    if (first)
        memcpy(st->Bnow, st->Bx, (size_t)nz * sizeof *st->Bnow);
    for (long k = 0; k < nz; ++k)
        st->Bx[k] = (1.0 - t) * st->Bprev[k] + t * st->Bnow[k];
    return inertia(st, NULL);
}

/* The zero in (lo, hi) of the k-th root of |det| interpolated linearly from
 * the pivots at the ends (k eigenvalues crossing make det ~ (t - t*)^k near
 * t*: k = 2 for the two bending planes of a square section), when the sign of
 * det(hi) / det(lo) fits k; else NaN. */
static double det_zero(const double *Dlo, const double *Dhi, int n, int k, double lo, double hi)
{
    double r = 1.0;
    for (int i = 0; i < n; ++i)
        r *= Dhi[i] / Dlo[i];
    if (k < 1 || !isfinite(r) || r == 0.0 || (r < 0.0) != (k % 2 == 1))
        return NAN;
    return lo + (hi - lo) / (1.0 + pow(fabs(r), 1.0 / k));
}

/* The bracket [lo, hi] (count_before at lo, another count at hi) and the
 * pivots at its ends while it narrows. */
typedef struct bracket {
    double lo, hi;
    double *Dlo, *Dhi;
    int have_lo, have_hi, count_hi;
} bracket;

/* The count at t moves one end of the bracket to t. */
static void probe(bk_stability *st, bracket *b, double t, int count_before, int first)
{
    int c = count_at(st, t, first);
    const double *D = st->use_band ? st->band.D : st->D;
    if (c == count_before) {
        b->lo = t;
        memcpy(b->Dlo, D, (size_t)st->n * sizeof *b->Dlo);
        b->have_lo = 1;
    } else {
        b->hi = t;
        if (c >= 0)                      /* (a zero pivot ends the factorization early) */
            memcpy(b->Dhi, D, (size_t)st->n * sizeof *b->Dhi);
        b->have_hi = c >= 0;
        b->count_hi = c;
    }
}

static int crossing_k(const bracket *b, int count_before)
{
    return b->count_hi > count_before ? b->count_hi - count_before : count_before - b->count_hi;
}

double bk_stability_crossing(bk_stability *st, int count_before)
{
    if (!st->have_prev || st->n == 0)
        return NAN;
    if (st->lender)
        bk_band_clobbered(st->lender);
    double t0 = bk_clock_s();
    const int n = st->n;
    /* the ends: the accepted check's pivots (t = 0) and the current one's (t = 1) */
    bracket b = {0.0, 1.0, st->dcross, st->dcross + n, st->ok_acc, st->ok_chk, st->count_chk};
    if (b.have_lo)
        memcpy(b.Dlo, st->dacc, (size_t)n * sizeof *b.Dlo);
    if (b.have_hi)
        memcpy(b.Dhi, st->dchk, (size_t)n * sizeof *b.Dhi);
    const double width = ldexp(1.0, -BK_CROSSING_BISECTIONS);
    int guess = 1, first = 1;
    const int cap = 3 * BK_CROSSING_BISECTIONS;         /* factorizations at most */
    for (int nf = 0; b.hi - b.lo > width && nf < cap; ) {
        double g = guess && b.have_lo && b.have_hi
                       ? det_zero(b.Dlo, b.Dhi, n, crossing_k(&b, count_before), b.lo, b.hi) : NAN;
        if (!isfinite(g)) {                              /* bisection */
            probe(st, &b, 0.5 * (b.lo + b.hi), count_before, first);
            first = 0, nf++, guess = 1;
            continue;
        }
        const double d = fmax(BK_CROSSING_GUESS_WIDTH * (b.hi - b.lo), 0.25 * width);
        const double t1 = g - d, t2 = g + d, was = b.hi - b.lo;
        if (t1 > b.lo) {
            probe(st, &b, t1, count_before, first);
            first = 0, nf++;
        }
        if (b.lo >= t1 && t2 < b.hi && nf < cap) {       /* the zero is above t1 */
            probe(st, &b, t2, count_before, first);
            first = 0, nf++;
        }
        guess = b.hi - b.lo <= 2.0 * d * (1.0 + 1e-12) || b.hi - b.lo < 0.5 * was;   /* it bracketed: again */
    }
    if (!first && !st->use_band)
        memcpy(st->Bx, st->Bnow, (size_t)st->Bp[n] * sizeof *st->Bx);
    double t = 0.5 * (b.lo + b.hi);
    if (b.have_lo && b.have_hi) {
        double z = det_zero(b.Dlo, b.Dhi, n, crossing_k(&b, count_before), b.lo, b.hi);
        if (isfinite(z))
            t = z;
    }
    st->t_spent += bk_clock_s() - t0;
    return t;
}

static void stability_check(bk_stability *st, const double *Ax, bk_stability_result *res);

void bk_stability_check(bk_stability *st, const double *Ax, bk_stability_result *res)
{
    double t0 = bk_clock_s();
    stability_check(st, Ax, res);
    st->t_spent += bk_clock_s() - t0;
}

static void stability_check(bk_stability *st, const double *Ax, bk_stability_result *res)
{
    int n = st->n;
    if (st->lender)
        bk_band_clobbered(st->lender);
    memset(res, 0, sizeof *res);
    res->eig_min = res->eig_max = NAN;
    if (n == 0)
        return;
    fill(st, Ax);
    int c = inertia(st, st->bnow);
    st->ok_chk = c >= 0;
    st->count_chk = c;
    if (c < 0) {
        /* An exactly zero pivot: singular on the constraint tangent space. */
        res->ok = 0;
        res->eig_min = 0.0;
        st->have_vec = 0;
        return;
    }
    memcpy(st->dchk, st->use_band ? st->band.D : st->D, (size_t)n * sizeof *st->dchk);
    res->ok = 1;
    res->negative = c;
    if (!st->s->m->stat.eigenvalues)       /* the inertia alone (static.eigenvalues = false) */
        return;

    /* Inverse iteration for the smallest-magnitude eigenvalue, warm-started
     * from the previous eigenvector. */
    if (!st->have_vec)
        start_vector(st->x, n);
    double lam = NAN;
    for (int it = 0; it < INV_ITERS; ++it) {
        if (st->use_band) {
            memcpy(st->y, st->x, (size_t)n * sizeof *st->y);
            bk_bandsym_solve(&st->band, st->y);
        } else {
            ldl_perm(n, st->z, st->x, st->P);
            ldl_lsolve(n, st->z, st->Lp, st->Li, st->Lx);
            ldl_dsolve(n, st->z, st->D);
            ldl_ltsolve(n, st->z, st->Lp, st->Li, st->Lx);
            ldl_permt(n, st->y, st->z, st->P);
        }
        /* y = A^-1 x; Rayleigh quotient of the normalized y */
        normalize(st->y, n);
        matvec(st, st->y, st->z);
        double l = dot(st->y, st->z, n);
        /* residual |A y - l y| */
        double r2 = 0.0;
        for (int i = 0; i < n; ++i) {
            double t = st->z[i] - l * st->y[i];
            r2 += t * t;
        }
        memcpy(st->x, st->y, (size_t)n * sizeof *st->x);
        int done = it > 0 && fabs(l - lam) <= 1e-10 * fabs(l) && sqrt(r2) <= 1e-6 * fabs(l);
        lam = l;
        if (done)
            break;
    }
    res->eig_min = lam;
    st->have_vec = isfinite(lam);

    /* Power iteration for the largest magnitude (an estimate: a few digits),
     * warm-started from the previous check's vector: it stops when two
     * estimates agree to 1e-3. */
    if (!st->have_vmax) {
        start_vector(st->xmax, n);
    } else {
        /* a tenth of a fresh start vector, so that a mode that has overtaken the
         * previous dominant one is not missing from the warm start */
        start_vector(st->z, n);
        for (int i = 0; i < n; ++i)
            st->xmax[i] += 0.1 * st->z[i];
        normalize(st->xmax, n);
    }
    double big = 0.0, prev = 0.0;
    for (int it = 0; it < POW_ITERS; ++it) {
        matvec(st, st->xmax, st->z);
        big = sqrt(dot(st->z, st->z, n));
        if (!(big > 0.0))
            break;
        for (int i = 0; i < n; ++i)
            st->xmax[i] = st->z[i] / big;
        if (it >= 3 && fabs(big - prev) <= 1e-3 * big)
            break;
        prev = big;
    }
    st->have_vmax = big > 0.0 && isfinite(big);
    res->eig_max = big;
}

/* The values now become the previous ones (the next check fills the others;
 * borrowed, the values now are copied: their place is the band LU's). */
void bk_stability_accept(bk_stability *st)
{
    double *t = st->bprev;
    if (st->lender) {
        memcpy(st->bprev, st->bnow, (size_t)st->band.ldab * (size_t)st->n * sizeof *st->bprev);
    } else {
        st->bprev = st->bnow;
        st->bnow = t;
    }
    t = st->Bprev;
    st->Bprev = st->Bx;
    st->Bx = t;
    t = st->dacc;
    st->dacc = st->dchk;
    st->dchk = t;
    st->ok_acc = st->ok_chk;
    st->have_prev = 1;
}

void bk_stability_free(bk_stability *st)
{
    free(st->ismult);
    free(st->dcross);
    free(st->Bp);
    free(st->Bi);
    free(st->src);
    free(st->srct);
    free(st->Bx);
    free(st->Bprev);
    free(st->Bnow);
    free(st->Lp);
    free(st->Parent);
    free(st->Lnz);
    free(st->Flag);
    free(st->Pattern);
    free(st->P);
    free(st->Pinv);
    free(st->D);
    free(st->Y);
    free(st->x);
    free(st->y);
    free(st->z);
    free(st->xmax);
    free(st->Li);
    free(st->Lx);
    if (st->lender)
        st->band.ab = NULL;              /* the band LU's */
    else
        free(st->bnow);
    free(st->bprev);
    bk_bandsym_free(&st->band);
    memset(st, 0, sizeof *st);
}
