/* plain.h -- a plain quadrature-loop implementation of the ANCF continuum
 * element internal force and tangent, for the kernel benchmark (bench/).
 *
 * Written the way one writes it by hand, not from the generator: at each
 * quadrature point the deformation gradient F = sum_a q_a (x) grad N_a, the
 * invariants I1, I2, J, the first Piola-Kirchhoff stress
 * P = W1 dI1/dF + W2 dI2/dF + W3 dJ/dF and the 9 x 9 material tangent
 * A = dP/dF (chain rule through the invariants), then
 *     f_a += w P grad N_a,   K_ab += w grad N_a . A . grad N_b
 * with runtime loops over nodes, points and tensor indices and the full
 * (not only the upper) tangent.  The shape-function gradients at the points
 * are tabulated once (bench/plain_tab: written by report/bench_kernels.py).
 */
#ifndef BK_PLAIN_H
#define BK_PLAIN_H

enum { PLAIN_SVK = 0, PLAIN_NEO_HOOKEAN, PLAIN_MOONEY_RIVLIN, PLAIN_ARRUDA_BOYCE };

typedef struct plain_rule {
    int npts, nshape;
    const double *pts;   /* per point: weight (volume incl.), then grad N_a (3 per shape function) */
} plain_rule;

/* law by name, or -1 */
int plain_law(const char *name);

/* f[3*nshape]; K[(3 nshape)^2] row-major (NULL: force only). */
void plain_force_tangent(const plain_rule *r, int law, const double *mat, const double *q,
                         double *f, double *K);

#endif
