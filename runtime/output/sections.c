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
#include "base/filewriter.h"

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
 * (pos: x, y, z; out: N, Q2, Q3, T, M2, M3); on_thread: written by a job on
 * the queue's thread (csvrow.h bk_row_begin_thread). */
static void section_row(FILE *fp, bk_rowqueue *rq, int on_thread, int step, double t, const char *beam, int e,
                        const char *source, int point, double xi, double s, const double *pos, const double *out)
{
    bk_row r;
    if (on_thread)
        bk_row_begin_thread(&r, fp, rq);
    else
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
 * into ssec (forces.h) and their points into pos (sres: the thread's scratch). */
static void stress_values(const bk_forces *f, const bk_model *m, int e, const double *qe, double *sres, double *pos,
                          double *ssec)
{
    const bk_elem *el = &m->elems[e];
    const bk_pair *p = m->pairs[el->pair];
    if (!p->sections)
        return;
    p->sections(m->geoms[el->geom], qe, m->tabs[el->geom], m->mats[el->mat].params, sres);
    for (int k = 0; k < p->nsample; ++k) {
        const double *o = sres + 9 * k;
        section_components(m, e, qe, p->sample_xi[k], o + 3, o + 6, 1.0,
                           ssec + 6 * ((size_t)f->maxsample * (size_t)e + (size_t)k));
        for (int i = 0; i < 3; ++i)
            pos[3 * k + i] = o[i];
    }
}

/* Section record k's section forces: its element's nodal actions at both ends
 * into sec and their points into spos, its own stress resultants into ssec
 * (arrays laid out as f->sec, f->spos, f->ssec; buf, sres: the thread's
 * scratch). */
static void section_values(const bk_forces *f, bk_system *s, int k, double x, const double *q, const double *qd,
                           const double *qdd, double *buf, double *sres, double *sec, double *ssec, double *spos)
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
    double *pos = spos + (6 + 3 * (size_t)f->maxsample) * (size_t)e;
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
                           sec + 12 * (size_t)e + 6 * end);
    }
    if (f->sections)
        stress_values(f, m, e, qe, sres, pos + 6, ssec);
}

/* The rows of sections.csv of step `step` from sec, ssec and spos (laid out
 * as f's), in the records' order. */
static void section_rows(bk_forces *f, const bk_model *m, int step, double x, int on_thread, const double *sec,
                         const double *ssec, const double *spos)
{
    for (int k = 0; f->sections && k < m->nsection; ++k) {
        const bk_section_rec *sr = &m->sections[k];
        const int e = sr->elem;
        const bk_pair *p = m->pairs[m->elems[e].pair];
        const bk_element *et = p->element;
        const double *pos = spos + (6 + 3 * (size_t)f->maxsample) * (size_t)e;
        for (int end = 0; end < 2; ++end)
            section_row(f->sections, f->rq, on_thread, step, x, sr->beam, e, "nodal", end,
                        et->node_xi[end ? et->nnode - 1 : 0], end ? sr->s1 : sr->s0, pos + 3 * end,
                        sec + 12 * (size_t)e + 6 * end);
        for (int j = 0; p->sections && j < p->nsample; ++j) {
            const double xi = p->sample_xi[j];
            section_row(f->sections, f->rq, on_thread, step, x, sr->beam, e, p->sample_source, j, xi,
                        sr->s0 + xi * (sr->s1 - sr->s0), pos + 6 + 3 * j,
                        ssec + 6 * ((size_t)f->maxsample * (size_t)e + (size_t)j));
        }
    }
}

/* The values of a state for every record (buf, sres: the thread's scratch). */
static void all_values(const bk_forces *f, bk_system *s, double x, const double *q, const double *qd, const double *qdd,
                       double *buf, double *sres, double *sec, double *ssec, double *spos)
{
    for (int k = 0; k < s->m->nsection; ++k)
        section_values(f, s, k, x, q, qd, qdd, buf, sres, sec, ssec, spos);
}

/* The writer thread: a handed-over state's section forces and rows. */
static void sections_job(const void *arg, FILE *unused)
{
    (void)unused;
    const bk_sections_job *j = arg;
    bk_forces *f = j->f;
    const double *qd = j->dyn ? j->qd : NULL, *qdd = j->dyn ? j->qdd : NULL;
    all_values(f, j->s, j->x, j->q, qd, qdd, f->wbuf, f->wsres, j->sec, j->ssec, j->spos);
    section_rows(f, j->s->m, j->step, j->x, 1, j->sec, j->ssec, j->spos);
}

void bk_forces_sections_free(bk_forces *f)
{
    for (int k = 0; f->sjob && k < BK_SECTIONS_JOBS; ++k) {
        bk_sections_job *j = &f->sjob[k];
        free(j->q);
        free(j->qd);
        free(j->qdd);
        free(j->sec);
        free(j->ssec);
        free(j->spos);
    }
    free(f->sjob);
    free(f->wbuf);
    free(f->wsres);
    f->sjob = NULL;
    f->wbuf = f->wsres = NULL;
}

