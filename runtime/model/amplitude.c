/* amplitude.c -- ramp, step, sine, piecewise-linear table, cycloidal and quintic
 * rest-to-rest and cubic-spline amplitudes with their first two derivatives. */
#include "model/amplitude.h"

#include <math.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

double bk_amp_eval(const bk_amplitude *a, double x, int k)
{
    const double *p = a->par;
    switch (a->type) {
    case BK_AMP_RAMP:
        if (x <= p[0])
            return 0.0;
        if (x >= p[1])
            return k == 0 ? 1.0 : 0.0;
        return k == 0 ? (x - p[0]) / (p[1] - p[0]) : k == 1 ? 1.0 / (p[1] - p[0]) : 0.0;
    case BK_AMP_STEP:
        return k == 0 && x >= p[0] ? 1.0 : 0.0;
    case BK_AMP_SINE: {
        double w = 2.0 * M_PI * p[1], ph = w * x + p[2];
        return k == 0 ? p[3] + p[0] * sin(ph) : k == 1 ? p[0] * w * cos(ph) : -p[0] * w * w * sin(ph);
    }
    case BK_AMP_TABLE: {
        int n = a->npar / 2;
        if (x <= p[0])
            return k == 0 ? p[1] : 0.0;
        if (x >= p[2 * (n - 1)])
            return k == 0 ? p[2 * n - 1] : 0.0;
        int lo = 0, hi = n - 1;            /* p[2 lo] <= x < p[2 hi] */
        while (hi - lo > 1) {
            int mid = (lo + hi) / 2;
            if (p[2 * mid] <= x)
                lo = mid;
            else
                hi = mid;
        }
        double x0 = p[2 * lo], a0 = p[2 * lo + 1], x1 = p[2 * hi], a1 = p[2 * hi + 1];
        double slope = (a1 - a0) / (x1 - x0);
        return k == 0 ? a0 + slope * (x - x0) : k == 1 ? slope : 0.0;
    }
    case BK_AMP_CYCLOID:
    case BK_AMP_QUINTIC: {
        const double T = p[1] - p[0], u = (x - p[0]) / T;
        if (u <= 0.0)
            return 0.0;
        if (u >= 1.0)
            return k == 0 ? 1.0 : 0.0;
        if (a->type == BK_AMP_CYCLOID) {        /* u - sin(2 pi u)/(2 pi) */
            const double w = 2.0 * M_PI;
            return k == 0 ? u - sin(w * u) / w : k == 1 ? (1.0 - cos(w * u)) / T : w * sin(w * u) / (T * T);
        }
        const double v = 1.0 - u;               /* 10 u^3 - 15 u^4 + 6 u^5 */
        return k == 0 ? u * u * u * (10.0 - 15.0 * u + 6.0 * u * u) : k == 1 ? 30.0 * u * u * v * v / T
                                                                              : 60.0 * u * v * (v - u) / (T * T);
    }
    case BK_AMP_SPLINE: {
        int n = a->npar / 3;
        if (x <= p[0] || n < 2)
            return k == 0 ? p[1] : 0.0;
        if (x >= p[3 * (n - 1)])
            return k == 0 ? p[3 * n - 2] : 0.0;
        int lo = 0, hi = n - 1;            /* p[3 lo] <= x < p[3 hi] */
        while (hi - lo > 1) {
            int mid = (lo + hi) / 2;
            if (p[3 * mid] <= x)
                lo = mid;
            else
                hi = mid;
        }
        const double h = p[3 * hi] - p[3 * lo], A = (p[3 * hi] - x) / h, B = 1.0 - A;
        const double y0 = p[3 * lo + 1], m0 = p[3 * lo + 2], y1 = p[3 * hi + 1], m1 = p[3 * hi + 2];
        if (k == 0)
            return A * y0 + B * y1 + ((A * A * A - A) * m0 + (B * B * B - B) * m1) * h * h / 6.0;
        if (k == 1)
            return (y1 - y0) / h - (3.0 * A * A - 1.0) * h * m0 / 6.0 + (3.0 * B * B - 1.0) * h * m1 / 6.0;
        return A * m0 + B * m1;
    }
    default:
        return 0.0;
    }
}

double bk_load_factor(const bk_model *m, int amp, double x)
{
    if (amp < 0)
        return bk_model_in_time(m) ? 1.0 : x;
    return bk_amp_eval(&m->amps[amp], x, 0);
}
