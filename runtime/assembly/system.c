/* system.c -- equation numbering, the sparse pattern of the Newton matrix,
 * each element's and joint's scatter map into it, the evaluation groups and
 * their buffers (bk_system_create, bk_system_free; system.h). */
#include "assembly/system.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/system_impl.h"

#include "linalg/linsolve.h"

/* n doubles aligned to 64 bytes (a cache line, one AVX-512 register): the lane
 * kernels' vector loads and stores then never straddle two lines (every group
 * slot is a multiple of BK_LANES = 8 doubles).  Freed with free(). */
static double *alloc_lanes(size_t n)
{
    size_t bytes = (n * sizeof(double) + 63) / 64 * 64;
    return aligned_alloc(64, bytes ? bytes : 64);
}

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* The pattern of the Newton matrix (element blocks, the coupling blocks of
 * s->couple, constraint rows, joints) and every scatter map into it: Ap, Ai,
 * nnz, eslot*, efirst, zslot, cslot*, jslot*, diag.  0, or -1 when out of
 * memory (what was made is freed by bk_free_pattern). */
int bk_make_pattern(bk_system *s)
{
    const bk_model *m = s->m;
    /* Count entries per column (duplicates included). */
    long *cnt = calloc((size_t)s->neq + 1, sizeof *cnt);
    if (!cnt)
        return -1;
    for (int e = 0; e < m->nelem; ++e) {
        const bk_elem *el = &m->elems[e];
        int nd = m->pairs[el->pair]->element->ndof;
        int nf = 0;
        for (int k = 0; k < nd; ++k)
            nf += s->eq[el->dofs[k]] >= 0;
        for (int k = 0; k < nd; ++k)
            if (s->eq[el->dofs[k]] >= 0)
                cnt[s->eq[el->dofs[k]]] += nf;
    }
    for (int c = 0; c < m->nlincon; ++c) {
        const bk_lincon *lc = &m->lincons[c];
        for (int k = 0; k < lc->nterm; ++k) {
            int q = s->eq[lc->dof[k]];
            if (q >= 0) {
                cnt[q] += 1;
                cnt[s->nfree + c] += 1;
            }
        }
    }
    for (int j = 0; j < m->nnlcon; ++j) {
        const bk_nlcon *jc = &m->nlcons[j];
        int nr = s->jrow[j + 1] - s->jrow[j], nf = 0;
        for (int k = 0; k < BK_JOINT_NX; ++k)
            nf += joint_eq(s, jc, k) >= 0;
        for (int k = 0; k < BK_JOINT_NX; ++k)
            if (joint_eq(s, jc, k) >= 0)
                cnt[joint_eq(s, jc, k)] += nf + nr;
        for (int r = 0; r < nr; ++r)
            cnt[s->nfree + s->jrow[j] + r] += nf;
    }
    for (int k = 0; k < s->ncouple; ++k)           /* coupling blocks of element pairs (both ways) */
        for (int side = 0; side < 2; ++side) {
            const bk_elem *ea = &m->elems[s->couple[2 * k + side]], *eb = &m->elems[s->couple[2 * k + 1 - side]];
            const int na = m->pairs[ea->pair]->element->ndof, nb = m->pairs[eb->pair]->element->ndof;
            int nf = 0;
            for (int a = 0; a < na; ++a)
                nf += s->eq[ea->dofs[a]] >= 0;
            for (int b = 0; b < nb; ++b)
                if (s->eq[eb->dofs[b]] >= 0)
                    cnt[s->eq[eb->dofs[b]]] += nf;
        }
    /* Fill buckets, then sort and deduplicate each column. */
    long *off = calloc((size_t)s->neq + 1, sizeof *off);
    if (!off) {
        free(cnt);
        return -1;
    }
    for (int j = 0; j < s->neq; ++j)
        off[j + 1] = off[j] + cnt[j];
    int *rows = malloc((size_t)(off[s->neq] ? off[s->neq] : 1) * sizeof *rows);
    if (!rows) {
        free(cnt);
        free(off);
        return -1;
    }
    memset(cnt, 0, ((size_t)s->neq + 1) * sizeof *cnt);
    for (int e = 0; e < m->nelem; ++e) {
        const bk_elem *el = &m->elems[e];
        int nd = m->pairs[el->pair]->element->ndof;
        for (int b = 0; b < nd; ++b) {
            int col = s->eq[el->dofs[b]];
            if (col < 0)
                continue;
            for (int a = 0; a < nd; ++a) {
                int row = s->eq[el->dofs[a]];
                if (row >= 0)
                    rows[off[col] + cnt[col]++] = row;
            }
        }
    }
    for (int c = 0; c < m->nlincon; ++c) {
        const bk_lincon *lc = &m->lincons[c];
        int cc = s->nfree + c;
        for (int k = 0; k < lc->nterm; ++k) {
            int q = s->eq[lc->dof[k]];
            if (q >= 0) {
                rows[off[q] + cnt[q]++] = cc;
                rows[off[cc] + cnt[cc]++] = q;
            }
        }
    }
    for (int j = 0; j < m->nnlcon; ++j) {
        const bk_nlcon *jc = &m->nlcons[j];
        int nr = s->jrow[j + 1] - s->jrow[j];
        for (int b = 0; b < BK_JOINT_NX; ++b) {
            int col = joint_eq(s, jc, b);
            if (col < 0)
                continue;
            for (int a = 0; a < BK_JOINT_NX; ++a)
                if (joint_eq(s, jc, a) >= 0)
                    rows[off[col] + cnt[col]++] = joint_eq(s, jc, a);
            for (int r = 0; r < nr; ++r) {
                int cc = s->nfree + s->jrow[j] + r;
                rows[off[col] + cnt[col]++] = cc;
                rows[off[cc] + cnt[cc]++] = col;
            }
        }
    }
    for (int k = 0; k < s->ncouple; ++k)
        for (int side = 0; side < 2; ++side) {
            const bk_elem *ea = &m->elems[s->couple[2 * k + side]], *eb = &m->elems[s->couple[2 * k + 1 - side]];
            const int na = m->pairs[ea->pair]->element->ndof, nb = m->pairs[eb->pair]->element->ndof;
            for (int b = 0; b < nb; ++b) {
                const int col = s->eq[eb->dofs[b]];
                for (int a = 0; a < na && col >= 0; ++a)
                    if (s->eq[ea->dofs[a]] >= 0)
                        rows[off[col] + cnt[col]++] = s->eq[ea->dofs[a]];
            }
        }
    s->Ap = malloc(((size_t)s->neq + 1) * sizeof *s->Ap);
    if (!s->Ap) {
        free(cnt);
        free(off);
        free(rows);
        return -1;
    }
    /* each column's rows without repeats (seen: the last column a row was
     * seen in, one array a thread), then sorted: they come as a few ascending
     * runs, one per element, which an insertion sort takes in about linear
     * time (qsort was a tenth of a small model's run); the columns on the
     * threads, then packed in order */
    int nth = 1;
#ifdef _OPENMP
    if (m->nelem >= BK_PAR_MIN_ELEMS)
        nth = omp_get_max_threads() > 1 ? omp_get_max_threads() : 1;
#endif
    int *seen = malloc((size_t)nth * ((size_t)s->neq + 1) * sizeof *seen);
    if (!seen) {
        free(cnt);
        free(off);
        free(rows);
        return -1;
    }
    BK_OMP(omp parallel num_threads(nth) if (nth > 1))
    {
        int *sn = seen, neq = s->neq;
#ifdef _OPENMP
        sn += (size_t)omp_get_thread_num() * ((size_t)neq + 1);
#endif
        for (int j = 0; j < neq; ++j)
            sn[j] = -1;
        BK_OMP(omp for schedule(static))
        for (int j = 0; j < neq; ++j) {
            int *col = rows + off[j];
            long n = cnt[j], u = 0;
            for (long k = 0; k < n; ++k)
                if (sn[col[k]] != j) {
                    sn[col[k]] = j;
                    col[u++] = col[k];
                }
            if (u > 64)
                qsort(col, (size_t)u, sizeof *col, cmp_int);
            else
                for (long k = 1; k < u; ++k) {
                    const int v = col[k];
                    long i = k;
                    for (; i > 0 && col[i - 1] > v; --i)
                        col[i] = col[i - 1];
                    col[i] = v;
                }
            cnt[j] = u;
        }
    }
    long nnz = 0;
    for (int j = 0; j < s->neq; ++j) {
        s->Ap[j] = (int)nnz;
        memmove(rows + nnz, rows + off[j], (size_t)cnt[j] * sizeof *rows);
        nnz += cnt[j];
    }
    s->Ap[s->neq] = (int)nnz;
    s->nnz = nnz;
    free(cnt);
    free(off);
    s->Ai = realloc(rows, (size_t)(nnz ? nnz : 1) * sizeof *rows);
    if (!s->Ai) {
        free(rows);
        free(seen);
        return -1;
    }

    /* Scatter maps (seen, one array a thread, is their scratch). */
    s->eslot_off = malloc(((size_t)m->nelem + 1) * sizeof *s->eslot_off);
    if (!s->eslot_off) {
        free(seen);
        return -1;
    }
    long tot = 0;
    for (int e = 0; e < m->nelem; ++e) {
        int nd = m->pairs[m->elems[e].pair]->element->ndof;
        s->eslot_off[e] = (int)tot;
        tot += (long)nd * nd;
    }
    s->eslot_off[m->nelem] = (int)tot;
    s->eslot = malloc((size_t)(tot ? tot : 1) * sizeof *s->eslot);
    if (!s->eslot) {
        free(seen);
        return -1;
    }
    {
        /* a[row]: the slot of row in the column at hand (one pass over the column instead of a
         * bisection per entry); a slot outside that column's range is another column's */
        BK_OMP(omp parallel num_threads(nth) if (nth > 1))
        {
            int *a = seen;
#ifdef _OPENMP
            a += (size_t)omp_get_thread_num() * ((size_t)s->neq + 1);
#endif
            for (int j = 0; j < s->neq; ++j)
                a[j] = -1;
            BK_OMP(omp for schedule(static))
            for (int e = 0; e < m->nelem; ++e) {
                const bk_elem *el = &m->elems[e];
                int nd = m->pairs[el->pair]->element->ndof;
                int *sl = s->eslot + s->eslot_off[e];
                for (int c = 0; c < nd; ++c) {
                    const int col = s->eq[el->dofs[c]];
                    const int lo = col >= 0 ? s->Ap[col] : 0, hi = col >= 0 ? s->Ap[col + 1] : 0;
                    for (int p = lo; p < hi; ++p)
                        a[s->Ai[p]] = p;
                    for (int r = 0; r < nd; ++r) {
                        const int row = s->eq[el->dofs[r]], p = row >= 0 ? a[row] : -1;
                        sl[r * nd + c] = p >= lo && p < hi ? p : -1;
                    }
                }
            }
        }
        free(seen);
    }
    /* The first term of every slot in element order is stored, not added
     * (assembly zeroes only the slots no element touches): efirst marks it. */
    s->efirst = calloc((size_t)(tot ? tot : 1), 1);
    {
        unsigned char *seen = calloc((size_t)(s->nnz ? s->nnz : 1), 1);
        if (!s->efirst || !seen) {
            free(seen);
            return -1;
        }
        long nz = 0;
        for (long k = 0; k < tot; ++k)
            if (s->eslot[k] >= 0 && !seen[s->eslot[k]])
                seen[s->eslot[k]] = 1, s->efirst[k] = 1;
        for (long k = 0; k < s->nnz; ++k)
            nz += !seen[k];
        s->zslot = malloc((size_t)(nz ? nz : 1) * sizeof *s->zslot);
        if (!s->zslot) {
            free(seen);
            return -1;
        }
        for (long k = 0; k < s->nnz; ++k)
            if (!seen[k])
                s->zslot[s->nzslot++] = k;
        free(seen);
    }
    s->cslot_off = malloc(((size_t)m->nlincon + 1) * sizeof *s->cslot_off);
    if (!s->cslot_off)
        return -1;
    tot = 0;
    for (int c = 0; c < m->nlincon; ++c) {
        s->cslot_off[c] = (int)tot;
        tot += 2L * m->lincons[c].nterm;
    }
    s->cslot_off[m->nlincon] = (int)tot;
    s->cslot = malloc((size_t)(tot ? tot : 1) * sizeof *s->cslot);
    if (!s->cslot)
        return -1;
    for (int c = 0; c < m->nlincon; ++c) {
        const bk_lincon *lc = &m->lincons[c];
        int *sl = s->cslot + s->cslot_off[c];
        for (int k = 0; k < lc->nterm; ++k) {
            int q = s->eq[lc->dof[k]];
            sl[2 * k] = q >= 0 ? bk_find_slot(s, s->nfree + c, q) : -1;
            sl[2 * k + 1] = q >= 0 ? bk_find_slot(s, q, s->nfree + c) : -1;
        }
    }
    s->jslot_off = malloc(((size_t)m->nnlcon + 1) * sizeof *s->jslot_off);
    if (!s->jslot_off)
        return -1;
    tot = 0;
    for (int j = 0; j < m->nnlcon; ++j) {
        s->jslot_off[j] = (int)tot;
        tot += BK_JOINT_NX * BK_JOINT_NX + 2L * BK_JOINT_NX * (s->jrow[j + 1] - s->jrow[j]);
    }
    s->jslot_off[m->nnlcon] = (int)tot;
    s->jslot = malloc((size_t)(tot ? tot : 1) * sizeof *s->jslot);
    if (!s->jslot)
        return -1;
    for (int j = 0; j < m->nnlcon; ++j) {
        const bk_nlcon *jc = &m->nlcons[j];
        const int nx = BK_JOINT_NX, nr = s->jrow[j + 1] - s->jrow[j];
        int *sl = s->jslot + s->jslot_off[j];
        for (int a = 0; a < nx; ++a)
            for (int b = 0; b < nx; ++b) {
                int ra = joint_eq(s, jc, a), cb = joint_eq(s, jc, b);
                sl[nx * a + b] = ra >= 0 && cb >= 0 ? bk_find_slot(s, ra, cb) : -1;
            }
        for (int r = 0; r < nr; ++r)
            for (int k = 0; k < nx; ++k) {
                int qk = joint_eq(s, jc, k), cc = s->nfree + s->jrow[j] + r;
                sl[nx * nx + nx * r + k] = qk >= 0 ? bk_find_slot(s, cc, qk) : -1;
                sl[nx * nx + nx * nr + nx * r + k] = qk >= 0 ? bk_find_slot(s, qk, cc) : -1;
            }
    }
    s->diag = malloc((size_t)(s->nfree ? s->nfree : 1) * sizeof *s->diag);
    if (!s->diag)
        return -1;
    for (int j = 0; j < s->nfree; ++j)
        s->diag[j] = bk_find_slot(s, j, j);
    return 0;
}

