/* numfmt_check.c -- bk_fmt_g17, bk_fmt_e and bk_fmt_g (runtime/base/numfmt.c)
 * against glibc's "%.17g", "%.{prec}e" and "%.{prec}g".
 *
 *   numfmt_check [NRANDOM [NNICE [SEED]]]   checks; exit 0 when all pass
 *   numfmt_check --bench [N]                 ns per value, bk_fmt_g17 vs snprintf
 *   numfmt_check --stdin                     bit patterns (hex, one a line) in,
 *                                            bk_fmt_g17's text out, one a line
 *
 * Every value checked: strtod of the text gives v back bit for bit (finite v),
 * the text is the one snprintf(buf, .., "%.17g", v) writes, and so are those of
 * "%.3e", "%.6e", "%.9e", "%.6g" and of "%.{k}e", "%.{k+1}g" with k going
 * round 0..16 from one value to the next (their mismatches count in
 * mismatch); the returned length
 * is strlen and < BK_NUMFMT_MAX (the output buffer is malloc'ed at exactly
 * BK_NUMFMT_MAX bytes, so AddressSanitizer sees an overrun).  Value sets, one
 * output line each ("set=NAME n=.. mismatch=.. roundtrip=.."):
 *   edge     +-0, inf, nan, subnormal and normal limits, every power of 2 and
 *            its neighbours, powers of 10 (1e-330 .. 1e310) and neighbours,
 *            9.99..9e+k carries, 1000 doubles each side of %g's notation
 *            switches (1e-5, 1e-4, 1e16, 1e17), the two doubles nearest a
 *            rounding boundary without being on it
 *   halfway  doubles whose exact decimal has 18 significant digits ending in 5
 *            (m 2^-j, m odd, m 5^j in [1e17, 1e18)): the only halfway cases of
 *            17 digits, rounded to even by glibc; and their neighbours
 *   random   NRANDOM random bit patterns
 *   nice     NNICE values like a CSV holds: short decimals (d.dddEk), integers,
 *            i*0.001, a/b, log-uniform in [1e-20, 1e20], running sums, sin(i)
 * Allowed mismatches: none.  A mismatch is printed with both texts (the first
 * 20) and makes the exit status 1; a round-trip failure too.
 */
#include "base/numfmt.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static char *out;                /* BK_NUMFMT_MAX bytes, malloc'ed */
static long n_checked, n_mismatch, n_roundtrip, n_printed;

static uint64_t rng_state = 0x9E3779B97F4A7C15u;

static uint64_t rnd(void)       /* splitmix64 */
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15u);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    return z ^ (z >> 31);
}

static double unit(void)        /* uniform in [0, 1) */
{
    return (double)(rnd() >> 11) * 0x1p-53;
}

static double from_bits(uint64_t b)
{
    double v;
    memcpy(&v, &b, sizeof v);
    return v;
}

static uint64_t to_bits(double v)
{
    uint64_t b;
    memcpy(&b, &v, sizeof b);
    return b;
}

/* bk_fmt_e / bk_fmt_g against snprintf's "%.{prec}e" / "%.{prec}g" (no
 * round-trip: fewer digits). */
static void check_prec(double v, int is_e, int prec)
{
    char ref[64];
    int len = is_e ? bk_fmt_e(out, v, prec) : bk_fmt_g(out, v, prec);
    snprintf(ref, sizeof ref, is_e ? "%.*e" : "%.*g", prec, v);
    if (len < 0 || len >= BK_NUMFMT_MAX || (size_t)len != strlen(out) || strcmp(out, ref) != 0) {
        ++n_mismatch;
        if (n_printed++ < 20)
            fprintf(stderr, "bits=%016llx %%.%d%c numfmt=\"%s\" (len %d) glibc=\"%s\"\n",
                    (unsigned long long)to_bits(v), prec, is_e ? 'e' : 'g', out, len, ref);
    }
}

static void check(double v)
{
    /* the precisions the tables use, and one more of each kind in turn */
    static int turn;
    check_prec(v, 1, 3);
    check_prec(v, 1, 6);
    check_prec(v, 1, 9);
    check_prec(v, 0, 6);
    check_prec(v, 1, turn % 17);
    check_prec(v, 0, 1 + turn % 17);
    turn++;
    char ref[64];
    int len = bk_fmt_g17(out, v);
    snprintf(ref, sizeof ref, "%.17g", v);
    ++n_checked;
    int bad = 0;
    if (len < 0 || len >= BK_NUMFMT_MAX || (size_t)len != strlen(out)) {
        ++n_mismatch;
        bad = 1;
    } else if (strcmp(out, ref) != 0) {
        ++n_mismatch;
        bad = 1;
    }
    if (!isnan(v) && to_bits(strtod(out, NULL)) != to_bits(v)) {
        ++n_roundtrip;
        bad = 1;
    }
    if (bad && n_printed++ < 20)
        fprintf(stderr, "bits=%016llx numfmt=\"%s\" (len %d) glibc=\"%s\"\n",
                (unsigned long long)to_bits(v), out, len, ref);
}

