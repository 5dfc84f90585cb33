/* reader_int_check.c -- harness of tests/test_reader_int.py: the model
 * reader's integers (runtime/model/reader.c rd_inum, its own decimal parser)
 * against the C library's strtol, token by token.
 *
 * usage: reader_int_check N SEED
 * Makes N random tokens (digit strings of 1 to 25 digits with leading zeros,
 * signs, and tokens strtol reads only in part or not at all: letters,
 * "0x", exponents, a lone sign, a point), reads each with rd_inum in a range
 * [lo, hi] (the whole int range, or a random one), and prints key=value
 * lines: tokens, accepted (by strtol's rule), differ (tokens where rd_inum's
 * value or its error differs from strtol's rule: accepted when strtol reads
 * the whole token with no range error and the value lies in [lo, hi]; then
 * that value, else lo and one error line). */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/reader.h"

static unsigned long long state;

static unsigned rnd(unsigned n)
{
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (unsigned)((state >> 33) % n);
}

static void token(char *t)
{
    static const char *odd[] = {"+", "-", "0x10", "1e3", "12a", "a12", "1.0", "--1", "+-1", "٣", "1_000", "0b1", ".5"};
    int k = 0;
    if (rnd(20) == 0) {
        strcpy(t, odd[rnd(sizeof odd / sizeof *odd)]);
        return;
    }
    int s = rnd(6);
    if (s == 0)
        t[k++] = '-';
    else if (s == 1)
        t[k++] = '+';
    const int nd = 1 + (rnd(4) == 0 ? rnd(25) : rnd(11));
    for (int i = 0; i < nd; ++i)
        t[k++] = (char)('0' + (i == 0 && rnd(3) ? 1 + rnd(9) : rnd(10)));
    if (rnd(50) == 0)
        t[k++] = (char)"x.e-+ "[rnd(5)];
    t[k] = '\0';
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: %s N SEED\n", argv[0]);
        return 2;
    }
    const long n = atol(argv[1]);
    state = strtoull(argv[2], NULL, 10);
    FILE *null = fopen("/dev/null", "w");
    if (!null)
        return 1;
    long accepted = 0, differ = 0;
    char t[64];
    for (long i = 0; i < n; ++i) {
        token(t);
        int lo = INT_MIN, hi = INT_MAX;
        if (rnd(2)) {
            lo = (int)rnd(2000000) - 1000000;
            hi = lo + (int)rnd(2000000);
        }
        char *end;
        errno = 0;
        const long v = strtol(t, &end, 10);
        const int ok = *end == '\0' && end != t && errno == 0 && v >= lo && v <= hi;
        bk_reader r = {0};
        r.buf = t;
        r.len = strlen(t);
        r.path = "check";
        r.err = null;
        const int got = rd_inum(&r, "x", lo, hi);
        accepted += ok;
        if (ok ? (r.failed || got != (int)v) : (!r.failed || got != lo)) {
            if (differ < 5)
                fprintf(stderr, "differ: '%s' in [%d, %d]: strtol %ld (whole %d), rd_inum %d (failed %d)\n", t, lo, hi,
                        v, *end == '\0', got, r.failed);
            ++differ;
        }
    }
    fclose(null);
    printf("tokens=%ld\naccepted=%ld\ndiffer=%ld\n", n, accepted, differ);
    return 0;
}
