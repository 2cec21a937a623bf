/* SPDX-License-Identifier: MIT */
/*
 * preint_intervals.c: the pre-integrated table's intervals (docs/algorithm.md section 2): their records, once a
 * table, and their transmittances for each diagonal's piece length, from which preint.c builds the entries.
 */
#include "fixmath.h"
#include "preint.h"

/* The records of the intervals, once a table: the weights; step = (w - w_before) 2^30 + 2^29 and w_q60 = w 2^30
 * - 2^29 + the half of Q1.15 (block_dense's constants: the colourless records before the first interval and
 * after the last count as weight 0); the mean extinction (t0 + t1) / 2 in Q.24. An interval whose mean rounds to
 * 0 lets all through at every length: its t is set to 1 here, once; the others are listed for vfi_preint_transmittances().
 * Returns how many are listed; *grey: whether every weight's three channels are equal (block_dense_grey). */
uint32_t vfi_preint_list_intervals(const vfi_classify_t *cls, const vfi_table_scratch_t *scratch, bool *grey)
{
    const uint32_t count = cls->n - 1;
    vfi_interval_t *iv = scratch->interval + 1; /* interval m at iv + m, m = -1 .. count */
    *grey = true;
    for (uint32_t m = 0; m < count; m++) {
        for (int c = 0; c < 3; c++)
            iv[m].w[c] = cls->weight_q30[m * 3 + c];
        *grey = *grey && iv[m].w[1] == iv[m].w[0] && iv[m].w[2] == iv[m].w[0];
    }
    for (int c = 0; c < 3; c++)
        iv[-1].w[c] = iv[count].w[c] = 0;
    iv[-1].t = iv[count].t = ONE_Q30;
    uint32_t listed = 0;
    for (uint32_t m = 0; m <= count; m++) {
        vfi_interval_t *v = &iv[m];
        for (int c = 0; c < 3; c++)
            v->step[c] = ((int64_t)v->w[c] - (int64_t)v[-1].w[c]) * (INT64_C(1) << 30) + (int64_t)HALF_Q30;
        if (m == count)
            break;
        v->mean_q24 = (uint32_t)(((uint64_t)cls->tau_q28[m] + cls->tau_q28[m + 1] + 16) >> 5);
        scratch->first_visible[m] = (uint16_t)listed;
        if (v->mean_q24 != 0)
            scratch->visible[listed++] = (uint16_t)m;
        else
            v->t = ONE_Q30;
    }
    for (int64_t m = -1; m <= (int64_t)count; m++)
        for (int c = 0; c < 3; c++)
            iv[m].w_q60[c] = ((uint64_t)iv[m].w[c] << 30) + (HALF_Q15_IN_Q60 - HALF_Q30);
    scratch->first_visible[count] = (uint16_t)listed;
    return listed;
}

/* The listed intervals' transmittance exp(-mean L) for pieces of length L (Q.28, in d_ref): the brute force's
 * 1 - opacity, to the bit (the same exponential, inline); lit: and alpha t(x) of the same x. */
static VF_ALWAYS_INLINE void transmittance(const uint32_t *exp_tables, vfi_interval_t *v, uint64_t length_q28,
                                           bool lit)
{
    /* the mean extinction in Q.24 times the length in Q.28: Q.52, back to Q.28 */
    const uint64_t x = ((uint64_t)v->mean_q24 * length_q28 + (UINT64_C(1) << 23)) >> 24;
    v->t = vfi_exp_neg_q28_with(exp_tables, x);
    if (VF_LIT_TABLES && lit)
        v->g = vfi_emission_depth_q30(x, v->t);
}

static VF_ALWAYS_INLINE void transmittances_body(const vfi_table_scratch_t *scratch, uint32_t visible_count,
                                                 uint32_t count, uint64_t length_q28, bool lit)
{
    const uint32_t *exp_tables = vfi_exp_neg_tables();
    vfi_interval_t *iv = scratch->interval + 1;
    if (visible_count == count) /* all listed: no list to read */
        for (vfi_interval_t *v = iv; v < iv + count; v++)
            transmittance(exp_tables, v, length_q28, lit);
    else
        for (uint32_t k = 0; k < visible_count; k++)
            transmittance(exp_tables, &iv[scratch->visible[k]], length_q28, lit);
}

/* Once a diagonal, unlit and lit each with the body inlined. */
void vfi_preint_transmittances(const vfi_table_scratch_t *scratch, uint32_t visible_count, uint32_t count,
                               uint64_t length_q28)
{
    transmittances_body(scratch, visible_count, count, length_q28, false);
}

void vfi_preint_transmittances_lit(const vfi_table_scratch_t *scratch, uint32_t visible_count, uint32_t count,
                                   uint64_t length_q28)
{
    transmittances_body(scratch, visible_count, count, length_q28, true);
}

/* d / r in Q.28 from d in Q16.16, rounded: (d 2^12 + r / 2) / r. Long division in 16-bit digits, so that each
 * step is a 32-bit division (remainder < r < 2^16, so remainder 2^16 + digit < 2^32) where vfi_udiv64 took
 * 64 shift-and-subtract steps; the quotient is the same. */
uint64_t vfi_preint_piece_length_q28(uint32_t slab_q16, uint32_t r)
{
    uint64_t num = ((uint64_t)slab_q16 << 12) + r / 2, q = 0;
    uint32_t rem = 0;
    for (int shift = 48; shift >= 0; shift -= 16) {
        uint32_t cur = (rem << 16) | (uint32_t)((num >> shift) & 0xFFFFu);
        q = (q << 16) | (cur / r);
        rem = cur % r;
    }
    return q;
}

#if VF_TABLE_ON_DEMAND
/* The listed intervals k_lo .. k_hi - 1's transmittances (lit: and alpha t(x)) for pieces of length_q28. */
void vfi_preint_transmittances_listed(const vfi_table_scratch_t *scratch, uint32_t k_lo, uint32_t k_hi,
                                      uint64_t length_q28, bool lit)
{
    const uint32_t *exp_tables = vfi_exp_neg_tables();
    vfi_interval_t *iv = scratch->interval + 1;
    for (uint32_t k = k_lo; k < k_hi; k++)
        transmittance(exp_tables, &iv[scratch->visible[k]], length_q28, lit);
}
#endif
