/* tables.h -- the registry of a run's result tables (CSV files): every table
 * an analysis, an interaction or the output itself writes is registered here
 * when it is opened, and the registry flushes and closes them all.  No fixed
 * number of tables: the registry grows (at set-up, never while rows are
 * written).
 *
 * A table is registered by its spec, written with BK_TABLE below as a
 * constant of the module that writes it:
 *   static const bk_table_spec springs_csv = BK_TABLE("springs.csv",
 *       "runs with `[[spring]]`", "step,time,spring,length\n");
 * its file name, which runs write it and its header.  That is the whole
 * registration: `./build.sh gen` reads every BK_TABLE(...) of runtime/ (its
 * arguments string literals only) and writes the table of CSV files of
 * docs/reference/outputs.md from them (gen/outputs_emit.py; specs of one file
 * name from several writers are merged there).
 *
 * Sizes and directions:
 *   bk_tables_open   in: dir, spec (name: the file name, at most
 *                    BK_TABLE_NAME - 1 characters; header: its first line,
 *                    with the newline), rows (1: written with bk_row,
 *                    csvrow.h, and so may be queued to the writer thread).
 *                    Out: the stream, owned by
 *                    the registry; NULL on failure, with "error: DIR/NAME:
 *                    cannot write: ..." on err (nothing registered).
 *   bk_tables_add    registers a stream opened elsewhere (taken over: closed
 *                    with the others); -1 when out of memory (fp closed).
 *   bk_tables_rows   the streams written with bk_row, in registration order,
 *                    into fp[max]; returns their count.
 *   bk_tables_flush  flushes every open stream (skip: one the caller must not
 *                    touch, e.g. queued to the writer thread; may be NULL).
 *   bk_tables_close  closes every stream; 0, or -1 with "error: DIR/NAME:
 *                    cannot write: REASON" on err (if not NULL) for each that
 *                    could not be written.
 *   bk_tables_free   closes what is open (unreported) and frees. */
#ifndef BK_TABLES_H
#define BK_TABLES_H

#include <stdio.h>

#define BK_TABLE_NAME 64

/* A table's registration (see above): its file name, its header (the
 * columns, comma-separated, ending in a newline) and the runs that write it
 * (markdown: the "written by" cell of the outputs reference). */
typedef struct bk_table_spec {
    const char *name;
    const char *written_by;
    const char *header;
} bk_table_spec;

#define BK_TABLE(name, written_by, header) {(name), (written_by), (header)}

typedef struct bk_table {
    char name[BK_TABLE_NAME];
    FILE *fp;                /* owned; NULL once closed */
    char *buf;               /* owned: its stdio buffer (may be NULL) */
    char *header;            /* owned: its header line (NULL: bk_tables_add) */
    int rows;                /* written with bk_row */
} bk_table;

typedef struct bk_tables {
    bk_table *t;             /* owned: [cap] */
    int n, cap;
} bk_tables;

FILE *bk_tables_open(bk_tables *ts, const char *dir, const bk_table_spec *spec, int rows, FILE *err);
/* The open stream of the table `name` already registered, or NULL (a table
 * that two writers share, e.g. contacts.csv of rigid and beam contact). */
FILE *bk_tables_find(const bk_tables *ts, const char *name);
/* The table written to the stream fp, or NULL. */
const bk_table *bk_tables_of(const bk_tables *ts, const FILE *fp);
int bk_tables_add(bk_tables *ts, const char *name, FILE *fp, int rows);
int bk_tables_rows(const bk_tables *ts, FILE **fp, int max);
void bk_tables_flush(bk_tables *ts, int (*skip)(void *ctx, FILE *fp), void *ctx);
int bk_tables_close(bk_tables *ts, const char *dir, FILE *err);
void bk_tables_free(bk_tables *ts);

#endif
