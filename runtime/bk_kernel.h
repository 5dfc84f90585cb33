/* bk_kernel.h -- the whole contract between generated kernels and the runtime.
 *
 * The generator (gen/) writes, into out/kernels/, one file pair per element
 * (<element>.{c,h}: interpolation, mass and volume integrals, section frame,
 * moment loads, per-element constants) and one per element x material pair
 * (<element>_<material>.{c,h}: energy, internal force, tangent).  Each defines
 * `const` descriptors of the types below; the runtime only calls through them
 * and knows an element by its descriptor alone: what its coordinates are
 * (field roles), what it can do (capabilities), never by names.
 * An element family may put code its elements share into further generated
 * files (the geometrically exact rods: rod_strain.c, rod_common.c,
 * rod_inertia.c); out/kernels/index.json lists, per pair, every file a solver
 * links, and the descriptors point into them like into any other kernel code.
 *
 * Version.  BK_KERNEL_VERSION changes whenever anything below changes.  Every
 * generated file states the version it was generated for and does not compile
 * against another (`#error`), and so does the kernel table of each solver
 * (gen/solver_build.py, from the version index.json records).  The generator
 * reads the version, the geometry slots, the field roles and the capabilities
 * from this file (gen/contract.py).
 *
 * Layouts (all arrays are plain doubles, caller-owned):
 *   geom[BK_NGEOM] element geometry, slots enum bk_geom_slot: length, section
 *                width along the first section axis d1, height along the
 *                second d2, area, second moments about d1 and d2, polar moment
 *                (SI units).  Continuum elements use l, b, h and the band
 *                (layers: each layer of a section is an element of its own on
 *                the same coordinates, integrating its band of the height).
 *   q[ndof]      element coordinates: per node its fields (nodal vectors of 3
 *                components, quaternions of 4), then element-internal unknowns
 *                (Lagrange multipliers of constrained beam theories); what each
 *                field is says field_role.
 *   q0[ndof]     the element's coordinates in the reference configuration.
 *   tab[ntab]    per-element constants from tabulate(geom, q0): quadrature
 *                weights, shape-function gradients, reference strains.
 *                Congruent elements share one table.
 *   mat[nparam]  material parameters, named by param_names (SI units).
 *   f[ndof]      internal force dU/dq.
 *   K[ndof*ndof] tangent df/dq, row-major, full (kernels write the upper
 *                triangle and mirror it).
 *   sec[9*nsample] section resultants (bk_pair.sections): per sample point
 *                the centreline position, the force n and the moment m about
 *                that point, global axes.
 *
 * Kernels are pure: no allocation, no global state, no calls into the runtime;
 * outputs are overwritten, never accumulated.
 */
#ifndef BK_KERNEL_H
#define BK_KERNEL_H

#define BK_KERNEL_VERSION 8

/* Lane kernels (bk_pair.force_lanes, force_tangent_lanes) evaluate BK_LANES
 * elements of one pair per call, so that the compiler vectorizes across
 * elements.  Every array is in structure-of-arrays order: entry k of lane l
 * (the l-th element of the call) at [k * BK_LANES + l]:
 *   q[ndof * BK_LANES]          in   element coordinates
 *   tab[ntab * BK_LANES]        in   each lane's table from tabulate()
 *   mat[nparam * BK_LANES]      in   each lane's material parameters
 *   f[ndof * BK_LANES]          out  internal force (overwritten)
 *   K[ndof * ndof * BK_LANES]   out  tangent, row-major per lane, full
 *                                    (upper triangle computed, mirrored)
 * Lane l gives the result of force() / force_tangent() on lane l's inputs to
 * round-off (the vector code may round differently, so not bitwise).  Every
 * lane is computed: a caller with fewer elements fills the unused lanes with
 * valid inputs (a copy of a used lane) and ignores their outputs. */
#define BK_LANES 8

