/* analysis.c -- the table of analyses (see analysis.h). */
#include "analysis/analysis.h"

#include <stddef.h>

#include "analysis/buckling.h"
#include "analysis/dynamics.h"
#include "analysis/modal.h"
#include "analysis/static.h"

static int runs_static(const bk_model *m)
{
    return m->analysis == BK_ANALYSIS_STATIC && m->stat.method == BK_METHOD_LOAD_CONTROL;
}
static int runs_continuation(const bk_model *m)
{
    return m->analysis == BK_ANALYSIS_STATIC && m->stat.method == BK_METHOD_ARC_LENGTH;
}
static int runs_dynamic(const bk_model *m) { return m->analysis == BK_ANALYSIS_DYNAMIC; }
static int runs_modal(const bk_model *m) { return m->analysis == BK_ANALYSIS_MODAL; }
static int runs_buckling(const bk_model *m) { return m->analysis == BK_ANALYSIS_BUCKLING; }

static const bk_analysis_module table[] = {
    {"static", runs_static, bk_run_static},
    {"continuation", runs_continuation, bk_solve_continuation},
    {"dynamic", runs_dynamic, bk_solve_dynamic},
    {"modal", runs_modal, bk_solve_modal},
    {"buckling", runs_buckling, bk_solve_buckling},
};

const bk_analysis_module *bk_analysis_for(const bk_model *m)
{
    for (size_t k = 0; k < sizeof table / sizeof table[0]; ++k)
        if (table[k].runs(m))
            return &table[k];
    return NULL;
}
