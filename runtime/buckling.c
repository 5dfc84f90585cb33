/* buckling.c -- linear (eigen)buckling: the critical load factors of the
 * scene's loads and their mode shapes (scene.analysis = "buckling").
 *
 * Owns the base state, the prebuckling path, the dense reduced matrices and
 * their eigenproblem.  May call: assembly (system.h, loads.h), the static solve
 * (newton.h) for a preloaded base state, quaternion.h, GSL's dense linear
 * algebra, and the output's frame and mode writers (output.h).
 *
 * The loads are linear in the load factor x on [x0, x0 + 1]: x0 = 0 about the
 * reference state; x0 = 1 about the static equilibrium under the preloads
 * (gen/scene/buckling.py: preloads constant beyond 1, the scaled loads zero at
 * 1 and at their value at 2).  With R(q, x) = f_int(q) - Q(q, x) (every load,
 * follower and configuration-dependent ones included) and a factor mu of the
 * scaled loads, R(q, mu) = (1 - mu) R(q, x0) + mu R(q, x0 + 1), T = dR/dq.
 * About the base state q0, K0 = T(q0, 0), the prebuckling path is
 * q(mu) = q0 + mu u + mu^2 w / 2 (quaternions kept at unit length), with
 *     K0 u = F = -dR/dmu,   K0 w = -d2/dmu2 R(q0 + mu u, mu),
 * and the tangent along it T(q(mu), mu) = K0 + mu K1 + mu^2 K2 (central
 * differences of three assembled tangents, h max|u| = 1e-4 of the model
 * length, at most 1e-4).  The factors solve
 *     (K0 + lam K1 + lam^2 K2) phi = 0
 * on the free DOFs and the null space Z of the linear constraints and of the
 * quaternions' gauge (GSL QR of the rows' transpose, as modal.c): with
 * A = Z^T K0 Z, B = Z^T K1 Z, C = Z^T K2 Z and nu = 1/lam,
 *     nu [phi; psi] = [0, I; -A^{-1} C, -A^{-1} B] [phi; psi]
 * (GSL, nonsymmetric: multipliers of euler_bernoulli, kirchhoff, followers).
 * Without K2 the change of the elastic stiffness along u in K1 moves the
 * factor of a symmetric bifurcation at second order unbalanced: the strip's
 * lateral-torsional factor is 8.80 N so, 11.48 N with K2 (closed form 11.47).
 * Reported: the `modes` real factors of least magnitude (|Im nu| <= 1e-6
 * |nu|; |nu| >= 1e-8 max |nu|), positive ones first in ascending order, then
 * negative ones by increasing magnitude (the loads reversed buckle at |lam|).
 * Dense: meant for small models.  Joints nonlinear in q are refused.
 */
#include "buckling.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "loads.h"
#include "newton.h"
#include "quaternion.h"

#define BK_BUCKLING_MAXDOF 1000    /* the companion matrix is twice that */
#define BK_BUCKLING_STEP 1e-4      /* h max|u| relative to the model length (at most 1 m) */
#define BK_BUCKLING_IMAG 1e-6      /* |Im nu| / |nu| of a real factor */
#define BK_BUCKLING_RANGE 1e-8     /* smallest |nu| / max |nu| reported */

/* The work of one analysis, freed by work_free. */
typedef struct work {
    int nz, nquat;
    int *quat;                                   /* first DOF of each free nodal quaternion */
    double *f, *g, *r, *fext, *u, *w, *qp, *phi, *Ax; /* [ndof] each, Ax [nnz] */
    gsl_matrix *K0, *K1, *K2, *Z, *T, *A, *B, *C;
    gsl_vector *b, *y;
    gsl_permutation *perm;
} work;

static void work_free(work *w)
{
    free(w->quat), free(w->f), free(w->g), free(w->r), free(w->fext), free(w->u), free(w->w), free(w->qp);
    free(w->phi), free(w->Ax);
    gsl_matrix_free(w->K0), gsl_matrix_free(w->K1), gsl_matrix_free(w->K2), gsl_matrix_free(w->Z);
    gsl_matrix_free(w->T), gsl_matrix_free(w->A), gsl_matrix_free(w->B), gsl_matrix_free(w->C);
    gsl_vector_free(w->b), gsl_vector_free(w->y);
    gsl_permutation_free(w->perm);
}

