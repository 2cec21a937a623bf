/* SPDX-License-Identifier: MIT */
/*
 * table_store.h: how the table builders round a Q.30 value (1.0 = 2^30) into the three table formats of
 * tables.h, shared by tables.c (point table, brute force) and preint.c (the incremental builder) so that they
 * round alike. Static inline: the builders call these for every entry.
 *
 * No clamp. A builder's values are at most 1.0 + VFI_STORE_SLACK_Q30 (tables.c and preint.c prove their
 * bounds: 0 and 1023 LSB; a front-weighted value is at most its entry's C or a before the rounding), and every
 * conversion here maps 1.0 + VFI_STORE_SLACK_Q30 to at most 1.0 of its format: round(x 2^15) is 2^15 below
 * 1.0 + 2^-16 (slack < 2^14); round(255 x) is 255 below 1.0 + 2^-1 / 255 (slack < 2^29 / 255); round(L x),
 * L = 2^B - 1 <= 4095, is L below 1.0 + 2^-1 / L (slack < 2^29 / 4095).
 * tests/core/test_classify_tables.c checks the three at 1.0 + VFI_STORE_SLACK_Q30.
 */
#ifndef VF_TABLE_STORE_H
#define VF_TABLE_STORE_H

#include "tables.h"

#define VFI_STORE_SLACK_Q30 16383u /* the largest excess over 1.0 that still rounds to 1.0 in every format */

static inline uint16_t vfi_q30_to_q15(uint32_t v)
{
    return (uint16_t)((v + (1u << 14)) >> 15);
}

static inline uint8_t vfi_q30_to_u8(uint32_t v)
{
    return (uint8_t)(((uint64_t)v * 255 + (UINT64_C(1) << 29)) >> 30); /* round(255 x) */
}

/* round((2^B - 1) x) / (2^B - 1), back in Q1.15 */
static inline uint16_t vfi_q30_to_grid(uint32_t v, uint32_t bits)
{
    uint64_t levels = (UINT64_C(1) << bits) - 1;
    uint64_t q = ((uint64_t)v * levels + (UINT64_C(1) << 29)) >> 30;
    return (uint16_t)((q * VFI_ONE_Q15 + levels / 2) / levels);
}

/* vfi_store_q30 out of line (preint.c), for the point table and the brute force in tables.c, whose speed does not
 * matter: one copy of the rounding in a build for size. out by address: the table's record is 5 words, more than
 * the registers that pass arguments on 32-bit ARM. */
void vfi_store_entry(const vfi_table_out_t *out, size_t entry, uint32_t r, uint32_t g, uint32_t b, uint32_t a);

/* Four Q.30 values into entry `entry` of the table at q15 (with grid_bits) or u8, whichever is set. */
static inline void vfi_store_values_q30(uint16_t *q15, uint8_t *u8, uint32_t grid_bits, size_t entry, uint32_t r,
                                        uint32_t g, uint32_t b, uint32_t a)
{
    if (q15 && grid_bits) {
        uint16_t *e = q15 + entry * 4;
        e[0] = vfi_q30_to_grid(r, grid_bits);
        e[1] = vfi_q30_to_grid(g, grid_bits);
        e[2] = vfi_q30_to_grid(b, grid_bits);
        e[3] = vfi_q30_to_grid(a, grid_bits);
    } else if (q15) {
        uint16_t *e = q15 + entry * 4;
        e[0] = vfi_q30_to_q15(r);
        e[1] = vfi_q30_to_q15(g);
        e[2] = vfi_q30_to_q15(b);
        e[3] = vfi_q30_to_q15(a);
    } else {
        uint8_t *e = u8 + entry * 4;
        e[0] = vfi_q30_to_u8(r);
        e[1] = vfi_q30_to_u8(g);
        e[2] = vfi_q30_to_u8(b);
        e[3] = vfi_q30_to_u8(a);
    }
}

/* Four Q.30 values as they are (order 2's pieces, preint2.h). */
static inline void vfi_put_q30(uint32_t *q30, size_t entry, uint32_t r, uint32_t g, uint32_t b, uint32_t a)
{
    uint32_t *e = q30 + entry * 4;
    e[0] = r;
    e[1] = g;
    e[2] = b;
    e[3] = a;
}

/* Entry `entry` of the table: r, g, b premultiplied and opacity a, Q.30. Inline: a call from preint.c's loops,
 * even one taken for the 8-bit and grid formats only, leaves the default format's loop fewer registers for its runs. */
static inline void vfi_store_q30(vfi_table_out_t out, size_t entry, uint32_t r, uint32_t g, uint32_t b, uint32_t a)
{
    if (VF_ORDER2 && out.q30) /* order 2's pieces, kept as they are */
        vfi_put_q30(out.q30, entry, r, g, b, a);
    else
        vfi_store_values_q30(out.q15, out.u8, out.grid_bits, entry, r, g, b, a);
}

/* The entry's front-weighted values D_f r, g, b and S_f, Q.30, into out.lit_q15 or out.lit_u8. */
static inline void vfi_store_lit_q30(vfi_table_out_t out, size_t entry, uint32_t r, uint32_t g, uint32_t b,
                                     uint32_t a)
{
    if (VF_ORDER2 && out.lit_q30)
        vfi_put_q30(out.lit_q30, entry, r, g, b, a);
    else
        vfi_store_values_q30(out.lit_q15, out.lit_u8, out.grid_bits, entry, r, g, b, a);
}

#endif
