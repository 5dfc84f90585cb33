/* csvrow.c -- rows of the result tables (see csvrow.h). */
#include "csvrow.h"

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
