/* system.c -- equation numbering, sparse pattern, assembly. */
#include "assembly/system.h"

#include "linalg/linsolve.h"

#include <math.h>

#include "model/amplitude.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#define BK_OMP(...) _Pragma(#__VA_ARGS__)
#else
#define BK_OMP(...)
#endif

/* Smaller models are evaluated by one thread: for them the fork/join and the
 * barrier cost more than they save (and much more on a loaded machine, where
 * a descheduled thread holds up the barrier: a 32-element gef pendulum spent
 * half its time spinning in libgomp with 2 threads on 2 busy cores). */
#define BK_PAR_MIN_ELEMS 256
/* Most parts of the parallel assembly (one per thread; owner codes of a byte). */
#define BK_MAX_PARTS 250
/* Parts per thread: the threads take parts as they finish the last (dynamic
 * schedule), so a thread whose core is busy with another process does fewer
 * of them instead of holding up the others. */
#define BK_PARTS_PER_THREAD 8

/* A pair whose elements are evaluated BK_LANES per call (bk_kernel.h, "Lane kernels"). */
static int lane_pair(const bk_pair *p)
{
    return p->force_lanes && p->force_tangent_lanes && p->nparam <= BK_MAT_MAXPARAM;
}

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

/* Equation of joint coordinate k (-1: constant or fixed). */
static int joint_eq(const bk_system *s, const bk_nlcon *c, int k)
{
    return c->dof[k] >= 0 ? s->eq[c->dof[k]] : -1;
}

/* Joint coordinates x[BK_JOINT_NX] from q (constants where dof < 0; with
 * rates, 0 there). */
static void joint_x(const bk_nlcon *c, const double *q, int rates, double *x)
{
    for (int k = 0; k < BK_JOINT_NX; ++k)
        x[k] = c->dof[k] >= 0 ? q[c->dof[k]] : rates ? 0.0 : c->x0[k];
}

