/* contact_force.c -- the contact interaction: barrier forces between the sample
 * points of beams' centrelines and rigid primitives, their Jacobian, the step
 * limiter (see contact_force.h). */
#include "assembly/contact_force.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/system.h"
#include "base/csvrow.h"
#include "base/tables.h"
#include "contact.h"

/* Scratch of the interaction: one element's force and matrix. */
typedef struct contact_work {
    double *fe, *Ke;                 /* [maxdof], [maxdof^2] */
    FILE *table;                     /* contacts.csv (registered in the run's tables), or NULL */
} contact_work;

int bk_contact_present(const bk_model *m)
{
    return m->contact && m->contact->nset > 0;
}

int bk_contact_make(bk_system *s, void **self)
{
    size_t md = (size_t)(s->maxdof > 0 ? s->maxdof : 1);
    contact_work *w = calloc(1, sizeof *w);
    if (w) {
        w->fe = malloc(md * sizeof *w->fe);
        w->Ke = malloc(md * md * sizeof *w->Ke);
    }
    *self = w;
    return w && w->fe && w->Ke ? 0 : -1;
}

static void contact_free(void *self)
{
    contact_work *w = self;
    if (w) {
        free(w->fe);
        free(w->Ke);
    }
    free(w);
}

/* The distance function of primitive p at x: out[0] = g, out[1..3] its
 * gradient, out[4..12] its Hessian (the gap kernels of out/kernels/contact.h;
 * a capsule's ends are spheres). */
static void gap(const bk_contact_prim *p, const double *x, double *out)
{
    switch (p->shape) {
    case BK_CONTACT_HALF_SPACE:
        bk_contact_gap_half_space(x, p->prm, out);
        return;
    case BK_CONTACT_SPHERE:
        bk_contact_gap_sphere(x, p->prm, out);
        return;
    default: {
        double seg[14];
        bk_contact_gap_segment(x, p->prm, seg);
        if (seg[13] > 0.0 && seg[13] < 1.0) {
            memcpy(out, seg, 13 * sizeof *out);
            return;
        }
        const double *end = seg[13] <= 0.0 ? p->prm : p->prm + 3;
        const double sph[4] = {end[0], end[1], end[2], p->prm[6]};
        bk_contact_gap_sphere(x, sph, out);
    }
    }
}

/* Sample point k of element e at q: its shape functions N and position x;
 * returns its share of the element's length (see model/contact.h). */
static double sample(const bk_model *m, int e, const double *qe, int k, int nsample, double *N, double *x)
{
    const bk_element *et = bk_elem_type(m, e);
    const double xi = nsample == 1 ? 0.5 : (double)k / (nsample - 1);
    et->shape(m->geoms[m->elems[e].geom], xi, 0.0, 0.0, N);
    x[0] = x[1] = x[2] = 0.0;
    for (int a = 0; a < et->nshape; ++a)
        for (int i = 0; i < 3; ++i)
            x[i] += N[a] * qe[et->shape_dof[a] + i];
    if (nsample == 1)
        return 1.0;
    return (k == 0 || k == nsample - 1 ? 0.5 : 1.0) / (nsample - 1);
}

