/* kernels.c -- kernel benchmark driver (./build.sh bench, report/bench_kernels.py).
 *
 * usage: bench_kernels SPEC
 * SPEC (written by report/bench_kernels.py), whitespace separated:
 *   geom l b h A I1 I2 Ip
 *   timing REPEATS TARGET_SECONDS     (TARGET_SECONDS <= 0: no timing, comparison only)
 *   then per pair:  pair NAME NMAT m_1 .. m_NMAT LAW NPTS NSHAPE  [NPTS x (1 + 3 NSHAPE) numbers]
 *   (LAW "-" and NPTS 0: no plain loop for this pair)
 * Prints CSV: per pair the shortest time (of REPEATS timed loops) of one internal-force call and of one
 * force + tangent call of the generated kernel (one element per call), of its
 * lane kernels per element (BK_LANES elements per call, what the solvers use;
 * NaN when the pair has none) and of the plain quadrature loop
 * (bench/plain.c), the largest difference between the generated kernel and the
 * plain loop and between the lane kernel and the one-element kernel.
 * Times are the thread's CPU time (CLOCK_THREAD_CPUTIME_ID): on a shared
 * machine a time slice given to another process does not count.  The
 * shortest loop, not the median: what remains of other load (a process on
 * the core's other hardware thread sharing its floating-point units, caches)
 * only ever slows a loop down, and it comes and goes between the repeats.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bk_kernel.h"
#include "plain.h"

extern const bk_pair *const bk_linked_pairs[];
extern const int bk_nlinked_pairs;

typedef struct job {
    const bk_pair *p;
    const plain_rule *rule;
    int law;
    const double *q, *tab, *mat;
    double *f, *K;
    int tangent, plain, lanes;
} job;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static void call(const job *j)
{
    if (j->plain)
        plain_force_tangent(j->rule, j->law, j->mat, j->q, j->f, j->tangent ? j->K : NULL);
    else if (j->lanes && j->tangent)
        j->p->force_tangent_lanes(j->q, j->tab, j->mat, j->f, j->K);
    else if (j->lanes)
        j->p->force_lanes(j->q, j->tab, j->mat, j->f);
    else if (j->tangent)
        j->p->force_tangent(j->q, j->tab, j->mat, j->f, j->K);
    else
        j->p->force(j->q, j->tab, j->mat, j->f);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The shortest over repeats of the time of one call, each repeat long enough
 * to be timed reliably. */
static double time_call(const job *j, int repeats, double target)
{
    long n = 1;
    for (;;) {
        double t0 = now();
        for (long i = 0; i < n; ++i)
            call(j);
        double t = now() - t0;
        if (t >= target || n > (1L << 30))
            break;
        n = t > 0 ? (long)(n * fmin(100.0, 1.3 * target / t)) + 1 : n * 10;
    }
    double *ts = malloc((size_t)repeats * sizeof *ts);
    if (!ts)
        return NAN;
    for (int r = 0; r < repeats; ++r) {
        double t0 = now();
        for (long i = 0; i < n; ++i)
            call(j);
        ts[r] = (now() - t0) / n;
    }
    qsort(ts, (size_t)repeats, sizeof *ts, cmp_double);
    double best = ts[0];
    free(ts);
    return best;
}

static const bk_pair *find_pair(const char *name)
{
    char buf[256];
    for (int i = 0; i < bk_nlinked_pairs; ++i) {
        const bk_pair *p = bk_linked_pairs[i];
        snprintf(buf, sizeof buf, "%s_%s_%s", p->element->name, p->material, p->integration);
        if (strcmp(buf, name) == 0)
            return p;
    }
    return NULL;
}

