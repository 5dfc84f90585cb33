/* reader.h -- the model file's tokens: a reader holds the whole file (or one
 * interaction record of it, rd_open_record) and reports the first error,
 * naming the file, as one line; every reading function does nothing once an
 * error was reported.  model/ reads the file with it, and an interaction
 * module (assembly/interaction.h) its own record. */
#ifndef BK_READER_H
#define BK_READER_H

#include <stddef.h>
#include <stdio.h>

#include "model/model.h"

#define MAXN 100000000

typedef struct bk_reader {
    char *buf;               /* owned: the whole file, NUL-terminated */
    size_t len, pos;         /* its length; where the next token starts */
    const char *path;
    FILE *err;
    int failed;
    char tok[256];
} bk_reader;

int rd_load(bk_reader *r);                   /* r->path into r->buf; 0, or -1 after a message */
void rd_fail(bk_reader *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
const char *rd_next_tok(bk_reader *r);      /* the next token, NULL at the end */
const char *rd_next(bk_reader *r, const char *what);   /* ... and an error naming `what` there */
void rd_expect(bk_reader *r, const char *kw);
const char *rd_field(bk_reader *r, const char *rec, const char *key);  /* value of "key=value" */
double rd_parse_num(bk_reader *r, const char *what, const char *t);
double rd_fnum(bk_reader *r, const char *rec, const char *key);
int rd_fint(bk_reader *r, const char *rec, const char *key, int lo, int hi);
double rd_num(bk_reader *r, const char *what);
int rd_inum(bk_reader *r, const char *what, int lo, int hi);
void *rd_xcalloc(bk_reader *r, size_t n, size_t size);
void rd_copy_token(bk_reader *r, char *dst, size_t n, const char *what);
char *rd_line(bk_reader *r);                /* the rest of the line, unescaped (malloc'd), or NULL */

/* The records after the header, by job (options.c, extras.c). */
void bk_model_read_options(bk_reader *r, bk_model *m);
void bk_model_read_extras(bk_reader *r, bk_model *m);
void bk_model_read_scene_warnings(bk_reader *r, bk_model *m);  /* extras.c */
void bk_model_read_records(bk_reader *r, bk_model *m);       /* records.c */
void bk_model_records_free(bk_model *m);

/* A reader of the record rec's text (a copy, owned by r until
 * rd_close_record); messages name the model file and the record.  0, or -1
 * after one line to err. */
int rd_open_record(bk_reader *r, const bk_model_record *rec, FILE *err);
/* Ends reading a record: an error when tokens are left; frees r's text.  0, or
 * -1 when reading failed (the message was written). */
int rd_close_record(bk_reader *r);
void bk_model_read_point_masses(bk_reader *r, bk_model *m);  /* point_mass_read.c */

#endif
