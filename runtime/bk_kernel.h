/* bk_kernel.h -- the whole contract between generated kernels and the runtime.
 *
 * The generator (gen/) writes, into out/kernels/, one file pair per element
 * (<element>.{c,h}: interpolation, mass and volume integrals, section frame,
 * moment loads, per-element constants) and one per element x material pair
 * (<element>_<material>.{c,h}: energy, internal force, tangent).  Each defines
 * `const` descriptors of the types below; the runtime only calls through them.
 * An element family may put code its elements share into further generated
 * files (the geometrically exact rods: rod_strain.c, rod_common.c,
 * rod_inertia.c); out/kernels/index.json lists, per pair, every file a solver
 * links, and the descriptors point into them like into any other kernel code.
 *
 * Layouts (all arrays are plain doubles, caller-owned):
 *   geom[BK_NGEOM] element geometry: {l, b, h, A, I1, I2, Ip}: length, section
 *                width along the first section axis d1, height along the
 *                second d2, area, second moments about d1 and d2, polar moment
 *                (SI units).  Continuum elements use l, b, h.
 *   q[ndof]      element coordinates: per node its fields (nodal vectors of 3
 *                components, quaternions of 4), then element-internal unknowns
 *                (Lagrange multipliers of constrained beam theories).
 *   q0[ndof]     the element's coordinates in the reference configuration.
 *   tab[ntab]    per-element constants from tabulate(geom, q0): quadrature
 *                weights, shape-function gradients, reference strains.
 *                Congruent elements share one table.
 *   mat[nparam]  material parameters, named by param_names (SI units).
 *   f[ndof]      internal force dU/dq.
 *   K[ndof*ndof] tangent df/dq, row-major, full (kernels write the upper
 *                triangle and mirror it).
 *
 * Kernels are pure: no allocation, no global state, no calls into the runtime;
 * outputs are overwritten, never accumulated.
 */
#ifndef BK_KERNEL_H
#define BK_KERNEL_H

#define BK_NGEOM 7

typedef struct bk_element {
    const char *name;
    const char *title;
    int nnode;                        /* nodes per element                           */
    int ndof;                         /* element coordinates, internal ones included */
    const double *node_xi;            /* [nnode] node positions along the axis, 0..1 */
    /* Fields of the element coordinates, in order: name ("r", "r_x", "r_yz", ...
     * nodal vectors; "p" nodal quaternion; "lambda" internal multiplier), the
     * first element DOF and the dimension (3, 4 or 1). */
    int nfield;
    const char *const *field_name;
    const int *field_dof;
    const int *field_dim;
    /* Coordinates of the straight element along +x with section axes +y, +z. */
    void (*reference)(const double *restrict geom, double *restrict q0);
    /* Position interpolation r(xi, y, z) = sum_a N_a q[shape_dof[a] + (0, 1, 2)]:
     * used for point forces and gravity. */
    int nshape;
    const int *shape_dof;             /* [nshape]                                    */
    void (*shape)(const double *restrict geom, double xi, double y, double z,
                  double *restrict N);
    /* m[a*nshape+b] = integral of N_a N_b over the element volume (m^3). */
    void (*mass)(const double *restrict geom, double *restrict m);
    /* v[a] = integral of N_a over the element volume (m^3). */
    void (*volume)(const double *restrict geom, double *restrict v);
    /* Centreline point xi: position pos[3] and section frame d[9] = d1, d2, d3
     * (section axes, axis-like third vector); entries the element does not
     * define are NaN. */
    void (*frame)(const double *restrict geom, double xi, const double *restrict q,
                  double *restrict pos, double *restrict d);
    /* Moment M (N m, fixed in space) on the section at xi: generalized force
     * Q[ndof] and its Jacobian dQ[ndof*ndof] (row-major).  NULL: the element
     * carries no moments. */
    void (*moment)(const double *restrict geom, double xi, const double *restrict q,
                   const double *restrict M, double *restrict Q, double *restrict dQ);
    /* Inertia not captured by the constant mass of the position interpolation
     * (rotary inertia of beams with nodal rotations), per unit density: force
     * f(q, qd, qdd) = d/dt dT/dqd - dT/dq, its derivatives Mq = df/dqdd,
     * Cq = df/dqd, Kq = df/dq (row-major ndof x ndof) and the kinetic energy T.
     * NULL: none. */
    void (*rotary)(const double *restrict geom, const double *restrict q, const double *restrict qd,
                   const double *restrict qdd, double *restrict f, double *restrict Mq,
                   double *restrict Cq, double *restrict Kq, double *restrict T);
} bk_element;

typedef struct bk_pair {
    const bk_element *element;
    const char *material;
    const char *integration;
    int nparam;
    const char *const *param_names;
    int ntab;
    int nqp;                          /* quadrature points over all rule parts       */
    long ops_force;                   /* operations per element call (see header)    */
    long ops_force_tangent;
    void (*tabulate)(const double *restrict geom, const double *restrict q0,
                     double *restrict tab);
    double (*energy)(const double *restrict q, const double *restrict tab,
                     const double *restrict mat);
    void (*force)(const double *restrict q, const double *restrict tab,
                  const double *restrict mat, double *restrict f);
    void (*force_tangent)(const double *restrict q, const double *restrict tab,
                          const double *restrict mat, double *restrict f,
                          double *restrict K);
    /* Kelvin-Voigt damping: viscous force f(q, qd) with parameters visc[nvisc]
     * (the viscous stiffnesses: retardation time x elastic constants), its
     * derivatives C = df/dqd and K ~ df/dq (the part from the viscous stress,
     * without the variation of the strain rate with q).  NULL: not offered. */
    int nvisc;
    void (*viscous)(const double *restrict q, const double *restrict qd, const double *restrict tab,
                    const double *restrict visc, double *restrict f, double *restrict C,
                    double *restrict K);
    /* State checks: inv[3 p + 0..2] = J = det F, I1, I2 of C = F^T F at the nqp
     * quadrature points (NULL: not offered, e.g. rod elements), and the range
     * of principal Green strains the law is meant for (both 0: no limit). */
    void (*invariants)(const double *restrict q, const double *restrict tab, double *restrict inv);
    double green_strain_min, green_strain_max;
} bk_pair;

#endif
