/* numfmt.c -- bk_fmt_g17: a double as "%.17g" writes it (see numfmt.h).
 *
 * What it computes.  For finite v != 0 let |v| = m 2^e (m a 53-bit integer,
 * top bit set; subnormals normalized), E = e + 52 and k0 = floor(E log10 2)
 * (the integer formula in the code is checked for every E), so that
 * 10^k0 <= |v| < 10^(k0+2).  With p = 16 - k0, X = |v| 10^p lies in
 * [1e16, 1e18): its integer part has 17 or 18 digits.  The digits of "%.17g"
 * are Y = X (17 digits) or Y = X / 10 (18 digits), i.e. Y = m 2^e 10^p' with
 * p' = p or p - 1, rounded to an integer, a halfway case to even as glibc does;
 * the decimal exponent is 16 - p' (+1 when rounding carries to 1e17).  The
 * digits are then laid out as %g lays them out.
 *
 * Method.  10^p = T 2^b with T in [2^127, 2^128); the table holds T' = floor(T)
 * for p in [-291, 340] (made with Python integers: T' = 10^p >> b for p >= 0,
 * else 2^-b // 10^-p; b = floor(p log2 10) - 127 is pow10_exp2, checked against
 * the table for every p).  X' = m T' 2^-s, s = -(e + b), is one 53 x 128-bit
 * product (two 64 x 64 -> 128 multiplies); s is in [123, 126] for every binary
 * exponent (checked when the table was made), so X' splits into a 64-bit
 * integer part q and the top 64 bits f of its fraction.
 *
 * Error argument.  T - T' < 1 and m < 2^53, so 0 <= X - m T' 2^-s < 2^53 2^-123
 * = 2^-70, and dropping the fraction bits below f loses < 2^-64: the exact X
 * lies in [q + f 2^-64, q + (f + 1.125) 2^-64).  Rounding to nearest changes
 * only at a boundary B (q + 1/2 for 17 digits, 10j + 5 for 18); when B is not
 * in that interval every value in it rounds alike, so the digits are exact.
 * That leaves f in {2^63 - 1, 2^63} (17 digits), or r = q mod 10 = 5 with
 * f = 0, or r = 4 with f = 2^64 - 1 (18 digits).  There `halfway` decides
 * exactly: Y is a half-integer iff 2Y = m 2^(e+1+p') 5^p' is an odd integer (a
 * condition on the exponent of 2 and, for p' < 0, divisibility of m by
 * 5^-p'), and a halfway Y goes to even.  A value in that window that is not
 * halfway lies within 1.125 2^-64 of B without being on it; it is handed to
 * snprintf("%.17g"), which is exact.  An exhaustive search in exact rational
 * arithmetic (for each binary exponent and p', all m in [2^52, 2^53) with
 * Y mod 1 that close to 1/2 -- a tenth of that for Y = X / 10 -- enumerated
 * with a Euclid-like first-hit algorithm for a m mod b in an interval) found
 * one such magnitude among all doubles: 0x1.3de005bd620dfp+216 =
 * 130766226318786535e48 + 3.72e29 (in tests/numfmt_check.c; a second hit, at
 * 2^717, has an 18-digit X, so it is not in a window).  So the text is
 * glibc's always, and it round-trips because 17 correctly rounded digits
 * identify any double.  Pure integer arithmetic: the same bytes natively and
 * under valgrind.
 */
#include "base/numfmt.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

typedef unsigned __int128 bk_u128;

#include "base/pow10_table.h"

/* b with 10^p in [2^(b+127), 2^(b+128)): floor(p log2 10) - 127, checked for
 * every p of the table (gcc shifts a negative int arithmetically: a floor). */
static inline int pow10_exp2(int p)
{
    return ((p * 1741647) >> 19) - 127;
}

