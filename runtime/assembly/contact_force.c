/* contact_force.c -- the contact interaction: barrier forces between the sample
 * points of beams' centrelines and rigid primitives, their Jacobian, the step
 * limiter (see contact_force.h). */
#include "assembly/contact_force.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/system.h"
#include "model/amplitude.h"
#include "base/csvrow.h"
#include "base/tables.h"
#include "contact.h"

/* Scratch of the interaction: one element's force and matrix. */
typedef struct contact_work {
    double *fe, *Ke;                 /* [maxdof], [maxdof^2] */
    FILE *table;                     /* contacts.csv (registered in the run's tables), or NULL */
    int npoint;                      /* sample points of every set */
    double *lam, *nrm, *xprev;       /* [npoint], [3 npoint] x 2: the lagged normal force, normal, position */
    double *shift;                   /* [3 nprim] each primitive's translation at the path point last assembled */
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
        const bk_contact_model *cm = s->m->contact;
        for (int c = 0; c < cm->nset; ++c)
            w->npoint += cm->sets[c].nelem * cm->sets[c].nsample;
        size_t np = (size_t)(w->npoint > 0 ? w->npoint : 1);
        w->fe = malloc(md * sizeof *w->fe);
        w->Ke = malloc(md * md * sizeof *w->Ke);
        w->lam = calloc(np, sizeof *w->lam);
        w->nrm = calloc(3 * np, sizeof *w->nrm);
        w->xprev = calloc(3 * np, sizeof *w->xprev);
        w->shift = calloc(3 * (size_t)(cm->nprim > 0 ? cm->nprim : 1), sizeof *w->shift);
    }
    *self = w;
    return w && w->fe && w->Ke && w->lam && w->nrm && w->xprev && w->shift ? 0 : -1;
}

static void contact_free(void *self)
{
    contact_work *w = self;
    if (w) {
        free(w->fe);
        free(w->Ke);
        free(w->lam);
        free(w->nrm);
        free(w->xprev);
        free(w->shift);
    }
    free(w);
}

/* The distance function of primitive p translated by d[3] at x: out[0] = g,
 * out[1..3] its gradient, out[4..12] its Hessian (the gap kernels of
 * out/kernels/contact.h; a capsule's ends are spheres). */
static void gap(const bk_contact_prim *p, const double *d, const double *x, double *out)
{
    double prm[BK_CONTACT_MAXPRM];
    memcpy(prm, p->prm, sizeof prm);
    switch (p->shape) {
    case BK_CONTACT_HALF_SPACE:
        prm[3] += prm[0] * d[0] + prm[1] * d[1] + prm[2] * d[2];
        bk_contact_gap_half_space(x, prm, out);
        return;
    case BK_CONTACT_SPHERE:
        for (int i = 0; i < 3; ++i)
            prm[i] += d[i];
        bk_contact_gap_sphere(x, prm, out);
        return;
    default: {
        for (int i = 0; i < 3; ++i)
            prm[i] += d[i], prm[3 + i] += d[i];
        double seg[14];
        bk_contact_gap_segment(x, prm, seg);
        if (seg[13] > 0.0 && seg[13] < 1.0) {
            memcpy(out, seg, 13 * sizeof *out);
            return;
        }
        const double *end = seg[13] <= 0.0 ? prm : prm + 3;
        const double sph[4] = {end[0], end[1], end[2], prm[6]};
        bk_contact_gap_sphere(x, sph, out);
    }
    }
}

