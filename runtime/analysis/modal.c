/* modal.c -- natural frequencies and mode shapes of the linearized system.
 *
 * About the reference state (or the static equilibrium under the scene's loads,
 * modal.about = "static"), the tangent K and the mass M (constant part plus the
 * rotary inertia of beams with nodal rotations) are restricted to the free DOFs
 * and to the null space Z of the linear constraints G (GSL QR of G^T):
 *     K_r = Z^T K Z,  M_r = Z^T M Z,
 * and the dense symmetric-definite problem M_r x = mu (K_r + sigma M_r) x is
 * solved with GSL (gsl_eigen_gensymmv); omega^2 = 1/mu - sigma.  The shift
 * sigma makes the right-hand matrix definite for free structures (rigid modes
 * have omega = 0) and massless directions (quaternion scale) give mu = 0, i.e.
 * infinite frequency, and are dropped.  Dense: meant for small models; above
 * BK_MODAL_MAXDOF free DOFs (or with modal.solver = "sparse") the lowest modes
 * come from shift-invert Lanczos on the sparse Newton matrix instead
 * (modal_sparse.c).
 *
 * Output: the state the modes are about goes to sensors.csv and step_*.vtu (the
 * static load steps, or the reference as step 0); each mode to modes.csv,
 * mode_sensors.csv and mode_NN.vtu (bk_output_mode normalizes and scales it).
 */
#include "analysis/analysis.h"
#include "analysis/modal.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_sort_vector.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/static.h"
#include "assembly/interaction.h"

#define BK_MODAL_MAXDOF 4000

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static void add_element_block(const bk_system *s, int e, const double *Ke, double c, gsl_matrix *A)
{
    const bk_model *m = s->m;
    const bk_elem *el = &m->elems[e];
    int nd = m->pairs[el->pair]->element->ndof;
    for (int a = 0; a < nd; ++a) {
        int i = s->eq[el->dofs[a]];
        if (i < 0)
            continue;
        for (int b = 0; b < nd; ++b) {
            int j = s->eq[el->dofs[b]];
            if (j >= 0)
                *gsl_matrix_ptr(A, (size_t)i, (size_t)j) += c * Ke[a * nd + b];
        }
    }
}

/* Column c of G^T (the Jacobian row of constraint c), by bk_constraint_jacobian_row. */
typedef struct gt_col {
    gsl_matrix *GT;
    int c;
} gt_col;

static void gt_add(void *ctx, int eq, double v)
{
    gt_col *g = ctx;
    *gsl_matrix_ptr(g->GT, (size_t)eq, (size_t)g->c) += v;
}

static void k_add(void *ctx, int i, int j, double v)
{
    *gsl_matrix_ptr((gsl_matrix *)ctx, (size_t)i, (size_t)j) += v;
}

/* The interactions' stiffness at the modal state (bk_modal_interactions) into
 * the dense K[nfree nfree]; fint[ndof] scratch.  0, or -1. */
static int add_interactions(bk_system *s, const double *q, double *fint, gsl_matrix *K)
{
    double *Ax = calloc((size_t)(s->nnz > 0 ? s->nnz : 1), sizeof *Ax);
    if (!Ax || bk_modal_interactions(s, q, fint, Ax) != 0) {
        free(Ax);
        return -1;
    }
    for (int j = 0; j < s->nfree; ++j)
        for (int k = s->Ap[j]; k < s->Ap[j + 1]; ++k)
            if (s->Ai[k] < s->nfree)
                k_add(K, s->Ai[k], j, Ax[k]);
    free(Ax);
    return 0;
}

/* The frequencies summary.json lists (every mode is in modes.csv). */
#define BK_SUMMARY_FREQUENCIES 64

/* Writes mode number k (from 1) of angular frequency omega, its vector x on
 * the free DOFs (equation order), through shape[ndof] (scratch). */
static void put_mode(const bk_system *s, bk_output *out, const double *q, int k, double omega, const double *x,
                     double *shape, double *freqs, int *nfreq)
{
    for (int i = 0; i < s->m->ndof; ++i)
        shape[i] = s->eq[i] >= 0 ? x[s->eq[i]] : 0.0;     /* fixed DOFs 0; bk_output_mode normalizes */
    const double vals[2] = {omega / (2.0 * M_PI), omega};
    bk_output_mode(out, k, vals, q, shape);
    if (*nfreq < BK_SUMMARY_FREQUENCIES)
        freqs[(*nfreq)++] = omega / (2.0 * M_PI);
}

