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
 *   /tables/NAME/COL  [nrow] each column COL of each result table NAME.csv
 *                     (float64, int64 or 64-byte strings, as the first row had
 *                     them): the very values the CSV prints
 *
 * Every row is kept in memory and written to the file when the run's tables are
 * flushed (output.c: every 0.5 s of wall time, output.c BK_FLUSH_INTERVAL), when
 * BK_H5_ROWS rows of a dataset are buffered, and at the end, each time followed
 * by H5Fflush: a run that is interrupted or fails keeps every row; one killed
 * outright keeps the rows up to its last flush.  Every HDF5 call is made on the
 * solve thread (the mirror of the tables, csvrow.h bk_rowsink, is given the
 * rows' values there, whether or not the writer thread formats their text).
 *
 * Sizes and directions:
 *   bk_h5_open    in: m, dir, tables (the run's registry: the mirrored tables'
 *                 names and headers; not owned, must outlive h).  0, or -1 with
 *                 "error: DIR/results.h5: cannot write: ..." on err.
 *   bk_h5_state   in: step, t, q[ndof], qd[ndof] or NULL.
 *   bk_h5_flush   writes what is buffered and flushes the file; 0 or -1.
 *   bk_h5_close   flushes and closes; 0, or -1 with the first failure's line on
 *                 err (if not NULL).  Safe on a closed or never opened h. */
#ifndef BK_H5_H
#define BK_H5_H

#include <stdint.h>
#include <stdio.h>

#include "base/csvrow.h"
#include "base/tables.h"
#include "model/model.h"

#define BK_H5_ROWS 4096        /* rows of a dataset buffered at most before they are written */
#define BK_H5_STR 64           /* bytes of a string cell (names: model.h's 64) */

typedef int64_t bk_h5_id;       /* an hid_t (int64_t in HDF5 >= 1.10: checked in h5.c) */

typedef struct bk_h5_col {
    char name[64];
    int type;                 /* 0 not yet known, 1 float64, 2 int64, 3 string */
    bk_h5_id ds;              /* its dataset, 0 before the first write */
    void *buf;                /* owned: [cap] cells of its type */
} bk_h5_col;

typedef struct bk_h5_table {
    const FILE *fp;           /* the CSV stream it mirrors */
    char name[64];            /* the CSV's name without ".csv" */
    int ncol;
    bk_h5_col *col;           /* owned: [ncol] */
    long nrow;                /* rows in the file */
    int nbuf, cap;            /* rows buffered, room */
    int field;                /* the field of the row being given */
} bk_h5_table;

typedef struct bk_h5 {
    int open;
    bk_h5_id file, tables_group;
    char path[1100];
    const bk_model *m;
    const bk_tables *tables;
    int ndof, with_qd;
    long nstate;              /* states in the file */
    int nbuf, cap;            /* states buffered, room (rows) */
    long *step;               /* owned: [cap] */
    double *time, *q, *qd;    /* owned: [cap], [cap ndof], [cap ndof] */
    bk_h5_id ds_step, ds_time, ds_q, ds_qd;
    double *qd_last;          /* owned: [ndof] the velocities given for step qd_step */
    int qd_step;              /* -1: none */
    bk_h5_table *tab;         /* owned: [ntab] the mirrored tables */
    int ntab, captab;
    bk_rowsink sink;          /* the tables' mirror (csvrow.h), ctx = this */
    int failed;               /* an HDF5 call failed: */
    char failure[200];        /*   which */
} bk_h5;

int bk_h5_open(bk_h5 *h, const bk_model *m, const char *dir, const bk_tables *tables, FILE *err);
void bk_h5_velocity(bk_h5 *h, int step, const double *qd);
void bk_h5_state(bk_h5 *h, int step, double t, const double *q);
int bk_h5_flush(bk_h5 *h);
int bk_h5_close(bk_h5 *h, FILE *err);

#endif
