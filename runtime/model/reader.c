/* reader.c -- the model file's tokens: loading the file, the next token, named
 * fields `key=value`, numbers and integers with their ranges, and the one error
 * line (see reader.h). */
#include "model/reader.h"
#include "base/bigalloc.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* Reads the whole file r->path into r->buf (in pieces: its size need not be
 * known).  Returns 0, or -1 after one line to r->err. */
int rd_load(bk_reader *r)
{
    const char *path = r->path;
    FILE *err = r->err;
    FILE *fp = fopen(path, "r");
    if (!fp) {
        fprintf(err, "error: %s: cannot open model file: %s\n", path, strerror(errno));
        return -1;
    }
    /* the whole file in memory (read in pieces: its size need not be known) */
    size_t cap = 1 << 16;
    r->buf = bk_big_malloc(cap);
    while (r->buf) {
        r->len += fread(r->buf + r->len, 1, cap - r->len - 1, fp);
        if (r->len < cap - 1)
            break;
        char *nb = bk_big_realloc(r->buf, cap *= 2);
        if (!nb)
            free(r->buf);
        r->buf = nb;
    }
    int bad = !r->buf || ferror(fp);
    fclose(fp);
    if (bad) {
        fprintf(err, "error: %s: %s\n", path, r->buf ? "cannot read model file" : "out of memory");
        free(r->buf);
        return -1;
    }
    r->buf[r->len] = '\0';
    return 0;
}



void rd_fail(bk_reader *r, const char *fmt, ...)
{
    if (r->failed)
        return;
    r->failed = 1;
    va_list ap;
    va_start(ap, fmt);
    fprintf(r->err, "error: %s: ", r->path);
    vfprintf(r->err, fmt, ap);
    fprintf(r->err, "\n");
    va_end(ap);
}

