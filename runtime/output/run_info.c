/* run_info.c -- warnings, stability events and critical points of a run, in
 * growable storage (see run_info.h). */
#include "output/run_info.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"

/* Room for n + 1 items of size sz in *p (capacity *cap); 0, or -1 when out of memory. */
static int room(void **p, int *cap, int n, size_t sz)
{
    if (n < *cap)
        return 0;
    int c = *cap ? 2 * *cap : 8;
    void *q = realloc(*p, (size_t)c * sz);
    if (!q)
        return -1;
    *p = q;
    *cap = c;
    return 0;
}

void bk_warn(bk_run_info *info, FILE *console, const char *scene, const char *fmt, ...)
{
    char text[BK_WARNING_LEN];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    for (int k = 0; k < info->nwarning; ++k)
        if (strcmp(info->warnings[k], text) == 0)
            return;
    char *copy = NULL;
    if (info->nwarning >= BK_MAX_WARNINGS ||
        room((void **)&info->warnings, &info->warning_cap, info->nwarning, sizeof *info->warnings) != 0 ||
        !(copy = malloc(strlen(text) + 1))) {
        info->warnings_dropped++;
        return;
    }
    strcpy(copy, text);
    info->warnings[info->nwarning++] = copy;
    if (console)
        fprintf(console, "warning: %s: %s\n", scene, text);
}

bk_stability_event *bk_run_add_stability(bk_run_info *info)
{
    if (room((void **)&info->stability, &info->stability_cap, info->nstability, sizeof *info->stability) != 0)
        return NULL;
    bk_stability_event *ev = &info->stability[info->nstability++];
    memset(ev, 0, sizeof *ev);
    return ev;
}

bk_critical_point *bk_run_insert_critical(bk_run_info *info, int at)
{
    if (room((void **)&info->critical, &info->critical_cap, info->ncritical, sizeof *info->critical) != 0)
        return NULL;
    memmove(info->critical + at + 1, info->critical + at, (size_t)(info->ncritical - at) * sizeof *info->critical);
    info->ncritical++;
    memset(&info->critical[at], 0, sizeof info->critical[at]);
    return &info->critical[at];
}

int bk_run_summary(bk_run_info *info, const char *key, const char *json)
{
    if (room((void **)&info->summary_key, &info->summary_cap, info->nsummary, sizeof *info->summary_key) != 0)
        return -1;
    int cap = info->summary_cap;         /* the second array follows the first's capacity */
    char **js = realloc(info->summary_json, (size_t)cap * sizeof *js);
    if (!js)
        return -1;
    info->summary_json = js;
    char *k = malloc(strlen(key) + 1), *v = malloc(2 * strlen(json) + 1);
    if (!k || !v) {
        free(k);
        free(v);
        return -1;
    }
    strcpy(k, key);
    bk_json_repair(json, v);          /* summary.json stays JSON whatever the text held (nan: null) */
    for (int e = 0; e < info->nsummary; ++e)
        if (strcmp(info->summary_key[e], key) == 0) {   /* a second entry under one key: merged */
            char *both = bk_json_merge(info->summary_json[e], v);
            free(k);
            free(v);
            if (!both)
                return -1;
            free(info->summary_json[e]);
            info->summary_json[e] = both;
            return 0;
        }
    info->summary_key[info->nsummary] = k;
    info->summary_json[info->nsummary++] = v;
    return 0;
}

void bk_run_info_free(bk_run_info *info)
{
    for (int k = 0; k < info->nsummary; ++k) {
        free(info->summary_key[k]);
        free(info->summary_json[k]);
    }
    free(info->summary_key);
    free(info->summary_json);
    info->summary_key = info->summary_json = NULL;
    info->nsummary = info->summary_cap = 0;
    for (int k = 0; k < info->nwarning; ++k)
        free(info->warnings[k]);
    free(info->warnings);
    free(info->stability);
    free(info->critical);
    info->warnings = NULL;
    info->stability = NULL;
    info->critical = NULL;
    info->nwarning = info->warning_cap = 0;
    info->nstability = info->stability_cap = 0;
    info->ncritical = info->critical_cap = 0;
}
