/* contact_force.c -- the contact interaction: barrier forces between the sample
 * points of beams' centrelines and rigid primitives, their Jacobian, the
 * lagged friction state, the step limiter (see contact_force.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/contact_impl.h"
#include "assembly/system.h"
#include "assembly/system_impl.h"
#include "model/amplitude.h"
#include "base/csvrow.h"
#include "base/tables.h"
#include "contact.h"

/* The coupling blocks of every element of a set whose primitive belongs to a
 * rigid body with the body's element (the Newton pattern grows by them once,
 * before any analysis has used it).  0 or 1, or -1 when out of memory. */
static int body_couplings(bk_system *s, const bk_contact_model *cm)
{
    int n = 0, r = 0;
    for (int c = 0; c < cm->nset; ++c)
        n += cm->prims[cm->sets[c].prim].body >= 0 ? cm->sets[c].nelem : 0;
    if (n == 0)
        return 0;
    int *pairs = malloc(2 * (size_t)n * sizeof *pairs), k = 0;
    if (!pairs)
        return -1;
    for (int c = 0; c < cm->nset; ++c)
        for (int i = 0; cm->prims[cm->sets[c].prim].body >= 0 && i < cm->sets[c].nelem; ++i, ++k) {
            pairs[2 * k] = cm->sets[c].elems[i];
            pairs[2 * k + 1] = cm->prims[cm->sets[c].prim].body;
        }
    r = bk_system_couple(s, n, pairs);
    free(pairs);
    return r;
}

static int contact_make(bk_system *s, const bk_model_record *rec, void **self, FILE *err)
{
    bk_contact_model *cm = bk_contact_model_read(s->m, rec, err);
    if (!cm)
        return -1;
    size_t md = (size_t)(s->maxdof > 0 ? s->maxdof : 1) + 7;
    contact_work *w = calloc(1, sizeof *w);
    if (!w)
        bk_contact_model_free(cm);
    if (w) {
        w->cm = cm;
        w->pf.stem = "contacts";
        for (int c = 0; c < cm->nset; ++c)
            w->npoint += cm->sets[c].nelem * cm->sets[c].nsample;
        size_t np = (size_t)(w->npoint > 0 ? w->npoint : 1), nent = 1;
        for (int c = 0; c < cm->nset; ++c)
            nent += (size_t)cm->sets[c].nelem;
        w->X = malloc(3 * np * sizeof *w->X);
        w->cand = calloc(nent, sizeof *w->cand);
        w->lb = calloc(nent, sizeof *w->lb);
        w->fe = malloc(md * sizeof *w->fe);
        w->Ke = malloc(md * md * sizeof *w->Ke);
        size_t ns = 1;
        for (int c = 0; c < cm->nset; ++c)
            for (int i = 0; i < cm->sets[c].nelem; ++i)
                if ((size_t)bk_elem_type(s->m, cm->sets[c].elems[i])->nshape > ns)
                    ns = (size_t)bk_elem_type(s->m, cm->sets[c].elems[i])->nshape;
        w->Kc = malloc(9 * (ns + 1) * ns * sizeof *w->Kc);   /* the blocks, and one row of them */
        w->lam = calloc(np, sizeof *w->lam);
        w->nrm = calloc(3 * np, sizeof *w->nrm);
        w->xprev = calloc(3 * np, sizeof *w->xprev);
        w->arm = calloc(3 * np, sizeof *w->arm);
        w->tot = calloc(6 * (size_t)(cm->nset > 0 ? cm->nset : 1), sizeof *w->tot);
        w->place = calloc(BK_CONTACT_PLACEMENT * (size_t)(cm->nprim > 0 ? cm->nprim : 1), sizeof *w->place);
        for (int i = 0; w->place && i < cm->nprim; ++i)    /* in place until a path point is assembled */
            bk_contact_placement(&cm->prims[i], 0.0, w->place + BK_CONTACT_PLACEMENT * i);
    }
    const int shapes = w ? contact_sample_shapes(w, s->m) : -1;
    *self = w;
    if (!w || shapes != 0 || body_couplings(s, cm) < 0 ||
        !(w->tot && w->fe && w->Ke && w->Kc && w->lam && w->nrm && w->xprev && w->arm && w->place && w->X &&
          w->cand && w->lb)) {
        fprintf(err, "error: contact: out of memory\n");
        return -1;
    }
    return 0;
}

