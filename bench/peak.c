/* peak.c -- one core's peak double-precision FLOP rate, measured
 * (./build.sh bench, report/bench_kernels.py measured_peak).
 *
 * usage: bench_peak
 * Prints "peak_gflops,RATE": the fastest of PASSES timed loops of fused
 * multiply-adds on 64-byte vectors (8 doubles: one AVX-512 register, two AVX2
 * ones), NACC independent chains so that the FMA units never wait for a
 * result (latency 4 cycles x 2 units needs 8).  It is what the lane kernels'
 * arithmetic could reach on this core at the clock it runs vector code at: a
 * figure read off /proc/cpuinfo (flags x nominal MHz) assumes the nominal
 * clock, which AVX-512 code on many CPUs does not get, and an FMA unit count
 * that not every model has.  Times are the thread's CPU time, as in
 * bench/kernels.c.
 */
#include <stdio.h>
#include <time.h>

#define NACC 16
#define ITERS 2000000L
#define PASSES 7

typedef double v8d __attribute__((vector_size(64)));

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* NACC chains acc = acc a + b (each converges to b / (1 - a): no overflow, no
 * subnormal); returns their sum so that nothing is optimized away. */
__attribute__((noinline)) static double fma_chains(long iters, double a, double b)
{
    v8d acc[NACC], x, y;
    for (int k = 0; k < 8; ++k) {
        x[k] = a;
        y[k] = b;
    }
    for (int c = 0; c < NACC; ++c)
        for (int k = 0; k < 8; ++k)
            acc[c][k] = c + k;
    for (long i = 0; i < iters; ++i) {
#pragma GCC unroll 16
        for (int c = 0; c < NACC; ++c)
            acc[c] = acc[c] * x + y;
    }
    double s = 0.0;
    for (int c = 0; c < NACC; ++c)
        for (int k = 0; k < 8; ++k)
            s += acc[c][k];
    return s;
}

int main(void)
{
    double best = 1e30, sum = 0.0;
    for (int p = 0; p < PASSES; ++p) {
        double t0 = now();
        sum += fma_chains(ITERS, 0.9999999, 1e-7);
        double t = now() - t0;
        if (t < best)
            best = t;
    }
    const double flops = (double)ITERS * NACC * 8 * 2;   /* an FMA: two operations */
    printf("peak_gflops,%.4f\n", flops / best / 1e9);
    return sum == sum ? 0 : 1;                           /* (uses the sum) */
}
