/* median_clock.h -- the wall clock and the median of timings, for the bench
 * programs that take medians of repeated runs (newton_iter.c, band_lapack.c). */
#ifndef BK_BENCH_MEDIAN_CLOCK_H
#define BK_BENCH_MEDIAN_CLOCK_H

#include <stdlib.h>
#include <time.h>

/* Seconds of the monotonic wall clock. */
static inline double bench_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static inline int bench_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of v[n] (n >= 1; v is sorted in place). */
static inline double bench_median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, bench_cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

#endif