static void contact_free(void *self)
{
    contact_work *w = self;
    if (w) {
        free(w->Kc);
        free(w->X), free(w->cand), free(w->lb);
        free(w->tot);
        free(w->Nc);
        free(w->Noff);
        bk_point_frames_free(&w->pf);
        free(w->fe);
        free(w->Ke);
        free(w->lam);
        free(w->nrm);
        free(w->xprev);
        free(w->arm);
        free(w->qdof);
        free(w->place);
        bk_contact_model_free(w->cm);
    }
    free(w);
}
/* ---- assemble: the element's force and matrix, scattered after its points ---- */

typedef struct assembly {
    contact_work *w;
    bk_system *s;
    double *fint, *Ax;
    int touched, bad;
    int ke_used;                     /* the element's Ke holds terms (zeroed at its first use) */
} assembly;

/* The equation of local coordinate a of the element block (the element's
 * DOFs, then its primitive's body's), or -1. */
static int block_eq(const bk_system *s, const point *pt, int a)
{
    const int nd = pt->et->ndof;
    const int dof = a < nd ? s->m->elems[pt->e].dofs[a] : s->m->elems[pt->prim->body].dofs[a - nd];
    return s->eq[dof];
}

static void assemble_element(void *ctx, point *pt, int end)
{
    assembly *a = ctx;
    if (!end) {
        a->touched = a->ke_used = 0;
        return;
    }
    if (!a->touched)
        return;
    contact_work *w = a->w;
    a->bad |= bk_scatter(a->s->m, pt->e, w->fe, 1.0, a->fint);
    if (pt->prim->body < 0) {
        if (!a->Ax)
            return;
        const bk_element *et = pt->et;
        const int ns = et->nshape, nd = et->ndof;
        /* the blocks N_i N_j Kv (i <= j; Kv is a Hessian, so the block (j, i) is (i, j)'s transpose) straight
         * to the matrix, or to Ke when it holds a rolling point's terms */
        const int *sl = a->s->eslot + a->s->eslot_off[pt->e];
        for (int i = 0; i < ns; ++i)
            for (int j = i; j < ns; ++j) {
                const double *blk = w->Kc + 9 * (i * ns + j);
                const int o1 = et->shape_dof[i] * nd + et->shape_dof[j], o2 = et->shape_dof[j] * nd + et->shape_dof[i];
                if (a->ke_used) {
                    for (int r = 0; r < 3; ++r)
                        for (int c = 0; c < 3; ++c) {
                            w->Ke[o1 + r * nd + c] += blk[3 * r + c];
                            if (i < j)
                                w->Ke[o2 + r * nd + c] += blk[3 * c + r];
                        }
                    continue;
                }
                for (int r = 0; r < 3; ++r)
                    for (int c = 0; c < 3; ++c) {
                        const int k = sl[o1 + r * nd + c];
                        if (k >= 0)
                            a->Ax[k] += blk[3 * r + c];
                    }
                if (i < j)
                    for (int r = 0; r < 3; ++r)
                        for (int c = 0; c < 3; ++c) {
                            const int k = sl[o2 + r * nd + c];
                            if (k >= 0)
                                a->Ax[k] += blk[3 * c + r];
                        }
            }
        if (a->ke_used)
            bk_scatter_matrix(a->s, pt->e, w->Ke, 1.0, a->Ax);
        return;
    }
    const int nd = pt->et->ndof, nb = nd + 7;
    const int *bd = a->s->m->elems[pt->prim->body].dofs;
    for (int k = 0; k < 7; ++k) {
        a->bad |= !isfinite(w->fe[nd + k]);
        a->fint[bd[k]] += w->fe[nd + k];
    }
    if (!a->Ax)
        return;
    for (int c = 0; c < nb; ++c) {
        const int col = block_eq(a->s, pt, c);
        if (col < 0)
            continue;
        for (int r = 0; r < nb; ++r) {
            const int row = block_eq(a->s, pt, r);
            const long slot = row >= 0 ? bk_find_slot(a->s, row, col) : -1;
            if (slot >= 0)
                a->Ax[slot] += w->Ke[r * nb + c];
        }
    }
}

/* Adds the friction of rolling point pt, which acts on its section's surface
 * point y = x + w(p) (p the quaternion of its node, at DOF qd): fv[nv], Kv on
 * v = (y, body), taken to the element block by G = dy/dq (N_i on the
 * positions, dw/dp on p) and the term sum_r f_r d2 w_r/dp2 (the lever arm's
 * own curvature: the moment's Jacobian). */
