/* bandlu.c -- band LU with partial pivoting after a reverse Cuthill-McKee
 * ordering (see bandlu.h). */
#include "linalg/bandlu.h"
#include "base/bigalloc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "linalg/band_impl.h"


/* Breadth-first search from `root` over the unvisited nodes of the pattern
 * (neighbours by increasing degree); appends them to order[*len...]; returns
 * the last node reached (the deepest level).  mark: 1 = visited. */
static int bfs(int root, const int *Ap, const int *Ai, const int *deg, char *mark, int *order, int *len,
               int *nbr)
{
    int head = *len, last = root;
    order[(*len)++] = root;
    mark[root] = 1;
    while (head < *len) {
        int v = order[head++], k = 0;
        last = v;
        for (int p = Ap[v]; p < Ap[v + 1]; ++p) {
            int u = Ai[p];
            if (mark[u])
                continue;
            mark[u] = 1;
            /* insertion by degree (lists are short: the couplings of one node) */
            int q = k++;
            while (q > 0 && deg[nbr[q - 1]] > deg[u]) {
                nbr[q] = nbr[q - 1];
                --q;
            }
            nbr[q] = u;
        }
        for (int q = 0; q < k; ++q)
            order[(*len)++] = nbr[q];
    }
    return last;
}

/* Reverse Cuthill-McKee order of the (structurally symmetric) pattern:
 * perm[new] = old.  Each connected component starts from a pseudo-peripheral
 * node (the end of a search from the end of a search from its node of least
 * degree). */
int bk_band_rcm(int n, const int *Ap, const int *Ai, int *perm)
{
    int *deg = malloc((size_t)n * sizeof *deg), *nbr = malloc((size_t)n * sizeof *nbr);
    int *tmp = malloc((size_t)n * sizeof *tmp);
    char *mark = calloc((size_t)n, 1);
    if (!deg || !nbr || !tmp || !mark) {
        free(deg), free(nbr), free(tmp), free(mark);
        return -1;
    }
    for (int i = 0; i < n; ++i)
        deg[i] = Ap[i + 1] - Ap[i];
    int len = 0;
    for (;;) {
        int start = -1;
        for (int i = 0; i < n; ++i)
            if (!mark[i] && (start < 0 || deg[i] < deg[start]))
                start = i;
        if (start < 0)
            break;
        /* two trial searches to find a far end of the component, then the real one */
        int root = start;
        for (int trial = 0; trial < 2; ++trial) {
            int l0 = len, tl = len;
            int far = bfs(root, Ap, Ai, deg, mark, tmp, &tl, nbr);
            for (int k = l0; k < tl; ++k)
                mark[tmp[k]] = 0;
            root = far;
        }
        bfs(root, Ap, Ai, deg, mark, perm, &len, nbr);
    }
    for (int i = 0; i < n / 2; ++i) {
        int t = perm[i];
        perm[i] = perm[n - 1 - i];
        perm[n - 1 - i] = t;
    }
    free(deg), free(nbr), free(tmp), free(mark);
    return 0;
}

/* The widths of the pattern (Ap, Ai) in the order iperm (old -> new): the
 * largest distance of an entry below the diagonal (*kl) and above it (*ku). */
void bk_band_widths(int n, const int *Ap, const int *Ai, const int *iperm, int *kl, int *ku)
{
    int lo = 0, up = 0;
    for (int j = 0; j < n; ++j)
        for (int p = Ap[j]; p < Ap[j + 1]; ++p) {
            int d = iperm[Ai[p]] - iperm[j];
            if (d > lo)
                lo = d;
            if (-d > up)
                up = -d;
        }
    *kl = lo;
    *ku = up;
}

int bk_band_plan(bk_band *b, int n, const int *Ap, const int *Ai, long max_storage)
{
    memset(b, 0, sizeof *b);
    b->n = n;
    b->Ap = Ap;
    b->Ai = Ai;
    b->perm = malloc((size_t)(n > 0 ? n : 1) * sizeof *b->perm);
    b->iperm = malloc((size_t)(n > 0 ? n : 1) * sizeof *b->iperm);
    if (!b->perm || !b->iperm || bk_band_rcm(n, Ap, Ai, b->perm) != 0) {
        bk_band_free(b);
        return -1;
    }
    for (int i = 0; i < n; ++i)
        b->iperm[b->perm[i]] = i;
    int kl, ku;
    bk_band_widths(n, Ap, Ai, b->iperm, &kl, &ku);
    b->kl = kl;
    b->ku = ku;
    /* rows below the band up to a multiple of BK_BAND_LANES: the update loops
     * run over whole vectors (the extra rows hold zeros and stay zero) */
    b->klp = (kl + BK_BAND_LANES - 1) / BK_BAND_LANES * BK_BAND_LANES;
    b->ldab = kl + ku + b->klp + 1;
    if ((double)b->ldab * n > (double)max_storage) {
        bk_band_free(b);
        return 1;
    }
    b->ab = bk_big_malloc((size_t)b->ldab * (size_t)(n > 0 ? n : 1) * sizeof *b->ab);
    b->rs = malloc((size_t)(n > 0 ? n : 1) * sizeof *b->rs);
    b->ipiv = malloc((size_t)(n > 0 ? n : 1) * sizeof *b->ipiv);
    b->w = malloc((size_t)(n > 0 ? n : 1) * sizeof *b->w);
    if (!b->ab || !b->rs || !b->ipiv || !b->w) {
        bk_band_free(b);
        return -1;
    }
    b->rcond = NAN;
    b->dirty = kl + ku;                              /* fresh storage: all of it zeroed once */
    return 0;
}

