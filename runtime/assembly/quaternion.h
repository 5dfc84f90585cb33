/* quaternion.h -- the nodal quaternions of a model (fields of role
 * BK_FIELD_QUATERNION: gef, euler_bernoulli, kirchhoff).  Those elements use the rotation of p/|p|,
 * so rescaling p changes no strain and no kinetic energy; the solvers keep
 * the quaternions at unit length with these helpers.
 *
 * Ownership: bk_quat_list() returns an array owned by the caller (free()). */
#ifndef BK_QUATERNION_H
#define BK_QUATERNION_H

#include "assembly/system.h"

/* First global DOF of every nodal quaternion whose four components are free,
 * each listed once; *n receives the count.  NULL (with *n = 0) when there are
 * none or on allocation failure (*n = -1). */
int *bk_quat_list(const bk_system *s, int *n);

/* Scales each listed quaternion in q to unit length; when v is not NULL, also
 * removes from each rate vector v[k] (nv of them, e.g. velocity and
 * acceleration) its component along the quaternion (the gauge direction). */
void bk_quat_normalize(const int *list, int n, double *q, double *const *v, int nv);

/* As bk_quat_normalize for a motion: q to unit length, the velocity qd without
 * its gauge component, and each of the nacc accelerations acc[k] given the
 * gauge component a unit quaternion's second derivative has, p . p'' = -|p'|^2
 * (removing it instead makes the rotation of bodies whose inertia sits in the
 * quaternions, rigid bodies, first-order accurate in time). */
void bk_quat_normalize_motion(const int *list, int n, double *q, double *qd, double *const *acc, int nacc);

#endif
