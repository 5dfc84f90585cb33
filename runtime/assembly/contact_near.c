/* contact_near.c -- the broad phase of contact with rigid primitives
 * (contact_impl.h): every element's sample points (kept in contact_work.X),
 * their box taken into the primitive's reference coordinates, a lower bound
 * of the primitive's gap over that box (exact for a half-space and a sphere;
 * for a capsule and a box the distance to their own axis-aligned box), and
 * the elements whose box comes within the barrier's reach plus the section's
 * radius (or that have a point rubbing) marked as candidates for the exact
 * narrow phase (contact_points.c).  Linear in the number of elements. */
#include <math.h>
#include <string.h>

#include "assembly/contact_force.h"
#include "assembly/contact_impl.h"
#include "assembly/system.h"

/* The affine map z = A y + b of a world point y to primitive prim's reference
 * coordinates at its placement pl (or, on a body, at the body's coordinates
 * qb): from the map of the origin and its derivative in y. */
static void affine_map(const bk_contact_prim *prim, const double *pl, const double *qb, double *A, double *b)
{
    static const double o[3] = {0.0, 0.0, 0.0};
    bk_contact_map mp;
    bk_contact_map_point(prim, pl, qb, o, &mp);
    for (int i = 0; i < 3; ++i) {
        b[i] = mp.z[i];
        for (int k = 0; k < 3; ++k)
            A[3 * i + k] = mp.identity ? (double)(i == k) : mp.J[mp.nv * i + k];
    }
}

/* The squared distance between boxes [lo, hi] and [plo, phi]. */
static double box_box2(const double *lo, const double *hi, const double *plo, const double *phi)
{
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double g = fmax(0.0, fmax(plo[k] - hi[k], lo[k] - phi[k]));
        d2 += g * g;
    }
    return d2;
}

/* A lower bound of the reference primitive's gap over the box [lo, hi]. */
static double gap_below(const bk_contact_prim *p, const double *lo, const double *hi)
{
    const double *prm = p->prm;
    double plo[3], phi[3];
    switch (p->shape) {
    case BK_CONTACT_HALF_SPACE: {         /* n . z - d at the box's corner furthest into the solid */
        double g = -prm[3];
        for (int k = 0; k < 3; ++k)
            g += prm[k] * (prm[k] > 0.0 ? lo[k] : hi[k]);
        return g;
    }
    case BK_CONTACT_SPHERE:
        return sqrt(box_box2(lo, hi, prm, prm)) - prm[3];
    case BK_CONTACT_CAPSULE:              /* the segment's box, less the radius */
        for (int k = 0; k < 3; ++k)
            plo[k] = fmin(prm[k], prm[3 + k]), phi[k] = fmax(prm[k], prm[3 + k]);
        return sqrt(box_box2(lo, hi, plo, phi)) - prm[6];
    default:                              /* box: centre c, half-sizes h, rows of A its axes */
        for (int k = 0; k < 3; ++k) {
            double e = 0.0;
            for (int j = 0; j < 3; ++j)
                e += fabs(prm[6 + 3 * j + k]) * prm[3 + j];
            plo[k] = prm[k] - e, phi[k] = prm[k] + e;
        }
        return sqrt(box_box2(lo, hi, plo, phi));
    }
}

