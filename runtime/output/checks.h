/* checks.h -- is a converged state physically plausible?  Warnings for results
 * that are likely wrong even though Newton converged:
 *   - an inverted element: J = det F <= 0 at a quadrature point (the beam was
 *     turned inside out, e.g. by a huge compressive load);
 *   - a volume ratio J outside [BK_J_MIN, BK_J_MAX];
 *   - principal Green strains outside the range the material law is meant for
 *     (bk_pair green_strain_min/max; St. Venant-Kirchhoff: [-0.2, 0.5]).
 *   - a displacement of a node beyond BK_FAR_FACTOR times the model's size
 *     (its length scale): not credible (units, or a load far beyond what the
 *     structure carries);
 *   - parts of beams passing through one another (or a beam through itself)
 *     when no beam contact is modelled (overlap.h).
 * Each kind is reported once, at its first occurrence (element, position, load
 * factor or time, value), on the console and in summary.json "warnings".
 * Elements whose kernels offer no invariants (rod elements) are not checked.
 */
#ifndef BK_CHECKS_H
#define BK_CHECKS_H

#include <stddef.h>
#include <stdio.h>

#include "output/output.h"
#include "output/overlap.h"
#include "assembly/system.h"

#define BK_J_MIN 0.2
#define BK_J_MAX 5.0
#define BK_FAR_FACTOR 100.0

typedef struct bk_checks {
    double *inv;             /* [3 * largest nqp] invariants of one element (owned) */
    double *qe;              /* [largest element ndof] (owned)                        */
    int inverted, volume, strain, far;   /* reported already */
    bk_overlap overlap;      /* parts passing through one another (overlap.h) */
} bk_checks;

int bk_checks_init(bk_checks *c, const bk_system *s);
void bk_checks_free(bk_checks *c);

/* Checks the state q at load factor / time t ("load factor" or "t" in `what`). */
void bk_checks_state(bk_checks *c, const bk_system *s, const double *q, const char *what, double t,
                     bk_run_info *info, FILE *console);

/* Is the state q admissible: every coordinate finite and J = det F > 0 at
 * every quadrature point of the elements whose kernels offer invariants?
 * Returns 1, or 0 with a one-line reason in why[n] (the element, where it is,
 * its least J; or the first non-finite coordinate).  Analyses accept a step or
 * load increment only at an admissible state. */
int bk_checks_admissible(bk_checks *c, const bk_system *s, const double *q, char *why, size_t n);

/* Principal values of the symmetric positive semi-definite tensor with
 * invariants I1, I2, I3 (e.g. C = F^T F, I3 = J^2), ascending, into x[3]. */
void bk_principal_from_invariants(double I1, double I2, double I3, double *x);

#endif