static void check_pm(double v)
{
    check(v);
    check(-v);
}

static void check_around(double v, int k)      /* v and k doubles each side */
{
    double lo = v, hi = v;
    check_pm(v);
    for (int i = 0; i < k; ++i) {
        lo = nextafter(lo, 0.0);
        hi = nextafter(hi, INFINITY);
        check_pm(lo);
        if (isfinite(hi))
            check_pm(hi);
    }
}

static void report(const char *set, long n0, long mis0, long rt0)
{
    printf("set=%s n=%ld mismatch=%ld roundtrip=%ld\n", set, n_checked - n0, n_mismatch - mis0,
           n_roundtrip - rt0);
}

static void edge_values(void)
{
    char s[64];
    check_pm(0.0);
    check_pm(INFINITY);
    check(NAN);
    check(-NAN);
    check(from_bits(0x7ff0000000000001u));     /* signalling-type payloads */
    check(from_bits(0xfff8000000000123u));
    check_around(from_bits(1), 3);             /* smallest subnormal */
    check_around(from_bits(0x000fffffffffffffu), 3);   /* largest subnormal */
    check_around(DBL_MIN, 3);
    check_around(DBL_MAX, 3);
    for (int i = 0; i < 52; ++i)               /* one-bit subnormals */
        check_pm(from_bits(UINT64_C(1) << i));
    for (int e = -1074; e <= 1023; ++e)        /* each binary exponent, both ends */
        check_around(ldexp(1.0, e), 2);
    for (int e = -330; e <= 310; ++e) {
        snprintf(s, sizeof s, "1e%d", e);
        check_around(strtod(s, NULL), 3);
        const char *forms[] = {"9.9999999999999999e%d", "9.99999999999999995e%d",
                               "9.9999999999999998e%d", "9.999999999999999e%d", "5e%d", "2.5e%d",
                               "1.00000000000000005e%d", "1.2345678901234567e%d"};
        for (size_t j = 0; j < sizeof forms / sizeof *forms; ++j) {
            snprintf(s, sizeof s, forms[j], e);
            double v = strtod(s, NULL);
            if (isfinite(v))
                check_around(v, 1);
        }
    }
    const double sw[] = {1e-5, 1e-4, 1e16, 1e17, 0.99999999999999999e-4, 9.9999999999999999e15,
                         9.99999999999999999e16, 1e-3, 1e15};
    for (size_t i = 0; i < sizeof sw / sizeof *sw; ++i)
        check_around(sw[i], 1000);
    check_pm(9007199254740992.0);              /* 2^53 and neighbours */
    check_pm(9007199254740993.0);
    check_pm(4503599627370495.5);
    /* the doubles nearest a rounding boundary without being on it (an exhaustive
     * search, see runtime/base/numfmt.c): 17 digits, and 18 digits before rounding */
    check_around(0x1.3de005bd620dfp+216, 2);
    check_around(0x1.f92bacb3cb40cp+717, 2);
    check_pm(0.1);
    check_pm(1.0 / 3.0);
    check_pm(2.0 / 3.0);
}

/* Halfway cases: v = m 2^-j with m odd and m 5^j an 18-digit integer, so that
 * v's exact decimal has 18 significant digits, the last one 5. */
static void halfway_values(long n)
{
    uint64_t p5 = 1;
    for (long i = 0; i < n; ++i) {
        int j = 1 + (int)(rnd() % 26);
        p5 = 1;
        for (int t = 0; t < j; ++t)
            p5 *= 5;
        uint64_t lo = (UINT64_C(100000000000000000) + p5 - 1) / p5;
        uint64_t hi = UINT64_C(999999999999999999) / p5;         /* m 5^j < 1e18 */
        if (hi >= UINT64_C(1) << 53)
            hi = (UINT64_C(1) << 53) - 1;
        if (lo > hi)
            continue;
        uint64_t m = (lo + rnd() % (hi - lo + 1)) | 1;
        if (m > hi)
            m -= 2;
        if (m < lo)
            continue;
        double v = ldexp((double)m, -j);                        /* exact */
        if (i % 4 == 0)
            check_around(v, 1);
        else
            check_pm(v);
    }
}

static void random_values(long n)
{
    for (long i = 0; i < n; ++i)
        check(from_bits(rnd()));
}

