/* SPDX-License-Identifier: MIT */
/*
 * preint2.h: order 2 (docs/algorithm.md, section 8; El Hajjar, Marchesin, Dischler and Mongenet 2008): the 3D table
 * T2[front][middle][back] of a slab of two slices, built from first-order pieces (preint2.c), and what compositing
 * reads of it (composite_order2.c).
 *
 * An entry's quadratic P(t) through its three entry scalars is cut into K pieces of t; piece i joins P(t_i) and
 * P(t_{i+1}) and is the entry (idx(P(t_i)), idx(P(t_{i+1}))) of the n-entry 2D table for length 2d / K. That 2D
 * table (the pieces) is built once by the incremental builder (preint.c) into Q.30, unrounded, and every 3D entry
 * composites its K pieces in Q.30 and is rounded once, into the table's format.
 */
#ifndef VF_PREINT2_H
#define VF_PREINT2_H

#include "tables.h"

#define VFI_ORDER2_PIECES 16u /* K: pieces a slab's curve is cut into (docs/algorithm.md, section 8) */

/* The pieces of one order-2 table: the 2D table for length 2d / K in Q.30 (r, g, b, a a entry, [front * n + back]),
 * and with lighting its front-weighted values (D_f r, g, b and S_f, docs/algorithm.md section 7). They are built
 * from the classification with every extinction divided by K / 2 (tau), so that a table built for d is the table
 * for 2d / K: the division rounds at 2^-28, where rounding 2d / K itself to the Q16.16 of the builders' lengths
 * would cost up to 3 bits of the slab length. */
typedef struct vfi_order2_pieces {
    uint32_t *tau;   /* [n], Q4.28 */
    uint32_t *table; /* [n * n * 4], Q.30 */
    uint32_t *lit;   /* [n * n * 4], Q.30, or NULL: no lighting */
    uint32_t n;
} vfi_order2_pieces_t;

/* Arena bytes for the pieces of an n-entry table (lit: with the front-weighted values). */
size_t vfi_order2_pieces_bytes(uint32_t n, bool lit);
vf_status_t vfi_order2_pieces_alloc(vfi_order2_pieces_t *pieces, uint32_t n, bool lit, vf_arena_t *arena);

/* The pieces for slabs of 2d (d = slab_q16, Q16.16) from the classification cls, with the incremental builder's
 * scratch (from vfi_table_scratch_alloc_lit when lit); lit: also the front-weighted values (pieces->lit set). */
void vfi_order2_pieces_build(vfi_order2_pieces_t *pieces, const vfi_classify_t *cls, uint32_t slab_q16,
                             const vfi_table_scratch_t *scratch, bool lit);

/* The n2^3 entries of the order-2 table from its pieces, into out (q15 with grid_bits, or u8; four values an entry,
 * [(front * n2 + middle) * n2 + back]) and, when out has lit outputs (and the pieces theirs), the entries' front-
 * and back-weighted values W_f r, g, b, S_f and W_b r, g, b, S_b, eight values an entry at the same index (stored
 * as entries 2e and 2e + 1 of four). Part part of parts writes the entries of the fronts f = part, part + parts, ...
 * and of their mirrors (the same curve from the back), no other: parts may run side by side, and all parts give
 * the whole table, to the bit. */
void vfi_order2_table_part(const vfi_order2_pieces_t *pieces, uint32_t n2, vfi_table_out_t out, uint32_t part,
                           uint32_t parts);

/* The table entries (of the classification's n) that a sample of scalar v can touch in a preint2 renderer, for
 * the run-length encoder: those of its order-2 entries' scalars (the nearest, or with interpolated lookups the two
 * around it), whose curves the pieces follow, beside those the classification gave it for the last slab's order-1
 * lookup (nearest, or bilinear for interpolated ones). The curve of an entry stays within its three scalars
 * (section 8), so a segment whose cells hold no visible entry in that range is exactly zero. Call after
 * vfi_classify_alloc and before vfi_classify, which reads them. */
void vfi_order2_scalar_entries(vfi_classify_t *cls, uint32_t n2, bool interpolated);

/* What compositing reads of the order-2 table: one of q15 and u8, and with lighting one of lit_q15 and lit_u8
 * (eight values an entry). */
typedef struct vfi_lookup2 {
    const uint16_t *q15;
    const uint8_t *u8;
    const uint16_t *lit_q15;
    const uint8_t *lit_u8;
    uint32_t n2;
} vfi_lookup2_t;

#endif
