/* arc_path.c -- the visited points of an arc-length path, for detecting a
 * return to one of them (a closed loop; see continuation.h). */
#include "analysis/continuation.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>


void bk_arc_path_free(arc_path *p)
{
    free(p->lam), free(p->arc), free(p->u), free(p->q), free(p->quat), free(p->isq);
}

/* Keep the point (q, lam) at the arc length arc from the start; 0, or -1 when out of memory. */
int bk_arc_path_push(arc_path *p, const bk_model *m, const double *q, double lam, double arc)
{
    if (p->n == p->cap) {
        int cap = p->cap ? 2 * p->cap : 64;
        double *l = realloc(p->lam, (size_t)cap * sizeof *l);
        if (!l)
            return -1;
        p->lam = l;
        double *ar = realloc(p->arc, (size_t)cap * sizeof *ar);
        if (!ar)
            return -1;
        p->arc = ar;
        double *u = realloc(p->u, (size_t)cap * 3 * (size_t)(p->ns > 0 ? p->ns : 1) * sizeof *u);
        if (!u)
            return -1;
        p->u = u;
        p->cap = cap;
    }
    if (p->nq == p->n && (long)(p->nq + 1) * p->nd <= ARC_PATH_BUDGET) {
        if (p->nq == p->qcap) {      /* doubling, within the budget; out of memory: no more states kept */
            long cap = p->qcap ? 2L * p->qcap : 64;
            if (cap * p->nd > ARC_PATH_BUDGET)
                cap = ARC_PATH_BUDGET / (p->nd > 0 ? p->nd : 1);
            double *s = realloc(p->q, (size_t)cap * (size_t)p->nd * sizeof *s);
            if (s)
                p->q = s, p->qcap = (int)cap;
        }
        if (p->nq < p->qcap) {
            memcpy(p->q + (size_t)p->nq * p->nd, q, (size_t)p->nd * sizeof *q);
            p->nq++;
        }
    }
    bk_critical_point cp;
    bk_sensor_displacements(m, q, &cp);
    for (int k = 0; k < p->ns; ++k)
        for (int i = 0; i < 3; ++i)
            p->u[(size_t)p->n * 3 * p->ns + 3 * k + i] = cp.u[k][i];
    p->arc[p->n] = arc;
    p->lam[p->n++] = lam;
    return 0;
}

/* The cheap test of the point (u: its sensor displacements, lam) against the
 * segment [k, k+1]; du, dlam: the change over the last step. */
int bk_arc_path_near(const arc_path *p, int k, const double *u, double lam, const double *du, double dlam)
{
    double l0 = p->lam[k], l1 = p->lam[k + 1], tl = 0.25 * (fabs(dlam) + fabs(l1 - l0)) + 1e-12 * fabs(lam);
    if (lam < fmin(l0, l1) - tl || lam > fmax(l0, l1) + tl)
        return 0;
    const double *u0 = p->u + (size_t)k * 3 * p->ns, *u1 = u0 + 3 * p->ns;
    for (int s = 0; s < p->ns; ++s) {
        double dn = 0.0, ds = 0.0;
        for (int i = 0; i < 3; ++i) {
            double d = u1[3 * s + i] - u0[3 * s + i];
            dn += du[3 * s + i] * du[3 * s + i], ds += d * d;
        }
        double tu = 0.25 * (sqrt(dn) + sqrt(ds)) + 1e-12;
        for (int i = 0; i < 3; ++i) {
            double a = u0[3 * s + i], b = u1[3 * s + i], x = u[3 * s + i];
            if (x < fmin(a, b) - tu || x > fmax(a, b) + tu)
                return 0;
        }
    }
    return 1;
}

/* The full test: the weighted distance of (q, lam) from the segment [k, k+1]
 * of kept states (k + 1 < p->nq) into *dist, the segment's length into *len. */
void bk_arc_path_distance(const arc_path *p, const bk_system *s, const arc_ctx *c, double L2, int k,
                              const double *q, double lam, double *dist, double *len)
{
    const double *a = p->q + (size_t)k * p->nd, *b = a + p->nd;
    double xa = c->psi2 * (lam - p->lam[k]) * (lam - p->lam[k]);
    double ba = c->psi2 * (p->lam[k + 1] - p->lam[k]) * (p->lam[k + 1] - p->lam[k]);
    double xb = c->psi2 * (lam - p->lam[k]) * (p->lam[k + 1] - p->lam[k]);
    for (int j = 0; j < s->nfree; ++j) {
        int i = c->fdof[j];
        if (p->isq[i] || c->W[j] == 0.0)
            continue;
        double dx = q[i] - a[i], db = b[i] - a[i];
        xa += c->W[j] * dx * dx, ba += c->W[j] * db * db, xb += c->W[j] * dx * db;
    }
    for (int g = 0; g < p->nquat; ++g) {
        const int *d = p->quat + 4 * g;
        double nx = 0.0, na = 0.0, nb = 0.0, sa = 0.0;
        for (int i = 0; i < 4; ++i)
            nx += q[d[i]] * q[d[i]], na += a[d[i]] * a[d[i]], nb += b[d[i]] * b[d[i]], sa += q[d[i]] * a[d[i]];
        nx = 1.0 / sqrt(nx), na = (sa < 0.0 ? -1.0 : 1.0) / sqrt(na), nb = (sa < 0.0 ? -1.0 : 1.0) / sqrt(nb);
        for (int i = 0; i < 4; ++i) {
            double dx = q[d[i]] * nx - a[d[i]] * na, db = b[d[i]] * nb - a[d[i]] * na;
            xa += L2 * dx * dx, ba += L2 * db * db, xb += L2 * dx * db;
        }
    }
    double t = ba > 0.0 ? fmin(fmax(xb / ba, 0.0), 1.0) : 0.0;
    *dist = sqrt(fmax(xa - 2.0 * t * xb + t * t * ba, 0.0));
    *len = sqrt(ba);
}

