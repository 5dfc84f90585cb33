/* clock.h -- wall-clock time for the run's own timings (summary.json wall_s,
 * output_s, stability_s) and for the output intervals: seconds on the
 * monotonic clock (its origin is arbitrary; only differences mean anything). */
#ifndef BK_CLOCK_H
#define BK_CLOCK_H

#include <time.h>

static inline double bk_clock_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#endif
