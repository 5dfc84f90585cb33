/* dyn_frame.c -- the rotating frame of a dynamic run (dynamic.frame): the
 * frame's rotation at a time, the inertia forces in it (translational frame
 * forces and the rotary inertia turned in and out), the inertial state and
 * multipliers for the outputs (the equations: dyn_frame.h; the frame made from
 * its constraint: dyn_frame_setup.c). */
#include "analysis/dyn_frame.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double UNTURNED[3] = {1.0, 0.0, 0.0};   /* the d-th derivative of T on such a coordinate */

/* The d-th time derivative of T on a block of the kind, row-major dim x dim. */
static const double *blockmat(const bk_dyn_frame *f, int kind, int d, int *dim)
{
    *dim = kind == 3 ? 4 : kind ? 3 : 1;
    return kind == 3 ? f->L[d] : kind ? f->R[d] : UNTURNED + d;
}

/* y = B x (trans: B^T x) for B the d-th derivative of T on an element's blocks. */
static void vapply(const bk_dyn_frame *f, const bk_element *et, int d, int trans, const double *x, double *y)
{
    for (int k = 0; k < et->nfield; ++k) {
        int dim;
        const double *B = blockmat(f, bk_frame_field_kind(et, k), d, &dim);
        const int o = et->field_dof[k];
        for (int i = 0; i < dim; ++i) {
            double s = 0.0;
            for (int j = 0; j < dim; ++j)
                s += (trans ? B[j * dim + i] : B[i * dim + j]) * x[o + j];
            y[o + i] = s;
        }
    }
}

/* x[0 .. n-1] (stride) all zero: the inertia matrices are sparse by blocks */
static int zero(const double *x, int n, int stride)
{
    for (int i = 0; i < n; ++i)
        if (x[i * stride] != 0.0)
            return 0;
    return 1;
}

/* out += c A B (A, out: ndof x ndof row-major), B the d-th derivative of T. */
static void rmul_add(const bk_dyn_frame *f, const bk_element *et, int d, double c, const double *A, double *out)
{
    const int nd = et->ndof;
    if (c == 0.0)
        return;
    for (int k = 0; k < et->nfield; ++k) {
        int dim;
        const double *B = blockmat(f, bk_frame_field_kind(et, k), d, &dim);
        const int o = et->field_dof[k];
        for (int i = 0; i < nd; ++i)
            for (int j = 0; j < dim && !zero(A + i * nd + o, dim, 1); ++j) {
                double s = 0.0;
                for (int l = 0; l < dim; ++l)
                    s += A[i * nd + o + l] * B[l * dim + j];
                out[i * nd + o + j] += c * s;
            }
    }
}

/* out = T^T A. */
static void tmul(const bk_dyn_frame *f, const bk_element *et, const double *A, double *out)
{
    const int nd = et->ndof;
    for (int k = 0; k < et->nfield; ++k) {
        int dim;
        const double *B = blockmat(f, bk_frame_field_kind(et, k), 0, &dim);
        const int o = et->field_dof[k];
        if (zero(A + o * nd, dim * nd, 1)) {
            memset(out + o * nd, 0, (size_t)(dim * nd) * sizeof *out);
            continue;
        }
        for (int j = 0; j < dim; ++j)
            for (int c = 0; c < nd; ++c) {
                if (zero(A + o * nd + c, dim, nd)) {
                    out[(o + j) * nd + c] = 0.0;
                    continue;
                }
                double s = 0.0;
                for (int l = 0; l < dim; ++l)
                    s += B[l * dim + j] * A[(o + l) * nd + c];
                out[(o + j) * nd + c] = s;
            }
    }
}

/* y = q less the axis point on the positions (element blocks). */
static void element_y(const bk_dyn_frame *f, const bk_element *et, const double *qe, double *y, double sign)
{
    memcpy(y, qe, (size_t)et->ndof * sizeof *y);
    for (int k = 0; k < et->nfield; ++k)
        if (bk_frame_field_kind(et, k) == 1)
            for (int i = 0; i < 3; ++i)
                y[et->field_dof[k] + i] -= sign * f->c[i];
}

static void quat_lmat(const double *a, double *L)
{
    const double M[16] = {a[0], -a[1], -a[2], -a[3], a[1], a[0], -a[3], a[2],
                          a[2], a[3], a[0], -a[1], a[3], -a[2], a[1], a[0]};
    memcpy(L, M, sizeof M);
}