static const bk_table_spec modes_csv = BK_TABLE("modes.csv", "modal", "mode,frequency_hz,omega,scale_m\n");
static const bk_table_spec mode_sensors_csv =
    BK_TABLE("mode_sensors.csv", "modal",
             "mode,frequency_hz,sensor,x,y,z,dx,dy,dz,shape_x,shape_y,shape_z\n");

/* The sparse path (modal_sparse.c) and its outputs. */
static int modal_sparse(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log, double *freqs,
                        int *nfreq)
{
    const int n = s->nfree, want = s->m->modal.modes;
    double *om = malloc((size_t)want * sizeof *om), *X = malloc((size_t)want * (size_t)n * sizeof *X);
    double *shape = malloc((size_t)s->m->ndof * sizeof *shape);
    int got = 0, steps = 0, rc = 1;
    if (!om || !X || !shape)
        snprintf(info->message, sizeof info->message, "out of memory for %d modes of %d free DOFs", want, n);
    else if (bk_modal_sparse(s, q, want, om, X, &got, &steps, info->message, sizeof info->message) == 0 &&
             bk_output_modes_begin(out, &modes_csv, &mode_sensors_csv, info->message, sizeof info->message) == 0) {
        for (int k = 0; k < got; ++k)
            put_mode(s, out, q, k + 1, om[k], X + (size_t)k * (size_t)n, shape, freqs, nfreq);
        info->steps = got;
        if (got < want)
            bk_warn(info, log, s->m->name, "only %d of the %d modes asked for converged (sparse modal solver)", got,
                    want);
        if (log)
            fprintf(log, "  %d modes (%d free DOFs, %d constraints; sparse: %d shift-invert Lanczos steps)\n", got,
                    n, s->ncon, steps);
        rc = 0;
    }
    info->converged = rc == 0;
    free(om), free(X), free(shape);
    return rc;
}