/* R(q, x) into f[ndof] and its tangent into Ax (the Newton matrix's K block;
 * the constraint slots stay zero).  -1 on a non-finite internal force. */
static int residual_at(bk_system *s, const double *q, double x, const double *fext, double *f, double *Ax)
{
    if (bk_assemble_internal(s, q, f, Ax) != 0)
        return -1;
    bk_assemble_follower(s, q, x, f, Ax);
    bk_assemble_loads(s, q, x, f, Ax);
    for (int i = 0; i < s->m->ndof; ++i)
        f[i] -= x * fext[i];
    return 0;
}

/* D += c Ax on the free rows and columns. */
static void add_dense(const bk_system *s, const double *Ax, double c, gsl_matrix *D)
{
    for (int j = 0; j < s->nfree; ++j)
        for (int k = s->Ap[j]; k < s->Ap[j + 1]; ++k)
            if (s->Ai[k] < s->nfree)
                *gsl_matrix_ptr(D, (size_t)s->Ai[k], (size_t)j) += c * Ax[k];
}

/* R(q, mu) into f[ndof]; D1 += c1 T(q, mu) and D2 += c2 T(q, mu) (D2 may be
 * NULL).  -1 on a non-finite internal force. */
static int eval(bk_system *s, work *w, const double *q, double x0, double mu, double *f, gsl_matrix *D1,
                double c1, gsl_matrix *D2, double c2)
{
    if (residual_at(s, q, x0, w->fext, w->g, w->Ax) != 0)
        return -1;
    add_dense(s, w->Ax, c1 * (1.0 - mu), D1);
    if (D2)
        add_dense(s, w->Ax, c2 * (1.0 - mu), D2);
    if (residual_at(s, q, x0 + 1.0, w->fext, f, w->Ax) != 0)
        return -1;
    add_dense(s, w->Ax, c1 * mu, D1);
    if (D2)
        add_dense(s, w->Ax, c2 * mu, D2);
    for (int i = 0; i < s->m->ndof; ++i)
        f[i] = (1.0 - mu) * w->g[i] + mu * f[i];
    return 0;
}

/* w->qp = q0 + mu u + mu^2 w / 2 (with_w), quaternions at unit length. */
static void path(const bk_model *m, work *w, const double *q0, double mu, int with_w)
{
    for (int i = 0; i < m->ndof; ++i)
        w->qp[i] = q0[i] + mu * w->u[i] + (with_w ? 0.5 * mu * mu * w->w[i] : 0.0);
    bk_quat_normalize(w->quat, w->nquat, w->qp, NULL, 0);
}

typedef struct gt_col {
    gsl_matrix *GT;
    int c;
} gt_col;

static void gt_add(void *ctx, int eq, double v)
{
    gt_col *g = ctx;
    *gsl_matrix_ptr(g->GT, (size_t)eq, (size_t)g->c) += v;
}

/* w->Z: an orthonormal basis of the null space at (q, x) of the linear
 * constraints and of the gauge of each free nodal quaternion p, p . dp = 0
 * (NULL when there are none: the identity); w->nz its dimension. */
static int null_space(bk_system *s, work *w, const double *q, double x, char *msg, size_t nmsg)
{
    int n = s->nfree, ncon = s->ncon, nc = ncon + w->nquat, r = 0;
    w->nz = n;
    if (nc == 0)
        return 0;
    int mn = n < nc ? n : nc;
    gsl_matrix *GT = gsl_matrix_calloc((size_t)n, (size_t)nc), *Q = gsl_matrix_alloc((size_t)n, (size_t)n);
    gsl_matrix *R = gsl_matrix_alloc((size_t)n, (size_t)nc);
    gsl_vector *tau = gsl_vector_alloc((size_t)mn);
    if (!GT || !Q || !R || !tau) {
        snprintf(msg, nmsg, "out of memory for the constraints' null space");
        r = -1;
        goto done;
    }
    for (int c = 0; c < ncon; ++c) {
        gt_col col = {GT, c};
        bk_constraint_jacobian_row(s, q, x, c, gt_add, &col);
    }
    for (int k = 0; k < w->nquat; ++k)
        for (int j = 0; j < 4; ++j)
            gsl_matrix_set(GT, (size_t)s->eq[w->quat[k] + j], (size_t)(ncon + k), q[w->quat[k] + j]);
    gsl_linalg_QR_decomp(GT, tau);
    double rmax = 0.0;
    for (int i = 0; i < mn; ++i)
        rmax = fmax(rmax, fabs(gsl_matrix_get(GT, i, i)));
    for (int i = 0; i < mn; ++i)
        if (fabs(gsl_matrix_get(GT, i, i)) > 1e-12 * rmax)
            r++;
    w->nz = n - r;
    if (w->nz <= 0) {
        snprintf(msg, nmsg, "the constraints leave no free motion");
        r = -1;
        goto done;
    }
    gsl_linalg_QR_unpack(GT, tau, Q, R);
    if (!(w->Z = gsl_matrix_alloc((size_t)n, (size_t)w->nz))) {
        snprintf(msg, nmsg, "out of memory for the constraints' null space");
        r = -1;
        goto done;
    }
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < w->nz; ++j)
            gsl_matrix_set(w->Z, i, j, gsl_matrix_get(Q, i, r + j));
    r = 0;
