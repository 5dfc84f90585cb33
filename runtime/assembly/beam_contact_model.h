/* beam_contact_model.h -- the beam-to-beam contact data: per set, the
 * beams (chains of elements in order along each) whose centrelines may touch
 * one another and, with self, themselves, and the barrier that keeps them
 * apart (the interaction's own model record "beam_contact", read by
 * beam_contact_read.c; used by beam_contact*.c).
 *
 * Each element's centreline is sampled at nsample >= 2 points, xi = k /
 * (nsample - 1), and taken as the polyline through them: its segments.  Two
 * segments of different beams, or of one beam (self) further apart along it
 * than exclude (the arc length between their nearest ends; adjacent segments
 * are always excluded), have the distance s = d - rA - rB, d the distance of
 * their closest points (out/kernels/contact_pairs.h), rA, rB the elements'
 * section radii.  Their barrier energy is kappa w b(s), w the mean of the two
 * segments' reference lengths, b(s) = -(s - shat)^2 ln(s / shat) below shat,
 * zero beyond (out/kernels/contact.h).  Friction (mu > 0) is lagged over a
 * step as for rigid primitives (model/contact.h): the slip of the closest
 * points relative to each other since the last accepted state, in the plane
 * normal to the lagged normal, against the lagged normal force; the
 * coefficient passes from mu_s to mu_k between a slip of eps and 2 eps since
 * the anchor, as for rigid primitives (bk_contact_transition). */
#ifndef BK_BEAM_CONTACT_MODEL_H
#define BK_BEAM_CONTACT_MODEL_H

#include <stdio.h>

typedef struct bk_beam_contact_set {
    double shat;                     /* barrier reach (m), > 0 */
    double kappa;                    /* barrier stiffness (N/m per metre), > 0 */
    double mu;                       /* static Coulomb coefficient mu_s, >= 0 */
    double mu_k;                     /* kinetic coefficient, 0 <= mu_k <= mu_s */
    double slip;                     /* slip tolerance (m), > 0 */
    double exclude;                  /* arc length (m) within which segments of one beam do not touch, >= 0 */
    int nsample;                     /* sample points per element, >= 2 */
    int self;                        /* 1: each beam may touch itself */
    int nchain;                      /* beams of the set */
    int *chain_off;                  /* [nchain + 1] each beam's first entry in elems */
    int nelem;
    int *elems;                      /* [nelem] elements, in order along each beam */
    double *radius;                  /* [nelem] their section radii (m) */
    double *s0;                      /* [nelem] arc length of each element's start along its beam (m) */
} bk_beam_contact_set;

typedef struct bk_beam_contact_model {
    int nset;
    bk_beam_contact_set *sets;
} bk_beam_contact_model;

struct bk_model;
struct bk_model_record;

/* The record's data (the model for its element count and analysis), or NULL
 * after one line to err. */
bk_beam_contact_model *bk_beam_contact_model_read(const struct bk_model *m, const struct bk_model_record *rec,
                                                  FILE *err);
/* Frees beam contact data read from a model file. */
void bk_beam_contact_model_free(bk_beam_contact_model *bm);

#endif
