/* loads.h -- loads beyond the constant dead loads of bk_external_load: every
 * load with an amplitude (amplitude.h), follower forces and moments (they turn
 * with the section frame), distributed loads per unit length (dead or
 * follower) and tendons.  The runtime knows no element formula: positions come
 * from the element's shape(), section frames and the Jacobian of a follower
 * load's direction from section_frame() (generated with its derivative),
 * moments from moment(); a tendon's line (tendons.c) from the shape functions'
 * xi-derivative by a five-point stencil (exact for the polynomial shape
 * functions of degree <= 4 of the continuum elements) or, on rods, from
 * section_line(). */
#ifndef BK_LOADS_H
#define BK_LOADS_H

#include "assembly/system.h"

/* At x (time in dynamics, load factor in statics): subtracts the generalized
 * loads Q(q, x) from fint[ndof] and, when Ax is not NULL, adds -dQ/dq to the
 * Newton matrix (unsymmetric for follower loads). */
void bk_assemble_loads(bk_system *s, const double *q, double x, double *fint, double *Ax);

/* The same without allocation, with scratch made once (bk_loads_scratch_new
 * for the system's largest element, NULL when out of memory) for the loads
 * interaction (interactions.c); bk_assemble_loads makes one per call. */
typedef struct bk_loads_scratch bk_loads_scratch;
bk_loads_scratch *bk_loads_scratch_new(int maxdof);
void bk_loads_scratch_free(bk_loads_scratch *ls);
void bk_assemble_loads_in(bk_system *s, bk_loads_scratch *ls, const double *q, double x, double *fint, double *Ax);
/* 1 when the model has loads of bk_assemble_loads (else it adds nothing). */
int bk_loads_present(const bk_model *m);

/* The loads element e carries itself (distributed loads, tendon pieces, gravity,
 * point forces and moments strictly inside it; dead or varying, whichever
 * interaction or the dead load vector assembles them) at x, over its DOFs,
 * added to Qe[ndof]: the loads interaction's answer to element_loads
 * (interaction.h).  Thread-safe (scratch of its own per call). */
void bk_element_loads(const bk_system *s, const double *q, double x, int e, double *Qe);
/* 1 when the model has a load record that bk_element_loads answers for. */
int bk_element_loads_present(const bk_model *m);

/* The potentials at x of the loads of bk_assemble_loads that have one,
 * relative to the reference state m->q0: added to *Vg, gravity with an
 * amplitude (-a(x) rho g . displacement over the volume); to *Vf, dead point
 * and distributed forces (-a(x) f . displacement of their points) and tendons
 * (T(x) times the change of the tendon's length).  Followers and moments have
 * none and are left out. */
void bk_load_potentials(const bk_system *s, const double *q, double x, double *Vg, double *Vf);

/* Orthonormal section frame at xi of element e with coordinates qe: R[9] =
 * e1, e2, e3 (the element's section_frame(): e3 along the element's axis-like
 * d3, e1 the part of d1 normal to it).  Returns -1 where the element defines
 * no section axes (the cable) or the frame is degenerate (not finite). */
int bk_section_frame(const bk_model *m, int e, const double *qe, double xi, double *R);

#endif