done:
    gsl_matrix_free(GT), gsl_matrix_free(Q), gsl_matrix_free(R), gsl_vector_free(tau);
    return r;
}

/* out = Z^T D Z (out = D without Z). */
static void reduce(work *w, const gsl_matrix *D, gsl_matrix *out)
{
    if (!w->Z) {
        gsl_matrix_memcpy(out, D);
        return;
    }
    gsl_blas_dgemm(CblasNoTrans, CblasNoTrans, 1.0, D, w->Z, 0.0, w->T);
    gsl_blas_dgemm(CblasTrans, CblasNoTrans, 1.0, w->Z, w->T, 0.0, out);
}

/* x[ndof] (fixed DOFs 0) from the reduced vector v[nz] (stride). */
static void expand(const bk_system *s, const work *w, const double *v, size_t stride, double *x)
{
    for (int i = 0; i < s->m->ndof; ++i) {
        int j = s->eq[i];
        double a = 0.0;
        if (j >= 0 && w->Z)
            for (int c = 0; c < w->nz; ++c)
                a += gsl_matrix_get(w->Z, j, c) * v[c * stride];
        else if (j >= 0)
            a = v[j * stride];
        x[i] = a;
    }
}

/* x[ndof] = c Z A^{-1} Z^T f (f over all DOFs; A holds its LU factors). */
static void solve(const bk_system *s, work *w, const double *f, double c, double *x)
{
    for (int i = 0; i < s->m->ndof; ++i)
        if (s->eq[i] >= 0)
            gsl_vector_set(w->b, (size_t)s->eq[i], c * f[i]);
    if (w->Z)
        gsl_blas_dgemv(CblasTrans, 1.0, w->Z, w->b, 0.0, w->y);
    else
        gsl_vector_memcpy(w->y, w->b);
    gsl_linalg_LU_svx(w->A, w->perm, w->y);
    expand(s, w, w->y->data, w->y->stride, x);
}

typedef struct factor {
    double lam;
    int k;
} factor;

static int by_magnitude(const void *a, const void *b)
{
    double x = fabs(((const factor *)a)->lam), y = fabs(((const factor *)b)->lam);
    return (x > y) - (x < y);
}

/* positive factors ascending, then negative ones by increasing magnitude */
static int by_report_order(const void *a, const void *b)
{
    double x = ((const factor *)a)->lam, y = ((const factor *)b)->lam;
    if ((x > 0.0) != (y > 0.0))
        return x > 0.0 ? -1 : 1;
    return (fabs(x) > fabs(y)) - (fabs(x) < fabs(y));
}

/* The base state: the reference (x0 = 0, step 0 of the output) or the static
 * equilibrium under the preloads (x0 = 1, the static load steps). */
static int base_state(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log, double *x0)
{
    const bk_model *m = s->m;
    *x0 = 0.0;
    if (!m->modal.about_static) {
        memcpy(q, m->q0, (size_t)m->ndof * sizeof *q);
        bk_output_step(out, 0, 0.0, q);
        return 0;
    }
    bk_run_info sinfo = {0};
    int st = bk_solve_static(s, q, out, &sinfo, log);
    bk_output_last_frame(out, sinfo.steps, sinfo.load_factor, q);
    info->newton_iterations = sinfo.newton_iterations;
    info->cutbacks = sinfo.cutbacks;
    info->factorizations = sinfo.factorizations;
    info->load_factor = sinfo.load_factor;
    for (int k = 0; k < sinfo.nwarning; ++k)            /* already printed by the static solve */
        bk_warn(info, NULL, m->name, "preloaded state: %s", sinfo.warnings[k]);
    if (st != 0) {
        snprintf(info->message, sizeof info->message, "preloaded state for the buckling analysis: %.900s",
                 sinfo.message);
        info->interrupted = sinfo.interrupted;
        return -1;
    }
    *x0 = 1.0;
    return 0;
}

