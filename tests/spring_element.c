/* spring_element.c -- an axial spring and an inextensible link written by hand
 * against runtime/bk_kernel.h (see spring_element.h). */
#include "spring_element.h"

#include <math.h>

/* No lane kernels: force_lanes, force_tangent_lanes stay NULL (one element per call);
 * no section resultants: sections stays NULL (sections.csv has the nodal rows only);
 * no damping: the viscous kernels stay NULL. */
#if !defined(BK_KERNEL_VERSION) || BK_KERNEL_VERSION != 8
#error "tests/spring_element.c is written for runtime/bk_kernel.h version 8"
#endif

/* d = r_1 - r_0, its length and direction. */
static double axis(const double *q, double *n)
{
    double d[3] = {q[3] - q[0], q[4] - q[1], q[5] - q[2]};
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int i = 0; i < 3; ++i)
        n[i] = d[i] / len;
    return len;
}

/* Adds s * [B; -B; ...] pattern: K[(a i), (b j)] += sign(a, b) s M_ij for the
 * two nodes a, b (sign + on the diagonal node blocks, - off it). */
static void add_node_blocks(int nd, const double M[9], double s, double *K)
{
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    K[(3 * a + i) * nd + 3 * b + j] += (a == b ? s : -s) * M[3 * i + j];
}

/* Hessian of |d| with respect to d: (I - n n^T) / |d|. */
static void length_hessian(const double *n, double len, double H[9])
{
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            H[3 * i + j] = ((i == j) - n[i] * n[j]) / len;
}

/* ---- element: shared by spring and link (the link adds the multiplier) ---- */

static void reference(const double *restrict geom, double *restrict q0)
{
    for (int i = 0; i < 6; ++i)
        q0[i] = 0.0;
    q0[3] = geom[BK_GEOM_L];
}

static void link_reference(const double *restrict geom, double *restrict q0)
{
    reference(geom, q0);
    q0[6] = 0.0;
}

static void shape(const double *restrict geom, double xi, double y, double z, double *restrict N)
{
    (void)geom; (void)y; (void)z;
    N[0] = 1.0 - xi;
    N[1] = xi;
}

static void mass(const double *restrict geom, double *restrict m)
{
    double c = geom[BK_GEOM_A] * geom[BK_GEOM_L] / 6.0;
    m[0] = m[3] = 2.0 * c;
    m[1] = m[2] = c;
}

static void volume(const double *restrict geom, double *restrict v)
{
    v[0] = v[1] = 0.5 * geom[BK_GEOM_A] * geom[BK_GEOM_L];
}

static void frame(const double *restrict geom, double xi, const double *restrict q, double *restrict pos,
                  double *restrict d)
{
    (void)geom;
    double n[3];
    axis(q, n);
    for (int i = 0; i < 3; ++i) {
        pos[i] = (1.0 - xi) * q[i] + xi * q[3 + i];
        d[i] = d[3 + i] = NAN;
        d[6 + i] = n[i];
    }
}

static const double node_xi[2] = {0.0, 1.0};
static const int shape_dof[2] = {0, 3};
static const bk_field_role spring_roles[2] = {BK_FIELD_POSITION, BK_FIELD_POSITION};
static const char *const spring_names[2] = {"r", "r"};
static const int spring_dofs[2] = {0, 3};
static const int spring_dims[2] = {3, 3};
static const bk_field_role link_roles[3] = {BK_FIELD_POSITION, BK_FIELD_POSITION, BK_FIELD_MULTIPLIER};
static const char *const link_names[3] = {"r", "r", "lambda"};
static const int link_dofs[3] = {0, 3, 6};
static const int link_dims[3] = {3, 3, 1};

const bk_element spring_element = {
    .name = "spring", .title = "axial spring (test element)", .nnode = 2, .ndof = 6, .node_xi = node_xi,
    .caps = 0, .nfield = 2, .field_role = spring_roles, .field_name = spring_names, .field_dof = spring_dofs,
    .field_dim = spring_dims, .reference = reference, .nshape = 2, .shape_dof = shape_dof, .shape = shape,
    .mass = mass, .volume = volume, .frame = frame,
};