static int find_slot(const bk_system *s, int row, int col)
{
    int lo = s->Ap[col], hi = s->Ap[col + 1];      /* bisection over the sorted rows of col */
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (s->Ai[mid] < row)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < s->Ap[col + 1] && s->Ai[lo] == row ? lo : -1;
}

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
static int make_parts(bk_system *s)
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
    for (int p = 0; p < np; ++p)
        for (int e = s->group[s->part[p]]; e < s->group[s->part[p + 1]]; ++e) {
            const int nd = bk_elem_type(m, e)->ndof, *sl = s->eslot + s->eslot_off[e], *d = m->elems[e].dofs;
            for (int k = 0; k < nd * nd; ++k)
                if (sl[k] >= 0)
                    mark_owner(&sown[sl[k]], p);
            for (int k = 0; k < nd; ++k)
                mark_owner(&down[d[k]], p);
        }
    /* elements with a shared slot or DOF get a scatter map with stage codes */
    long nmap = 0, nstage = 0;
    s->pel = malloc(((size_t)m->nelem + 1) * sizeof *s->pel);
    if (!s->pel)
        goto fail;
    for (int e = 0; e < m->nelem; ++e) {
        const int nd = bk_elem_type(m, e)->ndof, *sl = s->eslot + s->eslot_off[e], *d = m->elems[e].dofs;
        long ns = 0;
        for (int k = 0; k < nd * nd; ++k)
            ns += sl[k] >= 0 && sown[sl[k]] == 255;
        for (int k = 0; k < nd; ++k)
            ns += down[d[k]] == 255;
        s->pel[e] = ns ? nmap : -1;
        nmap += ns ? (long)nd * nd + nd : 0;
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

    /* Count entries per column (duplicates included). */
    long *cnt = calloc((size_t)s->neq + 1, sizeof *cnt);
    if (!cnt)
        goto oom;
    for (int e = 0; e < m->nelem; ++e) {
        const bk_elem *el = &m->elems[e];
        int nd = m->pairs[el->pair]->element->ndof;
        if (nd > s->maxdof)
            s->maxdof = nd;
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
    /* Fill buckets, then sort and deduplicate each column. */
    long *off = calloc((size_t)s->neq + 1, sizeof *off);
    if (!off) {
        free(cnt);
        goto oom;
    }
    for (int j = 0; j < s->neq; ++j)
        off[j + 1] = off[j] + cnt[j];
    int *rows = malloc((size_t)(off[s->neq] ? off[s->neq] : 1) * sizeof *rows);
    if (!rows) {
        free(cnt);
        free(off);
        goto oom;
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
    s->Ap = malloc(((size_t)s->neq + 1) * sizeof *s->Ap);
    if (!s->Ap) {
        free(cnt);
        free(off);
        free(rows);
        goto oom;
    }
    /* each column's rows without repeats (seen: the last column a row was
     * seen in), then sorted: they come as a few ascending runs, one per
     * element, which an insertion sort takes in about linear time (qsort was a
     * tenth of a small model's run) */
    int *seen = malloc(((size_t)s->neq + 1) * sizeof *seen);
    if (!seen) {
        free(cnt);
        free(off);
        free(rows);
        goto oom;
    }
    for (int j = 0; j < s->neq; ++j)
        seen[j] = -1;
    long nnz = 0;
    for (int j = 0; j < s->neq; ++j) {
        int *col = rows + off[j];
        long n = cnt[j], u = 0;
        for (long k = 0; k < n; ++k)
            if (seen[col[k]] != j) {
                seen[col[k]] = j;
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
        s->Ap[j] = (int)nnz;
        memmove(rows + nnz, col, (size_t)u * sizeof *col);
        nnz += u;
    }
    s->Ap[s->neq] = (int)nnz;
    s->nnz = nnz;
    free(seen);
    free(cnt);
    free(off);
    s->Ai = realloc(rows, (size_t)(nnz ? nnz : 1) * sizeof *rows);
    if (!s->Ai) {
        free(rows);
        goto oom;
    }

    /* Scatter maps. */
    s->eslot_off = malloc(((size_t)m->nelem + 1) * sizeof *s->eslot_off);
    if (!s->eslot_off)
        goto oom;
    long tot = 0;
    for (int e = 0; e < m->nelem; ++e) {
        int nd = m->pairs[m->elems[e].pair]->element->ndof;
        s->eslot_off[e] = (int)tot;
        tot += (long)nd * nd;
    }
    s->eslot_off[m->nelem] = (int)tot;
    s->eslot = malloc((size_t)(tot ? tot : 1) * sizeof *s->eslot);
    if (!s->eslot)
        goto oom;
    {
        /* at[row]: the slot of row in the column at hand (one pass over the
         * column instead of a bisection per entry); a slot outside that
         * column's range is another column's */
        int *at = malloc(((size_t)s->neq + 1) * sizeof *at);
        if (!at)
            goto oom;
        for (int j = 0; j < s->neq; ++j)
            at[j] = -1;
        for (int e = 0; e < m->nelem; ++e) {
            const bk_elem *el = &m->elems[e];
            int nd = m->pairs[el->pair]->element->ndof;
            int *sl = s->eslot + s->eslot_off[e];
            for (int c = 0; c < nd; ++c) {
                const int col = s->eq[el->dofs[c]];
                const int lo = col >= 0 ? s->Ap[col] : 0, hi = col >= 0 ? s->Ap[col + 1] : 0;
                for (int p = lo; p < hi; ++p)
                    at[s->Ai[p]] = p;
                for (int r = 0; r < nd; ++r) {
                    const int row = s->eq[el->dofs[r]], p = row >= 0 ? at[row] : -1;
                    sl[r * nd + c] = p >= lo && p < hi ? p : -1;
                }
            }
        }
        free(at);
    }
    /* The first term of every slot in element order is stored, not added
     * (assembly zeroes only the slots no element touches): efirst marks it. */
    s->efirst = calloc((size_t)(tot ? tot : 1), 1);
    {
        unsigned char *seen = calloc((size_t)(s->nnz ? s->nnz : 1), 1);
        if (!s->efirst || !seen) {
            free(seen);
            goto oom;
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
            goto oom;
        }
        for (long k = 0; k < s->nnz; ++k)
            if (!seen[k])
                s->zslot[s->nzslot++] = k;
        free(seen);
    }
    s->cslot_off = malloc(((size_t)m->nlincon + 1) * sizeof *s->cslot_off);
    if (!s->cslot_off)
        goto oom;
    tot = 0;
    for (int c = 0; c < m->nlincon; ++c) {
        s->cslot_off[c] = (int)tot;
        tot += 2L * m->lincons[c].nterm;
    }
    s->cslot_off[m->nlincon] = (int)tot;
    s->cslot = malloc((size_t)(tot ? tot : 1) * sizeof *s->cslot);
    if (!s->cslot)
        goto oom;
    for (int c = 0; c < m->nlincon; ++c) {
        const bk_lincon *lc = &m->lincons[c];
        int *sl = s->cslot + s->cslot_off[c];
        for (int k = 0; k < lc->nterm; ++k) {
            int q = s->eq[lc->dof[k]];
            sl[2 * k] = q >= 0 ? find_slot(s, s->nfree + c, q) : -1;
            sl[2 * k + 1] = q >= 0 ? find_slot(s, q, s->nfree + c) : -1;
        }
    }
    s->jslot_off = malloc(((size_t)m->nnlcon + 1) * sizeof *s->jslot_off);
    if (!s->jslot_off)
        goto oom;
    tot = 0;
    for (int j = 0; j < m->nnlcon; ++j) {
        s->jslot_off[j] = (int)tot;
        tot += BK_JOINT_NX * BK_JOINT_NX + 2L * BK_JOINT_NX * (s->jrow[j + 1] - s->jrow[j]);
    }
    s->jslot_off[m->nnlcon] = (int)tot;
    s->jslot = malloc((size_t)(tot ? tot : 1) * sizeof *s->jslot);
    if (!s->jslot)
        goto oom;
    for (int j = 0; j < m->nnlcon; ++j) {
        const bk_nlcon *jc = &m->nlcons[j];
        const int nx = BK_JOINT_NX, nr = s->jrow[j + 1] - s->jrow[j];
        int *sl = s->jslot + s->jslot_off[j];
        for (int a = 0; a < nx; ++a)
            for (int b = 0; b < nx; ++b) {
                int ra = joint_eq(s, jc, a), cb = joint_eq(s, jc, b);
                sl[nx * a + b] = ra >= 0 && cb >= 0 ? find_slot(s, ra, cb) : -1;
            }
        for (int r = 0; r < nr; ++r)
            for (int k = 0; k < nx; ++k) {
                int qk = joint_eq(s, jc, k), cc = s->nfree + s->jrow[j] + r;
                sl[nx * nx + nx * r + k] = qk >= 0 ? find_slot(s, cc, qk) : -1;
                sl[nx * nx + nx * nr + nx * r + k] = qk >= 0 ? find_slot(s, qk, cc) : -1;
            }
    }
    s->diag = malloc((size_t)(s->nfree ? s->nfree : 1) * sizeof *s->diag);
    if (!s->diag)
        goto oom;
    for (int j = 0; j < s->nfree; ++j)
        s->diag[j] = find_slot(s, j, j);
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
    if (make_parts(s) != 0)
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
    free(s->eq);
    free(s->Ap);
    free(s->Ai);
    free(s->eslot_off);
    free(s->eslot);
    free(s->cslot);
    free(s->cslot_off);
    free(s->diag);
    free(s->jrow);
    free(s->jslot);
    free(s->jslot_off);
    free(s->fe);
    free(s->Ke);
    free(s->bq);
    free(s->bf);
    free(s->bK);
    free(s->btab);
    free(s->bmat);
    free(s->group);
    free(s->efirst);
    free(s->zslot);
    free(s->part);
    free(s->pel);
    free(s->pmap);
    free(s->stage);
    free(s->sh_ptr);
    free(s->sh_idx);
    free(s->sh_to);
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
static void eval_group(const bk_system *s, int g, const double *q, double *restrict bq,
                       double *restrict bf, double *restrict bK, double *restrict btab,
                       double *restrict bmat, int tangent)
{
    const bk_model *m = s->m;
    const int e0 = s->group[g], n = s->group[g + 1] - e0;
    const bk_elem *el0 = &m->elems[e0];
    const bk_pair *p = m->pairs[el0->pair];
    if (!lane_pair(p)) {
        bk_gather(m, e0, q, bq);
        const double *tab = m->tabs[el0->geom], *mat = m->mats[el0->mat].params;
        if (tangent)
            p->force_tangent(bq, tab, mat, bf, bK);
        else
            p->force(bq, tab, mat, bf);
        return;
    }
    const int nd = p->element->ndof, nt = p->ntab, np = p->nparam;
    /* unused lanes repeat the last element (valid inputs; outputs ignored) */
    for (int l = 0; l < BK_LANES; ++l) {
        const bk_elem *el = &m->elems[e0 + (l < n ? l : n - 1)];
        const int *d = el->dofs;
        const double *tab = m->tabs[el->geom], *mat = m->mats[el->mat].params;
        for (int k = 0; k < nd; ++k)
            bq[k * BK_LANES + l] = q[d[k]];
        for (int k = 0; k < nt; ++k)
            btab[k * BK_LANES + l] = tab[k];
        for (int k = 0; k < np; ++k)
            bmat[k * BK_LANES + l] = mat[k];
    }
    if (tangent)
        p->force_tangent_lanes(bq, btab, bmat, bf, bK);
    else
        p->force_lanes(bq, btab, bmat, bf);
}

/* Element e's f and K at stride `stride` (1: plain, BK_LANES: one lane of a
 * lane group) into fint and Ax; 1 when f has a non-finite entry. */
static int scatter_strided(const bk_system *s, int e, const double *fe, const double *Ke, int stride,
                           double *fint, double *Ax)
{
    const bk_model *m = s->m;
    const int *d = m->elems[e].dofs;
    const int nd = bk_elem_type(m, e)->ndof;
    int bad = 0;
    for (int k = 0; k < nd; ++k) {
        const double v = fe[(size_t)k * stride];
        if (!isfinite(v))
            bad = 1;
        fint[d[k]] += v;
    }
    if (Ax) {
        const int *sl = s->eslot + s->eslot_off[e];
        const unsigned char *first = s->efirst + s->eslot_off[e];
        for (int k = 0; k < nd * nd; ++k) {
            const double v = Ke[(size_t)k * stride];
            if (sl[k] < 0)
                continue;
            if (first[k])
                Ax[sl[k]] = 0.0 + v;   /* as adding v to a zeroed slot: -0.0 gives +0.0 */
            else if (v != 0.0)
                Ax[sl[k]] += v;
        }
    }
    return bad;
}

/* The same, where the parallel assembly stages an element's terms for shared
 * slots and DOFs (s->pel, system.h); serially (no pel) scatter_strided. */
static int scatter_strided_part(const bk_system *s, int e, const double *fe, const double *Ke, int stride,
                                double *fint, double *Ax)
{
    if (!s->pel || s->pel[e] < 0)                /* serial, or nothing shared */
        return scatter_strided(s, e, fe, Ke, stride, fint, Ax);
    const int nd = bk_elem_type(s->m, e)->ndof, *code = s->pmap + s->pel[e];
    double *stage = s->stage;
    int bad = 0;
    for (int k = 0; k < nd; ++k) {
        const double v = fe[(size_t)k * stride];
        const int c = code[nd * nd + k];
        if (!isfinite(v))
            bad = 1;
        if (c >= 0)
            fint[c] += v;
        else
            stage[-2 - c] = v;
    }
    if (Ax) {
        const unsigned char *first = s->efirst + s->eslot_off[e];
        for (int k = 0; k < nd * nd; ++k) {
            const double v = Ke[(size_t)k * stride];
            const int c = code[k];
            if (c >= 0) {
                if (first[k])
                    Ax[c] = 0.0 + v;
                else if (v != 0.0)
                    Ax[c] += v;
            } else if (c <= -2)
                stage[-2 - c] = v;
        }
    }
    return bad;
}

static int scatter_group(const bk_system *s, int g, const double *bf, const double *bK, double *fint, double *Ax)
{
    const int e0 = s->group[g], n = s->group[g + 1] - e0;
    if (!lane_pair(s->m->pairs[s->m->elems[e0].pair]))
        return scatter_strided_part(s, e0, bf, bK, 1, fint, Ax);
    int bad = 0;
    for (int l = 0; l < n; ++l)
        bad |= scatter_strided_part(s, e0 + l, bf + l, Ax ? bK + l : NULL, BK_LANES, fint, Ax);
    return bad;
}

int bk_scatter(const bk_model *m, int e, const double *xe, double c, double *x)
{
    const int *d = m->elems[e].dofs;
    const int nd = bk_elem_type(m, e)->ndof;
    int bad = 0;
    for (int k = 0; k < nd; ++k) {
        if (!isfinite(xe[k]))
            bad = 1;
        x[d[k]] += c * xe[k];
    }
    return bad;
}

void bk_scatter_matrix(const bk_system *s, int e, const double *Ke, double c, double *Ax)
{
    const int nd = bk_elem_type(s->m, e)->ndof;
    const int *sl = s->eslot + s->eslot_off[e];
    for (int k = 0; k < nd * nd; ++k)
        if (sl[k] >= 0 && Ke[k] != 0.0)
            Ax[sl[k]] += c * Ke[k];
}

void bk_element_mass(const bk_model *m, int e, double *work, double *Me)
{
    const bk_elem *el = &m->elems[e];
    const bk_element *et = bk_elem_type(m, e);
    const int ns = et->nshape, nd = et->ndof;
    const double rho = m->mats[el->mat].rho;
    et->mass(m->geoms[el->geom], work);
    for (int k = 0; k < nd * nd; ++k)
        Me[k] = 0.0;
    for (int a = 0; a < ns; ++a)
        for (int b = 0; b < ns; ++b)
            for (int i = 0; i < 3; ++i)
                Me[(et->shape_dof[a] + i) * nd + et->shape_dof[b] + i] = rho * work[a * ns + b];
}

int bk_element_has_role(const bk_element *et, bk_field_role role)
{
    for (int f = 0; f < et->nfield; ++f)
        if (et->field_role[f] == role)
            return 1;
    return 0;
}

/* Position shape functions N of element e times a vector v into x:
 * x[dof of shape function a, component k] += c N[a] v[k]. */
static void scatter_shape(const bk_model *m, int e, const double *N, const double *v, double c, double *x)
{
    const int *d = m->elems[e].dofs;
    const bk_element *et = bk_elem_type(m, e);
    for (int a = 0; a < et->nshape; ++a)
        for (int k = 0; k < 3; ++k)
            x[d[et->shape_dof[a] + k]] += c * N[a] * v[k];
}

int bk_assemble_internal(bk_system *s, const double *q, double *fint, double *Ax)
{
    const bk_model *m = s->m;
    int bad = 0;
    const int ng = s->ngroup, tangent = Ax != NULL;
    const size_t sq = s->slot_q, sK = s->slot_K, st = s->slot_tab, sm = (size_t)BK_LANES * BK_MAT_MAXPARAM;
    if (Ax)                            /* slots no element writes (constraint rows) */
        for (long k = 0; k < s->nzslot; ++k)
            Ax[s->zslot[k]] = 0.0;
    if (s->npart > 1) {
        memset(fint, 0, (size_t)m->ndof * sizeof *fint);
        BK_OMP(omp parallel num_threads(s->nthreads) reduction(|: bad))
        {
            int t = 0;
#ifdef _OPENMP
            t = omp_get_thread_num();
#endif
            /* each part by one thread, whichever is free (the order of every
             * sum is the part's own, or the staged element order) */
            BK_OMP(omp for schedule(dynamic, 1) nowait)
            for (int p = 0; p < s->npart; ++p)
                for (int g = s->part[p]; g < s->part[p + 1]; ++g) {
                    eval_group(s, g, q, s->bq + t * sq, s->bf + t * sq, s->bK + t * sK, s->btab + t * st,
                               s->bmat + t * sm, tangent);
                    bad |= scatter_group(s, g, s->bf + t * sq, s->bK + t * sK, fint, Ax);
                }
        }
        /* the shared slots and DOFs, their terms in element order */
        for (int i = 0; i < s->nshared; ++i) {
            const long to = s->sh_to[i];
            if (i < s->nshared_dof) {
                for (int j = s->sh_ptr[i]; j < s->sh_ptr[i + 1]; ++j)
                    fint[to] += s->stage[s->sh_idx[j]];
            } else if (Ax) {
                double a = 0.0;                /* a shared slot's first term is staged too */
                for (int j = s->sh_ptr[i]; j < s->sh_ptr[i + 1]; ++j) {
                    const double v = s->stage[s->sh_idx[j]];
                    if (v != 0.0)
                        a += v;
                }
                Ax[to] = a;
            }
        }
    } else {
        /* Serial: no OpenMP region at all (libgomp allocates a team even for
         * a region whose if clause is false).  Same groups, same order of sums. */
        memset(fint, 0, (size_t)m->ndof * sizeof *fint);
        for (int g = 0; g < ng; ++g) {
            eval_group(s, g, q, s->bq, s->bf, s->bK, s->btab, s->bmat, tangent);
            bad |= scatter_group(s, g, s->bf, s->bK, fint, Ax);
        }
    }
    return bad ? -1 : 0;
}

double bk_strain_energy(const bk_system *s, const double *q)
{
    const bk_model *m = s->m;
    double qe[BK_MAX_ELEMENT_DOF], U = 0.0;
    for (int e = 0; e < m->nelem; ++e) {
        const bk_elem *el = &m->elems[e];
        const bk_pair *p = m->pairs[el->pair];
        bk_gather(m, e, q, qe);
        U += p->energy(qe, m->tabs[el->geom], m->mats[el->mat].params);
    }
    return U;
}

void bk_force_shape(const bk_model *m, const bk_force_load *f, double *N)
{
    const bk_element *et = bk_elem_type(m, f->elem);
    const double *g = m->geoms[m->elems[f->elem].geom];
    if (!f->section) {
        et->shape(g, f->xi, f->y, f->z, N);
        return;
    }
    /* uniform over the rectangle b x h: 3 x 3 Gauss points, exact for shape
     * functions up to degree 5 across the section */
    static const double gp[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
    static const double gw[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
    double Na[BK_MAX_SHAPE];
    for (int a = 0; a < et->nshape; ++a)
        N[a] = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            et->shape(g, f->xi, 0.5 * g[BK_GEOM_B] * gp[i], 0.5 * g[BK_GEOM_H] * gp[j], Na);
            for (int a = 0; a < et->nshape; ++a)
                N[a] += gw[i] * gw[j] * Na[a];
        }
}

void bk_external_load(const bk_system *s, double *fext)
{
    const bk_model *m = s->m;
    double N[BK_MAX_SHAPE];
    memset(fext, 0, (size_t)m->ndof * sizeof *fext);
    for (int i = 0; i < m->nforce; ++i) {
        const bk_force_load *f = &m->forces[i];
        if (f->amp >= 0 || f->follower)
            continue;                  /* bk_assemble_loads (loads.h) */
        bk_force_shape(m, f, N);
        scatter_shape(m, f->elem, N, f->value, 1.0, fext);
    }
    if (m->has_gravity) {
        double *g = calloc((size_t)m->ndof, sizeof *g);
        if (g) {
            bk_gravity_load(s, g);
            for (int i = 0; i < m->ndof; ++i)
                fext[i] += g[i];
            free(g);
        }
    }
}

void bk_gravity_load(const bk_system *s, double *fg)
{
    const bk_model *m = s->m;
    double N[BK_MAX_SHAPE];
    memset(fg, 0, (size_t)m->ndof * sizeof *fg);
    if (m->has_gravity && !m->gravity_amp) {       /* with an amplitude: bk_assemble_loads */
        for (int e = 0; e < m->nelem; ++e) {
            const bk_elem *el = &m->elems[e];
            bk_elem_type(m, e)->volume(m->geoms[el->geom], N);
            scatter_shape(m, e, N, m->gravity, m->mats[el->mat].rho, fg);
        }
    }
}

void bk_assemble_follower(bk_system *s, const double *q, double lam, double *fint, double *Ax)
{
    const bk_model *m = s->m;
    double qe[BK_MAX_ELEMENT_DOF];
    for (int i = 0; i < m->nmoment; ++i) {
        const bk_moment_load *mo = &m->moments[i];
        if (mo->amp >= 0 || mo->follower)
            continue;                  /* bk_assemble_loads (loads.h) */
        const bk_elem *el = &m->elems[mo->elem];
        bk_gather(m, mo->elem, q, qe);
        bk_elem_type(m, mo->elem)->moment(m->geoms[el->geom], mo->xi, qe, mo->value, s->fe, s->Ke);
        bk_scatter(m, mo->elem, s->fe, -lam, fint);
        if (Ax)
            bk_scatter_matrix(s, mo->elem, s->Ke, -lam, Ax);
    }
}

/* Time factors of a rheonomic constraint: (C, S) = d^k/dt^k of (cos phi, sin phi). */
static void angle_factors(const bk_lincon *c, double t, int k, double *C, double *S)
{
    double w = 2.0 * M_PI * c->freq;
    double phi = c->kappa * (c->rate * t + c->amp * sin(w * t));
    double d1 = c->kappa * (c->rate + c->amp * w * cos(w * t));
    double d2 = -c->kappa * c->amp * w * w * sin(w * t);
    if (c->ampl) {
        phi += c->kappa * c->angle * bk_amp_eval(c->ampl, t, 0);
        d1 += c->kappa * c->angle * bk_amp_eval(c->ampl, t, 1);
        d2 += c->kappa * c->angle * bk_amp_eval(c->ampl, t, 2);
    }
    double cp = cos(phi), sp = sin(phi);
    if (k == 0) {
        *C = cp;
        *S = sp;
    } else if (k == 1) {
        *C = -sp * d1;
        *S = cp * d1;
    } else {
        *C = -cp * d1 * d1 - sp * d2;
        *S = -sp * d1 * d1 + cp * d2;
    }
}

double bk_constraint_row(const bk_lincon *c, const double *x, double t, int k, int with_rhs)
{
    double C, S, sum = 0.0;
    angle_factors(c, t, k, &C, &S);
    if (with_rhs)
        sum = -(k == 0 ? c->r0 : 0.0) - c->rc * C - c->rs * S;
    for (int j = 0; j < c->nterm; ++j)
        sum += ((k == 0 ? c->c0[j] : 0.0) + c->cc[j] * C + c->cs[j] * S) * x[c->dof[j]];
    return sum;
}

/* The joints' part of bk_assemble_constraints: rows s g, s G^T nu into the
 * free rows, s G, s G^T and the Hessian term s sum_k nu_k d2 g_k/dq2. */
static void assemble_joints(const bk_system *s, const double *q, const double *nu, double *r, double *Ax)
{
    const bk_model *m = s->m;
    const int nx = BK_JOINT_NX;
    double x[BK_JOINT_NX], g[BK_JOINT_MAXROW], G[BK_JOINT_MAXROW * BK_JOINT_NX], H[BK_JOINT_NX * BK_JOINT_NX];
    for (int j = 0; j < m->nnlcon; ++j) {
        const bk_nlcon *c = &m->nlcons[j];
        const int nr = s->jrow[j + 1] - s->jrow[j], row0 = s->jrow[j];
        const int *sl = s->jslot + s->jslot_off[j];
        joint_x(c, q, 0, x);
        c->kind->eval(x, c->prm, g, G);
        for (int i = 0; i < nr; ++i) {
            if (r)
                r[s->nfree + row0 + i] = s->cscale * g[i];
            for (int k = 0; k < nx; ++k) {
                int e = joint_eq(s, c, k);
                if (e < 0)
                    continue;
                if (r && nu)
                    r[e] += s->cscale * G[nx * i + k] * nu[row0 + i];
                if (Ax && sl[nx * nx + nx * i + k] >= 0) {
                    Ax[sl[nx * nx + nx * i + k]] += s->cscale * G[nx * i + k];
                    Ax[sl[nx * nx + nx * nr + nx * i + k]] += s->cscale * G[nx * i + k];
                }
            }
        }
        if (Ax && nu) {
            c->kind->hessian(x, c->prm, nu + row0, H);
            for (int k = 0; k < nx * nx; ++k)
                if (sl[k] >= 0)
                    Ax[sl[k]] += s->cscale * H[k];
        }
    }
}

void bk_constraint_accel_rhs(const bk_system *s, const double *q, const double *qd, double t, double *r)
{
    const bk_model *m = s->m;
    const int nx = BK_JOINT_NX;
    for (int c = 0; c < m->nlincon; ++c)
        r[s->nfree + c] = -s->cscale * (2.0 * bk_constraint_row(&m->lincons[c], qd, t, 1, 0)
                                        + bk_constraint_row(&m->lincons[c], q, t, 2, 1));
    double x[BK_JOINT_NX], xd[BK_JOINT_NX], nu[BK_JOINT_MAXROW], H[BK_JOINT_NX * BK_JOINT_NX];
    for (int j = 0; j < m->nnlcon; ++j) {
        const bk_nlcon *c = &m->nlcons[j];
        const int nr = s->jrow[j + 1] - s->jrow[j];
        joint_x(c, q, 0, x);
        joint_x(c, qd, 1, xd);
        for (int i = 0; i < nr; ++i) {
            for (int k = 0; k < nr; ++k)
                nu[k] = k == i;
            c->kind->hessian(x, c->prm, nu, H);
            double v = 0.0;
            for (int a = 0; a < nx; ++a)
                for (int b = 0; b < nx; ++b)
                    v += xd[a] * H[nx * a + b] * xd[b];
            r[s->nfree + s->jrow[j] + i] = -s->cscale * v;
        }
    }
}

void bk_constraint_jacobian_row(const bk_system *s, const double *q, double t, int c,
                                void (*add)(void *ctx, int eq, double v), void *ctx)
{
    const bk_model *m = s->m;
    if (c < m->nlincon) {
        const bk_lincon *lc = &m->lincons[c];
        double C, S;
        angle_factors(lc, t, 0, &C, &S);
        for (int k = 0; k < lc->nterm; ++k)
            if (s->eq[lc->dof[k]] >= 0)
                add(ctx, s->eq[lc->dof[k]], lc->c0[k] + lc->cc[k] * C + lc->cs[k] * S);
        return;
    }
    int j = 0;
    while (j + 1 < m->nnlcon && s->jrow[j + 1] <= c)
        ++j;
    const bk_nlcon *jc = &m->nlcons[j];
    double x[BK_JOINT_NX], g[BK_JOINT_MAXROW], G[BK_JOINT_MAXROW * BK_JOINT_NX];
    joint_x(jc, q, 0, x);
    jc->kind->eval(x, jc->prm, g, G);
    for (int k = 0; k < BK_JOINT_NX; ++k)
        if (joint_eq(s, jc, k) >= 0)
            add(ctx, joint_eq(s, jc, k), G[BK_JOINT_NX * (c - s->jrow[j]) + k]);
}

int bk_constraint_multipliers(bk_system *s, const double *q, double t, const double *r, double *nu)
{
    if (s->ncon == 0)
        return 0;
    double *Ax = calloc((size_t)(s->nnz ? s->nnz : 1), sizeof *Ax);
    double *b = calloc((size_t)s->neq, sizeof *b);
    bk_linsolver ls = {0};
    int rc = -1;
    if (!Ax || !b)
        goto out;
    /* [c I  s G^T; s G  0] [x; dnu] = [-r; 0]: x = -(r + s G^T dnu)/c with G x = 0 */
    for (int j = 0; j < s->nfree; ++j)
        if (s->diag[j] >= 0)
            Ax[s->diag[j]] = s->cscale;
    bk_assemble_constraints(s, q, NULL, t, NULL, Ax);
    for (int j = 0; j < s->nfree; ++j)
        b[j] = -r[j];
    if (bk_lin_init(&ls, s->neq, s->Ap, s->Ai) != BK_LIN_OK || bk_lin_factor(&ls, Ax) != BK_LIN_OK ||
        ls.rcond < 1e-12 || bk_lin_solve(&ls, b) != BK_LIN_OK)
        goto out;
    for (int c = 0; c < s->ncon; ++c)
        if (!isfinite(b[s->nfree + c]))
            goto out;
    for (int c = 0; c < s->ncon; ++c)
        nu[c] += b[s->nfree + c];
    rc = 0;
out:
    bk_lin_free(&ls);
    free(Ax);
    free(b);
    return rc;
}

void bk_constraint_hessian(const bk_system *s, const double *q, const double *lam,
                           void (*add)(void *ctx, int i, int j, double v), void *ctx)
{
    const int nx = BK_JOINT_NX;
    double x[BK_JOINT_NX], H[BK_JOINT_NX * BK_JOINT_NX];
    for (int j = 0; j < s->m->nnlcon; ++j) {
        const bk_nlcon *c = &s->m->nlcons[j];
        joint_x(c, q, 0, x);
        c->kind->hessian(x, c->prm, lam + s->jrow[j], H);
        for (int a = 0; a < nx; ++a)
            for (int b = 0; b < nx; ++b)
                if (joint_eq(s, c, a) >= 0 && joint_eq(s, c, b) >= 0 && H[nx * a + b] != 0.0)
                    add(ctx, joint_eq(s, c, a), joint_eq(s, c, b), H[nx * a + b]);
    }
}

void bk_assemble_constraints(const bk_system *s, const double *q, const double *nu, double t,
                             double *r, double *Ax)
{
    const bk_model *m = s->m;
    for (int c = 0; c < m->nlincon; ++c) {
        const bk_lincon *lc = &m->lincons[c];
        const int *sl = s->cslot + s->cslot_off[c];
        double C, S;
        angle_factors(lc, t, 0, &C, &S);
        double g = -(lc->r0 + lc->rc * C + lc->rs * S);
        for (int k = 0; k < lc->nterm; ++k) {
            double coef = lc->c0[k] + lc->cc[k] * C + lc->cs[k] * S;
            g += coef * q[lc->dof[k]];
            int qe = s->eq[lc->dof[k]];
            if (qe >= 0 && r)
                r[qe] += s->cscale * coef * nu[c];
            if (Ax && sl[2 * k] >= 0) {
                Ax[sl[2 * k]] += s->cscale * coef;
                Ax[sl[2 * k + 1]] += s->cscale * coef;
            }
        }
        if (r)
            r[s->nfree + c] = s->cscale * g;
    }
    assemble_joints(s, q, nu, r, Ax);
}

double bk_constraint_coef(const bk_lincon *c, int k, double t)
{
    double C, S;
    angle_factors(c, t, 0, &C, &S);
    return c->c0[k] + c->cc[k] * C + c->cs[k] * S;
}

double bk_constraint_residual(const bk_system *s, const double *q, double t)
{
    double worst = 0.0;
    for (int c = 0; c < s->m->nlincon; ++c)
        worst = fmax(worst, fabs(bk_constraint_row(&s->m->lincons[c], q, t, 0, 1)));
    double x[BK_JOINT_NX], g[BK_JOINT_MAXROW], G[BK_JOINT_MAXROW * BK_JOINT_NX];
    for (int j = 0; j < s->m->nnlcon; ++j) {
        const bk_nlcon *c = &s->m->nlcons[j];
        joint_x(c, q, 0, x);
        c->kind->eval(x, c->prm, g, G);
        for (int i = 0; i < c->kind->nrow; ++i)
            worst = fmax(worst, fabs(g[i]));
    }
    return worst;
}

void bk_eval_point(const bk_model *m, const double *q, int e, double xi, double *pos, double *d)
{
    double qe[BK_MAX_ELEMENT_DOF], dd[9];
    bk_gather(m, e, q, qe);
    bk_elem_type(m, e)->frame(m->geoms[m->elems[e].geom], xi, qe, pos, d ? d : dd);
}
