/* SPDX-License-Identifier: MIT */
/*
 * wide.h: exact 128-bit unsigned arithmetic for the tests' oracles, in portable C.
 *
 * The oracles need products and quotients wider than 64 bits. GCC's __int128 exists only on 64-bit targets, and
 * the suites must also build and run for 32-bit ARM (make test-cross), so the oracles use this instead; signs are
 * handled by the caller (sign and magnitude). test_fixmath checks it against __int128 where that exists.
 */
#ifndef VF_TESTS_WIDE_H
#define VF_TESTS_WIDE_H

#include <stdint.h>

typedef struct {
    uint64_t hi, lo;
} w128_t;

static inline w128_t w128(uint64_t x)
{
    w128_t r = {0, x};
    return r;
}

/* a b, exactly, from four 32 x 32 -> 64-bit products */
static inline w128_t w128_mul(uint64_t a, uint64_t b)
{
    uint64_t al = a & 0xFFFFFFFFu, ah = a >> 32, bl = b & 0xFFFFFFFFu, bh = b >> 32;
    uint64_t ll = al * bl, lh = al * bh, hl = ah * bl, hh = ah * bh;
    uint64_t mid = (ll >> 32) + (lh & 0xFFFFFFFFu) + (hl & 0xFFFFFFFFu); /* < 3 2^32: no overflow */
    w128_t r = {hh + (lh >> 32) + (hl >> 32) + (mid >> 32), (mid << 32) | (ll & 0xFFFFFFFFu)};
    return r;
}

/* a + b modulo 2^128 */
static inline w128_t w128_add(w128_t a, w128_t b)
{
    w128_t r = {a.hi + b.hi, a.lo + b.lo};
    r.hi += r.lo < a.lo;
    return r;
}

/* a - b modulo 2^128 */
static inline w128_t w128_sub(w128_t a, w128_t b)
{
    w128_t r = {a.hi - b.hi - (a.lo < b.lo), a.lo - b.lo};
    return r;
}

static inline w128_t w128_shl(w128_t a, unsigned s) /* s < 128 */
{
    if (s == 0)
        return a;
    w128_t r = s >= 64 ? (w128_t){a.lo << (s - 64), 0} : (w128_t){(a.hi << s) | (a.lo >> (64 - s)), a.lo << s};
    return r;
}

static inline w128_t w128_shr(w128_t a, unsigned s) /* s < 128 */
{
    if (s == 0)
        return a;
    w128_t r = s >= 64 ? (w128_t){0, a.hi >> (s - 64)} : (w128_t){a.hi >> s, (a.lo >> s) | (a.hi << (64 - s))};
    return r;
}

/* -1, 0 or 1 as a <, = or > b */
static inline int w128_cmp(w128_t a, w128_t b)
{
    if (a.hi != b.hi)
        return a.hi < b.hi ? -1 : 1;
    return a.lo < b.lo ? -1 : a.lo > b.lo;
}

static inline unsigned w128_bits(w128_t a) /* position of the highest set bit + 1; 0 for 0 */
{
    unsigned n = 0;
    uint64_t w = a.hi ? a.hi : a.lo;
    while (w) {
        n++;
        w >>= 1;
    }
    return a.hi ? n + 64 : n;
}

/* floor(n / d) and, when rem is not NULL, n mod d; d != 0. Schoolbook binary long division. */
static inline w128_t w128_div(w128_t n, w128_t d, w128_t *rem)
{
    w128_t q = {0, 0};
    unsigned nb = w128_bits(n), db = w128_bits(d);
    if (nb >= db) {
        unsigned shift = nb - db;
        w128_t ds = w128_shl(d, shift);
        for (unsigned i = shift + 1; i-- > 0;) {
            q = w128_shl(q, 1);
            if (w128_cmp(n, ds) >= 0) {
                n = w128_sub(n, ds);
                q.lo |= 1;
            }
            ds = w128_shr(ds, 1);
        }
    }
    if (rem)
        *rem = n;
    return q;
}

#endif
