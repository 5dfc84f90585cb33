/* partition.c -- the parts of the parallel assembly: contiguous runs of
 * element groups of about equal cost, and the staging of the terms that two
 * parts share, so that every sum is made in element order whatever the
 * thread count; the owner marks DOF by DOF on the threads (system.h). */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/system_impl.h"

/* Owner code of a matrix slot or DOF while the parts are made: 0 untouched,
 * p + 1 touched by part p only, 255 touched by two parts or more. */
static void mark_owner(unsigned char *o, int p)
{
    if (*o == 0)
        *o = (unsigned char)(p + 1);
    else if (*o != p + 1)
        *o = 255;
}

typedef struct {
    long to;                           /* DOF or slot */
    int idx;                           /* stage index (element order) */
} stage_ref;

static int cmp_stage_ref(const void *a, const void *b)
{
    const stage_ref *x = a, *y = b;
    if (x->to != y->to)
        return (x->to > y->to) - (x->to < y->to);
    return (x->idx > y->idx) - (x->idx < y->idx);
}

/* The parts of the parallel assembly (system.h): contiguous runs of groups of
 * about equal cost, BK_PARTS_PER_THREAD per thread; the slots and DOFs that
 * elements of two parts add into, and the stage entries that keep those
 * elements' terms. */
int bk_make_parts(bk_system *s)
{
    const bk_model *m = s->m;
    s->npart = 1;
    if (s->nthreads < 2 || m->nelem < BK_PAR_MIN_ELEMS)
        return 0;
    int np = s->nthreads * BK_PARTS_PER_THREAD;
    if (np > BK_MAX_PARTS)
        np = BK_MAX_PARTS;
    if (np > s->ngroup)
        np = s->ngroup;
    if (np < 2)
        return 0;
    s->part = malloc(((size_t)np + 1) * sizeof *s->part);
    if (!s->part)
        return -1;
    /* cost of a group ~ its scatter: nd^2 + nd per element, plus a call */
    double total = 0.0, acc = 0.0;
    for (int e = 0; e < m->nelem; ++e) {
        const double nd = bk_elem_type(m, e)->ndof;
        total += nd * nd + nd;
    }
    total += 64.0 * s->ngroup;
    int t = 1;
    s->part[0] = 0;
    for (int g = 0; g < s->ngroup; ++g) {
        for (int e = s->group[g]; e < s->group[g + 1]; ++e) {
            const double nd = bk_elem_type(m, e)->ndof;
            acc += nd * nd + nd;
        }
        acc += 64.0;
        while (t < np && acc >= total * t / np)
            s->part[t++] = g + 1;
    }
    while (t < np)
        s->part[t++] = s->ngroup;
    s->part[np] = s->ngroup;
    s->npart = np;

    unsigned char *sown = calloc((size_t)(s->nnz ? s->nnz : 1), 1), *down = calloc((size_t)m->ndof + 1, 1);
    if (!sown || !down) {
        free(sown);
        free(down);
        return -1;
    }
    /* owner codes DOF by DOF on the threads (a code does not depend on the
     * order of the marks): a DOF's from its elements, the slots of its column
     * (no other DOF's elements write them) from the column's entries of its
     * elements' maps.  Only code 255 (shared) is used below: a DOF whose
     * elements (in element order) begin and end in one part, and its column,
     * are left unmarked; every element of a slot has the slot's column DOF, so
     * an element with a shared slot has a shared DOF. */
    int *ep = malloc(((size_t)m->nelem + 1) * sizeof *ep);
    s->pel = malloc(((size_t)m->nelem + 1) * sizeof *s->pel);
    if (!ep || !s->pel) {
        free(ep);
        goto fail;
    }
    for (int p = 0; p < np; ++p)
        for (int e = s->group[s->part[p]]; e < s->group[s->part[p + 1]]; ++e)
            ep[e] = p;
    const int nth = s->nthreads;
    BK_OMP(omp parallel for num_threads(nth) schedule(static) if (nth > 1))
    for (int d = 0; d < m->ndof; ++d) {
        const int i0 = s->dinc_ptr[d], i1 = s->dinc_ptr[d + 1];
        if (i0 == i1 || ep[s->dinc[2 * i0]] == ep[s->dinc[2 * i1 - 2]])
            continue;
        for (int i = i0; i < i1; ++i) {
            const int e = s->dinc[2 * i], c = s->dinc[2 * i + 1], nd = bk_elem_type(m, e)->ndof;
            const int *sl = s->eslot + s->eslot_off[e];
            mark_owner(&down[d], ep[e]);
            for (int r = 0; r < nd; ++r)
                if (sl[r * nd + c] >= 0)
                    mark_owner(&sown[sl[r * nd + c]], ep[e]);
        }
    }
    free(ep);
    /* elements with a shared slot or DOF get a scatter map with stage codes
     * (their counts on the threads, then the offsets in element order) */
    BK_OMP(omp parallel for num_threads(nth) schedule(static) if (nth > 1))
    for (int e = 0; e < m->nelem; ++e) {
        const int nd = bk_elem_type(m, e)->ndof, *sl = s->eslot + s->eslot_off[e], *d = m->elems[e].dofs;
        long ns = 0;
        for (int k = 0; k < nd; ++k)
            ns += down[d[k]] == 255;
        for (int k = 0; k < nd * nd && ns; ++k)
            ns += sl[k] >= 0 && sown[sl[k]] == 255;
        s->pel[e] = ns;
    }
    long nmap = 0, nstage = 0;
    for (int e = 0; e < m->nelem; ++e) {
        const long ns = s->pel[e];
        s->pel[e] = ns ? nmap : -1;
        nmap += ns ? (long)bk_elem_type(m, e)->ndof * (bk_elem_type(m, e)->ndof + 1) : 0;
        nstage += ns;
    }
    s->pmap = malloc((size_t)(nmap ? nmap : 1) * sizeof *s->pmap);
    s->stage = malloc((size_t)(nstage ? nstage : 1) * sizeof *s->stage);
    stage_ref *fr = malloc((size_t)(nstage ? nstage : 1) * sizeof *fr);
    stage_ref *kr = malloc((size_t)(nstage ? nstage : 1) * sizeof *kr);
    s->sh_ptr = malloc((size_t)(nstage + 1) * sizeof *s->sh_ptr);
    s->sh_to = malloc((size_t)(nstage ? nstage : 1) * sizeof *s->sh_to);
    s->sh_idx = malloc((size_t)(nstage ? nstage : 1) * sizeof *s->sh_idx);
    if (!s->pmap || !s->stage || !fr || !kr || !s->sh_ptr || !s->sh_to || !s->sh_idx) {
        free(fr);
        free(kr);
        goto fail;
    }
    int idx = 0, nf = 0, nk = 0;
    for (int e = 0; e < m->nelem; ++e) {
        if (s->pel[e] < 0)
            continue;
        const int nd = bk_elem_type(m, e)->ndof, *sl = s->eslot + s->eslot_off[e], *d = m->elems[e].dofs;
        int *code = s->pmap + s->pel[e];
        /* stage indices in the serial scatter's order: fint entries, then Ax */
        for (int k = 0; k < nd; ++k)
            if (down[d[k]] == 255) {
                fr[nf++] = (stage_ref){d[k], idx};
                code[nd * nd + k] = -2 - idx++;
            } else
                code[nd * nd + k] = d[k];
        for (int k = 0; k < nd * nd; ++k)
            if (sl[k] >= 0 && sown[sl[k]] == 255) {
                kr[nk++] = (stage_ref){sl[k], idx};
                code[k] = -2 - idx++;
            } else
                code[k] = sl[k];
    }
    qsort(fr, (size_t)nf, sizeof *fr, cmp_stage_ref);
    qsort(kr, (size_t)nk, sizeof *kr, cmp_stage_ref);
    /* one list per shared DOF (first), then per shared slot, in element order */
    int nt = 0;
    s->nshared_dof = 0;
    for (int i = 0; i < nf + nk; ++i) {
        const stage_ref *r = i < nf ? &fr[i] : &kr[i - nf];
        const int first = i == 0 || i == nf || r->to != (i < nf ? fr[i - 1].to : kr[i - nf - 1].to);
        if (first) {
            s->sh_ptr[nt] = i;
            s->sh_to[nt++] = r->to;
            if (i < nf)
                s->nshared_dof = nt;
        }
        s->sh_idx[i] = r->idx;
    }
    s->sh_ptr[nt] = nf + nk;
    s->nshared = nt;
    free(fr);
    free(kr);
    free(sown);
    free(down);
    return 0;
fail:
    free(sown);
    free(down);
    return -1;
}

void bk_free_parts(bk_system *s)
{
    free(s->part);
    free(s->pel);
    free(s->pmap);
    free(s->stage);
    free(s->sh_ptr);
    free(s->sh_idx);
    free(s->sh_to);
    s->part = NULL, s->pel = NULL, s->pmap = NULL, s->stage = NULL;
    s->sh_ptr = s->sh_idx = NULL, s->sh_to = NULL;
    s->nshared = s->nshared_dof = 0;
}
