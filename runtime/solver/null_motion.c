/* null_motion.c -- the motion a singular Newton matrix leaves free (null_motion.h). */
#include "solver/null_motion.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* the element, field and node of each DOF (first element that has it) */
typedef struct dof_at {
    int elem, field, node;
} dof_at;

static void locate(const bk_model *m, dof_at *at)
{
    for (int i = 0; i < m->ndof; ++i)
        at[i].elem = -1;
    for (int e = 0; e < m->nelem; ++e) {
        const bk_element *et = m->pairs[m->elems[e].pair]->element;
        int seen[BK_FIELD_MULTIPLIER + 1] = {0};
        for (int f = 0; f < et->nfield; ++f) {
            int role = et->field_role[f], node = seen[role]++;
            for (int k = 0; k < et->field_dim[f]; ++k) {
                int d = m->elems[e].dofs[et->field_dof[f] + k];
                if (at[d].elem < 0)
                    at[d] = (dof_at){e, f, node};
            }
        }
    }
}

/* "beam 'b' at s = 2 m" for node `node` of element e (nodes evenly along it) */
static void where(const bk_model *m, int e, int node, int nnode, char *buf, size_t n)
{
    for (int k = 0; k < m->nsection; ++k)
        if (m->sections[k].elem == e) {
            const bk_section_rec *r = &m->sections[k];
            double xi = nnode > 1 ? (double)node / (nnode - 1) : 0.0;
            snprintf(buf, n, "beam '%s' at s = %.4g m", r->beam, r->s0 + xi * (r->s1 - r->s0));
            return;
        }
    snprintf(buf, n, "element %d node %d", e, node);
}

