/* SPDX-License-Identifier: MIT */
/*
 * segment.h: what one segment (a slice sample, or a slab) adds to a pixel: the table entry, looked up nearest or
 * bilinear in an 8- or 16-bit table, corrected for the slab length by the lut if asked (docs/algorithm.md,
 * section 4b), then composited front to back. Static inline so that the compositing loops keep them in line.
 *
 * All values here are Q1.15 (1.0 = 32768), r, g, b, a, colour premultiplied.
 */
#ifndef VF_SEGMENT_H
#define VF_SEGMENT_H

#include "renderer.h"

/* Entry e (index into the table, in entries) as Q1.15. An 8-bit value v is v / 255: (257 v + 1) / 2 is
 * v * 32768 / 255 within half an LSB, and 255 gives exactly 32768. */
static inline void vfi_fetch_from(const uint16_t *q15, const uint8_t *u8, size_t e, uint32_t out[4])
{
    if (q15) {
        const uint16_t *p = q15 + e * 4;
        out[0] = p[0], out[1] = p[1], out[2] = p[2], out[3] = p[3];
    } else {
        const uint8_t *p = u8 + e * 4;
        for (int k = 0; k < 4; k++)
            out[k] = (257u * p[k] + 1u) >> 1;
    }
}

static inline void vfi_fetch(const vfi_lookup_ctx_t *c, size_t e, uint32_t out[4])
{
    vfi_fetch_from(c->q15, c->u8, e, out);
}

/* x = (1 - f) x + f y per channel, f in Q0.16 (up to 65536); values at most 1.0 (32768), so the sum of the two
 * products is at most 2^31 and 32 bits hold it. */
static inline void vfi_lerp(uint32_t x[4], const uint32_t y[4], uint32_t f)
{
    for (int k = 0; k < 4; k++)
        x[k] = (x[k] * (65536u - f) + y[k] * f + 0x8000u) >> 16;
}

/* The four bilinear weights of fractions fx, fy (Q0.16), summing to exactly 65536: w00 w10 w01 w11. */
static inline void vfi_weights(uint32_t fx, uint32_t fy, uint32_t w[4])
{
    if (fx == 65536 || fy == 65536) { /* a clamped last entry: the products below would need 33 bits */
        uint64_t w11 = ((uint64_t)fx * fy + 0x8000u) >> 16;
        w[3] = (uint32_t)w11;
    } else {
        w[3] = (fx * fy + 0x8000u) >> 16;
    }
    w[1] = fx - w[3];
    w[2] = fy - w[3];
    w[0] = 65536u - fx - fy + w[3];
}

/* A bilinear table position (Q.16, from vfi_position_of_sample) as an entry below and a fraction to the next:
 * i = min(floor(x), N - 2), f = x - i (so f is 65536 at the last entry). */
static inline void vfi_split_position(uint32_t n, uint32_t x_q16, uint32_t *i, uint32_t *f)
{
    uint32_t whole = x_q16 >> 16;
    *i = whole < n - 1 ? whole : n - 2;
    *f = x_q16 - (*i << 16);
}

/* The lut correction: a' = F(a), C' = C G(a), F and G linear between knots 1/1024 apart (32 LSB of Q1.15).
 * vfi_lut_at gives F(a) (Q1.15) and G(a) (Q16.16). */
static inline uint64_t vfi_lut_at(const uint16_t *lut_f, const uint32_t *lut_g, uint32_t seg_a, uint32_t *fa)
{
    uint32_t a = seg_a > VFI_ONE_Q15 ? VFI_ONE_Q15 : seg_a;
    uint32_t k = a >> 5, f = a & 31u;
    uint32_t k1 = k < 1024 ? k + 1 : 1024;
    *fa = (lut_f[k] * (32u - f) + lut_f[k1] * f + 16u) >> 5;
    return ((uint64_t)lut_g[k] * (32u - f) + (uint64_t)lut_g[k1] * f + 16u) >> 5;
}

static inline uint32_t vfi_lut_colour(uint32_t c, uint64_t g)
{
    return (uint32_t)(((uint64_t)c * g + 0x8000u) >> 16);
}

static inline void vfi_correct(const vfi_lookup_ctx_t *c, uint32_t seg[4])
{
    uint32_t fa;
    const uint64_t g = vfi_lut_at(c->lut_f, c->lut_g, seg[3], &fa);
    for (int n = 0; n < 3; n++)
        seg[n] = vfi_lut_colour(seg[n], g);
    seg[3] = fa;
}

/* The same for a slab's entry and its front-weighted values (D_f r, g, b and S_f: all scale with the colour). */
static inline void vfi_correct_lit(const vfi_lookup_ctx_t *c, uint32_t seg[4], uint32_t lit[4])
{
    uint32_t fa;
    const uint64_t g = vfi_lut_at(c->lut_f, c->lut_g, seg[3], &fa);
    for (int n = 0; n < 3; n++)
        seg[n] = vfi_lut_colour(seg[n], g);
    for (int n = 0; n < 4; n++)
        lit[n] = vfi_lut_colour(lit[n], g);
    seg[3] = fa;
}

/* Lighting (docs/algorithm.md, section 7). A sample's or voxel's segment lit with its shade: C' = min(L_d C + L_s a,
 * a) per channel (L_d, L_s Q2.14: the sum stays below 2^32), then times the gradient factor g (Q1.15). */
