/* body_contact.c -- a rigid body's primitive resting on a fixed primitive
 * (the model's record "body_contact", gen/scene/body_contact.py; issue 34: a
 * body on a table).  The body's primitive is resolved by points fixed in the
 * body: a sphere's centre and a capsule's end centres with their radius, a
 * box's eight corners (radius 0).  A point at a = R0^T (Z - X) in the body's
 * frame (Z its reference position, X, R0 the body's reference centre and
 * rotation) is at y = r + R(p) a for the body's centre r and quaternion p
 * (out/kernels/contact.h bk_contact_lever: R(p) a, its derivatives in p and
 * the second-derivative term), at the distance s = g(y) - radius from the
 * fixed primitive (g its gap, contact_geometry.h).  Energy per point:
 * kappa b(s), the barrier of the beams' contact (contact_model.h), with its
 * step limiter (each point keeps a tenth of its distance) and the refusal of
 * a state with s <= 0.  Friction is the beams' lagged Coulomb law
 * (contact_impl.h contact_friction_terms' formula): the normal force and
 * normal of the last accepted state, the slip of the body's material point
 * at the surface (the point itself for a corner; for a sphere or capsule end
 * the point y - radius n, a point of the body that turns with it, so that a
 * ball rolls) since its anchor; a sticking point keeps its anchor.  The force
 * and Jacobian on the body's 7 coordinates are exact (the chain through
 * y(r, p) with its second derivative).
 *
 * Record (gen/scene/body_contact.py):
 *   bcontacts N
 *   bc BODY X(3) R0(9) SHAPE prm(15) ASHAPE aprm(15) REACH STIFFNESS MU_S MU_K SLIP   (N times) */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/contact_geometry.h"
#include "assembly/contact_model.h"
#include "assembly/interaction.h"
#include "assembly/system.h"
#include "assembly/system_impl.h"
#include "base/csvrow.h"
#include "base/tables.h"
#include "contact.h"
#include "model/reader.h"

#define BC_MAXPT 8                   /* points of one body primitive (a box's corners) */

typedef struct bc_set {
    int body;                        /* the body's element */
    bk_contact_prim against;         /* the fixed primitive (no motion, no body) */
    double shat, kappa, mu, mu_k, slip;
    int npt;
    double arm[BC_MAXPT][3];         /* the points in the body's frame */
    double rad[BC_MAXPT];            /* their radii (sphere, capsule) or 0 (corners) */
    double lam[BC_MAXPT], nrm[BC_MAXPT][3], xa[BC_MAXPT][3];   /* lagged friction: normal force, normal, anchor */
    double farm[BC_MAXPT][3];        /* friction's point in the body's frame (the surface point last accepted) */
    int shape;
} bc_set;

typedef struct bc_work {
    int nset;
    bc_set *sets;
    FILE *table;
} bc_work;

/* ---- reading ---- */