/* The quadratic eigenproblem through its companion matrix, and the output of
 * the modes.  A holds the LU factors of Z^T K0 Z; B, C are overwritten. */
static int modes(bk_system *s, work *w, const double *q, bk_output *out, bk_run_info *info, FILE *log)
{
    const bk_model *m = s->m;
    int nz = w->nz, n2 = 2 * nz, rc = -1;
    gsl_matrix *E = gsl_matrix_calloc((size_t)n2, (size_t)n2);
    gsl_vector_complex *nu = gsl_vector_complex_alloc((size_t)n2);
    gsl_matrix_complex *V = gsl_matrix_complex_alloc((size_t)n2, (size_t)n2);
    gsl_eigen_nonsymmv_workspace *ws = gsl_eigen_nonsymmv_alloc((size_t)n2);
    factor *fac = malloc((size_t)n2 * sizeof *fac);
    double *v = malloc((size_t)nz * sizeof *v);
    if (!E || !nu || !V || !ws || !fac || !v) {
        snprintf(info->message, sizeof info->message, "out of memory for the buckling eigenproblem");
        goto done;
    }
    for (int j = 0; j < nz; ++j) {                   /* B <- A^{-1} B, C <- A^{-1} C */
        gsl_vector_view cb = gsl_matrix_column(w->B, (size_t)j), cc = gsl_matrix_column(w->C, (size_t)j);
        gsl_linalg_LU_svx(w->A, w->perm, &cb.vector);
        gsl_linalg_LU_svx(w->A, w->perm, &cc.vector);
    }
    for (int i = 0; i < nz; ++i) {
        gsl_matrix_set(E, (size_t)i, (size_t)(nz + i), 1.0);
        for (int j = 0; j < nz; ++j) {
            gsl_matrix_set(E, (size_t)(nz + i), (size_t)j, -gsl_matrix_get(w->C, i, j));
            gsl_matrix_set(E, (size_t)(nz + i), (size_t)(nz + j), -gsl_matrix_get(w->B, i, j));
        }
    }
    if (gsl_eigen_nonsymmv(E, nu, V, ws) != 0) {
        snprintf(info->message, sizeof info->message, "the buckling eigenproblem did not converge");
        goto done;
    }
    double numax = 0.0;
    for (int k = 0; k < n2; ++k)
        numax = fmax(numax, gsl_complex_abs(gsl_vector_complex_get(nu, (size_t)k)));
    int nf = 0, ncomplex = 0;
    double cmax = 0.0;                               /* the largest |nu| of a complex pair */
    for (int k = 0; k < n2; ++k) {
        gsl_complex z = gsl_vector_complex_get(nu, (size_t)k);
        double a = gsl_complex_abs(z);
        if (!(a >= BK_BUCKLING_RANGE * numax) || a == 0.0)
            continue;                                /* no buckling along it (lam beyond the range) */
        if (fabs(GSL_IMAG(z)) > BK_BUCKLING_IMAG * a) {
            ncomplex++, cmax = fmax(cmax, a);
            continue;
        }
        fac[nf].lam = 1.0 / GSL_REAL(z);
        fac[nf++].k = k;
    }
    qsort(fac, (size_t)nf, sizeof *fac, by_magnitude);
    if (cmax > 0.0 && (nf == 0 || 1.0 / cmax < fabs(fac[0].lam)))
        bk_warn(info, out->console, m->name, "complex critical factors from |lam| = %.6g on, below every real "
                "one: the loads are not conservative (follower loads); flutter is beyond a buckling analysis",
                1.0 / cmax);
    if (nf == 0) {
        snprintf(info->message, sizeof info->message,
                 "no buckling: no real critical factor (no compression, no moment, or non-conservative loads)");
        goto done;
    }
    int want = nf < m->modal.nmodes ? nf : m->modal.nmodes;
    qsort(fac, (size_t)want, sizeof *fac, by_report_order);
    if (bk_output_modes_begin(out, info->message, sizeof info->message) != 0)
        goto done;
    for (int r = 0; r < want; ++r) {
        double n2r = 0.0;
        for (int c = 0; c < nz; ++c)
            v[c] = GSL_REAL(gsl_matrix_complex_get(V, (size_t)c, (size_t)fac[r].k)), n2r += v[c] * v[c];
        if (n2r == 0.0)                              /* (a real vector scaled by i) */
            for (int c = 0; c < nz; ++c)
                v[c] = GSL_IMAG(gsl_matrix_complex_get(V, (size_t)c, (size_t)fac[r].k));
        expand(s, w, v, 1, w->phi);
        bk_output_mode(out, r + 1, fac[r].lam, fac[r].lam, q, w->phi);
        if (log)
            fprintf(log, "  buckling mode %d: load factor %.9g (%d complex dropped)\n", r + 1, fac[r].lam,
                    ncomplex);
    }
    info->steps = want;
    rc = 0;
done:
    gsl_matrix_free(E);
    gsl_vector_complex_free(nu);
    gsl_matrix_complex_free(V);
    if (ws)
        gsl_eigen_nonsymmv_free(ws);
    free(fac);
    free(v);
    return rc;
}

