/* csvrow.c -- rows of the result tables (see csvrow.h). */
#include "base/csvrow.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

FILE *bk_table_open(const char *dir, const char *name, const char *header, char **buf, FILE *err)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    *buf = NULL;
    FILE *fp = fopen(path, "w");
    if (!fp) {
        fprintf(err, "error: %s: cannot write: %s\n", path, strerror(errno));
        return NULL;
    }
    *buf = malloc(BK_TABLE_BUFFER);
    if (*buf && setvbuf(fp, *buf, _IOFBF, BK_TABLE_BUFFER) != 0) {
        free(*buf);
        *buf = NULL;
    }
    fputs(header, fp);
    return fp;
}

#include "base/filewriter.h"

/* ---- rows formatted here (or by the writer thread, from a chunk) ---- */

static void fmt_begin(bk_row *r, FILE *fp)
{
    r->n = 0;
    r->nfield = 0;
    r->fp = fp;
    r->q = NULL;
    r->table = -1;
}

/* Room for need more bytes (and the newline): a full buffer goes to fp. */
static void room(bk_row *r, size_t need)
{
    if ((size_t)r->n + need + 2 > sizeof r->buf) {
        fwrite(r->buf, 1, (size_t)r->n, r->fp);
        r->n = 0;
    }
}

static void separator(bk_row *r)
{
    if (r->nfield++ > 0)
        r->buf[r->n++] = ',';
}

static void fmt_num(bk_row *r, double v)
{
    room(r, BK_NUMFMT_MAX + 1);
    separator(r);
    r->n += bk_fmt_g17(r->buf + r->n, v);
}

static void fmt_int(bk_row *r, long v)
{
    room(r, 24);
    separator(r);
    char tmp[24];
    int k = 0;
    unsigned long u = v < 0 ? 0UL - (unsigned long)v : (unsigned long)v;
    do {
        tmp[k++] = (char)('0' + u % 10);
        u /= 10;
    } while (u);
    if (v < 0)
        r->buf[r->n++] = '-';
    while (k)
        r->buf[r->n++] = tmp[--k];
}

/* s[len]; sep: a new field (else the continuation of the last one) */
static void fmt_str(bk_row *r, const char *s, size_t len, int sep)
{
    room(r, len + 1);
    if (sep)
        separator(r);
    if ((size_t)r->n + len + 2 > sizeof r->buf) {     /* longer than the buffer: straight through */
        fwrite(r->buf, 1, (size_t)r->n, r->fp);
        fwrite(s, 1, len, r->fp);
        r->n = 0;
        return;
    }
    memcpy(r->buf + r->n, s, len);
    r->n += (int)len;
}

static void fmt_e(bk_row *r, double v, int prec)
{
    room(r, BK_NUMFMT_MAX + 1);
    separator(r);
    r->n += bk_fmt_e(r->buf + r->n, v, prec);
}

static void fmt_g(bk_row *r, double v, int prec)
{
    room(r, BK_NUMFMT_MAX + 1);
    separator(r);
    r->n += bk_fmt_g(r->buf + r->n, v, prec);
}

static void fmt_end(bk_row *r)
{
    r->buf[r->n++] = '\n';
    fwrite(r->buf, 1, (size_t)r->n, r->fp);
    r->n = 0;
    r->nfield = 0;
}

/* ---- rows recorded in a chunk for the writer thread ---- */

enum { T_BEGIN = 1, T_NUM, T_INT, T_STR, T_STRMORE, T_E, T_G, T_END };
#define STR_PIECE 1024                   /* a string is recorded in pieces of at most this */

/* Room for need bytes in the chunk being filled: a full one is handed over. */
static unsigned char *rq_room(bk_rowqueue *q, size_t need)
{
    if (q->pos + need > BK_ROWQ_CHUNK)
        bk_rowqueue_submit(q, 0);
    return q->chunk[q->cur] + q->pos;
}

static void rq_value(bk_rowqueue *q, int tag, int prec, const void *v8)
{
    unsigned char *p = rq_room(q, 10);
    p[0] = (unsigned char)tag;
    p[1] = (unsigned char)prec;
    memcpy(p + 2, v8, 8);
    q->pos += 10;
}

static void rq_str(bk_rowqueue *q, const char *s, size_t len)
{
    int tag = T_STR;
    do {
        size_t k = len < STR_PIECE ? len : STR_PIECE;
        unsigned char *p = rq_room(q, 3 + k);
        p[0] = (unsigned char)tag;
        p[1] = (unsigned char)(k & 0xff);
        p[2] = (unsigned char)(k >> 8);
        memcpy(p + 3, s, k);
        q->pos += 3 + k;
        s += k;
        len -= k;
        tag = T_STRMORE;
    } while (len > 0);
}

