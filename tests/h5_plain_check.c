/* h5_plain_check.c -- runtime/output/h5_plain.c against the HDF5 library: the
 * same objects written twice, by h5_plain into PLAIN and by libhdf5 into LIB
 * (test_h5_plain.py reads both with h5py and compares them, and with the
 * values written here):
 *   /                attributes name = "beam" (a string), empty = "" (stored
 *                    as one null byte), count = -5 (int64)
 *   /ints32          int32 [3]: 1, -2, 2147483647
 *   /ints64          int64 [2]: -9223372036854775807, 42
 *   /doubles         float64 [2, 3]: 1.5, -0.0, 1e-300, inf, nan, -2.25e17
 *   /pad64           64-byte null-padded strings [2]: "arm", "a longer name"
 *   /term8           8-byte null-terminated strings [2]: "r_x", "lambda"
 *   /rows            compound [3] of step (int64), time (float64), name
 *                    (64-byte null-padded), x (float64): (k, k / 4, "pt<k>", -k)
 *   /many/d0..d9     int32 [1]: k (a group of more than 8 links)
 *   /none            empty group
 *   /zero            int64 [0]
 *   /big             float64 [3000, 4]: row i, column j holds i / 2 - j (96 kB:
 *                    written from in place, h5_plain.h BK_H5P_BY_REFERENCE)
 *   /bigrows         compound [400] as /rows, (k, k / 4, "pt<k>", -k): also in
 *                    place, between the object headers
 * Also prints "checksums equal" when bk_h5p_checksum agrees with the
 * library's own (H5_checksum_lookup3) for every length 0..299 of random bytes.
 * Exit status 0, or 1 when a write failed. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hdf5.h>

#include "output/h5_plain.h"

uint32_t H5_checksum_lookup3(const void *key, size_t length, uint32_t initval);   /* (HDF5's, internal) */

typedef struct {
    int64_t step;
    double time;
    char name[64];
    double x;
} row;

static int32_t i32[3] = {1, -2, 2147483647};
static int64_t i64[2] = {-9223372036854775807LL, 42};
static char pad64[2][64] = {"arm", "a longer name"};
static char term8[2][8] = {"r_x", "lambda"};
static const char *const many_names[10] = {"d0", "d1", "d2", "d3", "d4", "d5", "d6", "d7", "d8", "d9"};

static int write_plain(const char *path, const double *dbl, const row *rows, const double *big,
                       const row *bigrows)
{
    static const bk_h5p_type I32 = {BK_H5P_I32, 4, 0, 0, 0, 0, 0}, I64 = {BK_H5P_I64, 8, 0, 0, 0, 0, 0},
                             F64 = {BK_H5P_F64, 8, 0, 0, 0, 0, 0},
                             S64 = {BK_H5P_STR, 64, BK_H5P_NULLPAD, 0, 0, 0, 0},
                             S8 = {BK_H5P_STR, 8, BK_H5P_NULLTERM, 0, 0, 0, 0};
    const char *mn[4] = {"step", "time", "name", "x"};
    const size_t mo[4] = {offsetof(row, step), offsetof(row, time), offsetof(row, name), offsetof(row, x)};
    const bk_h5p_type *mt[4] = {&I64, &F64, &S64, &F64};
    const bk_h5p_type rt = {BK_H5P_COMPOUND, sizeof(row), 0, 4, mn, mo, mt};
    bk_h5p p;
    bk_h5p_begin(&p);
    uint64_t d3[1] = {3}, d2[1] = {2}, m23[2] = {2, 3}, d1[1] = {1}, d0[1] = {0}, many[10];
    uint64_t mbig[2] = {3000, 4}, d400[1] = {400};
    for (int k = 0; k < 10; ++k) {
        int32_t v = k;
        many[k] = bk_h5p_dataset(&p, &I32, 1, d1, &v);
    }
    const char *names[] = {"ints32", "ints64", "doubles", "pad64", "term8", "rows", "many", "none", "zero",
                           "big", "bigrows"};
    uint64_t addrs[11];
    addrs[9] = bk_h5p_dataset(&p, &F64, 2, mbig, big);
    addrs[0] = bk_h5p_dataset(&p, &I32, 1, d3, i32);
    addrs[1] = bk_h5p_dataset(&p, &I64, 1, d2, i64);
    addrs[2] = bk_h5p_dataset(&p, &F64, 2, m23, dbl);
    addrs[3] = bk_h5p_dataset(&p, &S64, 1, d2, pad64);
    addrs[4] = bk_h5p_dataset(&p, &S8, 1, d2, term8);
    addrs[5] = bk_h5p_dataset(&p, &rt, 1, d3, rows);
    addrs[6] = bk_h5p_group(&p, 10, many_names, many, 0, NULL);
    addrs[7] = bk_h5p_group(&p, 0, NULL, NULL, 0, NULL);
    addrs[8] = bk_h5p_dataset(&p, &I64, 1, d0, NULL);
    addrs[10] = bk_h5p_dataset(&p, &rt, 1, d400, bigrows);
    const bk_h5p_attr at[3] = {{"name", "beam", 0}, {"empty", "", 0}, {"count", NULL, -5}};
    uint64_t root = bk_h5p_group(&p, 11, names, addrs, 3, at);
    FILE *fp = bk_h5p_finish(&p, root) == 0 && p.nref == 2 ? fopen(path, "wb") : NULL;
    int ok = fp && bk_h5p_write(&p, fileno(fp)) == 0;
    if (fp && fclose(fp) != 0)
        ok = 0;
    bk_h5p_free(&p);
    return ok ? 0 : -1;
}