static int alloc_work(const bk_system *s, work *w)
{
    size_t nd = (size_t)s->m->ndof, n = (size_t)s->nfree;
    w->quat = bk_quat_list(s, &w->nquat);
    w->f = calloc(nd, sizeof *w->f), w->g = calloc(nd, sizeof *w->g), w->r = calloc(nd, sizeof *w->r);
    w->fext = calloc(nd, sizeof *w->fext), w->u = calloc(nd, sizeof *w->u), w->w = calloc(nd, sizeof *w->w);
    w->qp = calloc(nd, sizeof *w->qp), w->phi = calloc(nd, sizeof *w->phi);
    w->Ax = calloc((size_t)s->nnz, sizeof *w->Ax);
    w->K0 = gsl_matrix_calloc(n, n), w->K1 = gsl_matrix_calloc(n, n), w->K2 = gsl_matrix_calloc(n, n);
    w->b = gsl_vector_calloc(n);
    int ok = w->nquat >= 0 && w->f && w->g && w->r && w->fext && w->u && w->w && w->qp && w->phi && w->Ax;
    return ok && w->K0 && w->K1 && w->K2 && w->b ? 0 : -1;
}

static int alloc_reduced(const bk_system *s, work *w)
{
    size_t nz = (size_t)w->nz;
    w->A = gsl_matrix_alloc(nz, nz), w->B = gsl_matrix_alloc(nz, nz), w->C = gsl_matrix_alloc(nz, nz);
    w->T = w->Z ? gsl_matrix_alloc((size_t)s->nfree, nz) : NULL;
    w->y = gsl_vector_alloc(nz);
    w->perm = gsl_permutation_alloc(nz);
    return w->A && w->B && w->C && (!w->Z || w->T) && w->y && w->perm ? 0 : -1;
}

