/* sections.c -- section forces along the beams (sections.csv): from the
 * nodal actions of the elements, and from the elements' own stress resultants
 * at their sample points where the pair offers them (see forces.h). */
#include "output/forces_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/loads.h"
#include "model/amplitude.h"
#include "base/csvrow.h"

#ifdef _OPENMP
#include <omp.h>
#endif

/* The force and moment the element's node `node` (first or last) exerts on it,
 * about the node's position xn. */
static void node_action(const bk_forces *f, const bk_model *m, int e, int node, const double *q, const double *ge,
                        double *xn, double *F, double *M)
{
    const bk_element *et = bk_elem_type(m, e);
    int n = -1, pos = -1;
    F[0] = F[1] = F[2] = M[0] = M[1] = M[2] = 0.0;
    for (int k = 0; k < et->nfield; ++k) {
        if (et->field_role[k] == BK_FIELD_POSITION) {
            ++n;
            if (n == node)
                pos = et->field_dof[k];
        }
        if (et->field_role[k] == BK_FIELD_MULTIPLIER || n != node)
            continue;
        if (et->field_role[k] == BK_FIELD_POSITION)
            for (int i = 0; i < 3; ++i)
                xn[i] = q[m->elems[e].dofs[pos + i]];
    }
    n = -1;
    for (int k = 0; k < et->nfield; ++k) {
        if (et->field_role[k] == BK_FIELD_POSITION)
            ++n;
        if (et->field_role[k] == BK_FIELD_MULTIPLIER || n != node)
            continue;
        for (int c = 0; c < et->field_dim[k]; ++c) {
            int l = et->field_dof[k] + c;
            bk_forces_map_dof(f, q, m->elems[e].dofs[l], ge[l], xn, F, M);
        }
    }
}

/* N, Q2, Q3, T, M2, M3 of the force F and the moment M (global axes) on the
 * section at xi of element e (state qe), sign sg: in the orthonormal section
 * frame; without section axes (the cable) the axial force and the torque only. */
static void section_components(const bk_model *m, int e, const double *qe, double xi, const double *F,
                               const double *M, double sg, double *out)
{
    double R[9];
    if (bk_section_frame(m, e, qe, xi, R) == 0) {
        for (int i = 0; i < 3; ++i) {
            const double *ax = R + 3 * ((i + 2) % 3);     /* e3, e1, e2 */
            out[i] = sg * (F[0] * ax[0] + F[1] * ax[1] + F[2] * ax[2]);
            out[3 + i] = sg * (M[0] * ax[0] + M[1] * ax[1] + M[2] * ax[2]);
        }
    } else {                            /* no section axes: the axial force and torque only */
        const bk_element *et = bk_elem_type(m, e);
        double pos[3], d[9];
        et->frame(m->geoms[m->elems[e].geom], xi, qe, pos, d);
        double n3 = sqrt(d[6] * d[6] + d[7] * d[7] + d[8] * d[8]);
        for (int i = 0; i < 6; ++i)
            out[i] = NAN;
        out[0] = sg * (F[0] * d[6] + F[1] * d[7] + F[2] * d[8]) / n3;
        out[3] = sg * (M[0] * d[6] + M[1] * d[7] + M[2] * d[8]) / n3;
    }
}

/* One row of sections.csv: step,time,beam,element,source,point,xi,s,x,y,z,N,Q2,Q3,T,M2,M3
 * (pos: x, y, z; out: N, Q2, Q3, T, M2, M3). */
static void section_row(FILE *fp, bk_rowqueue *rq, int step, double t, const char *beam, int e, const char *source,
                        int point, double xi, double s, const double *pos, const double *out)
{
    bk_row r;
    bk_row_begin(&r, fp, rq);
    bk_row_int(&r, step);
    bk_row_num(&r, t);
    bk_row_str(&r, beam);
    bk_row_int(&r, e);
    bk_row_str(&r, source);
    bk_row_int(&r, point);
    bk_row_num(&r, xi);
    bk_row_num(&r, s);
    for (int i = 0; i < 3; ++i)
        bk_row_num(&r, pos[i]);
    for (int i = 0; i < 6; ++i)
        bk_row_num(&r, out[i]);
    bk_row_end(&r);
}

/* The element's own stress resultants (bk_pair.sections) at its sample points
 * into f->ssec and their points into pos (sres: the thread's scratch). */
static void stress_values(bk_forces *f, const bk_model *m, int e, const double *qe, double *sres, double *pos)
{
    const bk_elem *el = &m->elems[e];
    const bk_pair *p = m->pairs[el->pair];
    if (!p->sections)
        return;
    p->sections(m->geoms[el->geom], qe, m->tabs[el->geom], m->mats[el->mat].params, sres);
    for (int k = 0; k < p->nsample; ++k) {
        const double *o = sres + 9 * k;
        section_components(m, e, qe, p->sample_xi[k], o + 3, o + 6, 1.0,
                           f->ssec + 6 * ((size_t)f->maxsample * (size_t)e + (size_t)k));
        for (int i = 0; i < 3; ++i)
            pos[3 * k + i] = o[i];
    }
}

/* Section record k's section forces: its element's nodal actions at both ends
 * into f->sec and their points into f->spos, its own stress resultants (buf,
 * sres: the thread's scratch). */
