/* buckling.c -- linear (eigen)buckling: the critical load factors of the
 * scene's loads and their mode shapes (scene.analysis = "buckling").
 *
 * Owns the base state, the prebuckling path, the dense reduced matrices and
 * their eigenproblem.  May call: assembly (system.h, the interactions), the
 * static solve (static.h) for a preloaded base state, quaternion.h, GSL's dense linear
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
#include "analysis/analysis.h"
#include "analysis/buckling.h"
#include "analysis/buckling_impl.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/static.h"
#include "assembly/quaternion.h"

#define BK_BUCKLING_MAXDOF 1000    /* the companion matrix is twice that */
#define BK_BUCKLING_STEP 1e-4      /* h max|u| relative to the model length (at most 1 m) */
#define BK_BUCKLING_IMAG 1e-6      /* |Im nu| / |nu| of a real factor */
#define BK_BUCKLING_RANGE 1e-8     /* smallest |nu| / max |nu| reported */

/* R(q, x) into f[ndof] and its tangent into Ax (the Newton matrix's K block;
 * the constraint slots stay zero).  -1 on a non-finite internal force. */
static int residual_at(bk_system *s, const double *q, double x, const double *fext, double *f, double *Ax)
{
    if (bk_assemble_internal(s, q, f, Ax) != 0)
        return -1;
    if (bk_assemble_interactions(s, q, &(bk_path){.factor = x, .x = x}, f, Ax) != 0)
        return -1;
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

/* A real critical factor and its eigenvector's column. */
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
    if (m->modal.about != BK_ABOUT_STATIC) {
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
    bk_run_info_free(&sinfo);
    if (st != 0) {
        snprintf(info->message, sizeof info->message, "preloaded state for the buckling analysis: %.900s",
                 sinfo.message);
        info->interrupted = sinfo.interrupted;
        return -1;
    }
    *x0 = 1.0;
    return 0;
}

/* The factors reported (summary.json buckling.load_factors: the modes'). */
#define BK_REPORTED 64
typedef struct reported {
    double lam[BK_REPORTED];
    int n;
} reported;

/* The quadratic eigenproblem through its companion matrix, and the output of
 * the modes.  A holds the LU factors of Z^T K0 Z; B, C are overwritten. */
static int modes(bk_system *s, work *w, const double *q, bk_output *out, bk_run_info *info, FILE *log,
                 reported *rep)
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
    int want = nf < m->modal.modes ? nf : m->modal.modes;
    qsort(fac, (size_t)want, sizeof *fac, by_report_order);
    static const bk_table_spec modes_csv = BK_TABLE("modes.csv", "buckling", "mode,load_factor,scale_m\n");
    static const bk_table_spec mode_sensors_csv =
        BK_TABLE("mode_sensors.csv", "buckling",
                 "mode,load_factor,sensor,x,y,z,dx,dy,dz,shape_x,shape_y,shape_z\n");
    if (bk_output_modes_begin(out, &modes_csv, &mode_sensors_csv, info->message, sizeof info->message) != 0)
        goto done;
    for (int r = 0; r < want; ++r) {
        double n2r = 0.0;
        for (int c = 0; c < nz; ++c)
            v[c] = GSL_REAL(gsl_matrix_complex_get(V, (size_t)c, (size_t)fac[r].k)), n2r += v[c] * v[c];
        if (n2r == 0.0)                              /* (a real vector scaled by i) */
            for (int c = 0; c < nz; ++c)
                v[c] = GSL_IMAG(gsl_matrix_complex_get(V, (size_t)c, (size_t)fac[r].k));
        bk_bw_expand(s, w, v, 1, w->phi);
        bk_output_mode(out, r + 1, &fac[r].lam, q, w->phi);
        if (rep->n < BK_REPORTED)
            rep->lam[rep->n++] = fac[r].lam;
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


static int buckling(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log, reported *rep)
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
    const int njoint = bk_constraints_nonlinear(s);
    if (njoint > 0) {
        snprintf(info->message, sizeof info->message,
                 "buckling analysis takes linear constraints only (clamps, joints of beam nodes to the ground, "
                 "rigid joints of rod nodes); this model has %d joint%s nonlinear in q", njoint,
                 njoint == 1 ? "" : "s");
        return 1;
    }
    if (base_state(s, q, out, info, log, &x0) != 0)
        return 1;
    gsl_set_error_handler_off();
    if (bk_bw_alloc_work(s, &w) != 0) {
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
    if (bk_bw_null_space(s, &w, q, x0, info->message, sizeof info->message) != 0)
        goto done;
    if (bk_bw_alloc_reduced(s, &w) != 0) {
        snprintf(info->message, sizeof info->message, "out of memory for the dense buckling matrices");
        goto done;
    }
    /* A = Z^T K0 Z (LU), u = Z A^{-1} Z^T F */
    bk_bw_reduce(&w, w.K0, w.A);
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
    bk_bw_solve(s, &w, w.f, 1.0, w.u);
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
    bk_bw_solve(s, &w, w.f, -1.0, w.w);
    gsl_matrix_set_zero(w.K1);
    gsl_matrix_memcpy(w.K2, w.K0);
    gsl_matrix_scale(w.K2, -1.0 / (h * h));
    for (int sg = -1; sg <= 1; sg += 2) {
        path(m, &w, q, sg * h, 1);
        if (eval(s, &w, w.qp, x0, sg * h, w.phi, w.K1, sg / (2.0 * h), w.K2, 1.0 / (2.0 * h * h)) != 0)
            goto nonfinite;
    }
    bk_bw_reduce(&w, w.K1, w.B);
    bk_bw_reduce(&w, w.K2, w.C);
    if (modes(s, &w, q, out, info, log, rep) != 0)
        goto done;
    if (log)
        fprintf(log, "  %d free DOFs, null space %d, h = %.3e\n", n, w.nz, h);
    rc = 0;
    goto done;
nonfinite:
    snprintf(info->message, sizeof info->message, "non-finite internal force at or near the base state");
done:
    info->converged = rc == 0;
    bk_bw_work_free(&w);
    return rc;
}

int bk_solve_buckling(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log)
{
    reported rep = {.n = 0};
    int rc = buckling(s, q, out, info, log, &rep);
    /* summary.json "buckling": about what, the factors, the critical one (null: none positive) */
    char text[BK_REPORTED * 26 + 128];
    int len = snprintf(text, sizeof text, "{\"about\": \"%s\", \"load_factors\": [",
                       s->m->modal.about == BK_ABOUT_STATIC ? "preloaded" : "reference");
    for (int k = 0; k < rep.n; ++k)
        len += snprintf(text + len, sizeof text - (size_t)len, "%s%.17g", k ? ", " : "", rep.lam[k]);
    if (rep.n > 0 && rep.lam[0] > 0.0 && isfinite(rep.lam[0]))
        snprintf(text + len, sizeof text - (size_t)len, "], \"critical_load_factor\": %.17g}", rep.lam[0]);
    else
        snprintf(text + len, sizeof text - (size_t)len, "], \"critical_load_factor\": null}");
    if (bk_run_summary(info, "buckling", text) != 0 && rc == 0) {
        snprintf(info->message, sizeof info->message, "out of memory");
        rc = 1;
    }
    return rc;
}

static int runs_buckling(const bk_model *m)
{
    return m->analysis == BK_ANALYSIS_BUCKLING;
}

/* Its modes (and the preload's static steps' frames). */
static void plan_buckling(const bk_model *m, bk_output_plan *p)
{
    p->room = m->stat.load_steps * (1 + 2 * m->stat.cycles) + 4;
    p->modes = m->modal.modes;
}

const bk_analysis_module bk_analysis_buckling = {"buckling", runs_buckling, bk_solve_buckling, plan_buckling};
