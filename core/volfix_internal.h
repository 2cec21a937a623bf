/* SPDX-License-Identifier: MIT */
/*
 * volfix_internal.h: what volfix's own tests and simulator reach into, beyond the public interface of volfix.h.
 * Not installed: nothing here is promised to users, and it may change with any version.
 *   - fault injection in the arena, for the tests' fault loops;
 *   - read access to the intermediate image and the tables, for tests that check a stage on its own;
 *   - the general compositing loops on demand, for tests that check the plain ones against them.
 */
#ifndef VOLFIX_INTERNAL_H
#define VOLFIX_INTERNAL_H

#include "volfix.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Allocation number `count` + 1 from this arena fails, and every one after it (0: none fails). The count
 * includes the allocations already made, so `vfi_arena_fail_after(a, a->allocs + n)` lets n more succeed. */
void vfi_arena_fail_after(vf_arena_t *arena, uint32_t count);

/* The intermediate image of the frame begun last (Q1.15 premultiplied r, g, b, a, int_w * int_h pixels), and the
 * tables (Q1.15 r, g, b, a per entry, colour premultiplied; the 2D table indexed [front * N + back]). NULL before
 * they exist, and for 8-bit tables. */
const uint16_t *vfi_renderer_intermediate(const vf_renderer_t *renderer);
const uint16_t *vfi_renderer_point_table(const vf_renderer_t *renderer);
const uint16_t *vfi_renderer_preint_table(const vf_renderer_t *renderer);
/* A thread's copy of the 2D table (vf_thread_table_t) in the frame begun last, whose built diagonals are the
 * shared table's; NULL when the frame shares its table or the memory is short. */
const uint16_t *vfi_renderer_thread_table(const vf_renderer_t *renderer, const vf_thread_table_t *table);
/* preint2's 3D table (Q1.15 r, g, b, a, [(front * N2 + middle) * N2 + back]) and, for lit frames, its eight front-
 * and back-weighted values an entry; NULL as above. (vfi_renderer_preint_table is its 2D table, the last slab's.) */
const uint16_t *vfi_renderer_order2_table(const vf_renderer_t *renderer);
const uint16_t *vfi_renderer_order2_lit_table(const vf_renderer_t *renderer);

/* Composite with the general loops alone (true), never the plain ones: the same pixels, to the bit, which tests
 * check; the plain loops exist for speed. */
void vfi_renderer_general_loops(vf_renderer_t *renderer, bool general);

#ifdef __cplusplus
}
#endif

#endif /* VOLFIX_INTERNAL_H */
