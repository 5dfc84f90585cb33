/* beam_contact_friction.c -- Coulomb friction between beams, lagged over a
 * step as for rigid primitives (model/contact.h): per pair of segments in
 * contact at the last accepted state, its normal force lam, unit normal n,
 * the parameters sg, tau of its closest points and the anchor, their relative
 * position where the slip is measured from.  The slip is
 * u_t = (I - n n^T) (P(sg) - Q(tau) - anchor), P and Q linear in the segments'
 * ends at the lagged parameters, and the friction energy mu lam f0(|u_t|),
 * f0' = f1 the smoothed slip function of out/kernels/contact.h: Coulomb's
 * mu lam beyond the slip tolerance, a stiff spring below it; mu passes from
 * the static mu_s to the kinetic mu_k between a slip of eps and 2 eps
 * (bk_contact_transition), so a pair sliding 2 eps or more a step rubs with
 * mu_k and one that stops holds with mu_s.  A pair that
 * sticks keeps its anchor and parameters (no creep under a load below the
 * limit); one that slid, or came into contact, takes the present ones. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/beam_contact_impl.h"
#include "contact.h"

static int cmp_key(const void *a, const void *b)
{
    const int *x = a, *y = b;
    for (int k = 0; k < 5; ++k)
        if (x[k] != y[k])
            return (x[k] > y[k]) - (x[k] < y[k]);
    return 0;
}

static void key_of(const seg_pair *sp, int *key)
{
    key[0] = sp->c, key[1] = sp->i, key[2] = sp->k, key[3] = sp->j, key[4] = sp->l;
}

const bc_lag *bc_lag_find(const bc_work *w, const seg_pair *sp)
{
    int key[5];
    key_of(sp, key);
    return w->nlag > 0 ? bsearch(key, w->lag, (size_t)w->nlag, sizeof *w->lag, cmp_key) : NULL;
}

int bc_lag_any(const bc_work *w, int c, int i, int j)
{
    int lo = 0, hi = w->nlag;                /* the first key (c, i, ...) or beyond: keys sort by set, i first */
    while (lo < hi) {
        const int mid = lo + (hi - lo) / 2;
        const int *k = w->lag[mid].key;
        if (k[0] < c || (k[0] == c && k[1] < i))
            lo = mid + 1;
        else
            hi = mid;
    }
    for (; lo < w->nlag && w->lag[lo].key[0] == c && w->lag[lo].key[1] == i; ++lo)
        if (w->lag[lo].key[3] == j)
            return 1;
    return 0;
}

/* The weights of the pair's four ends in P(sg) - Q(tau). */
static void weights(double sg, double tau, double *c)
{
    c[0] = 1.0 - sg, c[1] = sg, c[2] = -(1.0 - tau), c[3] = -tau;
}

/* The slip u_t of the pair since its anchor (y = |u_t|). */
double bc_slip(const bc_lag *lg, const seg_pair *sp, double *ut)
{
    double c[4], u[3] = {0.0, 0.0, 0.0};
    weights(lg->sg, lg->tau, c);
    for (int a = 0; a < 4; ++a)
        for (int r = 0; r < 3; ++r)
            u[r] += c[a] * sp->pts[a][r];
    for (int r = 0; r < 3; ++r)
        u[r] -= lg->anchor[r];
    const double un = u[0] * lg->n[0] + u[1] * lg->n[1] + u[2] * lg->n[2];
    for (int r = 0; r < 3; ++r)
        ut[r] = u[r] - un * lg->n[r];
    return sqrt(ut[0] * ut[0] + ut[1] * ut[1] + ut[2] * ut[2]);
}