static const char digits2[200] = {
    '0','0','0','1','0','2','0','3','0','4','0','5','0','6','0','7','0','8','0','9',
    '1','0','1','1','1','2','1','3','1','4','1','5','1','6','1','7','1','8','1','9',
    '2','0','2','1','2','2','2','3','2','4','2','5','2','6','2','7','2','8','2','9',
    '3','0','3','1','3','2','3','3','3','4','3','5','3','6','3','7','3','8','3','9',
    '4','0','4','1','4','2','4','3','4','4','4','5','4','6','4','7','4','8','4','9',
    '5','0','5','1','5','2','5','3','5','4','5','5','5','6','5','7','5','8','5','9',
    '6','0','6','1','6','2','6','3','6','4','6','5','6','6','6','7','6','8','6','9',
    '7','0','7','1','7','2','7','3','7','4','7','5','7','6','7','7','7','8','7','9',
    '8','0','8','1','8','2','8','3','8','4','8','5','8','6','8','7','8','8','8','9',
    '9','0','9','1','9','2','9','3','9','4','9','5','9','6','9','7','9','8','9','9',
};

/* The 8 decimal digits of x < 10^8. */
static inline void put8(char *d, uint32_t x)
{
    uint32_t a = x / 10000, b = x % 10000;
    memcpy(d, digits2 + 2 * (a / 100), 2);
    memcpy(d + 2, digits2 + 2 * (a % 100), 2);
    memcpy(d + 4, digits2 + 2 * (b / 100), 2);
    memcpy(d + 6, digits2 + 2 * (b % 100), 2);
}

/* Is m 2^e 10^p exactly an integer plus 1/2 (m > 0)? */
static int halfway(uint64_t m, int e, int p)
{
    int t = __builtin_ctzll(m);
    m >>= t;
    if (e + t + 1 + p != 0)
        return 0;
    if (p >= 0)
        return 1;
    if (p < -22)                      /* 5^23 > 2^53 > m */
        return 0;
    uint64_t d = 1;
    for (int i = 0; i < -p; ++i)
        d *= 5;
    return m % d == 0;
}

/* The digits are kept in a DIGITS-byte buffer, '0' past the 17th, so that the
 * layouts below copy whole blocks of 16 or 17 bytes (no call for a copy of
 * variable length) and write past the text's end, within BK_NUMFMT_MAX. */
#define DIGITS 34
static const uint64_t ZEROS8 = UINT64_C(0x3030303030303030);     /* "00000000" */

static inline void pad_digits(char *d)
{
    memcpy(d + 17, "00000000000000000", 17);     /* d[17..33]: what the layouts' copies read */
}

/* The number of digits of d[0..16] without the trailing zeros (at least 1),
 * from two 8-byte words: the last byte that is not '0' (little endian). */
static inline int significant(const char *d)
{
    uint64_t w;
    memcpy(&w, d + 9, 8);
    if (w != ZEROS8)
        return 9 + 8 - (__builtin_clzll(w ^ ZEROS8) >> 3);
    memcpy(&w, d + 1, 8);
    if (w != ZEROS8)
        return 1 + 8 - (__builtin_clzll(w ^ ZEROS8) >> 3);
    return 1;
}

/* |v| = m 2^e of a finite v != 0 (m with its top bit at 52; subnormals
 * normalized): the 17 significant digits of "%.17e", d[0..16] (d: DIGITS
 * bytes, '0' past them), and their decimal exponent *xp; 0, or -1 in the window where snprintf decides (see
 * the error argument above). */
