/* csvrow.h -- one row of a result table (CSV), built in a buffer and written
 * with one fwrite: numbers with bk_fmt_g17 (numfmt.h: the text of "%.17g",
 * several times faster than fprintf) or with fewer digits (bk_fmt_e,
 * bk_fmt_g: the text of "%.Ne", "%.Ng"), integers and names.
 *
 *   bk_row r;  bk_row_begin(&r, fp);
 *   bk_row_int(&r, step);  bk_row_num(&r, t);  bk_row_str(&r, name);
 *   bk_row_end(&r);                          -- "step,t,name\n" to fp
 *
 * Fields are separated by commas; bk_row_end adds the newline.  A row longer
 * than the buffer is written in pieces (no field is cut).  No allocation. */
#ifndef BK_CSVROW_H
#define BK_CSVROW_H

#include <stdio.h>

#include "numfmt.h"

typedef struct bk_row {
    char buf[2048];
    int n;                   /* bytes in buf */
    int nfield;              /* fields so far in the row */
    FILE *fp;                /* where the row goes */
} bk_row;

void bk_row_begin(bk_row *r, FILE *fp);
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