static void section_values(bk_forces *f, bk_system *s, int k, double x, const double *q, const double *qd,
                           const double *qdd, double *buf, double *sres)
{
    const bk_model *m = s->m;
    size_t md = (size_t)s->maxdof;
    double *ge = buf, *Qe = ge + md, *qe = Qe + md, *qde = qe + md, *qdde = qde + md;
    double *K1 = qdde + md, *K2 = K1 + md * md, *K3 = K2 + md * md, *Me = K3 + md * md;
    const double ra = m->dyn.rayleigh_alpha, rb = m->dyn.rayleigh_beta;
    const bk_section_rec *sr = &m->sections[k];
    const int e = sr->elem;
    const bk_elem *el = &m->elems[e];
    const bk_pair *p = m->pairs[el->pair];
    const bk_element *et = p->element;
    const bk_mat *mat = &m->mats[el->mat];
    const int ne = et->ndof;
    double *pos = f->spos + (6 + 3 * (size_t)f->maxsample) * (size_t)e;
    bk_gather(m, e, q, qe);
    if (qdd && rb != 0.0)
        p->force_tangent(qe, m->tabs[el->geom], mat->params, ge, K1);
    else
        p->force(qe, m->tabs[el->geom], mat->params, ge);
    if (qdd) {
        bk_gather(m, e, qd, qde);
        bk_gather(m, e, qdd, qdde);
        if (rb != 0.0)
            for (int i = 0; i < ne; ++i)
                for (int j = 0; j < ne; ++j)
                    ge[i] += rb * K1[i * ne + j] * qde[j];
        bk_element_mass(m, e, K1, Me);
        for (int j = 0; j < ne; ++j)
            Qe[j] = qdde[j] + ra * qde[j];           /* (Qe is free until the viscous forces) */
        bk_forces_rows_times(ne, Me, Qe, ge, 0);
        if (mat->nvisc > 0 && p->viscous) {
            p->viscous_force(qe, qde, m->tabs[el->geom], mat->visc, Qe);
            for (int i = 0; i < ne; ++i)
                ge[i] += Qe[i];
        }
        if (et->rotary) {
            double T = 0.0;
            et->rotary(m->geoms[el->geom], qe, qde, qdde, Qe, K1, K2, K3, &T);
            for (int i = 0; i < ne; ++i)
                ge[i] += mat->rho * Qe[i];
        }
    }
    memset(Qe, 0, (size_t)ne * sizeof *Qe);      /* the interactions' forces along the element */
    for (int k = 0; k < s->ninter; ++k)
        if (s->inter[k].ops->element_loads)
            s->inter[k].ops->element_loads(s->inter[k].self, s, q, x, e, Qe);
    for (int i = 0; i < ne; ++i)
        ge[i] -= Qe[i];
    for (int end = 0; end < 2; ++end) {
        double *xn = pos + 3 * end, F[3], M[3];
        xn[0] = xn[1] = xn[2] = NAN;
        node_action(f, m, e, end ? et->nnode - 1 : 0, q, ge, xn, F, M);
        section_components(m, e, qe, et->node_xi[end ? et->nnode - 1 : 0], F, M, end ? 1.0 : -1.0,
                           f->sec + 12 * (size_t)e + 6 * end);
    }
    if (f->sections)
        stress_values(f, m, e, qe, sres, pos + 6);
}

/* The section forces of every section record, on the threads (each record's
 * own computation: the same bits for any thread count), then their rows in
 * the records' order. */
void bk_forces_sections(bk_forces *f, bk_system *s, int step, double x, const double *q, const double *qd,
                           const double *qdd)
{
    const bk_model *m = s->m;
    const int nsec = m->nsection;
    if (nsec >= BK_SECTIONS_PAR_MIN) {
#pragma omp parallel num_threads(f->nthread)
        {
            int t = 0;
#ifdef _OPENMP
            t = omp_get_thread_num();
#endif
            double *buf = f->sbuf + (size_t)t * f->sbuf_stride, *sres = f->sres + (size_t)t * f->sres_stride;
#pragma omp for schedule(static)
            for (int k = 0; k < nsec; ++k)
                section_values(f, s, k, x, q, qd, qdd, buf, sres);
        }
    } else {            /* no parallel region (libgomp allocates a team even when it runs alone) */
        for (int k = 0; k < nsec; ++k)
            section_values(f, s, k, x, q, qd, qdd, f->sbuf, f->sres);
    }
    for (int k = 0; f->sections && k < nsec; ++k) {
        const bk_section_rec *sr = &m->sections[k];
        const int e = sr->elem;
        const bk_pair *p = m->pairs[m->elems[e].pair];
        const bk_element *et = p->element;
        const double *pos = f->spos + (6 + 3 * (size_t)f->maxsample) * (size_t)e;
        for (int end = 0; end < 2; ++end)
            section_row(f->sections, f->rq, step, x, sr->beam, e, "nodal", end, et->node_xi[end ? et->nnode - 1 : 0],
                        end ? sr->s1 : sr->s0, pos + 3 * end, f->sec + 12 * (size_t)e + 6 * end);
        for (int j = 0; p->sections && j < p->nsample; ++j) {
            const double xi = p->sample_xi[j];
            section_row(f->sections, f->rq, step, x, sr->beam, e, p->sample_source, j, xi,
                        sr->s0 + xi * (sr->s1 - sr->s0), pos + 6 + 3 * j,
                        f->ssec + 6 * ((size_t)f->maxsample * (size_t)e + (size_t)j));
        }
    }
    f->sec_step = step;
}