void bk_band_clobbered(bk_band *b)
{
    b->dirty = b->kl + b->ku;
}

/* 2 when an entry of Ax in the CSC columns of new columns c >= from is not
 * finite, else `st` (the result of a factorization that stopped early: a
 * non-finite value is reported as such wherever it is). */
static int nonfinite_after(const bk_band *b, const double *Ax, int from, int st)
{
    for (int c = from; c < b->n; ++c) {
        const int j = b->perm[c];
        for (int p = b->Ap[j]; p < b->Ap[j + 1]; ++p)
            if (!(fabs(Ax[p]) <= INFINITY))
                return 2;
    }
    return st;
}

/* The factorization streams the band once: three cursors move along the new
 * columns, the row-scale scan ahead of the fill by kl + ku columns (row i
 * has its last entry in column i + ku, the fill of column c needs rows up to
 * c + kl), the fill (zero the band column, scaled CSC entries into it) ahead
 * of the elimination by kl + ku (step j updates columns up to j + kl + ku).
 * The window between the cursors stays in cache: each value is read from
 * memory once and the band written once, whatever n.  Each band entry gets
 * the same operations in the same order as with separate passes. */
static void band_back_solve(bk_band *b, double *x);

/* The factorization (x == NULL) or the factorization and the solve of A x = b
 * with b in x: the forward substitution then runs inside the elimination,
 * step j right after column j of L is made (while it is in cache), and only
 * the back substitution reads the factors again.  The operations on x are
 * those of bk_band_solve in the same order: the same bits. */
