/* json.c -- JSON values for summary.json, and the merge of two entries under one key (see json.h). */
#include "base/json.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void bk_json_string(FILE *fp, const char *s)
{
    fputc('"', fp);
    for (; *s; ++s) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(fp, "\\%c", c);
        else if (c < 0x20)
            fprintf(fp, "\\u%04x", c);
        else
            fputc(c, fp);
    }
    fputc('"', fp);
}

void bk_json_num(FILE *fp, double v)
{
    if (isfinite(v))
        fprintf(fp, "%.17g", v);
    else
        fprintf(fp, "null");
}

void bk_json_vec3(FILE *fp, const double *v)
{
    fputc('[', fp);
    for (int i = 0; i < 3; ++i) {
        fprintf(fp, "%s", i ? ", " : "");
        bk_json_num(fp, v[i]);
    }
    fputc(']', fp);
}

void bk_json_repair(const char *p, char *out)
{
    while (*p) {
        if (*p == '"') {                         /* a string: copied as it is */
            *out++ = *p++;
            while (*p && *p != '"') {
                if (*p == '\\' && p[1])
                    *out++ = *p++;
                *out++ = *p++;
            }
            if (*p)
                *out++ = *p++;
        } else if (isdigit((unsigned char)*p) || *p == '.' ||
                   ((*p == '-' || *p == '+') && (isdigit((unsigned char)p[1]) || p[1] == '.'))) {
            do                                   /* a number, its exponent included */
                *out++ = *p++;
            while (isalnum((unsigned char)*p) || *p == '.' || ((*p == '-' || *p == '+') && (p[-1] == 'e' ||
                                                                                         p[-1] == 'E')));
        } else if (isalpha((unsigned char)*p) || ((*p == '-' || *p == '+') && isalpha((unsigned char)p[1]))) {
            const char *w = p + !isalpha((unsigned char)*p), *e = w;
            while (isalnum((unsigned char)*e))
                ++e;
            size_t n = (size_t)(e - p);
            if ((n == 4 && !strncmp(p, "true", 4)) || (n == 5 && !strncmp(p, "false", 5)) ||
                (n == 4 && !strncmp(p, "null", 4)))
                memcpy(out, p, n), out += n;
            else
                memcpy(out, "null", 4), out += 4;
            p = e;
        } else {
            *out++ = *p++;
        }
    }
    *out = 0;
}

/* The end of the JSON value starting at p (at its first character): past a
 * string, or at the ',' '}' or ']' that ends it at its own depth. */
static const char *value_end(const char *p)
{
    int depth = 0;
    for (; *p; ++p) {
        if (*p == '"') {
            for (++p; *p && *p != '"'; ++p)
                if (*p == '\\' && p[1])
                    ++p;
            if (!*p)
                return p;
        } else if (*p == '{' || *p == '[') {
            depth++;
        } else if (*p == '}' || *p == ']') {
            if (depth-- == 0)
                return p;
        } else if (*p == ',' && depth == 0) {
            return p;
        }
    }
    return p;
}

typedef struct member {
    const char *name, *value;        /* name: past its opening quote */
    size_t nlen, vlen;
} member;

/* The top-level members of the object text s (at most max); their count, or
 * -1 when s is not an object of "name": value members. */
static int members(const char *s, member *m, int max)
{
    const char *p = s;
    while (*p == ' ' || *p == '\n')
        ++p;
    if (*p++ != '{')
        return -1;
    int n = 0;
    for (;;) {
        while (*p == ' ' || *p == '\n' || *p == ',')
            ++p;
        if (*p == '}')
            return n;
        if (*p != '"' || n == max)
            return -1;
        const char *name = p + 1, *q = strchr(name, '"');
        if (!q)
            return -1;
        for (p = q + 1; *p == ' ' || *p == ':'; ++p) {
        }
        const char *end = value_end(p);
        if (!*end)
            return -1;
        m[n++] = (member){.name = name, .nlen = (size_t)(q - name), .value = p, .vlen = (size_t)(end - p)};
        p = end;
    }
}

static int named(const member *m, const char *name)
{
    return m->nlen == strlen(name) && strncmp(m->name, name, m->nlen) == 0;
}

/* A member's number, or NAN for null (or anything that is not a number). */
static double number(const member *m)
{
    char *end;
    double v = strtod(m->value, &end);
    return end == m->value ? NAN : v;
}

char *bk_json_merge(const char *a, const char *b)
{
    member ma[64], mb[64];
    const int na = members(a, ma, 64), nb = members(b, mb, 64);
    if (na < 0 || nb < 0)
        return NULL;
    size_t cap = strlen(a) + strlen(b) + 64 * 32, len = 1;
    char *out = malloc(cap);
    if (!out)
        return NULL;
    strcpy(out, "{");
    for (int i = 0; i < na + nb; ++i) {
        const member *m = i < na ? &ma[i] : &mb[i - na];
        const member *other = NULL, *them = i < na ? mb : ma;
        for (int j = 0; j < (i < na ? nb : na); ++j)
            if (them[j].nlen == m->nlen && strncmp(them[j].name, m->name, m->nlen) == 0)
                other = &them[j];
        if (i >= na && other)                   /* taken with the first's */
            continue;
        len += (size_t)snprintf(out + len, cap - len, "%s\"%.*s\": ", len > 1 ? ", " : "", (int)m->nlen, m->name);
        const int lo = named(m, "min_distance"), hi = named(m, "max_penetration");
        if (other && (lo || hi)) {
            const double u = number(m), v = number(other);
            const double w = isnan(u) ? v : isnan(v) ? u : lo ? fmin(u, v) : fmax(u, v);
            if (isnan(w))
                len += (size_t)snprintf(out + len, cap - len, "null");
            else
                len += (size_t)snprintf(out + len, cap - len, "%.17g", w);
        } else {
            len += (size_t)snprintf(out + len, cap - len, "%.*s", (int)m->vlen, m->value);
        }
    }
    snprintf(out + len, cap - len, "}");
    return out;
}