static int modal(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log, double *freqs, int *nfreq)
{
    const bk_model *m = s->m;
    int n = s->nfree, nc = s->ncon, rc = 1;
    gsl_matrix *K = NULL, *M = NULL, *Z = NULL, *T = NULL, *Kr = NULL, *Mr = NULL, *V = NULL, *GT = NULL;
    gsl_vector *tau = NULL, *mu = NULL;
    gsl_eigen_gensymmv_workspace *ws = NULL;
    double *buf = NULL, *fint = NULL, *me = NULL, *qd0 = NULL;
    if (n == 0) {
        snprintf(info->message, sizeof info->message, "every DOF is fixed: no modes");
        return 1;
    }
    const int sparse = m->modal.solver == BK_SOLVER_SPARSE || (m->modal.solver == BK_SOLVER_AUTO &&
                                                                 n > BK_MODAL_MAXDOF);
    if (n > BK_MODAL_MAXDOF && !sparse) {
        snprintf(info->message, sizeof info->message, "the dense modal solver is limited to %d free DOFs; this "
                 "model has %d (modal.solver = \"sparse\" or \"auto\")", BK_MODAL_MAXDOF, n);
        return 1;
    }
    for (int e = 0; e < m->nelem; ++e) {
        const bk_element *et = bk_elem_type(m, e);
        if (bk_element_has_role(et, BK_FIELD_MULTIPLIER)) {
            snprintf(info->message, sizeof info->message,
                     "modal analysis needs a positive semi-definite tangent; element %s has internal "
                     "Lagrange multipliers (use gef)", et->name);
            return 1;
        }
    }
    /* The state the modes are about: sensors.csv rows and step_*.vtu frames (the
     * static load steps, or the reference as step 0); the modes go to their own
     * files (bk_output_mode). */
    if (m->modal.about == BK_ABOUT_STATIC) {
        bk_run_info sinfo = {0};
        int st = bk_solve_static(s, q, out, &sinfo, log);
        bk_output_last_frame(out, sinfo.steps, sinfo.load_factor, q);
        info->newton_iterations = sinfo.newton_iterations;
        info->cutbacks = sinfo.cutbacks;
        info->load_factor = sinfo.load_factor;
        for (int k = 0; k < sinfo.nwarning; ++k)       /* already printed by the static solve */
            bk_warn(info, NULL, m->name, "static state: %s", sinfo.warnings[k]);
        bk_run_info_free(&sinfo);
        if (st != 0) {
            snprintf(info->message, sizeof info->message, "static state for the modal analysis: %.900s", sinfo.message);
            info->interrupted = sinfo.interrupted;
            return 1;
        }
    } else {
        memcpy(q, m->q0, (size_t)m->ndof * sizeof *q);
        bk_output_step(out, 0, 0.0, q);
    }
    if (bk_interactions_prepare(s, q) != 0) {        /* (contact's pairs at q: the pattern may grow) */
        snprintf(info->message, sizeof info->message, "out of memory for the interactions at the modal state");
        return 1;
    }
    if (sparse)
        return modal_sparse(s, q, out, info, log, freqs, nfreq);
    int md = s->maxdof;
    K = gsl_matrix_calloc((size_t)n, (size_t)n);
    M = gsl_matrix_calloc((size_t)n, (size_t)n);
    buf = calloc((size_t)md * (size_t)md * 3 + (size_t)md * 4, sizeof *buf);
    me = calloc((size_t)md * (size_t)md, sizeof *me);
    fint = calloc((size_t)m->ndof, sizeof *fint);
    qd0 = calloc((size_t)md, sizeof *qd0);
    if (!K || !M || !buf || !me || !fint || !qd0) {
        snprintf(info->message, sizeof info->message, "out of memory for the dense modal matrices");
        goto done;
    }
    /* K and M element by element */
    for (int e = 0; e < m->nelem; ++e) {
        const bk_elem *el = &m->elems[e];
        const bk_pair *p = m->pairs[el->pair];
        const bk_element *et = p->element;
        double *qe = buf + 3 * (size_t)md * md, *fe = qe + md, *Ke = buf;
        bk_gather(m, e, q, qe);
        p->force_tangent(qe, m->tabs[el->geom], m->mats[el->mat].params, fe, Ke);
        add_element_block(s, e, Ke, 1.0, K);
        double rho = m->mats[el->mat].rho;
        bk_element_mass(m, e, me, Ke);
        add_element_block(s, e, Ke, 1.0, M);
        if (et->rotary) {
            double Trot, *Mq = buf, *Cq = buf + (size_t)md * md, *Kq = buf + 2 * (size_t)md * md;
            et->rotary(m->geoms[el->geom], qe, qd0, qd0, fe, Mq, Cq, Kq, &Trot);
            add_element_block(s, e, Mq, rho, M);
        }
    }
    /* the interactions' stiffness (springs, joint motors, contact, loads that
     * turn with the structure), assembled on the pattern, its free block added */
    if (add_interactions(s, q, fint, K) != 0) {
        snprintf(info->message, sizeof info->message, "out of memory, or an interaction's stiffness is not "
                 "finite at the modal state");
        goto done;
    }
    /* symmetrize (kernels are symmetric to round-off) */
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j) {
            double k = 0.5 * (gsl_matrix_get(K, i, j) + gsl_matrix_get(K, j, i));
            double mm = 0.5 * (gsl_matrix_get(M, i, j) + gsl_matrix_get(M, j, i));
            gsl_matrix_set(K, i, j, k);
            gsl_matrix_set(K, j, i, k);
            gsl_matrix_set(M, i, j, mm);
            gsl_matrix_set(M, j, i, mm);
        }
    /* null space of the constraints */
    int r = 0, nz = n;
    if (nc > 0) {
        GT = gsl_matrix_calloc((size_t)n, (size_t)nc);
        for (int c = 0; c < nc; ++c) {
            gt_col col = {GT, c};
            bk_constraint_jacobian_row(s, q, 0.0, c, gt_add, &col);
        }
        int mn = n < nc ? n : nc;
        tau = gsl_vector_alloc((size_t)mn);
        gsl_linalg_QR_decomp(GT, tau);
        double rmax = 0.0;
        for (int i = 0; i < mn; ++i)
            rmax = fmax(rmax, fabs(gsl_matrix_get(GT, i, i)));
        for (int i = 0; i < mn; ++i)
            if (fabs(gsl_matrix_get(GT, i, i)) > 1e-12 * rmax)
                r++;
        nz = n - r;
        gsl_matrix *Q = gsl_matrix_alloc((size_t)n, (size_t)n), *R = gsl_matrix_alloc((size_t)n, (size_t)nc);
        gsl_linalg_QR_unpack(GT, tau, Q, R);
        Z = gsl_matrix_alloc((size_t)n, (size_t)(nz > 0 ? nz : 1));
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < nz; ++j)
                gsl_matrix_set(Z, i, j, gsl_matrix_get(Q, i, r + j));
        gsl_matrix_free(Q);
        gsl_matrix_free(R);
        /* Joints nonlinear in q carry a geometric stiffness sum_k lam_k d2 g_k/dq2
         * in a loaded state: the multipliers from G^T lam = f_ext - f_int at the
         * static equilibrium (least squares on the QR above; independent rows). */
        if (bk_constraints_nonlinear(s) > 0 && m->modal.about == BK_ABOUT_STATIC && r == nc && nc <= n) {
            gsl_vector *b = gsl_vector_calloc((size_t)n), *lam = gsl_vector_alloc((size_t)nc);
            gsl_vector *res = gsl_vector_alloc((size_t)n);
            double *fext = calloc((size_t)m->ndof, sizeof *fext);
            if (!b || !lam || !res || !fext) {
                gsl_vector_free(b), gsl_vector_free(lam), gsl_vector_free(res), free(fext);
                snprintf(info->message, sizeof info->message, "out of memory");
                goto done;
            }
            const bk_path at = {.factor = 1.0, .x = 1.0};      /* the static state: load factor 1 */
            bk_assemble_internal(s, q, fint, NULL);
            bk_assemble_interactions(s, q, &at, fint, NULL);
            bk_external_load(s, fext);
            for (int i = 0; i < m->ndof; ++i)
                if (s->eq[i] >= 0)
                    gsl_vector_set(b, (size_t)s->eq[i], fext[i] - fint[i]);
            gsl_set_error_handler_off();
            if (gsl_linalg_QR_lssolve(GT, tau, b, lam, res) == 0)
                bk_constraint_hessian(s, q, 1.0, lam->data, k_add, K);   /* the static state: load factor 1 */
            gsl_vector_free(b), gsl_vector_free(lam), gsl_vector_free(res), free(fext);
        }
    }
    if (nz <= 0) {
        snprintf(info->message, sizeof info->message, "the constraints leave no free motion");
        goto done;
    }
    if (Z) {
        T = gsl_matrix_alloc((size_t)n, (size_t)nz);
        Kr = gsl_matrix_alloc((size_t)nz, (size_t)nz);
        Mr = gsl_matrix_alloc((size_t)nz, (size_t)nz);
        gsl_blas_dgemm(CblasNoTrans, CblasNoTrans, 1.0, K, Z, 0.0, T);
        gsl_blas_dgemm(CblasTrans, CblasNoTrans, 1.0, Z, T, 0.0, Kr);
        gsl_blas_dgemm(CblasNoTrans, CblasNoTrans, 1.0, M, Z, 0.0, T);
        gsl_blas_dgemm(CblasTrans, CblasNoTrans, 1.0, Z, T, 0.0, Mr);
    } else {
        Kr = K;
        Mr = M;
        K = M = NULL;
    }
    double trK = 0.0, trM = 0.0;
    for (int i = 0; i < nz; ++i) {
        trK += gsl_matrix_get(Kr, i, i);
        trM += gsl_matrix_get(Mr, i, i);
    }
    if (!(trM > 0.0)) {
        snprintf(info->message, sizeof info->message, "the model has no mass (set rho)");
        goto done;
    }
    double sigma = 1e-6 * fabs(trK) / trM;
    gsl_matrix *B = gsl_matrix_alloc((size_t)nz, (size_t)nz), *Mcopy = gsl_matrix_alloc((size_t)nz, (size_t)nz);
    gsl_matrix_memcpy(B, Kr);
    gsl_matrix_memcpy(Mcopy, Mr);
    gsl_matrix_scale(Mcopy, sigma);
    gsl_matrix_add(B, Mcopy);
    gsl_matrix_memcpy(Mcopy, Mr);
    mu = gsl_vector_alloc((size_t)nz);
    V = gsl_matrix_alloc((size_t)nz, (size_t)nz);
    ws = gsl_eigen_gensymmv_alloc((size_t)nz);
    gsl_set_error_handler_off();
    int st = gsl_eigen_gensymmv(Mcopy, B, mu, V, ws);
    gsl_matrix_free(B);
    gsl_matrix_free(Mcopy);
    if (st != 0) {
        snprintf(info->message, sizeof info->message,
                 "eigenproblem failed (tangent not positive semi-definite: is the state stable?)");
        goto done;
    }
    gsl_eigen_gensymmv_sort(mu, V, GSL_EIGEN_SORT_VAL_DESC);
    /* outputs */
    int want = m->modal.modes, got = 0;
    double *shape = calloc((size_t)m->ndof, sizeof *shape);
    if (!shape) {
        snprintf(info->message, sizeof info->message, "out of memory");
        goto done;
    }
    double *x = calloc((size_t)n, sizeof *x);
    if (!x || bk_output_modes_begin(out, &modes_csv, &mode_sensors_csv, info->message, sizeof info->message) != 0) {
        if (!x)
            snprintf(info->message, sizeof info->message, "out of memory");
        free(shape), free(x);
        goto done;
    }
    for (int k = 0; k < nz && got < want; ++k) {
        double muk = gsl_vector_get(mu, k);
        if (!(muk > 1e-14 / (trK / trM + sigma)))
            break;                              /* massless directions: infinite frequency */
        double w2 = 1.0 / muk - sigma;
        double omega = w2 > 0.0 ? sqrt(w2) : 0.0;
        for (int j = 0; j < n; ++j) {          /* the mode on the free DOFs */
            double v = 0.0;
            if (Z)
                for (int c = 0; c < nz; ++c)
                    v += gsl_matrix_get(Z, j, c) * gsl_matrix_get(V, c, k);
            else
                v = gsl_matrix_get(V, j, k);
            x[j] = v;
        }
        put_mode(s, out, q, ++got, omega, x, shape, freqs, nfreq);
    }
    free(shape), free(x);
    info->steps = got;
    if (log)
        fprintf(log, "  %d modes (%d free DOFs, %d constraints of rank %d)\n", got, n, nc, r);
    rc = 0;
