/* newton_iter.c -- cost of one Newton iteration of a model (./build.sh bench,
 * scaling section).
 *
 * usage: bench_newton MODEL_FILE ITERATIONS [MATRIX_FILE]
 * Reads the model as the solver does, builds the system and the linear
 * solver's analysis, then times ITERATIONS Newton iterations at a perturbed
 * configuration: internal forces and tangent (bk_assemble_internal),
 * constraint rows, then the numeric factorization with the solve
 * (bk_lin_factor_solve, as the nonlinear solver does with a new matrix; the
 * band solver does the forward substitution during the elimination):
 * iteration_s = assembly_s + factor_s.  assembly_s includes the model's
 * interactions (loads, contact: their state accepted once at the start
 * configuration, as after a converged step), timed alone as interactions_s.  solve_s is one more solve with the
 * kept factors (an iteration that reuses them).  Prints key=value lines: the
 * medians of each part, the setup time, the peak resident memory (VmHWM) and the
 * counts of KLU analyses, numeric factorizations and full (pivoting,
 * allocating) factorizations.
 * The rest of a Newton iteration of the solver is timed apart: the
 * interactions' prepare before it (prepare_s; beam contact's check whether a
 * point moved enough for its broad phase) and their step limiter of the
 * correction (limit_s); and, in a model with contact, each broad phase alone
 * (contact_broad_s: rigid primitives', also part of interactions_s;
 * beam_broad_s: beam contact's, run again at the same state as a rebuild
 * does).  Every *_s key has a *_cpu_s twin from the thread's CPU clock (the
 * bench runs one thread; on a loaded machine CPU time is the steadier).
 * MATRIX_FILE: the first iteration's Newton matrix and right-hand side are
 * also written there, for bench/band_lapack.c: int32 n, int64 nnz, then
 * Ap[n+1], Ai[nnz] (int32), Ax[nnz], b[n] (double), native byte order.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "median_clock.h"
#include "linalg/linsolve.h"
#include "model/model.h"
#include "assembly/beam_contact.h"
#include "assembly/contact_force.h"
#include "assembly/interaction.h"
#include "assembly/system.h"

extern const bk_pair *const bk_linked_pairs[];
extern const int bk_nlinked_pairs;

/* Seconds of this thread's CPU clock. */
static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* The timed parts of an iteration: wall and CPU seconds of each. */
enum { T_ITER, T_ASM, T_FACT, T_SOLVE, T_INTER, T_PREP, T_LIMIT, T_BROAD, T_BBROAD, NT };
static const char *const tname[NT] = {"iteration", "assembly", "factor", "solve", "interactions", "prepare",
                                      "limit", "contact_broad", "beam_broad"};

static int dump_matrix(const char *path, const bk_system *s, const double *Ax, const double *b)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    int n = s->neq;
    long long nnz = s->nnz;
    int ok = fwrite(&n, sizeof n, 1, f) == 1 && fwrite(&nnz, sizeof nnz, 1, f) == 1 &&
             fwrite(s->Ap, sizeof *s->Ap, (size_t)n + 1, f) == (size_t)n + 1 &&
             fwrite(s->Ai, sizeof *s->Ai, (size_t)nnz, f) == (size_t)nnz &&
             fwrite(Ax, sizeof *Ax, (size_t)nnz, f) == (size_t)nnz && fwrite(b, sizeof *b, (size_t)n, f) == (size_t)n;
    return fclose(f) == 0 && ok ? 0 : -1;
}