static void assemble_roll(assembly *a, const point *pt)
{
    contact_work *w = a->w;
    const bk_element *et = pt->et;
    const int nd = et->ndof, nv = pt->mpf.nv, nb = nd + (nv - 3), qd = w->qdof[pt->p];
    double fz[3] = {0.0, 0.0, 0.0}, Kz[9] = {0.0}, fv[10], Kv[100], lev[31];
    contact_friction_terms(w, pt->set, pt->p, pt->mpf.z, fz, Kz);
    bk_contact_chain(&pt->mpf, fz, Kz, fv, a->Ax ? Kv : NULL);
    /* G rows: each y_r is a sum of (dof, coefficient) terms, nshape + 4 of them */
    int gd[BK_MAX_SHAPE + 4];
    double gc[3][BK_MAX_SHAPE + 4];
    const int ng = et->nshape + 4;
    for (int i = 0; i < et->nshape; ++i)
        gd[i] = et->shape_dof[i];
    for (int j = 0; j < 4; ++j)
        gd[et->nshape + j] = qd + j;
    for (int r = 0; r < 3; ++r) {
        for (int i = 0; i < et->nshape; ++i)
            gc[r][i] = pt->N[i];
        for (int j = 0; j < 4; ++j)
            gc[r][et->nshape + j] = pt->lev[3 + 4 * r + j];
    }
    /* the DOF of term t of row r: positions r + shape_dof, the quaternion's own */
#define GDOF(t, r) ((t) < et->nshape ? gd[t] + (r) : gd[t])
    for (int r = 0; r < 3; ++r)
        for (int t = 0; t < ng; ++t)
            w->fe[GDOF(t, r)] += gc[r][t] * fv[r];
    for (int k = 3; k < nv; ++k)
        w->fe[nd + k - 3] += fv[k];
    if (!a->Ax)
        return;
    for (int r = 0; r < 3; ++r)                  /* G^T K_yy G */
        for (int c = 0; c < 3; ++c) {
            const double k = Kv[nv * r + c];
            if (k == 0.0)
                continue;
            for (int t = 0; t < ng; ++t)
                for (int u = 0; u < ng; ++u)
                    w->Ke[(size_t)GDOF(t, r) * nb + GDOF(u, c)] += gc[r][t] * k * gc[c][u];
        }
    for (int r = 0; r < 3; ++r)                  /* G^T K_yb, K_by G */
        for (int k = 3; k < nv; ++k)
            for (int t = 0; t < ng; ++t) {
                w->Ke[(size_t)GDOF(t, r) * nb + nd + k - 3] += gc[r][t] * Kv[nv * r + k];
                w->Ke[(size_t)(nd + k - 3) * nb + GDOF(t, r)] += Kv[nv * k + r] * gc[r][t];
            }
    for (int k = 3; k < nv; ++k)
        for (int l = 3; l < nv; ++l)
            w->Ke[(size_t)(nd + k - 3) * nb + nd + l - 3] += Kv[nv * k + l];
#undef GDOF
    bk_contact_lever(pt->qe + qd, w->arm + 3 * pt->p, fv, lev);   /* f . d2w/dp2 */
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            w->Ke[(size_t)(qd + i) * nb + qd + j] += lev[15 + 4 * i + j];
}

static void assemble_point(void *ctx, point *pt)
{
    assembly *a = ctx;
    contact_work *w = a->w;
    const bk_element *et = pt->et;
    const int nd = et->ndof, nv = pt->mp.nv, nb = nd + (nv - 3);
    double fv[10], Kv[100];
    if (!(pt->dist > 0.0)) {
        a->bad = 1;                          /* through the surface: not an admissible state */
        return;
    }
    if (!contact_acts(w, pt))
        return;
    if (pt->roll) {                          /* the barrier on x here, the friction on the surface point */
        double fz[3], Kz[9];
        contact_barrier_terms(pt->set, pt->wl, pt->g, pt->dist, fz, Kz);
        bk_contact_chain(&pt->mp, fz, Kz, fv, a->Ax ? Kv : NULL);
    } else {
        contact_point_force(w, pt, fv, a->Ax ? Kv : NULL);
    }
    if (!a->touched) {
        memset(w->fe, 0, (size_t)nb * sizeof *w->fe);
        if (a->Ax && nv == 3)
            memset(w->Kc, 0, 9 * (size_t)et->nshape * (size_t)et->nshape * sizeof *w->Kc);
        a->touched = 1;
    }
    if (a->Ax && !a->ke_used && (pt->roll || nv > 3)) {
        memset(w->Ke, 0, (size_t)nb * (size_t)nb * sizeof *w->Ke);
        a->ke_used = 1;
    }
    if (pt->roll)
        assemble_roll(a, pt);
    /* v = (x, body): x = sum N_i r_i, so the block's rows are N_i times x's, then the body's */
    for (int i = 0; i < et->nshape; ++i)
        for (int r = 0; r < 3; ++r)
            w->fe[et->shape_dof[i] + r] += pt->N[i] * fv[r];
    for (int k = 3; k < nv; ++k)
        w->fe[nd + k - 3] += fv[k];
    if (!a->Ax)
        return;
    if (nv == 3) {                           /* the blocks N_i N_j Kv, i <= j, to the matrix after the last point */
        const int ns = et->nshape;
        for (int i = 0; i < ns; ++i)
            for (int j = i; j < ns; ++j) {
                double *restrict blk = w->Kc + 9 * (i * ns + j);
                const double nij = pt->N[i] * pt->N[j];
#pragma omp simd
                for (int k = 0; k < 9; ++k)
                    blk[k] += nij * Kv[k];
            }
        return;
    }
    for (int av = 0; av < nv; ++av)
        for (int bv = 0; bv < nv; ++bv) {
            const double kab = Kv[nv * av + bv];
            if (kab == 0.0)
                continue;
            for (int i = 0; i < (av < 3 ? et->nshape : 1); ++i) {
                const int row = av < 3 ? et->shape_dof[i] + av : nd + av - 3;
                const double ni = av < 3 ? pt->N[i] : 1.0;
                for (int j = 0; j < (bv < 3 ? et->nshape : 1); ++j) {
                    const int col = bv < 3 ? et->shape_dof[j] + bv : nd + bv - 3;
                    w->Ke[row * nb + col] += ni * (bv < 3 ? pt->N[j] : 1.0) * kab;
                }
            }
        }
}

