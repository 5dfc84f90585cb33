/* contact_model.h -- the contact interaction's data: rigid primitives and, per
 * set, the elements whose centrelines may touch one of them, with the barrier
 * that keeps them apart (read from the model's record "contact",
 * contact_read.c; used by contact_force.c).
 *
 * A set's elements are sampled at nsample points each: the ends and the
 * points between at equal steps, xi = k / (nsample - 1), with the weights of
 * the trapezoidal rule (L / (nsample - 1), half at the ends: a node shared by
 * two elements counts once), or the middle alone (nsample = 1, weight L).  A
 * point x of the centreline with section radius r (a circle's radius, or the
 * set's contact radius) has the distance s = g(x) - r to the primitive, g the
 * primitive's gap (out/kernels/contact.h).  Its barrier energy is kappa w b(s)
 * with w its weight and b(s) = -(s - shat)^2 ln(s / shat) for s < shat, zero
 * beyond.  Friction (mu > 0) is lagged over a step (incremental potential
 * contact): with the normal force lam and the unit normal n of the last
 * accepted state and the slip u_t = (I - n n^T)(x - x_prev) since then, the
 * point's friction energy is mu lam f0(|u_t|), f0' = f1 the smoothed slip
 * function of out/kernels/contact.h (2 y/eps - y^2/eps^2 below eps, 1 beyond):
 * Coulomb's mu lam beyond a slip of eps, a stiff spring below.  The
 * coefficient passes smoothly from the static mu to the kinetic mu_k between a
 * slip of eps and 2 eps since the anchor (bk_contact_transition), and the
 * anchor of a sliding point trails it by eps: a point that stops holds with
 * mu, one that goes on sliding by eps a step rubs with mu_k.  The friction
 * energy stays a function of the slip, so the Jacobian is exact. */
#ifndef BK_CONTACT_MODEL_H
#define BK_CONTACT_MODEL_H

#include <stdio.h>

#include "model/model.h"

enum bk_contact_shape {
    BK_CONTACT_HALF_SPACE = 0,       /* prm: unit normal n (out of the solid), offset d: solid where n.x < d */
    BK_CONTACT_SPHERE = 1,           /* prm: centre c, radius R */
    BK_CONTACT_CAPSULE = 2,          /* prm: ends a, b, radius R (a segment swept by a sphere) */
    BK_CONTACT_BOX = 3               /* prm: centre c, half-sizes h, axes A (row k: axis k): |A (x - c)|_k <= h_k */
};
#define BK_CONTACT_MAXPRM 15

/* A primitive in the reference configuration and how it moves: with the
 * factor f of its amplitude (or the load factor), by the translation f motion
 * and the rotation of the vector f turn (rad) about pivot; or, when body >= 0,
 * with the rigid body of element body (its reference centre and rotation in
 * body_ref: X, then R0 row-major).  A point y of a beam is taken back to the
 * primitive's reference coordinates z (assembly/contact_geometry.h), where
 * the gap is the reference primitive's. */
typedef struct bk_contact_prim {
    int shape;                       /* enum bk_contact_shape */
    double prm[BK_CONTACT_MAXPRM];   /* in the reference position */
    double motion[3];                /* prescribed translation (m), times the factor of amplitude amp */
    double turn[3];                  /* prescribed rotation vector (rad), times the same factor */
    double pivot[3];                 /* the point it turns about (m) */
    int amp;                         /* amplitude index (amplitude.h bk_load_factor), -1: the load factor */
    int body;                        /* element of the rigid body it belongs to, -1: none */
    double body_ref[12];             /* that body's reference centre X and rotation R0 (row-major) */
} bk_contact_prim;

typedef struct bk_contact_set {
    int prim;                        /* index into bk_contact_model.prims */
    double shat;                     /* barrier reach (m), > 0 */
    double kappa;                    /* barrier stiffness (N/m per metre of beam), > 0 */
    double mu;                       /* static Coulomb coefficient mu_s, >= 0 (0: frictionless) */
    double mu_k;                     /* kinetic coefficient, 0 <= mu_k <= mu_s */
    double slip;                     /* slip tolerance eps (m), > 0: sticking up to eps of slip per step */
    int nsample;                     /* sample points per element, >= 1 */
    int nelem;
    int *elems;                      /* [nelem] elements of the set */
    double *radius;                  /* [nelem] their section radii (m) */
} bk_contact_set;

typedef struct bk_contact_model {
    int nprim, nset;
    bk_contact_prim *prims;
    bk_contact_set *sets;
} bk_contact_model;

/* The contact data of the model's record rec (contact_read.c), or NULL after
 * one line to err. */
bk_contact_model *bk_contact_model_read(const bk_model *m, const bk_model_record *rec, FILE *err);
/* Frees what bk_contact_model_read returned (NULL: nothing). */
void bk_contact_model_free(bk_contact_model *cm);

#endif
