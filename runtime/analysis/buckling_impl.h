/* buckling_impl.h -- what the buckling analysis (buckling.c) shares with its
 * work arrays and its reduction to the constraints' null space
 * (buckling_space.c), private to analysis/. */
#ifndef BK_BUCKLING_IMPL_H
#define BK_BUCKLING_IMPL_H

#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include <stddef.h>

#include "assembly/system.h"

/* The work of one analysis, freed by work_free. */
typedef struct work {
    int nz, nquat;
    int *quat;                                   /* first DOF of each free nodal quaternion */
    double *f, *g, *r, *fext, *u, *w, *qp, *phi, *Ax; /* [ndof] each, Ax [nnz] */
    gsl_matrix *K0, *K1, *K2, *Z, *T, *A, *B, *C;
    gsl_vector *b, *y;
    gsl_permutation *perm;
} work;

void bk_bw_work_free(work *w);
int bk_bw_null_space(bk_system *s, work *w, const double *q, double x, char *msg, size_t nmsg);
void bk_bw_reduce(work *w, const gsl_matrix *D, gsl_matrix *out);
void bk_bw_expand(const bk_system *s, const work *w, const double *v, size_t stride, double *x);
void bk_bw_solve(const bk_system *s, work *w, const double *f, double c, double *x);
int bk_bw_alloc_work(const bk_system *s, work *w);
int bk_bw_alloc_reduced(const bk_system *s, work *w);

#endif
