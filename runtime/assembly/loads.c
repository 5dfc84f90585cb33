/* loads.c -- loads with amplitudes, follower loads, distributed loads, tendons (tendons.c). */
#include "assembly/loads.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/tendons.h"
#include "model/amplitude.h"

/* 5-point Gauss-Legendre rule on [-1, 1] */
static const double GX[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                             0.9061798459386640};
static const double GW[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                             0.2369268850561891};

int bk_section_frame(const bk_model *m, int e, const double *qe, double xi, double *R)
{
    const bk_element *et = bk_elem_type(m, e);
    if (!et->section_frame)
        return -1;
    et->section_frame(m->geoms[m->elems[e].geom], xi, qe, R, NULL);
    for (int k = 0; k < 9; ++k)
        if (!isfinite(R[k]))
            return -1;
    return 0;
}

/* A follower vector at xi: v = c1 e1 + c2 e2 + c3 e3 in the section frame of
 * qe and, with dv != NULL, dv[3 ndof] = dv/dqe from the frame's generated
 * Jacobian (dR[9 ndof] scratch).  The scene compiler and the model reader
 * admit follower loads only on elements with a section_frame(). */
static void follower_vector(const bk_model *m, int e, const double *qe, double xi, const double *c, double *v,
                            double *dv, double *dR)
{
    double R[9];
    const bk_element *et = bk_elem_type(m, e);
    const int nd = et->ndof;
    et->section_frame(m->geoms[m->elems[e].geom], xi, qe, R, dv ? dR : NULL);
    for (int k = 0; k < 3; ++k)
        v[k] = c[0] * R[k] + c[1] * R[3 + k] + c[2] * R[6 + k];
    if (!dv)
        return;
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < nd; ++j)
            dv[k * nd + j] = c[0] * dR[k * nd + j] + c[1] * dR[(3 + k) * nd + j] + c[2] * dR[(6 + k) * nd + j];
}

/* Q += fac N^T v and K += fac N^T dv (a force v at the point with shape
 * functions N). */
static void add_force(const bk_element *et, const double *N, const double *v, const double *dv, double fac,
                      double *Q, double *K)
{
    const int nd = et->ndof;
    for (int a = 0; a < et->nshape; ++a)
        for (int k = 0; k < 3; ++k) {
            int row = et->shape_dof[a] + k;
            Q[row] += fac * N[a] * v[k];
            if (K && dv)
                for (int j = 0; j < nd; ++j)
                    K[row * nd + j] += fac * N[a] * dv[k * nd + j];
        }
}

typedef struct scratch {
    double qe[BK_MAX_ELEMENT_DOF];
    double N[BK_MAX_SHAPE];
    double *dv;                  /* [3 ndof] */
    double *dR;                  /* [9 ndof]: the section frame's Jacobian */
    double *Qk, *Kk;             /* moment kernel: [ndof], [ndof^2] */
} scratch;

static void point_force(const bk_model *m, const bk_force_load *f, double fac, scratch *w, double *Q, double *K)
{
    const bk_element *et = bk_elem_type(m, f->elem);
    double v[3];
    bk_force_shape(m, f, w->N);
    if (f->follower) {
        follower_vector(m, f->elem, w->qe, f->xi, f->value, v, K ? w->dv : NULL, w->dR);
        add_force(et, w->N, v, w->dv, fac, Q, K);
    } else {
        add_force(et, w->N, f->value, NULL, fac, Q, NULL);
    }
}

