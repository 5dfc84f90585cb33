/* csvrow.h -- one row of a result table (CSV), built in a buffer and written
 * with one fwrite: numbers with bk_fmt_g17 (numfmt.h: the text of "%.17g",
 * several times faster than fprintf) or with fewer digits (bk_fmt_e,
 * bk_fmt_g: the text of "%.Ne", "%.Ng"), integers and names.
 *
 *   bk_row r;  bk_row_begin(&r, fp, NULL);
 *   bk_row_int(&r, step);  bk_row_num(&r, t);  bk_row_str(&r, name);
 *   bk_row_end(&r);                          -- "step,t,name\n" to fp
 *
 * Fields are separated by commas; bk_row_end adds the newline.  A row longer
 * than the buffer is written in pieces (no field is cut).  No allocation.
 *
 * Rows handed to a writer thread (bk_rowqueue): once bk_rowqueue_start has
 * been given a run's tables and the background writer's thread (filewriter.h),
 * bk_row_begin(&r, fp, q) with one of those streams records the row's fields
 * as values (a tag byte and 8 bytes a number; strings copied) in a chunk of
 * BK_ROWQ_CHUNK bytes instead of formatting them; a full chunk (or one handed
 * over by bk_rowqueue_submit) is formatted by the thread into the same streams,
 * in order, with the same text as here.  Until bk_rowqueue_stop the streams
 * are the thread's: the caller neither writes nor flushes them.  Formatting a
 * row costs 0.3-1 us (20-25 ns a number), recording it a tenth of that: a
 * dynamic run with 1000 steps formats 2-3 ms of rows.
 *
 * Sizes and directions:
 *   bk_rowqueue_start   in: w (the thread, not owned: it must outlive the queue's
 *                       use; the sink may have it mirror the rows too: a
 *                       mirrored table's rows then cost the caller only
 *                       their recording), fp[n] (n <= BK_ROWQ_TABLES; NULL entries are
 *                       skipped), step_bytes: about what an output step
 *                       records (a 10,000-element beam's sections.csv: 3 MB),
 *                       to have chunks enough for it (4 .. BK_ROWQ_CHUNKS)
 *                       so that the caller goes on while the thread formats
 *                       (with two it waited for the thread at every
 *                       chunk; with two and small steps, while the thread
 *                       was busy with other work, e.g. HDF5's start).  0, or -1 when out of memory (the rows stay
 *                       formatted here).
 *   bk_rowqueue_submit  hands over the chunk being filled; flush: the thread
 *                       then flushes every stream (the 0.5 s flush of output.c).
 *   bk_rowqueue_offer   hands over the chunk being filled when it holds at
 *                       least min_bytes and the next chunk is free (no wait):
 *                       called at each output step, it keeps what is left for
 *                       bk_rowqueue_stop small.
 *   bk_rowqueue_stop    hands over what is left and waits until the thread has
 *                       formatted it (not flushed: closing a stream flushes it
 *                       and reports a failure with its errno); the streams are
 *                       the caller's again.  Safe on a queue never started.
 *   bk_rowqueue_thread_rows  1 when q runs, fp is one of its streams and fp's
 *                       rows are mirrored by the thread (or not at all): a job
 *                       handed to q's thread (bk_filewriter_call) may then
 *                       write fp's rows itself with bk_row_begin_thread, in
 *                       the order of the hand-overs (the caller records none
 *                       of fp's rows meanwhile: they would come out when their
 *                       chunk is formatted).
 *   bk_rowqueue_free    stops and frees the chunks (after the run's results are
 *                       written: unmapping them cost 0.1-0.3 ms).  q must be
 *                       zeroed before its first bk_rowqueue_start. */
#ifndef BK_CSVROW_H
#define BK_CSVROW_H

#include <stdio.h>

#include "base/numfmt.h"

#define BK_ROWQ_TABLES 8
#define BK_ROWQ_CHUNK (128 << 10)
#define BK_ROWQ_CHUNKS 32          /* the most chunks a queue cycles through */

struct bk_filewriter;

/* A mirror of the tables' rows (the run's results.h5: output/h5.h): given the
 * values of every row begun with a queue that has a sink.  A row formatted
 * here, or queued for a thread that does not mirror its table, is given as it
 * is written (on the caller's thread): begin gives the mirror's row (NULL:
 * that table is not mirrored); then one call per field, and end.  A queued
 * row of a table the thread mirrors (table, at bk_rowqueue_start) is given by
 * the queue's thread as it formats the row: tbegin gives the mirror's row
 * (NULL: not mirrored), then the fields and end as above (the first STR_PIECE
 * bytes of a long string). */