static void read_sets(bk_reader *r, const bk_model *m, bc_work *w)
{
    rd_expect(r, "bcontacts");
    const int n = rd_inum(r, "body contacts", 0, MAXN);
    if (r->failed)
        return;
    w->sets = rd_xcalloc(r, (size_t)(n > 0 ? n : 1), sizeof *w->sets);
    if (r->failed)
        return;
    w->nset = n;
    for (int c = 0; c < n && !r->failed; ++c) {
        bc_set *s = &w->sets[c];
        double X[3], R0[9], prm[15];
        rd_expect(r, "bc");
        s->body = rd_inum(r, "body contact body", 0, m->nelem - 1);
        for (int k = 0; k < 3; ++k)
            X[k] = rd_num(r, "body contact reference centre");
        for (int k = 0; k < 9; ++k)
            R0[k] = rd_num(r, "body contact reference rotation");
        s->shape = rd_inum(r, "body contact shape", BK_CONTACT_SPHERE, BK_CONTACT_BOX);
        for (int k = 0; k < 15; ++k)
            prm[k] = rd_num(r, "body contact primitive parameter");
        s->against.shape = rd_inum(r, "body contact fixed shape", 0, BK_CONTACT_BOX);
        for (int k = 0; k < 15; ++k)
            s->against.prm[k] = rd_num(r, "body contact fixed primitive parameter");
        s->against.amp = -1, s->against.body = -1;
        s->shat = rd_num(r, "body contact reach");
        s->kappa = rd_num(r, "body contact stiffness");
        s->mu = rd_num(r, "body contact static friction");
        s->mu_k = rd_num(r, "body contact kinetic friction");
        s->slip = rd_num(r, "body contact slip tolerance");
        if (r->failed)
            return;
        if (!(s->shat > 0.0) || !(s->kappa > 0.0) || !(s->slip > 0.0) || !(s->mu_k >= 0.0) || !(s->mu >= s->mu_k))
            rd_fail(r, "body contact %d: reach, stiffness and slip tolerance must be positive, 0 <= kinetic <= "
                    "static friction", c);
        if (bk_elem_type(m, s->body)->ndof != 7)
            rd_fail(r, "body contact %d: element %d is not a rigid body (7 coordinates r, p)", c, s->body);
        double Z[BC_MAXPT][3];
        if (s->shape == BK_CONTACT_SPHERE) {
            s->npt = 1;
            memcpy(Z[0], prm, sizeof Z[0]);
            s->rad[0] = prm[3];
        } else if (s->shape == BK_CONTACT_CAPSULE) {
            s->npt = 2;
            memcpy(Z[0], prm, sizeof Z[0]);
            memcpy(Z[1], prm + 3, sizeof Z[1]);
            s->rad[0] = s->rad[1] = prm[6];
        } else {
            s->npt = 8;
            for (int k = 0; k < 8; ++k)
                for (int i = 0; i < 3; ++i) {
                    Z[k][i] = prm[i];
                    for (int a = 0; a < 3; ++a)
                        Z[k][i] += ((k >> (2 - a)) & 1 ? 1.0 : -1.0) * prm[3 + a] * prm[6 + 3 * a + i];
                }
        }
        for (int k = 0; k < s->npt; ++k)          /* a = R0^T (Z - X) */
            for (int i = 0; i < 3; ++i) {
                s->arm[k][i] = 0.0;
                for (int j = 0; j < 3; ++j)
                    s->arm[k][i] += R0[3 * j + i] * (Z[k][j] - X[j]);
                s->farm[k][i] = s->arm[k][i];
            }
    }
}

static void bc_free(void *self)
{
    bc_work *w = self;
    if (w)
        free(w->sets);
    free(w);
}

static int bc_make(bk_system *s, const bk_model_record *rec, void **self, FILE *err)
{
    bk_reader r;
    *self = NULL;
    if (rd_open_record(&r, rec, err) != 0)
        return -1;
    bc_work *w = rd_xcalloc(&r, 1, sizeof *w);
    if (w)
        read_sets(&r, s->m, w);
    *self = w;
    return rd_close_record(&r) != 0 ? -1 : 0;
}

/* ---- a point ---- */

typedef struct bc_point {
    double y[3], lev[31];            /* where it is; bk_contact_lever of its arm (w, dw/dp) */
    double g[13], dist;              /* the fixed primitive's gap at y; the distance */
    double yf[3], levf[31];          /* friction's point and its lever */
    int rubs;                        /* friction acts (mu > 0 and a lagged normal force) */
} bc_point;

static void bc_eval(const bc_set *st, int k, const double *qb, bc_point *pt)
{
    static const double nof[3] = {0.0, 0.0, 0.0};
    bk_contact_lever(qb + 3, st->arm[k], nof, pt->lev);
    for (int i = 0; i < 3; ++i)
        pt->y[i] = qb[i] + pt->lev[i];
    bk_contact_gap_ref(&st->against, pt->y, pt->g);
    pt->dist = pt->g[0] - st->rad[k];
    pt->rubs = st->mu > 0.0 && st->lam[k] > 0.0;
    if (pt->rubs) {
        bk_contact_lever(qb + 3, st->farm[k], nof, pt->levf);
        for (int i = 0; i < 3; ++i)
            pt->yf[i] = qb[i] + pt->levf[i];
    }
}

/* The lagged friction at the friction point yf: force fp[3] (adds), stiffness Kp[9] (adds); the slip in the
 * tangent plane since the anchor (*slip). */
static void bc_friction(const bc_set *st, int k, const double *yf, double *fp, double *Kp, double *slip)
{
    const double *n = st->nrm[k];
    double u[3], ut[3], f[4], h[2];
    for (int r = 0; r < 3; ++r)
        u[r] = yf[r] - st->xa[k][r];
    const double un = u[0] * n[0] + u[1] * n[1] + u[2] * n[2];
    for (int r = 0; r < 3; ++r)
        ut[r] = u[r] - un * n[r];
    const double y = sqrt(ut[0] * ut[0] + ut[1] * ut[1] + ut[2] * ut[2]);
    *slip = y;
    bk_contact_friction(y, st->slip, f);
    bk_contact_transition(y, st->slip, h);
    const double mu = st->mu - (st->mu - st->mu_k) * h[0], dmu = -(st->mu - st->mu_k) * h[1];
    const double py = mu * f[2], dpy = dmu * f[2] + mu * f[3], c = st->lam[k];
    for (int r = 0; r < 3; ++r) {
        fp[r] += c * py * ut[r];
        for (int j = 0; j < 3 && Kp; ++j)
            Kp[3 * r + j] += c * (py * ((r == j) - n[r] * n[j]) + (y > 0.0 ? dpy / y * ut[r] * ut[j] : 0.0));
    }
}

