/*
 * shade.h: lighting as compositing reads it (docs/algorithm.md, section 7): the shade table of a frame (every normal
 * code's diffuse and specular light), the gradient-opacity ramp, and a sample's shade from its voxels' codes.
 */
#ifndef VF_SHADE_H
#define VF_SHADE_H

#include "volfix.h"

/* A shade table entry: L_d in the low half, L_s in the high half, each Q2.14 (16384 = 1.0; at most ka + 2 kd < 3
 * and 2 ks). */
#define VFI_SHADE_ONE 16384u
static inline uint32_t vfi_shade_diffuse(uint32_t shade)
{
    return shade & 0xFFFFu;
}
static inline uint32_t vfi_shade_specular(uint32_t shade)
{
    return shade >> 16;
}

/* The view's rotation R (section 3), Q2.30: factor.c's, for the shade table. */
void vfi_view_rotation(const vf_view_t *view, int32_t r_q30[3][3]);

/* The shade table for rotation r and lighting: entry `code` of `count` codes (the last, count - 1, is the code
 * without a normal), from the codes' unit normals (normals.h, Q1.30). */
void vfi_shade_table(int32_t r_q30[3][3], const vf_lighting_t *lighting, const int32_t *unit, uint32_t count,
                     uint32_t *shade);

/* The gradient-opacity factor of each 8-bit magnitude, Q1.15 (32768 = 1): 1 everywhere without a ramp. */
void vfi_gradient_ramp(uint8_t lo, uint8_t hi, uint16_t factor[256]);

/* What a lit row needs: the frame's shade table, the ramp (NULL: no gradient opacity), and where the codes and
 * magnitudes of the slices' copy are (the same offsets as the scalars': normals.h). */
typedef struct vfi_shading {
    const uint32_t *shade;      /* NULL: unlit colours */
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

/* The shade of the sample at p (a voxel of the copy at sh->slices; its row is row elements long) with fractions
 * fx, fy (Q0.16). */
static inline vfi_shade_t vfi_sample_shade(const vfi_shading_t *sh, const uint8_t *p, uint32_t row, uint32_t fx,
                                           uint32_t fy)
{
    const size_t at = (size_t)(p - sh->slices);
    vfi_shade_t out = {VFI_SHADE_ONE, 0, 32768u};
    if (!sh->bilinear) {
        const size_t v = at + (fy >= 32768u ? row : 0) + (fx >= 32768u ? 1 : 0);
        if (sh->shade) {
            const uint32_t e = sh->shade[sh->codes[v]];
            out.d = vfi_shade_diffuse(e), out.s = vfi_shade_specular(e);
        }
        if (sh->ramp)
            out.g = sh->ramp[sh->magnitudes[v]];
        return out;
    }
    /* weights w00 w10 w01 w11 summing to 2^16 (segment.h's vfi_weights, written here without its clamp: fx, fy
     * < 2^16 for a slice sample) */
    const uint32_t w11 = (fx * fy + 0x8000u) >> 16, w10 = fx - w11, w01 = fy - w11, w00 = 65536u - fx - fy + w11;
    const size_t v[4] = {at, at + 1, at + row, at + row + 1};
    const uint32_t w[4] = {w00, w10, w01, w11};
    if (sh->shade) {
        uint32_t d = 0, s = 0;
        for (int k = 0; k < 4; k++) {
            const uint32_t e = sh->shade[sh->codes[v[k]]];
            d += vfi_shade_diffuse(e) * w[k];
            s += vfi_shade_specular(e) * w[k];
        }
        out.d = (d + 0x8000u) >> 16, out.s = (s + 0x8000u) >> 16;
    }
    if (sh->ramp) {
        uint32_t g = 0;
        for (int k = 0; k < 4; k++)
            g += sh->ramp[sh->magnitudes[v[k]]] * w[k];
        out.g = (g + 0x8000u) >> 16;
    }
    return out;
}

#endif
