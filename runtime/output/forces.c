/* forces.c -- reactions and section forces (see forces.h). */
#include "output/forces_impl.h"
#include "base/bigalloc.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "model/amplitude.h"
#include "base/csvrow.h"
#include "base/json.h"

#ifdef _OPENMP
#include <omp.h>
#endif

static const bk_table_spec reactions_csv =
    BK_TABLE("reactions.csv", "runs with a `[[constraint]]`",
             "step,time,constraint,name,type,at,x,y,z,Fx,Fy,Fz,Mx,My,Mz\n");
static const bk_table_spec sections_csv =
    BK_TABLE("sections.csv", "statics and dynamics", "step,time,beam,element,source,point,xi,s,x,y,z,N,Q2,Q3,T,M2,M3\n");

int bk_forces_open(bk_forces *f, const bk_model *m, int path, const char *dir, bk_tables *ts, FILE *err)
{
    memset(f, 0, sizeof *f);
    f->m = m;
    size_t nd = (size_t)m->ndof;
    int maxdof = 1;
    for (int e = 0; e < m->nelem; ++e)
        if (bk_elem_type(m, e)->ndof > maxdof)
            maxdof = bk_elem_type(m, e)->ndof;
    size_t md = (size_t)maxdof;
    f->fld = malloc(4 * nd * sizeof *f->fld);
    f->kind = calloc(nd, 1);
    f->comp = calloc(nd, 1);
    f->res = calloc(nd, sizeof *f->res);
    f->fext = calloc(nd, sizeof *f->fext);
    /* element buffers: q, qd, qdd, force, work, and four ndof^2 matrices */
    f->buf = calloc(6 * md + 4 * md * md, sizeof *f->buf);
    f->last = calloc((size_t)(m->nreaction ? m->nreaction : 1), sizeof *f->last);
    f->sec = bk_big_malloc(12 * (size_t)m->nelem * sizeof *f->sec);
    f->sec_step = -1;
    f->scur = -1;
    int maxsample = 1;
    for (int e = 0; e < m->nelem; ++e)
        if (m->pairs[m->elems[e].pair]->sections && m->pairs[m->elems[e].pair]->nsample > maxsample)
            maxsample = m->pairs[m->elems[e].pair]->nsample;
    f->maxsample = maxsample;
    f->nthread = 1;
#ifdef _OPENMP
    f->nthread = omp_get_max_threads() > 1 ? omp_get_max_threads() : 1;
#endif
    const size_t ne = (size_t)(m->nelem ? m->nelem : 1);
    /* a slot per thread when the section forces run on the threads, apart
     * (bigalloc.h); else one (no gap: a small run touches no more memory) */
    const int slots = m->nsection >= BK_SECTIONS_PAR_MIN ? f->nthread : 1;
    f->sbuf_stride = bk_thread_stride(6 * md + 4 * md * md, slots);
    f->sres_stride = bk_thread_stride(9 * (size_t)maxsample, slots);
    f->sbuf = calloc((size_t)slots * f->sbuf_stride, sizeof *f->sbuf);
    f->sres = malloc((size_t)slots * f->sres_stride * sizeof *f->sres);
    f->spos = bk_big_malloc((6 + 3 * (size_t)maxsample) * ne * sizeof *f->spos);
    f->ssec = bk_big_malloc(6 * (size_t)maxsample * (size_t)(m->nelem ? m->nelem : 1) * sizeof *f->ssec);
    if (!f->fld || !f->kind || !f->comp || !f->res || !f->fext || !f->buf || !f->last || !f->sec || !f->sres ||
        !f->ssec || !f->sbuf || !f->spos) {
        fprintf(err, "error: out of memory for the reactions and section forces\n");
        return -1;
    }
    /* the elements that touch a DOF a reaction reads from the residual */
    char *held = calloc(nd ? nd : 1, 1);
    f->relem = malloc((size_t)(m->nelem ? m->nelem : 1) * sizeof *f->relem);
    if (!held || !f->relem) {
        free(held);
        fprintf(err, "error: out of memory for the reactions and section forces\n");
        return -1;
    }
    for (int c = 0; c < m->nreaction; ++c)
        for (int k = 0; k < m->reactions[c].nfixed; ++k)
            held[m->reactions[c].fixed[k]] = 1;
    for (int e = 0; e < m->nelem; ++e) {
        int touch = 0;
        for (int k = 0; k < bk_elem_type(m, e)->ndof && !touch; ++k)
            touch = held[m->elems[e].dofs[k]];
        if (touch)
            f->relem[f->nrelem++] = e;
    }
    free(held);
    /* dynamics: their mass matrices, constant, once (the residual of every step uses them) */
    if (path == BK_PATH_TIME && f->nrelem > 0) {
        f->rmass = malloc((size_t)f->nrelem * md * md * sizeof *f->rmass);
        if (!f->rmass) {
            fprintf(err, "error: out of memory for the reactions and section forces\n");
            return -1;
        }
        for (int k = 0; k < f->nrelem; ++k)
            bk_element_mass(m, f->relem[k], f->buf, f->rmass + (size_t)k * md * md);
    }
    for (size_t i = 0; i < 4 * nd; ++i)
        f->fld[i] = -1;
    for (size_t i = 0; i < 12 * (size_t)m->nelem; ++i)
        f->sec[i] = NAN;
    for (size_t i = 0; i < 6 * (size_t)maxsample * (size_t)m->nelem; ++i)
        f->ssec[i] = NAN;
    for (int e = 0; e < m->nelem; ++e) {
        const bk_element *et = bk_elem_type(m, e);
        for (int k = 0; k < et->nfield; ++k) {
            bk_field_role role = et->field_role[k];
            int kind = role == BK_FIELD_POSITION ? K_POS : bk_field_is_gradient(role) ? K_GRAD
                       : role == BK_FIELD_QUATERNION ? K_QUAT : K_NONE;
            for (int c = 0; c < et->field_dim[k] && c < 4; ++c) {
                int d = m->elems[e].dofs[et->field_dof[k] + c];
                f->kind[d] = (signed char)kind;
                f->comp[d] = (signed char)c;
                for (int c2 = 0; c2 < et->field_dim[k] && c2 < 4; ++c2)
                    f->fld[4 * d + c2] = m->elems[e].dofs[et->field_dof[k] + c2];
            }
        }
    }
    if (m->nreaction > 0 &&
        !(f->reactions = bk_tables_open(ts, dir, &reactions_csv, 1, err)))
        return -1;
    if (path != BK_PATH_NONE && bk_joints_open(f, m, dir, ts, err) != 0)
        return -1;
    if (m->nsection > 0 && path != BK_PATH_NONE &&
        !(f->sections = bk_tables_open(ts, dir, &sections_csv, 1, err)))
        return -1;
    return 0;
}