/* The jobs and the thread's scratch, at the first hand-over; 0 or -1. */
static int make_jobs(bk_forces *f, const bk_system *s)
{
    const bk_model *m = s->m;
    const size_t nd = (size_t)(m->ndof ? m->ndof : 1), md = (size_t)s->maxdof;
    const size_t ne = (size_t)(m->nelem ? m->nelem : 1), ms = (size_t)f->maxsample;
    f->sjob = calloc(BK_SECTIONS_JOBS, sizeof *f->sjob);
    f->wbuf = calloc(6 * md + 4 * md * md, sizeof *f->wbuf);
    f->wsres = malloc(9 * ms * sizeof *f->wsres);
    int ok = f->sjob && f->wbuf && f->wsres;
    for (int k = 0; ok && k < BK_SECTIONS_JOBS; ++k) {
        bk_sections_job *j = &f->sjob[k];
        ok = (j->q = malloc(nd * sizeof *j->q)) && (j->qd = malloc(nd * sizeof *j->qd)) &&
             (j->qdd = malloc(nd * sizeof *j->qdd)) && (j->sec = malloc(12 * ne * sizeof *j->sec)) &&
             (j->ssec = malloc(6 * ms * ne * sizeof *j->ssec)) &&
             (j->spos = malloc((6 + 3 * ms) * ne * sizeof *j->spos));
        /* (NaN where an element has no section record or sample points, as f->sec, f->ssec) */
        for (size_t i = 0; ok && i < 12 * ne; ++i)
            j->sec[i] = NAN;
        for (size_t i = 0; ok && i < 6 * ms * ne; ++i)
            j->ssec[i] = NAN;
    }
    if (!ok)
        bk_forces_sections_free(f);
    return ok ? 0 : -1;
}

/* The state handed to the rows' writer thread w for its section forces and
 * rows (a small model's cost the solve 20-70 us an output step, the copy of
 * the state 1-3 us); 0, or -1 when they are to be made here: the next job is
 * still in use, rows of sections.csv recorded here are still in the queue's
 * chunk and the next chunk is not free (they must come out first), or no
 * memory. */
static int hand_over(bk_forces *f, bk_system *s, bk_filewriter *w, int step, double x, const double *q,
                     const double *qd, const double *qdd)
{
    const bk_model *m = s->m;
    if (!f->sjob && make_jobs(f, s) != 0)
        return -1;
    bk_sections_job *j = &f->sjob[f->sjobk];
    if (j->ticket > 0 && !bk_filewriter_done(w, j->ticket))
        return -1;
    if (f->srows) {
        bk_rowqueue_offer(f->rq, 1);
        if (f->rq->pos > 0)
            return -1;
        f->srows = 0;
    }
    f->sjobk = (f->sjobk + 1) % BK_SECTIONS_JOBS;
    j->f = f;
    j->s = s;
    j->step = step;
    j->x = x;
    j->dyn = qd && qdd;
    memcpy(j->q, q, (size_t)m->ndof * sizeof *q);
    if (j->dyn) {
        memcpy(j->qd, qd, (size_t)m->ndof * sizeof *qd);
        memcpy(j->qdd, qdd, (size_t)m->ndof * sizeof *qdd);
    }
    f->sw = w;
    f->scur = (int)(j - f->sjob);
    j->ticket = bk_filewriter_call(w, sections_job, j);
    return 0;
}

int bk_forces_frame_sections(bk_forces *f, const bk_filewriter *by, const double **sec, const double **ssec)
{
    if (f->scur >= 0) {
        bk_sections_job *j = &f->sjob[f->scur];
        if (by && by == f->sw) {
            *sec = j->sec;
            *ssec = j->ssec;
            return 1;
        }
        if (bk_filewriter_done(f->sw, j->ticket)) {
            *sec = j->sec;
            *ssec = j->ssec;
            return 0;
        }
        /* being made by the thread: the values here too (its rows are its) */
        all_values(f, j->s, j->x, j->q, j->dyn ? j->qd : NULL, j->dyn ? j->qdd : NULL, f->sbuf, f->sres, f->sec,
                   f->ssec, f->spos);
        f->scur = -1;
    }
    *sec = f->sec;
    *ssec = f->ssec;
    return 0;
}

void bk_forces_frame_handed(bk_forces *f, long ticket)
{
    if (f->scur >= 0)
        f->sjob[f->scur].ticket = ticket;
}

/* The section forces of every section record, on the threads (each record's
 * own computation: the same bits for any thread count), then their rows in
 * the records' order; or, for a small model once the rows' queue runs on a
 * thread that mirrors sections.csv, by that thread (forces.h sw). */
void bk_forces_sections(bk_forces *f, bk_system *s, int step, double x, const double *q, const double *qd,
                           const double *qdd)
{
    const bk_model *m = s->m;
    const int nsec = m->nsection;
    f->sec_step = step;
    if (nsec < BK_SECTIONS_PAR_MIN && f->sections && bk_rowqueue_thread_rows(f->rq, f->sections) &&
        hand_over(f, s, f->rq->w, step, x, q, qd, qdd) == 0)
        return;
    f->scur = -1;
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
                section_values(f, s, k, x, q, qd, qdd, buf, sres, f->sec, f->ssec, f->spos);
        }
    } else            /* no parallel region (libgomp allocates a team even when it runs alone) */
        all_values(f, s, x, q, qd, qdd, f->sbuf, f->sres, f->sec, f->ssec, f->spos);
    section_rows(f, m, step, x, 0, f->sec, f->ssec, f->spos);
    f->srows = bk_rowqueue_owns(f->rq, f->sections);
}
