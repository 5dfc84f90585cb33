/* h5.c -- results.h5 (see h5.h): the rows kept on the solve thread and handed
 * to the HDF5 thread (h5_file.c). */
#include "output/h5_impl.h"
#include "base/bigalloc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "model/model.h"

/* ---- the tables' mirror (csvrow.h bk_rowsink) ---- */

static size_t cell_size(int type)
{
    return type == 3 ? BK_H5_STR : 8;
}

/* The most rows a table's buffer holds before they are handed over (or, the
 * thread's, written): BK_H5_ROWS or BK_H5_TABLE_BYTES, whichever holds more.
 * Before the first row's types are known a row takes the most room a row can
 * (every cell a string). */
static size_t row_room(const bk_h5_table *t)
{
    return t->rowbytes ? t->rowbytes : (size_t)t->ncol * BK_H5_STR;
}

static long most_rows(const bk_h5_table *t)
{
    return (long)fmax((double)BK_H5_ROWS, (double)BK_H5_TABLE_BYTES / (double)row_room(t));
}

/* *buf of *cap rows grown (doubled, to `most` at the most once below it);
 * 0, or -1 out of memory. */
static int grow(const bk_h5_table *t, unsigned char **buf, long *cap, long most)
{
    long c = *cap ? 2 * *cap : 64;
    if (c > most && *cap < most)
        c = most;
    unsigned char *b = bk_big_realloc(*buf, (size_t)c * row_room(t));
    if (!b)
        return -1;
    *buf = b;
    *cap = c;
    return 0;
}

/* Room for one more row of t in the set being filled: full at most_rows, the
 * set is handed over. */
static int table_room(bk_h5 *h, bk_h5_table *t)
{
    if (t->nbuf[h->cur] < t->cap[h->cur])
        return 0;
    const long most = most_rows(t);
    if (t->cap[h->cur] >= most) {
        bk_h5_flush(h);
        if (t->nbuf[h->cur] < t->cap[h->cur])
            return 0;
    }
    long cap = t->cap[h->cur];
    if (grow(t, &t->buf[h->cur], &cap, most) != 0) {
        h->oom = 1;
        return -1;
    }
    t->cap[h->cur] = (int)cap;
    return 0;
}

/* Waits until the thread has done everything handed over. */
static void settle_thread(bk_h5 *h)
{
    for (int k = 0; k < 2; ++k)
        if (h->ticket[k] > 0) {
            bk_filewriter_wait(&h->fw, h->ticket[k]);
            h->ticket[k] = 0;
        }
}

/* A table seen for the first time: its name and columns from the registry
 * (the thread is idle meanwhile: it reads the list of tables). */
static bk_h5_table *new_table(bk_h5 *h, FILE *fp)
{
    settle_thread(h);
    if (h->ntab == h->captab) {
        int cap = h->captab ? 2 * h->captab : 8;
        bk_h5_table **nt = realloc(h->tab, (size_t)cap * sizeof *nt);
        if (!nt) {
            h->oom = 1;
            return NULL;
        }
        h->tab = nt;
        h->captab = cap;
    }
    bk_h5_table *t = calloc(1, sizeof *t);
    if (!t) {
        h->oom = 1;
        return NULL;
    }
    h->tab[h->ntab++] = t;
    t->h = h;
    t->fp = fp;
    const bk_table *rt = bk_tables_of(h->tables, fp);
    if (!rt || !rt->header)
        return t;                         /* (ncol 0: never mirrored) */
    snprintf(t->name, sizeof t->name, "%s", rt->name);
    char *dot = strstr(t->name, ".csv");
    if (dot)
        *dot = 0;
    int ncol = 1;
    for (const char *p = rt->header; *p && *p != '\n'; ++p)
        ncol += *p == ',';
    t->col = calloc((size_t)ncol, sizeof *t->col);
    if (!t->col) {
        h->oom = 1;
        return t;
    }
    const char *p = rt->header;
    for (int c = 0; c < ncol; ++c) {
        size_t len = strcspn(p, ",\n");
        snprintf(t->col[c].name, sizeof t->col[c].name, "%.*s", (int)(len < 63 ? len : 63), p);
        p += len + (p[len] == ',');
    }
    t->ncol = ncol;
    return t;
}

static bk_h5_table *table_of(bk_h5 *h, FILE *fp)
{
    for (int k = 0; k < h->ntab; ++k)
        if (h->tab[k]->fp == fp)
            return h->tab[k];
    return new_table(h, fp);
}

/* A row of t begins in the thread's rows (write: their most written when
 * full, which the thread alone may: h5_file.c). */
