/* SPDX-License-Identifier: MIT */
/*
 * normals.h: per-voxel normal codes and gradient magnitudes for lighting (docs/algorithm.md, section 7), made once
 * per volume from the voxels as stored, and kept one copy per principal axis in the slices' layout (slices.h), so
 * that compositing reads a sample's normals at the offset it reads its scalars.
 */
#ifndef VF_NORMALS_H
#define VF_NORMALS_H

#include "slices.h"

/* Levels a side of the octahedron for normal_bits bits: L = 2^(bits / 2) - 1 (odd, so that 0 is a level). Codes
 * 0 .. L^2 - 1 are normals; L^2 is the code of a voxel without a gradient. */
static inline uint32_t vfi_normal_levels(uint32_t normal_bits)
{
    return (UINT32_C(1) << (normal_bits / 2)) - 1;
}

static inline uint32_t vfi_normal_code_count(uint32_t levels)
{
    return levels * levels + 1;
}

/* The code of gradient (gx, gy, gz): the octahedral map, rounded exactly (section 7). */
uint32_t vfi_normal_code(int64_t gx, int64_t gy, int64_t gz, uint32_t levels);

/* The unit normal of every code as Q1.30 x, y, z, world axes; (0, 0, 0) for the code L^2. Q1.30 rather than
 * fewer bits because a high shininess magnifies a normal's error in the specular term (e x^(e - 1) times it). */
void vfi_normals_decode(uint32_t levels, int32_t *unit);

/* Normal codes (uint16_t, in the slices' layout) and 8-bit gradient magnitudes for the copies of every principal
 * axis. codes[a] must hold vfi_slices_bytes(dims, a) uint16_t, magnitudes[a] as many bytes. */
void vfi_normals_build(const vf_volume_t *volume, uint32_t levels, uint16_t *const codes[3],
                       uint8_t *const magnitudes[3]);

#endif