static int digits17(uint64_t m, int e, char *d, int *xp)
{
    /* X' = m 10^p 2^e = q + f 2^-64 (truncated; see the error argument) */
    int k0 = ((e + 52) * 78913) >> 18;            /* floor((e + 52) log10 2) */
    int p = 16 - k0;
    const uint64_t *t = pow10_tab[p - P10_MIN];
    int sh = -(e + pow10_exp2(p));                /* in [123, 126] */
    bk_u128 plo = (bk_u128)m * t[1], phi = (bk_u128)m * t[0];
    bk_u128 mid = (bk_u128)(uint64_t)phi + (plo >> 64);
    uint64_t w0 = (uint64_t)plo, w1 = (uint64_t)mid;
    uint64_t w2 = (uint64_t)(phi >> 64) + (uint64_t)(mid >> 64);
    uint64_t q = (w2 << (128 - sh)) | (w1 >> (sh - 64));
    uint64_t f = (w1 << (128 - sh)) | (w0 >> (sh - 64));

    const uint64_t half = UINT64_C(1) << 63, e16 = UINT64_C(10000000000000000);
    /* both roundings, one kept (whether X has 18 digits follows the
     * mantissa: a branch on it would be mispredicted often) */
    const int fold = q >= 10 * e16;
    const uint64_t q10 = q / 10;
    const unsigned r = (unsigned)(q - 10 * q10);
    const int up17 = f > half, doubt17 = f == half || f == half - 1;
    const int up18 = r >= 5, doubt18 = (r == 5 && f == 0) | (r == 4 && f == UINT64_MAX);
    uint64_t n = fold ? q10 : q;
    int up = fold ? up18 : up17, doubt = fold ? doubt18 : doubt17;
    if (doubt) {
        if (!halfway(m, e, p - fold))            /* near a boundary, not on it */
            return -1;
        up = (int)(n & 1);
    }
    n += (uint64_t)up;
    int x = 16 - p + fold;                        /* decimal exponent of the result */
    if (n == 10 * e16) {
        n = e16;
        ++x;
    }
    uint64_t hi = n / 100000000;                  /* 9 digits */
    d[0] = (char)('0' + hi / 100000000);
    put8(d + 1, (uint32_t)(hi % 100000000));
    put8(d + 9, (uint32_t)(n % 100000000));
    pad_digits(d);
    *xp = x;
    return 0;
}

/* Decodes v: writes its sign to *s; 1 with (m, e) for a finite v != 0, else
 * 0 with the text of +-0 ("0" + zero_tail), inf or nan written after the sign
 * and *len its total length. */
static int decode(double v, char *buf, char **s, uint64_t *mp, int *ep, const char *zero_tail, int *len)
{
    uint64_t bits;
    memcpy(&bits, &v, sizeof bits);
    int be = (int)(bits >> 52) & 0x7ff;
    uint64_t m = bits & ((UINT64_C(1) << 52) - 1);
    char *t = buf;
    *t = '-';                                     /* kept only for a negative v (no branch on the sign) */
    t += bits >> 63;
    *s = t;
    if (be == 0x7ff) {
        memcpy(t, m ? "nan" : "inf", 4);
        *len = (int)(t - buf) + 3;
        return 0;
    }
    if (be) {
        *mp = m | UINT64_C(1) << 52;
        *ep = be - 1075;
        return 1;
    }
    if (m) {                                      /* subnormal: normalize */
        int z = __builtin_clzll(m) - 11;
        *mp = m << z;
        *ep = -1074 - z;
        return 1;
    }
    size_t k = strlen(zero_tail);
    *t = '0';
    memcpy(t + 1, zero_tail, k + 1);
    *len = (int)(t - buf) + 1 + (int)k;
    return 0;
}

/* d[0..16] rounded to its first P digits (1 <= P <= 17), to nearest from the
 * 17-digit text: exact, since that text is within half a unit of its 17th
 * digit of v, except when the rest is exactly 5000..., where v may lie on
 * either side of the halfway point (-1: snprintf decides).  A carry out of
 * d[0] makes it 1 and increments *x. */
static int round_digits(char d[17], int P, int *x)
{
    if (P >= 17)
        return 0;
    if (d[P] < '5')
        return 0;
    if (d[P] == '5') {
        int k = P + 1;
        while (k < 17 && d[k] == '0')
            ++k;
        if (k == 17)
            return -1;
    }
    int i = P - 1;
    while (i >= 0 && d[i] == '9')
        d[i--] = '0';
    if (i >= 0) {
        d[i]++;
    } else {
        d[0] = '1';
        ++*x;
    }
    return 0;
}