static double maxabs(const double *a, size_t n)
{
    double m = 0.0;
    for (size_t i = 0; i < n; ++i)
        m = fmax(m, fabs(a[i]));
    return m;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s SPEC\n", argv[0]);
        return 1;
    }
    FILE *in = fopen(argv[1], "r");
    if (!in) {
        perror(argv[1]);
        return 1;
    }
    double geom[BK_NGEOM], target;
    int repeats;
    char word[256];
    if (fscanf(in, "%255s", word) != 1 || strcmp(word, "geom") != 0)
        return 1;
    for (int i = 0; i < BK_NGEOM; ++i)
        if (fscanf(in, "%lf", &geom[i]) != 1)
            return 1;
    if (fscanf(in, "%255s %d %lf", word, &repeats, &target) != 3 || repeats < 1)
        return 1;
    printf("pair,ndof,nqp,ops_force,ops_force_tangent,t_force_s,t_force_tangent_s,"
           "t_lanes_force_s,t_lanes_force_tangent_s,"
           "t_plain_force_s,t_plain_force_tangent_s,plain_rel_diff_f,plain_rel_diff_K,lanes_rel_diff\n");
    char name[256], law[64];
    while (fscanf(in, "%255s", word) == 1) {
        int nmat, npts, nshape;
        double mat[16];
        if (strcmp(word, "pair") != 0 || fscanf(in, "%255s %d", name, &nmat) != 2 || nmat > 16)
            return 1;
        for (int i = 0; i < nmat; ++i)
            if (fscanf(in, "%lf", &mat[i]) != 1)
                return 1;
        if (fscanf(in, "%63s %d %d", law, &npts, &nshape) != 3)
            return 1;
        size_t npt_vals = (size_t)npts * (1 + 3 * (size_t)nshape);
        double *pts = malloc((npt_vals ? npt_vals : 1) * sizeof *pts);
        if (!pts)
            return 1;
        for (size_t i = 0; i < npt_vals; ++i)
            if (fscanf(in, "%lf", &pts[i]) != 1)
                return 1;
        const bk_pair *p = find_pair(name);
        if (!p) {
            fprintf(stderr, "bench_kernels: pair %s is not linked\n", name);
            return 1;
        }
        int nd = p->element->ndof;
        double *q = calloc((size_t)nd, sizeof *q), *tab = calloc((size_t)p->ntab + 1, sizeof *tab);
        double *f = calloc((size_t)nd, sizeof *f), *K = calloc((size_t)nd * nd, sizeof *K);
        double *f2 = calloc((size_t)nd, sizeof *f2), *K2 = calloc((size_t)nd * nd, sizeof *K2);
        if (!q || !tab || !f || !K || !f2 || !K2)
            return 1;
        p->element->reference(geom, q);
        p->tabulate(geom, q, tab);
        /* a deformed state: 1 % of the element length on positions, 1 % on slopes */
        for (int k = 0; k < nd; ++k)
            q[k] += 0.01 * sin(1.7 * k + 0.3) * (k % 3 == 0 ? 1.0 : 0.7) * (fabs(q[k]) > 0.05 ? 1.0 : geom[0] / 0.1);
        /* TARGET_SECONDS <= 0: no timing, only the comparison (tests) */
        int timed = target > 0.0;
        job j = {p, NULL, -1, q, tab, mat, f, K, 0, 0, 0};
        double tf = timed ? time_call(&j, repeats, target) : NAN;
        j.tangent = 1;
        double tft = timed ? time_call(&j, repeats, target) : NAN;
        /* lane kernels: BK_LANES differently deformed copies, lane-ordered */
        double tlf = NAN, tlft = NAN, dl = NAN;
        if (p->force_lanes && p->force_tangent_lanes) {
            const int W = BK_LANES, np = p->nparam;
            /* 64-byte aligned, as the runtime's buffers (runtime/assembly/system.c: alloc_lanes) */
            double *lq = aligned_alloc(64, (size_t)nd * W * sizeof *lq);
            double *ltab = aligned_alloc(64, ((size_t)p->ntab + 1) * W * sizeof *ltab);
            double *lmat = aligned_alloc(64, (size_t)(np + 1) * W * sizeof *lmat);
            double *lf = aligned_alloc(64, (size_t)nd * W * sizeof *lf);
            double *lK = aligned_alloc(64, (size_t)nd * nd * W * sizeof *lK);
            if (!lq || !ltab || !lmat || !lf || !lK)
                return 1;
            for (int l = 0; l < W; ++l) {
                for (int k = 0; k < nd; ++k)
                    lq[k * W + l] = q[k] * (1.0 + 1e-3 * l * cos(0.9 * k + l));
                for (int k = 0; k < p->ntab; ++k)
                    ltab[k * W + l] = tab[k];
                for (int k = 0; k < np; ++k)
                    lmat[k * W + l] = mat[k];
            }
            job lj = {p, NULL, -1, lq, ltab, lmat, lf, lK, 0, 0, 1};
            tlf = timed ? time_call(&lj, repeats, target) / W : NAN;
            lj.tangent = 1;
            tlft = timed ? time_call(&lj, repeats, target) / W : NAN;
            /* every lane against the one-element kernel */
            p->force_tangent_lanes(lq, ltab, lmat, lf, lK);
            double num = 0.0, den = 0.0;
            for (int l = 0; l < W; ++l) {
                for (int k = 0; k < nd; ++k)
                    f2[k] = lq[k * W + l];
                p->force_tangent(f2, tab, mat, f, K);
                for (int k = 0; k < nd * nd; ++k) {
                    num = fmax(num, fabs(lK[k * W + l] - K[k]));
                    den = fmax(den, fabs(K[k]));
                }
            }
            dl = num / den;
            free(lq), free(ltab), free(lmat), free(lf), free(lK);
        }
        double tpf = NAN, tpft = NAN, df = NAN, dK = NAN;
        plain_rule rule = {npts, nshape, pts};
        int lw = plain_law(law);
        if (npts > 0 && lw >= 0 && 3 * nshape == nd) {
            job pj = {p, &rule, lw, q, tab, mat, f2, K2, 0, 1, 0};
            tpf = timed ? time_call(&pj, repeats, target) : NAN;
            pj.tangent = 1;
            tpft = timed ? time_call(&pj, repeats, target) : NAN;
            p->force_tangent(q, tab, mat, f, K);
            plain_force_tangent(&rule, lw, mat, q, f2, K2);
            for (int k = 0; k < nd; ++k)
                f2[k] -= f[k];
            for (int k = 0; k < nd * nd; ++k)
                K2[k] -= K[k];
            df = maxabs(f2, (size_t)nd) / maxabs(f, (size_t)nd);
            dK = maxabs(K2, (size_t)nd * nd) / maxabs(K, (size_t)nd * nd);
        }
        printf("%s,%d,%d,%ld,%ld,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.3e,%.3e,%.3e\n", name, nd, p->nqp, p->ops_force,
               p->ops_force_tangent, tf, tft, tlf, tlft, tpf, tpft, df, dK, dl);
        fflush(stdout);
        free(q), free(tab), free(f), free(K), free(f2), free(K2), free(pts);
    }
    fclose(in);
    return 0;
}