void bk_frame_at(bk_dyn_frame *f, double t)
{
    if (!f || !f->on)
        return;
    f->t = t;
    const double ph = bk_frame_angle(f, t, 0) - f->th0, d1 = bk_frame_angle(f, t, 1), d2 = bk_frame_angle(f, t, 2);
    const double *n = f->n;
    const double K[9] = {0.0, -n[2], n[1], n[2], 0.0, -n[0], -n[1], n[0], 0.0};
    double K2[9];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            K2[3 * i + j] = n[i] * n[j] - (i == j);
    const double cp = cos(ph), sp = sin(ph), ch = cos(0.5 * ph), sh = sin(0.5 * ph);
    for (int i = 0; i < 9; ++i) {
        f->R[0][i] = (i % 4 == 0) + sp * K[i] + (1.0 - cp) * K2[i];
        f->R[1][i] = d1 * (cp * K[i] + sp * K2[i]);
        f->R[2][i] = d2 * (cp * K[i] + sp * K2[i]) + d1 * d1 * (cp * K2[i] - sp * K[i]);
    }
    double r[3][4] = {{ch}, {-0.5 * d1 * sh}, {-0.5 * d2 * sh - 0.25 * d1 * d1 * ch}};
    for (int i = 0; i < 3; ++i) {
        r[0][1 + i] = sh * n[i];
        r[1][1 + i] = 0.5 * d1 * ch * n[i];
        r[2][1 + i] = (0.5 * d2 * ch - 0.25 * d1 * d1 * sh) * n[i];
    }
    for (int d = 0; d < 3; ++d)
        quat_lmat(r[d], f->L[d]);
}

double bk_frame_ctime(const bk_dyn_frame *f, double t)
{
    return f && f->on ? 0.0 : t;
}

/* A global block's dimension, the d-th derivative of T on it and its y. */
static const double *block_y(const bk_dyn_frame *f, int b, int d, const double *q, double *y, int *dim)
{
    const int *bl = f->block[b];
    const double *B = blockmat(f, bl[0], d, dim);
    for (int i = 0; i < *dim; ++i)
        y[i] = q[bl[1 + i]] - (bl[0] == 1 ? f->c[i] : 0.0);
    return B;
}

static void matvec(const double *B, int dim, const double *x, double *y, int trans)
{
    for (int i = 0; i < dim; ++i) {
        y[i] = 0.0;
        for (int j = 0; j < dim; ++j)
            y[i] += (trans ? B[j * dim + i] : B[i * dim + j]) * x[j];
    }
}

void bk_frame_velocity(const bk_dyn_frame *f, const bk_model *m, const double *q, const double *qd, double *va)
{
    memcpy(va, qd, (size_t)m->ndof * sizeof *va);
    for (int b = 0; b < f->nblock; ++b) {
        int dim;
        double y[4], u[4], v[4];
        const double *B1 = block_y(f, b, 1, q, y, &dim), *B0 = blockmat(f, f->block[b][0], 0, &dim);
        matvec(B1, dim, y, u, 0);
        matvec(B0, dim, u, v, 1);
        for (int i = 0; i < dim; ++i)
            va[f->block[b][1 + i]] += v[i];
    }
}

void bk_frame_initial(bk_dyn_frame *f, const bk_system *s, const double *q, double *qd)
{
    const bk_model *m = s->m;
    bk_frame_at(f, 0.0);
    for (int b = 0; b < f->nblock; ++b) {           /* q' = T^T (q_a' - T' y) */
        int dim;
        double y[4], u[4], v[4];
        const double *B1 = block_y(f, b, 1, q, y, &dim), *B0 = blockmat(f, f->block[b][0], 0, &dim);
        matvec(B1, dim, y, u, 0);
        for (int i = 0; i < dim; ++i)
            u[i] = qd[f->block[b][1 + i]] - u[i];
        matvec(B0, dim, u, v, 1);
        for (int i = 0; i < dim; ++i)
            qd[f->block[b][1 + i]] = v[i];
    }
    const bk_reaction *rc = f->rc;
    for (int k = 0; k < rc->nlin; ++k)
        qd[m->lincons[rc->lin[k]].dof[0]] = 0.0;
    for (int i = 0; f->joint && i < 7; ++i)
        qd[m->nlcons[rc->nlcon].dof[i]] = 0.0;
}

void bk_frame_held_rows(const bk_dyn_frame *f, const bk_system *s, double *r)
{
    const bk_reaction *rc = f->rc;
    for (int k = 0; k < rc->nlin; ++k)
        r[s->nfree + rc->lin[k]] = 0.0;
    for (int k = f->row0; f->joint && k < s->jrow[rc->nlcon + 1]; ++k)
        r[s->nfree + k] = 0.0;
}