static int describe(const bk_system *s, const double *x, const double *q, char *buf, size_t n)
{
    const bk_model *m = s->m;
    dof_at *at = malloc((size_t)m->ndof * sizeof *at);
    double *v = calloc((size_t)m->ndof, sizeof *v);
    if (!at || !v) {
        free(at), free(v);
        return -1;
    }
    locate(m, at);
    double xf = 0.0, xc = 0.0;
    for (int i = 0; i < m->ndof; ++i)
        if (s->eq[i] >= 0)
            v[i] = x[s->eq[i]], xf = fmax(xf, fabs(v[i]));
    for (int c = 0; c < s->ncon; ++c)
        xc = fmax(xc, fabs(x[s->nfree + c]));
    int len;
    if (!(xf > 1e-6 * xc)) {
        len = snprintf(buf, n, "the constraint rows are dependent (redundant joints or a joint that repeats a "
                               "fixed DOF): their reactions are not unique");
        free(at), free(v);
        return 0;
    }
    /* the largest translation of a node and the largest turning of a section
     * (quaternions: 2 Im(dp conj(p)); section vectors d: d x dd / |d|^2), and
     * whether every node translates alike */
    int it = -1, ir = -1, uniform = 1, first = -1;
    double tmax = 0.0, rmax = 0.0, tvec[3] = {0}, rvec[3] = {0};
    for (int i = 0; i < m->ndof; ++i) {
        if (at[i].elem < 0)
            continue;
        const bk_element *et = m->pairs[m->elems[at[i].elem].pair]->element;
        int f = at[i].field, role = et->field_role[f];
        if (m->elems[at[i].elem].dofs[et->field_dof[f]] != i || role == BK_FIELD_MULTIPLIER)
            continue;                            /* the first DOF of its field stands for it */
        const double *p = q + i, *dp = v + i;
        double d[3];
        if (role == BK_FIELD_POSITION) {
            if (first < 0)
                first = i;
            for (int k = 0; k < 3; ++k)
                uniform &= fabs(dp[k] - v[first + k]) <= 1e-3 * xf;
            double a = sqrt(dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2]);
            if (a > tmax)
                tmax = a, it = i, memcpy(tvec, dp, sizeof tvec);
            continue;
        }
        if (role == BK_FIELD_QUATERNION) {
            const double cr[3] = {dp[2] * p[3] - dp[3] * p[2], dp[3] * p[1] - dp[1] * p[3], dp[1] * p[2] - dp[2] * p[1]};
            for (int k = 0; k < 3; ++k)
                d[k] = 2.0 * (-dp[0] * p[k + 1] + p[0] * dp[k + 1] - cr[k]);
        } else {
            double pp = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
            if (!(pp > 0.0))
                continue;
            d[0] = (p[1] * dp[2] - p[2] * dp[1]) / pp;
            d[1] = (p[2] * dp[0] - p[0] * dp[2]) / pp;
            d[2] = (p[0] * dp[1] - p[1] * dp[0]) / pp;
        }
        double a = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (a > rmax)
            rmax = a, ir = i, memcpy(rvec, d, sizeof rvec);
    }
    const double L = m->length_scale > 0.0 ? m->length_scale : 1.0;
    const int turning = ir >= 0 && rmax * L > 1e-3 * tmax;
    char pos[128];
    len = snprintf(buf, n, "free motion (null vector of the matrix):");
    if (it >= 0 && uniform && !turning) {
        snprintf(buf + len, n - (size_t)len, " a rigid translation of every node along (%.2f, %.2f, %.2f)",
                 tvec[0] / tmax, tvec[1] / tmax, tvec[2] / tmax);
    } else {
        if (it >= 0 && tmax > 1e-3 * rmax * L) {
            const bk_element *et = m->pairs[m->elems[at[it].elem].pair]->element;
            where(m, at[it].elem, at[it].node, et->nnode, pos, sizeof pos);
            len += snprintf(buf + len, n - (size_t)len, " the largest translation at %s, along (%.2f, %.2f, %.2f)%s",
                            pos, tvec[0] / tmax, tvec[1] / tmax, tvec[2] / tmax, turning ? ";" : "");
        }
        if (turning && len >= 0 && (size_t)len < n) {
            const bk_element *et = m->pairs[m->elems[at[ir].elem].pair]->element;
            where(m, at[ir].elem, at[ir].node, et->nnode, pos, sizeof pos);
            snprintf(buf + len, n - (size_t)len, " the section turning most at %s, about (%.2f, %.2f, %.2f)", pos,
                     rvec[0] / rmax, rvec[1] / rmax, rvec[2] / rmax);
        }
    }
    free(at), free(v);
    return 0;
}

int bk_null_motion(const bk_system *s, const double *Ax, const double *q, bk_linsolver *ls, char *buf, size_t n)
{
    buf[0] = 0;
    double *A = malloc((size_t)s->nnz * sizeof *A), *x = malloc((size_t)s->neq * sizeof *x);
    int rc = -1;
    if (!A || !x)
        goto out;
    memcpy(A, Ax, (size_t)s->nnz * sizeof *A);
    double dmax = 0.0;
    for (int j = 0; j < s->nfree; ++j)
        if (s->diag[j] >= 0)
            dmax = fmax(dmax, fabs(A[s->diag[j]]));
    for (int j = 0; j < s->nfree; ++j)
        if (s->diag[j] >= 0)
            A[s->diag[j]] += 1e-9 * (dmax > 0.0 ? dmax : 1.0);
    if (bk_lin_factor(ls, A) != BK_LIN_OK)
        goto out;
    for (int i = 0; i < s->neq; ++i)           /* a start with every direction in it */
        x[i] = 1.0 + 0.37 * sin(1.0 + 2.3 * i);
    for (int it = 0; it < 4; ++it) {
        if (bk_lin_solve(ls, x) != BK_LIN_OK)
            goto out;
        double nx = 0.0;
        for (int i = 0; i < s->neq; ++i)
            nx = fmax(nx, fabs(x[i]));
        if (!(nx > 0.0) || !isfinite(nx))
            goto out;
        for (int i = 0; i < s->neq; ++i)
            x[i] /= nx;
    }
    rc = describe(s, x, q, buf, n);
out:
    free(A);
    free(x);
    return rc;
}
