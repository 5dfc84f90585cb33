/* modal.h -- natural frequencies and mode shapes (see modal.c). */
#ifndef BK_MODAL_H
#define BK_MODAL_H

#include <stdio.h>

#include "output/output.h"
#include "assembly/system.h"

/* Writes modes.csv and one sensors.csv row per mode (step = mode number,
 * time = frequency in Hz, the configuration displaced along the mode).  q
 * holds the linearization state on return.  Returns 0 on success. */
int bk_solve_modal(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log);

/* The lowest `want` modes at the state q by shift-invert Lanczos on the sparse
 * Newton matrix (modal_sparse.c): omega[want] (out, rad/s, ascending),
 * X[want nfree] (out, row k the k-th mode on the free DOFs), *got (out) how
 * many converged, *steps (out) the Lanczos steps.  0, or 1 with a message in
 * msg[nmsg]. */
int bk_modal_sparse(bk_system *s, const double *q, int want, double *omega, double *X, int *got, int *steps,
                    char *msg, size_t nmsg);

/* Every interaction's stiffness at the state the modes are about (springs,
 * joint motors, contact, and at a static state the configuration-dependent
 * loads at its load factor 1): the tangent each assembles, added into Ax[nnz]
 * (in/out, on the pattern, after bk_interactions_prepare at q); fint[ndof] is
 * scratch.  0, or -1 on a non-finite interaction (modal_sparse.c). */
int bk_modal_interactions(bk_system *s, const double *q, double *fint, double *Ax);

#endif
