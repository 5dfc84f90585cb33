/* band_lapack.c -- the runtime's band LU against LAPACK's band solver on the
 * same Newton matrix (./build.sh bench, report/bench_band.py).
 *
 * usage: bench_band MATRIX_FILE REPEATS
 * MATRIX_FILE as bench/newton_iter.c writes it (int32 n, int64 nnz, Ap[n+1],
 * Ai[nnz], Ax[nnz], b[n]).  Both solvers get the matrix in the runtime's
 * reverse Cuthill-McKee order and its band widths (bk_band_plan), and each
 * timed call does what a Newton iteration with a new matrix does: the band
 * filled from the sparse values, factored, and the right-hand side solved:
 *   band:   bk_band_factor_solve (row scaling, threshold pivoting, the
 *           forward substitution during the elimination)
 *   lapack: the band filled in LAPACK's layout (2 kl + ku + 1 rows), dgbtrf,
 *           dgbtrs -- whichever LAPACK and BLAS the program is linked with
 *           (reference LAPACK, or OpenBLAS).
 * Prints key=value lines: n, kl, ku, the medians band_s and lapack_s, and the
 * largest difference of the two solutions relative to the largest entry.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "linalg/bandlu.h"
#include "median_clock.h"

void dgbtrf_(const int *m, const int *n, const int *kl, const int *ku, double *ab, const int *ldab, int *ipiv,
             int *info);
void dgbtrs_(const char *trans, const int *n, const int *kl, const int *ku, const int *nrhs, const double *ab,
             const int *ldab, const int *ipiv, double *b, const int *ldb, int *info, size_t trans_len);

/* LAPACK's band of the matrix in the plan's order: ab[(kl + ku + i - j) + j ldab]. */
static void fill_lapack(const bk_band *p, const int *Ap, const int *Ai, const double *Ax, double *ab, int ldab)
{
    int n = p->n;
    memset(ab, 0, (size_t)ldab * (size_t)n * sizeof *ab);
    for (int jo = 0; jo < n; jo++) {
        int j = p->iperm[jo];
        for (int k = Ap[jo]; k < Ap[jo + 1]; k++) {
            int i = p->iperm[Ai[k]];
            ab[(size_t)(p->kl + p->ku + i - j) + (size_t)j * (size_t)ldab] += Ax[k];
        }
    }
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: %s MATRIX_FILE REPEATS\n", argv[0]);
        return 1;
    }
    int reps = atoi(argv[2]) > 0 ? atoi(argv[2]) : 1;
    FILE *f = fopen(argv[1], "rb");
    int n;
    long long nnz;
    if (!f || fread(&n, sizeof n, 1, f) != 1 || fread(&nnz, sizeof nnz, 1, f) != 1 || n <= 0 || nnz <= 0) {
        fprintf(stderr, "bench_band: cannot read %s\n", argv[1]);
        return 1;
    }
    int *Ap = malloc(((size_t)n + 1) * sizeof *Ap), *Ai = malloc((size_t)nnz * sizeof *Ai);
    double *Ax = malloc((size_t)nnz * sizeof *Ax), *b = malloc((size_t)n * sizeof *b);
    if (!Ap || !Ai || !Ax || !b || fread(Ap, sizeof *Ap, (size_t)n + 1, f) != (size_t)n + 1 ||
        fread(Ai, sizeof *Ai, (size_t)nnz, f) != (size_t)nnz || fread(Ax, sizeof *Ax, (size_t)nnz, f) != (size_t)nnz ||
        fread(b, sizeof *b, (size_t)n, f) != (size_t)n) {
        fprintf(stderr, "bench_band: %s is short\n", argv[1]);
        return 1;
    }
    fclose(f);
    bk_band p;
    if (bk_band_plan(&p, n, Ap, Ai, BK_BAND_MAX_STORAGE) != 0) {
        fprintf(stderr, "bench_band: no band plan (the band is too wide)\n");
        return 1;
    }
    int kl = p.kl, ku = p.ku, ldab = 2 * kl + ku + 1, nrhs = 1, info = 0;
    double *ab = malloc((size_t)ldab * (size_t)n * sizeof *ab);
    double *x1 = malloc((size_t)n * sizeof *x1), *x2 = malloc((size_t)n * sizeof *x2), *y = malloc((size_t)n * sizeof *y);
    int *ipiv = malloc((size_t)n * sizeof *ipiv);
    double *t1 = malloc((size_t)reps * sizeof *t1), *t2 = malloc((size_t)reps * sizeof *t2);
    if (!ab || !x1 || !x2 || !y || !ipiv || !t1 || !t2)
        return 1;
    for (int r = 0; r < reps; r++) {           /* interleaved: a slow spell reaches both alike */
        memcpy(x1, b, (size_t)n * sizeof *b);
        double a = bench_now();
        int st = bk_band_factor_solve(&p, Ax, x1);
        double c = bench_now();
        for (int i = 0; i < n; i++)            /* LAPACK's right-hand side in the plan's order */
            y[i] = b[p.perm[i]];
        double d = bench_now();
        fill_lapack(&p, Ap, Ai, Ax, ab, ldab);
        dgbtrf_(&n, &n, &kl, &ku, ab, &ldab, ipiv, &info);
        if (info == 0)
            dgbtrs_("N", &n, &kl, &ku, &nrhs, ab, &ldab, ipiv, y, &n, &info, 1);
        double e = bench_now();
        if (st != 0 || info != 0) {
            fprintf(stderr, "bench_band: factorization failed (band %d, LAPACK info %d)\n", st, info);
            return 2;
        }
        t1[r] = c - a;
        t2[r] = e - d;
    }
    double dmax = 0, xmax = 0;
    for (int i = 0; i < n; i++) {
        x2[p.perm[i]] = y[i];
    }
    for (int i = 0; i < n; i++) {
        dmax = fmax(dmax, fabs(x1[i] - x2[i]));
        xmax = fmax(xmax, fabs(x1[i]));
    }
    printf("n=%d\nnnz=%lld\nkl=%d\nku=%d\nband_s=%.6e\nlapack_s=%.6e\nsolution_difference=%.3e\n", n, nnz, kl, ku,
           bench_median(t1, reps), bench_median(t2, reps), xmax > 0 ? dmax / xmax : dmax);
    bk_band_free(&p);
    free(Ap), free(Ai), free(Ax), free(b), free(ab), free(x1), free(x2), free(y), free(ipiv), free(t1), free(t2);
    return 0;
}