static inline void vfi_light_point(uint32_t seg[4], vfi_shade_t sh)
{
    for (int n = 0; n < 3; n++) {
        const uint32_t c = (sh.d * seg[n] + sh.s * seg[3] + 0x2000u) >> 14;
        seg[n] = c < seg[3] ? c : seg[3];
    }
    if (sh.g != 32768u)
        for (int n = 0; n < 4; n++)
            seg[n] = (seg[n] * sh.g + 0x4000u) >> 15;
}

/* A slab's entry (seg) and front-weighted values (lit) lit with its front and back samples' shades:
 * C' = L_db C + (L_df - L_db) D_f + L_sb a + (L_sf - L_sb) S_f, clamped to [0, a], then times (g_f + g_b) / 2.
 * Written as L_df D_f + L_db (C - D_f) + L_sf S_f + L_sb (a - S_f): the builders keep D_f <= C and S_f <= a in
 * every format (tables.h), so every term is non-negative and the sum, at most 3 C + 2 a in Q2.14 x Q1.15, fits 32
 * bits: the same number as the first form, without a sign or a 64-bit product. */
static inline uint32_t vfi_lit_specular(uint32_t a, uint32_t s_f, vfi_shade_t f, vfi_shade_t b)
{
    return f.s * s_f + b.s * (a - s_f);
}

static inline uint32_t vfi_lit_channel(uint32_t c, uint32_t d_f, uint32_t a, uint32_t specular, vfi_shade_t f,
                                       vfi_shade_t b)
{
    const uint32_t v = (f.d * d_f + b.d * (c - d_f) + specular + 0x2000u) >> 14;
    return v < a ? v : a;
}

static inline void vfi_light_slab(uint32_t seg[4], const uint32_t lit[4], vfi_shade_t f, vfi_shade_t b)
{
    const uint32_t specular = vfi_lit_specular(seg[3], lit[3], f, b);
    for (int n = 0; n < 3; n++)
        seg[n] = vfi_lit_channel(seg[n], lit[n], seg[3], specular, f, b);
    const uint32_t g = (f.g + b.g + 1) >> 1;
    if (g != 32768u)
        for (int n = 0; n < 4; n++)
            seg[n] = (seg[n] * g + 0x4000u) >> 15;
}

/* Front to back: C += (1 - A) C_seg, A += (1 - A) a_seg. True when the pixel became opaque. */
static inline bool vfi_blend(uint16_t *px, const uint32_t seg[4])
{
    uint32_t t = VFI_ONE_Q15 - px[3];
    px[0] = (uint16_t)(px[0] + ((t * seg[0] + 0x4000u) >> 15));
    px[1] = (uint16_t)(px[1] + ((t * seg[1] + 0x4000u) >> 15));
    px[2] = (uint16_t)(px[2] + ((t * seg[2] + 0x4000u) >> 15));
    px[3] = (uint16_t)(px[3] + ((t * (seg[3] > VFI_ONE_Q15 ? VFI_ONE_Q15 : seg[3]) + 0x4000u) >> 15));
    return px[3] >= VFI_OPAQUE_Q15;
}

/* The same for a lit segment's values, each at most 1.0 (no clamp). */
static inline bool vfi_blend_rgba(uint16_t *px, uint32_t r, uint32_t g, uint32_t b, uint32_t a)
{
    uint32_t t = VFI_ONE_Q15 - px[3];
    px[0] = (uint16_t)(px[0] + ((t * r + 0x4000u) >> 15));
    px[1] = (uint16_t)(px[1] + ((t * g + 0x4000u) >> 15));
    px[2] = (uint16_t)(px[2] + ((t * b + 0x4000u) >> 15));
    px[3] = (uint16_t)(px[3] + ((t * a + 0x4000u) >> 15));
    return px[3] >= VFI_OPAQUE_Q15;
}

/* The same for an entry of a 16-bit table used as it is (the default path: no copy, no conversion). */
static inline bool vfi_blend_q15(uint16_t *px, const uint16_t *e)
{
    uint32_t t = VFI_ONE_Q15 - px[3];
    px[0] = (uint16_t)(px[0] + ((t * e[0] + 0x4000u) >> 15));
    px[1] = (uint16_t)(px[1] + ((t * e[1] + 0x4000u) >> 15));
    px[2] = (uint16_t)(px[2] + ((t * e[2] + 0x4000u) >> 15));
    px[3] = (uint16_t)(px[3] + ((t * e[3] + 0x4000u) >> 15));
    return px[3] >= VFI_OPAQUE_Q15;
}

/* vfi_blend_rgba for a grey segment (r = g = b = c): one colour product, its sum added to all three channels of the
 * pixel's word at once. Each channel's sum stays below 2^16 (at most 1.0 and a rounding), so the adds in one word
 * do not carry into each other: every channel gets the sum vfi_blend_rgba gives it, whether or not the pixel's
 * three colours are equal. */
static inline bool vfi_blend_grey(uint16_t *px, uint32_t c, uint32_t a)
{
    const uint64_t before = px[0] | (uint64_t)px[1] << 16 | (uint64_t)px[2] << 32 | (uint64_t)px[3] << 48;
    const uint32_t t = VFI_ONE_Q15 - px[3];
    const uint32_t add_c = (t * c + 0x4000u) >> 15, add_a = (t * a + 0x4000u) >> 15;
    const uint64_t after = before + (add_c * 0x10001u | (uint64_t)(add_c | add_a << 16) << 32);
    px[0] = (uint16_t)after;
    px[1] = (uint16_t)(after >> 16);
    px[2] = (uint16_t)(after >> 32);
    px[3] = (uint16_t)(after >> 48);
    return px[3] >= VFI_OPAQUE_Q15;
}

#endif