typedef struct bk_rowsink {
    void *ctx;
    void *(*begin)(void *ctx, FILE *fp);
    void (*num)(void *row, double v);        /* bk_row_num, bk_row_e, bk_row_g */
    void (*integer)(void *row, long v);
    void (*str)(void *row, const char *s, size_t len);
    void (*end)(void *row);
    /* at bk_rowqueue_start, on the caller's thread: the mirror of fp's table
     * when the thread w is to give its rows, else NULL (NULL: none is) */
    void *(*table)(void *ctx, FILE *fp, const struct bk_filewriter *w);
    void *(*tbegin)(void *table);            /* on w's thread */
} bk_rowsink;

typedef struct bk_rowqueue {
    struct bk_filewriter *w;           /* NULL: not started (rows are formatted by the caller) */
    FILE *fp[BK_ROWQ_TABLES];          /* the streams whose rows are queued */
    int nfp;
    int nchunk;                        /* chunks in the cycle (4 .. BK_ROWQ_CHUNKS) */
    unsigned char *chunk[BK_ROWQ_CHUNKS];   /* owned: [BK_ROWQ_CHUNK] each */
    size_t len[BK_ROWQ_CHUNKS];        /* bytes handed over in chunk k */
    int flush[BK_ROWQ_CHUNKS];         /* chunk k: flush the streams after it */
    long ticket[BK_ROWQ_CHUNKS];       /* the call formatting chunk k (0: none) */
    long last;                         /* the last chunk's call (0: none) */
    int cur;                           /* the chunk being filled, */
    size_t pos;                        /*   its bytes so far */
    int unflushed;                     /* chunks handed over since the last flush without one */
    struct bk_rowqueue_job { struct bk_rowqueue *q; int k; } job[BK_ROWQ_CHUNKS];
    /* the thread's: the row being formatted (its fields may span two chunks) */
    struct bk_row *row;                /* owned */
    const bk_rowsink *sink;            /* not owned: the rows' mirror, or NULL (kept by start and stop) */
    void *mirror[BK_ROWQ_TABLES];      /* per stream: its table's mirror given by the thread (sink->table),
                                        * or NULL: given by the caller */
    void *mrow;                        /* the thread's: the mirror's row being given, or NULL */
} bk_rowqueue;

typedef struct bk_row {
    char buf[2048];
    int n;                   /* bytes in buf */
    int nfield;              /* fields so far in the row */
    FILE *fp;                /* where the row goes */
    bk_rowqueue *q;          /* non-NULL: the row is recorded in q (table `table`) */
    int table;
    const bk_rowsink *sink;  /* the mirror of the row's values (sink->begin gave mirror), */
    void *mirror;            /*   or NULL */
} bk_row;

int bk_rowqueue_start(bk_rowqueue *q, struct bk_filewriter *w, FILE *const *fp, int n, size_t step_bytes);
void bk_rowqueue_submit(bk_rowqueue *q, int flush);
void bk_rowqueue_offer(bk_rowqueue *q, size_t min_bytes);
void bk_rowqueue_stop(bk_rowqueue *q);
void bk_rowqueue_free(bk_rowqueue *q);
/* 1 when q is started and fp is one of its streams (the writer thread's). */
int bk_rowqueue_owns(const bk_rowqueue *q, FILE *fp);

int bk_rowqueue_thread_rows(const bk_rowqueue *q, FILE *fp);
/* A row of fp written by a job on q's thread (bk_rowqueue_thread_rows):
 * formatted into fp there, and mirrored as the thread mirrors q's rows. */
void bk_row_begin_thread(bk_row *r, FILE *fp, const bk_rowqueue *q);
/* q: NULL or not started, or fp not one of its streams: formatted here.
 * Either way, q's sink (when it has one) is given the row's values. */
void bk_row_begin(bk_row *r, FILE *fp, bk_rowqueue *q);
void bk_row_num(bk_row *r, double v);              /* as "%.17g" */
void bk_row_int(bk_row *r, long v);                /* as "%ld" */
void bk_row_str(bk_row *r, const char *s);         /* as "%s" (names: no quoting) */
void bk_row_e(bk_row *r, double v, int prec);     /* as "%.{prec}e" (numfmt.h bk_fmt_e) */
void bk_row_g(bk_row *r, double v, int prec);     /* as "%.{prec}g" (numfmt.h bk_fmt_g) */
void bk_row_end(bk_row *r);                        /* newline, and the row to fp */

/* DIR/NAME opened for writing with a buffer of BK_TABLE_BUFFER bytes (a table
 * is written in a few large writes, and a short run's at its close) and its
 * header line written; *buf: that buffer, the caller's to free after fclose
 * (NULL if it could not be had: the stream keeps stdio's own).  NULL on
 * failure, with "error: DIR/NAME: cannot write: ..." on err. */
#define BK_TABLE_BUFFER (1 << 16)
FILE *bk_table_open(const char *dir, const char *name, const char *header, char **buf, FILE *err);

#endif
