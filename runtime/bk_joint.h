/* bk_joint.h -- the contract between the generated joint kernels
 * (out/kernels/joints.c, gen/body.py) and the runtime (runtime/assembly/constraints.c).
 *
 * A joint couples two frames a and b, each a node with a position and a
 * rotation quaternion (a rod node, a rigid body) or the ground (constant
 * coordinates).  Layouts (caller-owned doubles):
 *   x[BK_JOINT_NX]      (r_a, p_a, r_b, p_b): positions and quaternions of both
 *                       frames (the rotation is that of p/|p|);
 *   prm[BK_JOINT_NPARAM] (c_a, c_b, A_a, A_b): the joint point in each frame and
 *                       the joint axes in each frame (3 x 3, column-major: the
 *                       columns are the axes, the third the joint axis);
 *   g[nrow]             the constraint values, zero when the joint holds;
 *   G[nrow * NX]        dg/dx, row-major;
 *   H[NX * NX]          sum_k nu[k] d2 g_k / dx2 (full, symmetric).
 * Kernels are pure: no allocation, no global state; outputs overwritten.
 */
#ifndef BK_JOINT_H
#define BK_JOINT_H

#define BK_JOINT_VERSION 1
#define BK_JOINT_NX 14
#define BK_JOINT_NPARAM 24
#define BK_JOINT_MAXROW 6

typedef struct bk_joint_kind {
    const char *name;                 /* the scene's constraint.type                 */
    int nrow;                         /* constraint equations                         */
    void (*eval)(const double *restrict x, const double *restrict prm, double *restrict g,
                 double *restrict G);
    void (*hessian)(const double *restrict x, const double *restrict prm, const double *restrict nu,
                    double *restrict H);
} bk_joint_kind;

#endif
