/* analysis.c -- the choice of the model's analysis from the table of analysis
 * modules (see analysis.h; the table is generated at build time from the
 * modules' descriptors in runtime/analysis/, gen/solver_build.py). */
#include "analysis/analysis.h"

#include <stddef.h>
#include <string.h>

const bk_analysis_module *bk_analysis_for(const bk_model *m)
{
    for (int k = 0; k < bk_analysis_count; ++k)
        if (bk_analysis_table[k]->runs(m))
            return bk_analysis_table[k];
    return NULL;
}

void bk_analysis_plan(const bk_analysis_module *an, const bk_model *m, bk_output_plan *p)
{
    memset(p, 0, sizeof *p);
    p->path = bk_analysis_path(m->analysis);   /* (the path kind the schema gives each analysis) */
    if (an && an->plan)
        an->plan(m, p);
}
