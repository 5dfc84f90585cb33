/* beam_contact.c -- the beam-to-beam contact interaction: barrier forces
 * between segments of the beams' sampled centrelines, their Jacobian, the
 * broad phase that keeps the pattern's coupling blocks ahead of the
 * contacts, the step limiter, its rows of contacts.csv and summary.json
 * "beam_contact" (see beam_contact.h). */
#include "assembly/beam_contact.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/beam_contact_impl.h"
#include "assembly/contact_broad.h"
#include "assembly/system.h"
#include "contact.h"
#include "contact_pairs.h"

void bc_free(void *self)
{
    bc_work *w = self;
    if (!w)
        return;
    bk_point_frames_free(&w->pf);
    free(w->base), free(w->ebase), free(w->chain), free(w->N), free(w->X), free(w->Xref), free(w->D);
    free(w->margin), free(w->cand), free(w->pairs), free(w->box), free(w->lag);
    bk_beam_contact_model_free(w->own);
    free(w->gp), free(w->Hp), free(w->T), free(w->used);
    for (int k = 0; k < 2; ++k)
        free(w->fe[k]);
    for (int k = 0; k < 4; ++k)
        free(w->Kb[k]);
    free(w);
}

static double elem_len(const bk_model *m, int e)
{
    return m->geoms[m->elems[e].geom][BK_GEOM_L];
}

/* Point p's motion (or position) from DOF-indexed values v: sum N_a v_a. */
static void point_of(const bk_model *m, const bc_work *w, int e, int p, const double *ve, double *x)
{
    const bk_element *et = bk_elem_type(m, e);
    const double *N = w->N + (size_t)p * w->nsh;
    x[0] = x[1] = x[2] = 0.0;
    for (int a = 0; a < et->nshape; ++a)
        for (int r = 0; r < 3; ++r)
            x[r] += N[a] * ve[et->shape_dof[a] + r];
}

void bc_points(bc_work *w, const bk_system *s, const double *v, int on_eq, double *X)
{
    const bk_model *m = s->m;
    const bk_beam_contact_model *bm = w->bm;
    double ve[BK_MAX_ELEMENT_DOF];
    for (int c = 0; c < bm->nset; ++c) {
        const bk_beam_contact_set *set = &bm->sets[c];
        for (int i = 0; i < set->nelem; ++i) {
            const int e = set->elems[i];
            const int *dofs = m->elems[e].dofs;
            for (int k = 0; k < bk_elem_type(m, e)->ndof; ++k)
                ve[k] = !on_eq ? v[dofs[k]] : s->eq[dofs[k]] >= 0 ? v[s->eq[dofs[k]]] : 0.0;
            for (int k = 0; k < set->nsample; ++k) {
                const int p = w->base[c] + i * set->nsample + k;
                point_of(m, w, e, p, ve, X + 3 * p);
            }
        }
    }
}

/* The arc length between segment k of entry i and segment l of entry j of
 * one beam (0 for adjacent or overlapping segments). */
static double arc_gap(const bk_model *m, const bk_beam_contact_set *set, int i, int k, int j, int l)
{
    const int ns1 = set->nsample - 1;
    const double hi = elem_len(m, set->elems[i]) / ns1, hj = elem_len(m, set->elems[j]) / ns1;
    const double a0 = set->s0[i] + k * hi, a1 = a0 + hi, b0 = set->s0[j] + l * hj, b1 = b0 + hj;
    return fmax(0.0, fmax(b0 - a1, a0 - b1));
}

/* Whether segment k of entry i and segment l of entry j of set c may touch:
 * different beams, or one beam with self-contact and more than `exclude` of
 * arc length between them (adjacent segments never). */
static int allowed(const bc_work *w, const bk_model *m, int c, int i, int k, int j, int l)
{
    const bk_beam_contact_set *set = &w->bm->sets[c];
    if (w->chain[w->ebase[c] + i] != w->chain[w->ebase[c] + j])
        return 1;
    return set->self && arc_gap(m, set, i, k, j, l) > set->exclude;
}

/* The broad phase over every set at the positions X: the candidate element
 * pairs, and their coupling blocks in the pattern.  0, or -1 out of memory. */
