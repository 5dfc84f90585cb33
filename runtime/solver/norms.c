/* norms.c -- rotation-invariant norms and round-off floors (see norms.h). */
#include "solver/norms.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

int bk_norms_init(bk_norms *n, const bk_system *s)
{
    const bk_model *m = s->m;
    n->neq = s->neq;
    n->ngroup = 0;
    n->gstart = malloc((size_t)(s->neq + 1) * sizeof *n->gstart);
    n->geq = malloc((size_t)(s->neq > 0 ? s->neq : 1) * sizeof *n->geq);
    char *seen = calloc((size_t)(s->neq > 0 ? s->neq : 1), 1);
    if (!n->gstart || !n->geq || !seen) {
        free(seen);
        bk_norms_free(n);
        return -1;
    }
    int k = 0;
    n->gstart[0] = 0;
    /* nodal fields of 3 or 4 components whose free part is whole */
    for (int e = 0; e < m->nelem; ++e) {
        const bk_elem *el = &m->elems[e];
        const bk_element *et = m->pairs[el->pair]->element;
        for (int f = 0; f < et->nfield; ++f) {
            int dim = et->field_dim[f];
            if (dim < 3)
                continue;
            const int *d = el->dofs + et->field_dof[f];
            int whole = 1;
            for (int i = 0; i < dim; ++i)
                whole = whole && s->eq[d[i]] >= 0 && !seen[s->eq[d[i]]];
            if (!whole)
                continue;
            for (int i = 0; i < dim; ++i) {
                seen[s->eq[d[i]]] = 1;
                n->geq[k++] = s->eq[d[i]];
            }
            n->gstart[++n->ngroup] = k;
        }
    }
    /* everything else (partly held fields, internal unknowns, multipliers)
     * one by one */
    for (int i = 0; i < s->neq; ++i)
        if (!seen[i]) {
            n->geq[k++] = i;
            n->gstart[++n->ngroup] = k;
        }
    free(seen);
    return 0;
}

void bk_norms_free(bk_norms *n)
{
    free(n->gstart);
    free(n->geq);
    n->gstart = n->geq = NULL;
    n->ngroup = 0;
}

double bk_norm_free_max(const bk_norms *n, const bk_system *s, const double *x)
{
    double mx = 0.0;
    for (int g = 0; g < n->ngroup; ++g) {
        if (n->geq[n->gstart[g]] >= s->nfree)
            continue;
        double ss = 0.0;
        for (int k = n->gstart[g]; k < n->gstart[g + 1]; ++k)
            ss += x[n->geq[k]] * x[n->geq[k]];
        mx = fmax(mx, ss);
    }
    return sqrt(mx);
}

double bk_norm_dof_max(const bk_norms *n, const bk_system *s, const double *a, const double *b)
{
    /* every field of every element (fixed DOFs included: a held position
     * still sets the size of q); shared nodes are visited more than once */
    const bk_model *m = s->m;
    double mx = 0.0;
    (void)n;
    for (int e = 0; e < m->nelem; ++e) {
        const bk_elem *el = &m->elems[e];
        const bk_element *et = m->pairs[el->pair]->element;
        for (int f = 0; f < et->nfield; ++f) {
            const int *d = el->dofs + et->field_dof[f];
            double ss = 0.0;
            for (int i = 0; i < et->field_dim[f]; ++i) {
                double v = a[d[i]] - (b ? b[d[i]] : 0.0);
                ss += v * v;
            }
            mx = fmax(mx, ss);
        }
    }
    return sqrt(mx);
}

/* The mean square of the matrix entries in the columns of group g, in four
 * partial sums: one chain of dependent additions over every matrix entry was a
 * tenth of a small model's solve (it runs for every new matrix). */
static double group_mean_square(const bk_norms *n, const bk_system *s, const double *Ax, int g)
{
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
    const int dim = n->gstart[g + 1] - n->gstart[g];
    for (int k = n->gstart[g]; k < n->gstart[g + 1]; ++k) {
        const int j = n->geq[k], len = s->Ap[j + 1] - s->Ap[j];
        const double *x = Ax + s->Ap[j];
        int p = 0;
        for (; p + 4 <= len; p += 4) {
            s0 += x[p] * x[p];
            s1 += x[p + 1] * x[p + 1];
            s2 += x[p + 2] * x[p + 2];
            s3 += x[p + 3] * x[p + 3];
        }
        for (; p < len; ++p)
            s0 += x[p] * x[p];
    }
    return ((s0 + s1) + (s2 + s3)) / dim;
}

double bk_norm_matrix_max(const bk_norms *n, const bk_system *s, const double *Ax)
{
    /* a large model's groups on the threads (a maximum: the same for any thread
     * count; one parallel region a new matrix); a small model's without entering
     * a parallel region at all: libgomp allocates a team for a region even when
     * its if clause is false, and this runs at every new matrix
     * (tests/test_bench_alloc.py) */
    double mx = 0.0;
    if (n->ngroup >= 4096) {
#pragma omp parallel for schedule(static) reduction(max : mx)
        for (int g = 0; g < n->ngroup; ++g) {
            const double v = group_mean_square(n, s, Ax, g);
            if (v > mx)
                mx = v;
        }
    } else {
        for (int g = 0; g < n->ngroup; ++g) {
            const double v = group_mean_square(n, s, Ax, g);
            if (v > mx)
                mx = v;
        }
    }
    return sqrt(mx);
}

double bk_norm2(const double *v, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; ++i)
        s += v[i] * v[i];
    return sqrt(s);
}

bk_floors bk_round_off_floors(const bk_norms *n, const bk_system *s, const double *q, const double *Ax)
{
    double qmax = bk_norm_dof_max(n, s, q, NULL);
    double kmax = bk_norm_matrix_max(n, s, Ax);
    bk_floors f;
    f.force = 100.0 * DBL_EPSILON * kmax * qmax;
    f.increment = 64.0 * DBL_EPSILON * qmax;
    f.energy = sqrt(f.force * f.increment);
    return f;
}