void bk_free_pattern(bk_system *s)
{
    free(s->Ap);
    free(s->Ai);
    free(s->eslot_off);
    free(s->eslot);
    free(s->efirst);
    free(s->zslot);
    free(s->cslot);
    free(s->cslot_off);
    free(s->jslot);
    free(s->jslot_off);
    free(s->diag);
    s->Ap = s->Ai = s->eslot_off = s->eslot = s->cslot = s->cslot_off = s->jslot = s->jslot_off = s->diag = NULL;
    s->efirst = NULL;
    s->zslot = NULL;
    s->nzslot = 0;
    s->nnz = 0;
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
        s->slot_q = sq, s->slot_K = sK, s->slot_tab = st;
    }
    s->nthreads = 1;
#ifdef _OPENMP
    s->nthreads = omp_get_max_threads();
    if (s->nthreads < 1)
        s->nthreads = 1;
#endif
    if (bk_make_parts(s) != 0)
        goto oom;
    {
        /* one evaluation slot per thread (one when serial) */
        const size_t np = (size_t)(s->npart > 1 ? s->nthreads : 1);
        s->bq = alloc_lanes(np * s->slot_q);
        s->bf = alloc_lanes(np * s->slot_q);
        s->bK = alloc_lanes(np * s->slot_K);
        s->btab = alloc_lanes(np * s->slot_tab);
        s->bmat = alloc_lanes(np * BK_LANES * BK_MAT_MAXPARAM);
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