static void rq_tag(bk_rowqueue *q, int tag, int arg)
{
    unsigned char *p = rq_room(q, 2);
    p[0] = (unsigned char)tag;
    p[1] = (unsigned char)arg;
    q->pos += 2;
}

/* The thread: chunk k's rows into their streams (bk_filewriter_make). */
static void format_chunk(const void *arg, FILE *unused)
{
    (void)unused;
    const struct bk_rowqueue_job *j = arg;
    bk_rowqueue *q = j->q;
    const unsigned char *p = q->chunk[j->k], *end = p + q->len[j->k];
    bk_row *r = q->row;
    while (p < end) {
        const int tag = p[0];
        double v;
        long iv;
        switch (tag) {
        case T_BEGIN:
            fmt_begin(r, q->fp[p[1]]);
            q->mrow = q->mirror[p[1]] ? q->sink->tbegin(q->mirror[p[1]]) : NULL;
            p += 2;
            break;
        case T_NUM:
        case T_E:
        case T_G:
            memcpy(&v, p + 2, 8);
            if (q->mrow)
                q->sink->num(q->mrow, v);
            if (tag == T_NUM)
                fmt_num(r, v);
            else if (tag == T_E)
                fmt_e(r, v, p[1]);
            else
                fmt_g(r, v, p[1]);
            p += 10;
            break;
        case T_INT:
            memcpy(&iv, p + 2, 8);
            if (q->mrow)
                q->sink->integer(q->mrow, iv);
            fmt_int(r, iv);
            p += 10;
            break;
        case T_STR:
        case T_STRMORE: {
            const size_t len = (size_t)p[1] | (size_t)p[2] << 8;
            if (q->mrow && tag == T_STR)
                q->sink->str(q->mrow, (const char *)p + 3, len);
            fmt_str(r, (const char *)p + 3, len, tag == T_STR);
            p += 3 + len;
            break;
        }
        default:                         /* T_END */
            if (q->mrow)
                q->sink->end(q->mrow);
            q->mrow = NULL;
            fmt_end(r);
            p += 2;
            break;
        }
    }
    if (q->flush[j->k])
        for (int t = 0; t < q->nfp; ++t)
            fflush(q->fp[t]);
}

int bk_rowqueue_start(bk_rowqueue *q, bk_filewriter *w, FILE *const *fp, int n, size_t step_bytes)
{
    bk_rowqueue_free(q);                 /* (keeps the sink) */
    const bk_rowsink *sink = q->sink;
    for (int k = 0; k < n && q->nfp < BK_ROWQ_TABLES; ++k)
        if (fp[k])
            q->fp[q->nfp++] = fp[k];
    const size_t want = 4 + step_bytes / BK_ROWQ_CHUNK;
    q->nchunk = want < BK_ROWQ_CHUNKS ? (int)want : BK_ROWQ_CHUNKS;
    int ok = (q->row = malloc(sizeof *q->row)) != NULL;
    for (int k = 0; k < q->nchunk; ++k) {
        ok = ok && (q->chunk[k] = malloc(BK_ROWQ_CHUNK)) != NULL;
        q->job[k] = (struct bk_rowqueue_job){q, k};
    }
    if (!ok) {
        bk_rowqueue_free(q);
        return -1;
    }
    for (int t = 0; t < q->nfp && sink && sink->table; ++t)   /* (before the thread has any row) */
        q->mirror[t] = sink->table(sink->ctx, q->fp[t], w);
    q->w = w;
    return 0;
}

void bk_rowqueue_submit(bk_rowqueue *q, int flush)
{
    if (!q->w)
        return;
    if (flush && q->pos == 0 && !q->unflushed)
        return;                          /* nothing since the last flush (a timed flush of a quiet run) */
    q->unflushed = !flush;
    const int k = q->cur;
    q->len[k] = q->pos;
    q->flush[k] = flush;
    q->ticket[k] = q->last = bk_filewriter_call(q->w, format_chunk, &q->job[k]);
    q->cur = (k + 1) % q->nchunk;
    q->pos = 0;
    if (q->ticket[q->cur] > 0)           /* the next chunk: formatted by now? */
        bk_filewriter_wait(q->w, q->ticket[q->cur]);
    q->ticket[q->cur] = 0;
}

