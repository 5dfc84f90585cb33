/* elastica_gsl.c -- closed-form inextensible elastica of a cantilever with a tip load
 * perpendicular to its undeformed axis (load direction fixed), with GSL's elliptic
 * integrals.  usage: elastica_gsl L EI P  ->  prints "u w": tip displacement along
 * the undeformed axis and along the load.
 *
 * With lambda = sqrt(P/EI) and k^2 = (1 + sin theta_L)/2 (theta_L the tip angle),
 * phi0 = asin(1/(sqrt(2) k)):
 *   lambda L = K(k) - F(phi0, k)
 *   x_L = 2 k cos(phi0) / lambda,   w = L - 2 (E(k) - E(phi0, k)) / lambda.
 */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_ellint.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static double residual(double k, double lL)
{
    double phi0 = asin(1.0 / (sqrt(2.0) * k));
    return gsl_sf_ellint_Kcomp(k, GSL_PREC_DOUBLE) - gsl_sf_ellint_F(phi0, k, GSL_PREC_DOUBLE) - lL;
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: %s L EI P\n", argv[0]);
        return 1;
    }
    double L = atof(argv[1]), EI = atof(argv[2]), P = atof(argv[3]);
    double lam = sqrt(P / EI), lL = lam * L;
    double lo = 1.0 / sqrt(2.0) * (1.0 + 1e-15), hi = 1.0 - 1e-16;
    for (int i = 0; i < 200; ++i) {
        double mid = 0.5 * (lo + hi);
        if (residual(mid, lL) > 0.0)
            hi = mid;
        else
            lo = mid;
    }
    double k = 0.5 * (lo + hi), phi0 = asin(1.0 / (sqrt(2.0) * k));
    double x = 2.0 * k * cos(phi0) / lam;
    double w = L - 2.0 * (gsl_sf_ellint_Ecomp(k, GSL_PREC_DOUBLE) - gsl_sf_ellint_E(phi0, k, GSL_PREC_DOUBLE)) / lam;
    printf("%.17g %.17g\n", x - L, w);
    return 0;
}
