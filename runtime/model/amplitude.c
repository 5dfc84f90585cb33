/* amplitude.c -- ramp, step, sine and piecewise-linear table amplitudes. */
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
