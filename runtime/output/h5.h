/* h5.h -- results.h5: one HDF5 file per run with every output step's state and
 * every result table (layout: docs/reference/results_h5.md).
 *
 *   /                 attributes scene, analysis, time_name ("time" or
 *                     "load_factor"), units, format (1)
 *   /step, /time      [nstep] the output steps and their time (s) or load factor
 *   /q                [nstep, ndof] the coordinates of each output step
 *   /qd               [nstep, ndof] their velocities (dynamics; NaN where the
 *                     analysis gave none, e.g. a failed run's last step)
 *   /dofs/...         [ndof] each DOF's node, beam, element, field, component
 *   /tables/NAME      [nrow] the rows of each result table NAME.csv, a
 *                     compound of its columns by their header names (float64,
 *                     int64 or 64-byte strings, as the first row had them):
 *                     the very values the CSV prints
 *
 * The rows (states, and the tables' rows given to the mirror, csvrow.h
 * bk_rowsink, on the solve thread) are kept in one of two sets of buffers.
 * A table whose rows this file's thread formats (csvrow.h bk_rowqueue on fw:
 * from the run's first frames on, or once its rows are due a thread:
 * rows_writer.c) is mirrored by the
 * thread instead, as it formats them, into rows of its own (bk_h5_table
 * tbuf: written with the set handed over next, or by the thread itself past
 * BK_H5_TABLE_BYTES, making the file if no set was handed over yet): the solve
 * thread then only records the rows' values (the mirror's cells and their
 * fresh memory took 2-10 ms of a 70-80 ms run).  A run whose rows all
 * come at its end (fewer than BK_H5_HANDOVER states, no table's buffer full,
 * shorter than the flush interval: most static runs and short dynamic ones)
 * gets its file in one
 * piece at bk_h5_close, without the HDF5 library (h5_whole.c, h5_plain.h:
 * contiguous datasets of exactly their rows): the library's start, its object
 * bookkeeping and its end took 2-3 ms of CPU time, more than such a run's
 * solve.  Otherwise every HDF5 call is made by the writer thread h owns
 * (filewriter.h: the run's one writer thread, which the ParaView frames and
 * the tables' rows share), one at a time, from the first set handed over on:
 * when the run's tables are flushed (output.c: every 0.5 s of wall time), when
 * a table's buffer is full (BK_H5_ROWS rows or BK_H5_TABLE_BYTES), every
 * BK_H5_HANDOVER states once the other set is written (unflushed, so that
 * the writing goes on beside the solve; while the thread is still at the
 * other set, the states go on filling this one up to its room), and at the
 * end, the set being
 * filled is handed to the thread, which appends it (and, when flushed,
 * flushes the file: H5Fflush), and the other set is filled meanwhile.  A
 * dataset is made at its first rows: chunked and extensible, or contiguous of
 * exactly its rows when those are the run's last.  h5py reads the same
 * datasets, types, values and attributes either way (only the layout and
 * maxshape differ).  A run written in one piece (no modification times are
 * kept) writes the same bytes each time; in a longer one the file's layout
 * (not its values) depends on when the timed flushes came and on how far
 * the thread was behind.  A
 * run that is interrupted or fails keeps every row; one killed outright keeps
 * the rows up to its last flush (none in its first 0.5 s, when the file, if
 * made, may not be readable).
 *
 * Sizes and directions:
 *   bk_h5_open      in: m, in_time (1: the states are in time, with
 *                   velocities: the analysis' plan, output.h), states (the
 *                   output states the run gives when known from the start,
 *                   else 0: with more than BK_H5_HANDOVER, HDF5 is started on
 *                   the thread now, 5-10 ms of its time that would otherwise
 *                   come in the middle of the run), dir, tables
 *                   (the run's registry: the mirrored
 *                   tables' names and headers; not owned, must outlive h);
 *                   cap: the bytes of its writer's file buffers (filewriter.h:
 *                   the thread is shared with the ParaView frames, vtk.h ext).
 *                   0, or -1 when out of memory (message on err).
 *   bk_h5_velocity  in: the velocities qd[ndof] of the state of output step
 *                   `step` given next (dynamics; copied).
 *   bk_h5_state     in: step, t, q[ndof] (copied).
 *   bk_h5_flush     hands the rows so far to the thread.
 *   bk_h5_close     writes the file in one piece or hands over the rest and
 *                   waits until the file is written and closed; 0, or -1 with
 *                   "error: DIR/results.h5: cannot write: REASON" on err (if
 *                   not NULL).  HDF5, if started, is ended by the thread
 *                   meanwhile.  Safe on a closed or never opened h.
 *   bk_h5_end       closes (if still open), waits until the thread has ended
 *                   (and HDF5), frees.  Safe on a never opened h (zeroed). */
#ifndef BK_H5_H
#define BK_H5_H

#include <stdint.h>
#include <stdio.h>

#include "base/csvrow.h"
#include "base/filewriter.h"
#include "base/tables.h"
#include "model/model.h"

