/* symsplit_check.c -- the symmetric band L D L^T in two halves and a separator
 * (runtime/linalg/symsplit.c, the stability checks' inertia of long bands)
 * against an eigenvalue count written here another way: Householder
 * reduction of the dense matrix to a tridiagonal one, then the Sturm sequence
 * at 0 (the number of negative eigenvalues, and the determinant as the
 * product of the sequence's terms).  Random symmetric band matrices shaped
 * like the Newton systems of beams (node blocks of 6 unknowns coupled to
 * their neighbours, a scrambled numbering, put in reverse Cuthill-McKee band
 * order by bk_bandsym_plan):
 *   dominant:   diagonals of random sign, dominant;
 *   indefinite: diagonals of random sign, not dominant;
 *   kkt:        a positive definite chain with multiplier rows tying unknowns
 *               of neighbouring nodes, their diagonals -1e-8 (the stability
 *               checks' regularized saddle point);
 *   zero:       a zero row and column: a zero pivot, reported;
 *   nonfinite:  a NaN entry, reported.
 * Each case is factored and solved with 1 thread (the blocks' own storage)
 * and with 2 threads (storage lent, as the split band LU lends it); prints
 * case= n= kd= factor= neg= (negative pivots) sturm= (negative eigenvalues)
 * band_neg= (the whole band's L D L^T, bandsym.c) logdet= (|log|det| from the
 * pivots - from the Sturm sequence|, relative) sign= (1: the signs of the
 * determinants agree) res= (relative residual of a solve, max norm)
 * same_threads= (the same bits for the pivots and the solve). */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/bandlu.h"
#include "linalg/symsplit.h"

#include "band_test_util.h"

static unsigned long long rng = 0x9E3779B97F4A7C15ULL;
static double urand(void)
{
    return bt_urand(&rng);
}

/* Householder tridiagonalization of the symmetric A (row-major, destroyed):
 * the diagonal a[n] and the subdiagonal e[n - 1]. */
static void tridiagonal(int n, double *A, double *a, double *e, double *v, double *p)
{
    for (int k = 0; k + 2 < n; ++k) {
        const int m = n - k - 1;                     /* the trailing block's size */
        double norm = 0.0;
        for (int i = 0; i < m; ++i)
            norm += A[(long)(k + 1 + i) * n + k] * A[(long)(k + 1 + i) * n + k];
        norm = sqrt(norm);
        const double x0 = A[(long)(k + 1) * n + k], alpha = x0 > 0.0 ? -norm : norm;
        for (int i = 0; i < m; ++i)
            v[i] = A[(long)(k + 1 + i) * n + k];
        v[0] -= alpha;
        double vn = 0.0;
        for (int i = 0; i < m; ++i)
            vn += v[i] * v[i];
        if (vn == 0.0)
            continue;
        vn = sqrt(vn);
        for (int i = 0; i < m; ++i)
            v[i] /= vn;
        /* B <- H B H, H = I - 2 v v^T: p = B v, q = p - (v^T p) v, B -= 2 (v q^T + q v^T) */
        double K = 0.0;
        for (int i = 0; i < m; ++i) {
            double sum = 0.0;
            for (int j = 0; j < m; ++j)
                sum += A[(long)(k + 1 + i) * n + (k + 1 + j)] * v[j];
            p[i] = sum;
            K += v[i] * sum;
        }
        for (int i = 0; i < m; ++i)
            p[i] -= K * v[i];
        for (int i = 0; i < m; ++i)
            for (int j = 0; j < m; ++j)
                A[(long)(k + 1 + i) * n + (k + 1 + j)] -= 2.0 * (v[i] * p[j] + p[i] * v[j]);
        A[(long)(k + 1) * n + k] = alpha;
    }
    for (int i = 0; i < n; ++i)
        a[i] = A[(long)i * n + i];
    for (int i = 0; i + 1 < n; ++i)
        e[i] = A[(long)(i + 1) * n + i];
}

/* The Sturm sequence of the tridiagonal (a, e) at 0: the number of negative
 * eigenvalues; *logdet, *sign: log |det| and the determinant's sign. */
static int sturm(int n, const double *a, const double *e, double *logdet, int *sign)
{
    int neg = 0;
    double q = 1.0;
    *logdet = 0.0;
    *sign = 1;
    for (int i = 0; i < n; ++i) {
        q = i == 0 ? a[0] : a[i] - e[i - 1] * e[i - 1] / q;
        if (q == 0.0)
            q = 1e-300;
        neg += q < 0.0;
        *logdet += log(fabs(q));
        *sign *= q < 0.0 ? -1 : 1;
    }
    return neg;
}

/* A(i, j) = A(j, i) = v, both in the pattern. */
static void set(double *A, char *mask, int n, int i, int j, double v)
{
    A[(long)i * n + j] = v;
    A[(long)j * n + i] = v;
    mask[(long)i * n + j] = 1;
    mask[(long)j * n + i] = 1;
}

enum { DOMINANT, INDEFINITE, KKT, ZERO, NONFINITE };

