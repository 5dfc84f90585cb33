/* beam_contact_limit.c -- the step limiter of beam contact (beam_contact.h):
 * no correction moves a sample point more than M/4 (the broad phase's
 * margin), and every candidate pair of segments keeps more than a tenth of
 * its distance; candidates whose elements are too far apart for the
 * correction to matter are left out by their boxes (bc_each_near_pair). */
#include <math.h>

#include "assembly/beam_contact_impl.h"
#include "assembly/system.h"

typedef struct limiter {
    const bc_work *w;
    double alpha;
} limiter;

static double norm3(const double *x)
{
    return sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
}

/* The distance of two segments is a minimum over their points of |P - Q|,
 * and P - Q moves by a function bilinear in the two segments' parameters:
 * so along a correction the distance changes at most by the largest
 * relative motion L of an end of one and an end of the other (a common
 * motion does not count).  A fraction alpha keeps the pair at a tenth of its
 * distance s0 or more when alpha L <= 0.9 s0; beyond that (a pair sliding
 * along the other moves far without approaching) the distance at the end of
 * the step is computed, the fraction halved until it keeps a tenth, and
 * alpha L held below twice the sum of the radii, so that no step takes a
 * centreline through the other and out beyond it (that needs a relative
 * motion of twice the radii at least). */
static void limit_pair(void *ctx, seg_pair *sp)
{
    limiter *l = ctx;
    const double *D = l->w->D;
    double L = 0.0;
    for (int a = 0; a < 2; ++a)
        for (int b = 2; b < 4; ++b) {
            const double *da = D + 3 * sp->pidx[a], *db = D + 3 * sp->pidx[b];
            const double r[3] = {da[0] - db[0], da[1] - db[1], da[2] - db[2]};
            L = fmax(L, norm3(r));
        }
    if (!(L > 0.0) || L * l->alpha <= 0.9 * sp->dist)
        return;
    const double safe = sp->dist > 0.0 ? 0.9 * sp->dist / L : 0.0, radii = sp->d - sp->dist;
    double alpha = fmin(l->alpha, 2.0 * radii / L);
    while (alpha > safe) {
        double x[4][3], sg, tau;
        const double *pts[4] = {x[0], x[1], x[2], x[3]};
        for (int a = 0; a < 4; ++a)
            for (int r = 0; r < 3; ++r)
                x[a][r] = sp->pts[a][r] + alpha * D[3 * sp->pidx[a] + r];
        if (bc_closest(pts, &sg, &tau) - radii >= 0.1 * sp->dist)
            break;
        alpha *= 0.5;
    }
    l->alpha = fmax(alpha, safe);
}

/* The largest motion |D| of a sample point of entry i of set c. */
static double largest_motion(const bc_work *w, int c, int i)
{
    const int ns = w->bm->sets[c].nsample;
    const double *D = w->D + 3 * (size_t)(w->base[c] + i * ns);
    double m2 = 0.0;
    for (int k = 0; k < ns; ++k) {
        const double d2 = D[3 * k] * D[3 * k] + D[3 * k + 1] * D[3 * k + 1] + D[3 * k + 2] * D[3 * k + 2];
        m2 = d2 > m2 ? d2 : m2;
    }
    return sqrt(m2);
}

/* A candidate whose pairs all keep a tenth of their distance at the present
 * fraction: the relative motion of two ends is at most the sum of the
 * elements' largest motions, a distance at least the boxes' gap less the
 * radii (limit_pair would leave the fraction). */
static int still_candidate(void *ctx, const seg_pair *sp, double gap)
{
    const limiter *l = ctx;
    const bk_beam_contact_set *set = &l->w->bm->sets[sp->c];
    const double s0 = gap - set->radius[sp->i] - set->radius[sp->j];
    const double L = largest_motion(l->w, sp->c, sp->i) + largest_motion(l->w, sp->c, sp->j);
    return s0 > 0.0 && L * l->alpha * (1.0 + 1e-9) <= 0.9 * s0;
}

double bc_step_limit(void *self, const bk_system *s, const double *q, const double *dx)
{
    bc_work *w = self;
    const bk_beam_contact_model *bm = w->bm;
    bc_points(w, s, q, 0, w->X);
    bc_points(w, s, dx, 1, w->D);
    limiter l = {.w = w, .alpha = 1.0};
    for (int c = 0; c < bm->nset; ++c)
        for (int p = w->base[c]; p < w->base[c] + bm->sets[c].nelem * bm->sets[c].nsample; ++p) {
            const double move = norm3(w->D + 3 * p);
            if (move * l.alpha > 0.25 * w->margin[c])
                l.alpha = 0.25 * w->margin[c] / move;
        }
    /* again until no pair lowers it: each pair then holds at the final fraction */
    for (int round = 0; round < 20; ++round) {
        const double before = l.alpha;
        bc_each_near_pair(w, s->m, limit_pair, NULL, still_candidate, &l);
        if (l.alpha == before)
            break;
    }
    return l.alpha;
}

