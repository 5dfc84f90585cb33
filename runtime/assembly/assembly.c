/* assembly.c -- internal forces and tangents of the elements into the Newton
 * system (the evaluation groups in parallel, every sum in element order), the
 * scatter of element vectors and matrices, element masses, the strain energy
 * and points of the centreline (system.h). */
#include "assembly/system.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/system_impl.h"

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
    for (int k = 0; k < m->npmass; ++k) {          /* point masses on it: m N^T N */
        const bk_point_mass *pm = &m->pmass[k];
        if (pm->elem != e)
            continue;
        et->shape(m->geoms[el->geom], pm->xi, 0.0, 0.0, work);
        for (int a = 0; a < ns; ++a)
            for (int b = 0; b < ns; ++b)
                for (int i = 0; i < 3; ++i)
                    Me[(et->shape_dof[a] + i) * nd + et->shape_dof[b] + i] += pm->mass * work[a] * work[b];
    }
}

void bk_element_weight(const bk_model *m, int e, double *N)
{
    const bk_elem *el = &m->elems[e];
    const bk_element *et = bk_elem_type(m, e);
    const double rho = m->mats[el->mat].rho;
    double Np[BK_MAX_SHAPE];
    et->volume(m->geoms[el->geom], N);
    for (int a = 0; a < et->nshape; ++a)
        N[a] *= rho;
    for (int k = 0; k < m->npmass; ++k)
        if (m->pmass[k].elem == e) {
            et->shape(m->geoms[el->geom], m->pmass[k].xi, 0.0, 0.0, Np);
            for (int a = 0; a < et->nshape; ++a)
                N[a] += m->pmass[k].mass * Np[a];
        }
}

int bk_element_has_role(const bk_element *et, bk_field_role role)
{
    for (int f = 0; f < et->nfield; ++f)
        if (et->field_role[f] == role)
            return 1;
    return 0;
}

int bk_assemble_internal(bk_system *s, const double *q, double *fint, double *Ax)
{
    const bk_model *m = s->m;
    int bad = 0;
    const int ng = s->ngroup, tangent = Ax != NULL;
    const size_t sq = s->slot_q, sK = s->slot_K, st = s->slot_tab, sm = s->slot_mat;
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

void bk_eval_point(const bk_model *m, const double *q, int e, double xi, double *pos, double *d)
{
    double qe[BK_MAX_ELEMENT_DOF], dd[9];
    bk_gather(m, e, q, qe);
    bk_elem_type(m, e)->frame(m->geoms[m->elems[e].geom], xi, qe, pos, d ? d : dd);
}

void bk_eval_sensor(const bk_model *m, const double *q, const bk_sensor *s, double *pos, double *d)
{
    double dd[9];
    d = d ? d : dd;
    bk_eval_point(m, q, s->elem, s->xi, pos, d);
    for (int k = 0; k < 3; ++k)
        if (s->off[k] != 0.0)          /* (a cable's d1, d2 are NaN: only where needed) */
            for (int i = 0; i < 3; ++i)
                pos[i] += s->off[k] * d[3 * k + i];
}

