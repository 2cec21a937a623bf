/*
 * tables.h: the lookup tables compositing reads, built from a classification for one slab length
 * (docs/algorithm.md, section 2). An entry is four Q1.15 values (1.0 = 32768): premultiplied r, g, b and
 * opacity a. The 2D table is indexed [front * N + back].
 */
#ifndef VF_TABLES_H
#define VF_TABLES_H

#include "classify.h"

#define VFI_ONE_Q15 32768u

/* Scratch the builders need besides their output: interval opacity and colour for one piece length. */
typedef struct vfi_table_scratch {
    uint32_t *interval_q30; /* [(n - 1) * 4]: alpha, r, g, b of interval m */
} vfi_table_scratch_t;

size_t vfi_table_scratch_bytes(uint32_t n);
vf_status_t vfi_table_scratch_alloc(vfi_table_scratch_t *scratch, uint32_t n, vf_arena_t *arena);

/* Order 0: entry i = (c_i a_i, a_i), a_i = 1 - exp(-tau_i d). out has n * 4 values. */
void vfi_point_table(const vfi_classify_t *cls, uint32_t slab_q16, uint16_t *out);

/* Order 1 by brute force, O(N^3): every off-diagonal entry composites its |b - f| intervals one by one. The
 * oracle for faster builders. out has n * n * 4 values. */
void vfi_preint_table_bruteforce(const vfi_classify_t *cls, uint32_t slab_q16, vfi_table_scratch_t *scratch,
                                 uint16_t *out);

#endif