done:
    info->converged = rc == 0;
    gsl_matrix_free(K);
    gsl_matrix_free(M);
    gsl_matrix_free(Z);
    gsl_matrix_free(T);
    gsl_matrix_free(Kr);
    gsl_matrix_free(Mr);
    gsl_matrix_free(V);
    gsl_matrix_free(GT);
    gsl_vector_free(tau);
    gsl_vector_free(mu);
    if (ws)
        gsl_eigen_gensymmv_free(ws);
    free(buf);
    free(me);
    free(fint);
    free(qd0);
    return rc;
}

int bk_solve_modal(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log)
{
    double freqs[BK_SUMMARY_FREQUENCIES];
    int nfreq = 0;
    int rc = modal(s, q, out, info, log, freqs, &nfreq);
    /* summary.json "frequencies_hz": the first ones, as "%.17g" (also [] when none) */
    char text[BK_SUMMARY_FREQUENCIES * 26 + 4];
    int len = snprintf(text, sizeof text, "[");
    for (int k = 0; k < nfreq; ++k)
        len += snprintf(text + len, sizeof text - (size_t)len, "%s%.17g", k ? ", " : "", freqs[k]);
    snprintf(text + len, sizeof text - (size_t)len, "]");
    if (bk_run_summary(info, "frequencies_hz", text) != 0 && rc == 0) {
        snprintf(info->message, sizeof info->message, "out of memory");
        rc = 1;
    }
    return rc;
}

static int runs_modal(const bk_model *m)
{
    return m->analysis == BK_ANALYSIS_MODAL;
}

/* Its modes (and, about a static state, the static load steps' frames). */
static void plan_modal(const bk_model *m, bk_output_plan *p)
{
    p->room = m->stat.load_steps * (1 + 2 * m->stat.cycles) + 4;
    p->modes = m->modal.modes;
}

const bk_analysis_module bk_analysis_modal = {"modal", runs_modal, bk_solve_modal, plan_modal};