static bk_h5_cursor *thread_row(bk_h5_table *t, int write)
{
    if (t->ntb == t->tcap) {
        const long most = most_rows(t);
        if (write && t->tcap >= most)
            bk_h5_write_thread_rows(t->h, t);
        else if (grow(t, &t->tbuf, &t->tcap, most) != 0) {
            t->toom = 1;
            return NULL;
        }
    }
    t->ct = (bk_h5_cursor){t, 0, -1, t->tbuf + (size_t)t->ntb * t->stride};   /* (stride 0 before the first row) */
    return &t->ct;
}

static void *sink_begin(void *ctx, FILE *fp)
{
    bk_h5 *h = ctx;
    if (!h->open)
        return NULL;
    bk_h5_table *t = table_of(h, fp);
    if (!t || t->ncol == 0)
        return NULL;
    if (t->threaded) {                    /* (a row after the queue's end: the thread is idle once settled) */
        settle_thread(h);
        return thread_row(t, 0);
    }
    if (table_room(h, t) != 0)
        return NULL;
    t->cs = (bk_h5_cursor){t, 0, h->cur, t->buf[h->cur] + (size_t)t->nbuf[h->cur] * t->stride};
    return &t->cs;
}

/* fp's table mirrored by results.h5's thread from now on, when w is that
 * thread (the rows of the set being filled become the first of its own):
 * called at the queue's start, before the thread has any of its rows. */
static void *sink_table(void *ctx, FILE *fp, const bk_filewriter *w)
{
    bk_h5 *h = ctx;
    if (!h->open || w != &h->fw)
        return NULL;
    settle_thread(h);                     /* (a set being written reads the table's rows: not now) */
    bk_h5_table *t = table_of(h, fp);
    if (!t || t->ncol == 0)
        return NULL;
    if (!t->threaded) {
        const int k = h->cur;
        t->tbuf = t->buf[k];
        t->tcap = t->cap[k];
        t->ntb = t->nbuf[k];
        t->buf[k] = NULL;
        t->cap[k] = t->nbuf[k] = 0;
        t->threaded = 1;
    }
    return t;
}

static void *sink_tbegin(void *table)
{
    return thread_row(table, 1);
}

/* Column c's type set (the first row's) and its offset in a row. */
static void settle(bk_h5_table *t, int c, int type)
{
    bk_h5_col *col = &t->col[c];
    if (col->type)
        return;
    col->type = type;
    col->off = c ? t->col[c - 1].off + cell_size(t->col[c - 1].type) : 0;
    if (c == t->ncol - 1)
        t->rowbytes = col->off + cell_size(type);
}

static void blank(bk_h5_cursor *r, int c)
{
    bk_h5_col *col = &r->t->col[c];
    unsigned char *b = r->row + col->off;
    if (col->type == 1) {
        double v = NAN;
        memcpy(b, &v, 8);
    } else if (col->type == 2)
        memset(b, 0, 8);
    else
        memset(b, 0, BK_H5_STR);
}

/* The cell of the row being given in the next column for a value of this
 * type; NULL (the cell blank) past the last column or when the column's type
 * (its first row's) is another. */
static unsigned char *cell(bk_h5_cursor *r, int type)
{
    bk_h5_table *t = r->t;
    if (r->field >= t->ncol)
        return NULL;
    const int c = r->field++;
    settle(t, c, type);
    if (t->col[c].type != type) {
        blank(r, c);
        return NULL;
    }
    return r->row + t->col[c].off;
}

static void sink_num(void *row, double v)
{
    unsigned char *p = cell(row, 1);
    if (p)
        memcpy(p, &v, 8);
}

static void sink_int(void *row, long v)
{
    unsigned char *p = cell(row, 2);
    int64_t w = v;
    if (p)
        memcpy(p, &w, 8);
}

static void sink_str(void *row, const char *s, size_t len)
{
    unsigned char *p = cell(row, 3);
    if (p) {                                   /* null-padded, cut at 64 bytes */
        const size_t k = len < BK_H5_STR ? len : BK_H5_STR;
        memcpy(p, s, k);
        memset(p + k, 0, BK_H5_STR - k);
    }
}

static void sink_end(void *row)
{
    bk_h5_cursor *r = row;
    bk_h5_table *t = r->t;
    for (; r->field < t->ncol; ++r->field) {   /* a short row: the rest blank (no type yet: float64) */
        settle(t, r->field, 1);
        blank(r, r->field);
    }
    if (t->stride == 0)                        /* the first row: its layout is every row's */
        t->stride = t->rowbytes;
    if (r->set < 0)
        t->ntb++;
    else
        t->nbuf[r->set]++;
    r->row = NULL;
}

