/* bk_kernel.h -- the whole contract between generated kernels and the runtime.
 *
 * The generator (gen/) writes, into out/kernels/, one file pair per element
 * (<element>.{c,h}: shape functions, mass, volume integrals, quadrature tables)
 * and one per element x material pair (<element>_<material>.{c,h}: energy,
 * internal force, tangent).  Each defines `const` descriptors of the types
 * below; the runtime only ever calls through them.
 *
 * Layouts (all arrays are plain doubles, caller-owned):
 *   geom[3]      element geometry {l, b, h}: length, section width along the
 *                first section axis, height along the second (m).
 *   q[ndof]      element coordinates, node-major: for each nodal vector
 *                (shape_vector[a] at node shape_node[a]) its x, y, z.
 *   tab[ntab]    per-element constants from tabulate(geom): for each
 *                quadrature point the weight (times l b h) and the nonzero
 *                shape-function gradients.  Depends on geometry only.
 *   mat[nparam]  material parameters, named by param_names (SI units).
 *   f[ndof]      internal force dU/dq (N, or N m for slope coordinates).
 *   K[ndof*ndof] tangent dF/dq, row-major, full (kernels write the upper
 *                triangle and mirror it).
 *
 * Kernels are pure: no allocation, no global state, no calls into the runtime;
 * outputs are overwritten, never accumulated.
 */
#ifndef BK_KERNEL_H
#define BK_KERNEL_H

typedef struct bk_element {
    const char *name;
    const char *title;
    int nnode;                        /* nodes per element                          */
    int nshape;                       /* shape functions (nodal vectors)            */
    int ndof;                         /* 3 * nshape                                 */
    const double *node_xi;            /* [nnode] node positions along the axis, 0..1 */
    const int *shape_node;            /* [nshape] node of each shape function       */
    const char *const *shape_vector;  /* [nshape] "r", "r_x", "r_y", ...            */
    /* N[a] at (xi in [0,1], y, z); dN (optional, may be NULL): [3*nshape] with
     * dN[3a+J] = dN_a/dx_J in physical coordinates. */
    void (*shape)(const double *restrict geom, double xi, double y, double z,
                  double *restrict N, double *restrict dN);
    /* m[a*nshape+b] = integral of N_a N_b over the element volume (m^3). */
    void (*mass)(const double *restrict geom, double *restrict m);
    /* v[a] = integral of N_a over the element volume (m^3). */
    void (*volume)(const double *restrict geom, double *restrict v);
} bk_element;

typedef struct bk_pair {
    const bk_element *element;
    const char *material;
    const char *integration;
    int nparam;
    const char *const *param_names;
    int ntab;
    int nqp;                          /* quadrature points over all rule parts      */
    long ops_force;                   /* operations per element call (see header)   */
    long ops_force_tangent;
    void (*tabulate)(const double *restrict geom, double *restrict tab);
    double (*energy)(const double *restrict q, const double *restrict tab,
                     const double *restrict mat);
    void (*force)(const double *restrict q, const double *restrict tab,
                  const double *restrict mat, double *restrict f);
    void (*force_tangent)(const double *restrict q, const double *restrict tab,
                          const double *restrict mat, double *restrict f,
                          double *restrict K);
} bk_pair;

#endif