static void point_moment(const bk_model *m, const bk_moment_load *mo, double fac, scratch *w, double *Q, double *K)
{
    const bk_element *et = bk_elem_type(m, mo->elem);
    const double *g = m->geoms[m->elems[mo->elem].geom];
    const int nd = et->ndof;
    if (!mo->follower) {
        et->moment(g, mo->xi, w->qe, mo->value, w->Qk, w->Kk);
        for (int i = 0; i < nd; ++i)
            Q[i] += fac * w->Qk[i];
        if (K)
            for (int i = 0; i < nd * nd; ++i)
                K[i] += fac * w->Kk[i];
        return;
    }
    /* Q = B(q) M(q), B[:, k] = Q(q, e_k): dQ = sum_k M_k dQ(e_k) + B dM/dq */
    double M[3];
    follower_vector(m, mo->elem, w->qe, mo->xi, mo->value, M, K ? w->dv : NULL, w->dR);
    for (int k = 0; k < 3; ++k) {
        double ek[3] = {0.0, 0.0, 0.0};
        ek[k] = 1.0;
        et->moment(g, mo->xi, w->qe, ek, w->Qk, w->Kk);
        for (int i = 0; i < nd; ++i)
            Q[i] += fac * M[k] * w->Qk[i];
        if (K)
            for (int i = 0; i < nd; ++i)
                for (int j = 0; j < nd; ++j)
                    K[i * nd + j] += fac * (M[k] * w->Kk[i * nd + j] + w->Qk[i] * w->dv[k * nd + j]);
    }
}

static void dist_load(const bk_model *m, const bk_dist_load *d, double fac, scratch *w, double *Q, double *K)
{
    const bk_element *et = bk_elem_type(m, d->elem);
    const double *g = m->geoms[m->elems[d->elem].geom];
    const double half = 0.5 * (d->xi1 - d->xi0);
    for (int p = 0; p < 5; ++p) {
        double xi = d->xi0 + half * (1.0 + GX[p]), wt = fac * GW[p] * half * g[BK_GEOM_L], v[3];
        et->shape(g, xi, 0.0, 0.0, w->N);
        if (d->follower) {
            follower_vector(m, d->elem, w->qe, xi, d->value, v, K ? w->dv : NULL, w->dR);
            add_force(et, w->N, v, w->dv, wt, Q, K);
        } else {
            add_force(et, w->N, d->value, NULL, wt, Q, NULL);
        }
    }
}

static int scratch_init(scratch *w, int maxdof)
{
    size_t md = (size_t)(maxdof > 0 ? maxdof : 1);
    w->dv = malloc(3 * md * sizeof *w->dv);
    w->dR = malloc(9 * md * sizeof *w->dR);
    w->Qk = malloc(md * sizeof *w->Qk);
    w->Kk = malloc(md * md * sizeof *w->Kk);
    return w->dv && w->dR && w->Qk && w->Kk ? 0 : -1;
}

static void scratch_free(scratch *w)
{
    free(w->dv);
    free(w->dR);
    free(w->Qk);
    free(w->Kk);
}

static int varying_force(const bk_force_load *f)
{
    return f->amp >= 0 || f->follower;
}

static int varying_moment(const bk_moment_load *mo)
{
    return mo->amp >= 0 || mo->follower;
}

/* One element's contribution of a load: gathers, zeroes Q (and K), evaluates. */
static void begin(const bk_model *m, int e, const double *q, scratch *w, double *Q, double *K)
{
    const int nd = bk_elem_type(m, e)->ndof;
    bk_gather(m, e, q, w->qe);
    memset(Q, 0, (size_t)nd * sizeof *Q);
    if (K)
        memset(K, 0, (size_t)nd * (size_t)nd * sizeof *K);
}

static void finish(bk_system *s, int e, const double *Q, const double *K, double *fint, double *Ax)
{
    bk_scatter(s->m, e, Q, -1.0, fint);
    if (Ax && K)
        bk_scatter_matrix(s, e, K, -1.0, Ax);
}

int bk_loads_present(const bk_model *m)
{
    int any = m->ndload > 0 || m->ntendon > 0 || (m->has_gravity && m->gravity_amp);
    for (int i = 0; i < m->nforce && !any; ++i)
        any = varying_force(&m->forces[i]);
    for (int i = 0; i < m->nmoment && !any; ++i)
        any = varying_moment(&m->moments[i]);
    return any;
}

struct bk_loads_scratch {
    scratch w;
};

bk_loads_scratch *bk_loads_scratch_new(int maxdof)
{
    bk_loads_scratch *ls = calloc(1, sizeof *ls);
    if (ls && scratch_init(&ls->w, maxdof) != 0) {
        bk_loads_scratch_free(ls);
        return NULL;
    }
    return ls;
}

void bk_loads_scratch_free(bk_loads_scratch *ls)
{
    if (ls)
        scratch_free(&ls->w);
    free(ls);
}

