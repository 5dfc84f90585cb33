/* contact_geometry.c -- a beam's point in a rigid primitive's reference
 * coordinates, the primitives' gaps there (the generated kernels of
 * out/kernels/contact.h: a box by its faces, edges and corners), and the
 * chain rule back to the variables (contact_geometry.h). */
#include "assembly/contact_geometry.h"

#include <math.h>
#include <string.h>

#include "contact.h"

void bk_contact_placement(const bk_contact_prim *p, double f, double *pl)
{
    double w[3] = {f * p->turn[0], f * p->turn[1], f * p->turn[2]};
    const double th = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    double *Q = pl;
    for (int i = 0; i < 9; ++i)
        Q[i] = i % 4 == 0;
    if (th > 0.0) {                   /* Rodrigues: Q = I + sin th K + (1 - cos th) K^2, K = [w/th]x */
        const double k[3] = {w[0] / th, w[1] / th, w[2] / th}, s = sin(th), c = 1.0 - cos(th);
        const double K[9] = {0.0, -k[2], k[1], k[2], 0.0, -k[0], -k[1], k[0], 0.0};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                double kk = 0.0;
                for (int l = 0; l < 3; ++l)
                    kk += K[3 * i + l] * K[3 * l + j];
                Q[3 * i + j] += s * K[3 * i + j] + c * kk;
            }
    }
    for (int i = 0; i < 3; ++i) {
        pl[9 + i] = p->pivot[i] + f * p->motion[i];
        pl[12 + i] = p->pivot[i];
    }
}

void bk_contact_map_point(const bk_contact_prim *p, const double *pl, const double *qb, const double *y,
                          bk_contact_map *mp)
{
    if (p->body >= 0) {
        double out[333];
        bk_contact_body_frame(y, qb, p->body_ref, out);
        mp->nv = 10;
        mp->identity = 0;
        memcpy(mp->z, out, 3 * sizeof *out);
        memcpy(mp->J, out + 3, 30 * sizeof *out);
        memcpy(mp->T, out + 33, 300 * sizeof *out);
        return;
    }
    const double *Q = pl, *c = pl + 9, *o = pl + 12;
    mp->nv = 3;
    mp->identity = Q[0] == 1.0 && Q[4] == 1.0 && Q[8] == 1.0 && c[0] == o[0] && c[1] == o[1] && c[2] == o[2];
    if (mp->identity) {               /* a rotation with a unit diagonal is the identity */
        mp->z[0] = y[0], mp->z[1] = y[1], mp->z[2] = y[2];
        return;
    }
    for (int i = 0; i < 3; ++i) {     /* z = Q^T (y - c) + o, J = Q^T */
        mp->z[i] = o[i];
        for (int k = 0; k < 3; ++k) {
            mp->z[i] += Q[3 * k + i] * (y[k] - c[k]);
            mp->J[3 * i + k] = Q[3 * k + i];
        }
    }
}

/* A box's gap: w = A (z - c) in its axes; outside across one face the
 * face's plane, across two the edge's line, across three the corner; inside
 * minus the depth to the nearest face (a state the contact refuses). */
