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
 *
 * Bricks: the cells in blocks of VFI_BRICK a side, in object space so that one set serves all three copies, each
 * with the lowest and highest scalar of the voxels its cells read (made once per window). A transfer function
 * then settles a whole brick by its range: no cell of it visible, or every cell visible (every scalar of the
 * range visible alone: vfi_range_solid), and the encoder reads the cells of the other bricks only. The run lists
 * are the same as from reading every cell. Builds without them (VF_RUN_BRICKS 0) read every cell.
 */
#ifndef VF_RUNS_H
#define VF_RUNS_H

#include "arena.h"
#include "classify.h"
#include "slices.h"

typedef struct vfi_runs {
    const uint32_t *row_start; /* [(n_k - 1) n_j + 1]: index of each row's first pair in pairs (uint16 units) */
    const uint16_t *pairs;     /* skip, length, skip, length, ... (the arena's, or prebuilt in read-only memory) */
    uint32_t nj;         /* rows per slab */
} vfi_runs_t;

/* Cells a brick side. 8: a brick's range costs 2 bytes for 512 cells, and is settled with two loads for the 8
 * cells of each row through it. */
#define VFI_BRICK 8

typedef struct vfi_bricks {
    uint8_t *range;   /* [n[0] n[1] n[2]] lowest and highest scalar of each brick, x fastest */
    uint32_t n[3];    /* bricks along x, y, z: ceil(dims / VFI_BRICK) */
} vfi_bricks_t;

size_t vfi_runs_index_bytes(const vfi_layout_t *layout);

size_t vfi_bricks_bytes(const uint32_t dims[3]);
/* Point bricks at range (vfi_bricks_bytes of memory) and size it for the volume. */
void vfi_bricks_init(vfi_bricks_t *bricks, const uint32_t dims[3], uint8_t *range);
/* The bricks' ranges from the copy for principal axis 2 (x fastest, the layout of slices.h). Brick b covers
 * cells b VFI_BRICK .. b VFI_BRICK + VFI_BRICK - 1 along each axis, which read voxels up to one further, the
 * last voxel standing for the copies' padding. */
void vfi_bricks_build(vfi_bricks_t *bricks, const uint8_t *z_copy, const uint32_t dims[3]);

/* Encode in one pass: the pairs go into pairs while they fit in `capacity` uint16 values, the row index into
 * row_start (when not NULL). Returns the values the whole encoding needs; more than capacity means it did not
 * fit (the pairs are then incomplete). pairs NULL: count only. bricks NULL: every cell is read (the tests'
 * oracle); else the bricks of the same window. */
size_t vfi_runs_encode(const uint8_t *copy, const vfi_layout_t *layout, const vfi_classify_t *cls,
                       const vfi_bricks_t *bricks, uint32_t *row_start, uint16_t *pairs, size_t capacity);

/* The same for the cells of slabs [k0, k1) alone: their rows' index entries (row_start[k0 n_j] ..
 * row_start[k1 n_j - 1], counted from the first value written here) and their pairs; no other entry is written,
 * so that slab ranges can be encoded side by side into one index. vfi_runs_encode is the range of every slab
 * followed by the index's closing entry. */
size_t vfi_runs_encode_slabs(const uint8_t *copy, const vfi_layout_t *layout, const vfi_classify_t *cls,
                             const vfi_bricks_t *bricks, uint32_t k0, uint32_t k1, uint32_t *row_start,
                             uint16_t *pairs, size_t capacity);

/* The three axes' indices from the arena, in axis order (false, and NULL for those that did not fit, when it is
 * short); *bytes: what the three take. Inline: a build without encodings in parts has one caller. */
static inline bool vfi_runs_indices(vf_arena_t *arena, const vfi_layout_t layout[3], uint32_t *index[3],
                                    size_t *bytes)
{
    bool fit = true;
    *bytes = 0;
    for (int a = 0; a < 3; a++) {
        const size_t index_bytes = vfi_runs_index_bytes(&layout[a]);
        index[a] = fit ? vfi_arena_alloc(arena, index_bytes) : NULL;
        fit = index[a] != NULL;
        *bytes += index_bytes;
    }
    return fit;
}

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
