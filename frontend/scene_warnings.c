/* scene_warnings.c -- scene warnings into summary.json (scene_warnings.h).
 * The solver writes the "warnings" array one string a line, so the file is
 * edited as text: the scene's strings first, then the solver's that are not
 * among them, each on its own line. */
#define _POSIX_C_SOURCE 200809L
#include "scene_warnings.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define OPEN "\n  \"warnings\": ["

typedef struct {
    char *s;
    size_t n, cap;
    int failed;
} buf;

static void put(buf *b, const char *s, size_t n)
{
    if (b->failed)
        return;
    if (b->n + n + 1 > b->cap) {
        size_t cap = (b->n + n + 1) * 2;
        char *p = realloc(b->s, cap);
        if (!p) {
            b->failed = 1;
            return;
        }
        b->s = p;
        b->cap = cap;
    }
    memcpy(b->s + b->n, s, n);
    b->n += n;
    b->s[b->n] = '\0';
}

/* s as the solver writes a JSON string: '"' and '\' escaped, control
 * characters as \u00XX, everything else as it is. */
static void json_string(buf *b, const char *s)
{
    put(b, "\"", 1);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') {
            char e[2] = {'\\', (char)c};
            put(b, e, 2);
        } else if (c < 0x20) {
            char e[8];
            snprintf(e, sizeof e, "\\u%04x", c);
            put(b, e, 6);
        } else {
            put(b, (const char *)&c, 1);
        }
    }
    put(b, "\"", 1);
}

/* Is the line [s, s + n) (trimmed) among the first k items of the list? */
static int listed(char *const *items, const size_t *lens, int k, const char *s, size_t n)
{
    for (int i = 0; i < k; i++)
        if (lens[i] == n && !memcmp(items[i], s, n))
            return 1;
    return 0;
}

int bk_add_scene_warnings(const char *run_dir, char *const *warnings, int n)
{
    if (n <= 0)
        return 0;
    char path[4096], tmp[4200];
    snprintf(path, sizeof path, "%s/summary.json", run_dir);
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    buf text = {0};
    char chunk[8192];
    size_t got;
    while ((got = fread(chunk, 1, sizeof chunk, f)) > 0)
        put(&text, chunk, got);
    fclose(f);
    int rc = -1;
    buf out = {0}, ours = {0};
    char **item = calloc((size_t)n, sizeof *item);
    size_t *len = calloc((size_t)n, sizeof *len);
    char *open = text.s ? strstr(text.s, OPEN) : NULL;
    char *end = open ? strstr(open, "],\n") : NULL;
    if (!item || !len || !end || text.failed)
        goto done;
    /* the scene's strings, encoded, one after another in `ours` */
    size_t *at = calloc((size_t)n, sizeof *at);
    if (!at)
        goto done;
    for (int i = 0; i < n; i++) {
        at[i] = ours.n;
        json_string(&ours, warnings[i]);
        len[i] = ours.n - at[i];
    }
    for (int i = 0; i < n && !ours.failed; i++)
        item[i] = ours.s + at[i];
    free(at);
    if (ours.failed)
        goto done;
    char *body = open + strlen(OPEN);
    put(&out, text.s, (size_t)(body - text.s));
    for (int i = 0; i < n; i++) {
        put(&out, i ? ",\n    " : "\n    ", i ? 6 : 5);
        put(&out, item[i], len[i]);
    }
    int count = n;
    for (char *line = body; line < end;) {
        char *nl = memchr(line, '\n', (size_t)(end - line));
        char *stop = nl ? nl : end;
        char *a = line, *b = stop;
        while (a < b && (*a == ' ' || *a == '\t' || *a == '\r'))
            a++;
        while (b > a && (b[-1] == ' ' || b[-1] == '\t' || b[-1] == '\r'))
            b--;
        while (b > a && b[-1] == ',')
            b--;
        if (b > a && !listed(item, len, n, a, (size_t)(b - a))) {
            put(&out, count ? ",\n    " : "\n    ", count ? 6 : 5);
            put(&out, a, (size_t)(b - a));
            count++;
        }
        line = nl ? nl + 1 : end;
    }
    put(&out, "\n  ", 3);
    put(&out, end, strlen(end));
    if (out.failed)
        goto done;
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    f = fopen(tmp, "wb");
    if (!f)
        goto done;
    size_t w = fwrite(out.s, 1, out.n, f);
    if (fclose(f) == 0 && w == out.n && rename(tmp, path) == 0)
        rc = 0;
done:
    free(item);
    free(len);
    free(text.s);
    free(out.s);
    free(ours.s);
    return rc;
}