#define BK_H5_ROWS 4096        /* rows of a dataset buffered at most before they are written, */
#define BK_H5_TABLE_BYTES (4 << 20)   /*   or a table's rows of this many bytes if more */
#define BK_H5_ROOM0 16         /* states per set allocated at first */
#define BK_H5_HANDOVER 64      /* states handed to the thread at a time (a write costs 0.1-0.2 ms and more) */
#define BK_H5_STR 64           /* bytes of a string cell (names: model.h's 64) */

typedef int64_t bk_h5_id;       /* an hid_t (int64_t in HDF5 >= 1.10: checked in h5.c) */

typedef struct bk_h5_col {
    char name[64];
    int type;                 /* 0 not yet known, 1 float64, 2 int64, 3 string (the first row's) */
    size_t off;               /* its offset in a row */
} bk_h5_col;

struct bk_h5;
struct bk_h5_table;

/* A row being given (the sink's row handle, csvrow.h bk_rowsink). */
typedef struct bk_h5_cursor {
    struct bk_h5_table *t;
    int field;                /* its next field */
    int set;                  /* its set, or -1: the thread's rows */
    unsigned char *row;       /* its place (NULL between rows) */
} bk_h5_cursor;

typedef struct bk_h5_table {
    struct bk_h5 *h;
    const FILE *fp;           /* the CSV stream it mirrors */
    char name[64];            /* the CSV's name without ".csv" */
    int ncol;
    bk_h5_col *col;           /* owned: [ncol] */
    size_t rowbytes, stride;  /* a row's bytes (known once the first row's last column is), the buffers' */
    unsigned char *buf[2];    /* owned: per set, [cap] rows */
    int nbuf[2], cap[2];      /* per set: rows buffered, room */
    bk_h5_cursor cs;          /* the row being given on the solve thread */
    /* A table whose rows results.h5's thread formats (csvrow.h bk_rowqueue
     * on h->fw) is mirrored by that thread from the queue's start on, into
     * rows of its own (the rows buffered before moved there): */
    int threaded;
    unsigned char *tbuf;      /* owned: [tcap] rows */
    long ntb, tcap;
    bk_h5_cursor ct;          /* the row the thread is giving */
    int toom;                 /* the thread ran out of memory for them (some are missing) */
    long nrow;                /* the thread's: rows in the file, */
    bk_h5_id ds, type;        /*   its dataset and compound type (0 before the first write) */
} bk_h5_table;

typedef struct bk_h5_job {
    struct bk_h5 *h;
    int what;                 /* 0 make the file, 1 write set `set`, 2 close the file, 3 end HDF5 */
    int set;
} bk_h5_job;

typedef struct bk_h5 {
    int open;                 /* between bk_h5_open and bk_h5_close */
    char path[1100];
    const bk_model *m;
    const bk_tables *tables;
    int ndof, with_qd;        /* with_qd: in time (bk_h5_open's in_time) */
    bk_filewriter fw;         /* owned: the HDF5 thread */
    int lib;                  /* HDF5 started: a set was handed to the thread before the end */
    bk_h5_job job[5];         /* make, write set 0, write set 1, close, end */
    long ticket[2];           /* the write of each set handed over (0: none pending) */
    int flush[2];             /* 1: the file is flushed after the set's write; 2: the set is the last */
    int cur;                  /* the set being filled */
    int cap;                  /* states per set (then the set is handed over) */
    int room[2];              /* states allocated per set: from BK_H5_ROOM0, doubled up to cap as
                               * they fill (a short run touches little fresh memory) */
    int nbuf[2];              /* states buffered per set */
    int unflushed;            /* sets handed over since the last flush without one */
    long *step[2];            /* owned: [room] per set */
    double *time[2], *q[2], *qd[2];   /* owned: [room], [room ndof], [room ndof] per set */
    double *qd_last;          /* owned: [ndof] the velocities given for step qd_step */
    int qd_step;              /* -1: none */
    bk_h5_table **tab;        /* owned: [ntab] the mirrored tables (each owned: a table's place is
                               * kept, the thread's rows refer to it) */
    int ntab, captab;
    bk_rowsink sink;          /* the tables' mirror (csvrow.h), ctx = this */
    int oom;                  /* the solve thread ran out of memory for rows (some are missing) */
    /* the thread's */
    bk_h5_id file, tables_group, ds_step, ds_time, ds_q, ds_qd;
    int tlib;                 /* the file was made by the thread for a table's rows (its rows past
                               * BK_H5_TABLE_BYTES: written, not kept) before any set was handed over */
    long nstate;              /* states in the file */
    int failed;               /* an HDF5 call failed: */
    char failure[200];        /*   which */
} bk_h5;

int bk_h5_open(bk_h5 *h, const bk_model *m, int in_time, int states, const char *dir, const bk_tables *tables,
               size_t cap, FILE *err);
void bk_h5_velocity(bk_h5 *h, int step, const double *qd);
void bk_h5_state(bk_h5 *h, int step, double t, const double *q);
void bk_h5_flush(bk_h5 *h);
int bk_h5_close(bk_h5 *h, FILE *err);
void bk_h5_end(bk_h5 *h);

#endif