static int broad_phase(bc_work *w, bk_system *s)
{
    const bk_model *m = s->m;
    const bk_beam_contact_model *bm = w->bm;
    w->ncand = 0;
    for (int c = 0; c < bm->nset; ++c) {
        const bk_beam_contact_set *set = &bm->sets[c];
        const int ns = set->nsample, last = ns - 2;
        for (int i = 0; i < set->nelem; ++i) {
            bk_box *b = &w->box[i];
            const double grow = set->radius[i] + 0.5 * set->shat + 0.5 * w->margin[c];
            for (int d = 0; d < 3; ++d)
                b->lo[d] = INFINITY, b->hi[d] = -INFINITY;
            for (int k = 0; k < ns; ++k)
                for (int d = 0; d < 3; ++d) {
                    const double x = w->X[3 * (w->base[c] + i * ns + k) + d];
                    b->lo[d] = fmin(b->lo[d], x - grow);
                    b->hi[d] = fmax(b->hi[d], x + grow);
                }
        }
        int np = bk_broad_pairs(w->box, set->nelem, &w->pairs, &w->cappair);
        if (np < 0)
            return -1;
        /* the overlapping pairs, then each element with itself (its far segments) */
        for (int k = 0; k < np + set->nelem; ++k) {
            const int i = k < np ? w->pairs[2 * k] : k - np, j = k < np ? w->pairs[2 * k + 1] : k - np;
            if (!allowed(w, m, c, i, 0, j, last) && !allowed(w, m, c, i, last, j, 0))
                continue;                        /* not even their farthest segments may touch */
            if (w->ncand + 1 > w->capcand) {
                int cap = 2 * w->capcand + 64, *p = realloc(w->cand, 3 * (size_t)cap * sizeof *p);
                if (!p)
                    return -1;
                w->cand = p, w->capcand = cap;
            }
            w->cand[3 * w->ncand] = c, w->cand[3 * w->ncand + 1] = i, w->cand[3 * w->ncand + 2] = j;
            w->ncand++;
        }
    }
    memcpy(w->Xref, w->X, 3 * (size_t)w->npt * sizeof *w->X);
    w->have_ref = 1;
    /* their coupling blocks (the element pairs, into the pairs' scratch) */
    if (w->ncand > w->cappair) {
        int *p = realloc(w->pairs, 2 * (size_t)w->ncand * sizeof *p);
        if (!p)
            return -1;
        w->pairs = p, w->cappair = w->ncand;
    }
    for (int k = 0; k < w->ncand; ++k) {
        const bk_beam_contact_set *set = &bm->sets[w->cand[3 * k]];
        w->pairs[2 * k] = set->elems[w->cand[3 * k + 1]];
        w->pairs[2 * k + 1] = set->elems[w->cand[3 * k + 2]];
    }
    return bk_system_couple(s, w->ncand, w->pairs) < 0 ? -1 : 0;
}

int bc_prepare(void *self, bk_system *s, const double *q)
{
    bc_work *w = self;
    const bk_beam_contact_model *bm = w->bm;
    bc_points(w, s, q, 0, w->X);
    int again = !w->have_ref;
    for (int c = 0; c < bm->nset && !again; ++c) {
        const int n = bm->sets[c].nelem * bm->sets[c].nsample;
        for (int p = w->base[c]; p < w->base[c] + n && !again; ++p) {
            const double *x = w->X + 3 * p, *y = w->Xref + 3 * p;
            const double dx = x[0] - y[0], dy = x[1] - y[1], dz = x[2] - y[2];
            again = dx * dx + dy * dy + dz * dz > 0.0625 * w->margin[c] * w->margin[c];
        }
    }
    return again ? broad_phase(w, s) : 0;
}

int bk_beam_contact_broad_phase(bk_system *s, const double *q)
{
    for (int k = 0; k < s->ninter; ++k)
        if (s->inter[k].ops == &bk_beam_contact_ops) {
            bc_work *w = s->inter[k].self;
            bc_points(w, s, q, 0, w->X);
            return broad_phase(w, s) != 0 ? -1 : w->ncand;
        }
    return -1;
}

