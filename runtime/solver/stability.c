/* stability.c -- the checks: inertia and extreme eigenvalues of the
 * constrained tangent, the crossing search between two checks (method in
 * stability.h; set-up in stability_setup.c). */
#include "solver/stability.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"

#define INV_ITERS 30
#define POW_ITERS 40


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

/* Negative pivots minus multipliers of the values vals (factored: those of
 * the symmetric solver's scratch in place); -1 on a zero pivot. */
static int inertia(bk_stability *st, const double *vals)
{
    if (bk_sym_factor(&st->sym, vals) != 0)
        return -1;
    int neg = bk_sym_negative(&st->sym) - st->nmult;
    return neg < 0 ? 0 : neg;
}

/* The count of the matrix interpolated at t between the accepted and the
 * current one, (1 - t) A_prev + t A, in the solver's scratch; its pivots in
 * bk_sym_pivots. */
static int count_at(bk_stability *st, double t)
{
    const long len = st->sym.nval;
    double *v = st->sym.scratch;
    for (long k = 0; k < len; ++k)
        v[k] = (1.0 - t) * st->prev[k] + t * st->sym.now[k];
    return inertia(st, v);
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
static void probe(bk_stability *st, bracket *b, double t, int count_before)
{
    int c = count_at(st, t);
    const double *D = bk_sym_pivots(&st->sym);
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
    bk_sym_begin(&st->sym);
    double t0 = bk_clock_s();
    const int n = st->n;
    /* the ends: the accepted check's pivots (t = 0) and the current one's (t = 1) */
    bracket b = {0.0, 1.0, st->dcross, st->dcross + n, st->ok_acc, st->ok_chk, st->count_chk};
    if (b.have_lo)
        memcpy(b.Dlo, st->dacc, (size_t)n * sizeof *b.Dlo);
    if (b.have_hi)
        memcpy(b.Dhi, st->dchk, (size_t)n * sizeof *b.Dhi);
    const double width = ldexp(1.0, -BK_CROSSING_BISECTIONS);
    int guess = 1;
    const int cap = 3 * BK_CROSSING_BISECTIONS;         /* factorizations at most */
    for (int nf = 0; b.hi - b.lo > width && nf < cap; ) {
        double g = guess && b.have_lo && b.have_hi
                       ? det_zero(b.Dlo, b.Dhi, n, crossing_k(&b, count_before), b.lo, b.hi) : NAN;
        if (!isfinite(g)) {                              /* bisection */
            probe(st, &b, 0.5 * (b.lo + b.hi), count_before);
            nf++, guess = 1;
            continue;
        }
        const double d = fmax(BK_CROSSING_GUESS_WIDTH * (b.hi - b.lo), 0.25 * width);
        const double t1 = g - d, t2 = g + d, was = b.hi - b.lo;
        if (t1 > b.lo) {
            probe(st, &b, t1, count_before);
            nf++;
        }
        if (b.lo >= t1 && t2 < b.hi && nf < cap) {       /* the zero is above t1 */
            probe(st, &b, t2, count_before);
            nf++;
        }
        guess = b.hi - b.lo <= 2.0 * d * (1.0 + 1e-12) || b.hi - b.lo < 0.5 * was;   /* it bracketed: again */
    }
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
    bk_sym_begin(&st->sym);
    memset(res, 0, sizeof *res);
    res->eig_min = res->eig_max = NAN;
    if (n == 0)
        return;
    bk_sym_fill(&st->sym, Ax, st->ismult, st->sym.now);
    int c = inertia(st, st->sym.now);
    st->ok_chk = c >= 0;
    st->count_chk = c;
    if (c < 0) {
        /* An exactly zero pivot: singular on the constraint tangent space. */
        res->ok = 0;
        res->eig_min = 0.0;
        st->have_vec = 0;
        return;
    }
    memcpy(st->dchk, bk_sym_pivots(&st->sym), (size_t)n * sizeof *st->dchk);
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
        bk_sym_solve(&st->sym, st->x, st->y);
        /* y = A^-1 x; Rayleigh quotient of the normalized y */
        normalize(st->y, n);
        bk_sym_matvec(&st->sym, st->sym.now, st->y, st->z);
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
        bk_sym_matvec(&st->sym, st->sym.now, st->xmax, st->z);
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
    bk_sym_keep_now(&st->sym, &st->prev);
    double *t = st->dacc;
    st->dacc = st->dchk;
    st->dchk = t;
    st->ok_acc = st->ok_chk;
    st->have_prev = 1;
}

void bk_stability_free(bk_stability *st)
{
    free(st->ismult);
    free(st->dcross);
    free(st->prev);
    free(st->x);
    free(st->y);
    free(st->z);
    free(st->xmax);
    bk_sym_free(&st->sym);
    memset(st, 0, sizeof *st);
}
