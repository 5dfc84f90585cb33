/* contact_force.h -- contact between beams and rigid primitives as an interaction
 * (interaction.h): for every set of the contact data (contact_model.h)
 * each element's sample points feel the barrier of their distance to the
 * set's primitive.  Residual and Jacobian are exact (the generated gap,
 * gradient, Hessian and barrier derivatives of out/kernels/contact.h, the
 * positions linear in the element coordinates through the element's shape
 * functions); the step limiter keeps every sample point's distance above a
 * tenth of what it was (the distances are 1-Lipschitz in the point), so that
 * no Newton iterate takes a sample point through a surface; a state with a
 * distance <= 0 is refused (assemble returns -1).  Between sample points the
 * surface is resolved to the sampling: nsample points per element. */
#ifndef BK_CONTACT_FORCE_H
#define BK_CONTACT_FORCE_H

#include "assembly/interaction.h"
#include "base/tables.h"

struct bk_system;
struct bk_model;

/* contacts.csv, shared by rigid and beam-to-beam contact (whichever
 * interaction opens it first writes the header): the last three columns name
 * the second beam, its element and segment of a beam-to-beam row (primitive
 * -1), empty for a primitive's. */
extern const bk_table_spec bk_contacts_csv;     /* (contact_output.c) */

extern const bk_interaction_ops bk_contact_ops;

/* The contact state at q: per set, the total force the primitive exerts on
 * the beams (F[3 nset], N) and the number of sample points within the barrier
 * (nactive[nset], may be NULL); the smallest distance of any sample point to
 * its primitive (m).  For the outputs and the tests. */
void bk_contact_state(const struct bk_system *s, const double *q, double *F, int *nactive, double *min_distance);

/* The broad phase of the contact with rigid primitives alone at q and the
 * path point (as assemble runs it first): the number of the sets' elements
 * that go on to the exact distances of their sample points (those within
 * the barrier's reach plus their radius of the primitive by their points'
 * box, or rubbing), or -1 when the system has no such contact.  For the
 * bench (its share of an iteration) and the tests. */
int bk_contact_broad_phase(const struct bk_system *s, const double *q, const bk_path *path);

#endif