void bk_assemble_loads(bk_system *s, const double *q, double x, double *fint, double *Ax)
{
    if (!bk_loads_present(s->m))
        return;
    bk_loads_scratch *ls = bk_loads_scratch_new(s->maxdof);
    if (!ls) {
        for (int i = 0; i < s->m->ndof; ++i)
            fint[i] = NAN;            /* out of memory: the solver stops on a non-finite residual */
        return;
    }
    bk_assemble_loads_in(s, ls, q, x, fint, Ax);
    bk_loads_scratch_free(ls);
}

void bk_assemble_loads_in(bk_system *s, bk_loads_scratch *ls, const double *q, double x, double *fint, double *Ax)
{
    const bk_model *m = s->m;
    scratch *w = &ls->w;
    double *Q = s->fe, *K = Ax ? s->Ke : NULL;
    for (int i = 0; i < m->nforce; ++i) {
        const bk_force_load *f = &m->forces[i];
        if (!varying_force(f))
            continue;
        begin(m, f->elem, q, w, Q, K);
        point_force(m, f, bk_load_factor(m, f->amp, x), w, Q, K);
        finish(s, f->elem, Q, K, fint, Ax);
    }
    for (int i = 0; i < m->nmoment; ++i) {
        const bk_moment_load *mo = &m->moments[i];
        if (!varying_moment(mo))
            continue;
        begin(m, mo->elem, q, w, Q, K);
        point_moment(m, mo, bk_load_factor(m, mo->amp, x), w, Q, K);
        finish(s, mo->elem, Q, K, fint, Ax);
    }
    for (int i = 0; i < m->ndload; ++i) {
        const bk_dist_load *d = &m->dloads[i];
        begin(m, d->elem, q, w, Q, d->follower ? K : NULL);
        dist_load(m, d, bk_load_factor(m, d->amp, x), w, Q, d->follower ? K : NULL);
        finish(s, d->elem, Q, d->follower ? K : NULL, fint, Ax);
    }
    if (m->has_gravity && m->gravity_amp) {
        double gf = bk_amp_eval(m->gravity_amp, x, 0);
        for (int e = 0; e < m->nelem; ++e) {
            const bk_element *et = bk_elem_type(m, e);
            memset(Q, 0, (size_t)et->ndof * sizeof *Q);
            bk_element_weight(m, e, w->N);
            add_force(et, w->N, m->gravity, NULL, gf, Q, NULL);
            bk_scatter(m, e, Q, -1.0, fint);
        }
    }
    for (int i = 0; i < m->ntendon; ++i) {
        const bk_tendon *t = &m->tendons[i];
        double T = t->tension * bk_load_factor(m, t->amp, x);
        for (int k = 0; k < t->npiece; ++k) {
            begin(m, t->pieces[k].elem, q, w, Q, K);
            bk_tendon_piece_load(m, &t->pieces[k], T, w->qe, w->dv, w->Kk, Q, K);
            finish(s, t->pieces[k].elem, Q, K, fint, Ax);
        }
    }
}

/* -v . (p(q) - p(q0)) at the point with shape functions N; qe, qe0 gathered. */
static double dead_work(const bk_element *et, const double *N, const double *v, const double *qe,
                        const double *qe0)
{
    double V = 0.0;
    for (int a = 0; a < et->nshape; ++a)
        for (int k = 0; k < 3; ++k)
            V -= N[a] * v[k] * (qe[et->shape_dof[a] + k] - qe0[et->shape_dof[a] + k]);
    return V;
}