void bk_frame_inertial(bk_dyn_frame *f, const bk_system *s, const double *q, const double *qd, const double *qdd,
                       const double *nu)
{
    const size_t nd = (size_t)s->m->ndof;
    memcpy(f->qa, q, nd * sizeof *q);
    memcpy(f->qda, qd, nd * sizeof *q);
    memcpy(f->qdda, qdd, nd * sizeof *q);
    if (nu && s->ncon)
        memcpy(f->nua, nu, (size_t)s->ncon * sizeof *nu);
    if (nu && f->joint)                         /* the joint's point rows turn with R, the others not */
        matvec(f->R[0], 3, nu + f->row0, f->nua + f->row0, 0);
    for (int b = 0; b < f->nblock; ++b) {
        const int *bl = f->block[b];
        int dim;
        double y[4], x[4], v[4], a[4], u[4];
        const double *B0 = block_y(f, b, 0, q, y, &dim);
        const double *B1 = blockmat(f, bl[0], 1, &dim), *B2 = blockmat(f, bl[0], 2, &dim);
        for (int i = 0; i < dim; ++i)
            x[i] = qd[bl[1 + i]], a[i] = qdd[bl[1 + i]];
        for (int i = 0; i < dim; ++i) {
            double p = bl[0] == 1 ? f->c[i] : 0.0, pd = 0.0, pdd = 0.0;
            for (int j = 0; j < dim; ++j) {
                p += B0[i * dim + j] * y[j];
                pd += B1[i * dim + j] * y[j] + B0[i * dim + j] * x[j];
                pdd += B2[i * dim + j] * y[j] + 2.0 * B1[i * dim + j] * x[j] + B0[i * dim + j] * a[j];
            }
            f->qa[bl[1 + i]] = p, f->qda[bl[1 + i]] = pd, f->qdda[bl[1 + i]] = pdd;
        }
        if (!nu || f->joint || f->rowof[bl[1]] < 0)
            continue;
        for (int i = 0; i < dim; ++i)             /* the rows' generalized forces turned back */
            v[i] = nu[f->rowof[bl[1 + i]]];
        matvec(B0, dim, v, u, 0);
        for (int i = 0; i < dim; ++i)
            f->nua[f->rowof[bl[1 + i]]] = u[i];
    }
}

void bk_frame_forces(bk_dyn_frame *f, const bk_system *s, const double *q, const double *qd, double gp, double kp,
                     double *fint, double *Ax)
{
    const bk_model *m = s->m;
    for (int e = 0; e < m->nelem; ++e) {
        const bk_element *et = bk_elem_type(m, e);
        const int nd = et->ndof;
        bk_gather(m, e, q, f->z);
        element_y(f, et, f->z, f->y, 1.0);
        bk_gather(m, e, qd, f->g);
        vapply(f, et, 1, 0, f->g, f->z);                /* z = T'' y + 2 T' q' */
        vapply(f, et, 2, 0, f->y, f->g);
        for (int i = 0; i < nd; ++i)
            f->z[i] = 2.0 * f->z[i] + f->g[i];
        bk_element_mass(m, e, f->W, f->Me);
        for (int i = 0; i < nd; ++i) {
            double v = 0.0;
            for (int j = 0; j < nd; ++j)
                v += f->Me[i * nd + j] * f->z[j];
            f->y[i] = v;
        }
        vapply(f, et, 0, 1, f->y, f->g);
        bk_scatter(m, e, f->g, 1.0, fint);
        if (Ax && (kp != 0.0 || gp != 0.0)) {
            memset(f->W, 0, (size_t)nd * nd * sizeof *f->W);
            rmul_add(f, et, 2, kp, f->Me, f->W);
            rmul_add(f, et, 1, 2.0 * gp, f->Me, f->W);
            tmul(f, et, f->W, f->S);
            bk_scatter_matrix(s, e, f->S, 1.0, Ax);
        }
    }
}

void bk_frame_rotary_in(bk_dyn_frame *f, const bk_element *et, double *qe, double *qde, double *qdde)
{
    const int nd = et->ndof;
    element_y(f, et, qe, f->y, 1.0);
    vapply(f, et, 2, 0, f->y, f->z);                    /* q_a'' = T'' y + 2 T' q' + T q'' */
    vapply(f, et, 1, 0, qde, f->g);
    for (int i = 0; i < nd; ++i)
        f->z[i] += 2.0 * f->g[i];
    vapply(f, et, 0, 0, qdde, f->g);
    for (int i = 0; i < nd; ++i)
        qdde[i] = f->z[i] + f->g[i];
    vapply(f, et, 1, 0, f->y, f->z);                    /* q_a' = T' y + T q' */
    vapply(f, et, 0, 0, qde, f->g);
    for (int i = 0; i < nd; ++i)
        qde[i] = f->z[i] + f->g[i];
    vapply(f, et, 0, 0, f->y, f->z);                    /* q_a = T y + offset */
    element_y(f, et, f->z, qe, -1.0);
}

void bk_frame_rotary_out(bk_dyn_frame *f, const bk_element *et, double *fe, double *Mq, double *Cq, double *Kq)
{
    const int nd = et->ndof;
    const size_t nn = (size_t)nd * nd * sizeof *Mq;
    vapply(f, et, 0, 1, fe, f->g);
    memcpy(fe, f->g, (size_t)nd * sizeof *fe);
    if (!Mq)
        return;
    double *S = f->S, *W = f->W, *X = f->Me;
    memset(S, 0, nn), memset(W, 0, nn), memset(X, 0, nn);
    rmul_add(f, et, 0, 1.0, Kq, S);                     /* Kq T + Cq T' + Mq T'' */
    rmul_add(f, et, 1, 1.0, Cq, S);
    rmul_add(f, et, 2, 1.0, Mq, S);
    rmul_add(f, et, 0, 1.0, Cq, W);                     /* Cq T + 2 Mq T' */
    rmul_add(f, et, 1, 2.0, Mq, W);
    rmul_add(f, et, 0, 1.0, Mq, X);                     /* Mq T */
    tmul(f, et, S, Kq);
    tmul(f, et, W, Cq);
    tmul(f, et, X, Mq);
}
