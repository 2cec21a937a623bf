/* SPDX-License-Identifier: MIT */
/*
 * classify.c: sample the transfer function at the table entries and derive what the table builders and the
 * run-length encoder need. Entry i stands for scalar s_i = i * 255 / (N - 1); a sample s is looked up at entry
 * round(s * (N - 1) / 255). Runs once per transfer-function change, so clarity wins over speed here.
 */
#include "arena.h"
#include "classify.h"
#include "fixmath.h"

#define SCALAR_MAX_Q8 (255u * 256u) /* the top of the scalar domain in Q8.8 */

static uint64_t tf_value_q30(const vf_tf_t *tf, uint32_t entry, uint32_t n, int channel);
static uint32_t channel_of(const vf_tf_point_t *p, int channel);

size_t vfi_classify_bytes(uint32_t n)
{
    return vfi_arena_block(sizeof(uint32_t) * n) + vfi_arena_block(sizeof(uint32_t) * n * 3) +
           vfi_arena_block(sizeof(uint32_t) * (n - 1) * 3) + vfi_arena_block(sizeof(uint16_t) * (n + 1)) +
           vfi_arena_block(sizeof(uint64_t) * (n + 1));
}

vf_status_t vfi_classify_alloc(vfi_classify_t *cls, uint32_t n, vf_lookup_t lookup, vf_arena_t *arena)
{
    cls->n = n;
    cls->tau_q28 = vfi_arena_alloc(arena, sizeof(uint32_t) * n);
    cls->colour_q30 = vfi_arena_alloc(arena, sizeof(uint32_t) * n * 3);
    cls->weight_q30 = vfi_arena_alloc(arena, sizeof(uint32_t) * (n - 1) * 3);
    cls->visible_before = vfi_arena_alloc(arena, sizeof(uint16_t) * (n + 1));
    cls->tau_sum_q28 = vfi_arena_alloc(arena, sizeof(uint64_t) * (n + 1));
    if (!cls->tau_q28 || !cls->colour_q30 || !cls->weight_q30 || !cls->visible_before || !cls->tau_sum_q28)
        return VF_ERR_NOMEM;
    for (uint32_t v = 0; v < 256; v++) {
        uint32_t e = (v * (n - 1) * 2 + 255) / 510; /* round(v (N - 1) / 255) */
        uint32_t below = v * (n - 1) / 255, above = (v * (n - 1) + 254) / 255; /* floor and ceil */
        cls->entry_of_scalar[v] = (uint16_t)e;
        cls->first_of_scalar[v] = (uint16_t)(lookup == VF_LOOKUP_BILINEAR ? below : e);
        cls->end_of_scalar[v] = (uint16_t)((lookup == VF_LOOKUP_BILINEAR ? above : e) + 1);
    }
    return VF_OK;
}