int contact_broad(contact_work *w, const bk_system *s, const double *q)
{
    const bk_model *m = s->m;
    const bk_contact_model *cm = w->cm;
    double qe[BK_MAX_ELEMENT_DOF], qb[7], A[9], b[3];
    int p = 0, entry = 0, ncand = 0;
    for (int c = 0; c < cm->nset; ++c) {
        const bk_contact_set *set = &cm->sets[c];
        const bk_contact_prim *prim = &cm->prims[set->prim];
        if (prim->body >= 0)
            bk_gather(m, prim->body, q, qb);
        affine_map(prim, w->place + BK_CONTACT_PLACEMENT * set->prim, qb, A, b);
        int ident = 1;                       /* (a primitive in its reference place: z = y) */
        for (int k = 0; k < 9; ++k)
            ident &= A[k] == (double)(k % 4 == 0) && (k >= 3 || b[k] == 0.0);
        const int ns = set->nsample;
        for (int i = 0; i < set->nelem; ++i, ++entry, p += ns) {
            const int e = set->elems[i];
            const bk_element *et = bk_elem_type(m, e);
            double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
            int rubs = 0;
            bk_gather(m, e, q, qe);
            for (int k = 0; k < ns; ++k) {
                const double *N = w->Nc + w->Noff[p + k];
                double *x = w->X + 3 * (p + k);
                x[0] = x[1] = x[2] = 0.0;
                for (int a = 0; a < et->nshape; ++a)
                    for (int r = 0; r < 3; ++r)
                        x[r] += N[a] * qe[et->shape_dof[a] + r];
                for (int r = 0; r < 3; ++r) {     /* (no NaN here: an element's coordinates are finite) */
                    lo[r] = x[r] < lo[r] ? x[r] : lo[r];
                    hi[r] = x[r] > hi[r] ? x[r] : hi[r];
                }
                rubs |= w->lam[p + k] > 0.0;
            }
            /* the box in the primitive's coordinates: centre A x_c + b, half-widths |A| h */
            double zlo[3], zhi[3], big = 0.0;
            for (int r = 0; r < 3; ++r) {
                double zc = b[r], zh = 0.0;
                if (ident) {
                    zc = 0.5 * (lo[r] + hi[r]), zh = 0.5 * (hi[r] - lo[r]);
                } else {
                    for (int k = 0; k < 3; ++k) {
                        zc += A[3 * r + k] * 0.5 * (lo[k] + hi[k]);
                        zh += fabs(A[3 * r + k]) * 0.5 * (hi[k] - lo[k]);
                    }
                }
                zlo[r] = ident ? lo[r] : zc - zh, zhi[r] = ident ? hi[r] : zc + zh;
                big += fabs(zc) + zh;
            }
            /* (a relative margin over the round-off of the bound against the exact gap's) */
            const double below = gap_below(prim, zlo, zhi) - set->radius[i] - 1e-12 * big;
            w->lb[entry] = below;
            w->cand[entry] = rubs || !(below >= set->shat * (1.0 + 1e-6));
            ncand += w->cand[entry];
        }
    }
    return ncand;
}

void contact_limit_candidates(contact_work *w, const bk_system *s, const double *dx)
{
    const bk_model *m = s->m;
    /* an element beyond the reach stays out of the limiter when no point of it moves 0.9 of its distance's
     * lower bound (the map of a primitive off a body turns: |dz| = |dx|); a body's every element is visited */
    for (int c = 0, entry = 0, p = 0; c < w->cm->nset; ++c) {
        const bk_contact_set *set = &w->cm->sets[c];
        const int body = w->cm->prims[set->prim].body >= 0;
        for (int i = 0; i < set->nelem; ++i, ++entry, p += set->nsample) {
            if (w->cand[entry])
                continue;
            if (body) {
                w->cand[entry] = 1;
                continue;
            }
            const int e = set->elems[i], *dofs = m->elems[e].dofs;
            const bk_element *et = bk_elem_type(m, e);
            double move = 0.0;
            for (int k = 0; k < set->nsample; ++k) {
                const double *N = w->Nc + w->Noff[p + k];
                double dv[3] = {0.0, 0.0, 0.0};
                for (int a = 0; a < et->nshape; ++a)
                    for (int r = 0; r < 3; ++r) {
                        const int eq = s->eq[dofs[et->shape_dof[a] + r]];
                        dv[r] += eq >= 0 ? N[a] * dx[eq] : 0.0;
                    }
                move = fmax(move, sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2]));
            }
            w->cand[entry] = !(move * (1.0 + 1e-6) <= 0.9 * w->lb[entry]);
        }
    }
}

int bk_contact_broad_phase(const bk_system *s, const double *q, const bk_path *path)
{
    for (int k = 0; k < s->ninter; ++k)
        if (s->inter[k].ops == &bk_contact_ops) {
            contact_work *w = s->inter[k].self;
            contact_set_placement(w, s->m, path->x);
            return contact_broad(w, s, q);
        }
    return -1;
}
