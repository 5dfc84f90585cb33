/* tables.c -- the registry of a run's result tables (see tables.h). */
#include "base/tables.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "base/csvrow.h"

/* Room for one more table; 0, or -1 when out of memory. */
static int grow(bk_tables *ts)
{
    if (ts->n < ts->cap)
        return 0;
    int cap = ts->cap ? 2 * ts->cap : 8;
    bk_table *t = realloc(ts->t, (size_t)cap * sizeof *t);
    if (!t)
        return -1;
    ts->t = t;
    ts->cap = cap;
    return 0;
}

static void put(bk_tables *ts, const char *name, const char *header, FILE *fp, char *buf, int rows)
{
    bk_table *t = &ts->t[ts->n++];
    t->header = header ? strdup(header) : NULL;     /* (NULL when out of memory: no mirror, csvrow.h) */
    snprintf(t->name, sizeof t->name, "%s", name);
    t->fp = fp;
    t->buf = buf;
    t->rows = rows;
}

FILE *bk_tables_open(bk_tables *ts, const char *dir, const bk_table_spec *spec, int rows, FILE *err)
{
    const char *name = spec->name, *header = spec->header;
    if (grow(ts) != 0) {
        fprintf(err, "error: out of memory\n");
        return NULL;
    }
    char *buf;
    FILE *fp = bk_table_open(dir, name, header, &buf, err);
    if (fp)
        put(ts, name, header, fp, buf, rows);
    return fp;
}

const bk_table *bk_tables_of(const bk_tables *ts, const FILE *fp)
{
    for (int k = 0; k < ts->n; ++k)
        if (ts->t[k].fp == fp)
            return &ts->t[k];
    return NULL;
}

FILE *bk_tables_find(const bk_tables *ts, const char *name)
{
    for (int k = 0; k < ts->n; ++k)
        if (ts->t[k].fp && strcmp(ts->t[k].name, name) == 0)
            return ts->t[k].fp;
    return NULL;
}

int bk_tables_add(bk_tables *ts, const char *name, FILE *fp, int rows)
{
    if (grow(ts) != 0) {
        fclose(fp);
        return -1;
    }
    put(ts, name, NULL, fp, NULL, rows);
    return 0;
}

int bk_tables_rows(const bk_tables *ts, FILE **fp, int max)
{
    int n = 0;
    for (int k = 0; k < ts->n && n < max; ++k)
        if (ts->t[k].fp && ts->t[k].rows)
            fp[n++] = ts->t[k].fp;
    return n;
}

void bk_tables_flush(bk_tables *ts, int (*skip)(void *ctx, FILE *fp), void *ctx)
{
    for (int k = 0; k < ts->n; ++k)
        if (ts->t[k].fp && !(skip && skip(ctx, ts->t[k].fp)))
            fflush(ts->t[k].fp);
}

int bk_tables_close(bk_tables *ts, const char *dir, FILE *err)
{
    int bad_any = 0;
    for (int k = 0; k < ts->n; ++k) {
        bk_table *t = &ts->t[k];
        if (!t->fp)
            continue;
        int bad = ferror(t->fp) != 0;
        int e = bad ? EIO : 0;
        if (fclose(t->fp) != 0 && !bad) {
            bad = 1;
            e = errno;
        }
        t->fp = NULL;
        if (bad && err)
            fprintf(err, "error: %s/%s: cannot write: %s\n", dir, t->name, strerror(e));
        bad_any |= bad;
    }
    return bad_any ? -1 : 0;
}

void bk_tables_free(bk_tables *ts)
{
    bk_tables_close(ts, "", NULL);
    for (int k = 0; k < ts->n; ++k) {
        free(ts->t[k].buf);
        free(ts->t[k].header);
    }
    free(ts->t);
    ts->t = NULL;
    ts->n = ts->cap = 0;
}