static int band_factor(bk_band *b, const double *Ax, double *x)
{
    const int n = b->n, kl = b->kl, ku = b->ku, kv = b->kl + b->ku, ldab = b->ldab;
    double *ab = b->ab, *rs = b->rs, *w = b->w;
    const int *Ap = b->Ap, *Ai = b->Ai, *perm = b->perm, *iperm = b->iperm;
    for (int i = 0; i < n; ++i)
        rs[i] = 0.0;
    int scanned = 0, scaled = 0, filled = 0;       /* columns scanned, rows scaled, columns filled */
    double umin = INFINITY, umax = 0.0;
    int ju = 0;                                      /* last column of U touched so far */
    int kvu = 0;                                     /* superdiagonals U has (ku without interchanges) */
    /* Rows of a column above superdiagonal `top` are zero from the last
     * factorization (it wrote up to its kvu); only the rows from there down are
     * zeroed and filled, so that without interchanges the kl rows kept for
     * their fill are neither read nor written: a third of the band's stream. */
    const int top = b->dirty > ku ? b->dirty : ku, row0 = kv - top;
    b->dirty = kv;                                   /* until this one has ended */
    for (int j = 0; j < n; ++j) {
        const int fill_to = j + kv + 1 < n ? j + kv + 1 : n;
        for (; filled < fill_to; ++filled) {
            const int c = filled, scan_to = c + kv + 1 < n ? c + kv + 1 : n;
            for (; scanned < scan_to; ++scanned) {
                const int jo = perm[scanned];
                for (int p = Ap[jo]; p < Ap[jo + 1]; ++p) {
                    const double a = fabs(Ax[p]);
                    const int i = iperm[Ai[p]];
                    if (!(a <= INFINITY))
                        return 2;
                    if (a > rs[i])
                        rs[i] = a;
                }
            }
            /* rows whose last column is scanned: their scale is final */
            const int scale_to = scanned == n ? n : scanned - ku;
            for (; scaled < scale_to; ++scaled) {
                if (!(rs[scaled] > 0.0))
                    return nonfinite_after(b, Ax, scanned, 1);   /* an empty row */
                rs[scaled] = 1.0 / rs[scaled];
                if (x)
                    w[scaled] = x[perm[scaled]] * rs[scaled];
            }
            double *bc = ab + (long)c * ldab;
            memset(bc + row0, 0, (size_t)(ldab - row0) * sizeof *bc);
            const int jo = perm[c];
            double *at = bc + kv - c;                /* at[i] = A(i, c), i in the new order */
            for (int p = Ap[jo]; p < Ap[jo + 1]; ++p) {
                const int i = iperm[Ai[p]];
                at[i] += Ax[p] * rs[i];
            }
        }
        const int km = kl < n - 1 - j ? kl : n - 1 - j;
        double *col = ab + kv + (long)j * ldab;      /* col[r] = A(j + r, j) */
        double amax = 0.0;
#pragma omp simd reduction(max : amax)
        for (int r = 0; r <= km; ++r) {
            const double a = fabs(col[r]);        /* (not fmax: a library call per entry) */
            amax = a > amax ? a : amax;
        }
        if (!(amax > 0.0))
            return nonfinite_after(b, Ax, scanned, 1);
        int piv = 0;
        if (!(fabs(col[0]) >= BK_BAND_PIVOT_TOL * amax))   /* the diagonal is too small: the largest */
            for (int r = 1; r <= km; ++r)
                if (fabs(col[r]) == amax) {
                    piv = r;
                    break;
                }
        b->ipiv[j] = j + piv;
        int last = j + b->ku + piv;
        if (last > n - 1)
            last = n - 1;
        if (last > ju)
            ju = last;
        if (piv != 0) {                              /* swap rows j and j + piv over columns j..ju */
            for (int c = j; c <= ju; ++c) {
                double *x = ab + (kv + j - c) + (long)c * ldab, *y = x + piv, t = *x;
                *x = *y;
                *y = t;
            }
        }
        const double d = col[0], inv = 1.0 / d;
        for (int r = 1; r <= km; ++r)
            col[r] *= inv;
        if (x) {                                     /* forward substitution, step j */
            if (piv != 0) {
                const double tw = w[j];
                w[j] = w[j + piv];
                w[j + piv] = tw;
            }
            const double tw = w[j];
            if (tw != 0.0)
                axpy_sub(km, tw, col + 1, w + j + 1);
        }
        if (ju - j > kvu)
            kvu = ju - j;
        const int kp = km == kl ? b->klp : km;          /* whole vectors inside the band */
        for (int c = j + 1; c <= ju; ++c) {
            double *cc = ab + (kv + j - c) + (long)c * ldab;   /* cc[r] = A(j + r, c) */
            const double a = cc[0];
            if (a != 0.0)
                axpy_sub(kp, a, col + 1, cc + 1);
        }
        double u = fabs(d);
        if (u < umin)
            umin = u;
        if (u > umax)
            umax = u;
    }
    b->rcond = n > 0 ? umin / umax : 1.0;
    b->kvu = kvu;
    b->dirty = kvu;
    if (x)
        band_back_solve(b, x);
    return 0;
}

int bk_band_factor(bk_band *b, const double *Ax)
{
    return band_factor(b, Ax, NULL);
}

int bk_band_factor_solve(bk_band *b, const double *Ax, double *x)
{
    return band_factor(b, Ax, x);
}

/* U x = w (kvu superdiagonals), then x back in the old order. */
static void band_back_solve(bk_band *b, double *x)
{
    const int n = b->n, kv = b->kl + b->ku, kvu = b->kvu, ldab = b->ldab;
    const double *ab = b->ab;
    double *w = b->w;
    for (int j = n - 1; j >= 0; --j) {
        const double *col = ab + kv + (long)j * ldab;   /* col[i - j] = U(i, j) */
        w[j] /= col[0];
        const double t = w[j];
        const int i0 = j - kvu > 0 ? j - kvu : 0;
        if (t != 0.0)
            axpy_sub(j - i0, t, col - (j - i0), w + i0);
    }
    for (int i = 0; i < n; ++i)
        x[b->perm[i]] = w[i];
}

void bk_band_solve(bk_band *b, double *x)
{
    const int n = b->n, kl = b->kl, kv = b->kl + b->ku, ldab = b->ldab;
    const double *ab = b->ab;
    double *w = b->w;
    for (int i = 0; i < n; ++i)
        w[i] = x[b->perm[i]] * b->rs[i];
    for (int j = 0; j < n; ++j) {                    /* L: unit lower, with the interchanges */
        int p = b->ipiv[j];
        if (p != j) {
            double t = w[j];
            w[j] = w[p];
            w[p] = t;
        }
        const int km = kl < n - 1 - j ? kl : n - 1 - j;
        const double *col = ab + kv + (long)j * ldab, t = w[j];
        if (t != 0.0)
            axpy_sub(km, t, col + 1, w + j + 1);
    }
    band_back_solve(b, x);
}

void bk_band_free(bk_band *b)
{
    free(b->perm);
    free(b->iperm);
    free(b->ab);
    free(b->rs);
    free(b->ipiv);
    free(b->w);
    memset(b, 0, sizeof *b);
}

