/* lanczos.c -- Lanczos with full reorthogonalization in a B-inner product, and
 * the Jacobi eigen-solver of its small tridiagonal matrix (see lanczos.h). */
#include "linalg/lanczos.h"

#define BK_LANCZOS_ROUNDS 6         /* runs at most: repeated eigenvalues need one run per copy, and one more */

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static double dot(int n, const double *x, const double *y)
{
    double s = 0.0;
    for (int i = 0; i < n; ++i)
        s += x[i] * y[i];
    return s;
}

void bk_jacobi_eigen(int m, double *A, double *w, double *V)
{
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j)
            V[i * m + j] = i == j;
    for (int sweep = 0; sweep < 100; ++sweep) {
        double off = 0.0, diag = 0.0;
        for (int i = 0; i < m; ++i) {
            diag += A[i * m + i] * A[i * m + i];
            for (int j = i + 1; j < m; ++j)
                off += A[i * m + j] * A[i * m + j];
        }
        if (off <= 1e-32 * diag || off == 0.0)
            break;
        for (int p = 0; p < m; ++p)
            for (int q = p + 1; q < m; ++q) {
                const double apq = A[p * m + q];
                if (apq == 0.0)
                    continue;
                /* the rotation that zeroes A[p][q]: t = tan of its angle, the smaller root */
                const double th = (A[q * m + q] - A[p * m + p]) / (2.0 * apq);
                const double t = (th >= 0.0 ? 1.0 : -1.0) / (fabs(th) + sqrt(th * th + 1.0));
                const double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
                for (int k = 0; k < m; ++k) {          /* A <- A J (columns p, q) */
                    const double akp = A[k * m + p], akq = A[k * m + q];
                    A[k * m + p] = c * akp - s * akq;
                    A[k * m + q] = s * akp + c * akq;
                }
                for (int k = 0; k < m; ++k) {          /* A <- J^T A (rows p, q) */
                    const double apk = A[p * m + k], aqk = A[q * m + k];
                    A[p * m + k] = c * apk - s * aqk;
                    A[q * m + k] = s * apk + c * aqk;
                }
                for (int k = 0; k < m; ++k) {          /* V <- V J */
                    const double vkp = V[k * m + p], vkq = V[k * m + q];
                    V[k * m + p] = c * vkp - s * vkq;
                    V[k * m + q] = s * vkp + c * vkq;
                }
            }
    }
    /* descending, the vectors with them (selection: m is small) */
    for (int i = 0; i < m; ++i)
        w[i] = A[i * m + i];
    for (int i = 0; i < m; ++i) {
        int b = i;
        for (int j = i + 1; j < m; ++j)
            if (w[j] > w[b])
                b = j;
        if (b == i)
            continue;
        double t = w[i];
        w[i] = w[b], w[b] = t;
        for (int k = 0; k < m; ++k) {
            t = V[k * m + i];
            V[k * m + i] = V[k * m + b], V[k * m + b] = t;
        }
    }
}

/* The Ritz values of T_m (alpha[m], beta[m - 1]) into w, its eigenvectors into
 * S (column k); T is scratch [m m]. */
static void ritz(int m, const double *alpha, const double *beta, double *T, double *w, double *S)
{
    memset(T, 0, (size_t)m * (size_t)m * sizeof *T);
    for (int i = 0; i < m; ++i) {
        T[i * m + i] = alpha[i];
        if (i + 1 < m)
            T[i * m + i + 1] = T[(i + 1) * m + i] = beta[i];
    }
    bk_jacobi_eigen(m, T, w, S);
}

/* w -= sum_i <w, L_i>_B L_i over the nl locked vectors L (B L in BL). */
static void deflate(int n, int nl, const double *L, const double *BL, double *w)
{
    for (int i = 0; i < nl; ++i) {
        const double c = dot(n, w, BL + (size_t)i * (size_t)n);
        const double *li = L + (size_t)i * (size_t)n;
        for (int k = 0; k < n; ++k)
            w[k] -= c * li[k];
    }
}

/* One Lanczos run B-orthogonal to the nl locked vectors L[nl n] (BL: B L):
 * its converged pairs into theta, X (see bk_lanczos). */