static int contact_assemble(void *self, bk_system *s, const double *q, const bk_path *p, double *fint, double *Ax)
{
    (void)p;
    contact_work *w = self;
    const bk_model *m = s->m;
    const bk_contact_model *cm = m->contact;
    double qe[BK_MAX_ELEMENT_DOF], N[BK_MAX_SHAPE], x[3], g[13], b[3];
    int bad = 0;
    for (int c = 0; c < cm->nset; ++c) {
        const bk_contact_set *set = &cm->sets[c];
        const bk_contact_prim *prim = &cm->prims[set->prim];
        for (int i = 0; i < set->nelem; ++i) {
            const int e = set->elems[i];
            const bk_element *et = bk_elem_type(m, e);
            const int nd = et->ndof;
            const double kl = m->geoms[m->elems[e].geom][BK_GEOM_L] * set->kappa;
            int touched = 0;
            bk_gather(m, e, q, qe);
            for (int k = 0; k < set->nsample; ++k) {
                const double wl = kl * sample(m, e, qe, k, set->nsample, N, x);
                gap(prim, x, g);
                const double dist = g[0] - set->radius[i];
                if (!(dist > 0.0)) {
                    bad = 1;                 /* through the surface: not an admissible state */
                    continue;
                }
                if (dist >= set->shat)
                    continue;
                bk_contact_barrier(dist, set->shat, b);
                if (!touched) {
                    memset(w->fe, 0, (size_t)nd * sizeof *w->fe);
                    if (Ax)
                        memset(w->Ke, 0, (size_t)nd * (size_t)nd * sizeof *w->Ke);
                    touched = 1;
                }
                /* E = wl b(s): fint += dE/dq = wl b' N^T grad g; K += wl N^T (b'' grad grad^T + b' H) N */
                for (int a = 0; a < et->nshape; ++a)
                    for (int r = 0; r < 3; ++r) {
                        const int row = et->shape_dof[a] + r;
                        w->fe[row] += wl * b[1] * N[a] * g[1 + r];
                        if (!Ax)
                            continue;
                        for (int cc = 0; cc < et->nshape; ++cc)
                            for (int j = 0; j < 3; ++j)
                                w->Ke[row * nd + et->shape_dof[cc] + j] +=
                                    wl * N[a] * N[cc] * (b[2] * g[1 + r] * g[1 + j] + b[1] * g[4 + 3 * r + j]);
                    }
            }
            if (touched) {
                bad |= bk_scatter(m, e, w->fe, 1.0, fint);
                if (Ax)
                    bk_scatter_matrix(s, e, w->Ke, 1.0, Ax);
            }
        }
    }
    return bad ? -1 : 0;
}

/* The fraction of dx[neq] that keeps every sample point at more than a tenth
 * of its distance: |grad g| = 1, so g moves by at most |dx_point|. */
static double contact_step_limit(void *self, const bk_system *s, const double *q, const double *dx)
{
    (void)self;
    const bk_model *m = s->m;
    const bk_contact_model *cm = m->contact;
    double qe[BK_MAX_ELEMENT_DOF], de[BK_MAX_ELEMENT_DOF], N[BK_MAX_SHAPE], x[3], g[13], alpha = 1.0;
    for (int c = 0; c < cm->nset; ++c) {
        const bk_contact_set *set = &cm->sets[c];
        const bk_contact_prim *prim = &cm->prims[set->prim];
        for (int i = 0; i < set->nelem; ++i) {
            const int e = set->elems[i];
            const bk_element *et = bk_elem_type(m, e);
            const int *dofs = m->elems[e].dofs;
            bk_gather(m, e, q, qe);
            for (int k = 0; k < et->ndof; ++k)
                de[k] = s->eq[dofs[k]] >= 0 ? dx[s->eq[dofs[k]]] : 0.0;
            for (int k = 0; k < set->nsample; ++k) {
                sample(m, e, qe, k, set->nsample, N, x);
                double dp[3] = {0.0, 0.0, 0.0};
                for (int a = 0; a < et->nshape; ++a)
                    for (int r = 0; r < 3; ++r)
                        dp[r] += N[a] * de[et->shape_dof[a] + r];
                const double move = sqrt(dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2]);
                if (!(move > 0.0))
                    continue;
                gap(prim, x, g);
                const double dist = g[0] - set->radius[i];
                if (move * alpha > 0.9 * dist)
                    alpha = dist > 0.0 ? 0.9 * dist / move : 0.0;
            }
        }
    }
    return alpha;
}

/* summary.json "contact": the smallest distance of a sample point to its
 * primitive, the largest penetration (0: none; a state through a surface is
 * refused), and per set its primitive, the force on the beams and the sample
 * points within the barrier. */
static int contact_summary(void *self, const bk_system *s, const double *q, char *buf, size_t n)
{
    (void)self;
    const bk_contact_model *cm = s->m->contact;
    double F[3 * 64], dmin;
    int nact[64];
    if (cm->nset > 64)
        return -1;
    bk_contact_state(s, q, F, nact, &dmin);
    int len = snprintf(buf, n, "{\"min_distance\": %.17g, \"max_penetration\": %.17g, \"sets\": [", dmin,
                       dmin < 0.0 ? -dmin : 0.0);
    for (int c = 0; c < cm->nset && len > 0 && (size_t)len < n; ++c)
        len += snprintf(buf + len, n - (size_t)len, "%s{\"primitive\": %d, \"force\": [%.17g, %.17g, %.17g], "
                        "\"active_points\": %d}", c ? ", " : "", cm->sets[c].prim, F[3 * c], F[3 * c + 1],
                        F[3 * c + 2], nact[c]);
    if (len > 0 && (size_t)len < n)
        len += snprintf(buf + len, n - (size_t)len, "]}");
    return len > 0 && (size_t)len < n ? 0 : -1;
}