const bk_element link_element = {
    .name = "link", .title = "inextensible link (test element)", .nnode = 2, .ndof = 7, .node_xi = node_xi,
    .caps = 0, .nfield = 3, .field_role = link_roles, .field_name = link_names, .field_dof = link_dofs,
    .field_dim = link_dims, .reference = link_reference, .nshape = 2, .shape_dof = shape_dof, .shape = shape,
    .mass = mass, .volume = volume, .frame = frame,
};

/* ---- pairs ---- */

static void tabulate(const double *restrict geom, const double *restrict q0, double *restrict tab)
{
    (void)geom;
    double n[3];
    tab[0] = axis(q0, n);
}

static double spring_energy(const double *restrict q, const double *restrict tab, const double *restrict mat)
{
    double n[3], e = axis(q, n) - tab[0];
    return 0.5 * mat[0] * e * e;
}

static void spring_force(const double *restrict q, const double *restrict tab, const double *restrict mat,
                         double *restrict f)
{
    double n[3], len = axis(q, n), t = mat[0] * (len - tab[0]);
    for (int i = 0; i < 3; ++i) {
        f[i] = -t * n[i];
        f[3 + i] = t * n[i];
    }
}

static void spring_force_tangent(const double *restrict q, const double *restrict tab,
                                 const double *restrict mat, double *restrict f, double *restrict K)
{
    double n[3], H[9], M[9], len = axis(q, n), k = mat[0], t = k * (len - tab[0]);
    spring_force(q, tab, mat, f);
    length_hessian(n, len, H);
    for (int i = 0; i < 9; ++i)
        M[i] = k * n[i / 3] * n[i % 3] + t * H[i];
    for (int i = 0; i < 36; ++i)
        K[i] = 0.0;
    add_node_blocks(6, M, 1.0, K);
}

static double link_energy(const double *restrict q, const double *restrict tab, const double *restrict mat)
{
    double n[3];
    return mat[0] * q[6] * (axis(q, n) - tab[0]);
}

static void link_force(const double *restrict q, const double *restrict tab, const double *restrict mat,
                       double *restrict f)
{
    double n[3], len = axis(q, n), t = mat[0] * q[6];
    for (int i = 0; i < 3; ++i) {
        f[i] = -t * n[i];
        f[3 + i] = t * n[i];
    }
    f[6] = mat[0] * (len - tab[0]);
}

static void link_force_tangent(const double *restrict q, const double *restrict tab, const double *restrict mat,
                               double *restrict f, double *restrict K)
{
    double n[3], H[9], len = axis(q, n), c = mat[0];
    link_force(q, tab, mat, f);
    length_hessian(n, len, H);
    for (int i = 0; i < 49; ++i)
        K[i] = 0.0;
    add_node_blocks(7, H, c * q[6], K);
    for (int i = 0; i < 3; ++i) {
        K[i * 7 + 6] = K[6 * 7 + i] = -c * n[i];
        K[(3 + i) * 7 + 6] = K[6 * 7 + 3 + i] = c * n[i];
    }
}

static const char *const spring_params[1] = {"k"};
static const char *const link_params[1] = {"c"};

const bk_pair spring_pair = {
    .element = &spring_element, .material = "linear", .integration = "exact", .nparam = 1,
    .param_names = spring_params, .ntab = 1, .nqp = 1, .tabulate = tabulate, .energy = spring_energy,
    .force = spring_force, .force_tangent = spring_force_tangent,
};

const bk_pair link_pair = {
    .element = &link_element, .material = "rigid", .integration = "exact", .nparam = 1,
    .param_names = link_params, .ntab = 1, .nqp = 1, .tabulate = tabulate, .energy = link_energy,
    .force = link_force, .force_tangent = link_force_tangent,
};