void bk_forces_close(bk_forces *f)
{
    f->reactions = f->sections = f->joints = NULL;   /* the run's tables close them */
    free(f->jstate);
    free(f->fld);
    free(f->kind);
    free(f->comp);
    free(f->res);
    free(f->fext);
    free(f->buf);
    free(f->last);
    free(f->sec);
    free(f->sres);
    free(f->sbuf);
    free(f->spos);
    free(f->ssec);
    free(f->relem);
    free(f->rmass);
    bk_forces_sections_free(f);
    memset(f, 0, sizeof *f);
}

static void cross_add(const double *a, const double *b, double c, double *out)
{
    out[0] += c * (a[1] * b[2] - a[2] * b[1]);
    out[1] += c * (a[2] * b[0] - a[0] * b[2]);
    out[2] += c * (a[0] * b[1] - a[1] * b[0]);
}

/* F, M (about x0) of the generalized force value r at global DOF d (forces.h). */
void bk_forces_map_dof(const bk_forces *f, const double *q, int d, double r, const double *x0, double *F, double *M)
{
    const int *fl = f->fld + 4 * d;
    int c = f->comp[d];
    double e[3] = {0.0, 0.0, 0.0};
    switch (f->kind[d]) {
    case K_POS: {
        double arm[3] = {q[fl[0]] - x0[0], q[fl[1]] - x0[1], q[fl[2]] - x0[2]};
        e[c] = 1.0;
        F[c] += r;
        cross_add(arm, e, r, M);
        break;
    }
    case K_GRAD: {
        double g[3] = {q[fl[0]], q[fl[1]], q[fl[2]]};
        e[c] = 1.0;
        cross_add(g, e, r, M);
        break;
    }
    case K_QUAT: {
        double w = q[fl[0]], v[3] = {q[fl[1]], q[fl[2]], q[fl[3]]};
        if (c == 0) {
            for (int i = 0; i < 3; ++i)
                M[i] -= 0.5 * r * v[i];
        } else {
            e[c - 1] = 1.0;
            for (int i = 0; i < 3; ++i)
                M[i] += 0.5 * w * r * e[i];
            cross_add(v, e, 0.5 * r, M);
        }
        break;
    }
    default:
        break;
    }
}

