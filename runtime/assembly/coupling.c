/* coupling.c -- coupling blocks between elements that nothing else couples
 * (beam-to-beam contact: elements of two beams, or far parts of one, whose
 * pairs are found as the run goes): the pattern made anew when they need
 * entries it lacks, and the scatter of a coupling block (system.h). */
#include <stdlib.h>
#include <string.h>

#include "assembly/system.h"
#include "assembly/system_impl.h"

static int cmp_pair(const void *a, const void *b)
{
    const int *x = a, *y = b;
    return x[0] != y[0] ? (x[0] > y[0]) - (x[0] < y[0]) : (x[1] > y[1]) - (x[1] < y[1]);
}

static int has_pair(const bk_system *s, int a, int b)
{
    const int key[2] = {a, b};
    return s->ncouple > 0 && bsearch(key, s->couple, (size_t)s->ncouple, 2 * sizeof *s->couple, cmp_pair) != NULL;
}

/* 1 when the pattern has every entry of the block rows of ea, columns of eb. */
static int block_present(const bk_system *s, int ea, int eb)
{
    const bk_model *m = s->m;
    const int na = bk_elem_type(m, ea)->ndof, nb = bk_elem_type(m, eb)->ndof;
    for (int b = 0; b < nb; ++b) {
        const int col = s->eq[m->elems[eb].dofs[b]];
        for (int a = 0; a < na && col >= 0; ++a) {
            const int row = s->eq[m->elems[ea].dofs[a]];
            if (row >= 0 && bk_find_slot(s, row, col) < 0)
                return 0;
        }
    }
    return 1;
}

int bk_system_couple(bk_system *s, int n, const int *pairs)
{
    int grow = 0, added = 0;
    for (int k = 0; k < n; ++k) {
        int a = pairs[2 * k] < pairs[2 * k + 1] ? pairs[2 * k] : pairs[2 * k + 1];
        int b = pairs[2 * k] < pairs[2 * k + 1] ? pairs[2 * k + 1] : pairs[2 * k];
        if (a == b || has_pair(s, a, b))
            continue;
        if (s->ncouple + added + 1 > s->capcouple) {
            int cap = 2 * (s->ncouple + added + 1) + 16;
            int *c = realloc(s->couple, 2 * (size_t)cap * sizeof *c);
            if (!c)
                return -1;
            s->couple = c, s->capcouple = cap;
        }
        s->couple[2 * (s->ncouple + added)] = a;
        s->couple[2 * (s->ncouple + added) + 1] = b;
        ++added;
        grow |= !block_present(s, a, b);
    }
    if (!added)
        return 0;
    /* sorted without repeats (a pair may come twice in one call) */
    int nc = s->ncouple + added, u = 0;
    qsort(s->couple, (size_t)nc, 2 * sizeof *s->couple, cmp_pair);
    for (int k = 0; k < nc; ++k)
        if (u == 0 || cmp_pair(s->couple + 2 * k, s->couple + 2 * (u - 1)) != 0) {
            s->couple[2 * u] = s->couple[2 * k], s->couple[2 * u + 1] = s->couple[2 * k + 1];
            ++u;
        }
    s->ncouple = u;
    if (!grow)
        return 0;
    bk_free_pattern(s);
    bk_free_parts(s);
    if (bk_make_pattern(s) != 0 || bk_make_parts(s) != 0)
        return -1;
    bk_free_incidence(s);
    s->pattern_gen++;
    return 1;
}

int bk_scatter_coupling(const bk_system *s, int ea, int eb, const double *K, double c, double *Ax)
{
    const bk_model *m = s->m;
    const int na = bk_elem_type(m, ea)->ndof, nb = bk_elem_type(m, eb)->ndof;
    int row[BK_MAX_ELEMENT_DOF], loc[BK_MAX_ELEMENT_DOF], nr = 0, missing = 0;
    for (int a = 0; a < na; ++a) {           /* ea's equations in increasing order (insertion), with their DOF */
        const int r = s->eq[m->elems[ea].dofs[a]];
        if (r < 0)
            continue;
        int t = nr++;
        for (; t > 0 && row[t - 1] > r; --t)
            row[t] = row[t - 1], loc[t] = loc[t - 1];
        row[t] = r, loc[t] = a;
    }
    if (nr == 0)
        return 0;
    for (int b = 0; b < nb; ++b) {
        const int col = s->eq[m->elems[eb].dofs[b]];
        if (col < 0)
            continue;
        /* the column's rows are sorted: a search for the first, then a walk along them */
        const int end = s->Ap[col + 1];
        int lo = s->Ap[col], hi = end;
        while (lo < hi) {
            const int mid = lo + (hi - lo) / 2;
            if (s->Ai[mid] < row[0])
                lo = mid + 1;
            else
                hi = mid;
        }
        for (int t = 0; t < nr; ++t) {
            const double v = K[loc[t] * nb + b];
            while (lo < end && s->Ai[lo] < row[t])
                ++lo;
            if (v == 0.0)
                continue;
            if (lo < end && s->Ai[lo] == row[t])
                Ax[lo] += c * v;
            else
                ++missing;
        }
    }
    return missing;
}
