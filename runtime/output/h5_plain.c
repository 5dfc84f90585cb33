/* h5_plain.c -- a whole HDF5 file made in memory without the HDF5 library (see
 * h5_plain.h); the encodings are those of HDF5's file format specification
 * (version 3.0): superblock 2, object header 2, dataspace 2, datatype 1
 * (numbers, strings) and 3 (compounds), fill value 3, layout 3 (contiguous),
 * attribute 3, link info 0, group info 0, link 1. */
#include "output/h5_plain.h"
#include "base/bigalloc.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/uio.h>

#define UNDEF UINT64_MAX         /* an undefined address */
#define SUPERBLOCK 48

enum {                           /* object header message types */
    MSG_DATASPACE = 0x01, MSG_LINK_INFO = 0x02, MSG_DATATYPE = 0x03, MSG_FILL = 0x05, MSG_LINK = 0x06,
    MSG_LAYOUT = 0x08, MSG_GROUP_INFO = 0x0A, MSG_ATTRIBUTE = 0x0C
};

/* ---- bytes ---- */

static unsigned char *room(bk_h5p *p, size_t k)
{
    if (p->oom)
        return NULL;
    if (p->n + k > p->cap) {
        size_t cap = p->cap ? p->cap : 4096;
        while (cap < p->n + k)
            cap *= 2;
        unsigned char *d = bk_big_realloc(p->data, cap);
        if (!d) {
            p->oom = 1;
            return NULL;
        }
        p->data = d;
        p->cap = cap;
    }
    unsigned char *at = p->data + p->n;
    p->n += k;
    return at;
}

/* k bytes of data written in their place from src (bk_h5p_write) */
static void refer(bk_h5p *p, const void *src, uint64_t k)
{
    if (p->oom)
        return;
    if (p->nref == p->capref) {
        int cap = p->capref ? 2 * p->capref : 16;
        bk_h5p_ref *r = realloc(p->ref, (size_t)cap * sizeof *r);
        if (!r) {
            p->oom = 1;
            return;
        }
        p->ref = r;
        p->capref = cap;
    }
    p->ref[p->nref++] = (bk_h5p_ref){p->n, src, (size_t)k};
    p->reflen += k;
}

static void put(bk_h5p *p, const void *src, size_t k)
{
    unsigned char *at = room(p, k);
    if (at && k)
        memcpy(at, src, k);
}

/* little-endian integers of `bytes` bytes, at the end or at offset `at` */
static void le(unsigned char *d, uint64_t v, int bytes)
{
    for (int i = 0; i < bytes; ++i)
        d[i] = (unsigned char)(v >> (8 * i));
}

static void put_le(bk_h5p *p, uint64_t v, int bytes)
{
    unsigned char *at = room(p, (size_t)bytes);
    if (at)
        le(at, v, bytes);
}

static void set_le(bk_h5p *p, size_t at, uint64_t v, int bytes)
{
    if (!p->oom)
        le(p->data + at, v, bytes);
}

#define ROT(x, k) (((x) << (k)) | ((x) >> (32 - (k))))

uint32_t bk_h5p_checksum(const void *data, size_t len)
{
    const unsigned char *k = data;
    uint32_t a, b, c;
    a = b = c = 0xdeadbeefu + (uint32_t)len;
    for (; len > 12; len -= 12, k += 12) {
        uint32_t w[3] = {0, 0, 0};
        for (int i = 0; i < 12; ++i)
            w[i / 4] += (uint32_t)k[i] << (8 * (i % 4));
        a += w[0];
        b += w[1];
        c += w[2];
        a -= c; a ^= ROT(c, 4);  c += b;
        b -= a; b ^= ROT(a, 6);  a += c;
        c -= b; c ^= ROT(b, 8);  b += a;
        a -= c; a ^= ROT(c, 16); c += b;
        b -= a; b ^= ROT(a, 19); a += c;
        c -= b; c ^= ROT(b, 4);  b += a;
    }
    if (len == 0)
        return c;
    uint32_t w[3] = {0, 0, 0};
    for (size_t i = 0; i < len; ++i)
        w[i / 4] += (uint32_t)k[i] << (8 * (i % 4));
    a += w[0];
    b += w[1];
    c += w[2];
    c ^= b; c -= ROT(b, 14);
    a ^= c; a -= ROT(c, 11);
    b ^= a; b -= ROT(a, 25);
    c ^= b; c -= ROT(b, 16);
    a ^= c; a -= ROT(c, 4);
    b ^= a; b -= ROT(a, 14);
    c ^= b; c -= ROT(b, 24);
    return c;
}

/* ---- messages ---- */

