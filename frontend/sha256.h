/* sha256.h -- SHA-256 (FIPS 180-4), the digest of the run cache's keys
 * (gen/cache.py key(); this is the launcher's copy).
 *
 *   bk_sha256 h;  bk_sha256_init(&h);
 *   bk_sha256_update(&h, data, n);       (any number of times)
 *   bk_sha256_hex(&h, out);              out: 65 chars, the 64 hex digits + NUL
 */
#ifndef BK_SHA256_H
#define BK_SHA256_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    uint32_t k[64];           /* the round constants */
    uint32_t h[8];            /* the chaining state */
    uint64_t nbytes;          /* bytes hashed so far */
    unsigned char buf[64];    /* a block not yet complete */
    size_t nbuf;
} bk_sha256;

void bk_sha256_init(bk_sha256 *s);
void bk_sha256_update(bk_sha256 *s, const void *data, size_t n);
void bk_sha256_hex(bk_sha256 *s, char out[65]);

#endif