void bk_load_potentials(const bk_system *s, const double *q, double x, double *Vg, double *Vf)
{
    const bk_model *m = s->m;
    double qe[BK_MAX_ELEMENT_DOF], qe0[BK_MAX_ELEMENT_DOF], N[BK_MAX_SHAPE];
    for (int i = 0; i < m->nforce; ++i) {
        const bk_force_load *f = &m->forces[i];
        if (f->amp < 0 || f->follower)
            continue;                       /* constant: in bk_external_load; follower: no potential */
        bk_gather(m, f->elem, q, qe);
        bk_gather(m, f->elem, m->q0, qe0);
        bk_force_shape(m, f, N);
        *Vf += bk_load_factor(m, f->amp, x) * dead_work(bk_elem_type(m, f->elem), N, f->value, qe, qe0);
    }
    for (int i = 0; i < m->ndload; ++i) {
        const bk_dist_load *d = &m->dloads[i];
        if (d->follower)
            continue;
        const bk_element *et = bk_elem_type(m, d->elem);
        const double *g = m->geoms[m->elems[d->elem].geom];
        const double half = 0.5 * (d->xi1 - d->xi0), fac = bk_load_factor(m, d->amp, x);
        bk_gather(m, d->elem, q, qe);
        bk_gather(m, d->elem, m->q0, qe0);
        for (int p = 0; p < 5; ++p) {
            et->shape(g, d->xi0 + half * (1.0 + GX[p]), 0.0, 0.0, N);
            *Vf += fac * GW[p] * half * g[BK_GEOM_L] * dead_work(et, N, d->value, qe, qe0);
        }
    }
    if (m->has_gravity && m->gravity_amp) {
        double gf = bk_amp_eval(m->gravity_amp, x, 0);
        for (int e = 0; e < m->nelem; ++e) {
            const bk_element *et = bk_elem_type(m, e);
            bk_gather(m, e, q, qe);
            bk_gather(m, e, m->q0, qe0);
            bk_element_weight(m, e, N);
            *Vg += gf * dead_work(et, N, m->gravity, qe, qe0);
        }
    }
    for (int i = 0; i < m->ntendon; ++i) {
        const bk_tendon *t = &m->tendons[i];
        double T = t->tension * bk_load_factor(m, t->amp, x);
        for (int k = 0; k < t->npiece; ++k) {
            bk_gather(m, t->pieces[k].elem, q, qe);
            bk_gather(m, t->pieces[k].elem, m->q0, qe0);
            *Vf += T * (bk_tendon_piece_length(m, &t->pieces[k], qe) - bk_tendon_piece_length(m, &t->pieces[k], qe0));
        }
    }
}

static int inside(double xi)
{
    return xi > 1e-12 && xi < 1.0 - 1e-12;
}

void bk_element_loads(const bk_system *s, const double *q, double x, int e, double *Qe)
{
    const bk_model *m = s->m;
    const bk_element *et = bk_elem_type(m, e);
    const int nd = et->ndof;
    scratch w;
    if (scratch_init(&w, nd) != 0) {
        scratch_free(&w);
        for (int i = 0; i < nd; ++i)
            Qe[i] = NAN;
        return;
    }
    bk_gather(m, e, q, w.qe);
    if (m->has_gravity) {
        double gf = m->gravity_amp ? bk_amp_eval(m->gravity_amp, x, 0) : bk_load_factor(m, -1, x);
        bk_element_weight(m, e, w.N);
        add_force(et, w.N, m->gravity, NULL, gf, Qe, NULL);
    }
    for (int i = 0; i < m->nforce; ++i) {
        const bk_force_load *f = &m->forces[i];
        if (f->elem == e && inside(f->xi))
            point_force(m, f, bk_load_factor(m, f->amp, x), &w, Qe, NULL);
    }
    for (int i = 0; i < m->nmoment; ++i) {
        const bk_moment_load *mo = &m->moments[i];
        if (mo->elem == e && inside(mo->xi) && et->moment)
            point_moment(m, mo, bk_load_factor(m, mo->amp, x), &w, Qe, NULL);
    }
    for (int i = 0; i < m->ndload; ++i)
        if (m->dloads[i].elem == e)
            dist_load(m, &m->dloads[i], bk_load_factor(m, m->dloads[i].amp, x), &w, Qe, NULL);
    for (int i = 0; i < m->ntendon; ++i) {
        const bk_tendon *t = &m->tendons[i];
        for (int k = 0; k < t->npiece; ++k)
            if (t->pieces[k].elem == e)
                bk_tendon_piece_load(m, &t->pieces[k], t->tension * bk_load_factor(m, t->amp, x), w.qe, w.dv, w.Kk,
                                     Qe, NULL);
    }
    scratch_free(&w);
}

int bk_element_loads_present(const bk_model *m)
{
    return m->has_gravity || m->nforce > 0 || m->nmoment > 0 || m->ndload > 0 || m->ntendon > 0;
}
