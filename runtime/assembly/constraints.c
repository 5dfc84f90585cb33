/* constraints.c -- the constraint rows of the Newton system: linear
 * constraints with coefficients that may turn with a prescribed angle, and
 * joints nonlinear in q (generated kernels, bk_joint.h); their residual,
 * Jacobian, Hessian term, time derivatives and starting multipliers
 * (system.h). */
#include "assembly/system.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/system_impl.h"

#include "linalg/linsolve.h"
#include "model/amplitude.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static void angle_factors(const bk_lincon *c, double t, int k, double *C, double *S)
{
    double w = 2.0 * M_PI * c->freq;
    double phi = c->kappa * (c->rate * t + c->amp * sin(w * t));
    double d1 = c->kappa * (c->rate + c->amp * w * cos(w * t));
    double d2 = -c->kappa * c->amp * w * w * sin(w * t);
    if (c->ampl) {
        phi += c->kappa * c->angle * bk_amp_eval(c->ampl, t, 0);
        d1 += c->kappa * c->angle * bk_amp_eval(c->ampl, t, 1);
        d2 += c->kappa * c->angle * bk_amp_eval(c->ampl, t, 2);
    }
    double cp = cos(phi), sp = sin(phi);
    if (k == 0) {
        *C = cp;
        *S = sp;
    } else if (k == 1) {
        *C = -sp * d1;
        *S = cp * d1;
    } else {
        *C = -cp * d1 * d1 - sp * d2;
        *S = -sp * d1 * d1 + cp * d2;
    }
}

/* The k-th time derivative of the prescribed-motion part of row c's
 * right-hand side, ru u(t) (u: its amplitude, else t itself). */
static double motion_rhs(const bk_lincon *c, double t, int k)
{
    if (c->ru == 0.0)
        return 0.0;
    if (c->uampl)
        return c->ru * bk_amp_eval(c->uampl, t, k);
    return c->ru * (k == 0 ? t : k == 1 ? 1.0 : 0.0);
}

double bk_joint_params(const bk_nlcon *c, double t, int k, double *prm)
{
    memcpy(prm, c->prm, BK_JOINT_NGEOM * sizeof *prm);
    prm[BK_JOINT_NGEOM] = prm[BK_JOINT_NGEOM + 1] = 0.0;
    const int kind = c->kind ? c->kind->driven : 0;
    if (!kind)
        return 0.0;
    double w = 2.0 * M_PI * c->freq;
    double th[3] = {c->rate * t + c->amp * sin(w * t), c->rate + c->amp * w * cos(w * t),
                    -c->amp * w * w * sin(w * t)};
    if (c->dampl)
        for (int i = 0; i < 3; ++i)
            th[i] += c->scale * bk_amp_eval(c->dampl, t, i);
    double *cs = prm + BK_JOINT_NGEOM;
    if (kind == 2) {                       /* translation: (1, x) */
        cs[0] = k == 0 ? 1.0 : 0.0;
        cs[1] = th[k];
    } else {                               /* rotation: (cos th, sin th) */
        double co = cos(th[0]), si = sin(th[0]);
        if (k == 0)
            cs[0] = co, cs[1] = si;
        else if (k == 1)
            cs[0] = -si * th[1], cs[1] = co * th[1];
        else
            cs[0] = -co * th[1] * th[1] - si * th[2], cs[1] = -si * th[1] * th[1] + co * th[2];
    }
    return th[0];
}

double bk_constraint_row(const bk_lincon *c, const double *x, double t, int k, int with_rhs)
{
    double C, S, sum = 0.0;
    angle_factors(c, t, k, &C, &S);
    if (with_rhs)
        sum = -(k == 0 ? c->r0 : 0.0) - c->rc * C - c->rs * S - motion_rhs(c, t, k);
    for (int j = 0; j < c->nterm; ++j)
        sum += ((k == 0 ? c->c0[j] : 0.0) + c->cc[j] * C + c->cs[j] * S) * x[c->dof[j]];
    return sum;
}

/* The joints' part of bk_assemble_constraints: rows s g, s G^T nu into the
 * free rows, s G, s G^T and the Hessian term s sum_k nu_k d2 g_k/dq2. */
