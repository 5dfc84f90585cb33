/* system.c -- the algebraic system of a model: equation numbering, the
 * pattern and scatter maps (made by pattern.c), the evaluation groups and
 * their buffers, the parts (bk_system_create, bk_system_free; system.h). */
#include "assembly/system.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/system_impl.h"
#include "base/bigalloc.h"

#include "linalg/linsolve.h"

/* n doubles aligned to 64 bytes (a cache line, one AVX-512 register): the lane
 * kernels' vector loads and stores then never straddle two lines (every group
 * slot is a multiple of BK_LANES = 8 doubles).  Freed with free(). */
static double *alloc_lanes(size_t n)
{
    size_t bytes = (n * sizeof(double) + 63) / 64 * 64;
    return aligned_alloc(64, bytes ? bytes : 64);
}

bk_system *bk_system_create(const bk_model *m, FILE *err)
{
    bk_system *s = calloc(1, sizeof *s);
    if (!s)
        goto oom;
    s->m = m;
    s->eq = malloc((size_t)m->ndof * sizeof *s->eq);
    if (!s->eq)
        goto oom;
    for (int i = 0; i < m->ndof; ++i)
        s->eq[i] = 0;
    for (int i = 0; i < m->nfixed; ++i)
        s->eq[m->fixed[i]] = -1;
    for (int i = 0; i < m->ndof; ++i)
        s->eq[i] = s->eq[i] < 0 ? -1 : s->nfree++;
    s->ncon = m->nlincon;
    s->jrow = malloc(((size_t)m->nnlcon + 1) * sizeof *s->jrow);
    if (!s->jrow)
        goto oom;
    for (int j = 0; j < m->nnlcon; ++j) {
        if (!m->nlcons[j].kind) {
            fprintf(err, "error: %s: joint %d (%s) has no kernel bound\n", m->name, j, m->nlcons[j].type);
            bk_system_free(s);
            return NULL;
        }
        s->jrow[j] = s->ncon;
        s->ncon += m->nlcons[j].kind->nrow;
    }
    s->jrow[m->nnlcon] = s->ncon;
    s->neq = s->nfree + s->ncon;
    s->cscale = 1.0;

    for (int e = 0; e < m->nelem; ++e)
        if (m->pairs[m->elems[e].pair]->element->ndof > s->maxdof)
            s->maxdof = m->pairs[m->elems[e].pair]->element->ndof;
    if (bk_make_pattern(s) != 0)
        goto oom;
    s->fe = malloc((size_t)(s->maxdof ? s->maxdof : 1) * sizeof *s->fe);
    s->Ke = malloc((size_t)(s->maxdof ? s->maxdof : 1) * (size_t)(s->maxdof ? s->maxdof : 1) * sizeof *s->Ke);
    if (!s->fe || !s->Ke)
        goto oom;
    {
        /* Groups (see system.h) and the buffer sizes of one group slot. */
        s->group = malloc(((size_t)m->nelem + 1) * sizeof *s->group);
        if (!s->group)
            goto oom;
        size_t sq = 1, sK = 1, st = 1;
        for (int e = 0; e < m->nelem;) {
            const bk_pair *p = m->pairs[m->elems[e].pair];
            int n = 1;
            if (lane_pair(p))
                while (n < BK_LANES && e + n < m->nelem && m->elems[e + n].pair == m->elems[e].pair)
                    ++n;
            size_t w = lane_pair(p) ? BK_LANES : 1, nd = (size_t)p->element->ndof;
            if (w * nd > sq)
                sq = w * nd;
            if (w * nd * nd > sK)
                sK = w * nd * nd;
            if (w * (size_t)(p->ntab > 0 ? p->ntab : 1) > st)
                st = w * (size_t)(p->ntab > 0 ? p->ntab : 1);
            s->group[s->ngroup++] = e;
            e += n;
        }
        s->group[s->ngroup] = m->nelem;
        s->slot_q = sq, s->slot_K = sK, s->slot_tab = st, s->slot_mat = (size_t)BK_LANES * BK_MAT_MAXPARAM;
    }
    s->nthreads = 1;
#ifdef _OPENMP
    s->nthreads = omp_get_max_threads();
    if (s->nthreads < 1)
        s->nthreads = 1;
#endif
    if (bk_make_parts(s) != 0)
        goto oom;
    bk_free_incidence(s);
    {
        /* one evaluation slot per thread (one when serial) */
        const size_t np = (size_t)(s->npart > 1 ? s->nthreads : 1);
        /* the threads' slots apart (bigalloc.h: adjacent ones made the
         * 10,000-element assembly on 2 threads take 9.4 ms instead of 6.9) */
        s->slot_q = bk_thread_stride(s->slot_q, (int)np), s->slot_K = bk_thread_stride(s->slot_K, (int)np);
        s->slot_tab = bk_thread_stride(s->slot_tab, (int)np), s->slot_mat = bk_thread_stride(s->slot_mat, (int)np);
        s->bq = alloc_lanes(np * s->slot_q);
        s->bf = alloc_lanes(np * s->slot_q);
        s->bK = alloc_lanes(np * s->slot_K);
        s->btab = alloc_lanes(np * s->slot_tab);
        s->bmat = alloc_lanes(np * s->slot_mat);
        if (!s->bq || !s->bf || !s->bK || !s->btab || !s->bmat)
            goto oom;
    }
    if (bk_interactions_create(s, err) != 0) {      /* (its message written) */
        bk_system_free(s);
        return NULL;
    }
    return s;
oom:
    fprintf(err, "error: out of memory while building the system of '%s'\n", m->name);
    bk_system_free(s);
    return NULL;
}

void bk_system_free(bk_system *s)
{
    if (!s)
        return;
    bk_interactions_free(s);
    bk_free_pattern(s);
    free(s->couple);
    free(s->eq);
    free(s->jrow);
    free(s->fe);
    free(s->Ke);
    free(s->bq);
    free(s->bf);
    free(s->bK);
    free(s->btab);
    free(s->bmat);
    free(s->group);
    bk_free_parts(s);
    free(s);
}

/* Element evaluation by groups (system.h).  Serially, each group is
 * evaluated and scattered in element order.  In parallel, each thread takes
 * its part (a run of groups of about equal cost) and scatters its elements
 * directly into the slots of fint and Ax that only its part adds into; terms
 * for slots shared with another part go to stage entries, summed after the
 * parallel region in element order.  Every entry therefore receives its terms
 * in element order, whatever the number of threads: results are
 * bit-identical for any OMP_NUM_THREADS. */
/* Group g into its slot: f (and K when tangent) of each element, lane-ordered
 * (entry k of lane l at [k * BK_LANES + l]) for a lane group, plain for a
 * single element without lane kernels. */