/* y[i] (+)= sum_j A[i n + j] v[j], j in order, over the n rows of A (n x n,
 * row-major), from y[i] or, with from_zero, from 0: four rows at a time, each
 * its own sum (the same bits as one row after the other, without waiting on
 * one chain of dependent additions). */
void bk_forces_rows_times(int n, const double *restrict A, const double *restrict v, double *restrict y,
                       int from_zero)
{
    int i = 0;
    for (; i + 4 <= n; i += 4) {
        const double *a0 = A + (size_t)i * n, *a1 = a0 + n, *a2 = a1 + n, *a3 = a2 + n;
        double s0 = from_zero ? 0.0 : y[i], s1 = from_zero ? 0.0 : y[i + 1];
        double s2 = from_zero ? 0.0 : y[i + 2], s3 = from_zero ? 0.0 : y[i + 3];
        for (int j = 0; j < n; ++j) {
            const double vj = v[j];
            s0 += a0[j] * vj;
            s1 += a1[j] * vj;
            s2 += a2[j] * vj;
            s3 += a3[j] * vj;
        }
        y[i] = s0, y[i + 1] = s1, y[i + 2] = s2, y[i + 3] = s3;
    }
    for (; i < n; ++i) {
        double s0 = from_zero ? 0.0 : y[i];
        for (int j = 0; j < n; ++j)
            s0 += A[(size_t)i * n + j] * v[j];
        y[i] = s0;
    }
}

/* The generalized residual without the constraint forces over every DOF:
 * f_int - f_ext (statics) + M (q'' + alpha q') + beta K q' + viscous + rotary
 * (dynamics), into f->res. */
