/* SPDX-License-Identifier: MIT */
/*
 * slices.h: the volume as 8-bit scalars (after the window), stored three times, once per principal axis, in
 * standard object order: for principal axis k, slice k holds n_j + 1 rows of n_i + 1 scalars. The extra column
 * and row repeat the last ones, so that a bilinear footprint at x = n_i - 1 (weight 0 on the neighbour) never
 * reads outside.
 */
#ifndef VF_SLICES_H
#define VF_SLICES_H

#include "volfix.h"

typedef struct vfi_layout {
    uint32_t ni, nj, nk;       /* dimensions along the standard axes */
    uint32_t row, slice;       /* bytes from one row (slice) to the next: n_i + 1, (n_i + 1)(n_j + 1) */
    int i_axis, j_axis;
} vfi_layout_t;

void vfi_layout(const uint32_t dims[3], int k_axis, vfi_layout_t *layout);
size_t vfi_slices_bytes(const uint32_t dims[3], int k_axis);

/* Window the volume into the copy for principal axis 2 (z, the file order), then transpose it into the copies
 * for axes 0 and 1. copies[a] must hold vfi_slices_bytes(dims, a). */
void vfi_slices_build(const vf_volume_t *volume, vf_window_t window, uint8_t *const copies[3]);

/* The copy for principal axis k_axis of a per-voxel array whose z copy is z (elements of elem = 1 or 2 bytes, in
 * the slices' layout), padded like the slices: the normals' copies are made as the slices' are. */
void vfi_transpose_copy(const void *z, const uint32_t dims[3], int k_axis, void *out, size_t elem);

/* The extra column and row of every slice of a copy (elements of elem bytes) set to repeat the last real ones. */
void vfi_pad_copy(void *copy, const vfi_layout_t *l, size_t elem);

/* The window's mapping of one raw value (docs/algorithm.md, section 1). */
uint8_t vfi_window_scalar(int32_t raw, vf_window_t window);

#endif
