/* json_tree.c -- the JSON reader of json_tree.h: recursive descent over the
 * text, nodes in one growing array (indices, so growing moves nothing). */
#include "json_tree.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *p, *end;
    bk_json *t;
    int depth;
} parser;

static void ws(parser *ps)
{
    while (ps->p < ps->end && (*ps->p == ' ' || *ps->p == '\n' || *ps->p == '\t' || *ps->p == '\r'))
        ps->p++;
}

static int node(parser *ps, int type)
{
    bk_json *t = ps->t;
    if (t->n == t->cap) {
        int cap = t->cap ? 2 * t->cap : 64;
        bk_jnode *v = realloc(t->node, (size_t)cap * sizeof *v);
        if (!v)
            return -1;
        t->node = v;
        t->cap = cap;
    }
    t->node[t->n] = (bk_jnode){.type = type, .first = -1, .next = -1};
    return t->n++;
}

static int value(parser *ps);

static int string(parser *ps)
{
    if (ps->p >= ps->end || *ps->p != '"')
        return -1;
    const char *s = ++ps->p;
    while (ps->p < ps->end && *ps->p != '"') {
        if (*ps->p == '\\')
            ps->p++;
        ps->p++;
    }
    if (ps->p >= ps->end)
        return -1;
    int i = node(ps, BK_JSTR);
    if (i < 0)
        return -1;
    ps->t->node[i].text = s;
    ps->t->node[i].len = (size_t)(ps->p - s);
    ps->p++;
    return i;
}

/* The members or items of an object ('}') or array (']') after its bracket. */
static int children(parser *ps, int parent, char close, int keyed)
{
    int last = -1;
    ws(ps);
    if (ps->p < ps->end && *ps->p == close) {
        ps->p++;
        return 0;
    }
    for (;;) {
        int k = -1;
        if (keyed) {
            ws(ps);
            if ((k = string(ps)) < 0)
                return -1;
            ws(ps);
            if (ps->p >= ps->end || *ps->p++ != ':')
                return -1;
        }
        int v = value(ps);
        if (v < 0)
            return -1;
        int head = keyed ? k : v;
        if (keyed)
            ps->t->node[k].next = v;
        if (last < 0)
            ps->t->node[parent].first = head;
        else
            ps->t->node[last].next = head;
        last = v;
        ps->t->node[parent].count++;
        ws(ps);
        if (ps->p >= ps->end)
            return -1;
        char c = *ps->p++;
        if (c == close)
            return 0;
        if (c != ',')
            return -1;
    }
}

static int value(parser *ps)
{
    ws(ps);
    if (ps->p >= ps->end || ++ps->depth > 64)
        return -1;
    int i = -1;
    char c = *ps->p;
    if (c == '{' || c == '[') {
        ps->p++;
        i = node(ps, c == '{' ? BK_JOBJ : BK_JARR);
        if (i < 0 || children(ps, i, c == '{' ? '}' : ']', c == '{') < 0)
            return -1;
    } else if (c == '"') {
        i = string(ps);
    } else {
        static const struct { const char *word; int type; } words[] = {
            {"null", BK_JNULL}, {"false", BK_JFALSE}, {"true", BK_JTRUE}};
        for (int w = 0; w < 3; w++) {
            size_t n = strlen(words[w].word);
            if ((size_t)(ps->end - ps->p) >= n && !memcmp(ps->p, words[w].word, n)) {
                ps->p += n;
                ps->depth--;
                return node(ps, words[w].type);
            }
        }
        const char *s = ps->p;
        while (ps->p < ps->end && strchr("+-0123456789.eE", *ps->p))
            ps->p++;
        if (ps->p == s)
            return -1;
        i = node(ps, BK_JNUM);
        if (i >= 0) {
            ps->t->node[i].text = s;
            ps->t->node[i].len = (size_t)(ps->p - s);
        }
    }
    ps->depth--;
    return i;
}

int bk_json_parse(const char *text, size_t len, bk_json *t)
{
    *t = (bk_json){0};
    parser ps = {text, text + len, t, 0};
    if (value(&ps) != 0)
        return -1;
    ws(&ps);
    return ps.p == ps.end ? 0 : -1;
}

void bk_json_free(bk_json *t)
{
    free(t->node);
    *t = (bk_json){0};
}

int bk_json_get(const bk_json *t, int obj, const char *key)
{
    if (obj < 0 || t->node[obj].type != BK_JOBJ)
        return -1;
    size_t n = strlen(key);
    for (int k = t->node[obj].first; k >= 0; k = t->node[t->node[k].next].next) {
        const bk_jnode *kn = &t->node[k];
        if (kn->len == n && !memcmp(kn->text, key, n))
            return kn->next;
    }
    return -1;
}

double bk_json_num(const bk_json *t, int i)
{
    if (i < 0 || t->node[i].type != BK_JNUM)
        return NAN;
    char buf[64];
    size_t n = t->node[i].len < sizeof buf - 1 ? t->node[i].len : sizeof buf - 1;
    memcpy(buf, t->node[i].text, n);
    buf[n] = '\0';
    return strtod(buf, NULL);
}

int bk_json_truthy(const bk_json *t, int i)
{
    if (i < 0)
        return 0;
    const bk_jnode *v = &t->node[i];
    switch (v->type) {
    case BK_JTRUE: return 1;
    case BK_JNUM: return bk_json_num(t, i) != 0;
    case BK_JSTR: return v->len > 0;
    case BK_JARR: case BK_JOBJ: return v->count > 0;
    default: return 0;
    }
}