static void put_type(bk_h5p *p, const bk_h5p_type *t)
{
    switch (t->kind) {
    case BK_H5P_I32:
    case BK_H5P_I64:                              /* fixed-point, version 1: signed, little-endian */
        put(p, "\x10\x08\0\0", 4);
        put_le(p, t->size, 4);
        put_le(p, 0, 2);                          /* bit offset */
        put_le(p, 8 * t->size, 2);                /* precision */
        break;
    case BK_H5P_F64:                              /* floating-point, version 1: IEEE, implied mantissa bit */
        put(p, "\x11\x20\x3f\0", 4);              /*   (sign at bit 63) */
        put_le(p, 8, 4);
        put_le(p, 0, 2);
        put_le(p, 64, 2);
        put(p, "\x34\x0b\x00\x34", 4);            /* exponent at 52, 11 bits; mantissa at 0, 52 bits */
        put_le(p, 1023, 4);
        break;
    case BK_H5P_STR: {                            /* string, version 1: ASCII */
        unsigned char h[4] = {0x13, (unsigned char)t->pad, 0, 0};
        put(p, h, 4);
        put_le(p, t->size, 4);
        break;
    }
    default: {                                    /* compound, version 3 */
        unsigned char h[4] = {0x36, (unsigned char)(t->nmember & 0xff), (unsigned char)(t->nmember >> 8), 0};
        put(p, h, 4);
        put_le(p, t->size, 4);
        int ob = 1;                               /* the bytes of an offset: those of the row's size */
        while (ob < 8 && (t->size >> (8 * ob)) != 0)
            ++ob;
        for (int k = 0; k < t->nmember; ++k) {
            put(p, t->names[k], strlen(t->names[k]) + 1);
            put_le(p, t->offsets[k], ob);
            put_type(p, t->types[k]);
        }
    }
    }
}

static void put_space(bk_h5p *p, int rank, const uint64_t *dims)
{
    unsigned char h[4] = {2, (unsigned char)rank, 0, rank ? 1 : 0};   /* version 2, no maxima; scalar or simple */
    put(p, h, 4);
    for (int k = 0; k < rank; ++k)
        put_le(p, dims[k], 8);
}

/* A message's header; its size is set by msg_end. */
static size_t msg_begin(bk_h5p *p, int type, int flags)
{
    size_t at = p->n;
    unsigned char h[4] = {(unsigned char)type, 0, 0, (unsigned char)flags};
    put(p, h, 4);
    return at;
}

static void msg_end(bk_h5p *p, size_t at)
{
    if (p->n - at - 4 > 0xffff)
        p->toolarge = 1;
    set_le(p, at + 1, p->n - at - 4, 2);
}

/* An object header: its prefix (the size of its one chunk set by ohdr_end). */
static size_t ohdr_begin(bk_h5p *p)
{
    size_t at = p->n;
    put(p, "OHDR\x02\x02", 6);                    /* version 2; the chunk's size in 4 bytes, no times */
    put_le(p, 0, 4);
    return at;
}

/* ... its address (no data is referred to within a header) */
static uint64_t ohdr_end(bk_h5p *p, size_t at)
{
    set_le(p, at + 6, p->n - at - 10, 4);
    if (!p->oom) {
        uint32_t sum = bk_h5p_checksum(p->data + at, p->n - at);
        put_le(p, sum, 4);
    }
    return at + p->reflen;
}

static void put_attr(bk_h5p *p, const bk_h5p_attr *a)
{
    size_t m = msg_begin(p, MSG_ATTRIBUTE, 0);
    size_t ln = strlen(a->name) + 1, lt = a->text ? strlen(a->text) : 0;
    bk_h5p_type t = {a->text ? BK_H5P_STR : BK_H5P_I64, a->text ? (lt ? lt : 1) : 8, BK_H5P_NULLTERM, 0, 0, 0, 0};
    put(p, "\x03\x00", 2);                        /* version 3 */
    put_le(p, ln, 2);
    size_t sizes = p->n;
    put_le(p, 0, 2);                              /* (the datatype's size, set below) */
    put_le(p, 4, 2);                              /* the dataspace's: a scalar */
    put(p, "", 1);                                /* ASCII name */
    put(p, a->name, ln);
    size_t t0 = p->n;
    put_type(p, &t);
    set_le(p, sizes, p->n - t0, 2);
    put_space(p, 0, NULL);
    if (a->text) {
        unsigned char *at = room(p, t.size);
        if (at) {
            memset(at, 0, t.size);
            memcpy(at, a->text, lt);
        }
    } else
        put_le(p, (uint64_t)a->value, 8);
    msg_end(p, m);
}

/* ---- objects ---- */

void bk_h5p_begin(bk_h5p *p)
{
    memset(p, 0, sizeof *p);
    unsigned char *at = room(p, SUPERBLOCK);
    if (at)
        memset(at, 0, SUPERBLOCK);
}