/* The barrier's force fp[3] and stiffness Kp[9] in y. */
static void bc_barrier(const bc_set *st, const bc_point *pt, double *fp, double *Kp)
{
    double b[3];
    memset(fp, 0, 3 * sizeof *fp);
    if (Kp)
        memset(Kp, 0, 9 * sizeof *Kp);
    if (!(pt->dist < st->shat))
        return;
    bk_contact_barrier(pt->dist, st->shat, b);
    for (int r = 0; r < 3; ++r) {
        fp[r] = st->kappa * b[1] * pt->g[1 + r];
        for (int j = 0; j < 3 && Kp; ++j)
            Kp[3 * r + j] = st->kappa * (b[2] * pt->g[1 + r] * pt->g[1 + j] + b[1] * pt->g[4 + 3 * r + j]);
    }
}

/* Adds a force fy[3] (stiffness Ky[9]) at the body point of arm `arm` (lever lev) to the body's fb[7] and
 * Kb[49]: G = dy/d(r, p) = [I | dw/dp], fb += G^T fy, Kb += G^T Ky G + sum_r fy_r d2 w_r/dp2. */
static void bc_add(const double *qb, const double *arm, const double *lev, const double *fy, const double *Ky,
                   double *fb, double *Kb)
{
    double G[3][7];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 7; ++c)
            G[r][c] = c < 3 ? (r == c) : lev[3 + 4 * r + c - 3];
    for (int c = 0; c < 7; ++c)
        fb[c] += G[0][c] * fy[0] + G[1][c] * fy[1] + G[2][c] * fy[2];
    if (!Kb)
        return;
    for (int a = 0; a < 7; ++a)
        for (int b = 0; b < 7; ++b) {
            double v = 0.0;
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c)
                    v += G[r][a] * Ky[3 * r + c] * G[c][b];
            Kb[7 * a + b] += v;
        }
    double hl[31];
    bk_contact_lever(qb + 3, arm, fy, hl);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            Kb[7 * (3 + i) + 3 + j] += hl[15 + 4 * i + j];
}

/* The force on the body (internal sign) fb[7] and Kb[49] of point k; fy_out (not NULL): the total force on the
 * point in space (internal sign), fn_out the barrier's normal force, ft_out the friction's magnitude. */
static void bc_point_force(const bc_set *st, int k, const double *qb, const bc_point *pt, double *fb, double *Kb,
                           double *fy_out, double *fn_out, double *ft_out, double *slip_out)
{
    double fy[3], Ky[9];
    bc_barrier(st, pt, fy, Kb ? Ky : NULL);
    if (fn_out)
        *fn_out = -(fy[0] * pt->g[1] + fy[1] * pt->g[2] + fy[2] * pt->g[3]);
    bc_add(qb, st->arm[k], pt->lev, fy, Ky, fb, Kb);
    double ff[3] = {0.0, 0.0, 0.0}, Kf[9] = {0.0}, slip = 0.0;
    if (pt->rubs) {
        bc_friction(st, k, pt->yf, ff, Kb ? Kf : NULL, &slip);
        bc_add(qb, st->farm[k], pt->levf, ff, Kf, fb, Kb);
    }
    if (fy_out)
        for (int r = 0; r < 3; ++r)
            fy_out[r] = fy[r] + ff[r];
    if (ft_out)
        *ft_out = sqrt(ff[0] * ff[0] + ff[1] * ff[1] + ff[2] * ff[2]);
    if (slip_out)
        *slip_out = slip;
}

/* ---- the interaction ---- */