static void full_residual(bk_forces *f, bk_system *s, double x, const double *q, const double *qd,
                          const double *qdd)
{
    const bk_model *m = s->m;
    const int nd = m->ndof;
    double lf = bk_load_factor(m, -1, x);
    size_t md = (size_t)s->maxdof;
    double *qe = f->buf, *qde = qe + md, *qdde = qde + md, *fe = qdde + md, *tmp = fe + md;
    double *K1 = tmp + md, *K2 = K1 + md * md, *K3 = K2 + md * md;
    /* internal forces of the elements at the held DOFs (the only entries read) */
    memset(f->res, 0, (size_t)nd * sizeof *f->res);
    for (int k = 0; k < f->nrelem; ++k) {
        const int e = f->relem[k];
        const bk_elem *el = &m->elems[e];
        const bk_pair *p = m->pairs[el->pair];
        bk_gather(m, e, q, qe);
        p->force(qe, m->tabs[el->geom], m->mats[el->mat].params, fe);
        bk_scatter(m, e, fe, 1.0, f->res);
    }
    const bk_path path = {.factor = lf, .x = x, .qd = qd};
    bk_assemble_interactions(s, q, &path, f->res, NULL);
    if (!f->have_fext) {                     /* dead loads of unit factor: constant */
        bk_external_load(s, f->fext);
        f->have_fext = 1;
    }
    for (int i = 0; i < nd; ++i)
        f->res[i] -= lf * f->fext[i];
    if (!qdd)
        return;
    const double ra = m->dyn.rayleigh_alpha, rb = m->dyn.rayleigh_beta;
    for (int kk = 0; kk < f->nrelem; ++kk) {
        const int e = f->relem[kk];
        const bk_elem *el = &m->elems[e];
        const bk_pair *p = m->pairs[el->pair];
        const bk_element *et = p->element;
        const bk_mat *mat = &m->mats[el->mat];
        const int ne = et->ndof;
        bk_gather(m, e, q, qe);
        bk_gather(m, e, qd, qde);
        bk_gather(m, e, qdd, qdde);
        const double *Me = f->rmass + (size_t)kk * md * md;
        for (int j = 0; j < ne; ++j)
            tmp[j] = qdde[j] + ra * qde[j];
        bk_forces_rows_times(ne, Me, tmp, fe, 1);
        bk_scatter(m, e, fe, 1.0, f->res);
        if (rb != 0.0) {
            p->force_tangent(qe, m->tabs[el->geom], mat->params, tmp, K1);
            bk_forces_rows_times(ne, K1, qde, fe, 1);
            for (int i = 0; i < ne; ++i)
                fe[i] *= rb;
            bk_scatter(m, e, fe, 1.0, f->res);
        }
        if (mat->nvisc > 0 && p->viscous) {
            p->viscous_force(qe, qde, m->tabs[el->geom], mat->visc, fe);
            bk_scatter(m, e, fe, 1.0, f->res);
        }
        if (et->rotary) {
            double T = 0.0;
            et->rotary(m->geoms[el->geom], qe, qde, qdde, fe, K1, K2, K3, &T);
            bk_scatter(m, e, fe, mat->rho, f->res);
        }
    }
}

/* The joint point of frame a of a joint nonlinear in q at xj: o_a = r_a + R(p_a/|p_a|) c_a
 * (bk_joint.h). */
static void joint_point(const double *xj, const double *prm, double *o)
{
    const double *p = xj + 3, *c = prm;
    double n = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3];
    double w = p[0], v[3] = {p[1], p[2], p[3]};
    double vc[3] = {v[1] * c[2] - v[2] * c[1], v[2] * c[0] - v[0] * c[2], v[0] * c[1] - v[1] * c[0]};
    double vvc[3] = {v[1] * vc[2] - v[2] * vc[1], v[2] * vc[0] - v[0] * vc[2], v[0] * vc[1] - v[1] * vc[0]};
    for (int i = 0; i < 3; ++i)                 /* R c = c + 2 (w v x c + v x (v x c)) / |p|^2 */
        o[i] = xj[i] + c[i] + 2.0 * (w * vc[i] + vvc[i]) / n;
}