/* e+XX / e-XXX as glibc writes an exponent. */
static char *put_exponent(char *s, int x)
{
    *s++ = 'e';
    *s++ = x < 0 ? '-' : '+';
    unsigned a = (unsigned)(x < 0 ? -x : x);
    if (a >= 100) {
        *s++ = (char)('0' + a / 100);
        a %= 100;
    }
    memcpy(s, digits2 + 2 * a, 2);
    return s + 2;
}

/* "%.Pg": the digits d[0..P-1] (rounded, exponent x; d as above) laid out as
 * %g lays them out (trailing zeros removed). */
static int layout_g(char *buf, char *s, char *d, int P, int x)
{
    if (P < 17)
        memset(d + P, '0', (size_t)(17 - P));
    const int nd = significant(d);
    if (x >= -4 && x < P) {                       /* fixed notation */
        if (x >= 0) {
            /* the integer part (x + 1 <= 17 digits), the point and the
             * fraction (nd - x - 1 <= 16 digits); an integer ends before the
             * point (no branch on which) */
            memcpy(s, d, 17);
            s[x + 1] = '.';
            memcpy(s + x + 2, d + x + 1, 16);
            s += nd <= x + 1 ? x + 1 : nd + 1;
        } else {
            memcpy(s, "0.0000", 6);
            s += 1 - x;
            memcpy(s, d, 17);
            s += nd;
        }
    } else {                                      /* d.ddde+XX */
        s[0] = d[0];
        s[1] = '.';
        memcpy(s + 2, d + 1, 16);
        s += nd > 1 ? nd + 1 : 1;
        s = put_exponent(s, x);
    }
    *s = '\0';
    return (int)(s - buf);
}

int bk_fmt_g17(char *buf, double v)
{
    char *s, d[DIGITS];
    uint64_t m;
    int e, x, len;
    if (!decode(v, buf, &s, &m, &e, "", &len))
        return len;
    if (digits17(m, e, d, &x) != 0)
        return snprintf(buf, BK_NUMFMT_MAX, "%.17g", v);
    return layout_g(buf, s, d, 17, x);
}

int bk_fmt_g(char *buf, double v, int prec)
{
    const int P = prec < 1 ? 1 : prec > 17 ? 17 : prec;
    char *s, d[DIGITS];
    uint64_t m;
    int e, x, len;
    if (!decode(v, buf, &s, &m, &e, "", &len))
        return len;
    if (digits17(m, e, d, &x) != 0 || round_digits(d, P, &x) != 0)
        return snprintf(buf, BK_NUMFMT_MAX, "%.*g", P, v);
    return layout_g(buf, s, d, P, x);
}

int bk_fmt_e(char *buf, double v, int prec)
{
    const int p = prec < 0 ? 0 : prec > 16 ? 16 : prec;
    static const char zeros[] = ".0000000000000000e+00";
    char *s, d[DIGITS], ztail[24];
    uint64_t m;
    int e, x, len;
    if (p == 0)
        memcpy(ztail, "e+00", 5);
    else {
        memcpy(ztail, zeros, (size_t)p + 1);
        memcpy(ztail + p + 1, "e+00", 5);
    }
    if (!decode(v, buf, &s, &m, &e, ztail, &len))
        return len;
    if (digits17(m, e, d, &x) != 0 || round_digits(d, p + 1, &x) != 0)
        return snprintf(buf, BK_NUMFMT_MAX, "%.*e", p, v);
    s[0] = d[0];
    s[1] = '.';
    memcpy(s + 2, d + 1, 16);                     /* p <= 16 digits */
    s += p > 0 ? p + 2 : 1;
    s = put_exponent(s, x);
    *s = '\0';
    return (int)(s - buf);
}
