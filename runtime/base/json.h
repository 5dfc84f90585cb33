/* json.h -- writing JSON values: strings escaped, numbers with "%.17g" and a
 * non-finite number as null (JSON has no NaN or infinity), and the repair of
 * JSON text made elsewhere whose numbers were printed without that care, and
 * the merge of two objects given under one summary key. */
#ifndef BK_JSON_H
#define BK_JSON_H

#include <stddef.h>
#include <stdio.h>

void bk_json_string(FILE *fp, const char *s);
void bk_json_num(FILE *fp, double v);
/* [v0, v1, v2] */
void bk_json_vec3(FILE *fp, const double *v);
/* in copied to out with every bare word outside strings that is not true,
 * false or null (nan, -nan, inf, -inf as printf writes them) replaced by
 * null; out has room for 2 strlen(in) + 1 characters (the most it can need). */
void bk_json_repair(const char *in, char *out);
/* The object texts a and b (at most 64 members each) as one object, malloc'ed:
 * a's members, then b's whose names a lacks; a member in both is a's, but for
 * "min_distance" (the smaller of the two numbers; null when neither is one)
 * and "max_penetration" (the larger).  NULL when either is not an object or
 * out of memory. */
char *bk_json_merge(const char *a, const char *b);

#endif
