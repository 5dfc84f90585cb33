/* contact_geometry.h -- where a point of a beam is relative to a rigid
 * primitive (model/contact.h): the map of the point y (and, for a primitive of
 * a rigid body, the body's coordinates) to the primitive's reference
 * coordinates z with its first and second derivatives, the reference
 * primitive's gap at z, and the chain rule that takes a force and stiffness
 * in z back to the variables.  Used by assembly/contact_force.c. */
#ifndef BK_CONTACT_GEOMETRY_H
#define BK_CONTACT_GEOMETRY_H

#include "assembly/contact_model.h"

/* The placement of a primitive that is not on a body at one path point:
 * Q (rotation, row-major) and the translated pivot c = pivot + f motion, so
 * that z = Q^T (y - c) + pivot.  pl[15] = Q[9], c[3], pivot[3]. */
#define BK_CONTACT_PLACEMENT 15
void bk_contact_placement(const bk_contact_prim *p, double f, double *pl);

/* The map of a point: v = y (nv = 3) or v = (y, r, p) of the primitive's body
 * (nv = 10); z[3], J = dz/dv (3 x nv, row-major with stride nv) and, for a
 * body, T = d2 z_k/dv2 (T + 100 k: 10 x 10 row-major; zero without a body). */
typedef struct bk_contact_map {
    int nv;
    int identity;                    /* 1: z = y (a primitive in its reference place): J = I, T = 0 */
    double z[3];
    double J[30];
    double T[300];
} bk_contact_map;

/* The map of point y[3] to primitive p's reference coordinates: pl its
 * placement (bk_contact_placement; unused for a body), qb[7] its body's
 * coordinates (unused without one). */
void bk_contact_map_point(const bk_contact_prim *p, const double *pl, const double *qb, const double *y,
                          bk_contact_map *mp);

/* The reference primitive's gap at z: out[0] = g (> 0 apart), out[1..3] its
 * gradient, out[4..12] its Hessian (row-major); |gradient| = 1. */
void bk_contact_gap_ref(const bk_contact_prim *p, const double *z, double *out);

/* fv[nv] = J^T fz and Kv[nv x nv] = J^T Kz J + sum_k fz[k] T_k, from the force
 * fz[3] and stiffness Kz[9] of a point in z (when Kv is not NULL). */
void bk_contact_chain(const bk_contact_map *mp, const double *fz, const double *Kz, double *fv, double *Kv);

#endif
