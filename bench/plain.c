/* plain.c -- plain quadrature loop for ANCF continuum elements (see plain.h). */
#include "plain.h"

#include <math.h>
#include <string.h>

int plain_law(const char *name)
{
    static const char *const names[] = {"svk", "neo_hookean", "mooney_rivlin", "arruda_boyce"};
    for (int i = 0; i < 4; ++i)
        if (strcmp(name, names[i]) == 0)
            return i;
    return -1;
}

/* First and second derivatives of W(I1, I2, J): d[3] = (W1, W2, W3),
 * dd[3][3] symmetric. */
static void law_derivatives(int law, const double *p, double I1, double I2, double J, double d[3],
                            double dd[3][3])
{
    memset(d, 0, 3 * sizeof *d);
    memset(dd, 0, 9 * sizeof **dd);
    switch (law) {
    case PLAIN_SVK: {            /* lambda/2 (trE)^2 + mu tr(E^2) */
        double lam = p[0], mu = p[1];
        d[0] = 0.25 * lam * (I1 - 3.0) + 0.5 * mu * (I1 - 1.0);
        d[1] = -0.5 * mu;
        dd[0][0] = 0.25 * lam + 0.5 * mu;
        break;
    }
    case PLAIN_NEO_HOOKEAN: {    /* mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2 */
        double lam = p[0], mu = p[1], lj = log(J);
        d[0] = 0.5 * mu;
        d[2] = (-mu + lam * lj) / J;
        dd[2][2] = (mu + lam * (1.0 - lj)) / (J * J);
        break;
    }
    case PLAIN_MOONEY_RIVLIN: {  /* c10 (Ib1 - 3) + c01 (Ib2 - 3) + kappa/2 (J - 1)^2 */
        double c10 = p[0], c01 = p[1], kap = p[2];
        double x = pow(J, -2.0 / 3.0), y = pow(J, -4.0 / 3.0);
        d[0] = c10 * x;
        d[1] = c01 * y;
        d[2] = -2.0 / 3.0 * c10 * x / J * I1 - 4.0 / 3.0 * c01 * y / J * I2 + kap * (J - 1.0);
        dd[0][2] = dd[2][0] = -2.0 / 3.0 * c10 * x / J;
        dd[1][2] = dd[2][1] = -4.0 / 3.0 * c01 * y / J;
        dd[2][2] = 10.0 / 9.0 * c10 * x / (J * J) * I1 + 28.0 / 9.0 * c01 * y / (J * J) * I2 + kap;
        break;
    }
    case PLAIN_ARRUDA_BOYCE: {   /* mu sum C_i lm^(2-2i) (Ib1^i - 3^i) + kappa/2 (J - 1)^2 */
        static const double c[5] = {0.5, 1.0 / 20.0, 11.0 / 1050.0, 19.0 / 7000.0, 519.0 / 673750.0};
        double mu = p[0], lm = p[1], kap = p[2];
        double x = pow(J, -2.0 / 3.0), Ib = x * I1;
        double g1 = 0.0, g2 = 0.0, s = 1.0;  /* dg/dIb, d2g/dIb2 */
        for (int i = 0; i < 5; ++i) {
            double ci = mu * c[i] / s;       /* s = lm^(2i) */
            g1 += ci * (i + 1) * pow(Ib, i);
            if (i > 0)
                g2 += ci * (i + 1) * i * pow(Ib, i - 1);
            s *= lm * lm;
        }
        double dIbJ = -2.0 / 3.0 * x / J * I1;       /* dIb/dJ */
        d[0] = g1 * x;
        d[2] = g1 * dIbJ + kap * (J - 1.0);
        dd[0][0] = g2 * x * x;
        dd[0][2] = dd[2][0] = g2 * x * dIbJ - 2.0 / 3.0 * g1 * x / J;
        dd[2][2] = g2 * dIbJ * dIbJ + g1 * 10.0 / 9.0 * x / (J * J) * I1 + kap;
        break;
    }
    }
}

static int eps3(int i, int j, int k)
{
    return ((i - j) * (j - k) * (k - i)) / 2;
}

