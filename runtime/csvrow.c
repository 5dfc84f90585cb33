/* csvrow.c -- rows of the result tables (see csvrow.h). */
#define _GNU_SOURCE              /* fopencookie */
#include "csvrow.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

struct bk_table {
    bk_precreate *pre;
    int k;                   /* its named slot in pre */
    int fd;                  /* -1 until the first write */
    int err;                 /* errno of the first failure, or 0 */
    int discard;
    char buf[BK_TABLE_BUFFER];
};

/* The stream's writes (fopencookie): n bytes, or 0 on failure (errno set). */
static ssize_t table_write(void *cookie, const char *b, size_t n)
{
    bk_table *t = cookie;
    if (t->discard)
        return (ssize_t)n;
    if (t->fd < 0 && !t->err && (t->fd = bk_precreate_named(t->pre, t->k)) < 0)
        t->err = errno ? errno : EIO;
    if (t->err) {
        errno = t->err;
        return 0;
    }
    size_t done = 0;
    while (done < n) {
        ssize_t w = write(t->fd, b + done, n - done);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0) {
            t->err = w < 0 ? errno : EIO;
            errno = t->err;
            return 0;
        }
        done += (size_t)w;
    }
    return (ssize_t)n;
}

static int table_close(void *cookie)
{
    bk_table *t = cookie;
    if (t->fd >= 0 && close(t->fd) != 0 && !t->err)
        t->err = errno;
    t->fd = -1;
    if (t->err) {
        errno = t->err;
        return EOF;
    }
    return 0;
}

FILE *bk_table_open(bk_precreate *pre, int k, const char *header, bk_table **tp)
{
    bk_table *t = *tp = malloc(sizeof *t);
    if (!t)
        return NULL;
    t->pre = pre;
    t->k = k;
    t->fd = -1;
    t->err = 0;
    t->discard = 0;
    cookie_io_functions_t io = {.read = NULL, .write = table_write, .seek = NULL, .close = table_close};
    FILE *fp = fopencookie(t, "w", io);
    if (!fp) {
        free(t);
        *tp = NULL;
        return NULL;
    }
    setvbuf(fp, t->buf, _IOFBF, sizeof t->buf);
    fputs(header, fp);
    return fp;
}

int bk_table_error(const bk_table *t)
{
    return t ? t->err : 0;
}

void bk_table_discard(bk_table *t)
{
    if (t)
        t->discard = 1;
}

void bk_table_free(bk_table *t)
{
    free(t);
}

void bk_row_begin(bk_row *r, FILE *fp)
{
    r->n = 0;
    r->nfield = 0;
    r->fp = fp;
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

void bk_row_num(bk_row *r, double v)
{
    room(r, BK_NUMFMT_MAX + 1);
    separator(r);
    r->n += bk_fmt_g17(r->buf + r->n, v);
}

void bk_row_int(bk_row *r, long v)
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

void bk_row_str(bk_row *r, const char *s)
{
    size_t len = strlen(s);
    room(r, len + 1);
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

void bk_row_e(bk_row *r, double v, int prec)
{
    room(r, BK_NUMFMT_MAX + 1);
    separator(r);
    r->n += bk_fmt_e(r->buf + r->n, v, prec);
}

void bk_row_g(bk_row *r, double v, int prec)
{
    room(r, BK_NUMFMT_MAX + 1);
    separator(r);
    r->n += bk_fmt_g(r->buf + r->n, v, prec);
}

void bk_row_end(bk_row *r)
{
    r->buf[r->n++] = '\n';
    fwrite(r->buf, 1, (size_t)r->n, r->fp);
    r->n = 0;
    r->nfield = 0;
}
