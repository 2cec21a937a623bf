/* SPDX-License-Identifier: MIT */
/*
 * runs.h: run-length encoding of the visible cells, per principal axis.
 *
 * A cell (i, j) of slab k is the 2x2x2 block of scalars (i..i+1, j..j+1, k..k+1) of the standard-order copy
 * (slices.h; the padding makes cells n_i - 1 and n_j - 1 exist). A cell is visible when some table entry in its
 * scalar range [min, max] has extinction > 0. A slab segment's front and back samples each lie on a face of
 * one cell, the two cells share a voxel, so the segment's scalar range is inside the union of their ranges:
 * a segment whose two cells are invisible contributes exactly nothing and is skipped without being read.
 *
 * Each row (k, j) of cells is a list of (skip, length) pairs: skip invisible cells, then length visible ones.
 */
#ifndef VF_RUNS_H
#define VF_RUNS_H

#include "classify.h"
#include "slices.h"

typedef struct vfi_runs {
    const uint32_t *row_start; /* [(n_k - 1) n_j + 1]: index of each row's first pair in pairs (uint16 units) */
    const uint16_t *pairs;     /* skip, length, skip, length, ... (the arena's, or prebuilt in read-only memory) */
    uint32_t nj;         /* rows per slab */
} vfi_runs_t;

size_t vfi_runs_index_bytes(const vfi_layout_t *layout);

/* Encode in one pass: the pairs go into pairs while they fit in `capacity` uint16 values, the row index into
 * row_start (when not NULL). Returns the values the whole encoding needs; more than capacity means it did not
 * fit (the pairs are then incomplete). pairs NULL: count only. */
size_t vfi_runs_encode(const uint8_t *copy, const vfi_layout_t *layout, const vfi_classify_t *cls,
                       uint32_t *row_start, uint16_t *pairs, size_t capacity);

/* Whether run lists made elsewhere (row_count index entries, pair_count values) are whole for this layout: the
 * index starts at 0, never falls, ends at pair_count, every row holds whole pairs and at most n_i cells. */
bool vfi_runs_valid(const uint32_t *row_start, size_t row_count, const uint16_t *pairs, size_t pair_count,
                    const vfi_layout_t *layout);

/* The pairs of cell row j of slab k, as [begin, end). */
static inline const uint16_t *vfi_runs_row(const vfi_runs_t *runs, uint32_t k, uint32_t j, const uint16_t **end)
{
    uint32_t r = k * runs->nj + j;
    *end = runs->pairs + runs->row_start[r + 1];
    return runs->pairs + runs->row_start[r];
}

#endif
