/* dyn_frame.h -- the rotating frame of a dynamic run (dynamic.frame,
 * dyn_frame.c), private to analysis/: the equations of motion in axes turning
 * with a prescribed rotation, whose node is then held still.
 *
 * The frame turns by phi(t) = theta(t) - theta(0) about the unit axis n
 * through the point c (the constraint's node), theta the constraint's own
 * angle.  Every coordinate block turns with it: positions x_a = R (x - c) + c,
 * nodal vectors (ANCF gradients) g_a = R g, quaternions p_a = r p (r the
 * frame's quaternion), element multipliers not at all.  Written q_a = T y +
 * offset (y = q less c on positions, T block diagonal), the inertial state is
 *   q_a' = T' y + T q',   q_a'' = T'' y + 2 T' q' + T q'',
 * and the inertia forces in the frame are T^T times the inertial ones there:
 *   translational  T^T M (T'' y + 2 T' q') besides M q'' (centrifugal and
 *                  Euler forces from T^T M T'', Coriolis from 2 T^T M T');
 *   rotary         T^T f_rot(q_a, q_a', q_a'') (the body angular velocity is
 *                  w_rel + Lambda^T omega: the gyroscopic coupling with the
 *                  frame comes with it), with
 *                  d/dq'' = T^T Mq T, d/dq' = T^T (Cq T + 2 Mq T'),
 *                  d/dq = T^T (Kq T + Cq T' + Mq T'').
 * Elastic and Kelvin-Voigt forces and tendons are the same in any rotated
 * axes; the frame's constraint rows are taken at t = 0. */
#ifndef BK_DYN_FRAME_H
#define BK_DYN_FRAME_H

#include <stddef.h>

#include "assembly/system.h"

typedef struct bk_dyn_frame {
    int on;
    double c[3], n[3];              /* a point of the axis (the node), the unit axis   */
    /* the constraint's angle theta(t) = rate t + amp sin(2 pi freq t) + scale a(t) */
    double rate, amp, freq, scale;
    const bk_amplitude *ampl;
    double th0;                     /* theta(0)                                        */
    const bk_reaction *rc;          /* the constraint: linear rows, or a joint (row0)  */
    int joint, row0;
    /* at the time of bk_frame_at: R and its time derivatives (row-major 3 x 3), the
     * left-multiplication matrices of r, r', r'' (4 x 4) */
    double t, R[3][9], L[3][16];
    int nblock;
    int (*block)[5];                /* kind (1 position, 2 vector, 3 quaternion), DOFs  */
    int *rowof;                     /* [ndof] the constraint's row on a DOF, -1: none   */
    double *qa, *qda, *qdda, *nua;  /* the inertial state (bk_frame_inertial)           */
    double *y, *z, *g, *Me, *W, *S;  /* element scratch: maxdof (y, z, g), maxdof^2      */
} bk_dyn_frame;

/* The constraint's angle theta(t) and its k-th time derivative (k = 0, 1, 2). */
double bk_frame_angle(const bk_dyn_frame *f, double t, int k);
/* The kind of block an element field is to the frame: 1 a position, 2 a vector
 * that turns (a gradient), 3 a quaternion, 0 a coordinate it does not turn. */
int bk_frame_field_kind(const bk_element *et, int k);

/* The frame of the model's dynamic.frame (f->on = 0 for "none"): 0, or -1
 * with the reason in msg (not a prescribed rotation to the ground, rows it
 * cannot turn, held DOFs off the axis, out of memory). */
int bk_frame_init(bk_dyn_frame *f, const bk_system *s, char *msg, size_t n);
void bk_frame_free(bk_dyn_frame *f);
/* The frame's rotation at t (f may be NULL: nothing). */
void bk_frame_at(bk_dyn_frame *f, double t);
/* The time the constraint rows are evaluated at: 0 in the frame (its
 * constraint held), else t. */
double bk_frame_ctime(const bk_dyn_frame *f, double t);
/* va = q' + T^T T' y: the inertial velocity in the frame's axes (the
 * velocity the powers of the energy balance are taken with). */
void bk_frame_velocity(const bk_dyn_frame *f, const bk_model *m, const double *q, const double *qd, double *va);
/* The inertial velocity at t = 0 (the model's initial velocities) into the
 * frame's; the frame's node then at rest. */
void bk_frame_initial(bk_dyn_frame *f, const bk_system *s, const double *q, double *qd);
/* The initial accelerations' constraint right-hand side of the frame's constraint
 * (its rows in r after the free ones): zero, the node held still. */
void bk_frame_held_rows(const bk_dyn_frame *f, const bk_system *s, double *r);
/* The state at the frame's time in the inertial frame into f->qa, qda, qdda and
 * the constraint's multipliers turned back (f->nua, for its reactions). */
void bk_frame_inertial(bk_dyn_frame *f, const bk_system *s, const double *q, const double *qd, const double *qdd,
                       const double *nu);
/* The translational frame forces T^T M (T'' y + 2 T' q') into fint; with Ax, kp
 * T^T M T'' + 2 gp T^T M T' into the Newton matrix. */
void bk_frame_forces(bk_dyn_frame *f, const bk_system *s, const double *q, const double *qd, double gp, double kp,
                     double *fint, double *Ax);
/* An element's coordinates and their rates into the inertial frame (before its
 * rotary inertia kernel), and the kernel's force and Jacobians back (Mq NULL:
 * the force only). */
void bk_frame_rotary_in(bk_dyn_frame *f, const bk_element *et, double *qe, double *qde, double *qdde);
void bk_frame_rotary_out(bk_dyn_frame *f, const bk_element *et, double *fe, double *Mq, double *Cq, double *Kq);

#endif