int bk_solve_buckling(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log)
{
    const bk_model *m = s->m;
    int n = s->nfree, nd = m->ndof, rc = 1;
    work w = {0};
    double x0 = 0.0;
    if (n == 0) {
        snprintf(info->message, sizeof info->message, "every DOF is fixed: nothing can buckle");
        return 1;
    }
    if (n > BK_BUCKLING_MAXDOF) {
        snprintf(info->message, sizeof info->message,
                 "buckling analysis is dense and limited to %d free DOFs; this model has %d", BK_BUCKLING_MAXDOF, n);
        return 1;
    }
    if (m->nnlcon > 0) {
        snprintf(info->message, sizeof info->message,
                 "buckling analysis takes linear constraints only (clamps, joints of beam nodes to the ground, "
                 "rigid joints of rod nodes); this model has %d joint%s nonlinear in q", m->nnlcon,
                 m->nnlcon == 1 ? "" : "s");
        return 1;
    }
    if (base_state(s, q, out, info, log, &x0) != 0)
        return 1;
    gsl_set_error_handler_off();
    if (alloc_work(s, &w) != 0) {
        snprintf(info->message, sizeof info->message, "out of memory for the dense buckling matrices");
        goto done;
    }
    bk_external_load(s, w.fext);
    /* K0, R(q0, 0) and the load F = R(q0, 0) - R(q0, 1) of the scaled loads */
    if (eval(s, &w, q, x0, 0.0, w.r, w.K0, 1.0, NULL, 0.0) != 0 || eval(s, &w, q, x0, 1.0, w.f, w.K1, 0.0, NULL, 0.0))
        goto nonfinite;
    double fmax_ = 0.0;
    for (int i = 0; i < nd; ++i)
        if (s->eq[i] >= 0)
            fmax_ = fmax(fmax_, fabs(w.r[i] - w.f[i]));
    if (!(fmax_ > 0.0)) {
        snprintf(info->message, sizeof info->message,
                 "no load to scale: the loads of the buckling analysis do not act on the free DOFs");
        goto done;
    }
    for (int i = 0; i < nd; ++i)
        w.f[i] = w.r[i] - w.f[i];
    if (null_space(s, &w, q, x0, info->message, sizeof info->message) != 0)
        goto done;
    if (alloc_reduced(s, &w) != 0) {
        snprintf(info->message, sizeof info->message, "out of memory for the dense buckling matrices");
        goto done;
    }
    /* A = Z^T K0 Z (LU), u = Z A^{-1} Z^T F */
    reduce(&w, w.K0, w.A);
    int signum;
    gsl_linalg_LU_decomp(w.A, w.perm, &signum);
    double pmin = INFINITY, pmax = 0.0;
    for (int i = 0; i < w.nz; ++i) {
        double d = fabs(gsl_matrix_get(w.A, i, i));
        pmin = fmin(pmin, d), pmax = fmax(pmax, d);
    }
    if (!(pmin > 1e-13 * pmax)) {
        snprintf(info->message, sizeof info->message,
                 "the tangent at the %s state is singular (pivot ratio %.1e): a rigid motion or mechanism the "
                 "constraints leave free (e.g. a beam's rotation about its own axis), or the preloads are "
                 "critical", x0 > 0.0 ? "preloaded" : "reference", pmax > 0.0 ? pmin / pmax : 0.0);
        goto done;
    }
    solve(s, &w, w.f, 1.0, w.u);
    double umax = 0.0;
    for (int i = 0; i < nd; ++i)
        umax = fmax(umax, fabs(w.u[i]));
    if (!(umax > 0.0) || !isfinite(umax)) {
        snprintf(info->message, sizeof info->message, "the prebuckling displacement is %s",
                 isfinite(umax) ? "zero" : "not finite");
        goto done;
    }
    /* w = -Z A^{-1} Z^T d2/dmu2 R(q0 + mu u, mu); then K1, K2 along q(mu) */
    double h = BK_BUCKLING_STEP * fmin(m->length_scale, 1.0) / umax;
    memset(w.f, 0, (size_t)nd * sizeof *w.f);
    for (int sg = -1; sg <= 1; sg += 2) {
        path(m, &w, q, sg * h, 0);
        if (eval(s, &w, w.qp, x0, sg * h, w.phi, w.K1, 0.0, NULL, 0.0) != 0)
            goto nonfinite;
        for (int i = 0; i < nd; ++i)
            w.f[i] += (w.phi[i] - w.r[i]) / (h * h);
    }
    solve(s, &w, w.f, -1.0, w.w);
    gsl_matrix_set_zero(w.K1);
    gsl_matrix_memcpy(w.K2, w.K0);
    gsl_matrix_scale(w.K2, -1.0 / (h * h));
    for (int sg = -1; sg <= 1; sg += 2) {
        path(m, &w, q, sg * h, 1);
        if (eval(s, &w, w.qp, x0, sg * h, w.phi, w.K1, sg / (2.0 * h), w.K2, 1.0 / (2.0 * h * h)) != 0)
            goto nonfinite;
    }
    reduce(&w, w.K1, w.B);
    reduce(&w, w.K2, w.C);
    if (modes(s, &w, q, out, info, log) != 0)
        goto done;
    if (log)
        fprintf(log, "  %d free DOFs, null space %d, h = %.3e\n", n, w.nz, h);
    rc = 0;
    goto done;
nonfinite:
    snprintf(info->message, sizeof info->message, "non-finite internal force at or near the base state");
done:
    info->converged = rc == 0;
    work_free(&w);
    return rc;
}
