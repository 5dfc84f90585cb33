/* main.c -- the per-scene solver: solver MODEL_FILE OUT_DIR [--quiet] [--verbose]
 *
 * Exit status: 0 converged; 1 bad input (model file, output directory);
 * 2 the solve did not converge (results of every converged step are kept);
 * 130 / 143 interrupted by SIGINT / SIGTERM (results so far kept, summary.json
 * says "interrupted": true; see interrupt.h).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "buckling.h"
#include "clock.h"
#include "dynamics.h"
#include "interrupt.h"
#include "modal.h"
#include "model.h"
#include "newton.h"
#include "output.h"
#include "system.h"

/* Defined by the per-scene kernel table generated at build time. */
extern const bk_pair *const bk_linked_pairs[];
extern const int bk_nlinked_pairs;
/* Defined by the generated joint kernels (out/kernels/joints.c). */
extern const bk_joint_kind *const bk_joint_kinds[];
extern const int bk_njoint_kinds;


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
    bk_output out;
    if (bk_output_open(&out, m, out_dir, !quiet && !verbose, stderr) != 0) {
        bk_output_close(&out);
        bk_system_free(s);
        bk_model_free(m);
        return 1;
    }
    out.console = quiet ? NULL : stderr;
    double *q = malloc((size_t)m->ndof * sizeof *q);
    if (!q) {
        fprintf(stderr, "error: out of memory\n");
        bk_output_close(&out);
        bk_system_free(s);
        bk_model_free(m);
        return 1;
    }
    bk_run_info info = {0};
    int rc;
    if (m->analysis == BK_DYNAMIC)
        rc = bk_solve_dynamic(s, q, &out, &info, verbose ? stderr : NULL);
    else if (m->analysis == BK_MODAL)
        rc = bk_solve_modal(s, q, &out, &info, verbose ? stderr : NULL);
    else if (m->analysis == BK_BUCKLING)
        rc = bk_solve_buckling(s, q, &out, &info, verbose ? stderr : NULL);
    else
        rc = bk_solve_static(s, q, &out, &info, verbose ? stderr : NULL);
    bk_output_final(&out, info.steps, info.load_factor, q);
    info.strain_energy = bk_strain_energy(s, q);
    /* every table on disk before the summary, and inside wall_s and output_s
     * (a short run writes its tables only now) */
    double tc = bk_clock_s();
    if (bk_output_close_tables(&out, stderr) != 0)
        out.write_failed = 1;
    out.t_output += bk_clock_s() - tc;
    info.wall_s = bk_clock_s() - t0;
    info.output_s = out.t_output;
    int wrc = bk_output_summary(&out, &info, q, stderr);   /* before the close: it reports the reactions */
    if (out.write_failed)
        wrc = -1;
    bk_output_close(&out);
    if (rc != 0)
        fprintf(stderr, "%s: %s: %s\n", info.interrupted ? "interrupted" : "error", m->name, info.message);
    free(q);
    bk_system_free(s);
    bk_model_free(m);
    if (info.interrupted)
        return 128 + info.interrupted;
    if (rc != 0)
        return 2;
    return wrc == 0 ? 0 : 1;
}