static int contact_assemble(void *self, bk_system *s, const double *q, const bk_path *path, double *fint,
                            double *Ax)
{
    contact_work *w = self;
    contact_set_placement(w, s->m, path->x);
    contact_broad(w, s, q);
    assembly a = {.w = w, .s = s, .fint = fint, .Ax = Ax};
    contact_each_candidate(w, s, q, assemble_point, assemble_element, &a);
    return a.bad ? -1 : 0;
}

/* ---- accept: the lagged friction state ---- */

/* The lagged friction state of a sample point from the accepted state: its
 * barrier force's magnitude and its unit normal; its anchor, the point its
 * slip is measured from: a sticking point (slip since the anchor below the
 * tolerance eps) keeps it, so that a load below the friction limit holds it
 * within eps however many steps it acts (no creep); a point that slid by eps
 * or more, or was not in contact, puts it where it is.  Anchor and normal are
 * in the primitive's reference coordinates (z), so the slip is relative to a
 * moving primitive or body. */
static void accept_point(void *ctx, point *pt)
{
    contact_work *w = ctx;
    const int p = pt->p;
    const double *zf = pt->roll ? pt->mpf.z : pt->mp.z;   /* where friction acted over the step */
    double *xa = w->xprev + 3 * p, *n = w->nrm + 3 * p, u[3], un = 0.0, ut2 = 0.0, b[3];
    for (int r = 0; r < 3; ++r)
        u[r] = zf[r] - xa[r], un += u[r] * n[r];
    for (int r = 0; r < 3; ++r)
        ut2 += (u[r] - un * n[r]) * (u[r] - un * n[r]);
    const double y = sqrt(ut2), eps = pt->set->slip;
    const int rubbed = w->lam[p] > 0.0;
    w->lam[p] = 0.0;
    if (pt->dist > 0.0 && pt->dist < pt->set->shat) {
        bk_contact_barrier(pt->dist, pt->set->shat, b);
        w->lam[p] = -pt->wl * b[1];
    }
    const double nold[3] = {n[0], n[1], n[2]};
    for (int r = 0; r < 3; ++r)
        n[r] = pt->g[1 + r];
    if (w->qdof[p] >= 0 && pt->set->mu > 0.0) {
        /* a section that rolls: the new lever arm -r n (n in space: J_y^T n, J_y the map's rotation), in its
         * node's frame (R^T by the lever of the unit vectors), the surface point there, and the anchor kept
         * by the slip of a sticking point (as on the centreline: a point that rolls without slipping sticks) */
        const int nv = pt->mp.nv;
        double nw[3], aw[3], y3[3], col[31], R[9];
        static const double e[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, nof[3] = {0, 0, 0};
        for (int c = 0; c < 3; ++c) {
            nw[c] = pt->mp.identity ? n[c] : 0.0;
            for (int k = 0; k < 3 && !pt->mp.identity; ++k)
                nw[c] += pt->mp.J[nv * k + c] * n[k];
        }
        for (int k = 0; k < 3; ++k) {
            bk_contact_lever(pt->qe + w->qdof[p], e[k], nof, col);
            for (int r = 0; r < 3; ++r)
                R[3 * r + k] = col[r];
        }
        for (int r = 0; r < 3; ++r)
            aw[r] = -pt->set->radius[pt->i] * nw[r], y3[r] = pt->x[r] + aw[r];
        for (int k = 0; k < 3; ++k)
            w->arm[3 * p + k] = R[k] * aw[0] + R[3 + k] * aw[1] + R[6 + k] * aw[2];
        bk_contact_map map;
        bk_contact_map_point(pt->prim, w->place + BK_CONTACT_PLACEMENT * pt->set->prim, pt->qb, y3, &map);
        for (int r = 0; r < 3; ++r)          /* the slip in the plane (the arm's turn lifts the old point) */
            xa[r] = map.z[r] - (rubbed && y < eps ? u[r] - un * nold[r] : 0.0);
        return;
    }
    for (int r = 0; r < 3; ++r)
        if (!rubbed || y >= eps)
            xa[r] = pt->mp.z[r];
}

static void contact_accept(void *self, const bk_system *s, const double *q, const bk_path *path)
{
    contact_work *w = self;
    contact_set_placement(w, s->m, path->x);
    contact_broad(w, s, q);              /* (the far points keep their state: it counts once they rub) */
    contact_each_candidate(w, s, q, accept_point, NULL, w);
}

/* ---- step limit: every sample point keeps a tenth of its distance ---- */

typedef struct limiter {
    const bk_system *s;
    const double *dx;
    double de[BK_MAX_ELEMENT_DOF + 7];   /* the correction on the element's DOFs, then its body's */
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
    for (int k = 0; pt->prim->body >= 0 && k < 7; ++k) {
        const int eq = block_eq(l->s, pt, pt->et->ndof + k);
        l->de[pt->et->ndof + k] = eq >= 0 ? l->dx[eq] : 0.0;
    }
}

/* |grad g| = 1, so the distance moves by at most the point's motion relative
 * to the primitive, dz = J dv (to first order in a body's rotation). */
static void limit_point(void *ctx, point *pt)
{
    limiter *l = ctx;
    double dv[10] = {0.0}, dp[3];
    const int nv = pt->mp.nv;
    for (int i = 0; i < pt->et->nshape; ++i)
        for (int r = 0; r < 3; ++r)
            dv[r] += pt->N[i] * l->de[pt->et->shape_dof[i] + r];
    for (int k = 3; k < nv; ++k)
        dv[k] = l->de[pt->et->ndof + k - 3];
    for (int r = 0; r < 3; ++r) {
        dp[r] = pt->mp.identity ? dv[r] : 0.0;
        for (int k = 0; k < nv && !pt->mp.identity; ++k)
            dp[r] += pt->mp.J[nv * r + k] * dv[k];
    }
    const double move = sqrt(dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2]);
    if (move > 0.0 && move * l->alpha > 0.9 * pt->dist)
        l->alpha = pt->dist > 0.0 ? 0.9 * pt->dist / move : 0.0;
}

