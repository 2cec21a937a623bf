/* SPDX-License-Identifier: MIT */
/*
 * classify.h: a transfer function sampled at the table's N entries (docs/algorithm.md, section 2): extinction
 * and colour per entry, the colour weight of each interval between entries, and what the run-length encoder
 * needs to know which scalar ranges are visible.
 */
#ifndef VF_CLASSIFY_H
#define VF_CLASSIFY_H

#include "volfix.h"

typedef struct vfi_classify {
    uint32_t n;                    /* entries */
    uint32_t *tau_q28;             /* [n] extinction per d_ref, Q4.28 */
    uint32_t *colour_q30;          /* [n * 3] r, g, b, Q.30 (1.0 = 2^30) */
    uint32_t *weight_q30;          /* [(n - 1) * 3] extinction-weighted mean colour of interval m, Q.30 */
    uint16_t *visible_before;      /* [n + 1] how many entries below i have tau > 0 */
    uint64_t *tau_sum_q28;         /* [n + 1] the sum of tau_q28 of the entries below i (partial slabs' depth) */
    uint16_t entry_of_scalar[256]; /* entry of each 8-bit voxel scalar (the same rounding as samples) */
    /* The entries a sample between scalars lo and hi can touch are first_of_scalar[lo] .. end_of_scalar[hi] - 1:
     * nearest lookups round(x); bilinear lookups floor(x) .. ceil(x), x = s (N - 1) / 255 (the entry above a
     * whole x has weight 0). */
    uint16_t first_of_scalar[256];
    uint16_t end_of_scalar[256];
    /* Whether [lo, hi] touches a visible entry only grows with hi (and as lo falls), so one threshold per lo says
     * it all: the smallest hi >= lo for which it does, 256 when none. One load per cell in the run encoder. */
    uint16_t visible_from[256];
    /* Whether every [a, b] inside [lo, hi] touches a visible entry: so when each scalar of [lo, hi] does alone
     * (visible_from[s] = s), which holds for hi below one threshold per lo: the smallest s >= lo whose scalar
     * alone touches none, 256 when none. The run encoder settles a brick of cells with it (runs.h). */
    uint16_t solid_until[256];
} vfi_classify_t;

/* Bytes vfi_classify_alloc takes from an arena for n entries. */
size_t vfi_classify_bytes(uint32_t n);
vf_status_t vfi_classify_alloc(vfi_classify_t *cls, uint32_t n, vf_lookup_t lookup, vf_arena_t *arena);

/* Checks the transfer function and fills cls (allocated for its n). */
vf_status_t vfi_classify(vfi_classify_t *cls, const vf_tf_t *tf);

/* Table entry round(s (N - 1) / 255) of a sample s in Q8.32, exactly: floor(X / (255 2^32)) equals
 * floor(floor(X / 2^32) / 255), and the second division is by a constant. Exact matters: a sample exactly
 * between two entries must go the way the reference's goes, or a narrow transfer-function peak flips. */
static inline uint32_t vfi_entry_of_sample_n(uint32_t n, uint64_t sample_q32)
{
    if (n == 256) /* the default: an entry per scalar, round(s) */
        return (uint32_t)((sample_q32 + (UINT64_C(1) << 31)) >> 32);
    uint64_t x = sample_q32 * (n - 1) + UINT64_C(255) * (UINT64_C(1) << 31);
    return (uint32_t)(x >> 32) / 255u;
}

static inline uint32_t vfi_entry_of_sample(const vfi_classify_t *cls, uint64_t sample_q32)
{
    return vfi_entry_of_sample_n(cls->n, sample_q32);
}

/* Whether a segment whose samples lie between 8-bit scalars lo and hi can touch a visible entry (tau > 0). */
static inline bool vfi_range_visible(const vfi_classify_t *cls, uint32_t scalar_lo, uint32_t scalar_hi)
{
    return scalar_hi >= cls->visible_from[scalar_lo];
}

/* Whether every segment whose samples lie between 8-bit scalars inside [lo, hi] touches a visible entry. */
static inline bool vfi_range_solid(const vfi_classify_t *cls, uint32_t scalar_lo, uint32_t scalar_hi)
{
    return scalar_hi < cls->solid_until[scalar_lo];
}

/* Table position of a sample in Q8.32 for a bilinear lookup: x = s (N - 1) / 255 in Q.16, floor(x 2^16) exactly
 * (so that a sample on an entry reads that entry alone). floor(X / (255 2^16)) with X = s (N - 1) < 2^50 is
 * floor(Y / 255) with Y = X >> 16 < 2^34, divided in two 32-bit steps: Y = 256 hi + lo, hi = 255 q + r. */
static inline uint32_t vfi_position_of_sample_n(uint32_t n, uint64_t sample_q32)
{
    if (n == 256) /* (N - 1) / 255 = 1 */
        return (uint32_t)(sample_q32 >> 16);
    uint64_t y = (sample_q32 * (n - 1)) >> 16;
    uint32_t hi = (uint32_t)(y >> 8), lo = (uint32_t)(y & 0xFFu);
    uint32_t q = hi / 255u, r = hi - q * 255u;
    return (q << 8) + ((r << 8) | lo) / 255u;
}

static inline uint32_t vfi_position_of_sample(const vfi_classify_t *cls, uint64_t sample_q32)
{
    return vfi_position_of_sample_n(cls->n, sample_q32);
}

#endif
