/* band_check.c -- the band LU of runtime/linalg/bandlu.c against dense Gaussian
 * elimination with complete pivoting written here (a different algorithm on a
 * dense copy), on matrices shaped like the Newton systems:
 *   chain:    a block-tridiagonal chain (beam nodes of 12 unknowns), unsymmetric
 *             values, given in a scrambled numbering (the ordering must find the band);
 *   kkt:      the chain plus multiplier rows and columns (zero diagonal) that
 *             tie unknowns of the first and of the last node (a closed loop:
 *             the band is wider) -- needs row interchanges;
 *   indefinite: a symmetric chain shifted so that it has negative eigenvalues;
 *   scaled:   rows of very different magnitudes (1e-6 ... 1e6);
 *   singular: a zero column must be reported, not solved.
 * Prints one line per case: case=NAME n= kl= ku= err= (relative solution
 * error, max norm) rcond= and the status codes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/bandlu.h"
#include "linalg/linsolve.h"

#include "band_test_util.h"

static unsigned long long rng = 0x9E3779B97F4A7C15ULL;
static double urand(void)
{
    return bt_urand(&rng);
}

/* Dense solve with complete pivoting, A (n x n, row-major) overwritten. */
static int dense_solve(int n, double *A, double *b, double *x)
{
    int *cp = malloc((size_t)n * sizeof *cp);
    for (int i = 0; i < n; ++i)
        cp[i] = i;
    for (int k = 0; k < n; ++k) {
        int pr = k, pc = k;
        double big = 0.0;
        for (int i = k; i < n; ++i)
            for (int j = k; j < n; ++j)
                if (fabs(A[i * n + j]) > big) {
                    big = fabs(A[i * n + j]);
                    pr = i;
                    pc = j;
                }
        if (big == 0.0) {
            free(cp);
            return 1;
        }
        for (int j = 0; j < n; ++j) {
            double t = A[k * n + j];
            A[k * n + j] = A[pr * n + j];
            A[pr * n + j] = t;
        }
        double t = b[k];
        b[k] = b[pr];
        b[pr] = t;
        for (int i = 0; i < n; ++i) {
            double s = A[i * n + k];
            A[i * n + k] = A[i * n + pc];
            A[i * n + pc] = s;
        }
        int c = cp[k];
        cp[k] = cp[pc];
        cp[pc] = c;
        for (int i = k + 1; i < n; ++i) {
            double f = A[i * n + k] / A[k * n + k];
            for (int j = k; j < n; ++j)
                A[i * n + j] -= f * A[k * n + j];
            b[i] -= f * b[k];
        }
    }
    double *y = malloc((size_t)n * sizeof *y);
    for (int i = n - 1; i >= 0; --i) {
        double s = b[i];
        for (int j = i + 1; j < n; ++j)
            s -= A[i * n + j] * y[j];
        y[i] = s / A[i * n + i];
    }
    for (int k = 0; k < n; ++k)
        x[cp[k]] = y[k];
    free(y);
    free(cp);
    return 0;
}

/* Negative eigenvalues of the symmetric matrix A (n x n, row-major, destroyed)
 * by cyclic Jacobi rotations. */
static int jacobi_negative(int n, double *A)
{
    for (int sweep = 0; sweep < 100; ++sweep) {
        double off = 0.0;
        for (int p = 0; p < n; ++p)
            for (int q = p + 1; q < n; ++q)
                off += A[p * n + q] * A[p * n + q];
        if (off < 1e-26)
            break;
        for (int p = 0; p < n; ++p)
            for (int q = p + 1; q < n; ++q) {
                double apq = A[p * n + q];
                if (fabs(apq) < 1e-300)
                    continue;
                double th = 0.5 * (A[q * n + q] - A[p * n + p]) / apq;
                double t = (th >= 0 ? 1.0 : -1.0) / (fabs(th) + sqrt(th * th + 1.0));
                double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
                for (int k = 0; k < n; ++k) {
                    double akp = A[k * n + p], akq = A[k * n + q];
                    A[k * n + p] = c * akp - s * akq;
                    A[k * n + q] = s * akp + c * akq;
                }
                for (int k = 0; k < n; ++k) {
                    double apk = A[p * n + k], aqk = A[q * n + k];
                    A[p * n + k] = c * apk - s * aqk;
                    A[q * n + k] = s * apk + c * aqk;
                }
            }
    }
    int neg = 0;
    for (int i = 0; i < n; ++i)
        neg += A[i * n + i] < 0.0;
    return neg;
}