static int lib_dataset(hid_t where, const char *name, hid_t type, int rank, const hsize_t *dims, const void *data)
{
    hid_t sp = H5Screate_simple(rank, dims, NULL);
    hid_t ds = H5Dcreate2(where, name, type, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    int rc = ds >= 0 && (dims[0] == 0 || H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) >= 0) ? 0 : -1;
    H5Dclose(ds);
    H5Sclose(sp);
    return rc;
}

static int lib_attr(hid_t obj, const char *name, const char *text, int64_t value)
{
    hid_t t = text ? H5Tcopy(H5T_C_S1) : H5Tcopy(H5T_STD_I64LE);
    if (text)
        H5Tset_size(t, strlen(text) ? strlen(text) : 1);
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(obj, name, t, sp, H5P_DEFAULT, H5P_DEFAULT);
    int rc = H5Awrite(a, text ? t : H5T_NATIVE_INT64, text ? (const void *)text : (const void *)&value) >= 0 ? 0 : -1;
    H5Aclose(a);
    H5Sclose(sp);
    H5Tclose(t);
    return rc;
}

static int write_lib(const char *path, const double *dbl, const row *rows, const double *big, const row *bigrows)
{
    hid_t f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (f < 0)
        return -1;
    hid_t s64 = H5Tcopy(H5T_C_S1), s8 = H5Tcopy(H5T_C_S1);
    H5Tset_size(s64, 64);
    H5Tset_strpad(s64, H5T_STR_NULLPAD);
    H5Tset_size(s8, 8);
    hid_t rt = H5Tcreate(H5T_COMPOUND, sizeof(row));
    H5Tinsert(rt, "step", offsetof(row, step), H5T_NATIVE_INT64);
    H5Tinsert(rt, "time", offsetof(row, time), H5T_NATIVE_DOUBLE);
    H5Tinsert(rt, "name", offsetof(row, name), s64);
    H5Tinsert(rt, "x", offsetof(row, x), H5T_NATIVE_DOUBLE);
    hsize_t d3[1] = {3}, d2[1] = {2}, m23[2] = {2, 3}, d1[1] = {1}, d0[1] = {0}, mbig[2] = {3000, 4}, d400[1] = {400};
    int rc = lib_attr(f, "name", "beam", 0) | lib_attr(f, "empty", "", 0) | lib_attr(f, "count", NULL, -5) |
             lib_dataset(f, "ints32", H5T_NATIVE_INT32, 1, d3, i32) | lib_dataset(f, "ints64", H5T_NATIVE_INT64, 1, d2, i64) |
             lib_dataset(f, "doubles", H5T_NATIVE_DOUBLE, 2, m23, dbl) | lib_dataset(f, "pad64", s64, 1, d2, pad64) |
             lib_dataset(f, "term8", s8, 1, d2, term8) | lib_dataset(f, "rows", rt, 1, d3, rows) |
             lib_dataset(f, "zero", H5T_NATIVE_INT64, 1, d0, NULL) |
             lib_dataset(f, "big", H5T_NATIVE_DOUBLE, 2, mbig, big) | lib_dataset(f, "bigrows", rt, 1, d400, bigrows);
    hid_t g = H5Gcreate2(f, "many", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    for (int k = 0; k < 10; ++k) {
        int32_t v = k;
        rc |= lib_dataset(g, many_names[k], H5T_NATIVE_INT32, 1, d1, &v);
    }
    H5Gclose(g);
    H5Gclose(H5Gcreate2(f, "none", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    H5Tclose(rt);
    H5Tclose(s8);
    H5Tclose(s64);
    if (H5Fclose(f) < 0)
        rc = -1;
    return rc;
}

/* rows (k, k / 4, "pt<k>", -k) */
static void fill_rows(row *rows, int n)
{
    memset(rows, 0, (size_t)n * sizeof *rows);
    for (int k = 0; k < n; ++k) {
        rows[k].step = k;
        rows[k].time = k / 4.0;
        snprintf(rows[k].name, sizeof rows[k].name, "pt%d", k);
        rows[k].x = -k;
    }
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: %s PLAIN LIB\n", argv[0]);
        return 2;
    }
    const double dbl[6] = {1.5, -0.0, 1e-300, INFINITY, NAN, -2.25e17};
    row rows[3];
    fill_rows(rows, 3);
    static double big[3000 * 4];
    for (int i = 0; i < 3000; ++i)
        for (int j = 0; j < 4; ++j)
            big[4 * i + j] = i / 2.0 - j;
    static row bigrows[400];
    fill_rows(bigrows, 400);
    unsigned char b[300];
    srand(1);
    int same = 1;
    for (size_t n = 0; n < sizeof b; ++n) {
        for (size_t i = 0; i < n; ++i)
            b[i] = (unsigned char)rand();
        same = same && H5_checksum_lookup3(b, n, 0) == bk_h5p_checksum(b, n);
    }
    printf("%s\n", same ? "checksums equal" : "checksums differ");
    int rc = write_plain(argv[1], dbl, rows, big, bigrows) | write_lib(argv[2], dbl, rows, big, bigrows);
    H5close();
    return rc ? 1 : 0;
}