int bk_beam_contact_make(bk_system *s, const bk_beam_contact_model *bm, void **self)
{
    const bk_model *m = s->m;
    bc_work *w = calloc(1, sizeof *w);
    *self = w;
    if (!w)
        return -1;
    w->bm = bm;
    w->pf.stem = "beam_contacts";
    size_t md = (size_t)(s->maxdof > 0 ? s->maxdof : 1);
    int nent = 0, maxel = 1, maxns = 2;
    w->base = calloc((size_t)bm->nset, sizeof *w->base);
    w->ebase = calloc((size_t)bm->nset, sizeof *w->ebase);
    w->margin = calloc((size_t)bm->nset, sizeof *w->margin);
    if (!w->base || !w->ebase || !w->margin)
        return -1;
    for (int c = 0; c < bm->nset; ++c) {
        const bk_beam_contact_set *set = &bm->sets[c];
        w->base[c] = w->npt, w->ebase[c] = nent;
        w->npt += set->nelem * set->nsample;
        nent += set->nelem;
        maxel = set->nelem > maxel ? set->nelem : maxel;
        maxns = set->nsample > maxns ? set->nsample : maxns;
        for (int i = 0; i < set->nelem; ++i) {
            const int nsh = bk_elem_type(m, set->elems[i])->nshape;
            w->nsh = nsh > w->nsh ? nsh : w->nsh;
        }
        /* M: the longest element, twice the thickest section, ten reaches */
        double M = 10.0 * set->shat;
        for (int i = 0; i < set->nelem; ++i)
            M = fmax(M, fmax(elem_len(m, set->elems[i]), 4.0 * set->radius[i]));
        w->margin[c] = M;
    }
    size_t np = (size_t)(w->npt > 0 ? w->npt : 1);
    w->chain = calloc((size_t)nent + 1, sizeof *w->chain);
    w->N = calloc(np * (size_t)(w->nsh > 0 ? w->nsh : 1), sizeof *w->N);
    w->X = calloc(3 * np, sizeof *w->X);
    w->Xref = calloc(3 * np, sizeof *w->Xref);
    w->D = calloc(3 * np, sizeof *w->D);
    w->box = calloc((size_t)maxel, sizeof *w->box);
    for (int k = 0; k < 2; ++k)
        w->fe[k] = malloc(md * sizeof *w->fe[k]);
    for (int k = 0; k < 4; ++k)
        w->Kb[k] = malloc(md * md * sizeof *w->Kb[k]);
    const size_t n3 = 6 * (size_t)maxns;
    w->gp = malloc(n3 * sizeof *w->gp);
    w->Hp = malloc(n3 * n3 * sizeof *w->Hp);
    w->T = malloc(n3 * md * sizeof *w->T);
    w->used = malloc(n3 / 3);
    if (!w->chain || !w->N || !w->X || !w->Xref || !w->D || !w->box || !w->fe[0] || !w->fe[1] || !w->Kb[0] ||
        !w->Kb[1] || !w->Kb[2] || !w->Kb[3] || !w->gp || !w->Hp || !w->T || !w->used)
        return -1;
    for (int c = 0; c < bm->nset; ++c) {
        const bk_beam_contact_set *set = &bm->sets[c];
        for (int b = 0; b < set->nchain; ++b)
            for (int i = set->chain_off[b]; i < set->chain_off[b + 1]; ++i)
                w->chain[w->ebase[c] + i] = b;
        for (int i = 0; i < set->nelem; ++i) {
            const int e = set->elems[i];
            double Nk[BK_MAX_SHAPE];
            for (int k = 0; k < set->nsample; ++k) {
                bk_elem_type(m, e)->shape(m->geoms[m->elems[e].geom], (double)k / (set->nsample - 1), 0.0, 0.0, Nk);
                memcpy(w->N + (size_t)(w->base[c] + i * set->nsample + k) * w->nsh, Nk,
                       (size_t)bk_elem_type(m, e)->nshape * sizeof *Nk);
            }
        }
    }
    return bc_prepare(w, s, m->q0);
}

/* ---- the distance of two segments ---- */

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double clamp01(double x)
{
    return x < 0.0 ? 0.0 : x > 1.0 ? 1.0 : x;
}