/* The fraction of dx[neq] that keeps every sample point at more than a tenth
 * of its distance (the primitives where the last residual had them: this
 * iterate's path point). */
static double contact_step_limit(void *self, const bk_system *s, const double *q, const double *dx)
{
    contact_work *w = self;
    limiter l = {.s = s, .dx = dx, .alpha = 1.0};
    contact_broad(w, s, q);
    contact_limit_candidates(w, s, dx);
    contact_each_candidate(w, s, q, limit_point, limit_element, &l);
    return l.alpha;
}

/* The gaps depend on q; on x too when a primitive moves (its placement's amplitude). */
static unsigned contact_depends(const void *self, const bk_system *s)
{
    const contact_work *w = self;
    (void)s;
    unsigned d = BK_DEPENDS_Q;
    for (int i = 0; i < w->cm->nprim; ++i)
        for (int k = 0; k < 3; ++k)
            if (w->cm->prims[i].motion[k] != 0.0 || w->cm->prims[i].turn[k] != 0.0)
                d |= BK_DEPENDS_X;
    return d;
}

const bk_interaction_ops bk_contact_ops = {.name = "contact", .assemble = contact_assemble,
                                           .step_limit = contact_step_limit, .accept = contact_accept,
                                           .tables = contact_tables, .rows = contact_rows, .frame = contact_frame,
                                           .summary_key = "contact", .uncounted_energy = 1,
                                           .summary = contact_summary, .free = contact_free,
                                           .depends = contact_depends};

/* The interaction module: made when the model has the record "contact". */
const bk_interaction_module bk_interaction_contact = {.ops = &bk_contact_ops, .order = 30, .record = "contact",
                                                      .make = contact_make};

