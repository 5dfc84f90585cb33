/* beam_contact.h -- beam-to-beam and self-contact as an interaction
 * (interaction.h): for every set of its data (its model record "beam_contact",
 * beam_contact_model.h) the segments of the beams' sampled centrelines feel
 * the barrier of their distances to one another (out/kernels/contact_pairs.h
 * for the distances, out/kernels/contact.h for the barrier), with the exact
 * Jacobian.  Action equals reaction: the energy of a pair depends on the
 * relative position of its segments only.
 *
 * Candidates and the pattern.  A broad phase (assembly/contact_broad.h) finds
 * the element pairs whose boxes, each inflated by its section radius, half
 * the barrier's reach and half a margin M, overlap; only their segments are
 * compared, and the Newton matrix's pattern is given their coupling blocks
 * (system.h bk_system_couple: it grows, never shrinks).  The broad phase runs
 * again (prepare, before a Newton iteration) as soon as a sample point moved
 * more than M/4 since the last one, and the step limiter lets no correction
 * move a point more than M/4: so every point stays within M/2 of where the
 * broad phase saw it, and a pair that was no candidate then stays beyond the
 * barrier's reach until the next one.  The step limiter also keeps every
 * candidate pair at more than a tenth of its distance (no iterate through a
 * beam); a state with a distance <= 0 is refused (assemble returns -1).
 * Friction (mu > 0): lagged per pair of segments, updated by accept
 * (beam_contact_friction.c). */
#ifndef BK_BEAM_CONTACT_H
#define BK_BEAM_CONTACT_H

#include "assembly/beam_contact_model.h"
#include "assembly/interaction.h"

struct bk_system;
struct bk_model;

extern const bk_interaction_ops bk_beam_contact_ops;
/* Its work for the sets bm (not owned: they must outlive it) into *self: the
 * broad phase at the reference configuration done, its pairs coupled; 0 or
 * -1 (out of memory).  The module (bk_interaction_beam_contact) makes it from
 * the model's record; tests from sets of their own. */
int bk_beam_contact_make(struct bk_system *s, const bk_beam_contact_model *bm, void **self);

/* The broad phase run again at q, whether or not a point moved (for the
 * bench: its cost; the tests): the number of candidate element pairs, or -1
 * (no beam contact, out of memory). */
int bk_beam_contact_broad_phase(struct bk_system *s, const double *q);

/* The state at q (for the outputs and the tests), of set c: the total force
 * on each of its beams (F[3 nchain], N), the pairs of segments within the
 * barrier's reach and the sum of their forces' magnitudes (N; both may be
 * NULL), and the smallest distance (section to section, m) of the pairs the
 * broad phase keeps (INFINITY: none).  Returns 0, or -1 when the system has
 * no beam contact. */
int bk_beam_contact_state(const struct bk_system *s, const double *q, int c, double *F, int *nactive,
                          double *normal, double *min_distance);

#endif
