/* buckling_space.c -- the buckling analysis's work arrays and its reduction
 * to the null space of the linear constraints and the quaternions' gauge
 * (GSL QR), with the products and solves on it (see buckling.c). */
#include "analysis/buckling_impl.h"

#include <gsl/gsl_blas.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/quaternion.h"

void bk_bw_work_free(work *w)
{
    free(w->quat), free(w->f), free(w->g), free(w->r), free(w->fext), free(w->u), free(w->w), free(w->qp);
    free(w->phi), free(w->Ax);
    gsl_matrix_free(w->K0), gsl_matrix_free(w->K1), gsl_matrix_free(w->K2), gsl_matrix_free(w->Z);
    gsl_matrix_free(w->T), gsl_matrix_free(w->A), gsl_matrix_free(w->B), gsl_matrix_free(w->C);
    gsl_vector_free(w->b), gsl_vector_free(w->y);
    gsl_permutation_free(w->perm);
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
int bk_bw_null_space(bk_system *s, work *w, const double *q, double x, char *msg, size_t nmsg)
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
void bk_bw_reduce(work *w, const gsl_matrix *D, gsl_matrix *out)
{
    if (!w->Z) {
        gsl_matrix_memcpy(out, D);
        return;
    }
    gsl_blas_dgemm(CblasNoTrans, CblasNoTrans, 1.0, D, w->Z, 0.0, w->T);
    gsl_blas_dgemm(CblasTrans, CblasNoTrans, 1.0, w->Z, w->T, 0.0, out);
}

/* x[ndof] (fixed DOFs 0) from the reduced vector v[nz] (stride). */
void bk_bw_expand(const bk_system *s, const work *w, const double *v, size_t stride, double *x)
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
void bk_bw_solve(const bk_system *s, work *w, const double *f, double c, double *x)
{
    for (int i = 0; i < s->m->ndof; ++i)
        if (s->eq[i] >= 0)
            gsl_vector_set(w->b, (size_t)s->eq[i], c * f[i]);
    if (w->Z)
        gsl_blas_dgemv(CblasTrans, 1.0, w->Z, w->b, 0.0, w->y);
    else
        gsl_vector_memcpy(w->y, w->b);
    gsl_linalg_LU_svx(w->A, w->perm, w->y);
    bk_bw_expand(s, w, w->y->data, w->y->stride, x);
}

int bk_bw_alloc_work(const bk_system *s, work *w)
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

int bk_bw_alloc_reduced(const bk_system *s, work *w)
{
    size_t nz = (size_t)w->nz;
    w->A = gsl_matrix_alloc(nz, nz), w->B = gsl_matrix_alloc(nz, nz), w->C = gsl_matrix_alloc(nz, nz);
    w->T = w->Z ? gsl_matrix_alloc((size_t)s->nfree, nz) : NULL;
    w->y = gsl_vector_alloc(nz);
    w->perm = gsl_permutation_alloc(nz);
    return w->A && w->B && w->C && (!w->Z || w->T) && w->y && w->perm ? 0 : -1;
}
