/* bandsplit_check.c -- the split band LU (runtime/linalg/bandsplit.c) against
 * a dense LU with row pivoting written here, on long chains shaped like the
 * Newton systems of beams (node blocks of 12 unknowns coupled to their
 * neighbours, unsymmetric values, a scrambled numbering):
 *   chain:    diagonally dominant;
 *   weak:     small diagonals: the blocks need row interchanges;
 *   kkt:      multiplier rows with a zero diagonal tying unknowns of neighbouring
 *             nodes (pin joints along the chain);
 *   scaled:   rows of magnitudes 1e-6 ... 1e6;
 *   singular: a zero column, reported, not solved;
 *   nonfinite: a NaN entry, reported.
 * Each case is factored and solved with 1 and with 2 OpenMP threads and again
 * with the same plan; prints case= n= kl= ku= s= factor= err= (relative error
 * against the dense solve, max norm) res= (relative residual) same_threads=
 * (1 and 2 threads: the same bits) same_again= (a second factorization: the
 * same bits) rcond=. */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/bandlu.h"
#include "linalg/bandsplit.h"

#include "band_test_util.h"

static unsigned long long rng = 0x2545F4914F6CDD1DULL;
static double urand(void)
{
    return bt_urand(&rng);
}

/* Dense LU with row pivoting, row by row elimination on a row-major copy. */
static int dense(int n, double *A, double *b)
{
    for (int k = 0; k < n; ++k) {
        int p = k;
        for (int i = k + 1; i < n; ++i)
            if (fabs(A[(long)i * n + k]) > fabs(A[(long)p * n + k]))
                p = i;
        if (A[(long)p * n + k] == 0.0)
            return 1;
        if (p != k) {
            for (int j = 0; j < n; ++j) {
                double t = A[(long)k * n + j];
                A[(long)k * n + j] = A[(long)p * n + j];
                A[(long)p * n + j] = t;
            }
            double t = b[k];
            b[k] = b[p];
            b[p] = t;
        }
        for (int i = k + 1; i < n; ++i) {
            double f = A[(long)i * n + k] / A[(long)k * n + k];
            if (f == 0.0)
                continue;
            for (int j = k; j < n; ++j)
                A[(long)i * n + j] -= f * A[(long)k * n + j];
            b[i] -= f * b[k];
        }
    }
    for (int i = n - 1; i >= 0; --i) {
        double s = b[i];
        for (int j = i + 1; j < n; ++j)
            s -= A[(long)i * n + j] * b[j];
        b[i] = s / A[(long)i * n + i];
    }
    return 0;
}

enum { CHAIN, WEAK, KKT, SCALED, SINGULAR, NONFINITE };

