/* body_forces.h -- the interaction of dead forces at body points (body_forces.c). */
#ifndef BK_BODY_FORCES_H
#define BK_BODY_FORCES_H

#include "assembly/interaction.h"
#include "assembly/system.h"

extern const bk_interaction_ops bk_body_force_ops;
int bk_body_forces_present(const bk_model *m);
int bk_body_forces_make(bk_system *s, void **self);

#endif