static void gap_box(const double *prm, const double *z, double *out)
{
    const double *c = prm, *h = prm + 3, *A = prm + 6;
    double w[3], pc[3], gw[13];
    int side[3], nout = 0;
    for (int k = 0; k < 3; ++k) {
        w[k] = 0.0;
        for (int j = 0; j < 3; ++j)
            w[k] += A[3 * k + j] * (z[j] - c[j]);
        side[k] = w[k] > h[k] ? 1 : w[k] < -h[k] ? -1 : 0;
        pc[k] = side[k] ? side[k] * h[k] : w[k];
        nout += side[k] != 0;
    }
    memset(gw, 0, sizeof gw);
    if (nout == 0) {
        int kmin = 0;
        for (int k = 1; k < 3; ++k)
            if (h[k] - fabs(w[k]) < h[kmin] - fabs(w[kmin]))
                kmin = k;
        gw[0] = -(h[kmin] - fabs(w[kmin]));
        gw[1 + kmin] = w[kmin] >= 0.0 ? 1.0 : -1.0;
    } else if (nout == 1) {
        double pr[4] = {0.0, 0.0, 0.0, 0.0};
        for (int k = 0; k < 3; ++k)
            if (side[k])
                pr[k] = side[k], pr[3] = h[k];
        bk_contact_gap_half_space(w, pr, gw);
    } else if (nout == 2) {
        double pr[7], sg[14];
        for (int k = 0; k < 3; ++k)
            pr[k] = pr[3 + k] = pc[k];
        for (int k = 0; k < 3; ++k)
            if (!side[k])
                pr[k] -= 1.0, pr[3 + k] += 1.0;   /* the edge's line, along the inside axis */
        pr[6] = 0.0;
        bk_contact_gap_segment(w, pr, sg);
        memcpy(gw, sg, sizeof gw);
    } else {
        const double pr[4] = {pc[0], pc[1], pc[2], 0.0};
        bk_contact_gap_sphere(w, pr, gw);
    }
    out[0] = gw[0];                   /* back to z: grad = A^T grad_w, H = A^T H_w A */
    for (int i = 0; i < 3; ++i) {
        out[1 + i] = 0.0;
        for (int k = 0; k < 3; ++k)
            out[1 + i] += A[3 * k + i] * gw[1 + k];
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double v = 0.0;
            for (int k = 0; k < 3; ++k)
                for (int l = 0; l < 3; ++l)
                    v += A[3 * k + i] * gw[4 + 3 * k + l] * A[3 * l + j];
            out[4 + 3 * i + j] = v;
        }
}

void bk_contact_gap_ref(const bk_contact_prim *p, const double *z, double *out)
{
    const double *prm = p->prm;
    switch (p->shape) {
    case BK_CONTACT_HALF_SPACE:
        bk_contact_gap_half_space(z, prm, out);
        return;
    case BK_CONTACT_SPHERE:
        bk_contact_gap_sphere(z, prm, out);
        return;
    case BK_CONTACT_BOX:
        gap_box(prm, z, out);
        return;
    default: {                        /* capsule: the segment's line, or the sphere at the nearer end */
        double seg[14];
        bk_contact_gap_segment(z, prm, seg);
        if (seg[13] > 0.0 && seg[13] < 1.0) {
            memcpy(out, seg, 13 * sizeof *out);
            return;
        }
        const double *end = seg[13] <= 0.0 ? prm : prm + 3;
        const double sph[4] = {end[0], end[1], end[2], prm[6]};
        bk_contact_gap_sphere(z, sph, out);
    }
    }
}

void bk_contact_chain(const bk_contact_map *mp, const double *fz, const double *Kz, double *fv, double *Kv)
{
    const int nv = mp->nv;
    const double *J = mp->J;
    if (mp->identity) {
        memcpy(fv, fz, 3 * sizeof *fv);
        if (Kv)
            memcpy(Kv, Kz, 9 * sizeof *Kv);
        return;
    }
    for (int a = 0; a < nv; ++a)
        fv[a] = J[a] * fz[0] + J[nv + a] * fz[1] + J[2 * nv + a] * fz[2];
    if (!Kv)
        return;
    double KJ[30];                    /* Kz J: 3 x nv */
    for (int i = 0; i < 3; ++i)
        for (int b = 0; b < nv; ++b)
            KJ[nv * i + b] = Kz[3 * i] * J[b] + Kz[3 * i + 1] * J[nv + b] + Kz[3 * i + 2] * J[2 * nv + b];
    for (int a = 0; a < nv; ++a)
        for (int b = 0; b < nv; ++b)
            Kv[nv * a + b] = J[a] * KJ[b] + J[nv + a] * KJ[nv + b] + J[2 * nv + a] * KJ[2 * nv + b];
    if (nv == 10)
        for (int k = 0; k < 3; ++k)
            for (int ab = 0; ab < 100; ++ab)
                Kv[ab] += fz[k] * mp->T[100 * k + ab];
}