/* Slots of geom[]. */
enum bk_geom_slot {
    BK_GEOM_L = 0,                    /* element length along the axis (m)           */
    BK_GEOM_B = 1,                    /* section width along d1 (m); circle: diameter */
    BK_GEOM_H = 2,                    /* section height along d2 (m); circle: diameter */
    BK_GEOM_A = 3,                    /* section area (m^2)                           */
    BK_GEOM_I1 = 4,                   /* second moment of area about d1 (m^4)         */
    BK_GEOM_I2 = 5,                   /* second moment of area about d2 (m^4)         */
    BK_GEOM_IP = 6,                   /* polar moment I1 + I2 (m^4)                   */
    BK_GEOM_SHAPE = 7,                /* section shape, enum bk_section_shape (0: unstated) */
    BK_GEOM_BAND_LO = 8,              /* continuum elements: the fractions of h left out */
    BK_GEOM_BAND_HI = 9,              /* below and above the band z in [(lo - 1/2) h,
                                       * (1/2 - hi) h] that tabulate(), mass(), volume()
                                       * and sections() integrate (one layer of a layered
                                       * section); 0, 0: the whole section          */
    BK_GEOM_BAND_AXIS = 10,           /* a layer: the height z / h (0: the middle) of the
                                       * layered section's neutral axis, where a rule
                                       * part with one point through the height (the
                                       * centreline part of selective reduced
                                       * integration) evaluates every layer          */
    BK_GEOM_EIGENSTRAIN = 11,         /* continuum elements: a free isotropic strain e
                                       * (thermal expansion alpha dT of a layer): the
                                       * stress-free state is the reference stretched by
                                       * 1 + e in every direction, tabulate() scales the
                                       * reference map by 1/(1 + e) and the weights by
                                       * (1 + e)^3 (mass and volume stay the reference's);
                                       * 0: none (version 8)                          */
    BK_NGEOM = 12
};

/* Section shapes (capabilities below say which an element takes). */
enum bk_section_shape { BK_SECTION_RECTANGLE = 1, BK_SECTION_CIRCLE = 2 };

/* What a field of the element coordinates is.  Nodal vectors (3 components)
 * are named by the derivative of the position they interpolate: r, r_x = dr/dx
 * along the axis, r_y, r_z across the section (along d1, d2), r_yy, r_yz, r_zz
 * the second section derivatives.  0 is not a role. */
typedef enum bk_field_role {
    BK_FIELD_POSITION = 1,            /* r: position (3)                              */
    BK_FIELD_R_X,                     /* r_x: axial gradient (3)                      */
    BK_FIELD_R_Y,                     /* r_y: section gradient along d1 (3)           */
    BK_FIELD_R_Z,                     /* r_z: section gradient along d2 (3)           */
    BK_FIELD_R_YY,                    /* r_yy: higher section vectors (3 each)        */
    BK_FIELD_R_YZ,
    BK_FIELD_R_ZZ,
    BK_FIELD_QUATERNION,              /* p: nodal rotation, the rotation of p/|p| (4) */
    BK_FIELD_MULTIPLIER               /* lambda: element-internal Lagrange multiplier (1) */
} bk_field_role;

/* Nodal vectors that a rigid rotation turns (and a translation leaves): the
 * gradients of the position. */
static inline int bk_field_is_gradient(bk_field_role role)
{
    return role >= BK_FIELD_R_X && role <= BK_FIELD_R_ZZ;
}

/* Element capabilities, bits of bk_element.caps. */
enum bk_element_cap {
    BK_CAP_SECTION_RECTANGLE = 1 << 0, /* takes rectangular sections b x h            */
    BK_CAP_SECTION_CIRCLE = 1 << 1,    /* takes circular sections (diameter b = h)    */
    BK_CAP_SECTION_FIELD = 1 << 2,     /* shape(xi, y, z) interpolates across the section:
                                        * a point of the section box is the element's
                                        * own (continuum elements); otherwise shape()
                                        * is that of the centreline and ignores y, z */
    BK_CAP_CURVED = 1 << 3,            /* the reference configuration may be curved:
                                        * tabulate(geom, q0) makes it stress free      */
    BK_CAP_MOMENT_ANYWHERE = 1 << 4,   /* moment() on the section at any xi            */
    BK_CAP_MOMENT_NODES = 1 << 5,      /* moment() on the node nearest xi              */
    BK_CAP_MOMENT_NO_TORSION = 1 << 6  /* moment() has no part about the axis (no section
                                        * orientation: the cable)                      */
};

/* Largest element the runtime takes: element DOFs and position shape functions. */
#define BK_MAX_ELEMENT_DOF 1024
#define BK_MAX_SHAPE 128

