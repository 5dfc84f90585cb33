/* pattern.c -- the sparse pattern of the Newton matrix (element blocks, the
 * coupling blocks of s->couple, constraint rows, joints) and every scatter map
 * into it, made column by column on the threads (bk_make_pattern,
 * bk_free_pattern; system_impl.h). */
#include <stdlib.h>
#include <string.h>

#include "assembly/system_impl.h"
#include "base/bigalloc.h"

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* The rows of the other terms than the elements' own blocks (constraint rows,
 * joints, coupling blocks), repeats included: column j's at xr[xo[j]..xo[j+1]).
 * 0, or -1 when out of memory. */
static int extra_rows(const bk_system *s, long **xo_out, int **xr_out)
{
    const bk_model *m = s->m;
    long *cnt = calloc((size_t)s->neq + 1, sizeof *cnt), *off = calloc((size_t)s->neq + 1, sizeof *off);
    if (!cnt || !off) {
        free(cnt), free(off);
        return -1;
    }
    for (int pass = 0; pass < 2; ++pass) {
        int *rows = NULL;
        if (pass == 1) {
            for (int j = 0; j < s->neq; ++j)
                off[j + 1] = off[j] + cnt[j];
            rows = malloc((size_t)(off[s->neq] ? off[s->neq] : 1) * sizeof *rows);
            if (!rows) {
                free(cnt), free(off);
                return -1;
            }
            memset(cnt, 0, ((size_t)s->neq + 1) * sizeof *cnt);
            *xr_out = rows;
        }
/* (pass 0 counts, pass 1 stores) */
#define PUT(col, row) (pass ? (void)(rows[off[col] + cnt[col]++] = (row)) : (void)cnt[col]++)
        for (int c = 0; c < m->nlincon; ++c) {
            const bk_lincon *lc = &m->lincons[c];
            const int cc = s->nfree + c;
            for (int k = 0; k < lc->nterm; ++k) {
                const int q = s->eq[lc->dof[k]];
                if (q >= 0) {
                    PUT(q, cc);
                    PUT(cc, q);
                }
            }
        }
        for (int j = 0; j < m->nnlcon; ++j) {
            const bk_nlcon *jc = &m->nlcons[j];
            const int nr = s->jrow[j + 1] - s->jrow[j];
            for (int b = 0; b < BK_JOINT_NX; ++b) {
                const int col = joint_eq(s, jc, b);
                if (col < 0)
                    continue;
                for (int a = 0; a < BK_JOINT_NX; ++a)
                    if (joint_eq(s, jc, a) >= 0)
                        PUT(col, joint_eq(s, jc, a));
                for (int r = 0; r < nr; ++r) {
                    const int cc = s->nfree + s->jrow[j] + r;
                    PUT(col, cc);
                    PUT(cc, col);
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
                            PUT(col, s->eq[ea->dofs[a]]);
                }
            }
#undef PUT
    }
    free(cnt);
    *xo_out = off;
    return 0;
}

/* The elements of each DOF, in element order: s->dinc[2 i] the element and
 * s->dinc[2 i + 1] the DOF's place in it, i in [dinc_ptr[d], dinc_ptr[d+1]). */
static int dof_incidence(bk_system *s)
{
    const bk_model *m = s->m;
    int *ptr = calloc((size_t)m->ndof + 1, sizeof *ptr);
    if (!ptr)
        return -1;
    for (int e = 0; e < m->nelem; ++e) {
        const int nd = bk_elem_type(m, e)->ndof, *d = m->elems[e].dofs;
        for (int k = 0; k < nd; ++k)
            ptr[d[k] + 1]++;
    }
    for (int d = 0; d < m->ndof; ++d)
        ptr[d + 1] += ptr[d];
    int *inc = bk_big_malloc(2 * (size_t)(ptr[m->ndof] ? ptr[m->ndof] : 1) * sizeof *inc);
    if (!inc) {
        free(ptr);
        return -1;
    }
    for (int e = 0; e < m->nelem; ++e) {
        const int nd = bk_elem_type(m, e)->ndof, *d = m->elems[e].dofs;
        for (int k = 0; k < nd; ++k) {
            const int i = ptr[d[k]]++;
            inc[2 * i] = e, inc[2 * i + 1] = k;
        }
    }
    for (int d = m->ndof; d > 0; --d)
        ptr[d] = ptr[d - 1];
    ptr[0] = 0;
    s->dinc_ptr = ptr, s->dinc = inc;
    return 0;
}

/* The pattern of the Newton matrix and every scatter map into it: Ap, Ai,
 * nnz, eslot*, efirst, zslot, cslot*, jslot*, diag, dinc*.  Each column's rows
 * are the equations of the elements at its DOF and its other terms (above),
 * without repeats and sorted: a first pass counts them, a second stores them
 * and, for each element at the column's DOF in element order, its scatter map
 * into the column and which entry is a slot's first term (efirst: the least
 * element, then the least row and column place in it).  The columns on the
 * threads; the result does not depend on their number.  0, or -1 when out of
 * memory (what was made is freed by bk_free_pattern). */
int bk_make_pattern(bk_system *s)
{
    const bk_model *m = s->m;
    const int neq = s->neq, *eq = s->eq;
    long *xo = NULL;
    int *xr = NULL, *cdof = NULL, *mk = NULL, *zc = NULL;
    int rc = -1;
    if (dof_incidence(s) != 0 || extra_rows(s, &xo, &xr) != 0)
        return -1;
    const int *ip = s->dinc_ptr, *inc = s->dinc;
    int nth = 1;
#ifdef _OPENMP
    if (m->nelem >= BK_PAR_MIN_ELEMS)
        nth = omp_get_max_threads() > 1 ? omp_get_max_threads() : 1;
#endif
    cdof = malloc(((size_t)neq + 1) * sizeof *cdof);
    zc = malloc(((size_t)neq + 1) * sizeof *zc);
    mk = bk_big_malloc(2 * (size_t)nth * ((size_t)neq + 1) * sizeof *mk);   /* two markers a thread */
    s->Ap = malloc(((size_t)neq + 1) * sizeof *s->Ap);
    s->eslot_off = malloc(((size_t)m->nelem + 1) * sizeof *s->eslot_off);
    s->diag = malloc((size_t)(s->nfree ? s->nfree : 1) * sizeof *s->diag);
    if (!cdof || !zc || !mk || !s->Ap || !s->eslot_off || !s->diag)
        goto done;
    for (int d = 0; d < m->ndof; ++d)
        if (eq[d] >= 0)
            cdof[eq[d]] = d;
    for (int j = s->nfree; j < neq; ++j)
        cdof[j] = -1;
    /* pass 1: each column's count of rows (sn[row] == j: row seen in column j) */
    BK_OMP(omp parallel num_threads(nth) if (nth > 1))
    {
        int *sn = mk;
#ifdef _OPENMP
        sn += 2 * (size_t)omp_get_thread_num() * ((size_t)neq + 1);
#endif
        for (int j = 0; j < neq; ++j)
            sn[j] = -1;
        BK_OMP(omp for schedule(static))
        for (int j = 0; j < neq; ++j) {
            int u = 0;
            for (int i = cdof[j] >= 0 ? ip[cdof[j]] : 0; cdof[j] >= 0 && i < ip[cdof[j] + 1]; ++i) {
                const int e = inc[2 * i], nd = bk_elem_type(m, e)->ndof, *d = m->elems[e].dofs;
                for (int r = 0; r < nd; ++r) {
                    const int row = eq[d[r]];
                    if (row >= 0 && sn[row] != j)
                        sn[row] = j, ++u;
                }
            }
            for (long k = xo[j]; k < xo[j + 1]; ++k)
                if (sn[xr[k]] != j)
                    sn[xr[k]] = j, ++u;
            zc[j] = u;
        }
    }
    long nnz = 0, tot = 0;
    for (int j = 0; j < neq; ++j) {
        s->Ap[j] = (int)nnz;
        nnz += zc[j];
    }
    s->Ap[neq] = (int)nnz;
    s->nnz = nnz;
    for (int e = 0; e < m->nelem; ++e) {
        const int nd = bk_elem_type(m, e)->ndof;
        s->eslot_off[e] = (int)tot;
        tot += (long)nd * nd;
    }
    s->eslot_off[m->nelem] = (int)tot;
    s->Ai = bk_big_malloc((size_t)(nnz ? nnz : 1) * sizeof *s->Ai);
    s->eslot = bk_big_malloc((size_t)(tot ? tot : 1) * sizeof *s->eslot);
    s->efirst = bk_big_calloc((size_t)(tot ? tot : 1), 1);
    if (!s->Ai || !s->eslot || !s->efirst)
        goto done;
    /* pass 2: the rows (a[row]: its slot in the column at hand; a slot outside
     * the column's range is another column's), the element maps and firsts
     * (sn[row] == -2 - j: row written by an element in column j); zc[j]: the
     * column's slots no element writes */
    BK_OMP(omp parallel num_threads(nth) if (nth > 1))
    {
        int *sn = mk, *a;
#ifdef _OPENMP
        sn += 2 * (size_t)omp_get_thread_num() * ((size_t)neq + 1);
#endif
        a = sn + neq + 1;
        for (int j = 0; j < neq; ++j)
            a[j] = -1;
        BK_OMP(omp for schedule(static))
        for (int j = 0; j < neq; ++j) {
            const int lo = s->Ap[j], hi = s->Ap[j + 1], i0 = cdof[j] >= 0 ? ip[cdof[j]] : 0,
                      i1 = cdof[j] >= 0 ? ip[cdof[j] + 1] : 0;
            int *col = s->Ai + lo, u = 0;
            for (int i = i0; i < i1; ++i) {
                const int e = inc[2 * i], nd = bk_elem_type(m, e)->ndof, *d = m->elems[e].dofs;
                for (int r = 0; r < nd; ++r) {
                    const int row = eq[d[r]];
                    if (row >= 0 && !(a[row] >= lo && a[row] < lo + u))
                        a[row] = lo + u, col[u++] = row;
                }
            }
            for (long k = xo[j]; k < xo[j + 1]; ++k)
                if (!(a[xr[k]] >= lo && a[xr[k]] < lo + u))
                    a[xr[k]] = lo + u, col[u++] = xr[k];
            /* they come as a few ascending runs, one per element, which an
             * insertion sort takes in about linear time */
            if (u > 64)
                qsort(col, (size_t)u, sizeof *col, cmp_int);
            else
                for (int k = 1; k < u; ++k) {
                    const int v = col[k];
                    int i = k;
                    for (; i > 0 && col[i - 1] > v; --i)
                        col[i] = col[i - 1];
                    col[i] = v;
                }
            for (int p = lo; p < hi; ++p)
                a[s->Ai[p]] = p;
            int z = hi - lo;
            for (int i = i0; i < i1; ++i) {
                const int e = inc[2 * i], c = inc[2 * i + 1], nd = bk_elem_type(m, e)->ndof, *d = m->elems[e].dofs;
                int *sl = s->eslot + s->eslot_off[e];
                unsigned char *fl = s->efirst + s->eslot_off[e];
                for (int r = 0; r < nd; ++r) {
                    const int row = eq[d[r]];
                    sl[r * nd + c] = row >= 0 ? a[row] : -1;
                    if (row >= 0 && sn[row] != -2 - j) {
                        sn[row] = -2 - j, --z;
                        fl[r * nd + c] = 1;
                    }
                }
            }
            zc[j] = z;
            if (j < s->nfree)
                s->diag[j] = a[j] >= lo && a[j] < hi ? a[j] : -1;
        }
    }
    /* the element entries of fixed columns */
    for (int dd = 0; dd < m->ndof; ++dd)
        if (eq[dd] < 0)
            for (int i = ip[dd]; i < ip[dd + 1]; ++i) {
                const int e = inc[2 * i], c = inc[2 * i + 1], nd = bk_elem_type(m, e)->ndof;
                for (int r = 0; r < nd; ++r)
                    s->eslot[s->eslot_off[e] + r * nd + c] = -1;
            }
    /* slots no element writes, in slot order: the columns that have them marked again */
    long nz = 0;
    for (int j = 0; j < neq; ++j)
        nz += zc[j];
    s->zslot = malloc((size_t)(nz ? nz : 1) * sizeof *s->zslot);
    if (!s->zslot)
        goto done;
    for (int j = 0; j < neq; ++j)
        mk[j] = -1;
    for (int j = 0; j < neq; ++j) {
        if (!zc[j])
            continue;
        for (int i = cdof[j] >= 0 ? ip[cdof[j]] : 0; cdof[j] >= 0 && i < ip[cdof[j] + 1]; ++i) {
            const int e = inc[2 * i], nd = bk_elem_type(m, e)->ndof, *d = m->elems[e].dofs;
            for (int r = 0; r < nd; ++r)
                if (eq[d[r]] >= 0)
                    mk[eq[d[r]]] = j;
        }
        for (int p = s->Ap[j]; p < s->Ap[j + 1]; ++p)
            if (mk[s->Ai[p]] != j)
                s->zslot[s->nzslot++] = p;
    }
    s->cslot_off = malloc(((size_t)m->nlincon + 1) * sizeof *s->cslot_off);
    if (!s->cslot_off)
        goto done;
    tot = 0;
    for (int c = 0; c < m->nlincon; ++c) {
        s->cslot_off[c] = (int)tot;
        tot += 2L * m->lincons[c].nterm;
    }
    s->cslot_off[m->nlincon] = (int)tot;
    s->cslot = malloc((size_t)(tot ? tot : 1) * sizeof *s->cslot);
    if (!s->cslot)
        goto done;
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
        goto done;
    tot = 0;
    for (int j = 0; j < m->nnlcon; ++j) {
        s->jslot_off[j] = (int)tot;
        tot += BK_JOINT_NX * BK_JOINT_NX + 2L * BK_JOINT_NX * (s->jrow[j + 1] - s->jrow[j]);
    }
    s->jslot_off[m->nnlcon] = (int)tot;
    s->jslot = malloc((size_t)(tot ? tot : 1) * sizeof *s->jslot);
    if (!s->jslot)
        goto done;
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
    rc = 0;
done:
    free(xo), free(xr), free(cdof), free(mk), free(zc);
    return rc;
}

void bk_free_incidence(bk_system *s)
{
    free(s->dinc_ptr);
    free(s->dinc);
    s->dinc_ptr = s->dinc = NULL;
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
    free(s->dinc_ptr);
    free(s->dinc);
    s->dinc_ptr = s->dinc = NULL;
    s->Ap = s->Ai = s->eslot_off = s->eslot = s->cslot = s->cslot_off = s->jslot = s->jslot_off = s->diag = NULL;
    s->efirst = NULL;
    s->zslot = NULL;
    s->nzslot = 0;
    s->nnz = 0;
}