double bc_closest(const double *const *pts, double *sg, double *tau)
{
    double u[3], v[3], r[3];
    for (int d = 0; d < 3; ++d)
        u[d] = pts[1][d] - pts[0][d], v[d] = pts[3][d] - pts[2][d], r[d] = pts[0][d] - pts[2][d];
    const double a = dot3(u, u), e = dot3(v, v), b = dot3(u, v), c = dot3(u, r), f = dot3(v, r);
    const double den = a * e - b * b;
    double s, t;
    if (den > PARALLEL_SIN2 * a * e) {
        s = clamp01((b * f - c * e) / den);
        t = (b * s + f) / e;
        if (t < 0.0)
            t = 0.0, s = clamp01(-c / a);
        else if (t > 1.0)
            t = 1.0, s = clamp01((b - c) / a);
    } else {
        /* parallel: the nearest of the four ends to the other segment */
        double best = INFINITY;
        s = t = 0.0;
        for (int k = 0; k < 4; ++k) {
            const double *p = pts[k], *q0 = pts[k < 2 ? 2 : 0], *q1 = pts[k < 2 ? 3 : 1];
            double ev[3], wv[3], z[3];
            for (int d = 0; d < 3; ++d)
                ev[d] = q1[d] - q0[d], wv[d] = p[d] - q0[d];
            const double h = clamp01(dot3(wv, ev) / dot3(ev, ev));
            for (int d = 0; d < 3; ++d)
                z[d] = wv[d] - h * ev[d];
            if (dot3(z, z) < best) {
                best = dot3(z, z);
                s = k < 2 ? (double)k : h;
                t = k < 2 ? h : (double)(k - 2);
            }
        }
    }
    double g[3];
    for (int d = 0; d < 3; ++d)
        g[d] = pts[0][d] + s * u[d] - pts[2][d] - t * v[d];
    *sg = s, *tau = t;
    return sqrt(dot3(g, g));
}

/* A generated kernel of n points (indices ip[n] into the pair's four):
 * its value, and its gradient and Hessian added times c into the pair's
 * coordinates (x0, x1, y0, y1): g[12], H[144]. */
static double kernel(void (*fn)(const double *, double *), int n, const int *ip, const double *const *pts,
                     double *g, double *H)
{
    double x[12], o[1 + 12 + 144];
    for (int k = 0; k < n; ++k)
        memcpy(x + 3 * k, pts[ip[k]], 3 * sizeof *x);
    fn(x, o);
    const int nx = 3 * n;
    const double sign = o[0] < 0.0 ? -1.0 : 1.0;  /* (the edge-edge distance is signed) */
    memset(g, 0, 12 * sizeof *g);
    memset(H, 0, 144 * sizeof *H);
    for (int a = 0; a < nx; ++a) {
        const int A = 3 * ip[a / 3] + a % 3;
        g[A] = sign * o[1 + a];
        for (int b = 0; b < nx; ++b)
            H[12 * A + 3 * ip[b / 3] + b % 3] = sign * o[1 + nx + nx * a + b];
    }
    return sign * o[0];
}

/* The distance of the segments' closest points (their kind from sg, tau). */
static double segment_distance(const double *const *pts, double sg, double tau, double *g, double *H)
{
    const int send = sg == 0.0 || sg == 1.0, tend = tau == 0.0 || tau == 1.0;
    if (!send && !tend)
        return kernel(bk_pair_dist_edge_edge, 4, (const int[]){0, 1, 2, 3}, pts, g, H);
    if (send && !tend)
        return kernel(bk_pair_dist_point_edge, 3, (const int[]){sg == 0.0 ? 0 : 1, 2, 3}, pts, g, H);
    if (!send)
        return kernel(bk_pair_dist_point_edge, 3, (const int[]){tau == 0.0 ? 2 : 3, 0, 1}, pts, g, H);
    return kernel(bk_pair_dist_point_point, 2, (const int[]){sg == 0.0 ? 0 : 1, tau == 0.0 ? 2 : 3}, pts, g, H);
}

/* The distance of end p of one segment to the other segment (q0, q1). */
static double end_distance(const double *const *pts, int p, int q0, int q1, double *g, double *H)
{
    double e[3], w[3];
    for (int d = 0; d < 3; ++d)
        e[d] = pts[q1][d] - pts[q0][d], w[d] = pts[p][d] - pts[q0][d];
    const double h = dot3(w, e) / dot3(e, e);
    if (h > 0.0 && h < 1.0)
        return kernel(bk_pair_dist_point_edge, 3, (const int[]){p, q0, q1}, pts, g, H);
    return kernel(bk_pair_dist_point_point, 2, (const int[]){p, h <= 0.0 ? q0 : q1}, pts, g, H);
}