typedef struct bk_element {
    const char *name;
    const char *title;
    int nnode;                        /* nodes per element                           */
    int ndof;                         /* element coordinates, internal ones included */
    const double *node_xi;            /* [nnode] node positions along the axis, 0..1 */
    unsigned caps;                    /* enum bk_element_cap bits                    */
    /* Fields of the element coordinates, in order: role, name (for messages:
     * "r", "r_x", "r_yz", ..., "p", "lambda"), the first element DOF and the
     * dimension (3, 4 or 1). */
    int nfield;
    const bk_field_role *field_role;
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
    /* Orthonormal section frame at xi, R[9] = e1, e2, e3 (rows): the element's
     * own rotation where it has one (nodal quaternions), else that of frame()'s
     * d: e3 = d3/|d3|, e1 = d1 - (d1 . e3) e3 normalised, e2 = e3 x e1.  When
     * dR is not NULL also its Jacobian dR[9*ndof], dR[k*ndof + j] = dR_k/dq_j
     * (the coordinates as the solver increments them: each one on its own,
     * quaternion components included).  Used by follower loads.  NULL: the
     * element defines no section axes (the cable). */
    void (*section_frame)(const double *restrict geom, double xi, const double *restrict q,
                          double *restrict R, double *restrict dR);
    /* A material line fixed in the sections at the offset a[2] along e1, e2 of
     * section_frame(), P(xi) = r(xi) + a[0] e1 + a[1] e2: its tangent t[3] =
     * dP/dxi; when dt is not NULL its Jacobian dt[3*ndof], dt[k*ndof + j] =
     * dt_k/dq_j; when u and H are not NULL also H[ndof*ndof] = d2(u . t)/dq2
     * (full, symmetric).  Used by tendons and chambers on elements that do not
     * interpolate across the section (rods; continuum elements route them
     * through shape()).  NULL: none.  (Version 8 added it.) */
    void (*section_line)(const double *restrict geom, double xi, const double *restrict q,
                         const double *restrict a, const double *restrict u, double *restrict t,
                         double *restrict dt, double *restrict H);
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
    /* The same for BK_LANES elements per call (see "Lane kernels" above);
     * NULL: not offered (call force() / force_tangent() per element). */
    void (*force_lanes)(const double *restrict q, const double *restrict tab,
                        const double *restrict mat, double *restrict f);
    void (*force_tangent_lanes)(const double *restrict q, const double *restrict tab,
                                const double *restrict mat, double *restrict f,
                                double *restrict K);
    /* Kelvin-Voigt damping with parameters visc[nvisc] (the viscous stiffnesses:
     * retardation time x elastic constants).  viscous_force: the viscous force
     * f(q, qd) = dD/dqd alone (what a residual-only evaluation needs; no
     * contraction), returning the Rayleigh dissipation function D (f . qd = 2 D).
     * viscous: f and the Newton-matrix part K = gc C + gk K_q, C = df/dqd
     * (symmetric) and K_q = df/dq at fixed qd (not symmetric), per point one
     * contraction of the symmetric part and one of the antisymmetric part of
     * K_q; (gc, gk) = (1, 0) gives C, (0, 1) K_q.  K is overwritten, full.  The lane
     * kernels do the same for BK_LANES elements ("Lane kernels" above; qd and
     * visc lane-ordered like q and mat, gc and gk shared).  nvisc 0: none of
     * them offered; the lane kernels may be NULL on their own.  (Version 7:
     * before, one viscous(q, qd, tab, visc, f, C, K) formed C and the stress
     * part of K_q alone, two contractions, on every call.) */
    int nvisc;
    double (*viscous_force)(const double *restrict q, const double *restrict qd, const double *restrict tab,
                            const double *restrict visc, double *restrict f);
    void (*viscous)(const double *restrict q, const double *restrict qd, const double *restrict tab,
                    const double *restrict visc, double gc, double gk, double *restrict f,
                    double *restrict K);
    void (*viscous_force_lanes)(const double *restrict q, const double *restrict qd,
                                const double *restrict tab, const double *restrict visc,
                                double *restrict f);
    void (*viscous_lanes)(const double *restrict q, const double *restrict qd, const double *restrict tab,
                          const double *restrict visc, double gc, double gk, double *restrict f,
                          double *restrict K);
    /* State checks: inv[3 p + 0..2] = J = det F, I1, I2 of C = F^T F at the nqp
     * quadrature points (NULL: not offered, e.g. rod elements), and the range
     * of principal Green strains the law is meant for (both 0: no limit). */
    void (*invariants)(const double *restrict q, const double *restrict tab, double *restrict inv);
    double green_strain_min, green_strain_max;
    /* Section resultants from the element's own stresses at nsample points
     * xi = sample_xi[k] along the axis (0..1): sec[9 k + 0..2] the centreline
     * point, 3..5 the force n and 6..8 the moment m about that point that the
     * part beyond the section (larger xi) exerts on the part before it, global
     * axes.  Rod elements: n = R C Gamma, m = R D K of the law at the Gauss
     * points (components held at zero by multipliers: the multiplier force);
     * the cable: n = W_a - d/dx W_b, m = r' x W_b of its energy W(r', r'');
     * continuum elements: the first Piola-Kirchhoff traction integrated over
     * the reference section, n = int P N0 dA0, m = int (r - r_c) x P N0 dA0.
     * sample_source: a label of where the components come from (sections.csv
     * column `source`, no commas).  NULL: not offered (sections.csv then has
     * the element's nodal-force rows only). */
    int nsample;
    const double *sample_xi;
    const char *sample_source;
    void (*sections)(const double *restrict geom, const double *restrict q, const double *restrict tab,
                     const double *restrict mat, double *restrict sec);
} bk_pair;

#endif