/* Each primitive's translation at the path point (the amplitude's variable x). */
static void set_shift(contact_work *w, const bk_model *m, double x)
{
    const bk_contact_model *cm = m->contact;
    for (int i = 0; i < cm->nprim; ++i) {
        const bk_contact_prim *p = &cm->prims[i];
        const double f = p->motion[0] != 0.0 || p->motion[1] != 0.0 || p->motion[2] != 0.0
                             ? bk_load_factor(m, p->amp, x) : 0.0;
        for (int k = 0; k < 3; ++k)
            w->shift[3 * i + k] = f * p->motion[k];
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

/* Force fp[3] (internal sign: what fint gains) and stiffness Kp[9] = dfp/dx of
 * sample point p at x: the barrier's and, with friction, the lagged friction's. */
static void point_terms(const contact_work *w, const bk_contact_set *set, int p, double wl, const double *x,
                        const double *g, double dist, double *fp, double *Kp)
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

/* A sample point as the visitor sees it (each_point). */
typedef struct point {
    const bk_contact_set *set;
    int c, i, e, k, p;               /* set, member of the set, element, sample, index over every set */
    const bk_element *et;
    double wl;                       /* kappa times the point's share of the element's length */
    double N[BK_MAX_SHAPE], x[3];    /* shape functions, position */
    double g[13], dist;              /* the primitive's gap with derivatives; the section's distance */
} point;

/* Calls fn(ctx, pt) for every sample point of every set at q (sets, their
 * elements, their samples, in order), and, when not NULL, element(ctx, pt,
 * 0) before an element's first point and element(ctx, pt, 1) after its last. */
static void each_point(const contact_work *w, const bk_system *s, const double *q, void (*fn)(void *, point *),
                       void (*element)(void *, point *, int), void *ctx)
{
    const bk_model *m = s->m;
    const bk_contact_model *cm = m->contact;
    double qe[BK_MAX_ELEMENT_DOF];
    point pt;
    pt.p = 0;
    for (pt.c = 0; pt.c < cm->nset; ++pt.c) {
        pt.set = &cm->sets[pt.c];
        const bk_contact_prim *prim = &cm->prims[pt.set->prim];
        for (pt.i = 0; pt.i < pt.set->nelem; ++pt.i) {
            pt.e = pt.set->elems[pt.i];
            pt.et = bk_elem_type(m, pt.e);
            const double kl = m->geoms[m->elems[pt.e].geom][BK_GEOM_L] * pt.set->kappa;
            bk_gather(m, pt.e, q, qe);
            if (element)
                element(ctx, &pt, 0);
            for (pt.k = 0; pt.k < pt.set->nsample; ++pt.k, ++pt.p) {
                pt.wl = kl * sample(m, pt.e, qe, pt.k, pt.set->nsample, pt.N, pt.x);
                gap(prim, w->shift + 3 * pt.set->prim, pt.x, pt.g);
                pt.dist = pt.g[0] - pt.set->radius[pt.i];
                fn(ctx, &pt);
            }
            if (element)
                element(ctx, &pt, 1);
        }
    }
}

/* Whether point pt feels the contact: within the barrier's reach, or rubbing. */
static int acts(const contact_work *w, const point *pt)
{
    return pt->dist < pt->set->shat || (pt->set->mu > 0.0 && w->lam[pt->p] > 0.0);
}

/* ---- assemble: the element's force and matrix, scattered after its points ---- */

typedef struct assembly {
    contact_work *w;
    bk_system *s;
    double *fint, *Ax;
    int touched, bad;
} assembly;

static void assemble_element(void *ctx, point *pt, int end)
{
    assembly *a = ctx;
    if (!end) {
        a->touched = 0;
        return;
    }
    if (!a->touched)
        return;
    a->bad |= bk_scatter(a->s->m, pt->e, a->w->fe, 1.0, a->fint);
    if (a->Ax)
        bk_scatter_matrix(a->s, pt->e, a->w->Ke, 1.0, a->Ax);
}

static void assemble_point(void *ctx, point *pt)
{
    assembly *a = ctx;
    contact_work *w = a->w;
    const bk_element *et = pt->et;
    const int nd = et->ndof;
    double fp[3], Kp[9];
    if (!(pt->dist > 0.0)) {
        a->bad = 1;                          /* through the surface: not an admissible state */
        return;
    }
    if (!acts(w, pt))
        return;
    point_terms(w, pt->set, pt->p, pt->wl, pt->x, pt->g, pt->dist, fp, Kp);
    if (!a->touched) {
        memset(w->fe, 0, (size_t)nd * sizeof *w->fe);
        if (a->Ax)
            memset(w->Ke, 0, (size_t)nd * (size_t)nd * sizeof *w->Ke);
        a->touched = 1;
    }
    for (int i = 0; i < et->nshape; ++i)     /* x = sum N_i r_i: fe += N^T fp, Ke += N^T Kp N */
        for (int r = 0; r < 3; ++r) {
            const int row = et->shape_dof[i] + r;
            w->fe[row] += pt->N[i] * fp[r];
            if (!a->Ax)
                continue;
            for (int j = 0; j < et->nshape; ++j)
                for (int c = 0; c < 3; ++c)
                    w->Ke[row * nd + et->shape_dof[j] + c] += pt->N[i] * pt->N[j] * Kp[3 * r + c];
        }
}

static int contact_assemble(void *self, bk_system *s, const double *q, const bk_path *path, double *fint,
                            double *Ax)
{
    contact_work *w = self;
    set_shift(w, s->m, path->x);
    assembly a = {.w = w, .s = s, .fint = fint, .Ax = Ax};
    each_point(w, s, q, assemble_point, assemble_element, &a);
    return a.bad ? -1 : 0;
}

/* ---- accept: the lagged friction state ---- */

/* The lagged friction state of a sample point from the accepted state: its
 * barrier force's magnitude and its unit normal; its anchor, the point its
 * slip is measured from: a sticking point (slip since the anchor below the
 * tolerance eps) keeps it, so that a load below the friction limit holds it
 * within eps however many steps it acts (no creep); a sliding one drags it to
 * eps behind itself along the slip (the friction spring stays at its limit,
 * as in elastic-plastic friction: a step that goes on sliding by eps rubs
 * with the kinetic coefficient, one that stops holds with the static); a
 * point that was not in contact puts it where it is. */
static void accept_point(void *ctx, point *pt)
{
    contact_work *w = ctx;
    const int p = pt->p;
    double *xa = w->xprev + 3 * p, *n = w->nrm + 3 * p, u[3], un = 0.0, ut2 = 0.0, b[3];
    for (int r = 0; r < 3; ++r)
        u[r] = pt->x[r] - xa[r], un += u[r] * n[r];
    for (int r = 0; r < 3; ++r)
        ut2 += (u[r] - un * n[r]) * (u[r] - un * n[r]);
    const double y = sqrt(ut2), eps = pt->set->slip;
    const int rubbed = w->lam[p] > 0.0;
    w->lam[p] = 0.0;
    if (pt->dist > 0.0 && pt->dist < pt->set->shat) {
        bk_contact_barrier(pt->dist, pt->set->shat, b);
        w->lam[p] = -pt->wl * b[1];
    }
    for (int r = 0; r < 3; ++r)
        if (!rubbed || y >= eps)
            xa[r] = pt->x[r];
    for (int r = 0; r < 3; ++r)
        n[r] = pt->g[1 + r];
}

static void contact_accept(void *self, const bk_system *s, const double *q, const bk_path *path)
{
    contact_work *w = self;
    set_shift(w, s->m, path->x);
    each_point(w, s, q, accept_point, NULL, w);
}

/* ---- step limit: every sample point keeps a tenth of its distance ---- */

typedef struct limiter {
    const bk_system *s;
    const double *dx;
    double de[BK_MAX_ELEMENT_DOF];   /* the correction on the element's DOFs */
    double alpha;
} limiter;

static void limit_element(void *ctx, point *pt, int end)
{
    limiter *l = ctx;
    const int *dofs = l->s->m->elems[pt->e].dofs;
    if (end)
        return;
    for (int k = 0; k < pt->et->ndof; ++k)
        l->de[k] = l->s->eq[dofs[k]] >= 0 ? l->dx[l->s->eq[dofs[k]]] : 0.0;
}

/* |grad g| = 1, so the distance moves by at most the point's motion. */
static void limit_point(void *ctx, point *pt)
{
    limiter *l = ctx;
    double dp[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < pt->et->nshape; ++i)
        for (int r = 0; r < 3; ++r)
            dp[r] += pt->N[i] * l->de[pt->et->shape_dof[i] + r];
    const double move = sqrt(dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2]);
    if (move > 0.0 && move * l->alpha > 0.9 * pt->dist)
        l->alpha = pt->dist > 0.0 ? 0.9 * pt->dist / move : 0.0;
}

/* The fraction of dx[neq] that keeps every sample point at more than a tenth
 * of its distance (the primitives where the last residual had them: this
 * iterate's path point). */
static double contact_step_limit(void *self, const bk_system *s, const double *q, const double *dx)
{
    limiter l = {.s = s, .dx = dx, .alpha = 1.0};
    each_point(self, s, q, limit_point, limit_element, &l);
    return l.alpha;
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
 * position, distance, the normal force, the tangential force, the friction
 * state (none, stick: slip since the last step below the tolerance, slip) and
 * the force on the beam there (N). */
static int contact_tables(void *self, const bk_system *s, bk_tables *ts, const char *dir, FILE *err)
{
    (void)s;
    contact_work *w = self;
    w->table = bk_tables_open(ts, dir, "contacts.csv", "step,time,set,primitive,element,point,x,y,z,distance,"
                              "normal_force,tangential_force,state,fx,fy,fz\n", 1, err);
    return w->table ? 0 : -1;
}

typedef struct rows {
    contact_work *w;
    int step;
    double t;
    bk_rowqueue *rq;
} rows;

static void row_point(void *ctx, point *pt)
{
    rows *rw = ctx;
    contact_work *w = rw->w;
    const bk_contact_set *set = pt->set;
    const double *g = pt->g;
    double b[3], fp[3], Kp[9];
    const int rubs = set->mu > 0.0 && w->lam[pt->p] > 0.0;
    if (!(pt->dist > 0.0) || !acts(w, pt))
        return;
    double fn = 0.0;
    if (pt->dist < set->shat) {
        bk_contact_barrier(pt->dist, set->shat, b);
        fn = -pt->wl * b[1];
    }
    point_terms(w, set, pt->p, pt->wl, pt->x, g, pt->dist, fp, Kp);
    const double fg = -(fp[0] * g[1] + fp[1] * g[2] + fp[2] * g[3]);
    double ft2 = 0.0, slip2 = 0.0;
    for (int r = 0; r < 3; ++r) {
        const double tr = -fp[r] - fg * g[1 + r], u = pt->x[r] - w->xprev[3 * pt->p + r];
        ft2 += tr * tr;
        slip2 += u * u;
    }
    bk_row r;
    bk_row_begin(&r, w->table, rw->rq);
    bk_row_int(&r, rw->step);
    bk_row_num(&r, rw->t);
    bk_row_int(&r, pt->c);
    bk_row_int(&r, set->prim);
    bk_row_int(&r, pt->e);
    bk_row_int(&r, pt->k);
    for (int d = 0; d < 3; ++d)
        bk_row_num(&r, pt->x[d]);
    bk_row_num(&r, pt->dist);
    bk_row_num(&r, fn);
    bk_row_num(&r, sqrt(ft2));
    bk_row_str(&r, !rubs ? "none" : sqrt(slip2) < set->slip ? "stick" : "slip");
    for (int d = 0; d < 3; ++d)
        bk_row_num(&r, -fp[d]);
    bk_row_end(&r);
}

static void contact_rows(void *self, const bk_system *s, int step, double t, const double *q, bk_rowqueue *rq)
{
    contact_work *w = self;
    rows rw = {.w = w, .step = step, .t = t, .rq = rq};
    if (w->table)
        each_point(w, s, q, row_point, NULL, &rw);
}

const bk_interaction_ops bk_contact_ops = {.name = "contact", .assemble = contact_assemble,
                                           .step_limit = contact_step_limit, .accept = contact_accept,
                                           .tables = contact_tables, .rows = contact_rows, .summary_key = "contact",
                                           .summary = contact_summary, .free = contact_free};

/* ---- the state for the outputs and the tests ---- */

typedef struct state {
    const contact_work *w;
    double *F, *min_distance;
    int *nactive;
} state;

static void state_point(void *ctx, point *pt)
{
    state *st = ctx;
    double fp[3], Kp[9];
    *st->min_distance = fmin(*st->min_distance, pt->dist);
    if (!(pt->dist > 0.0) || !acts(st->w, pt))
        return;
    point_terms(st->w, pt->set, pt->p, pt->wl, pt->x, pt->g, pt->dist, fp, Kp);
    for (int r = 0; r < 3; ++r)
        st->F[3 * pt->c + r] -= fp[r];       /* the force on the beam */
    if (st->nactive && pt->dist < pt->set->shat)
        st->nactive[pt->c]++;
}

void bk_contact_state(const bk_system *s, const double *q, double *F, int *nactive, double *min_distance)
{
    const bk_contact_model *cm = s->m->contact;
    const contact_work *w = NULL;
    for (int k = 0; k < s->ninter; ++k)
        if (s->inter[k].ops == &bk_contact_ops)
            w = s->inter[k].self;
    *min_distance = INFINITY;
    for (int c = 0; cm && c < cm->nset; ++c) {
        F[3 * c] = F[3 * c + 1] = F[3 * c + 2] = 0.0;
        if (nactive)
            nactive[c] = 0;
    }
    state st = {.w = w, .F = F, .min_distance = min_distance, .nactive = nactive};
    if (w)
        each_point(w, s, q, state_point, NULL, &st);
}
