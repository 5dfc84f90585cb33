/* contact_broad.c -- overlapping boxes by a spatial hash (contact_broad.h). */
#include "assembly/contact_broad.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

typedef struct cell_entry {
    uint64_t key;
    int box;
} cell_entry;

static int cmp_entry(const void *a, const void *b)
{
    const cell_entry *x = a, *y = b;
    if (x->key != y->key)
        return (x->key > y->key) - (x->key < y->key);
    return (x->box > y->box) - (x->box < y->box);
}

static int cmp_pair(const void *a, const void *b)
{
    const int *x = a, *y = b;
    return x[0] != y[0] ? (x[0] > y[0]) - (x[0] < y[0]) : (x[1] > y[1]) - (x[1] < y[1]);
}

/* A cell's key: its three integer coordinates mixed (equal keys of different
 * cells only cost a comparison of boxes that do not overlap). */
static uint64_t cell_key(int64_t i, int64_t j, int64_t k)
{
    uint64_t h = (uint64_t)i * 0x9E3779B97F4A7C15ULL;
    h ^= (uint64_t)j * 0xC2B2AE3D27D4EB4FULL + (h << 6) + (h >> 2);
    h ^= (uint64_t)k * 0x165667B19E3779F9ULL + (h << 6) + (h >> 2);
    return h;
}

static int overlap(const bk_box *a, const bk_box *b)
{
    for (int d = 0; d < 3; ++d)
        if (a->hi[d] < b->lo[d] || b->hi[d] < a->lo[d])
            return 0;
    return 1;
}

static int push(int **pairs, int *cap, int n, int i, int j)
{
    if (n + 1 > *cap) {
        int c = 2 * *cap + 64;
        int *p = realloc(*pairs, 2 * (size_t)c * sizeof *p);
        if (!p)
            return -1;
        *pairs = p, *cap = c;
    }
    (*pairs)[2 * n] = i, (*pairs)[2 * n + 1] = j;
    return 0;
}

int bk_broad_pairs(const bk_box *box, int n, int **pairs, int *cap)
{
    if (n < 2)
        return 0;
    double h = 0.0, origin[3] = {INFINITY, INFINITY, INFINITY};
    for (int b = 0; b < n; ++b)
        for (int d = 0; d < 3; ++d) {
            h = fmax(h, box[b].hi[d] - box[b].lo[d]);
            origin[d] = fmin(origin[d], box[b].lo[d]);
        }
    if (!(h > 0.0) || !isfinite(h))
        h = 1.0;
    cell_entry *ent = malloc(8 * (size_t)n * sizeof *ent);
    if (!ent)
        return -1;
    size_t ne = 0;
    for (int b = 0; b < n; ++b) {
        int64_t lo[3], hi[3];
        for (int d = 0; d < 3; ++d) {
            lo[d] = (int64_t)floor((box[b].lo[d] - origin[d]) / h);
            hi[d] = (int64_t)floor((box[b].hi[d] - origin[d]) / h);
            if (hi[d] > lo[d] + 1)          /* (round-off: a box spans at most two cells of its size) */
                hi[d] = lo[d] + 1;
        }
        for (int64_t i = lo[0]; i <= hi[0]; ++i)
            for (int64_t j = lo[1]; j <= hi[1]; ++j)
                for (int64_t k = lo[2]; k <= hi[2]; ++k)
                    ent[ne++] = (cell_entry){cell_key(i, j, k), b};
    }
    qsort(ent, ne, sizeof *ent, cmp_entry);
    int np = 0;
    for (size_t a = 0; a < ne;) {
        size_t e = a;
        while (e < ne && ent[e].key == ent[a].key)
            ++e;
        for (size_t x = a; x < e; ++x)
            for (size_t y = x + 1; y < e; ++y)
                if (ent[x].box != ent[y].box && overlap(&box[ent[x].box], &box[ent[y].box])) {
                    if (push(pairs, cap, np, ent[x].box, ent[y].box) != 0) {
                        free(ent);
                        return -1;
                    }
                    ++np;
                }
        a = e;
    }
    free(ent);
    if (np > 1)
        qsort(*pairs, (size_t)np, 2 * sizeof **pairs, cmp_pair);
    int u = 0;
    for (int k = 0; k < np; ++k)
        if (u == 0 || cmp_pair(*pairs + 2 * k, *pairs + 2 * (u - 1)) != 0) {
            (*pairs)[2 * u] = (*pairs)[2 * k], (*pairs)[2 * u + 1] = (*pairs)[2 * k + 1];
            ++u;
        }
    return u;
}
