/* numfmt.h -- a fast "%.17g" for the solver's CSV tables (see numfmt.c).
 *
 * glibc formats a double with multi-precision arithmetic; for "%.17g" that is
 * a tenth or more of a short static run.  bk_fmt_g17 gives the same text from
 * 128-bit integer arithmetic (no long double, no floating point at all, so a
 * valgrind run writes the same bytes as a native one).
 */
#ifndef BK_NUMFMT_H
#define BK_NUMFMT_H

/* Writes v as "%.17g" would (17 significant digits, trailing zeros removed, %g's
 * choice between fixed and exponent notation, exponent as e+XX / e-XXX like glibc),
 * NUL-terminated, into buf (at least BK_NUMFMT_MAX bytes); returns the length.
 * inf and nan as glibc writes them ("inf", "-inf", "nan", "-nan").  Assumes the
 * default rounding mode (to nearest), in which glibc rounds halfway cases to even. */
#define BK_NUMFMT_MAX 40
int bk_fmt_g17(char *buf, double v);

/* The same for "%.{prec}g" (prec 1..17; outside, clamped) and "%.{prec}e"
 * (prec 0..16): the 17 digits rounded to prec (+ 1) significant digits, which
 * is exact except when the digits dropped are exactly 5000...; that rare case,
 * where the 17-digit text cannot tell on which side of the halfway point v
 * lies, goes to snprintf.  Same buffer rules and return value. */
int bk_fmt_g(char *buf, double v, int prec);
int bk_fmt_e(char *buf, double v, int prec);

#endif