/* ---- the solve thread's side ---- */

static void hand_over(bk_h5 *h, int flush);
static void start_library(bk_h5 *h);

/* Set k's room for states: BK_H5_ROOM0, then twice what it was, at most
 * h->cap (a set being filled: the thread does not read it).  0, or -1 when
 * out of memory (the room as it was). */
static int grow_states(bk_h5 *h, int k)
{
    const int room = h->room[k] ? 2 * h->room[k] : BK_H5_ROOM0;
    const size_t r = (size_t)(room < h->cap ? room : h->cap), nd = (size_t)h->ndof;
    long *step = realloc(h->step[k], r * sizeof *step);
    if (step)
        h->step[k] = step;
    double *time = realloc(h->time[k], r * sizeof *time);
    if (time)
        h->time[k] = time;
    double *q = bk_big_realloc(h->q[k], r * nd * sizeof *q + 1);
    if (q)
        h->q[k] = q;
    double *qd = h->with_qd ? bk_big_realloc(h->qd[k], r * nd * sizeof *qd + 1) : NULL;
    if (qd)
        h->qd[k] = qd;
    if (!step || !time || !q || (h->with_qd && !qd))
        return -1;
    h->room[k] = (int)r;
    return 0;
}

int bk_h5_open(bk_h5 *h, const bk_model *m, int in_time, int states, const char *dir, const bk_tables *tables,
               size_t cap, FILE *err)
{
    memset(h, 0, sizeof *h);
    h->m = m;
    h->tables = tables;
    h->ndof = m->ndof;
    h->with_qd = in_time;
    h->qd_step = -1;
    h->sink = (bk_rowsink){h, sink_begin, sink_num, sink_int, sink_str, sink_end, sink_table, sink_tbegin};
    snprintf(h->path, sizeof h->path, "%s/results.h5", dir);
    size_t nd = (size_t)m->ndof;
    /* the states' buffers: up to 1 MB of rows per set (at least 16, at most
     * BK_H5_ROWS), allocated as they fill: 2 MB at the start put every later
     * block of a small run on a fresh huge page (bigalloc.h), a fault of
     * 0.1-0.2 ms on a virtual machine */
    h->cap = (int)fmax(16.0, fmin((double)BK_H5_ROWS, (double)(1 << 20) / (8.0 * (double)(nd + 1))));
    int ok = 1;
    for (int k = 0; k < 2; ++k)
        ok = ok && grow_states(h, k) == 0;
    h->qd_last = h->with_qd ? malloc(nd * sizeof *h->qd_last + 1) : NULL;
    if (!ok || (h->with_qd && !h->qd_last) || bk_filewriter_open(&h->fw, cap > 0 ? cap : 1, 0) != 0) {
        fprintf(err, "error: %s: out of memory\n", h->path);
        h->open = 1;                          /* (bk_h5_close frees) */
        h->failed = 1;
        snprintf(h->failure, sizeof h->failure, "out of memory");
        return -1;
    }
    h->job[0] = (bk_h5_job){h, 0, 0};
    h->job[1] = (bk_h5_job){h, 1, 0};
    h->job[2] = (bk_h5_job){h, 1, 1};
    h->job[3] = (bk_h5_job){h, 2, 0};
    h->job[4] = (bk_h5_job){h, 3, 0};
    h->open = 1;                          /* (HDF5 started at the first set handed over, */
    if (states > BK_H5_HANDOVER)          /*   or now when the run will hand sets over) */
        start_library(h);
    return 0;
}

void bk_h5_velocity(bk_h5 *h, int step, const double *qd)
{
    if (!h->open || !h->with_qd || !qd)
        return;
    memcpy(h->qd_last, qd, (size_t)h->ndof * sizeof *qd);
    h->qd_step = step;
}