int main(int argc, char **argv)
{
    if (argc != 3 && argc != 4) {
        fprintf(stderr, "usage: %s MODEL_FILE ITERATIONS [MATRIX_FILE]\n", argv[0]);
        return 1;
    }
    int nit = atoi(argv[2]);
    if (nit < 1)
        nit = 1;
    double t0 = bench_now();
    bk_model *m = bk_model_read(argv[1], bk_linked_pairs, bk_nlinked_pairs, stderr);
    if (!m)
        return 1;
    bk_system *s = bk_system_create(m, stderr);
    if (!s)
        return 1;
    bk_linsolver ls;
    if (bk_lin_init(&ls, s->neq, s->Ap, s->Ai) != BK_LIN_OK) {
        fprintf(stderr, "bench_newton: KLU analysis failed\n");
        return 1;
    }
    double t_setup = bench_now() - t0;
    int nd = m->ndof, ne = s->neq;
    double *q = malloc((size_t)nd * sizeof *q), *fint = malloc((size_t)nd * sizeof *fint);
    double *r = calloc((size_t)ne, sizeof *r), *r2 = calloc((size_t)ne, sizeof *r2), *nu = calloc((size_t)(s->ncon + 1), sizeof *nu);
    double *Ax = malloc((size_t)(s->nnz ? s->nnz : 1) * sizeof *Ax);
    double *tw = calloc((size_t)nit * NT, sizeof *tw), *tc = calloc((size_t)nit * NT, sizeof *tc);
    if (!q || !fint || !r || !r2 || !nu || !Ax || !tw || !tc)
        return 1;
    /* a smooth deformed state: small transverse sag growing along the model */
    for (int i = 0; i < nd; ++i)
        q[i] = m->q0[i] + (s->eq[i] >= 0 ? 1e-4 * sin(0.37 * i) : 0.0);
    const bk_path path = {.factor = 1.0, .x = 1.0};
    bk_interactions_accept(s, q, &path);           /* the lagged contact state of a converged step */
    int have_broad = bk_contact_broad_phase(s, q, &path) >= 0, have_bbroad = 0;
    for (int k = 0; k < s->ninter; ++k)
        have_bbroad |= s->inter[k].ops == &bk_beam_contact_ops;
    for (int it = 0; it < nit; ++it) {
        double *w = tw + (size_t)NT * it, *c = tc + (size_t)NT * it, w0, c0;
#define TIC (w0 = bench_now(), c0 = cpu_now())
#define TOC(k) (w[k] += bench_now() - w0, c[k] += cpu_now() - c0)
        TIC;
        int bad = bk_interactions_prepare(s, q) != 0;
        TOC(T_PREP);
        TIC;
        bad |= bk_assemble_internal(s, q, fint, Ax);
        TOC(T_ASM);
        TIC;
        bad |= bk_assemble_interactions(s, q, &path, fint, Ax) != 0;
        TOC(T_INTER);
        w[T_ASM] += w[T_INTER], c[T_ASM] += c[T_INTER];
        TIC;
        for (int i = 0; i < nd; ++i)
            if (s->eq[i] >= 0)
                r[s->eq[i]] = fint[i];
        bk_assemble_constraints(s, q, nu, 0.0, r, Ax);
        for (int i = 0; i < ne; ++i)
            r[i] = -r[i];
        memcpy(r2, r, (size_t)ne * sizeof *r);
        TOC(T_ASM);
        if (it == 0 && argc == 4 && dump_matrix(argv[3], s, Ax, r) != 0) {
            fprintf(stderr, "bench_newton: cannot write %s\n", argv[3]);
            return 1;
        }
        TIC;
        int st = bk_lin_factor_solve(&ls, Ax, r);   /* what a Newton iteration with a new matrix does */
        TOC(T_FACT);
        if (bad || st != BK_LIN_OK) {
            fprintf(stderr, "bench_newton: assembly (%d) or factorization (%d) failed\n", bad, st);
            return 2;
        }
        TIC;
        bk_lin_solve(&ls, r2);                      /* an iteration that keeps the factors */
        TOC(T_SOLVE);
        TIC;
        (void)bk_interactions_step_limit(s, q, r);  /* the limiter of the correction */
        TOC(T_LIMIT);
        if (have_broad) {
            TIC;
            bk_contact_broad_phase(s, q, &path);
            TOC(T_BROAD);
        }
        if (have_bbroad) {
            TIC;
            bk_beam_contact_broad_phase(s, q);
            TOC(T_BBROAD);
        }
#undef TIC
#undef TOC
        w[T_ITER] = w[T_ASM] + w[T_FACT], c[T_ITER] = c[T_ASM] + c[T_FACT];
    }
    /* Peak resident memory of this process image: VmHWM (getrusage's maxrss
     * would include the parent's peak before exec). */
    long hwm = -1;
    FILE *st = fopen("/proc/self/status", "r");
    if (st) {
        char line[256];
        while (fgets(line, sizeof line, st))
            if (sscanf(line, "VmHWM: %ld", &hwm) == 1)
                break;
        fclose(st);
    }
    if (hwm < 0) {
        struct rusage ru;
        getrusage(RUSAGE_SELF, &ru);
        hwm = ru.ru_maxrss;
    }
    printf("elements=%d\ndofs=%d\nequations=%d\nnnz=%ld\nthreads=%d\n", m->nelem, nd, ne, s->nnz, s->nthreads);
    printf("setup_s=%.6e\n", t_setup);
    double *col = malloc((size_t)nit * sizeof *col);
    if (!col)
        return 1;
    for (int k = 0; k < NT; ++k)
        for (int clock = 0; clock < 2; ++clock) {
            for (int it = 0; it < nit; ++it)
                col[it] = (clock ? tc : tw)[(size_t)NT * it + k];
            printf("%s%s_s=%.6e\n", tname[k], clock ? "_cpu" : "", bench_median(col, nit));
        }
    free(col);
    printf("analyses=%d\nfactorizations=%d\nfull_factorizations=%d\nmaxrss_kb=%ld\n", ls.nanalyze, ls.nfactor,
           ls.nfull, hwm);
    bk_lin_free(&ls);
    free(q), free(fint), free(r), free(r2), free(nu), free(Ax), free(tw), free(tc);
    bk_system_free(s);
    bk_model_free(m);
    return 0;
}