static int is_space(char c)
{
    return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* The next whitespace-separated token (at most 255 bytes, as "%255s" reads:
 * a longer one goes on in the next token), or NULL at the end.  (A model file
 * has thousands of tokens: reading each with fscanf, and making each one's
 * error-message name whether or not it was needed, were a tenth of a small
 * model's run.) */
const char *rd_next_tok(bk_reader *r)
{
    if (r->failed)
        return NULL;
    const char *p = r->buf + r->pos, *e = r->buf + r->len;
    while (p < e && is_space(*p))
        ++p;
    if (p == e)
        return NULL;
    size_t n = 0;
    while (p + n < e && n < sizeof r->tok - 1 && !is_space(p[n]))
        ++n;
    memcpy(r->tok, p, n);
    r->tok[n] = '\0';
    r->pos = (size_t)(p + n - r->buf);
    return r->tok;
}

/* next_tok, and an error naming `what` at the end of the file. */
const char *rd_next(bk_reader *r, const char *what)
{
    const char *t = rd_next_tok(r);
    if (!t && !r->failed)
        rd_fail(r, "model file ends early: expected %s", what);
    return t;
}

void rd_expect(bk_reader *r, const char *kw)
{
    const char *t = rd_next(r, kw);
    if (t && strcmp(t, kw) != 0)
        rd_fail(r, "expected keyword '%s', found '%s'", kw, t);
}

/* The value of the named field `rec.key` (token "key=value"). */
const char *rd_field(bk_reader *r, const char *rec, const char *key)
{
    const char *t = rd_next_tok(r);
    if (!t) {
        if (!r->failed)
            rd_fail(r, "model file ends early: expected field %s.%s", rec, key);
        return NULL;
    }
    size_t n = strlen(key);
    if (strncmp(t, key, n) != 0 || t[n] != '=') {
        rd_fail(r, "record '%s': expected field '%s=...', found '%s' (a model file of another beamkit version? "
                "rerun ./build.sh run)", rec, key, t);
        return NULL;
    }
    return t + n + 1;
}

/* The name of a value in an error message: `what`, or "rec.key" of a named
 * field (made only for the message). */
static const char *value_name(char *buf, size_t n, const char *what, const char *rec, const char *key)
{
    if (!rec)
        return what;
    snprintf(buf, n, "%s.%s", rec, key);
    return buf;
}

static double parse_num_of(bk_reader *r, const char *t, const char *what, const char *rec, const char *key)
{
    if (!t)
        return 0.0;
    char *end;
    errno = 0;
    double v = strtod(t, &end);
    if (*end != '\0' || errno == ERANGE || !isfinite(v)) {
        char name[128];
        rd_fail(r, "%s: expected a finite number, found '%s'", value_name(name, sizeof name, what, rec, key), t);
        return 0.0;
    }
    return v;
}

/* 1 when the token t is what strtol(t, &end, 10) reads whole (*end == '\0')
 * as a value below LONG_MAX / 10 in magnitude, the value in *v; else 0 (a
 * larger one is outside any int range as well).  (strtol's locale and base handling were a
 * fifth of reading a 10,000-element model; a token has no white space.) */
static int dec_int(const char *t, long *v)
{
    const char *p = t;
    const int neg = *p == '-';
    if (*p == '+' || *p == '-')
        ++p;
    if (!*p) {                                       /* strtol: no digits, end = t */
        *v = 0;
        return p == t;
    }
    long a = 0;
    for (; *p; ++p) {
        if (*p < '0' || *p > '9' || a > (LONG_MAX - 9) / 10)
            return 0;
        a = 10 * a + (*p - '0');
    }
    *v = neg ? -a : a;
    return 1;
}

static int parse_int_of(bk_reader *r, const char *t, const char *what, const char *rec, const char *key, int lo, int hi)
{
    if (!t)
        return lo;
    long v;
    if (!dec_int(t, &v) || v < lo || v > hi) {
        char name[128];
        rd_fail(r, "%s: expected an integer in [%d, %d], found '%s'", value_name(name, sizeof name, what, rec, key),
             lo, hi, t);
        return lo;
    }
    return (int)v;
}

double rd_parse_num(bk_reader *r, const char *what, const char *t)
{
    return parse_num_of(r, t, what, NULL, NULL);
}

double rd_fnum(bk_reader *r, const char *rec, const char *key)
{
    return parse_num_of(r, rd_field(r, rec, key), NULL, rec, key);
}

int rd_fint(bk_reader *r, const char *rec, const char *key, int lo, int hi)
{
    return parse_int_of(r, rd_field(r, rec, key), NULL, rec, key, lo, hi);
}

double rd_num(bk_reader *r, const char *what)
{
    return rd_parse_num(r, what, rd_next(r, what));
}

int rd_inum(bk_reader *r, const char *what, int lo, int hi)
{
    return parse_int_of(r, rd_next(r, what), what, NULL, NULL, lo, hi);
}

void *rd_xcalloc(bk_reader *r, size_t n, size_t size)
{
    if (r->failed)
        return NULL;
    void *p = bk_big_calloc(n ? n : 1, size);
    if (!p)
        rd_fail(r, "out of memory (%zu x %zu bytes)", n, size);
    return p;
}

void rd_copy_token(bk_reader *r, char *dst, size_t n, const char *what)
{
    const char *t = rd_next(r, what);
    if (t && strlen(t) >= n)
        rd_fail(r, "%s longer than %zu characters", what, n - 1);
    else if (t)
        memcpy(dst, t, strlen(t) + 1);
}

/* The rest of the current line after one space (a text record such as
 * `warning TEXT`): "\\" and "\n" in it read as a backslash and a newline
 * (gen/scene/model_file.py _line).  Malloc'd; NULL after an error. */
char *rd_line(bk_reader *r)
{
    if (r->failed)
        return NULL;
    const char *p = r->buf + r->pos, *e = r->buf + r->len;
    if (p < e && *p == ' ')
        ++p;
    const char *nl = memchr(p, '\n', (size_t)(e - p));
    size_t n = nl ? (size_t)(nl - p) : (size_t)(e - p);
    char *s = rd_xcalloc(r, n + 1, 1);
    if (!s)
        return NULL;
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) {
        char c = p[i];
        if (c == '\\' && i + 1 < n && (p[i + 1] == '\\' || p[i + 1] == 'n'))
            c = p[++i] == 'n' ? '\n' : '\\';
        s[k++] = c;
    }
    s[k] = '\0';
    r->pos = (size_t)(p + n - r->buf);
    return s;
}