static int run(int n, int want, int maxit, double tol, const bk_lanczos_ops *ops, int nl, const double *L,
               const double *BL, unsigned seed, double *theta, double *X, int *nconv, int *steps)
{
    *nconv = 0;
    *steps = 0;
    if (maxit > n)
        maxit = n;
    if (want > maxit)
        want = maxit;
    if (n <= 0 || want <= 0)
        return 1;
    const size_t nn = (size_t)n, mm = (size_t)maxit + 1;
    /* the basis grows as it is needed: most runs stop far below maxit */
    size_t cap = (size_t)(2 * want + 20) < mm ? (size_t)(2 * want + 20) : mm;
    double *V = malloc(cap * nn * sizeof *V), *BV = malloc(cap * nn * sizeof *BV);
    double *w = malloc(nn * sizeof *w), *bw = malloc(nn * sizeof *bw), *c = malloc(mm * sizeof *c);
    double *alpha = calloc(mm, sizeof *alpha), *beta = calloc(mm, sizeof *beta);
    double *T = malloc(mm * mm * sizeof *T), *S = malloc(mm * mm * sizeof *S), *rv = malloc(mm * sizeof *rv);
    int rc = -1, m = 0;
    if (!V || !BV || !w || !bw || !c || !alpha || !beta || !T || !S || !rv)
        goto done;
    /* the start: OP of a fixed pseudo-random vector (xorshift), B-normalized */
    uint64_t r = 0x9E3779B97F4A7C15ull + 0x2545F4914F6CDD1Dull * seed;
    for (int i = 0; i < n; ++i) {
        r ^= r << 13, r ^= r >> 7, r ^= r << 17;
        bw[i] = (double)(r >> 11) / 9007199254740992.0 - 0.5;
    }
    if (ops->op(ops->ctx, bw, w) != 0)
        goto done;
    deflate(n, nl, L, BL, w);
    deflate(n, nl, L, BL, w);
    ops->bprod(ops->ctx, w, bw);
    double nb = sqrt(fmax(dot(n, w, bw), 0.0));
    if (!(nb > 0.0) || !isfinite(nb)) {
        rc = 1;                                   /* OP B-annihilates everything: no eigenpair */
        goto done;
    }
    for (int i = 0; i < n; ++i)
        V[i] = w[i] / nb, BV[i] = bw[i] / nb;
    double tmax = 0.0;                            /* the largest |Ritz value| seen: the scale of "small" */
    for (m = 0; m < maxit;) {
        const double *v = V + (size_t)m * nn;
        if (ops->op(ops->ctx, v, w) != 0) {
            rc = -1;
            goto done;
        }
        /* w -= sum_i <w, v_i>_B v_i over every earlier vector, twice (the three-term
         * recurrence is the first pass's last two terms) */
        alpha[m] = 0.0;
        for (int pass = 0; pass < 2; ++pass) {
            for (int i = 0; i <= m; ++i)
                c[i] = dot(n, w, BV + (size_t)i * nn);
            for (int i = 0; i <= m; ++i) {
                const double *vi = V + (size_t)i * nn;
                for (int k = 0; k < n; ++k)
                    w[k] -= c[i] * vi[k];
            }
            alpha[m] += c[m];
            deflate(n, nl, L, BL, w);
        }
        ops->bprod(ops->ctx, w, bw);
        const double b = sqrt(fmax(dot(n, w, bw), 0.0));
        ++m;
        tmax = fmax(tmax, fabs(alpha[m - 1]));
        const int invariant = !(b > 1e-13 * fmax(tmax, 1e-300));
        if (invariant || (m >= want && (m % 5 == 0 || m == maxit))) {
            ritz(m, alpha, beta, T, rv, S);
            int good = 0;                 /* (an invariant subspace: every Ritz pair is exact) */
            for (int k = 0; k < want && k < m; ++k)
                if (invariant || fabs(b * S[(size_t)(m - 1) * (size_t)m + k]) <= tol * fabs(rv[k]))
                    good++;
                else
                    break;
            if (good == want || invariant || m == maxit) {
                *nconv = good;
                break;
            }
        }
        beta[m - 1] = b;
        if ((size_t)m + 1 > cap) {
            size_t nc = 2 * cap < mm ? 2 * cap : mm;
            double *nv = realloc(V, nc * nn * sizeof *V);
            if (nv)
                V = nv;
            double *nbv = nv ? realloc(BV, nc * nn * sizeof *BV) : NULL;
            if (nbv)
                BV = nbv;
            if (!nv || !nbv) {
                rc = -1;
                goto done;
            }
            cap = nc;
        }
        double *vn = V + (size_t)m * nn, *bvn = BV + (size_t)m * nn;
        for (int k = 0; k < n; ++k)
            vn[k] = w[k] / b, bvn[k] = bw[k] / b;
    }
    /* the Ritz pairs of the last check: theta, and x = V s */
    for (int k = 0; k < *nconv; ++k) {
        theta[k] = rv[k];
        if (!X)
            continue;
        double *x = X + (size_t)k * nn;
        memset(x, 0, nn * sizeof *x);
        for (int j = 0; j < m; ++j) {
            const double sj = S[(size_t)j * (size_t)m + k];
            const double *vj = V + (size_t)j * nn;
            for (int i = 0; i < n; ++i)
                x[i] += sj * vj[i];
        }
    }
    *steps = m;
    rc = *nconv == want ? 0 : 1;
done:
    free(V), free(BV), free(w), free(bw), free(c), free(alpha), free(beta), free(T), free(S), free(rv);
    return rc;
}

