/* contact_points.c -- the contact interaction's sample points: where they
 * are, their distance to their primitive, the barrier's and the lagged
 * friction's force and stiffness at each (contact_impl.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/contact_impl.h"
#include "assembly/system.h"
#include "model/amplitude.h"
#include "base/csvrow.h"
#include "base/tables.h"
#include "contact.h"

/* Each primitive's placement at the path point (the amplitude's variable x). */
void contact_set_placement(contact_work *w, const bk_model *m, double x)
{
    const bk_contact_model *cm = w->cm;
    for (int i = 0; i < cm->nprim; ++i) {
        const bk_contact_prim *p = &cm->prims[i];
        int moves = 0;
        for (int k = 0; k < 3; ++k)
            moves |= p->motion[k] != 0.0 || p->turn[k] != 0.0;
        bk_contact_placement(p, moves ? bk_load_factor(m, p->amp, x) : 0.0, w->place + BK_CONTACT_PLACEMENT * i);
    }
}

/* The parameter xi of sample k of nsample and its share of the element's
 * length (see model/contact.h). */
static double sample_at(int k, int nsample, double *xi)
{
    *xi = nsample == 1 ? 0.5 : (double)k / (nsample - 1);
    if (nsample == 1)
        return 1.0;
    return (k == 0 || k == nsample - 1 ? 0.5 : 1.0) / (nsample - 1);
}

int contact_sample_shapes(contact_work *w, const bk_model *m)
{
    const bk_contact_model *cm = w->cm;
    double N[BK_MAX_SHAPE], xi;
    long tot = 0;
    int p = 0;
    w->Noff = malloc(((size_t)w->npoint + 1) * sizeof *w->Noff);
    w->qdof = malloc(((size_t)w->npoint + 1) * sizeof *w->qdof);
    if (!w->Noff || !w->qdof)
        return -1;
    for (int c = 0; c < cm->nset; ++c)
        for (int i = 0; i < cm->sets[c].nelem; ++i)
            for (int k = 0; k < cm->sets[c].nsample; ++k, ++p) {
                w->Noff[p] = tot;
                tot += bk_elem_type(m, cm->sets[c].elems[i])->nshape;
            }
    w->Noff[p] = tot;
    w->Nc = malloc((size_t)(tot > 0 ? tot : 1) * sizeof *w->Nc);
    if (!w->Nc)
        return -1;
    p = 0;
    for (int c = 0; c < cm->nset; ++c)
        for (int i = 0; i < cm->sets[c].nelem; ++i) {
            const int e = cm->sets[c].elems[i];
            const bk_element *et = bk_elem_type(m, e);
            int best = 0;
            for (int k = 0; k < cm->sets[c].nsample; ++k, ++p) {
                sample_at(k, cm->sets[c].nsample, &xi);
                et->shape(m->geoms[m->elems[e].geom], xi, 0.0, 0.0, N);
                for (int a = 0; a < et->nshape; ++a)
                    w->Nc[w->Noff[p] + a] = N[a];
                w->qdof[p] = -1;           /* the quaternion of the node nearest xi (the j-th is node j's) */
                for (int f = 0, j = 0; f < et->nfield; ++f)
                    if (et->field_role[f] == BK_FIELD_QUATERNION && j < et->nnode) {
                        if (w->qdof[p] < 0 || fabs(et->node_xi[j] - xi) <= fabs(et->node_xi[best] - xi))
                            w->qdof[p] = et->field_dof[f], best = j;
                        j++;
                    }
            }
        }
    return 0;
}

void contact_barrier_terms(const bk_contact_set *set, double wl, const double *g, double dist, double *fp,
                           double *Kp)
{
    double b[3];
    memset(fp, 0, 3 * sizeof *fp);
    memset(Kp, 0, 9 * sizeof *Kp);
    if (dist < set->shat) {            /* E = wl b(s): dE/dx = wl b' grad g; d2E = wl (b'' grad grad^T + b' H) */
        bk_contact_barrier(dist, set->shat, b);
        for (int r = 0; r < 3; ++r) {
            fp[r] += wl * b[1] * g[1 + r];
            for (int j = 0; j < 3; ++j)
                Kp[3 * r + j] += wl * (b[2] * g[1 + r] * g[1 + j] + b[1] * g[4 + 3 * r + j]);
        }
    }
}

void contact_friction_terms(const contact_work *w, const bk_contact_set *set, int p, const double *x, double *fp,
                            double *Kp)
{
    if (set->mu > 0.0 && w->lam[p] > 0.0) {   /* D = mu lam f0(|u_t|), u_t = P (x - x_prev), P = I - n n^T */
        const double *n = w->nrm + 3 * p, *xp = w->xprev + 3 * p;
        double u[3], ut[3], f[4];
        for (int r = 0; r < 3; ++r)
            u[r] = x[r] - xp[r];
        const double un = u[0] * n[0] + u[1] * n[1] + u[2] * n[2];
        for (int r = 0; r < 3; ++r)
            ut[r] = u[r] - un * n[r];
        const double y = sqrt(ut[0] * ut[0] + ut[1] * ut[1] + ut[2] * ut[2]);
        double h[2];
        bk_contact_friction(y, set->slip, f);
        bk_contact_transition(y, set->slip, h);
        /* force lam phi(y) u_t / y, phi = mu(y) f1(y), mu(y) = mu_s - (mu_s - mu_k) h(y) */
        const double mu = set->mu - (set->mu - set->mu_k) * h[0], dmu = -(set->mu - set->mu_k) * h[1];
        const double py = mu * f[2], dpy = dmu * f[2] + mu * f[3], c = w->lam[p];
        for (int r = 0; r < 3; ++r) {
            fp[r] += c * py * ut[r];
            for (int j = 0; j < 3; ++j)
                Kp[3 * r + j] += c * (py * ((r == j) - n[r] * n[j]) + (y > 0.0 ? dpy / y * ut[r] * ut[j] : 0.0));
        }
    }
}

