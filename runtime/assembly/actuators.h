/* actuators.h -- what the modal analysis asks of the joint actuators'
 * interaction (actuators.c): motors acting on the two frames of a joint, open
 * loop or PD. */
#ifndef BK_ACTUATORS_H
#define BK_ACTUATORS_H

#include "assembly/interaction.h"
#include "assembly/system.h"

/* 1 when s has actuators (the model's record "actuator"). */
int bk_actuators_present(const bk_system *s);

/* For the modal analysis: the actuators at rest at q (the path variable x: the
 * load factor) -- their generalized forces subtracted from fint[ndof] (may be
 * NULL) and their stiffness -tau d2s/dq2 + kp g g^T through add(ctx, row
 * equation, column equation, value) (may be NULL); the angles unwrapped from
 * the reference configuration.  Nothing when s has no actuators. */
void bk_actuators_at_rest(const bk_system *s, const double *q, double x, double *fint,
                          void (*add)(void *ctx, int i, int j, double v), void *ctx);

#endif
