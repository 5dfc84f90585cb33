/* tendons.h -- one tendon piece (a tendon or a pneumatic chamber along part of
 * an element): its line's length l(q) = integral of |dP/dxi| over the piece,
 * the generalized force -T dl/dq of the potential T l and its tangent.  The
 * line P rides on the section at the offset (dy, dz): on continuum elements
 * through the shape functions (tendons.c says how), on rods through the
 * generated section_line() (the point fixed in the rotating section). */
#ifndef BK_TENDONS_H
#define BK_TENDONS_H

#include "model/model.h"

/* Q[ndof] -= T dl/dq and, when K is not NULL, K[ndof*ndof] -= T d2l/dq2, for
 * the element's coordinates qe; dt[3 ndof] and H[ndof*ndof] are scratch
 * (used on rods). */
void bk_tendon_piece_load(const bk_model *m, const bk_tendon_piece *tp, double T, const double *qe, double *dt,
                          double *H, double *Q, double *K);

/* l(qe): the same quadrature of |dP/dxi| as bk_tendon_piece_load. */
double bk_tendon_piece_length(const bk_model *m, const bk_tendon_piece *tp, const double *qe);

#endif