/* Force fp[3] (internal sign: what fint gains) and stiffness Kp[9] = dfp/dz of
 * sample point p: the barrier's (g: the gap at its point z) and, with
 * friction, the lagged friction's at xf. */
void contact_point_terms(const contact_work *w, const bk_contact_set *set, int p, double wl, const double *z,
                         const double *xf, const double *g, double dist, double *fp, double *Kp)
{
    (void)z;                           /* (the barrier needs only the gap there) */
    contact_barrier_terms(set, wl, g, dist, fp, Kp);
    contact_friction_terms(w, set, p, xf, fp, Kp);
}


/* Every sample point of every set at q, or (only) those of the last broad
 * phase's candidates (positions from w->X). */
static void visit(const contact_work *w, const bk_system *s, const double *q, void (*fn)(void *, point *),
                  void (*element)(void *, point *, int), void *ctx, int only)
{
    const bk_model *m = s->m;
    const bk_contact_model *cm = w->cm;
    double qe[BK_MAX_ELEMENT_DOF];
    point pt;
    int entry = 0;
    pt.p = 0;
    for (pt.c = 0; pt.c < cm->nset; ++pt.c) {
        pt.set = &cm->sets[pt.c];
        pt.prim = &cm->prims[pt.set->prim];
        const double *pl = w->place + BK_CONTACT_PLACEMENT * pt.set->prim;
        if (pt.prim->body >= 0)
            bk_gather(m, pt.prim->body, q, pt.qb);
        for (pt.i = 0; pt.i < pt.set->nelem; ++pt.i, ++entry) {
            if (only && !w->cand[entry]) {
                pt.p += pt.set->nsample;
                continue;
            }
            pt.e = pt.set->elems[pt.i];
            pt.et = bk_elem_type(m, pt.e);
            const double kl = m->geoms[m->elems[pt.e].geom][BK_GEOM_L] * pt.set->kappa;
            bk_gather(m, pt.e, q, qe);
            pt.qe = qe;
            if (element)
                element(ctx, &pt, 0);
            for (pt.k = 0; pt.k < pt.set->nsample; ++pt.k, ++pt.p) {
                double xi;
                pt.wl = kl * sample_at(pt.k, pt.set->nsample, &xi);
                pt.N = w->Nc + w->Noff[pt.p];
                if (only) {
                    memcpy(pt.x, w->X + 3 * pt.p, sizeof pt.x);
                } else {
                    pt.x[0] = pt.x[1] = pt.x[2] = 0.0;
                    for (int a = 0; a < pt.et->nshape; ++a)
                        for (int r = 0; r < 3; ++r)
                            pt.x[r] += pt.N[a] * qe[pt.et->shape_dof[a] + r];
                }
                bk_contact_map_point(pt.prim, pl, pt.qb, pt.x, &pt.mp);
                bk_contact_gap_ref(pt.prim, pt.mp.z, pt.g);
                pt.dist = pt.g[0] - pt.set->radius[pt.i];
                pt.roll = w->qdof[pt.p] >= 0 && pt.set->mu > 0.0 && w->lam[pt.p] > 0.0;
                if (pt.roll) {             /* friction on the surface point y = x + R(p) a */
                    static const double nof[3] = {0.0, 0.0, 0.0};
                    double y[3];
                    bk_contact_lever(qe + w->qdof[pt.p], w->arm + 3 * pt.p, nof, pt.lev);
                    for (int r = 0; r < 3; ++r)
                        y[r] = pt.x[r] + pt.lev[r];
                    bk_contact_map_point(pt.prim, pl, pt.qb, y, &pt.mpf);
                }
                fn(ctx, &pt);
            }
            if (element)
                element(ctx, &pt, 1);
        }
    }
}

/* Calls fn(ctx, pt) for every sample point of every set at q (sets, their
 * elements, their samples, in order), and, when not NULL, element(ctx, pt,
 * 0) before an element's first point and element(ctx, pt, 1) after its last. */
void contact_each_point(const contact_work *w, const bk_system *s, const double *q, void (*fn)(void *, point *),
                        void (*element)(void *, point *, int), void *ctx)
{
    visit(w, s, q, fn, element, ctx, 0);
}

void contact_each_candidate(const contact_work *w, const bk_system *s, const double *q,
                            void (*fn)(void *, point *), void (*element)(void *, point *, int), void *ctx)
{
    visit(w, s, q, fn, element, ctx, 1);
}

/* Whether point pt feels the contact: within the barrier's reach, or rubbing. */
int contact_acts(const contact_work *w, const point *pt)
{
    return pt->dist < pt->set->shat || (pt->set->mu > 0.0 && w->lam[pt->p] > 0.0);
}

/* The force fv[nv] and (Kv not NULL) stiffness Kv[nv^2] of point pt on its
 * variables v (mp.nv: the point's position, then its body's coordinates). */
void contact_point_force(const contact_work *w, const point *pt, double *fv, double *Kv)
{
    double fz[3], Kz[9];
    contact_point_terms(w, pt->set, pt->p, pt->wl, pt->mp.z, pt->roll ? pt->mpf.z : pt->mp.z, pt->g, pt->dist, fz,
                        Kz);
    bk_contact_chain(&pt->mp, fz, Kz, fv, Kv);
}