static int bc_assemble(void *self, bk_system *s, const double *q, const bk_path *path, double *fint, double *Ax)
{
    (void)path;
    bc_work *w = self;
    int bad = 0;
    for (int c = 0; c < w->nset; ++c) {
        bc_set *st = &w->sets[c];
        double qb[7], fb[7] = {0.0}, Kb[49] = {0.0};
        bk_gather(s->m, st->body, q, qb);
        int any = 0;
        for (int k = 0; k < st->npt; ++k) {
            bc_point pt;
            bc_eval(st, k, qb, &pt);
            if (!(pt.dist > 0.0)) {
                bad = 1;                     /* through the surface: not an admissible state */
                continue;
            }
            if (!(pt.dist < st->shat) && !pt.rubs)
                continue;
            bc_point_force(st, k, qb, &pt, fb, Ax ? Kb : NULL, NULL, NULL, NULL, NULL);
            any = 1;
        }
        if (!any)
            continue;
        bad |= bk_scatter(s->m, st->body, fb, 1.0, fint);
        if (Ax)
            bk_scatter_matrix(s, st->body, Kb, 1.0, Ax);
    }
    return bad ? -1 : 0;
}

/* Each point keeps a tenth of its distance: |grad g| = 1, the point moves by dy = dr + dw/dp dp to first
 * order. */
static double bc_step_limit(void *self, const bk_system *s, const double *q, const double *dx)
{
    bc_work *w = self;
    double alpha = 1.0;
    for (int c = 0; c < w->nset; ++c) {
        bc_set *st = &w->sets[c];
        double qb[7], db[7];
        const int *dofs = s->m->elems[st->body].dofs;
        bk_gather(s->m, st->body, q, qb);
        for (int k = 0; k < 7; ++k)
            db[k] = s->eq[dofs[k]] >= 0 ? dx[s->eq[dofs[k]]] : 0.0;
        for (int k = 0; k < st->npt; ++k) {
            bc_point pt;
            bc_eval(st, k, qb, &pt);
            double dy[3], mv = 0.0;
            for (int r = 0; r < 3; ++r) {
                dy[r] = db[r];
                for (int j = 0; j < 4; ++j)
                    dy[r] += pt.lev[3 + 4 * r + j] * db[3 + j];
                mv += dy[r] * dy[r];
            }
            mv = sqrt(mv);
            if (mv > 0.0 && mv * alpha > 0.9 * pt.dist)
                alpha = pt.dist > 0.0 ? 0.9 * pt.dist / mv : 0.0;
        }
    }
    return alpha;
}

/* The lagged friction state (see the head): the normal force and normal of the accepted state, the friction
 * point (the body's material point at y - radius n, in the body's frame) and its anchor, kept by the slip of
 * a sticking point. */
