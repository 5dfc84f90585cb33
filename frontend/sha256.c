/* sha256.c -- SHA-256 (FIPS 180-4).  The round constants and the initial
 * state are the first 32 fractional bits of the cube roots of the first 64
 * primes and of the square roots of the first 8; they are computed here
 * exactly, in integers (the largest x with x^3 <= p 2^96, x^2 <= p 2^64),
 * instead of being listed. */
#include "sha256.h"

#include <stdio.h>
#include <string.h>

typedef unsigned __int128 u128;

/* floor(p^(1/k) 2^32) mod 2^32, k = 2 or 3, by bisection on x^k <= p 2^(32k). */
static uint32_t root_bits(unsigned p, int k)
{
    u128 target = (u128)p << (32 * k);
    uint64_t lo = 0, hi = (uint64_t)1 << 41;          /* p < 2^9: the root < 2^35 */
    while (hi - lo > 1) {
        uint64_t mid = lo + (hi - lo) / 2;
        u128 v = (u128)mid * mid;
        if (k == 3)
            v *= mid;
        if (v <= target)
            lo = mid;
        else
            hi = mid;
    }
    return (uint32_t)lo;
}

static void constants(uint32_t k[64], uint32_t h0[8])
{
    unsigned n = 0;
    for (unsigned p = 2; n < 64; p++) {
        int prime = 1;
        for (unsigned d = 2; d * d <= p; d++)
            if (p % d == 0) {
                prime = 0;
                break;
            }
        if (!prime)
            continue;
        if (n < 8)
            h0[n] = root_bits(p, 2);
        k[n++] = root_bits(p, 3);
    }
}

static uint32_t rotr(uint32_t x, int r) { return (x >> r) | (x << (32 - r)); }

static void block(uint32_t h[8], const uint32_t k[64], const unsigned char *b)
{
    uint32_t w[64];
    for (int i = 0; i < 16; i++)
        w[i] = (uint32_t)b[4 * i] << 24 | (uint32_t)b[4 * i + 1] << 16 | (uint32_t)b[4 * i + 2] << 8 | b[4 * i + 3];
    for (int i = 16; i < 64; i++) {
        uint32_t s0 = rotr(w[i - 15], 7) ^ rotr(w[i - 15], 18) ^ (w[i - 15] >> 3);
        uint32_t s1 = rotr(w[i - 2], 17) ^ rotr(w[i - 2], 19) ^ (w[i - 2] >> 10);
        w[i] = w[i - 16] + s0 + w[i - 7] + s1;
    }
    uint32_t a = h[0], bb = h[1], c = h[2], d = h[3], e = h[4], f = h[5], g = h[6], hh = h[7];
    for (int i = 0; i < 64; i++) {
        uint32_t t1 = hh + (rotr(e, 6) ^ rotr(e, 11) ^ rotr(e, 25)) + ((e & f) ^ (~e & g)) + k[i] + w[i];
        uint32_t t2 = (rotr(a, 2) ^ rotr(a, 13) ^ rotr(a, 22)) + ((a & bb) ^ (a & c) ^ (bb & c));
        hh = g; g = f; f = e; e = d + t1;
        d = c; c = bb; bb = a; a = t1 + t2;
    }
    h[0] += a; h[1] += bb; h[2] += c; h[3] += d;
    h[4] += e; h[5] += f; h[6] += g; h[7] += hh;
}

void bk_sha256_init(bk_sha256 *s)
{
    constants(s->k, s->h);
    s->nbytes = 0;
    s->nbuf = 0;
}

void bk_sha256_update(bk_sha256 *s, const void *data, size_t n)
{
    const unsigned char *p = data;
    s->nbytes += n;
    if (s->nbuf) {
        size_t take = 64 - s->nbuf < n ? 64 - s->nbuf : n;
        memcpy(s->buf + s->nbuf, p, take);
        s->nbuf += take;
        p += take;
        n -= take;
        if (s->nbuf < 64)
            return;
        block(s->h, s->k, s->buf);
        s->nbuf = 0;
    }
    for (; n >= 64; p += 64, n -= 64)
        block(s->h, s->k, p);
    memcpy(s->buf, p, n);
    s->nbuf = n;
}

void bk_sha256_hex(bk_sha256 *s, char out[65])
{
    uint64_t bits = s->nbytes * 8;
    unsigned char pad[72] = {0x80};
    size_t npad = (s->nbuf < 56 ? 56 : 120) - s->nbuf;
    for (int i = 0; i < 8; i++)
        pad[npad + (size_t)i] = (unsigned char)(bits >> (56 - 8 * i));
    bk_sha256_update(s, pad, npad + 8);
    for (int i = 0; i < 8; i++)
        snprintf(out + 8 * i, 9, "%08x", (unsigned)s->h[i]);
}