static void write_reactions(bk_forces *f, bk_system *s, int step, double x, const double *q, const double *nu)
{
    const bk_model *m = s->m;
    for (int c = 0; c < m->nreaction; ++c) {
        const bk_reaction *rc = &m->reactions[c];
        double x0[3], F[3] = {0.0, 0.0, 0.0}, M[3] = {0.0, 0.0, 0.0};
        bk_eval_point(m, q, rc->elem, rc->xi, x0, NULL);
        if (rc->nlcon >= 0) {             /* about the joint point of frame a */
            const bk_nlcon *jc = &m->nlcons[rc->nlcon];
            double xj[7];
            for (int i = 0; i < 7; ++i)
                xj[i] = jc->dof[i] >= 0 ? q[jc->dof[i]] : jc->x0[i];
            joint_point(xj, jc->prm, x0);
        }
        for (int k = 0; k < rc->nfixed; ++k)
            bk_forces_map_dof(f, q, rc->fixed[k], f->res[rc->fixed[k]], x0, F, M);
        for (int k = 0; k < rc->nlin; ++k) {
            const bk_lincon *lc = &m->lincons[rc->lin[k]];
            for (int j = 0; j < lc->nterm; ++j) {
                int d = lc->dof[j], ok = rc->nside == 0;
                for (int i = 0; i < rc->nside && !ok; ++i)
                    ok = rc->side[i] == d;
                if (!ok)
                    continue;
                double r = nu ? -s->cscale * bk_constraint_coef(lc, j, x) * nu[rc->lin[k]] : NAN;
                bk_forces_map_dof(f, q, d, r, x0, F, M);
            }
        }
        for (int j = rc->nlcon; j >= 0 && j < rc->nlcon + rc->njoint; ++j) {
            /* a joint nonlinear in q: -s G^T nu on frame a's (r, p), or on the side's DOFs */
            const bk_nlcon *jc = &m->nlcons[j];
            double xj[BK_JOINT_NX], g[BK_JOINT_MAXROW], G[BK_JOINT_MAXROW * BK_JOINT_NX], prm[BK_JOINT_NPARAM];
            for (int i = 0; i < BK_JOINT_NX; ++i)
                xj[i] = jc->dof[i] >= 0 ? q[jc->dof[i]] : jc->x0[i];
            bk_joint_params(jc, x, 0, prm);
            jc->kind->eval(xj, prm, g, G);
            const int row0 = s->jrow[j];
            for (int i = 0; i < BK_JOINT_NX; ++i) {
                const int d = jc->dof[i];
                int ok = d >= 0 && rc->nside == 0 && i < 7;
                for (int k = 0; k < rc->nside && d >= 0 && !ok; ++k)
                    ok = rc->side[k] == d;
                if (!ok)
                    continue;
                double r = 0.0;
                for (int k = 0; k < jc->kind->nrow; ++k)
                    r += G[k * BK_JOINT_NX + i] * (nu ? nu[row0 + k] : NAN);
                bk_forces_map_dof(f, q, d, -s->cscale * r, x0, F, M);
            }
        }
        double *L = f->last[c];
        for (int i = 0; i < 3; ++i)
            L[i] = F[i], L[3 + i] = M[i], L[6 + i] = x0[i];
        if (f->reactions) {
            bk_row r;
            bk_row_begin(&r, f->reactions, f->rq);
            bk_row_int(&r, step);
            bk_row_num(&r, x);
            bk_row_int(&r, rc->index);
            bk_row_str(&r, rc->name);
            bk_row_str(&r, rc->type);
            bk_row_str(&r, rc->at);
            for (int i = 0; i < 9; ++i)
                bk_row_num(&r, i < 3 ? x0[i] : i < 6 ? F[i - 3] : M[i - 6]);
            bk_row_end(&r);
        }
    }
    f->have_last = 1;                    /* (flushed with the other tables: output.c) */
}

void bk_forces_step(bk_forces *f, bk_system *s, int step, double x, const double *q, const double *qd,
                    const double *qdd, const double *nu, int with_sections)
{
    if (!f->m)
        return;
    if (f->reactions) {
        if (f->nrelem > 0)
            full_residual(f, s, x, q, qd, qdd);
        write_reactions(f, s, step, x, q, nu);
        bk_joints_step(f, step, x, q, qd);
    }
    if (f->sections && with_sections)
        bk_forces_sections(f, s, step, x, q, qd, qdd);
}

void bk_forces_summary(const bk_forces *f, FILE *fp)
{
    if (!f->m || !f->have_last || f->m->nreaction == 0)
        return;
    fprintf(fp, "  \"reactions\": [");
    for (int c = 0; c < f->m->nreaction; ++c) {
        const bk_reaction *rc = &f->m->reactions[c];
        const double *L = f->last[c];
        fprintf(fp, "%s\n    {\"constraint\": %d, \"name\": \"%s\", \"type\": \"%s\", \"at\": \"%s\", \"point\": [",
                c ? "," : "", rc->index, rc->name, rc->type, rc->at);
        for (int i = 0; i < 3; ++i)
            bk_json_num(fp, L[6 + i]), fprintf(fp, i < 2 ? ", " : "], \"force\": [");
        for (int i = 0; i < 3; ++i)
            bk_json_num(fp, L[i]), fprintf(fp, i < 2 ? ", " : "], \"moment\": [");
        for (int i = 0; i < 3; ++i)
            bk_json_num(fp, L[3 + i]), fprintf(fp, i < 2 ? ", " : "]}");
    }
    fprintf(fp, "\n  ],\n");
    bk_joints_summary(f, fp);
}