void plain_force_tangent(const plain_rule *r, int law, const double *mat, const double *q,
                         double *f, double *K)
{
    const int ns = r->nshape, nd = 3 * ns, stride = 1 + 3 * ns;
    memset(f, 0, (size_t)nd * sizeof *f);
    if (K)
        memset(K, 0, (size_t)nd * nd * sizeof *K);
    for (int p = 0; p < r->npts; ++p) {
        const double *pt = r->pts + (size_t)p * stride;
        const double w = pt[0], *g = pt + 1;
        double F[3][3] = {{0}}, C[3][3], B[3][3], FC[3][3], cof[3][3];
        for (int a = 0; a < ns; ++a)
            for (int i = 0; i < 3; ++i)
                for (int k = 0; k < 3; ++k)
                    F[i][k] += q[3 * a + i] * g[3 * a + k];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                C[i][j] = B[i][j] = 0.0;
                for (int k = 0; k < 3; ++k) {
                    C[i][j] += F[k][i] * F[k][j];
                    B[i][j] += F[i][k] * F[j][k];
                }
            }
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                FC[i][j] = 0.0;
                for (int k = 0; k < 3; ++k)
                    FC[i][j] += F[i][k] * C[k][j];
            }
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k) {
                int i1 = (i + 1) % 3, i2 = (i + 2) % 3, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
                cof[i][k] = F[i1][k1] * F[i2][k2] - F[i1][k2] * F[i2][k1];
            }
        double I1 = C[0][0] + C[1][1] + C[2][2], trCC = 0.0, J = 0.0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                trCC += C[i][j] * C[j][i];
        for (int k = 0; k < 3; ++k)
            J += F[0][k] * cof[0][k];
        double I2 = 0.5 * (I1 * I1 - trCC);
        double d[3], dd[3][3];
        law_derivatives(law, mat, I1, I2, J, d, dd);
        double dI[3][3][3];   /* dI_m/dF_iK */
        double P[3][3];
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k) {
                dI[0][i][k] = 2.0 * F[i][k];
                dI[1][i][k] = 2.0 * (I1 * F[i][k] - FC[i][k]);
                dI[2][i][k] = cof[i][k];
                P[i][k] = d[0] * dI[0][i][k] + d[1] * dI[1][i][k] + d[2] * dI[2][i][k];
            }
        for (int a = 0; a < ns; ++a)
            for (int i = 0; i < 3; ++i) {
                double s = 0.0;
                for (int k = 0; k < 3; ++k)
                    s += P[i][k] * g[3 * a + k];
                f[3 * a + i] += w * s;
            }
        if (!K)
            continue;
        double A[3][3][3][3];  /* A[i][K][j][L] = d2W/dF_iK dF_jL */
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k)
                for (int j = 0; j < 3; ++j)
                    for (int l = 0; l < 3; ++l) {
                        double v = 0.0;
                        for (int m = 0; m < 3; ++m)
                            for (int n = 0; n < 3; ++n)
                                v += dd[m][n] * dI[m][i][k] * dI[n][j][l];
                        double dij = i == j, dkl = k == l;
                        v += d[0] * 2.0 * dij * dkl;
                        v += d[1] * (4.0 * F[i][k] * F[j][l] + 2.0 * I1 * dij * dkl -
                                     2.0 * (dij * C[k][l] + F[i][l] * F[j][k] + B[i][j] * dkl));
                        double h = 0.0;
                        for (int kk = 0; kk < 3; ++kk)
                            for (int mm = 0; mm < 3; ++mm) {
                                int e1 = eps3(i, j, kk), e2 = eps3(k, l, mm);
                                if (e1 && e2)
                                    h += e1 * e2 * F[kk][mm];
                            }
                        v += d[2] * h;
                        A[i][k][j][l] = v;
                    }
        for (int a = 0; a < ns; ++a) {
            double G[3][3][3];  /* G[i][j][L] = sum_K g_aK A[i][K][j][L] */
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    for (int l = 0; l < 3; ++l) {
                        double s = 0.0;
                        for (int k = 0; k < 3; ++k)
                            s += g[3 * a + k] * A[i][k][j][l];
                        G[i][j][l] = s;
                    }
            for (int b = 0; b < ns; ++b)
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j) {
                        double s = 0.0;
                        for (int l = 0; l < 3; ++l)
                            s += G[i][j][l] * g[3 * b + l];
                        K[(size_t)(3 * a + i) * nd + 3 * b + j] += w * s;
                    }
        }
    }
}
