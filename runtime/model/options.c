/* options.c -- the option records of the model file (scene, static,
 * continuation, dynamic, output, modal), read by the descriptor table
 * BK_OPTION_FIELDS of out/kernels/bk_options.h, generated from the options
 * schema (gen/options_schema.py): no option is named here.  Each field is
 * `key=value` in table order; integers and booleans are checked against their
 * range, numbers for being finite and in range, choices against their names
 * (stored as the index, the enum of bk_options.h). */
#include <stddef.h>
#include <string.h>

#include "model/reader.h"

typedef struct option_field {
    const char *record, *key;
    int type;                    /* enum bk_option_type */
    size_t offset, size;         /* of the member in bk_model */
    double lo;
    int lo_open;                 /* 1: lo itself is out of range */
    double hi;
    const char *names;           /* choices, space-separated */
} option_field;

#define BK_FIELD(rec, key, type, member, lo, lo_open, hi, names) \
    {rec, key, type, offsetof(bk_model, member), sizeof(((bk_model *)0)->member), lo, lo_open, hi, names},
static const option_field fields[] = {BK_OPTION_FIELDS(BK_FIELD)};
#undef BK_FIELD

/* The index of `v` among the space-separated `names`, -1: none. */
static int choice_index(const char *names, const char *v)
{
    size_t n = strlen(v);
    for (int i = 0; *names; ++i) {
        size_t w = strcspn(names, " ");
        if (w == n && strncmp(names, v, n) == 0)
            return i;
        names += w + (names[w] == ' ');
    }
    return -1;
}

static void read_field(bk_reader *r, bk_model *m, const option_field *f)
{
    char *p = (char *)m + f->offset;
    if (f->type == BK_OPT_INT || f->type == BK_OPT_BOOL) {
        int v = rd_fint(r, f->record, f->key, (int)f->lo, (int)f->hi);
        memcpy(p, &v, sizeof v);
        return;
    }
    if (f->type == BK_OPT_FLOAT) {
        double v = rd_fnum(r, f->record, f->key);
        if (!r->failed && (v < f->lo || (f->lo_open && v <= f->lo) || v > f->hi))
            rd_fail(r, "%s.%s: expected a number in %s%g, %g], found %.17g", f->record, f->key,
                    f->lo_open ? "(" : "[", f->lo, f->hi, v);
        memcpy(p, &v, sizeof v);
        return;
    }
    const char *t = rd_field(r, f->record, f->key);
    if (!t)
        return;
    if (f->type == BK_OPT_STR) {
        if (strlen(t) >= f->size)
            rd_fail(r, "%s.%s longer than %zu characters", f->record, f->key, f->size - 1);
        else
            memcpy(p, t, strlen(t) + 1);
        return;
    }
    int v = choice_index(f->names, t);
    if (v < 0)
        rd_fail(r, "%s.%s: '%s' is not supported by this solver (expected one of: %s)", f->record, f->key, t,
                f->names);
    memcpy(p, &v, sizeof v);
}

void bk_model_read_options(bk_reader *r, bk_model *m)
{
    const char *record = NULL;
    for (size_t i = 0; i < sizeof fields / sizeof fields[0] && !r->failed; ++i) {
        if (!record || strcmp(record, fields[i].record) != 0) {
            record = fields[i].record;
            rd_expect(r, record);
        }
        read_field(r, m, &fields[i]);
    }
}
