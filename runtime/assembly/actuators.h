/* actuators.h -- the joint actuators' interaction (actuators.c; model/actuator.h):
 * motors acting on the two frames of a joint, open loop or PD. */
#ifndef BK_ACTUATORS_H
#define BK_ACTUATORS_H

#include "assembly/interaction.h"
#include "assembly/system.h"

extern const bk_interaction_ops bk_actuator_ops;
int bk_actuators_present(const bk_model *m);
int bk_actuators_make(bk_system *s, void **self);

#endif