/* contacts.csv: one row per sample point within a barrier's reach and output
 * step: step, time (or load factor), set, primitive, element, point, its
 * position, distance and the force on the beam there (N). */
static int contact_tables(void *self, const bk_system *s, bk_tables *ts, const char *dir, FILE *err)
{
    (void)s;
    contact_work *w = self;
    w->table = bk_tables_open(ts, dir, "contacts.csv", "step,time,set,primitive,element,point,x,y,z,distance,"
                              "normal_force,fx,fy,fz\n", 1, err);
    return w->table ? 0 : -1;
}

static void contact_rows(void *self, const bk_system *s, int step, double t, const double *q, bk_rowqueue *rq)
{
    contact_work *w = self;
    const bk_model *m = s->m;
    const bk_contact_model *cm = m->contact;
    double qe[BK_MAX_ELEMENT_DOF], N[BK_MAX_SHAPE], x[3], g[13], b[3];
    if (!w->table)
        return;
    for (int c = 0; c < cm->nset; ++c) {
        const bk_contact_set *set = &cm->sets[c];
        const bk_contact_prim *prim = &cm->prims[set->prim];
        for (int i = 0; i < set->nelem; ++i) {
            const int e = set->elems[i];
            const double kl = m->geoms[m->elems[e].geom][BK_GEOM_L] * set->kappa;
            bk_gather(m, e, q, qe);
            for (int k = 0; k < set->nsample; ++k) {
                const double wl = kl * sample(m, e, qe, k, set->nsample, N, x);
                gap(prim, x, g);
                const double dist = g[0] - set->radius[i];
                if (!(dist > 0.0) || dist >= set->shat)
                    continue;
                bk_contact_barrier(dist, set->shat, b);
                const double fn = -wl * b[1];
                bk_row r;
                bk_row_begin(&r, w->table, rq);
                bk_row_int(&r, step);
                bk_row_num(&r, t);
                bk_row_int(&r, c);
                bk_row_int(&r, set->prim);
                bk_row_int(&r, e);
                bk_row_int(&r, k);
                for (int d = 0; d < 3; ++d)
                    bk_row_num(&r, x[d]);
                bk_row_num(&r, dist);
                bk_row_num(&r, fn);
                for (int d = 0; d < 3; ++d)
                    bk_row_num(&r, fn * g[1 + d]);
                bk_row_end(&r);
            }
        }
    }
}

const bk_interaction_ops bk_contact_ops = {.name = "contact", .assemble = contact_assemble,
                                           .step_limit = contact_step_limit, .tables = contact_tables,
                                           .rows = contact_rows, .summary_key = "contact",
                                           .summary = contact_summary, .free = contact_free};

void bk_contact_state(const bk_system *s, const double *q, double *F, int *nactive, double *min_distance)
{
    const bk_model *m = s->m;
    const bk_contact_model *cm = m->contact;
    double qe[BK_MAX_ELEMENT_DOF], N[BK_MAX_SHAPE], x[3], g[13], b[3];
    *min_distance = INFINITY;
    for (int c = 0; cm && c < cm->nset; ++c) {
        const bk_contact_set *set = &cm->sets[c];
        const bk_contact_prim *prim = &cm->prims[set->prim];
        F[3 * c] = F[3 * c + 1] = F[3 * c + 2] = 0.0;
        if (nactive)
            nactive[c] = 0;
        for (int i = 0; i < set->nelem; ++i) {
            const int e = set->elems[i];
            const double kl = m->geoms[m->elems[e].geom][BK_GEOM_L] * set->kappa;
            bk_gather(m, e, q, qe);
            for (int k = 0; k < set->nsample; ++k) {
                const double wl = kl * sample(m, e, qe, k, set->nsample, N, x);
                gap(prim, x, g);
                const double dist = g[0] - set->radius[i];
                *min_distance = fmin(*min_distance, dist);
                if (!(dist > 0.0) || dist >= set->shat)
                    continue;
                bk_contact_barrier(dist, set->shat, b);
                for (int r = 0; r < 3; ++r)
                    F[3 * c + r] -= wl * b[1] * g[1 + r];      /* the force on the beam: -dE/dx */
                if (nactive)
                    nactive[c]++;
            }
        }
    }
}