static void run(const char *name, int kind)
{
    const int nodes = 60, bs = 12, nd = nodes * bs, nm = kind == KKT ? 3 * (nodes - 1) : 0, n = nd + nm;
    double *D = calloc((size_t)n * n, sizeof *D);
    char *mask = calloc((size_t)n * n, 1);
    int *scr = bt_scramble(n, &rng);
#define AT(i, j) D[(long)scr[i] * n + scr[j]]
#define ON(i, j) mask[(long)scr[i] * n + scr[j]] = 1
    bt_chain(D, mask, n, scr, nodes, bs, BT_UNSYMMETRIC, &rng);
    for (int i = 0; i < nd; ++i)
        AT(i, i) += kind == WEAK ? 1e-4 * urand() : 6.0;
    if (kind == KKT)                                      /* multiplier: unknown k of node e equals that of e + 1 */
        for (int e = 0; e + 1 < nodes; ++e)
            for (int k = 0; k < 3; ++k) {
                int m = nd + 3 * e + k, u = e * bs + k, w = (e + 1) * bs + k;
                AT(m, u) = AT(u, m) = 1.0;
                AT(m, w) = AT(w, m) = -1.0;
                ON(m, u), ON(u, m), ON(m, w), ON(w, m), ON(m, m);
            }
    if (kind == SCALED)
        for (int i = 0; i < n; ++i) {
            double s = pow(10.0, 12.0 * urand() - 6.0);
            for (int j = 0; j < n; ++j)
                AT(i, j) *= s;
        }
    if (kind == SINGULAR)
        for (int i = 0; i < n; ++i)
            AT(i, 7 * bs) = 0.0;
    int *Ap, *Ai;
    double *Ax;
    const int nnz = bt_csc(n, D, mask, &Ap, &Ai, &Ax);
    if (kind == NONFINITE)
        Ax[nnz / 2] = NAN;
    double *xt = malloc((size_t)n * sizeof *xt), *b = malloc((size_t)n * sizeof *b);
    for (int i = 0; i < n; ++i)
        xt[i] = urand() - 0.5;
    bt_matvec(n, D, xt, b);
    bk_band band;
    bk_band_plan(&band, n, Ap, Ai, 1L << 26);
    bk_bandsplit sp;
    int plan = bk_bandsplit_plan(&sp, n, Ap, Ai, band.perm, band.kl, band.ku);
    double *x1 = malloc((size_t)n * sizeof *x1), *x2 = malloc((size_t)n * sizeof *x2), *x3 = malloc((size_t)n * sizeof *x3);
    memcpy(x1, b, (size_t)n * sizeof *x1);
    memcpy(x2, b, (size_t)n * sizeof *x2);
    memcpy(x3, b, (size_t)n * sizeof *x3);
    omp_set_num_threads(1);
    int f1 = plan == 0 ? bk_bandsplit_factor(&sp, Ax) : -9;
    if (f1 == 0)
        bk_bandsplit_solve(&sp, x1);
    double rc = sp.rcond;
    omp_set_num_threads(2);
    int f2 = plan == 0 ? bk_bandsplit_factor(&sp, Ax) : -9;
    if (f2 == 0)
        bk_bandsplit_solve(&sp, x2);
    int f3 = plan == 0 ? bk_bandsplit_factor(&sp, Ax) : -9;
    if (f3 == 0)
        bk_bandsplit_solve(&sp, x3);
    double err = NAN, res = NAN, band_res = NAN;
    double *xb = malloc((size_t)n * sizeof *xb);
    memcpy(xb, b, (size_t)n * sizeof *xb);
    if (bk_band_factor_solve(&band, Ax, xb) == 0) {
        band_res = 0.0;
        for (int i = 0; i < n; ++i) {
            double ri = -b[i];
            for (int j = 0; j < n; ++j)
                ri += D[(long)i * n + j] * xb[j];
            band_res = fmax(band_res, fabs(ri));
        }
    }
    free(xb);
    if (f1 == 0) {
        double *A = malloc((size_t)n * n * sizeof *A), *xr = malloc((size_t)n * sizeof *xr);
        memcpy(A, D, (size_t)n * n * sizeof *A);
        memcpy(xr, b, (size_t)n * sizeof *xr);
        if (dense(n, A, xr) == 0) {
            double e = 0.0, s = 0.0, r = 0.0, bn = 0.0;
            for (int i = 0; i < n; ++i) {
                e = fmax(e, fabs(x1[i] - xr[i]));
                s = fmax(s, fabs(xr[i]));
                double ri = -b[i];
                for (int j = 0; j < n; ++j)
                    ri += D[(long)i * n + j] * x1[j];
                r = fmax(r, fabs(ri));
                bn = fmax(bn, fabs(b[i]));
            }
            err = e / s;
            res = r / bn;
        }
        free(A);
        free(xr);
    }
    printf("case=%s n=%d kl=%d ku=%d s=%d plan=%d factor=%d err=%.3e res=%.3e same_threads=%d same_again=%d "
           "rcond=%.3e band_res=%.3e\n",
           name, n, band.kl, band.ku, sp.s, plan, f1, err, res,
           f1 == f2 && (f1 != 0 || memcmp(x1, x2, (size_t)n * sizeof *x1) == 0),
           f2 == f3 && (f2 != 0 || memcmp(x2, x3, (size_t)n * sizeof *x2) == 0), rc, band_res);
    bk_bandsplit_free(&sp);
    bk_band_free(&band);
    free(D), free(mask), free(scr), free(Ap), free(Ai), free(Ax), free(xt), free(b), free(x1), free(x2), free(x3);
}

int main(void)
{
    run("chain", CHAIN);
    run("weak", WEAK);
    run("kkt", KKT);
    run("scaled", SCALED);
    run("singular", SINGULAR);
    run("nonfinite", NONFINITE);
    return 0;
}
