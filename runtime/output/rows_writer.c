/* rows_writer.c -- which writer thread formats the run's table rows (see
 * output.h bk_output_rows_to_writer). */
#include "output/output.h"

/* The tables' rows are formatted by a writer thread (csvrow.h bk_rowqueue)
 * from the first output step that one runs: the frames' (vtk.h: a run with
 * enough frames), else results.h5's (h5.h: started for them from the
 * BK_ROWS_THREAD_AFTER-th output step on, if not by then for HDF5; a short
 * run formats its few rows itself), else, in a run without frames,
 * one of the output's own from its BK_ROWS_THREAD_AFTER-th output step on (a
 * dynamic run without frames formatted its rows on the solve thread: its
 * output took longer than with them).  From then on the tables are that
 * thread's until bk_output_close_tables. */
#define BK_ROWS_THREAD_AFTER 8
void bk_output_rows_to_writer(bk_output *o)
{
    if (o->rq.w)
        return;
    bk_filewriter *w = NULL;
    const int due = ++o->row_steps >= BK_ROWS_THREAD_AFTER;   /* (counted once a call: counted in both
                                                               * tests below, the output's own thread
                                                               * was due a step before results.h5's) */
    if (o->vtk.background && o->vtk.wp->threaded)
        w = o->vtk.wp;
    else if (o->h5.open && (o->h5.fw.threaded || due) && bk_filewriter_start(&o->h5.fw))
        w = &o->h5.fw;
    else if (o->vtk.every <= 0 && !o->own_tried && due) {
        o->own_tried = 1;
        if (bk_filewriter_open(&o->fw, 1, 1) == 0 && o->fw.threaded) {
            o->own_fw = 1;
            w = &o->fw;
        } else
            bk_filewriter_close(&o->fw);
    }
    if (!w)
        return;
    /* the tables written with bk_row (the mode tables are not) */
    FILE *list[BK_ROWQ_TABLES];
    int n = bk_tables_rows(&o->tables, list, BK_ROWQ_TABLES);
    /* what a step records: mostly sections.csv's rows (a number 10 bytes) */
    const size_t rows = (size_t)o->m->nsection * (2 + (size_t)o->forces.maxsample) + (size_t)o->m->nsensor;
    bk_rowqueue_start(&o->rq, w, list, n, o->forces.sections ? 20 * 10 * rows : 0);
}