void bk_h5_state(bk_h5 *h, int step, double t, const double *q)
{
    if (!h->open)
        return;
    if (h->nbuf[h->cur] == h->cap)
        bk_h5_flush(h);
    const int s = h->cur;
    if (h->nbuf[s] == h->room[s] && grow_states(h, s) != 0) {
        h->oom = 1;                       /* (reported by bk_h5_close; the state is missing) */
        return;
    }
    size_t nd = (size_t)h->ndof, k = (size_t)h->nbuf[s];
    h->step[s][k] = step;
    h->time[s][k] = t;
    memcpy(h->q[s] + k * nd, q, nd * sizeof *q);
    if (h->with_qd) {
        if (h->qd_step == step)
            memcpy(h->qd[s] + k * nd, h->qd_last, nd * sizeof *q);
        else
            for (size_t i = 0; i < nd; ++i)
                h->qd[s][k * nd + i] = NAN;
    }
    h->qd_step = -1;
    h->nbuf[s]++;
    /* every BK_H5_HANDOVER states to the thread, unflushed: the writing goes
     * on beside the solve instead of after it; while the thread still writes
     * the other set, this one goes on filling (to its room: then
     * bk_h5_flush waits) */
    if (h->nbuf[s] >= BK_H5_HANDOVER && (h->ticket[s ^ 1] <= 0 || bk_filewriter_done(&h->fw, h->ticket[s ^ 1])))
        hand_over(h, 0);
}

void bk_h5_flush(bk_h5 *h)
{
    if (!h->open)
        return;
    /* nothing written since the last flush: no HDF5 call (a long run's timed
     * flushes with no new output step would allocate in the library) */
    int empty = h->nbuf[h->cur] == 0 && !h->unflushed;
    for (int j = 0; j < h->ntab && empty; ++j)   /* (the thread's rows: maybe some) */
        empty = h->tab[j]->nbuf[h->cur] == 0 && !h->tab[j]->threaded;
    if (!empty)
        hand_over(h, 1);
}

/* HDF5 started and the file made by the thread (its first job). */
static void start_library(bk_h5 *h)
{
    h->lib = 1;
    bk_filewriter_start(&h->fw);          /* (if not yet: frames, rows) */
    bk_filewriter_call(&h->fw, bk_h5_run_job, &h->job[0]);
}

/* The set being filled to the thread (flush 1: then the file is flushed; 2:
 * the run's last rows, the sizes of the datasets not yet made), and the other
 * set, once written, to be filled. */
static void hand_over(bk_h5 *h, int flush)
{
    if (!h->lib)                          /* the first set */
        start_library(h);
    const int k = h->cur;
    h->flush[k] = flush;
    h->unflushed = flush != 1;
    h->ticket[k] = bk_filewriter_call(&h->fw, bk_h5_run_job, &h->job[1 + k]);
    h->cur = k ^ 1;
    if (h->ticket[h->cur] > 0)            /* the other set: written by now? */
        bk_filewriter_wait(&h->fw, h->ticket[h->cur]);
    h->ticket[h->cur] = 0;
    h->nbuf[h->cur] = 0;
    for (int j = 0; j < h->ntab; ++j)
        h->tab[j]->nbuf[h->cur] = 0;
}

int bk_h5_close(bk_h5 *h, FILE *err)
{
    int rc = 0;
    if (h->open) {
        /* a run whose rows all came now: the file in one piece, here (the
         * writer is idle: the frames are written, the rows' queue stopped) */
        int by_library = h->lib || h->tlib;
        if (h->fw.ready && !by_library)
            by_library = bk_h5_write_whole(h, h->cur) == 1;
        if (h->fw.ready && by_library) {
            hand_over(h, 2);              /* the last rows (closing the file flushes it) */
            bk_filewriter_wait(&h->fw, bk_filewriter_call(&h->fw, bk_h5_run_job, &h->job[3]));
            bk_filewriter_call(&h->fw, bk_h5_run_job, &h->job[4]);   /* HDF5 ended by bk_h5_end */
        }
        h->open = 0;
        for (int j = 0; j < h->ntab; ++j)    /* (the thread's: it is idle now) */
            h->oom = h->oom || h->tab[j]->toom;
        if (!h->failed && h->oom) {
            h->failed = 1;
            snprintf(h->failure, sizeof h->failure, "out of memory for the rows or states (some are missing)");
        }
        if (h->failed) {
            if (err)
                fprintf(err, "error: %s: cannot write: %s\n", h->path, h->failure);
            rc = -1;
        }
    }
    return rc;
}

void bk_h5_end(bk_h5 *h)
{
    bk_h5_close(h, NULL);
    bk_filewriter_close(&h->fw);          /* (drains: HDF5 ended) */
    for (int k = 0; k < h->ntab; ++k) {
        free(h->tab[k]->buf[0]);
        free(h->tab[k]->buf[1]);
        free(h->tab[k]->tbuf);
        free(h->tab[k]->col);
        free(h->tab[k]);
    }
    free(h->tab);
    for (int k = 0; k < 2; ++k) {
        free(h->step[k]);
        free(h->time[k]);
        free(h->q[k]);
        free(h->qd[k]);
    }
    free(h->qd_last);
    memset(h, 0, sizeof *h);
}