static void assemble_joints(const bk_system *s, const double *q, const double *nu, double t, double *r,
                            double *Ax)
{
    const bk_model *m = s->m;
    const int nx = BK_JOINT_NX;
    double x[BK_JOINT_NX], g[BK_JOINT_MAXROW], G[BK_JOINT_MAXROW * BK_JOINT_NX], H[BK_JOINT_NX * BK_JOINT_NX];
    double prm[BK_JOINT_NPARAM];
    for (int j = 0; j < m->nnlcon; ++j) {
        const bk_nlcon *c = &m->nlcons[j];
        const int nr = s->jrow[j + 1] - s->jrow[j], row0 = s->jrow[j];
        const int *sl = s->jslot + s->jslot_off[j];
        joint_x(c, q, 0, x);
        bk_joint_params(c, t, 0, prm);
        c->kind->eval(x, prm, g, G);
        for (int i = 0; i < nr; ++i) {
            if (r)
                r[s->nfree + row0 + i] = s->cscale * g[i];
            for (int k = 0; k < nx; ++k) {
                int e = joint_eq(s, c, k);
                if (e < 0)
                    continue;
                if (r && nu)
                    r[e] += s->cscale * G[nx * i + k] * nu[row0 + i];
                if (Ax && sl[nx * nx + nx * i + k] >= 0) {
                    Ax[sl[nx * nx + nx * i + k]] += s->cscale * G[nx * i + k];
                    Ax[sl[nx * nx + nx * nr + nx * i + k]] += s->cscale * G[nx * i + k];
                }
            }
        }
        if (Ax && nu) {
            c->kind->hessian(x, prm, nu + row0, H);
            for (int k = 0; k < nx * nx; ++k)
                if (sl[k] >= 0)
                    Ax[sl[k]] += s->cscale * H[k];
        }
    }
}

void bk_constraint_accel_rhs(const bk_system *s, const double *q, const double *qd, double t, double *r)
{
    const bk_model *m = s->m;
    const int nx = BK_JOINT_NX;
    for (int c = 0; c < m->nlincon; ++c)
        r[s->nfree + c] = -s->cscale * (2.0 * bk_constraint_row(&m->lincons[c], qd, t, 1, 0)
                                        + bk_constraint_row(&m->lincons[c], q, t, 2, 1));
    double x[BK_JOINT_NX], xd[BK_JOINT_NX], nu[BK_JOINT_MAXROW], H[BK_JOINT_NX * BK_JOINT_NX];
    double prm[BK_JOINT_NPARAM], g[BK_JOINT_MAXROW], G[BK_JOINT_MAXROW * BK_JOINT_NX];
    for (int j = 0; j < m->nnlcon; ++j) {
        const bk_nlcon *c = &m->nlcons[j];
        const int nr = s->jrow[j + 1] - s->jrow[j];
        joint_x(c, q, 0, x);
        joint_x(c, qd, 1, xd);
        bk_joint_params(c, t, 0, prm);
        for (int i = 0; i < nr; ++i) {
            for (int k = 0; k < nr; ++k)
                nu[k] = k == i;
            c->kind->hessian(x, prm, nu, H);
            double v = 0.0;
            for (int a = 0; a < nx; ++a)
                for (int b = 0; b < nx; ++b)
                    v += xd[a] * H[nx * a + b] * xd[b];
            r[s->nfree + s->jrow[j] + i] = -s->cscale * v;
        }
        if (c->kind->driven) {   /* the drive row: + 2 (dG/dt) q' + d2g/dt2 (bk_joint.h) */
            const int last = nr - 1;
            double v = 0.0;
            bk_joint_params(c, t, 1, prm);
            c->kind->eval(x, prm, g, G);
            for (int a = 0; a < nx; ++a)
                v += 2.0 * G[nx * last + a] * xd[a];
            bk_joint_params(c, t, 2, prm);
            c->kind->eval(x, prm, g, G);
            v += g[last];
            r[s->nfree + s->jrow[j] + last] -= s->cscale * v;
        }
    }
}

void bk_constraint_jacobian_row(const bk_system *s, const double *q, double t, int c,
                                void (*add)(void *ctx, int eq, double v), void *ctx)
{
    const bk_model *m = s->m;
    if (c < m->nlincon) {
        const bk_lincon *lc = &m->lincons[c];
        double C, S;
        angle_factors(lc, t, 0, &C, &S);
        for (int k = 0; k < lc->nterm; ++k)
            if (s->eq[lc->dof[k]] >= 0)
                add(ctx, s->eq[lc->dof[k]], lc->c0[k] + lc->cc[k] * C + lc->cs[k] * S);
        return;
    }
    int j = 0;
    while (j + 1 < m->nnlcon && s->jrow[j + 1] <= c)
        ++j;
    const bk_nlcon *jc = &m->nlcons[j];
    double x[BK_JOINT_NX], g[BK_JOINT_MAXROW], G[BK_JOINT_MAXROW * BK_JOINT_NX], prm[BK_JOINT_NPARAM];
    joint_x(jc, q, 0, x);
    bk_joint_params(jc, t, 0, prm);
    jc->kind->eval(x, prm, g, G);
    for (int k = 0; k < BK_JOINT_NX; ++k)
        if (joint_eq(s, jc, k) >= 0)
            add(ctx, joint_eq(s, jc, k), G[BK_JOINT_NX * (c - s->jrow[j]) + k]);
}

