/* contact_pairs_check.c -- the generated beam-to-beam distance kernels
 * (out/kernels/contact_pairs.c) against central differences of themselves
 * (distance -> gradient -> Hessian) and against distances computed here
 * another way: the point-edge distance by the cross product |w x e| / |e|,
 * the edge-edge distance from the closest points of the two lines (a 2 x 2
 * linear system) as the length of the vector between them, the squared
 * cosine of two segments' angle from their cross product.  Prints the
 * largest errors for tests/test_contact_pairs_kernels.py. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "contact_pairs.h"

typedef void (*dist_fn)(const double *, double *);

static unsigned long long rng = 0x2545F4914F6CDD1DULL;
static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

/* Largest errors of the gradient and Hessian of f (n coordinates) at x
 * against central differences, relative to max(1, |entry|); the Hessian's
 * asymmetry. */
static void fd_check(dist_fn f, int n, const double *x, double *eg, double *eh, double *esym)
{
    double o[160], op[160], om[160], xp[12], xm[12], h = 1e-6;
    f(x, o);
    for (int j = 0; j < n; ++j) {
        memcpy(xp, x, (size_t)n * sizeof *x);
        memcpy(xm, x, (size_t)n * sizeof *x);
        xp[j] += h;
        xm[j] -= h;
        f(xp, op);
        f(xm, om);
        double d = (op[0] - om[0]) / (2 * h);
        *eg = fmax(*eg, fabs(d - o[1 + j]) / fmax(1.0, fabs(o[1 + j])));
        for (int i = 0; i < n; ++i) {
            double dd = (op[1 + i] - om[1 + i]) / (2 * h), hv = o[1 + n + n * i + j];
            *eh = fmax(*eh, fabs(dd - hv) / fmax(1.0, fabs(hv)));
            *esym = fmax(*esym, fabs(hv - o[1 + n + n * j + i]));
        }
    }
}

static double dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

int main(void)
{
    double eg = 0, eh = 0, esym = 0, eclosed = 0, o[160];
    for (int trial = 0; trial < 300; ++trial) {
        double x[12];
        for (int k = 0; k < 12; ++k)
            x[k] = 2 * urand() - 1;
        fd_check(bk_pair_dist_point_point, 6, x, &eg, &eh, &esym);
        bk_pair_dist_point_point(x, o);
        double r[3] = {x[0] - x[3], x[1] - x[4], x[2] - x[5]};
        eclosed = fmax(eclosed, fabs(o[0] - sqrt(dot(r, r))));

        fd_check(bk_pair_dist_point_edge, 9, x, &eg, &eh, &esym);
        bk_pair_dist_point_edge(x, o);
        double e[3] = {x[6] - x[3], x[7] - x[4], x[8] - x[5]}, w[3] = {x[0] - x[3], x[1] - x[4], x[2] - x[5]};
        double c[3] = {w[1] * e[2] - w[2] * e[1], w[2] * e[0] - w[0] * e[2], w[0] * e[1] - w[1] * e[0]};
        eclosed = fmax(eclosed, fabs(o[0] - sqrt(dot(c, c) / dot(e, e))));

        fd_check(bk_pair_dist_edge_edge, 12, x, &eg, &eh, &esym);
        bk_pair_dist_edge_edge(x, o);
        /* closest points a0 + s u, b0 + t v: [u.u  -u.v; u.v  -v.v] (s, t) = (w.u, w.v), w = b0 - a0 */
        double u[3] = {x[3] - x[0], x[4] - x[1], x[5] - x[2]}, v[3] = {x[9] - x[6], x[10] - x[7], x[11] - x[8]};
        double ww[3] = {x[6] - x[0], x[7] - x[1], x[8] - x[2]};
        double A = dot(u, u), B = dot(u, v), C = dot(v, v), det = -A * C + B * B;
        double s = (dot(ww, u) * -C + B * dot(ww, v)) / det, t = (A * dot(ww, v) - B * dot(ww, u)) / det;
        double gap[3];
        for (int i = 0; i < 3; ++i)
            gap[i] = x[6 + i] + t * v[i] - x[i] - s * u[i];
        eclosed = fmax(eclosed, fabs(fabs(o[0]) - sqrt(dot(gap, gap))));

        fd_check(bk_pair_dist_cos2, 12, x, &eg, &eh, &esym);
        bk_pair_dist_cos2(x, o);
        /* cos^2 = 1 - |u x v|^2 / (|u|^2 |v|^2) */
        double cr[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        eclosed = fmax(eclosed, fabs(o[0] - (1.0 - dot(cr, cr) / (A * C))));
    }
    printf("grad_err=%.3e hess_err=%.3e hess_sym_err=%.3e closed_err=%.3e\n", eg, eh, esym, eclosed);
    return 0;
}
