/* actuators.h -- the joint actuators' interaction (actuators.c; model/actuator.h):
 * motors acting on the two frames of a joint, open loop or PD. */
#ifndef BK_ACTUATORS_H
#define BK_ACTUATORS_H

#include "assembly/interaction.h"
#include "assembly/system.h"

extern const bk_interaction_ops bk_actuator_ops;
int bk_actuators_present(const bk_model *m);
int bk_actuators_make(bk_system *s, void **self);

/* For the modal analysis: the actuators at rest at q (the path variable x: the
 * load factor) -- their generalized forces subtracted from fint[ndof] (may be
 * NULL) and their stiffness -tau d2s/dq2 + kp g g^T through add(ctx, row
 * equation, column equation, value) (may be NULL); the angles unwrapped from
 * the reference configuration. */
void bk_actuators_at_rest(const bk_system *s, const double *q, double x, double *fint,
                          void (*add)(void *ctx, int i, int j, double v), void *ctx);

#endif
