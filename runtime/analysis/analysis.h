/* analysis.h -- the table of analyses: what main.c dispatches through.
 *
 * An analysis is a module (a file or two in analysis/) that reaches the
 * problem only through the assembly (assembly/), the nonlinear and linear
 * solvers (solver/, linalg/) and the output (output/): it supplies residuals,
 * Newton matrices and a step controller to the one Newton solver
 * (solver/nonlinear.h) and writes its results through output.h.  A module
 * defines its descriptor, `const bk_analysis_module bk_analysis_NAME = {...};`
 * at the start of a line of a file in runtime/analysis/: the build lists
 * every such descriptor in the table (gen/solver_build.py), so adding an
 * analysis is its module, its scene keys and options, its tests.
 */
#ifndef BK_ANALYSIS_H
#define BK_ANALYSIS_H

#include <stdio.h>

#include "assembly/system.h"
#include "output/output.h"

typedef struct bk_analysis_module {
    const char *name;                /* for messages: "static", "continuation", ... */
    /* 1 when this module runs the model's analysis (model.h: analysis and its
     * options, e.g. static.method). */
    int (*runs)(const bk_model *m);
    /* Solves in place from the reference configuration in q[ndof]; q holds the
     * last converged configuration on return, info the counters, warnings and
     * (on failure) the message.  Returns 0 when the analysis completed, 1
     * otherwise. */
    int (*run)(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log);
    /* (optional) What it will write, for the output opened before it runs
     * (output.h bk_output_plan: the end of its path, its frames, ...); NULL:
     * nothing known. */
    void (*plan)(const bk_model *m, bk_output_plan *p);
} bk_analysis_module;

/* The table of every module (generated; in the order of their files). */
extern const bk_analysis_module *const bk_analysis_table[];
extern const int bk_analysis_count;

/* The module that runs the model's analysis, or NULL (then none of the table
 * claims it: a model file of another solver). */
const bk_analysis_module *bk_analysis_for(const bk_model *m);

/* The plan of module an (may be NULL) for m into *p (zeroed first). */
void bk_analysis_plan(const bk_analysis_module *an, const bk_model *m, bk_output_plan *p);

#endif
