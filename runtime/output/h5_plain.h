/* h5_plain.h -- a whole HDF5 file made in memory without the HDF5 library:
 * groups with attributes and contiguous datasets of fixed-size types, laid out
 * in HDF5's file format (version 2 superblock and object headers, compact
 * groups: what HDF5 1.8 and later read; docs/reference/results_h5.md).
 *
 * results.h5 of a run whose rows all come at its end is made this way
 * (h5_file.c): the library's own start, its file and object bookkeeping and
 * its end took 2-3 ms of CPU time, more than a small scene's solve.
 *
 * The file is built children first: a dataset's data, then its object header;
 * a group's members, then the group; the root group last, then the superblock
 * at the start is filled in.  Each object's function returns the address of
 * its object header, which its group's link names.
 *
 * Types: a cell is a signed little-endian integer (4 or 8 bytes), an IEEE
 * double, a fixed-size string (null-padded or null-terminated, ASCII) or a
 * compound of such cells at given offsets (one level).
 *
 * A dataset's data of BK_H5P_BY_REFERENCE bytes or more is not copied: the
 * file's bytes are p->data with each such block written in its place
 * (bk_h5p_write).  Copying it into fresh memory first cost as much as writing
 * it (on a VM each new page costs a fault of ~10 us: 4 ms for 1.4 MB).
 *
 * Sizes and directions:
 *   bk_h5p_begin    out: p emptied and the superblock's room made.
 *   bk_h5p_dataset  in: its type, rank 0 (a scalar), 1 or 2, dims[rank], the
 *                   data (rows in order, as the type lays them out; NULL when
 *                   a dimension is 0; when BK_H5P_BY_REFERENCE bytes or more,
 *                   not copied: it must stay as it is until bk_h5p_write).
 *                   The object header's address.
 *   bk_h5p_group    in: n links (names, object header addresses), na
 *                   attributes.  The object header's address.
 *   bk_h5p_finish   in: root: the root group's address: the superblock filled
 *                   in.  0, or -1 when some memory could not be had or a
 *                   type is too large for its message (toolarge).
 *   bk_h5p_write    in: fd, open for writing at the file's start: the whole
 *                   file written (p->data and the data in its places).  0,
 *                   or the errno of the failed write.
 *   bk_h5p_free     frees p's memory (not the data it refers to). */
#ifndef BK_H5_PLAIN_H
#define BK_H5_PLAIN_H

#include <stddef.h>
#include <stdint.h>

enum { BK_H5P_I32, BK_H5P_I64, BK_H5P_F64, BK_H5P_STR, BK_H5P_COMPOUND };

#define BK_H5P_NULLTERM 0      /* a string's padding: null-terminated (HDF5's H5T_C_S1) */
#define BK_H5P_NULLPAD 1       /*   null-padded */

typedef struct bk_h5p_type {
    int kind;                  /* BK_H5P_* */
    size_t size;               /* bytes of a cell (I32 4, I64 and F64 8; a string's; a compound's row) */
    int pad;                   /* a string's padding */
    int nmember;               /* a compound's members: */
    const char *const *names;  /*   [nmember] their names, */
    const size_t *offsets;     /*   [nmember] their offsets in a row, */
    const struct bk_h5p_type *const *types;   /*   [nmember] their types (not compounds) */
} bk_h5p_type;

typedef struct bk_h5p_attr {
    const char *name;
    const char *text;          /* a string attribute (null-terminated, its length the type's), or NULL: */
    int64_t value;             /*   an int64 one */
} bk_h5p_attr;

#define BK_H5P_BY_REFERENCE ((size_t)16 << 10)

/* A dataset's data written in its place: before p->data[at]. */
typedef struct bk_h5p_ref {
    size_t at;
    const void *data;          /* not owned */
    size_t len;
} bk_h5p_ref;

typedef struct bk_h5p {
    unsigned char *data;       /* owned: the file but the data referred to */
    size_t n, cap;
    bk_h5p_ref *ref;           /* owned: [nref] in the order of at */
    int nref, capref;
    uint64_t reflen;           /* bytes referred to so far (a byte's address: its offset in data + the
                                * bytes referred to before it) */
    int oom;                   /* some memory could not be had */
    int toolarge;              /* a message over 64 kB (a compound of thousands of members) */
} bk_h5p;

void bk_h5p_begin(bk_h5p *p);
uint64_t bk_h5p_dataset(bk_h5p *p, const bk_h5p_type *type, int rank, const uint64_t *dims, const void *data);
uint64_t bk_h5p_group(bk_h5p *p, int n, const char *const *names, const uint64_t *addrs, int na,
                      const bk_h5p_attr *attrs);
int bk_h5p_finish(bk_h5p *p, uint64_t root);
int bk_h5p_write(const bk_h5p *p, int fd);
void bk_h5p_free(bk_h5p *p);
/* HDF5's checksum of metadata (Bob Jenkins' lookup3 hashlittle, initval 0). */
uint32_t bk_h5p_checksum(const void *data, size_t len);

#endif
