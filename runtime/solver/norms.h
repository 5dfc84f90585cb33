/* norms.h -- rotation-invariant measures for Newton's convergence tests and
 * round-off floors (one set, used by every analysis).
 *
 * A rigid rotation of a scene turns every nodal vector field (positions,
 * position gradients r_x ... r_zz: 3 components; quaternions: 4) by an
 * orthogonal map.  Measures built from component maxima change with it, so
 * that the same scene converged in 6 iterations aligned with the axes and in
 * 25 or none when turned in space.  The measures here are Euclidean norms of
 * whole fields, column-block norms of the Newton matrix and scalar products:
 * unchanged by a rotation.
 */
#ifndef BK_NORMS_H
#define BK_NORMS_H

#include "assembly/system.h"

typedef struct bk_norms {
    int neq;
    int ngroup;
    int *gstart;     /* [ngroup+1] groups of equations: a free nodal field (its   */
    int *geq;        /* equations geq[gstart[g] .. gstart[g+1])), a scalar DOF   */
                     /* or a constraint multiplier; every equation in one group  */
} bk_norms;

/* Builds the groups from the element field descriptors.  Returns 0, -1 when
 * out of memory. */
int bk_norms_init(bk_norms *n, const bk_system *s);
void bk_norms_free(bk_norms *n);

/* Largest Euclidean norm of a group of x (indexed by equation) over the free
 * DOFs (groups of multipliers are skipped). */
double bk_norm_free_max(const bk_norms *n, const bk_system *s, const double *x);

/* The same for a difference of two DOF-indexed vectors a - b (b may be NULL). */
double bk_norm_dof_max(const bk_norms *n, const bk_system *s, const double *a, const double *b);

/* Largest column-block norm of the Newton matrix Ax (CSC, the system's
 * pattern): max over groups g of ||A[:, g]||_F / sqrt(|g|), the stiffness of
 * the stiffest field including its couplings to multipliers. */
double bk_norm_matrix_max(const bk_norms *n, const bk_system *s, const double *Ax);

/* Euclidean norm of v[0..n). */
double bk_norm2(const double *v, int n);

/* Round-off floors of one Newton iterate: below them a residual, an increment
 * or a correction's energy is noise. */
typedef struct bk_floors {
    double force;        /* K times a last-bit change of q: 100 eps kmax qmax      */
    double increment;    /* a few ulps of q: 64 eps qmax                           */
    double energy;       /* of a correction's energy norm sqrt|dx . r|: sqrt(force increment) */
} bk_floors;

/* The floors of iterate q (DOF-indexed) with Newton matrix Ax. */
bk_floors bk_round_off_floors(const bk_norms *n, const bk_system *s, const double *q, const double *Ax);

/* Energy test of Newton's convergence (statics and dynamics): the last
 * correction's energy norm sqrt|dx . r| at most this fraction of the first one
 * of the increment (or bk_floors.energy).  Newton converging quadratically, the
 * accepted iterate is then exact to about the square of it.  Unlike a length
 * test it does not wait for corrections along directions of next to no
 * stiffness (a beam's spin about its axis at a spherical joint), whose
 * round-off noise depends on how the scene is turned in space. */
#define BK_ENERGY_TOL 1e-7

#endif