/* e += c b(s), s = d - R, with its gradient and Hessian from those of d. */
static void add_barrier(double c, double d, const double *gd, const double *Hd, double R, double shat, double *e,
                        double *g, double *H)
{
    double b[3];
    if (d - R >= shat)
        return;
    bk_contact_barrier(d - R, shat, b);
    *e += c * b[0];
    for (int i = 0; i < 12; ++i) {
        g[i] += c * b[1] * gd[i];
#pragma omp simd
        for (int j = 0; j < 12; ++j)
            H[12 * i + j] += c * (b[2] * gd[i] * gd[j] + b[1] * Hd[12 * i + j]);
    }
}

double bc_pair_energy(const seg_pair *sp, double R, double shat, double ha, double hb, double *g, double *H)
{
    double gd[12], Hd[144], ess = 0.0, eps = 0.0, gss[12] = {0}, gps[12] = {0}, gc[12], Hc[144];
    static const int ends[4][3] = {{0, 2, 3}, {1, 2, 3}, {2, 0, 1}, {3, 0, 1}};
    const double c = kernel(bk_pair_dist_cos2, 4, (const int[]){0, 1, 2, 3}, sp->pts, gc, Hc);
    const double t = c <= BC_BLEND_C1 ? 0.0 : c >= BC_BLEND_C2 ? 1.0 : (c - BC_BLEND_C1) / (BC_BLEND_C2 - BC_BLEND_C1);
    const double S = t * t * t * (10.0 - 15.0 * t + 6.0 * t * t), xi = 1.0 - S;
    double Hss[144] = {0}, Hps[144] = {0};
    if (xi > 0.0) {                              /* crossing: the closest points, weight (ha + hb) / 2 */
        const double d = segment_distance(sp->pts, sp->sg, sp->tau, gd, Hd);
        add_barrier(0.5 * (ha + hb), d, gd, Hd, R, shat, &ess, gss, Hss);
    }
    if (xi < 1.0)                                /* along each other: each end to the other segment */
        for (int k = 0; k < 4; ++k) {
            const double d = end_distance(sp->pts, ends[k][0], ends[k][1], ends[k][2], gd, Hd);
            add_barrier(0.25 * (k < 2 ? ha : hb), d, gd, Hd, R, shat, &eps, gps, Hps);
        }
    /* E = xi Ess + (1 - xi) Eps: the blend's derivatives where 0 < t < 1 */
    const double k1 = t > 0.0 && t < 1.0 ? -30.0 * t * t * (t - 1.0) * (t - 1.0) / (BC_BLEND_C2 - BC_BLEND_C1) : 0.0;
    const double k2 = t > 0.0 && t < 1.0 ? -60.0 * t * (2.0 * t - 1.0) * (t - 1.0) /
                                                ((BC_BLEND_C2 - BC_BLEND_C1) * (BC_BLEND_C2 - BC_BLEND_C1)) : 0.0;
    const double de = ess - eps;                 /* dxi = k1 grad c; d2xi = k2 grad c grad c^T + k1 H c */
    for (int i = 0; i < 12; ++i) {
        g[i] = xi * gss[i] + (1.0 - xi) * gps[i] + de * k1 * gc[i];
        if (!H)
            continue;
#pragma omp simd
        for (int j = 0; j < 12; ++j)
            H[12 * i + j] = xi * Hss[12 * i + j] + (1.0 - xi) * Hps[12 * i + j] +
                            k1 * (gc[i] * (gss[j] - gps[j]) + (gss[i] - gps[i]) * gc[j]) +
                            de * (k2 * gc[i] * gc[j] + k1 * Hc[12 * i + j]);
    }
    return xi * ess + (1.0 - xi) * eps;
}

/* ---- the visitor of the candidate segment pairs (beam_contact_impl.h) ---- */

/* The distance between the boxes of the current sample points of entries i
 * and j of set c, less a round-off allowance: a lower bound of the distances
 * bc_closest finds between their segments. */
