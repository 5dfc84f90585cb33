/* records.c -- the interaction records of the model file: each interaction
 * module's own data (assembly/interaction.h), kept by the model as text and
 * read by the module with a reader of its own (model/reader.h):
 *   records N
 *   record NAME            (N times, each followed by the module's tokens, up
 *   ...                     to a line holding only "end_record")
 *   end_record
 * The model knows neither what a record holds nor which module reads it. */
#include <stdlib.h>
#include <string.h>

#include "model/reader.h"

/* The text of the record whose name was just read, up to its end_record
 * line, into rec (allocated). */
static void read_record(bk_reader *r, bk_model_record *rec)
{
    const char *start = r->buf + r->pos, *p = start;
    const char *end = NULL;
    while ((p = strstr(p, "end_record")) != NULL) {
        const int line_start = p == r->buf || p[-1] == '\n';
        const char after = p[strlen("end_record")];
        if (line_start && (after == '\n' || after == '\r' || after == '\0')) {
            end = p;
            break;
        }
        p += 1;
    }
    if (!end) {
        rd_fail(r, "record '%s' has no end_record line", rec->name);
        return;
    }
    size_t n = (size_t)(end - start);
    rec->text = rd_xcalloc(r, n + 1, 1);
    size_t nw = strlen(r->path) + strlen(rec->name) + 16;
    rec->where = rd_xcalloc(r, nw, 1);
    if (r->failed)
        return;
    memcpy(rec->text, start, n);
    snprintf(rec->where, nw, "%s, record %s", r->path, rec->name);
    r->pos = (size_t)(end - r->buf) + strlen("end_record");
}

void bk_model_read_records(bk_reader *r, bk_model *m)
{
    rd_expect(r, "records");
    int n = rd_inum(r, "records", 0, 1000);
    m->records = rd_xcalloc(r, (size_t)n, sizeof *m->records);
    for (int i = 0; i < n && !r->failed; ++i) {
        bk_model_record *rec = &m->records[i];
        m->nrecord = i + 1;                 /* (freed from here on) */
        rd_expect(r, "record");
        rd_copy_token(r, rec->name, sizeof rec->name, "record name");
        for (int k = 0; k < i && !r->failed; ++k)
            if (strcmp(m->records[k].name, rec->name) == 0)
                rd_fail(r, "record '%s' appears twice", rec->name);
        read_record(r, rec);
    }
}

const bk_model_record *bk_model_record_find(const bk_model *m, const char *name)
{
    for (int i = 0; i < m->nrecord; ++i)
        if (strcmp(m->records[i].name, name) == 0)
            return &m->records[i];
    return NULL;
}

int rd_open_record(bk_reader *r, const bk_model_record *rec, FILE *err)
{
    memset(r, 0, sizeof *r);
    r->path = rec->where;
    r->err = err;
    r->len = strlen(rec->text);
    r->buf = malloc(r->len + 1);
    if (!r->buf) {
        fprintf(err, "error: %s: out of memory\n", rec->where);
        return -1;
    }
    memcpy(r->buf, rec->text, r->len + 1);
    return 0;
}

int rd_close_record(bk_reader *r)
{
    if (!r->failed && rd_next_tok(r) != NULL)
        rd_fail(r, "unexpected '%s' after the record's data", r->tok);
    free(r->buf);
    r->buf = NULL;
    return r->failed ? -1 : 0;
}

void bk_model_records_free(bk_model *m)
{
    for (int i = 0; i < m->nrecord; ++i) {
        free(m->records[i].text);
        free(m->records[i].where);
    }
    free(m->records);
    m->records = NULL;
    m->nrecord = 0;
}