vf_status_t vfi_classify(vfi_classify_t *cls, const vf_tf_t *tf)
{
    if (!tf || !tf->points)
        return VF_ERR_NULL;
    if (tf->count == 0 || tf->count > VF_MAX_TF_POINTS)
        return VF_ERR_TF;
    for (uint32_t p = 0; p < tf->count; p++)
        if (tf->points[p].scalar_q8 > SCALAR_MAX_Q8 ||
            (p > 0 && tf->points[p].scalar_q8 < tf->points[p - 1].scalar_q8))
            return VF_ERR_TF;

    const uint32_t n = cls->n;
    cls->tau_sum_q28[0] = 0;
    uint16_t visible = 0;
    for (uint32_t i = 0; i < n; i++) {
        /* tau = -ln(1 - a0), a0 clamped to 1 - 2^-16 (vfi_neg_ln_q32 clamps its argument there). */
        uint64_t a0 = tf_value_q30(tf, i, n, 3);
        cls->tau_q28[i] = a0 == 0 ? 0 : vfi_neg_ln_q32(((UINT64_C(1) << 30) - a0) << 2);
        for (int c = 0; c < 3; c++)
            cls->colour_q30[i * 3 + c] = (uint32_t)tf_value_q30(tf, i, n, c);
        cls->visible_before[i] = visible;
        cls->tau_sum_q28[i + 1] = cls->tau_sum_q28[i] + cls->tau_q28[i];
        visible = (uint16_t)(visible + (cls->tau_q28[i] > 0));
    }
    cls->visible_before[n] = visible;

    /* The entries [lo, hi] can touch are first_of_scalar[lo] .. end_of_scalar[hi] - 1; some is visible when
     * visible_before differs across them. The threshold never falls as lo rises, so one sweep finds them all. */
    uint32_t hi = 0;
    for (uint32_t lo = 0; lo < 256; lo++) {
        const uint16_t below = cls->visible_before[cls->first_of_scalar[lo]];
        if (hi < lo)
            hi = lo;
        while (hi < 256 && cls->visible_before[cls->end_of_scalar[hi]] == below)
            hi++;
        cls->visible_from[lo] = (uint16_t)hi;
    }
    uint16_t until = 256; /* for the run encoder's bricks (VF_RUN_BRICKS) */
    for (uint32_t lo = 256; VF_RUN_BRICKS && lo-- > 0;) {
        if (cls->visible_from[lo] != lo)
            until = (uint16_t)lo;
        cls->solid_until[lo] = until;
    }

    /* Interval m (entries m, m + 1): w = (2 t0 c0 + t0 c1 + t1 c0 + 2 t1 c1) / (3 (t0 + t1)), the mean colour
     * weighted by the linear extinction; tau in Q.24 here keeps the sums of products below 2^63. */
    for (uint32_t m = 0; m + 1 < n; m++) {
        uint64_t t0 = cls->tau_q28[m] >> 4, t1 = cls->tau_q28[m + 1] >> 4;
        for (int c = 0; c < 3; c++) {
            uint64_t c0 = cls->colour_q30[m * 3 + c], c1 = cls->colour_q30[(m + 1) * 3 + c];
            uint64_t w;
            if (t0 + t1 == 0) {
                w = (c0 + c1 + 1) / 2;
            } else {
                uint64_t num = 2 * t0 * c0 + t0 * c1 + t1 * c0 + 2 * t1 * c1, den = 3 * (t0 + t1);
                w = vfi_udiv64(num + den / 2, den);
            }
            cls->weight_q30[m * 3 + c] = (uint32_t)w;
        }
    }
    return VF_OK;
}

/* Channel 0..3 (r, g, b, a) of the transfer function at entry i's scalar, as Q.30 (unorm16 65535 becomes 2^30).
 * The scalar i * 65280 / (N - 1) (Q8.8) is kept as the exact fraction num / (N - 1). */
static uint64_t tf_value_q30(const vf_tf_t *tf, uint32_t entry, uint32_t n, int channel)
{
    const vf_tf_point_t *pts = tf->points;
    const uint64_t den = n - 1;
    const uint64_t num = (uint64_t)entry * SCALAR_MAX_Q8;
    /* the last point at or left of the scalar: later points win at a shared scalar (a step) */
    uint32_t p = 0;
    while (p + 1 < tf->count && (uint64_t)pts[p + 1].scalar_q8 * den <= num)
        p++;
    uint64_t value_q16; /* unorm16 value with 16 more fraction bits */
    if (p + 1 == tf->count || (uint64_t)pts[p].scalar_q8 * den > num) {
        /* beyond the last point, or left of the first */
        value_q16 = (uint64_t)channel_of(&pts[p], channel) << 16;
    } else {
        /* v = v0 + (v1 - v0) (s - s0) / (s1 - s0), with s = num / den */
        int64_t v0 = channel_of(&pts[p], channel), v1 = channel_of(&pts[p + 1], channel);
        int64_t ds_num = (int64_t)(num - (uint64_t)pts[p].scalar_q8 * den);
        int64_t ds_den = (int64_t)(pts[p + 1].scalar_q8 - pts[p].scalar_q8) * (int64_t)den;
        int64_t step = vfi_sdiv64_round((v1 - v0) * ds_num * 65536, ds_den);
        value_q16 = (uint64_t)((v0 << 16) + step);
    }
    /* unorm16 (65535 = 1.0) to Q.30 */
    return vfi_udiv64((value_q16 << 14) + 65535 / 2, 65535);
}

static uint32_t channel_of(const vf_tf_point_t *p, int channel)
{
    switch (channel) {
    case 0: return p->r;
    case 1: return p->g;
    case 2: return p->b;
    default: return p->a;
    }
}