int bk_lanczos(int n, int want, int maxit, double tol, const bk_lanczos_ops *ops, double *theta, double *X,
               int *nconv, int *steps)
{
    *nconv = *steps = 0;
    if (maxit > n)
        maxit = n;
    if (want > maxit)
        want = maxit;
    if (n <= 0 || want <= 0)
        return 1;
    const size_t nn = (size_t)n, w2 = 2 * (size_t)want;
    /* locked pairs (the best `want` so far, descending) and a run's new ones after them */
    double *th = malloc(w2 * sizeof *th), *L = malloc(w2 * nn * sizeof *L), *BL = malloc(w2 * nn * sizeof *BL);
    int *idx = malloc(w2 * sizeof *idx), nl = 0, rc = -1;
    double *tmpv = malloc(w2 * nn * sizeof *tmpv), *tmpt = malloc(w2 * sizeof *tmpt);
    if (!th || !L || !BL || !idx || !tmpv || !tmpt)
        goto done;
    for (int round = 0; round < BK_LANCZOS_ROUNDS; ++round) {
        int nc, st;
        int r = run(n, want, maxit, tol, ops, nl, L, BL, (unsigned)round, th + nl, L + (size_t)nl * nn, &nc, &st);
        *steps += st;
        if (r < 0)
            goto done;
        if (round == 0 && nc < want) {          /* not converged: report what did */
            nl = nc;
            break;
        }
        /* merge: the best `want` of the locked and the new pairs (a new one that
         * ranks below every locked one changes nothing: then the locked ones are
         * all the operator has above it) */
        const int tot = nl + nc;
        for (int i = 0; i < tot; ++i)
            idx[i] = i;
        for (int i = 0; i < tot; ++i)            /* selection, descending */
            for (int j = i + 1; j < tot; ++j)
                if (th[idx[j]] > th[idx[i]]) {
                    int t = idx[i];
                    idx[i] = idx[j], idx[j] = t;
                }
        const int keep = tot < want ? tot : want;
        int changed = 0;
        for (int i = 0; i < keep; ++i)
            changed |= idx[i] >= nl;
        for (int i = 0; i < keep; ++i) {
            tmpt[i] = th[idx[i]];
            memcpy(tmpv + (size_t)i * nn, L + (size_t)idx[i] * nn, nn * sizeof *tmpv);
        }
        memcpy(th, tmpt, (size_t)keep * sizeof *th);
        memcpy(L, tmpv, (size_t)keep * nn * sizeof *L);
        nl = keep;
        for (int i = 0; i < nl; ++i)
            ops->bprod(ops->ctx, L + (size_t)i * nn, BL + (size_t)i * nn);
        if (!changed && round > 0)
            break;
    }
    *nconv = nl;
    memcpy(theta, th, (size_t)nl * sizeof *theta);
    if (X)
        memcpy(X, L, (size_t)nl * nn * sizeof *X);
    rc = nl == want ? 0 : 1;
done:
    free(th), free(L), free(BL), free(idx), free(tmpv), free(tmpt);
    return rc;
}
