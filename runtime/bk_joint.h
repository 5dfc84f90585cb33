/* bk_joint.h -- the contract between the generated joint kernels
 * (out/kernels/joints.c, gen/body.py) and the runtime (runtime/assembly/constraints.c).
 *
 * A joint couples two frames a and b, each a node with a position and a
 * rotation quaternion (a rod node, a rigid body) or the ground (constant
 * coordinates).  Layouts (caller-owned doubles):
 *   x[BK_JOINT_NX]      (r_a, p_a, r_b, p_b): positions and quaternions of both
 *                       frames (the rotation is that of p/|p|);
 *   prm[BK_JOINT_NPARAM] (c_a, c_b, A_a, A_b, c, s): the joint point in each frame,
 *                       the joint axes in each frame (3 x 3, column-major: the
 *                       columns are the axes, the third the joint axis) and,
 *                       for a driven joint, the drive's (c, s) at the time:
 *                       (cos th, sin th) of a prescribed rotation, (1, x) of a
 *                       prescribed translation (0 for the other kinds);
 *   g[nrow]             the constraint values, zero when the joint holds;
 *   G[nrow * NX]        dg/dx, row-major;
 *   H[NX * NX]          sum_k nu[k] d2 g_k / dx2 (full, symmetric).
 * The welds of an ANCF node to a frame (weld_vectors, weld_vector,
 * weld_tangent) read x[0 .. 5] as nodal vectors of the ANCF node and x[10 .. 13]
 * as p_b (x[6 .. 9] unused), prm[6 .. 11] as their reference directions in
 * frame b (gen/body.py); the runtime treats every kind alike.
 * A driven joint's last row is linear and homogeneous in (c, s): its k-th
 * time derivative (and that of its Jacobian) is the same row evaluated with
 * the k-th time derivatives of (c, s).
 * Kernels are pure: no allocation, no global state; outputs overwritten.
 */
#ifndef BK_JOINT_H
#define BK_JOINT_H

#define BK_JOINT_VERSION 2
#define BK_JOINT_NX 14
#define BK_JOINT_NPARAM 26
#define BK_JOINT_NGEOM 24      /* prm[0 .. 23]: the geometry, from the model file */
#define BK_JOINT_MAXROW 6

typedef struct bk_joint_kind {
    const char *name;                 /* the scene's constraint.type                 */
    int nrow;                         /* constraint equations                         */
    void (*eval)(const double *restrict x, const double *restrict prm, double *restrict g,
                 double *restrict G);
    void (*hessian)(const double *restrict x, const double *restrict prm, const double *restrict nu,
                    double *restrict H);
    int driven;                       /* 0; 1: prescribed rotation; 2: prescribed translation */
} bk_joint_kind;

#endif
