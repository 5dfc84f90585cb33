/* actuator.h -- the joint actuators of a model: motors acting equally and
 * oppositely on the two frames of a joint with an axis (a joint nonlinear in
 * q, model.h bk_nlcon), read with the model (model/actuator_read.c), assembled
 * by assembly/actuators.c.  With s the joint coordinate (the angle of frame a
 * relative to frame b about the axis, or a's displacement along it; 0 in the
 * reference configuration) and x the time (dynamics) or the load factor:
 *   effort = effort0 a_e(x) + kp (setpoint a_s(x) - s) + kd (setpoint a_s'(x) - s'),
 * a torque on a about the axis (and its opposite on b) or a force along it;
 * a_e: the amplitude eamp (-1: the load factor in statics, 1 in dynamics),
 * a_s: the amplitude samp (-1: the constant 1). */
#ifndef BK_ACTUATOR_MODEL_H
#define BK_ACTUATOR_MODEL_H

enum bk_actuator_kind { BK_ACT_ROTATION = 1, BK_ACT_TRANSLATION = 2 };

typedef struct bk_actuator {
    char name[64];
    int kind;                  /* bk_actuator_kind */
    int nlcon;                 /* its joint (model->nlcons) */
    double effort0;            /* N m or N */
    int eamp;                  /* amplitude of effort0, -1: the default */
    double kp, kd;             /* N m/rad, N m s/rad (or N/m, N s/m), >= 0 */
    double setpoint;           /* rad or m */
    int samp;                  /* amplitude of the set-point, -1: constant */
} bk_actuator;

typedef struct bk_actuator_model {
    int n;
    bk_actuator *acts;
} bk_actuator_model;

void bk_actuator_model_free(bk_actuator_model *am);

#endif
