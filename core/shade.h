/* SPDX-License-Identifier: MIT */
/*
 * shade.h: lighting as compositing reads it (docs/algorithm.md, section 7): the shade table of a frame (every normal
 * code's diffuse and specular light), the gradient-opacity ramp, and a sample's shade from its voxels' codes.
 */
#ifndef VF_SHADE_H
#define VF_SHADE_H

#include "volfix.h"

/* A shade table entry: L_d in the low 32-bit lane, L_s in the high one, each Q2.14 (16384 = 1.0; at most ka + 2 kd
 * < 3 and 2 ks, so below 2^16): lanes, so that one product serves both in the bilinear shade's lerps. A buffered
 * shade (composite_order1.c) is packed into 32 bits, L_d low and L_s high. */
#define VFI_SHADE_ONE 16384u
static inline uint32_t vfi_shade_diffuse(uint64_t shade)
{
    return (uint32_t)(shade & 0xFFFFu);
}
static inline uint32_t vfi_shade_specular(uint64_t shade)
{
    return (uint32_t)(shade >> 32);
}

/* The view's rotation R (section 3), Q2.30: factor.c's, for the shade table. */
void vfi_view_rotation(const vf_view_t *view, int32_t r_q30[3][3]);

/* The shade table for rotation r and lighting: entry `code` of `count` codes (the last, count - 1, is the code
 * without a normal), from the codes' unit normals (normals.h, Q1.30). */
void vfi_shade_table(int32_t r_q30[3][3], const vf_lighting_t *lighting, const int32_t *unit, uint32_t count,
                     uint64_t *shade);

/* The gradient-opacity factor of each 8-bit magnitude, Q1.15 (32768 = 1): 1 everywhere without a ramp. */
void vfi_gradient_ramp(uint8_t lo, uint8_t hi, uint16_t factor[256]);

/* What a lit row needs: the frame's shade table, the ramp (NULL: no gradient opacity), and where the codes and
 * magnitudes of the slices' copy are (the same offsets as the scalars': normals.h). */
typedef struct vfi_shading {
    const uint64_t *shade;      /* NULL: unlit colours */
    const uint16_t *ramp;       /* NULL: opacity as it is */
    const uint8_t *slices;      /* the copy's scalars, for the offset of a sample's voxel */
    const uint16_t *codes;
    const uint8_t *magnitudes;
    bool bilinear;              /* the four voxels' shades interpolated, else the nearest voxel's */
} vfi_shading_t;

/* A sample's shade: L_d, L_s (Q2.14) and the gradient factor g (Q1.15). */
typedef struct vfi_shade {
    uint32_t d, s, g;
} vfi_shade_t;

/* A shade in lanes packed into 32 bits (L_d low, L_s high), as buffers keep it, and back. */
static inline uint64_t vfi_shade_lanes(uint32_t packed)
{
    return (packed & 0xFFFFu) | (uint64_t)(packed >> 16) << 32;
}

static inline uint32_t vfi_shade_pack(uint64_t lanes)
{
    return (uint32_t)(lanes | lanes >> 16); /* each lane below 2^16: L_s lands on bits 16-31 over L_d's clear ones */
}

/* (1 - f) a + f b in each lane, f Q0.16, rounded: every lane below 2^16 in, so below 2^32 before the shift (no
 * carry from the low lane into the high one) and below 2^16 out. */
static inline uint64_t vfi_lanes_lerp(uint64_t a, uint64_t b, uint32_t f)
{
    const uint64_t x = a * (65536u - f) + b * f + (UINT64_C(0x8000) << 32 | 0x8000u);
    return (x & 0xFFFFFFFFu) >> 16 | (x >> 48) << 32;
}

/* The same for one value (the gradient factor). */
static inline uint32_t vfi_value_lerp(uint32_t a, uint32_t b, uint32_t f)
{
    return (a * (65536u - f) + b * f + 0x8000u) >> 16;
}

/* A column of the bilinear shade: the voxel at `at` and the one below it (row elements on), lerped by fy. */
static inline uint64_t vfi_shade_column(const vfi_shading_t *sh, size_t at, uint32_t row, uint32_t fy)
{
    return vfi_lanes_lerp(sh->shade[sh->codes[at]], sh->shade[sh->codes[at + row]], fy);
}

/* The shade of the voxel at index v of the slices: its normal's entry and its gradient ramp. */
static inline vfi_shade_t vfi_voxel_shade_at(const vfi_shading_t *sh, size_t v)
{
    vfi_shade_t out = {VFI_SHADE_ONE, 0, 32768u};
    if (sh->shade) {
        const uint64_t e = sh->shade[sh->codes[v]];
        out.d = vfi_shade_diffuse(e), out.s = vfi_shade_specular(e);
    }
    if (sh->ramp)
        out.g = sh->ramp[sh->magnitudes[v]];
    return out;
}

/* The shade of the sample at p (a voxel of the copy at sh->slices; its row is row elements long) with fractions
 * fx, fy (Q0.16). Bilinear: by columns, each lerped by fy, then the two columns by fx (the plain loops reuse a
 * column for the next pixel: composite_order1.c). */
static inline vfi_shade_t vfi_sample_shade(const vfi_shading_t *sh, const uint8_t *p, uint32_t row, uint32_t fx,
                                           uint32_t fy)
{
    const size_t at = (size_t)(p - sh->slices);
    vfi_shade_t out = {VFI_SHADE_ONE, 0, 32768u};
    if (!sh->bilinear)
        return vfi_voxel_shade_at(sh, at + (fy >= 32768u ? row : 0) + (fx >= 32768u ? 1 : 0));
    if (sh->shade) {
        const uint64_t e = vfi_lanes_lerp(vfi_shade_column(sh, at, row, fy), vfi_shade_column(sh, at + 1, row, fy), fx);
        out.d = vfi_shade_diffuse(e), out.s = vfi_shade_specular(e);
    }
    if (sh->ramp) {
        const uint16_t *ramp = sh->ramp;
        const uint8_t *m = sh->magnitudes + at;
        out.g = vfi_value_lerp(vfi_value_lerp(ramp[m[0]], ramp[m[row]], fy), vfi_value_lerp(ramp[m[1]], ramp[m[row + 1]], fy),
                               fx);
    }
    return out;
}

#endif
