/* lanczos_check.c -- the Lanczos eigen-solver (runtime/linalg/lanczos.h) on
 * problems with closed-form eigenvalues: K x = lambda M x with diagonal K and
 * M (repeated eigenvalues, and massless directions where M is zero), and the
 * second-difference matrix tridiag(-1, 2, -1) (eigenvalues 2 - 2 cos(k pi /
 * (n + 1))), each through OP = K^-1 M.  Prints "case=NAME key=value ..."
 * lines for tests/test_modal_sparse.py. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "linalg/lanczos.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define N 300

typedef struct problem {
    int tridiag;                 /* 0: K = diag(k); 1: K = tridiag(-1, 2, -1) */
    double k[N], m[N];
} problem;

static void bprod(void *ctx, const double *x, double *y)
{
    const problem *p = ctx;
    for (int i = 0; i < N; ++i)
        y[i] = p->m[i] * x[i];
}

/* y = K^-1 M x (the Thomas algorithm for the tridiagonal K). */
static int op(void *ctx, const double *x, double *y)
{
    const problem *p = ctx;
    if (!p->tridiag) {
        for (int i = 0; i < N; ++i)
            y[i] = p->m[i] * x[i] / p->k[i];
        return 0;
    }
    double c[N], d[N];
    for (int i = 0; i < N; ++i) {          /* forward: c_i = -1 / den_i, den_i = 2 + c_{i-1} */
        const double den = i > 0 ? 2.0 + c[i - 1] : 2.0;
        c[i] = -1.0 / den;
        d[i] = (p->m[i] * x[i] + (i > 0 ? d[i - 1] : 0.0)) / den;
    }
    y[N - 1] = d[N - 1];
    for (int i = N - 2; i >= 0; --i)
        y[i] = d[i] - c[i] * y[i + 1];
    return 0;
}

/* Runs the solver for `want` pairs; prints the largest relative error of the
 * eigenvalues against ref[want] (descending theta), the largest residual
 * |OP x - theta x|_M / theta and the largest deviation of X^T M X from I. */
static void check(const char *name, problem *p, int want, const double *ref)
{
    double theta[16], *X = malloc((size_t)want * N * sizeof *X), y[N], by[N];
    int nconv, steps;
    bk_lanczos_ops ops = {p, op, bprod};
    int rc = bk_lanczos(N, want, 4 * want + 60, 1e-12, &ops, theta, X, &nconv, &steps);
    double eerr = 0.0, res = 0.0, orth = 0.0;
    for (int k = 0; k < nconv; ++k) {
        eerr = fmax(eerr, fabs(theta[k] - ref[k]) / fabs(ref[k]));
        op(p, X + (size_t)k * N, y);
        for (int i = 0; i < N; ++i)
            y[i] -= theta[k] * X[(size_t)k * N + i];
        bprod(p, y, by);
        double r2 = 0.0;
        for (int i = 0; i < N; ++i)
            r2 += y[i] * by[i];
        res = fmax(res, sqrt(fabs(r2)) / fabs(theta[k]));
        for (int l = 0; l < nconv; ++l) {
            bprod(p, X + (size_t)l * N, by);
            double g = 0.0;
            for (int i = 0; i < N; ++i)
                g += X[(size_t)k * N + i] * by[i];
            orth = fmax(orth, fabs(g - (k == l)));
        }
    }
    printf("case=%s rc=%d nconv=%d want=%d steps=%d eig_err=%.3e residual=%.3e orth=%.3e\n", name, rc, nconv, want,
           steps, eerr, res, orth);
    free(X);
}

static int descending(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x < y) - (x > y);
}

int main(void)
{
    static problem p;
    /* diagonal K with repeated eigenvalues: k = 1, 1, 2, 3, 3, 3, 4, 5, ...; M = I */
    for (int i = 0; i < N; ++i) {
        p.k[i] = i < 2 ? 1.0 : i == 2 ? 2.0 : i < 6 ? 3.0 : (double)(i - 2);
        p.m[i] = 1.0;
    }
    const double rep[8] = {1.0, 1.0, 0.5, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, 0.25, 0.2};
    check("repeated", &p, 8, rep);
    /* massless directions: every third M zero; K = 1 + i: theta = m / k over the rest */
    double mass[N];
    int nm = 0;
    for (int i = 0; i < N; ++i) {
        p.k[i] = 1.0 + i;
        p.m[i] = i % 3 == 1 ? 0.0 : 1.0 + 0.5 * (i % 2);
        if (p.m[i] > 0.0)
            mass[nm++] = p.m[i] / p.k[i];
    }
    qsort(mass, (size_t)nm, sizeof *mass, descending);
    check("massless", &p, 6, mass);
    /* the second difference: theta_k = 1 / (2 - 2 cos(k pi / (N + 1))) */
    p.tridiag = 1;
    double lap[8];
    for (int i = 0; i < N; ++i)
        p.m[i] = 1.0;
    for (int k = 0; k < 8; ++k)
        lap[k] = 1.0 / (2.0 - 2.0 * cos((k + 1) * M_PI / (N + 1)));
    check("second_difference", &p, 8, lap);
    return 0;
}