static double nice_value(long i)
{
    switch (i % 8) {
    case 0: {                                  /* d.ddd e k: 1 to 9 digits */
        char s[48];
        uint64_t p = 10;
        for (int d = (int)(rnd() % 9); d > 0; --d)
            p *= 10;
        snprintf(s, sizeof s, "%llue%d", (unsigned long long)(rnd() % p), (int)(rnd() % 61) - 30);
        return strtod(s, NULL);
    }
    case 1:                                    /* integers up to 2^63 */
        return (double)(int64_t)(rnd() >> (1 + rnd() % 63));
    case 2:
        return (double)(int64_t)(rnd() % 10000000) * 0.001;
    case 3:
        return (double)(1 + rnd() % 1000) / (double)(1 + rnd() % 1000);
    case 4:
        return exp(log(1e-20) + unit() * (log(1e20) - log(1e-20)));
    case 5:
        return (double)(rnd() % 100000) * 1e-6 + (double)(rnd() % 1000);
    case 6:
        return sin((double)i);
    default:
        return (double)(int64_t)(rnd() % 2000001 - 1000000) * 0.1;
    }
}

static void nice_values(long n)
{
    for (long i = 0; i < n; ++i) {
        double v = nice_value(i);
        check(rnd() & 1 ? v : -v);
    }
    double t = 0.0, u = 0.0;                   /* running sums: a time column */
    for (long i = 0; i < n / 8; ++i) {
        check(t += 0.001);
        check(u += 1e-4);
    }
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ns per value for bk_fmt_g17 and snprintf "%.17g" on three kinds of values. */
static int bench(long n)
{
    double *v = malloc((size_t)n * sizeof *v);
    char ref[64];
    if (!v)
        return 2;
    for (int kind = 0; kind < 3; ++kind) {
        const char *name = kind == 0 ? "typical" : kind == 1 ? "short" : "random_bits";
        for (long i = 0; i < n; ++i) {
            if (kind == 0)                     /* solver-like: log-uniform 1e-6..1e6, signs */
                v[i] = (rnd() & 1 ? 1 : -1) * exp(log(1e-6) + unit() * (log(1e6) - log(1e-6)));
            else if (kind == 1)                /* i*0.001 style */
                v[i] = (double)(rnd() % 1000000) * 0.001;
            else
                do
                    v[i] = from_bits(rnd());
                while (!isfinite(v[i]));
        }
        unsigned sum = 0;
        double t0 = now();
        for (long i = 0; i < n; ++i)
            sum += (unsigned)bk_fmt_g17(out, v[i]) + (unsigned char)out[1];
        double t1 = now();
        for (long i = 0; i < n; ++i)
            sum += (unsigned)snprintf(ref, sizeof ref, "%.17g", v[i]) + (unsigned char)ref[1];
        double t2 = now();
        printf("bench=%s n=%ld numfmt_ns=%.1f snprintf_ns=%.1f speedup=%.1f (%u)\n", name, n,
               1e9 * (t1 - t0) / (double)n, 1e9 * (t2 - t1) / (double)n, (t2 - t1) / (t1 - t0), sum & 1);
    }
    free(v);
    return 0;
}

int main(int argc, char **argv)
{
    out = malloc(BK_NUMFMT_MAX);
    if (!out)
        return 2;
    if (argc > 1 && strcmp(argv[1], "--bench") == 0) {
        int r = bench(argc > 2 ? atol(argv[2]) : 2000000);
        free(out);
        return r;
    }
    if (argc > 1 && strcmp(argv[1], "--stdin") == 0) {
        char line[64];
        while (fgets(line, sizeof line, stdin)) {
            bk_fmt_g17(out, from_bits(strtoull(line, NULL, 16)));
            puts(out);
        }
        free(out);
        return 0;
    }
    long nrandom = argc > 1 ? atol(argv[1]) : 2000000;
    long nnice = argc > 2 ? atol(argv[2]) : 1000000;
    if (argc > 3)
        rng_state = strtoull(argv[3], NULL, 0);

    long n0 = n_checked, m0 = n_mismatch, r0 = n_roundtrip;
    edge_values();
    report("edge", n0, m0, r0);
    n0 = n_checked, m0 = n_mismatch, r0 = n_roundtrip;
    halfway_values(nnice / 4 + 1000);
    report("halfway", n0, m0, r0);
    n0 = n_checked, m0 = n_mismatch, r0 = n_roundtrip;
    random_values(nrandom);
    report("random", n0, m0, r0);
    n0 = n_checked, m0 = n_mismatch, r0 = n_roundtrip;
    nice_values(nnice);
    report("nice", n0, m0, r0);
    report("all", 0, 0, 0);
    free(out);
    return n_mismatch || n_roundtrip ? 1 : 0;
}
