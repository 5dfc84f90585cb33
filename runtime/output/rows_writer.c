/* rows_writer.c -- which writer thread formats the run's table rows (see
 * output.h bk_output_rows_to_writer). */
#include "output/output.h"

/* The tables' rows are formatted by a writer thread (csvrow.h bk_rowqueue)
 * from the first output step that one runs: the frames' (vtk.h: a run with
 * enough frames), else results.h5's (h5.h: started for them once the run is
 * due one, if not by then for HDF5; a short run formats its few rows
 * itself), else, in a run without frames or results.h5, one of the output's
 * own once due (a dynamic run without frames formatted its rows on the solve
 * thread: its output took longer than with them).  A run is due a thread from
 * its BK_ROWS_THREAD_AFTER-th output step, or earlier when it is expected to
 * give that many, as the frames' thread is started (vtk.c maybe_background):
 * known from the start (the plan's states: dynamics), or the steps so far over
 * the fraction of the run done (t over the plan's end) from the second step
 * (a roll-up of 25 increments without frames formatted and mirrored its first
 * 8 steps' rows on the solve thread: its output took longer than with frames).
 * From then on the tables are that thread's until bk_output_close_tables. */
#define BK_ROWS_THREAD_AFTER 8
/* Once the thread has the rows, what an output step recorded is handed over
 * when it reaches BK_ROWS_OFFER bytes and the thread is done with the chunk
 * before (csvrow.h bk_rowqueue_offer): rows formatted as the run goes, not
 * 128 kB of them left for the close to wait for (0.5-1 ms in a 1000-step
 * pendulum), and fewer fresh pages of the chunks touched. */
#define BK_ROWS_OFFER (16 << 10)
static void start_rows(bk_output *o, double t, int steps);

void bk_output_rows_to_writer(bk_output *o, double t)
{
    if (o->rq.w) {
        bk_rowqueue_offer(&o->rq, BK_ROWS_OFFER);
        return;
    }
    start_rows(o, t, ++o->row_steps);    /* (counted once a call) */
}

void bk_output_rows_due(bk_output *o, double t)
{
    if (!o->rq.w)
        start_rows(o, t, o->row_steps + 1);
}

/* The rows to a thread when one runs or the run, at its steps-th output
 * step, is due one. */
static void start_rows(bk_output *o, double t, int steps)
{
    bk_filewriter *w = NULL;
    const double frac = o->plan.end > 0.0 ? t / o->plan.end : -1.0;
    const int due = steps >= BK_ROWS_THREAD_AFTER || o->plan.states >= BK_ROWS_THREAD_AFTER ||
                    (frac > 0.0 && steps >= 2 && steps >= BK_ROWS_THREAD_AFTER * frac);
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