static void run(const char *name, int kind)
{
    const int nodes = 34, bs = 6, nd = nodes * bs, nm = kind == KKT ? 2 * (nodes - 1) : 0, n = nd + nm;
    double *A = calloc((size_t)n * n, sizeof *A);
    char *mask = calloc((size_t)n * n, 1);
    int *scr = bt_scramble(n, &rng);
#define SET(i, j, v) set(A, mask, n, scr[i], scr[j], (v))
    bt_chain(A, mask, n, scr, nodes, bs, BT_SYMMETRIC_SET, &rng);     /* neighbouring nodes' blocks */
    for (int i = 0; i < nd; ++i) {
        const double sgn = kind == KKT || urand() < 0.6 ? 1.0 : -1.0;
        SET(i, i, sgn * (kind == INDEFINITE ? 0.5 + urand() : 8.0 + urand()));
    }
    if (kind == KKT)                                     /* unknown k of node e equals that of e + 1 */
        for (int e = 0; e + 1 < nodes; ++e)
            for (int k = 0; k < 2; ++k) {
                const int m = nd + 2 * e + k;
                SET(m, e * bs + k, 1.0);
                SET(m, (e + 1) * bs + k, -1.0);
                SET(m, m, -1e-8);
            }
    if (kind == ZERO)                                    /* (the pattern kept) */
        for (int i = 0, z = scr[5 * bs + 2]; i < n; ++i)
            A[(long)i * n + z] = A[(long)z * n + i] = 0.0;
    int *Ap, *Ai;
    double *Ax;
    const int nnz = bt_csc(n, A, mask, &Ap, &Ai, &Ax);
    if (kind == NONFINITE)
        Ax[nnz / 2] = NAN;

    bk_bandsym bs1;
    bk_bandsym_plan(&bs1, n, Ap, Ai, NULL, -1, 1L << 24);
    const int kd = bs1.kd, ldab = bs1.ldab, m = (n - kd) / 2;
    double *band = malloc((size_t)ldab * n * sizeof *band);
    bk_bandsym_fill(&bs1, Ap, Ai, Ax, band);
    bk_symsplit own, lent;
    const long lens[2] = {(long)ldab * m + 5, (long)ldab * (n - m - kd)};
    double *store[2] = {malloc((size_t)lens[0] * sizeof(double)), malloc((size_t)lens[1] * sizeof(double))};
    int plan = bk_symsplit_plan(&own, n, kd, ldab, m, NULL, NULL) |
               bk_symsplit_plan(&lent, n, kd, ldab, m, store, lens);
    const int borrowed = lent.blk[0].borrowed && lent.blk[1].borrowed && !own.blk[0].borrowed;
    omp_set_num_threads(1);
    int f1 = plan == 0 ? bk_symsplit_factor(&own, band) : -9;
    omp_set_num_threads(2);
    int f2 = plan == 0 ? bk_symsplit_factor(&lent, band) : -9;
    int neg = 0;
    for (int i = 0; i < n; ++i)
        neg += own.D[i] < 0.0;
    int band_neg = bk_bandsym_factor(&bs1, band) == 0 ? 0 : -1;
    for (int i = 0; band_neg >= 0 && i < n; ++i)
        band_neg += bs1.D[i] < 0.0;

    /* a solve, in the band order */
    double *xt = malloc((size_t)n * sizeof *xt), *b = malloc((size_t)n * sizeof *b);
    double *x1 = malloc((size_t)n * sizeof *x1), *x2 = malloc((size_t)n * sizeof *x2);
    for (int i = 0; i < n; ++i)
        xt[i] = urand() - 0.5;
    bt_matvec(n, A, xt, b);
    double res = NAN;
    int same = f1 == f2 && (f1 != 0 || memcmp(own.D, lent.D, (size_t)n * sizeof *own.D) == 0);
    if (f1 == 0 && f2 == 0) {
        for (int i = 0; i < n; ++i)
            x1[i] = x2[i] = b[bs1.perm[i]];
        omp_set_num_threads(1);
        bk_symsplit_solve(&own, x1);
        omp_set_num_threads(2);
        bk_symsplit_solve(&lent, x2);
        same = same && memcmp(x1, x2, (size_t)n * sizeof *x1) == 0;
        for (int i = 0; i < n; ++i)
            x2[bs1.perm[i]] = x1[i];                     /* the solution in the matrix's order */
        double r = 0.0, bn = 0.0;
        for (int i = 0; i < n; ++i) {
            double ri = -b[i];
            for (int j = 0; j < n; ++j)
                ri += A[(long)i * n + j] * x2[j];
            r = fmax(r, fabs(ri));
            bn = fmax(bn, fabs(b[i]));
        }
        res = r / bn;
    }

    /* the reference: Householder + Sturm on the dense matrix */
    double *a = malloc((size_t)n * sizeof *a), *e = malloc((size_t)n * sizeof *e);
    double *v = malloc((size_t)n * sizeof *v), *pw = malloc((size_t)n * sizeof *pw);
    int nst = -1, sgn = 0;
    double ld = NAN, logdet = NAN, dsign = 1.0;
    if (kind != NONFINITE) {
        tridiagonal(n, A, a, e, v, pw);
        nst = sturm(n, a, e, &ld, &sgn);
    }
    if (f1 == 0) {
        logdet = 0.0;
        for (int i = 0; i < n; ++i) {
            logdet += log(fabs(own.D[i]));
            dsign *= own.D[i] < 0.0 ? -1.0 : 1.0;
        }
    }
    printf("case=%s n=%d kd=%d plan=%d factor=%d neg=%d sturm=%d band_neg=%d logdet=%.3e sign=%d res=%.3e "
           "same_threads=%d lent=%d\n", name, n, kd, plan, f1, f1 == 0 ? neg : -1, nst, band_neg,
           fabs(logdet - ld) / fmax(1.0, fabs(ld)), (dsign < 0.0) == (sgn < 0), res, same, borrowed);
    bk_symsplit_free(&own);
    bk_symsplit_free(&lent);
    bk_bandsym_free(&bs1);
    free(store[0]), free(store[1]), free(band);
    free(A), free(mask), free(scr), free(Ap), free(Ai), free(Ax), free(xt), free(b), free(x1), free(x2);
    free(a), free(e), free(v), free(pw);
}

int main(void)
{
    run("dominant", DOMINANT);
    run("indefinite", INDEFINITE);
    run("kkt", KKT);
    run("zero", ZERO);
    run("nonfinite", NONFINITE);
    return 0;
}