void bc_friction(const bk_beam_contact_set *set, const bc_lag *lg, const seg_pair *sp, double *g, double *H)
{
    double ut[3], f[4], h[2], c[4];
    const double y = bc_slip(lg, sp, ut), k = lg->lam;
    bk_contact_friction(y, set->slip, f);
    bk_contact_transition(y, set->slip, h);
    /* phi(y) = mu(y) f1(y) / y, mu(y) = mu_s - (mu_s - mu_k) h(y): the static coefficient up to a slip of eps,
     * the kinetic one from 2 eps */
    const double mu = set->mu - (set->mu - set->mu_k) * h[0], dmu = -(set->mu - set->mu_k) * h[1];
    const double py = mu * f[2], dpy = dmu * f[2] + mu * f[3];
    weights(lg->sg, lg->tau, c);
    /* d/du: k phi u_t; d2/du2: k (phi (I - n n^T) + phi'/y u_t u_t^T); u = sum c_a x_a */
    for (int a = 0; a < 4; ++a)
        for (int r = 0; r < 3; ++r) {
            g[3 * a + r] += c[a] * k * py * ut[r];
            if (!H)
                continue;
            for (int b = 0; b < 4; ++b)
                for (int s = 0; s < 3; ++s)
                    H[12 * (3 * a + r) + 3 * b + s] +=
                        c[a] * c[b] * k * (py * ((r == s) - lg->n[r] * lg->n[s]) +
                                           (y > 0.0 ? dpy / y * ut[r] * ut[s] : 0.0));
        }
}

/* accept: the lagged state of every pair within the barrier's reach now. */
typedef struct lagger {
    bc_work *w;
    const bk_model *m;
    bc_lag *next;
    int n, cap, bad;
} lagger;

static void lag_pair(void *ctx, seg_pair *sp)
{
    lagger *l = ctx;
    const bk_beam_contact_set *set = &l->w->bm->sets[sp->c];
    if (!(set->mu > 0.0) || !(sp->dist > 0.0) || sp->dist >= set->shat)
        return;
    double g[12], fa[3];
    bc_pair_energy(sp, set->radius[sp->i] + set->radius[sp->j], set->shat, sp->hi, sp->hj, g, NULL);
    for (int r = 0; r < 3; ++r)
        fa[r] = -set->kappa * (g[r] + g[3 + r]);        /* the barrier's force on the first segment */
    const double lam = sqrt(fa[0] * fa[0] + fa[1] * fa[1] + fa[2] * fa[2]);
    if (!(lam > 0.0))
        return;
    if (l->n + 1 > l->cap) {
        int cap = 2 * l->cap + 64;
        bc_lag *p = realloc(l->next, (size_t)cap * sizeof *p);
        if (!p) {
            l->bad = 1;
            return;
        }
        l->next = p, l->cap = cap;
    }
    bc_lag *lg = &l->next[l->n++];
    const bc_lag *old = bc_lag_find(l->w, sp);
    double ut[3];
    if (old && bc_slip(old, sp, ut) < set->slip) {
        *lg = *old;                                      /* sticks: the same material points, the same anchor */
    } else {
        key_of(sp, lg->key);
        lg->sg = sp->sg, lg->tau = sp->tau;
        double c[4];
        weights(lg->sg, lg->tau, c);
        for (int r = 0; r < 3; ++r) {
            lg->anchor[r] = 0.0;
            for (int a = 0; a < 4; ++a)
                lg->anchor[r] += c[a] * sp->pts[a][r];
        }
    }
    lg->lam = lam;
    for (int r = 0; r < 3; ++r)
        lg->n[r] = fa[r] / lam;
}

/* A candidate beyond the barrier's reach (its elements' boxes, less the
 * radii) has no pair to lag. */
static int far_candidate(void *ctx, const seg_pair *sp, double gap)
{
    const bk_beam_contact_set *set = &((const lagger *)ctx)->w->bm->sets[sp->c];
    return gap - set->radius[sp->i] - set->radius[sp->j] >= set->shat * (1.0 + 1e-6);
}

void bc_accept(void *self, const bk_system *s, const double *q, const bk_path *p)
{
    (void)p;
    bc_work *w = self;
    bc_points(w, s, q, 0, w->X);
    lagger l = {.w = w, .m = s->m};
    bc_each_near_pair(w, s->m, lag_pair, NULL, far_candidate, &l);
    if (l.bad) {                                         /* out of memory: no friction from this state on */
        free(l.next);
        l.next = NULL, l.n = 0;
    }
    if (l.n > 1)
        qsort(l.next, (size_t)l.n, sizeof *l.next, cmp_key);
    free(w->lag);
    w->lag = l.next, w->nlag = l.n;
}