int bk_constraint_multipliers(bk_system *s, const double *q, double t, const double *r, double *nu)
{
    if (s->ncon == 0)
        return 0;
    double *Ax = calloc((size_t)(s->nnz ? s->nnz : 1), sizeof *Ax);
    double *b = calloc((size_t)s->neq, sizeof *b);
    bk_linsolver ls = {0};
    int rc = -1;
    if (!Ax || !b)
        goto out;
    /* [c I  s G^T; s G  0] [x; dnu] = [-r; 0]: x = -(r + s G^T dnu)/c with G x = 0 */
    for (int j = 0; j < s->nfree; ++j)
        if (s->diag[j] >= 0)
            Ax[s->diag[j]] = s->cscale;
    bk_assemble_constraints(s, q, NULL, t, NULL, Ax);
    for (int j = 0; j < s->nfree; ++j)
        b[j] = -r[j];
    if (bk_lin_init(&ls, s->neq, s->Ap, s->Ai) != BK_LIN_OK || bk_lin_factor(&ls, Ax) != BK_LIN_OK ||
        ls.rcond < 1e-12 || bk_lin_solve(&ls, b) != BK_LIN_OK)
        goto out;
    for (int c = 0; c < s->ncon; ++c)
        if (!isfinite(b[s->nfree + c]))
            goto out;
    for (int c = 0; c < s->ncon; ++c)
        nu[c] += b[s->nfree + c];
    rc = 0;
out:
    bk_lin_free(&ls);
    free(Ax);
    free(b);
    return rc;
}

void bk_constraint_hessian(const bk_system *s, const double *q, double t, const double *lam,
                           void (*add)(void *ctx, int i, int j, double v), void *ctx)
{
    const int nx = BK_JOINT_NX;
    double x[BK_JOINT_NX], H[BK_JOINT_NX * BK_JOINT_NX], prm[BK_JOINT_NPARAM];
    for (int j = 0; j < s->m->nnlcon; ++j) {
        const bk_nlcon *c = &s->m->nlcons[j];
        joint_x(c, q, 0, x);
        bk_joint_params(c, t, 0, prm);
        c->kind->hessian(x, prm, lam + s->jrow[j], H);
        for (int a = 0; a < nx; ++a)
            for (int b = 0; b < nx; ++b)
                if (joint_eq(s, c, a) >= 0 && joint_eq(s, c, b) >= 0 && H[nx * a + b] != 0.0)
                    add(ctx, joint_eq(s, c, a), joint_eq(s, c, b), H[nx * a + b]);
    }
}

void bk_assemble_constraints(const bk_system *s, const double *q, const double *nu, double t,
                             double *r, double *Ax)
{
    const bk_model *m = s->m;
    for (int c = 0; c < m->nlincon; ++c) {
        const bk_lincon *lc = &m->lincons[c];
        const int *sl = s->cslot + s->cslot_off[c];
        double C, S;
        angle_factors(lc, t, 0, &C, &S);
        double g = -(lc->r0 + lc->rc * C + lc->rs * S) - motion_rhs(lc, t, 0);
        for (int k = 0; k < lc->nterm; ++k) {
            double coef = lc->c0[k] + lc->cc[k] * C + lc->cs[k] * S;
            g += coef * q[lc->dof[k]];
            int qe = s->eq[lc->dof[k]];
            if (qe >= 0 && r)
                r[qe] += s->cscale * coef * nu[c];
            if (Ax && sl[2 * k] >= 0) {
                Ax[sl[2 * k]] += s->cscale * coef;
                Ax[sl[2 * k + 1]] += s->cscale * coef;
            }
        }
        if (r)
            r[s->nfree + c] = s->cscale * g;
    }
    assemble_joints(s, q, nu, t, r, Ax);
}

double bk_constraint_coef(const bk_lincon *c, int k, double t)
{
    double C, S;
    angle_factors(c, t, 0, &C, &S);
    return c->c0[k] + c->cc[k] * C + c->cs[k] * S;
}

double bk_constraint_residual(const bk_system *s, const double *q, double t)
{
    double worst = 0.0;
    for (int c = 0; c < s->m->nlincon; ++c)
        worst = fmax(worst, fabs(bk_constraint_row(&s->m->lincons[c], q, t, 0, 1)));
    double x[BK_JOINT_NX], g[BK_JOINT_MAXROW], G[BK_JOINT_MAXROW * BK_JOINT_NX], prm[BK_JOINT_NPARAM];
    for (int j = 0; j < s->m->nnlcon; ++j) {
        const bk_nlcon *c = &s->m->nlcons[j];
        joint_x(c, q, 0, x);
        bk_joint_params(c, t, 0, prm);
        c->kind->eval(x, prm, g, G);
        for (int i = 0; i < c->kind->nrow; ++i)
            worst = fmax(worst, fabs(g[i]));
    }
    return worst;
}


int bk_constraints_nonlinear(const bk_system *s)
{
    return s->m->nnlcon;
}

int bk_constraints_on_path(const bk_system *s)
{
    const bk_model *m = s->m;
    for (int c = 0; c < m->nlincon; ++c) {
        const bk_lincon *lc = &m->lincons[c];
        if (lc->kappa == 0.0 || (lc->rate == 0.0 && lc->amp == 0.0 && !lc->ampl))
            continue;                    /* the angle is constant: so are the coefficients */
        for (int k = 0; k < lc->nterm; ++k)
            if (lc->cc[k] != 0.0 || lc->cs[k] != 0.0)
                return 1;
    }
    return 0;
}