static double box_gap(const bc_work *w, int c, int i, int j)
{
    const int ns = w->bm->sets[c].nsample;
    double lo[2][3], hi[2][3], d2 = 0.0, big = 0.0;
    for (int sd = 0; sd < 2; ++sd) {
        const double *x = w->X + 3 * (size_t)(w->base[c] + (sd ? j : i) * ns);
        for (int r = 0; r < 3; ++r)
            lo[sd][r] = hi[sd][r] = x[r];
        for (int k = 1; k < ns; ++k)
            for (int r = 0; r < 3; ++r) {
                const double v = x[3 * k + r];
                lo[sd][r] = v < lo[sd][r] ? v : lo[sd][r];
                hi[sd][r] = v > hi[sd][r] ? v : hi[sd][r];
            }
    }
    for (int r = 0; r < 3; ++r) {
        const double g = lo[1][r] - hi[0][r] > lo[0][r] - hi[1][r] ? lo[1][r] - hi[0][r] : lo[0][r] - hi[1][r];
        d2 += g > 0.0 ? g * g : 0.0;
        for (int sd = 0; sd < 2; ++sd)
            big = fmax(big, fmax(fabs(lo[sd][r]), fabs(hi[sd][r])));
    }
    return sqrt(d2) - 1e-14 * big;           /* (less the round-off of the segments' own distances) */
}

void bc_each_near_pair(const bc_work *w, const bk_model *m, void (*fn)(void *, seg_pair *),
                       void (*cand)(void *, seg_pair *, int), int (*skip)(void *, const seg_pair *, double),
                       void *ctx)
{
    seg_pair sp;
    for (int n = 0; n < w->ncand; ++n) {
        sp.c = w->cand[3 * n], sp.i = w->cand[3 * n + 1], sp.j = w->cand[3 * n + 2];
        const bk_beam_contact_set *set = &w->bm->sets[sp.c];
        const int ns = set->nsample;
        sp.ei = set->elems[sp.i], sp.ej = set->elems[sp.j];
        if (skip && sp.i != sp.j && skip(ctx, &sp, box_gap(w, sp.c, sp.i, sp.j)))
            continue;
        const double hi = elem_len(m, sp.ei) / (ns - 1), hj = elem_len(m, sp.ej) / (ns - 1);
        if (cand)
            cand(ctx, &sp, 0);
        for (sp.k = 0; sp.k < ns - 1; ++sp.k)
            for (sp.l = 0; sp.l < ns - 1; ++sp.l) {
                if (sp.i == sp.j && sp.l <= sp.k)
                    continue;                    /* within one element: each pair once */
                if (!allowed(w, m, sp.c, sp.i, sp.k, sp.j, sp.l))
                    continue;
                sp.pidx[0] = w->base[sp.c] + sp.i * ns + sp.k, sp.pidx[1] = sp.pidx[0] + 1;
                sp.pidx[2] = w->base[sp.c] + sp.j * ns + sp.l, sp.pidx[3] = sp.pidx[2] + 1;
                for (int a = 0; a < 4; ++a)
                    sp.pts[a] = w->X + 3 * sp.pidx[a];
                sp.d = bc_closest(sp.pts, &sp.sg, &sp.tau);
                sp.dist = sp.d - set->radius[sp.i] - set->radius[sp.j];
                sp.hi = hi, sp.hj = hj;
                fn(ctx, &sp);
            }
        if (cand)
            cand(ctx, &sp, 1);
    }
}

void bc_each_pair(const bc_work *w, const bk_model *m, void (*fn)(void *, seg_pair *),
                  void (*cand)(void *, seg_pair *, int), void *ctx)
{
    bc_each_near_pair(w, m, fn, cand, NULL, ctx);
}

/* The interaction module: made when the model has the record "beam_contact". */
static int make_module(bk_system *s, const bk_model_record *rec, void **self, FILE *err)
{
    bk_beam_contact_model *bm = bk_beam_contact_model_read(s->m, rec, err);
    if (!bm)
        return -1;
    const int r = bk_beam_contact_make(s, bm, self);
    if (*self)
        ((bc_work *)*self)->own = bm;    /* (freed with the work, also after a failure) */
    else
        bk_beam_contact_model_free(bm);
    if (r != 0)
        fprintf(err, "error: beam contact: out of memory\n");
    return r != 0 ? -1 : 0;
}

const bk_interaction_module bk_interaction_beam_contact = {.ops = &bk_beam_contact_ops, .order = 40,
                                                           .record = "beam_contact", .make = make_module};
