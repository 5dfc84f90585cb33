/* main.c -- the per-scene solver: solver MODEL_FILE OUT_DIR [--quiet] [--verbose]
 *
 * Exit status: 0 converged; 1 bad input (model file, output directory);
 * 2 the solve did not converge (results of every converged step are kept);
 * 130 / 143 interrupted by SIGINT / SIGTERM (results so far kept, summary.json
 * says "interrupted": true; see interrupt.h).
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/bigalloc.h"
#include "base/clock.h"
#include "analysis/analysis.h"
#include "base/interrupt.h"
#include "model/model.h"
#include "output/output.h"
#include "assembly/system.h"

/* Defined by the per-scene kernel table generated at build time. */
extern const bk_pair *const bk_linked_pairs[];
extern const int bk_nlinked_pairs;
/* Defined by the generated joint kernels (out/kernels/joints.c). */
extern const bk_joint_kind *const bk_joint_kinds[];
extern const int bk_njoint_kinds;


/* The results directory: made when missing (its parent must exist), refused
 * when it is something else; checked before the model is read, so that a run
 * of a large model does not set up for seconds and then fail to write. */
static int results_dir(const char *dir, FILE *err)
{
    struct stat st;
    if (stat(dir, &st) == 0) {
        if (S_ISDIR(st.st_mode))
            return 0;
        fprintf(err, "error: %s: the results directory is not a directory\n", dir);
        return -1;
    }
    if (errno == ENOENT && mkdir(dir, 0777) == 0)
        return 0;
    fprintf(err, "error: %s: cannot make the results directory: %s\n", dir, strerror(errno));
    return -1;
}

static int run(const char *model_path, const char *out_dir, int verbose, int quiet);

int main(int argc, char **argv)
{
    const char *model_path = NULL, *out_dir = NULL;
    int verbose = 0, quiet = 0;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--verbose") == 0)
            verbose = 1;
        else if (strcmp(argv[i], "--quiet") == 0)
            quiet = 1;
        else if (!model_path)
            model_path = argv[i];
        else if (!out_dir)
            out_dir = argv[i];
        else {
            fprintf(stderr, "error: unexpected argument '%s'\n", argv[i]);
            return 1;
        }
    }
    if (!model_path || !out_dir) {
        fprintf(stderr, "usage: %s MODEL_FILE OUT_DIR [--verbose | --quiet]\n", argv[0]);
        return 1;
    }
    if (results_dir(out_dir, stderr) != 0)
        return 1;
    void *heap_head = bk_big_heap();             /* (before the first large allocation) */
    const int rc = run(model_path, out_dir, verbose, quiet);
    free(heap_head);
    return rc;
}

/* The run: model read to results written; the exit status. */
static int run(const char *model_path, const char *out_dir, int verbose, int quiet)
{
    double t0 = bk_clock_s();
    if (bk_interrupt_block() != 0) {
        fprintf(stderr, "error: cannot block SIGINT/SIGTERM for a clean interruption\n");
        return 1;
    }
    bk_model *m = bk_model_read(model_path, bk_linked_pairs, bk_nlinked_pairs, stderr);
    if (!m)
        return 1;
    if (bk_model_bind_joints(m, bk_joint_kinds, bk_njoint_kinds, stderr) != 0) {
        bk_model_free(m);
        return 1;
    }
    if (!quiet && m->nelem > 100000)
        fprintf(stderr, "setting up %d elements, %d DOFs (sparse pattern, KLU analysis)...\n", m->nelem, m->ndof);
    bk_system *s = bk_system_create(m, stderr);
    if (!s) {
        bk_model_free(m);
        return 1;
    }
    const bk_analysis_module *an = bk_analysis_for(m);
    bk_output_plan plan;
    bk_analysis_plan(an, m, &plan);              /* what it will write, told to the output */
    /* on the heap, not this stack: its 29 kB would be fresh stack pages (a
     * fault each; 10 us apiece on a virtual machine with shadow page tables,
     * a tenth of a small run's output), the heap's are touched already */
    bk_output *out = malloc(sizeof *out);
    if (!out) {
        fprintf(stderr, "error: out of memory\n");
        bk_system_free(s);
        bk_model_free(m);
        return 1;
    }
    if (bk_output_open(out, m, &plan, out_dir, !quiet && !verbose, stderr) != 0) {
        bk_output_close(out);
        free(out);
        bk_system_free(s);
        bk_model_free(m);
        return 1;
    }
    out->console = quiet ? NULL : stderr;
    double *q = malloc((size_t)m->ndof * sizeof *q);
    if (!q) {
        fprintf(stderr, "error: out of memory\n");
        bk_output_close(out);
        free(out);
        bk_system_free(s);
        bk_model_free(m);
        return 1;
    }
    bk_run_info info = {0};
    int rc = 1;
    if (an)
        rc = an->run(s, q, out, &info, verbose ? stderr : NULL);
    else
        snprintf(info.message, sizeof info.message, "no analysis module of this solver runs the model's analysis");
    bk_output_final(out, info.steps, info.load_factor, q);
    info.strain_energy = bk_strain_energy(s, q);
    char nthr[16];
    snprintf(nthr, sizeof nthr, "%d", s->npart > 1 ? s->nthreads : 1);
    bk_run_summary(&info, "threads", nthr);      /* of the element evaluation (1: serial) */
    for (int k = 0; k < s->ninter; ++k) {        /* the interactions' own summary entries */
        const bk_interaction *it = &s->inter[k];
        char text[8192];
        if (it->ops->summary && it->ops->summary(it->self, s, q, text, sizeof text) == 0)
            bk_run_summary(&info, it->ops->summary_key, text);
    }
    /* every table on disk before the summary, and inside wall_s and output_s
     * (a short run writes its tables only now) */
    double tc = bk_clock_s();
    if (bk_output_close_tables(out, stderr) != 0)
        out->write_failed = 1;
    out->t_output += bk_clock_s() - tc;
    info.wall_s = bk_clock_s() - t0;
    info.output_s = out->t_output;
    int wrc = bk_output_summary(out, &info, q, stderr);   /* before the close: it reports the reactions */
    if (out->write_failed)
        wrc = -1;
    bk_output_close(out);
    free(out);
    if (rc != 0)
        fprintf(stderr, "%s: %s: %s\n", info.interrupted ? "interrupted" : "error", m->name, info.message);
    bk_run_info_free(&info);
    free(q);
    bk_system_free(s);
    bk_model_free(m);
    if (info.interrupted)
        return 128 + info.interrupted;
    if (rc != 0)
        return 2;
    return wrc == 0 ? 0 : 1;
}