void bk_rowqueue_offer(bk_rowqueue *q, size_t min_bytes)
{
    const int next = q->w ? (q->cur + 1) % q->nchunk : 0;
    if (q->w && q->pos >= min_bytes && (q->ticket[next] == 0 || bk_filewriter_done(q->w, q->ticket[next])))
        bk_rowqueue_submit(q, 0);
}

void bk_rowqueue_stop(bk_rowqueue *q)
{
    if (q->w && q->pos > 0 && bk_filewriter_idle(q->w)) {
        /* the last rows formatted here when the thread has done all it was
         * given (the tables are the caller's again): handing them over would
         * cost its wake-up and the wait (roll-up: 0.1-0.2 ms at the end) */
        const int k = q->cur;
        q->len[k] = q->pos;
        q->flush[k] = 0;
        format_chunk(&q->job[k], NULL);
        q->pos = 0;
    } else if (q->w) {
        bk_rowqueue_submit(q, 0);        /* (not flushed: the caller's fclose does, and reports a failure's errno) */
        bk_filewriter_wait(q->w, q->last);
    }
    q->w = NULL;                         /* (the chunks are kept until bk_rowqueue_free) */
    q->nfp = 0;
}

void bk_rowqueue_free(bk_rowqueue *q)
{
    bk_rowqueue_stop(q);
    for (int k = 0; k < BK_ROWQ_CHUNKS; ++k)
        free(q->chunk[k]);
    free(q->row);
    const bk_rowsink *sink = q->sink;
    memset(q, 0, sizeof *q);
    q->sink = sink;
}

int bk_rowqueue_owns(const bk_rowqueue *q, FILE *fp)
{
    if (!q->w)
        return 0;
    for (int t = 0; t < q->nfp; ++t)
        if (q->fp[t] == fp)
            return 1;
    return 0;
}

int bk_rowqueue_thread_rows(const bk_rowqueue *q, FILE *fp)
{
    for (int t = 0; q && q->w && t < q->nfp; ++t)
        if (q->fp[t] == fp)
            return !q->sink || q->mirror[t] != NULL;
    return 0;
}

void bk_row_begin_thread(bk_row *r, FILE *fp, const bk_rowqueue *q)
{
    fmt_begin(r, fp);
    r->sink = NULL;
    r->mirror = NULL;
    for (int t = 0; t < q->nfp; ++t)
        if (q->fp[t] == fp && q->mirror[t]) {
            r->mirror = q->sink->tbegin(q->mirror[t]);
            r->sink = r->mirror ? q->sink : NULL;
        }
}

/* ---- the row API: recorded when fp is one of a started queue's streams ---- */

void bk_row_begin(bk_row *r, FILE *fp, bk_rowqueue *q)
{
    fmt_begin(r, fp);
    r->sink = NULL;
    r->mirror = NULL;
    for (int t = 0; q && q->w && t < q->nfp; ++t)
        if (q->fp[t] == fp) {
            r->q = q;
            r->table = t;
            rq_tag(q, T_BEGIN, t);
            if (q->mirror[t])
                return;                  /* (mirrored by the thread) */
            break;
        }
    if (q && q->sink && (r->mirror = q->sink->begin(q->sink->ctx, fp)) != NULL)
        r->sink = q->sink;
}

void bk_row_num(bk_row *r, double v)
{
    if (r->mirror)
        r->sink->num(r->mirror, v);
    if (r->q)
        rq_value(r->q, T_NUM, 0, &v);
    else
        fmt_num(r, v);
}

void bk_row_int(bk_row *r, long v)
{
    if (r->mirror)
        r->sink->integer(r->mirror, v);
    if (r->q)
        rq_value(r->q, T_INT, 0, &v);
    else
        fmt_int(r, v);
}

void bk_row_str(bk_row *r, const char *s)
{
    if (r->mirror)
        r->sink->str(r->mirror, s, strlen(s));
    if (r->q)
        rq_str(r->q, s, strlen(s));
    else
        fmt_str(r, s, strlen(s), 1);
}

void bk_row_e(bk_row *r, double v, int prec)
{
    if (r->mirror)
        r->sink->num(r->mirror, v);
    if (r->q)
        rq_value(r->q, T_E, prec, &v);
    else
        fmt_e(r, v, prec);
}

void bk_row_g(bk_row *r, double v, int prec)
{
    if (r->mirror)
        r->sink->num(r->mirror, v);
    if (r->q)
        rq_value(r->q, T_G, prec, &v);
    else
        fmt_g(r, v, prec);
}

void bk_row_end(bk_row *r)
{
    if (r->mirror)
        r->sink->end(r->mirror);
    if (r->q)
        rq_tag(r->q, T_END, 0);
    else
        fmt_end(r);
}