static void bc_accept(void *self, const bk_system *s, const double *q, const bk_path *path)
{
    (void)path;
    bc_work *w = self;
    static const double e[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, nof[3] = {0, 0, 0};
    for (int c = 0; c < w->nset; ++c) {
        bc_set *st = &w->sets[c];
        double qb[7], R[9], col[31];
        bk_gather(s->m, st->body, q, qb);
        for (int k = 0; k < 3; ++k) {
            bk_contact_lever(qb + 3, e[k], nof, col);
            for (int r = 0; r < 3; ++r)
                R[3 * r + k] = col[r];
        }
        for (int k = 0; k < st->npt; ++k) {
            bc_point pt;
            bc_eval(st, k, qb, &pt);
            double u[3] = {0.0, 0.0, 0.0}, un = 0.0, y = 0.0, b[3];
            const double *n = st->nrm[k];
            if (pt.rubs) {
                for (int r = 0; r < 3; ++r)
                    u[r] = pt.yf[r] - st->xa[k][r], un += u[r] * n[r];
                for (int r = 0; r < 3; ++r)
                    u[r] -= un * n[r], y += u[r] * u[r];
                y = sqrt(y);
            }
            const int stick = pt.rubs && y < st->slip;
            st->lam[k] = 0.0;
            if (pt.dist > 0.0 && pt.dist < st->shat) {
                bk_contact_barrier(pt.dist, st->shat, b);
                st->lam[k] = -st->kappa * b[1];
            }
            double yf[3], aw[3];
            for (int r = 0; r < 3; ++r) {
                st->nrm[k][r] = pt.g[1 + r];
                aw[r] = pt.lev[r] - st->rad[k] * pt.g[1 + r];     /* the surface point, from the centre r */
                yf[r] = qb[r] + aw[r];
            }
            for (int i = 0; i < 3; ++i)
                st->farm[k][i] = R[i] * aw[0] + R[3 + i] * aw[1] + R[6 + i] * aw[2];
            for (int r = 0; r < 3; ++r)
                st->xa[k][r] = yf[r] - (stick ? u[r] : 0.0);
        }
    }
}

/* ---- outputs ---- */

static const bk_table_spec body_contacts_csv =
    BK_TABLE("body_contacts.csv", "runs with `[[body_contact]]`",
             "step,time,set,body,point,x,y,z,distance,normal_force,tangential_force,state,fx,fy,fz\n");

static int bc_tables(void *self, const bk_system *s, bk_tables *ts, const char *dir, FILE *err)
{
    (void)s;
    bc_work *w = self;
    w->table = bk_tables_open(ts, dir, &body_contacts_csv, 1, err);
    return w->table ? 0 : -1;
}

static void bc_rows(void *self, const bk_system *s, int step, double t, const double *q, bk_rowqueue *rq)
{
    bc_work *w = self;
    if (!w->table)
        return;
    for (int c = 0; c < w->nset; ++c) {
        const bc_set *st = &w->sets[c];
        double qb[7];
        bk_gather(s->m, st->body, q, qb);
        for (int k = 0; k < st->npt; ++k) {
            bc_point pt;
            bc_eval(st, k, qb, &pt);
            if (!(pt.dist > 0.0) || (!(pt.dist < st->shat) && !pt.rubs))
                continue;
            double fb[7] = {0.0}, fy[3], fn, ft, slip;
            bc_point_force(st, k, qb, &pt, fb, NULL, fy, &fn, &ft, &slip);
            bk_row r;
            bk_row_begin(&r, w->table, rq);
            bk_row_int(&r, step);
            bk_row_num(&r, t);
            bk_row_int(&r, c);
            bk_row_int(&r, st->body);
            bk_row_int(&r, k);
            for (int d = 0; d < 3; ++d)
                bk_row_num(&r, pt.y[d]);
            bk_row_num(&r, pt.dist);
            bk_row_num(&r, fn);
            bk_row_num(&r, ft);
            bk_row_str(&r, !pt.rubs ? "none" : slip < st->slip ? "stick" : "slip");
            for (int d = 0; d < 3; ++d)
                bk_row_num(&r, -fy[d]);              /* the force on the body */
            bk_row_end(&r);
        }
    }
}

static int bc_summary(void *self, const bk_system *s, const double *q, char *buf, size_t n)
{
    bc_work *w = self;
    double dmin = INFINITY;
    int len = 0;
    for (int c = 0; c < w->nset; ++c) {
        const bc_set *st = &w->sets[c];
        double qb[7], F[3] = {0.0, 0.0, 0.0}, N = 0.0;
        int act = 0;
        bk_gather(s->m, st->body, q, qb);
        for (int k = 0; k < st->npt; ++k) {
            bc_point pt;
            bc_eval(st, k, qb, &pt);
            dmin = fmin(dmin, pt.dist);
            if (!(pt.dist > 0.0) || (!(pt.dist < st->shat) && !pt.rubs))
                continue;
            double fb[7] = {0.0}, fy[3], fn;
            bc_point_force(st, k, qb, &pt, fb, NULL, fy, &fn, NULL, NULL);
            for (int r = 0; r < 3; ++r)
                F[r] -= fy[r];
            N += fn;
            act += pt.dist < st->shat;
        }
        len += snprintf(buf + len, (size_t)len < n ? n - (size_t)len : 0,
                        "%s{\"body\": %d, \"normal_force\": %.17g, \"force\": [%.17g, %.17g, %.17g], "
                        "\"active_points\": %d}", c ? ", " : "", st->body, N, F[0], F[1], F[2], act);
        if ((size_t)len >= n)
            return -1;
    }
    char head[128];
    const int hl = snprintf(head, sizeof head, "{\"min_distance\": %.17g, \"max_penetration\": %.17g, \"sets\": [",
                            dmin, dmin < 0.0 ? -dmin : 0.0);
    if ((size_t)(hl + len + 3) > n)
        return -1;
    memmove(buf + hl, buf, (size_t)len);
    memcpy(buf, head, (size_t)hl);
    memcpy(buf + hl + len, "]}", 3);
    return 0;
}

static const bk_interaction_ops bc_ops = {.name = "body_contact", .assemble = bc_assemble,
                                          .step_limit = bc_step_limit, .accept = bc_accept, .tables = bc_tables,
                                          .rows = bc_rows, .summary_key = "body_contact", .uncounted_energy = 1,
                                          .summary = bc_summary, .free = bc_free, .depends = bk_depends_on_q};

/* The interaction module: made when the model has the record "body_contact". */
const bk_interaction_module bk_interaction_body_contact = {.ops = &bc_ops, .order = 31, .record = "body_contact",
                                                           .make = bc_make};
