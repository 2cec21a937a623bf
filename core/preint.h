/* SPDX-License-Identifier: MIT */
/*
 * preint.h: the parts of the pre-integrated table's builder (preint.c) that work on its intervals, once a table
 * and once a diagonal (preint_intervals.c). tables.h is the builder's interface to the rest of the core.
 */
#ifndef VF_PREINT_H
#define VF_PREINT_H

#include "tables.h"

#define ONE_Q30 (UINT32_C(1) << 30)
#define HALF_Q30 (UINT64_C(1) << 29)
#define ONE_Q60 (UINT64_C(1) << 60)
#define HALF_Q15_IN_Q60 (UINT64_C(1) << 44) /* half an LSB of Q1.15, in Q.60 */

/* The records of the intervals, once a table (their weights and mean extinction; an interval that lets all through
 * at every length gets t = 1 here). Returns how many are listed for the transmittances; *grey: whether every
 * weight's three channels are equal. */
uint32_t vfi_preint_list_intervals(const vfi_classify_t *cls, const vfi_table_scratch_t *scratch, bool *grey);

/* The listed intervals' transmittances for pieces of length_q28 (Q.28, in d_ref); _lit: and their alpha t(x). */
void vfi_preint_transmittances(const vfi_table_scratch_t *scratch, uint32_t visible_count, uint32_t count,
                               uint64_t length_q28);
void vfi_preint_transmittances_lit(const vfi_table_scratch_t *scratch, uint32_t visible_count, uint32_t count,
                                   uint64_t length_q28);

/* The listed intervals k_lo .. k_hi - 1 only (a block of a table built as read). */
void vfi_preint_transmittances_listed(const vfi_table_scratch_t *scratch, uint32_t k_lo, uint32_t k_hi,
                                      uint64_t length_q28, bool lit);

/* A diagonal's piece length d / r in Q.28, d the slab length in Q16.16. */
uint64_t vfi_preint_piece_length_q28(uint32_t slab_q16, uint32_t r);

#endif