uint64_t bk_h5p_dataset(bk_h5p *p, const bk_h5p_type *type, int rank, const uint64_t *dims, const void *data)
{
    uint64_t bytes = type->size;
    for (int k = 0; k < rank; ++k)
        bytes *= dims[k];
    uint64_t where = bytes ? p->n + p->reflen : UNDEF;
    if (bytes >= BK_H5P_BY_REFERENCE)
        refer(p, data, bytes);
    else if (bytes)
        put(p, data, bytes);
    size_t h = ohdr_begin(p);
    size_t m = msg_begin(p, MSG_DATASPACE, 0);
    put_space(p, rank, dims);
    msg_end(p, m);
    m = msg_begin(p, MSG_DATATYPE, 1);            /* (constant) */
    put_type(p, type);
    msg_end(p, m);
    m = msg_begin(p, MSG_FILL, 1);
    put(p, "\x03\x0a", 2);                        /* version 3: space allocated late, fill value written if set */
    msg_end(p, m);
    m = msg_begin(p, MSG_LAYOUT, 0);
    put(p, "\x03\x01", 2);                        /* version 3, contiguous: */
    put_le(p, where, 8);                          /*   the data's address and size */
    put_le(p, bytes, 8);
    msg_end(p, m);
    return ohdr_end(p, h);
}

uint64_t bk_h5p_group(bk_h5p *p, int n, const char *const *names, const uint64_t *addrs, int na,
                      const bk_h5p_attr *attrs)
{
    size_t h = ohdr_begin(p);
    size_t m = msg_begin(p, MSG_LINK_INFO, 0);
    put(p, "\0\0", 2);                            /* version 0, no creation order */
    put_le(p, UNDEF, 8);                          /* no fractal heap, no name index: the links are here */
    put_le(p, UNDEF, 8);
    msg_end(p, m);
    m = msg_begin(p, MSG_GROUP_INFO, 0);
    if (n > 8) {                                  /* more links than the default compact 8 */
        put(p, "\0\x01", 2);
        put_le(p, (uint64_t)n, 2);
        put_le(p, 6, 2);
    } else
        put(p, "\0\0", 2);
    msg_end(p, m);
    for (int k = 0; k < n; ++k) {
        m = msg_begin(p, MSG_LINK, 0);
        size_t ln = strlen(names[k]);
        unsigned char hd[3] = {1, 0, (unsigned char)ln};   /* version 1, a hard link, name length in a byte */
        put(p, hd, 3);
        put(p, names[k], ln);
        put_le(p, addrs[k], 8);
        msg_end(p, m);
    }
    for (int k = 0; k < na; ++k)
        put_attr(p, &attrs[k]);
    return ohdr_end(p, h);
}

int bk_h5p_finish(bk_h5p *p, uint64_t root)
{
    if (p->oom || p->toolarge)
        return -1;
    unsigned char *s = p->data;
    memcpy(s, "\x89HDF\r\n\x1a\n\x02\x08\x08\x00", 12);   /* version 2, 8-byte addresses and lengths */
    le(s + 12, 0, 8);                                      /* base address */
    le(s + 20, UNDEF, 8);                                  /* no superblock extension */
    le(s + 28, p->n + p->reflen, 8);                       /* end of file */
    le(s + 36, root, 8);                                   /* the root group's object header */
    le(s + 44, bk_h5p_checksum(s, 44), 4);
    return 0;
}

int bk_h5p_write(const bk_h5p *p, int fd)
{
    /* the pieces in file order: data[0 .. ref 0's at), ref 0, data[.. ref 1's at), ... */
    struct iovec v[64];
    int nv = 0, r = 0;
    size_t at = 0;
    while (r <= p->nref) {
        while (nv < 63 && r <= p->nref) {
            size_t end = r < p->nref ? p->ref[r].at : p->n;
            if (end > at)
                v[nv++] = (struct iovec){p->data + at, end - at};
            at = end;
            if (r < p->nref && p->ref[r].len)
                v[nv++] = (struct iovec){(void *)p->ref[r].data, p->ref[r].len};
            ++r;
        }
        int k = 0;
        while (k < nv) {                          /* (a short write: the rest again) */
            ssize_t w = writev(fd, v + k, nv - k);
            if (w < 0 && errno == EINTR)
                continue;
            if (w <= 0)
                return w < 0 && errno ? errno : EIO;
            size_t done = (size_t)w;
            for (; k < nv && done >= v[k].iov_len; ++k)
                done -= v[k].iov_len;
            if (k < nv) {
                v[k].iov_base = (unsigned char *)v[k].iov_base + done;
                v[k].iov_len -= done;
            }
        }
        nv = 0;
    }
    return 0;
}

void bk_h5p_free(bk_h5p *p)
{
    free(p->ref);
    free(p->data);
    memset(p, 0, sizeof *p);
}