enum { CHAIN, KKT, INDEFINITE, SCALED, SINGULAR };

static void run(const char *name, int kind)
{
    const int nodes = 9, bs = 12, nd = nodes * bs, nm = kind == KKT ? 3 : 0, n = nd + nm;
    double *D = calloc((size_t)n * n, sizeof *D);
    char *mask = calloc((size_t)n * n, 1);
    int *scr = bt_scramble(n, &rng);                        /* scrambled numbering of the unknowns */
#define AT(i, j) D[scr[i] * n + scr[j]]
#define ON(i, j) mask[scr[i] * n + scr[j]] = 1
    bt_chain(D, mask, n, scr, nodes, bs, kind == INDEFINITE || kind == KKT ? BT_SYMMETRIC : BT_UNSYMMETRIC, &rng);
    for (int i = 0; i < nd; ++i)
        AT(i, i) += kind == INDEFINITE ? 1.0 : 6.0;       /* INDEFINITE: a shift that leaves negative eigenvalues */
    if (kind == KKT)
        for (int k = 0; k < nm; ++k) {                     /* multiplier k ties node 0 to the last node */
            int m = nd + k, u = k, w = (nodes - 1) * bs + k;
            AT(m, u) = AT(u, m) = 1.0;
            AT(m, w) = AT(w, m) = -1.0;
            ON(m, u), ON(u, m), ON(m, w), ON(w, m), ON(m, m);   /* a structural zero on the diagonal */
        }
    if (kind == SCALED)
        for (int i = 0; i < n; ++i) {
            double s = pow(10.0, 12.0 * urand() - 6.0);
            for (int j = 0; j < n; ++j)
                AT(i, j) *= s;
        }
    if (kind == SINGULAR)
        for (int i = 0; i < n; ++i)
            AT(i, 5) = 0.0;
    int *Ap, *Ai;
    double *Ax;
    const int nnz = bt_csc(n, D, mask, &Ap, &Ai, &Ax);
    double *xt = malloc((size_t)n * sizeof *xt), *b = malloc((size_t)n * sizeof *b);
    double *xr = malloc((size_t)n * sizeof *xr), *bd = malloc((size_t)n * sizeof *bd);
    for (int i = 0; i < n; ++i)
        xt[i] = urand() - 0.5;
    bt_matvec(n, D, xt, b);
    memcpy(bd, b, (size_t)n * sizeof *bd);
    bk_band band;
    int plan = bk_band_plan(&band, n, Ap, Ai, 1L << 24);
    int fac = plan == 0 ? bk_band_factor(&band, Ax) : -9;
    double err = NAN;
    int fused_same = -1;                 /* factor + solve in one pass: the same bits as the two calls */
    int reuse_same = -1;                 /* a plan factoring again: the same bits as a fresh plan */
    if (fac == 0) {
        double *bf = malloc((size_t)n * sizeof *bf);
        memcpy(bf, b, (size_t)n * sizeof *bf);
        bk_band_solve(&band, b);
        fused_same = bk_band_factor_solve(&band, Ax, bf) == 0 && memcmp(bf, b, (size_t)n * sizeof *b) == 0;
        /* The plan reused, as the Newton solver does: a second matrix on the
         * same pattern, diagonally dominant (no interchanges), after this
         * one (whose interchanges may have filled rows above the band), then
         * this one again after the storage was scribbled on as scratch (the
         * stability check borrows it): each the same bits as a fresh plan.
         * The factorization zeroes only the rows an earlier one may have
         * written; a row it wrongly assumed zero would show here. */
        double *Ay = malloc((size_t)nnz * sizeof *Ay), big = 0.0;
        for (int k = 0; k < nnz; ++k)
            big = fmax(big, fabs(Ax[k]));
        for (int j = 0; j < n; ++j)
            for (int p = Ap[j]; p < Ap[j + 1]; ++p)
                Ay[p] = Ax[p] + (Ai[p] == j ? 10.0 * n * big : 0.0);
        double *y1 = malloc((size_t)n * sizeof *y1), *y2 = malloc((size_t)n * sizeof *y2);
        bk_band fresh;
        reuse_same = bk_band_plan(&fresh, n, Ap, Ai, 1L << 24) == 0;
        for (int round = 0; round < 2 && reuse_same; ++round) {
            const double *Am = round == 0 ? Ay : Ax;
            memcpy(y1, bd, (size_t)n * sizeof *y1);
            memcpy(y2, bd, (size_t)n * sizeof *y2);
            if (round == 1) {
                for (long k = 0; k < (long)band.ldab * n; ++k)
                    band.ab[k] = NAN;
                bk_band_clobbered(&band);
            }
            reuse_same = bk_band_factor_solve(&fresh, Am, y1) == 0 && bk_band_factor_solve(&band, Am, y2) == 0 &&
                         memcmp(y1, y2, (size_t)n * sizeof *y1) == 0;
            bk_band_free(&fresh);
            if (round == 0 && reuse_same)
                reuse_same = bk_band_plan(&fresh, n, Ap, Ai, 1L << 24) == 0;
        }
        free(Ay), free(y1), free(y2);
        free(bf);
        double *A = malloc((size_t)n * n * sizeof *A);
        memcpy(A, D, (size_t)n * n * sizeof *A);
        int dr = dense_solve(n, A, bd, xr);
        free(A);
        double e = 0.0, s = 0.0;
        for (int i = 0; i < n; ++i) {
            e = fmax(e, fabs(b[i] - xr[i]));
            s = fmax(s, fabs(xr[i]));
        }
        err = dr == 0 ? e / s : NAN;
    }
    /* the same through the linear-solver object (band chosen) and through KLU
     * (a band too wide for the limit) must agree */
    bk_linsolver ls;
    int li = bk_lin_init(&ls, n, Ap, Ai);
    double *c = malloc((size_t)n * sizeof *c);
    bt_matvec(n, D, xt, c);
    double *Ax2 = malloc((size_t)nnz * sizeof *Ax2);
    memcpy(Ax2, Ax, (size_t)nnz * sizeof *Ax2);
    int lf = li == BK_LIN_OK ? bk_lin_factor(&ls, Ax2) : -9;
    double lerr = NAN;
    if (lf == BK_LIN_OK && bk_lin_solve(&ls, c) == BK_LIN_OK) {
        lerr = 0.0;
        for (int i = 0; i < n; ++i)
            lerr = fmax(lerr, fabs(c[i] - xt[i]));
    }
    /* each backend chosen explicitly (band LU, KLU, dense LU): the same solution */
    double kind_err[3] = {NAN, NAN, NAN};
    const bk_lin_kind kinds[3] = {BK_LIN_BAND, BK_LIN_KLU, BK_LIN_DENSE};
    for (int k = 0; k < 3; ++k) {
        bk_linsolver lk;
        double *ck = malloc((size_t)n * sizeof *ck);
        bt_matvec(n, D, xt, ck);
        memcpy(Ax2, Ax, (size_t)nnz * sizeof *Ax2);
        if (bk_lin_init_kind(&lk, n, Ap, Ai, kinds[k]) == BK_LIN_OK && bk_lin_factor(&lk, Ax2) == BK_LIN_OK &&
            bk_lin_solve(&lk, ck) == BK_LIN_OK) {
            kind_err[k] = 0.0;
            for (int i = 0; i < n; ++i)
                kind_err[k] = fmax(kind_err[k], fabs(ck[i] - xt[i]));
        }
        bk_lin_free(&lk);
        free(ck);
    }
    /* symmetric cases: the band LDL^T's inertia against Jacobi eigenvalues, and its solve */
    int sym_neg = -1, jac_neg = -1, sym_fac = -9;
    double sym_err = NAN, sym_mv_err = NAN;
    if (kind == INDEFINITE || kind == KKT) {
        /* the multipliers' zero diagonal regularized as the stability check does */
        for (int k = 0; k < nm; ++k)
            AT(nd + k, nd + k) = -1e-8;
        bt_to_csc(n, D, mask, Ap, Ai, Ax);
        bk_bandsym bs;
        int sym_plan = bk_bandsym_plan(&bs, n, Ap, Ai, NULL, -1, 1L << 24);
        double *band = sym_plan == 0 ? malloc((size_t)bs.ldab * n * sizeof *band) : NULL;
        if (band) {
            /* the band's product against the dense matrix's */
            bk_bandsym_fill(&bs, Ap, Ai, Ax, band);
            double *y = malloc((size_t)n * sizeof *y);
            bk_bandsym_matvec(&bs, band, xt, y);
            sym_mv_err = 0.0;
            for (int i = 0; i < n; ++i) {
                double r = 0.0;
                for (int j = 0; j < n; ++j)
                    r += D[i * n + j] * xt[j];
                sym_mv_err = fmax(sym_mv_err, fabs(y[i] - r) / (1.0 + fabs(r)));
            }
            free(y);
        }
        if (band && (sym_fac = bk_bandsym_factor(&bs, band)) == 0) {
            sym_neg = 0;
            for (int i = 0; i < n; ++i)
                sym_neg += bs.D[i] < 0.0;
            double *y = malloc((size_t)n * sizeof *y);
            bt_matvec(n, D, xt, y);
            bk_bandsym_solve(&bs, y);
            sym_err = 0.0;
            for (int i = 0; i < n; ++i)
                sym_err = fmax(sym_err, fabs(y[i] - xt[i]));
            free(y);
        }
        free(band);
        bk_bandsym_free(&bs);
        double *A = malloc((size_t)n * n * sizeof *A);
        memcpy(A, D, (size_t)n * n * sizeof *A);
        jac_neg = jacobi_negative(n, A);
        free(A);
    }
    printf("case=%s n=%d kl=%d ku=%d plan=%d factor=%d err=%.3e rcond=%.3e lin_band=%d lin_factor=%d lin_err=%.3e "
           "sym_factor=%d sym_negative=%d jacobi_negative=%d sym_err=%.3e sym_matvec_err=%.3e fused_same=%d reuse_same=%d "
           "band_err=%.3e klu_err=%.3e dense_err=%.3e\n",
           name, n, band.kl, band.ku, plan, fac, err, band.rcond, bk_lin_band(&ls) != NULL, lf, lerr, sym_fac, sym_neg,
           jac_neg, sym_err, sym_mv_err, fused_same, reuse_same, kind_err[0], kind_err[1], kind_err[2]);
    bk_lin_free(&ls);
    bk_band_free(&band);
    free(D), free(mask), free(scr), free(Ap), free(Ai), free(Ax), free(Ax2), free(xt), free(b), free(xr), free(bd),
        free(c);
#undef AT
#undef ON
}

int main(void)
{
    run("chain", CHAIN);
    run("kkt", KKT);
    run("indefinite", INDEFINITE);
    run("scaled", SCALED);
    run("singular", SINGULAR);
    return 0;
}
