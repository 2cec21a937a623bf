/* SPDX-License-Identifier: MIT */
/*
 * warp_rows.c: the warp's loops over a row of output pixels (warp.c finds each row's spans): the bilinear sums two
 * channels a word, the store into each output format, the background fills, the pixels near the intermediate
 * image's edges.
 */
#include "warp_rows.h"

/* A transparent pixel (Q1.15 r, g, b, a). Constant and file-wide because a local {0} array may compile to a
 * memset call (gcc -Os for Cortex-M4 does), and the core calls nothing outside itself. */
static const uint32_t transparent[4] = {0, 0, 0, 0};

static void store_pixel(const vfi_warp_row_t *w, unsigned char *dst, const uint32_t px[4]);

/* An intermediate pixel's four Q1.15 channels as one word: r in bits 0-15, g 16-31, b 32-47, a 48-63, one load
 * where the byte order allows (the image is 16-byte aligned, a pixel 8 bytes). */
static VF_ALWAYS_INLINE uint64_t load_pixel(const uint16_t *p)
{
#if defined(__GNUC__) && defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    typedef uint64_t __attribute__((__may_alias__)) pixel_word_t; /* read as a word what compositing wrote as halves */
    return *(const pixel_word_t *)(const void *)p;
#else
    return p[0] | (uint64_t)p[1] << 16 | (uint64_t)p[2] << 32 | (uint64_t)p[3] << 48;
#endif
}

/* The pixel px (Q1.15 r, g, b, a) as the format's bytes, the background behind it when there is one: store_pixel
 * with the format and the background constants, for the inner loop's specialisations. */
static VF_ALWAYS_INLINE void store_as(const vfi_warp_row_t *w, unsigned char *dst, const uint32_t px[4],
                                      vf_format_t format, bool have_bg)
{
    uint32_t c[3] = {px[0], px[1], px[2]};
    if (have_bg) {
        const uint32_t t = VFI_ONE_Q15 - (px[3] > VFI_ONE_Q15 ? VFI_ONE_Q15 : px[3]);
        c[0] += (t * w->bg[0] + 0x4000u) >> 15;
        c[1] += (t * w->bg[1] + 0x4000u) >> 15;
        c[2] += (t * w->bg[2] + 0x4000u) >> 15;
    }
    c[0] = c[0] > VFI_ONE_Q15 ? VFI_ONE_Q15 : c[0];
    c[1] = c[1] > VFI_ONE_Q15 ? VFI_ONE_Q15 : c[1];
    c[2] = c[2] > VFI_ONE_Q15 ? VFI_ONE_Q15 : c[2];
    switch (format) {
    case VF_FORMAT_RGB888:
        dst[0] = (unsigned char)((c[0] * 255u + 0x4000u) >> 15);
        dst[1] = (unsigned char)((c[1] * 255u + 0x4000u) >> 15);
        dst[2] = (unsigned char)((c[2] * 255u + 0x4000u) >> 15);
        break;
    case VF_FORMAT_RGB565: {
        uint32_t word = ((c[0] * 31u + 0x4000u) >> 15) << 11 | ((c[1] * 63u + 0x4000u) >> 15) << 5 |
                        ((c[2] * 31u + 0x4000u) >> 15);
        dst[0] = (unsigned char)(word & 0xFFu);
        dst[1] = (unsigned char)(word >> 8);
        break;
    }
    default: /* VF_FORMAT_XRGB8888: bytes B, G, R, X */
        dst[0] = (unsigned char)((c[2] * 255u + 0x4000u) >> 15);
        dst[1] = (unsigned char)((c[1] * 255u + 0x4000u) >> 15);
        dst[2] = (unsigned char)((c[0] * 255u + 0x4000u) >> 15);
        dst[3] = 0xFFu;
        break;
    }
}

/* vf_format_bytes where the format is a constant, so that a specialised loop's byte counts are too. */
static VF_ALWAYS_INLINE uint32_t format_bytes(vf_format_t format)
{
    return format == VF_FORMAT_RGB888 ? 3u : format == VF_FORMAT_RGB565 ? 2u : 4u;
}

/* The bilinear sums take two channels a word, in 32-bit lanes: r and b where a pixel word has them, g (and a)
 * shifted down, or g alone left where it is (g 2^16, a word of its own). A lane's four products sum to at most
 * 65535 x 65536 (the weights sum to 65536) and its rounding half on top stays below 2^32: no lane carries into
 * the next, and every sum is the one the four products of a channel give alone. */
#define LANES_RB UINT64_C(0x0000FFFF0000FFFF)
#define LANE_G UINT64_C(0x00000000FFFF0000)
#define HALF_Q16 UINT64_C(0x0000800000008000) /* 0.5 in Q0.16 in each lane */
#define HALF_Q15 UINT64_C(0x0000400000004000) /* 0.5 in Q0.15 in each lane */
#define TOP_RGB UINT64_C(0x0000800080008000)  /* r, g and b of 32768 and above */

/* A pixel's r, b (lanes of rb, Q1.15) and g, each below 32768, as the format's bytes over no background: what
 * store_as gives them (no clamp can act), with r and b converted side by side in their lanes. */
static VF_ALWAYS_INLINE void store_fast(unsigned char *dst, uint64_t rb, uint32_t g, vf_format_t format)
{
    switch (format) {
    case VF_FORMAT_RGB888: {
        const uint64_t o = (rb * 255u + HALF_Q15) >> 15; /* r in bits 0-7, b in 32-39, bits 8-16 clear */
        dst[0] = (unsigned char)o;
        dst[1] = (unsigned char)((g * 255u + 0x4000u) >> 15);
        dst[2] = (unsigned char)(o >> 32);
        break;
    }
    case VF_FORMAT_RGB565: {
        const uint64_t o = (rb * 31u + HALF_Q15) >> 15; /* r in bits 0-4, b in 32-36, bits 5-16 clear */
        const uint32_t word = ((uint32_t)o & 0x1Fu) << 11 | ((g * 63u + 0x4000u) >> 15) << 5 | (uint32_t)(o >> 32);
        dst[0] = (unsigned char)(word & 0xFFu);
        dst[1] = (unsigned char)(word >> 8);
        break;
    }
    default: { /* VF_FORMAT_XRGB8888: bytes B, G, R, X */
        const uint64_t o = (rb * 255u + HALF_Q15) >> 15;
        dst[0] = (unsigned char)(o >> 32);
        dst[1] = (unsigned char)((g * 255u + 0x4000u) >> 15);
        dst[2] = (unsigned char)o;
        dst[3] = 0xFFu;
        break;
    }
    }
}

/* A grey pixel's colour c (its r = g = b, Q1.15, below 32768) as the format's bytes over no background: store_fast
 * with one conversion for three channels (rgb565's r and b share one too). */
static VF_ALWAYS_INLINE void store_grey(unsigned char *dst, uint32_t c, vf_format_t format)
{
    switch (format) {
    case VF_FORMAT_RGB888: {
        const unsigned char o = (unsigned char)((c * 255u + 0x4000u) >> 15);
        dst[0] = o, dst[1] = o, dst[2] = o;
        break;
    }
    case VF_FORMAT_RGB565: {
        const uint32_t rb = (c * 31u + 0x4000u) >> 15, word = rb << 11 | ((c * 63u + 0x4000u) >> 15) << 5 | rb;
        dst[0] = (unsigned char)(word & 0xFFu);
        dst[1] = (unsigned char)(word >> 8);
        break;
    }
    default: { /* VF_FORMAT_XRGB8888: bytes B, G, R, X */
        const unsigned char o = (unsigned char)((c * 255u + 0x4000u) >> 15);
        dst[0] = o, dst[1] = o, dst[2] = o, dst[3] = 0xFFu;
        break;
    }
    }
}

/* Bilinear of the pixel words t00, t10 (right), t01 (below), t11 with Q0.16 fractions fx, fy: px, Q1.15 r, g, b, a,
 * each channel's sum rounded once. */
static void bilinear(uint64_t t00, uint64_t t10, uint64_t t01, uint64_t t11, uint32_t fx, uint32_t fy, uint32_t px[4])
{
    const uint32_t w11 = (fx * fy + 0x8000u) >> 16;
    const uint32_t w00 = 65536u - fx - fy + w11, w10 = fx - w11, w01 = fy - w11;
    const uint64_t rb = (t00 & LANES_RB) * w00 + (t10 & LANES_RB) * w10 + (t01 & LANES_RB) * w01 +
                        (t11 & LANES_RB) * w11 + HALF_Q16;
    const uint64_t ga = (t00 >> 16 & LANES_RB) * w00 + (t10 >> 16 & LANES_RB) * w10 + (t01 >> 16 & LANES_RB) * w01 +
                        (t11 >> 16 & LANES_RB) * w11 + HALF_Q16;
    px[0] = (uint32_t)(rb >> 16) & 0xFFFFu;
    px[1] = (uint32_t)(ga >> 16) & 0xFFFFu;
    px[2] = (uint32_t)(rb >> 48);
    px[3] = (uint32_t)(ga >> 48);
}

/* count pixels from dst, each with all four neighbours inside the image (u, v >= 0: the shifts are floors), the
 * first at (u, v), then a step of (du, dv) a pixel; the format and background constants, whether the weights
 * keep all 16 fraction bits, and whether the image is grey (every pixel's r = g = b: then the fast path sums r
 * alone, in 32 bits, and stores it for all three) (vfi_warp_inner). */
static VF_ALWAYS_INLINE void inner_body(const vfi_warp_row_t *w, const uint16_t *img, int64_t iw, int64_t u, int64_t v,
                                        int64_t du, int64_t dv, unsigned char *dst, uint32_t count,
                                        const unsigned char *background, vf_format_t format, bool have_bg,
                                        bool full_bits, bool grey)
{
    const uint32_t bpp = format_bytes(format), mask = full_bits ? 0xFFFFu : w->fraction_mask;
    unsigned char bytes[4]; /* the background, a copy the stores cannot alias */
    for (uint32_t k = 0; k < bpp; k++)
        bytes[k] = background[k];
    for (uint32_t x = 0; x < count; x++, u += du, v += dv, dst += bpp) {
        const uint16_t *p00 = img + ((size_t)(v >> 32) * (size_t)iw + (size_t)(u >> 32)) * 4;
        const uint16_t *p01 = p00 + iw * 4;
        const uint64_t t00 = load_pixel(p00), t10 = load_pixel(p00 + 4), t01 = load_pixel(p01),
                       t11 = load_pixel(p01 + 4);
        const uint64_t any = t00 | t10 | t01 | t11;
        if (any == 0) { /* all four transparent black: exactly what the weights would give, the background */
            for (uint32_t k = 0; k < bpp; k++)
                dst[k] = bytes[k];
            continue;
        }
        const uint32_t fx = (uint32_t)(u >> 16) & mask, fy = (uint32_t)(v >> 16) & mask;
        if (VF_SPECIAL_LOOPS && !have_bg && !(any & TOP_RGB)) {
            /* Every tap's r, g, b is below 32768, so each sum, a rounded convex combination, is too: bilinear's
             * sums without a, and the fast store. */
            const uint32_t w11 = (fx * fy + 0x8000u) >> 16;
            const uint32_t w00 = 65536u - fx - fy + w11, w10 = fx - w11, w01 = fy - w11;
            if (grey) { /* r's sum, the others' too: four products below 2^31 in all and the rounding half */
                store_grey(dst,
                           ((uint32_t)(uint16_t)t00 * w00 + (uint32_t)(uint16_t)t10 * w10 +
                            (uint32_t)(uint16_t)t01 * w01 + (uint32_t)(uint16_t)t11 * w11 + 0x8000u) >> 16,
                           format);
                continue;
            }
            const uint64_t g = (t00 & LANE_G) * w00 + (t10 & LANE_G) * w10 + (t01 & LANE_G) * w01 +
                               (t11 & LANE_G) * w11 + (UINT64_C(0x8000) << 16);
            const uint64_t rb = (t00 & LANES_RB) * w00 + (t10 & LANES_RB) * w10 + (t01 & LANES_RB) * w01 +
                                (t11 & LANES_RB) * w11 + HALF_Q16;
            store_fast(dst, (rb >> 16) & LANES_RB, (uint32_t)(g >> 32), format);
            continue;
        }
        uint32_t px[4];
        bilinear(t00, t10, t01, t11, fx, fy, px);
        store_as(w, dst, px, format, have_bg);
    }
}

/* inner_body for any format, background and fraction bits */
static void inner_general(const vfi_warp_row_t *w, const uint16_t *img, int64_t iw, int64_t u, int64_t v, int64_t du,
                          int64_t dv, unsigned char *dst, uint32_t count, const unsigned char *background)
{
    inner_body(w, img, iw, u, v, du, dv, dst, count, background, w->format, w->have_bg, false, false);
}

/* inner_body for the row's format and background, and over no background whether the image is grey: a loop for
 * each with VF_SPECIAL_LOOPS and Q0.16 weights (the default), else one that asks */
void vfi_warp_inner(const vfi_warp_row_t *w, const uint16_t *img, int64_t iw, int64_t u, int64_t v, int64_t du,
                    int64_t dv, unsigned char *dst, uint32_t count, const unsigned char *background)
{
    if (!VF_SPECIAL_LOOPS || w->fraction_mask != 0xFFFFu) {
        inner_general(w, img, iw, u, v, du, dv, dst, count, background);
        return;
    }
    switch (w->format) {
    case VF_FORMAT_RGB888:
        if (w->have_bg)
            inner_body(w, img, iw, u, v, du, dv, dst, count, background, VF_FORMAT_RGB888, true, true, false);
        else if (w->grey)
            inner_body(w, img, iw, u, v, du, dv, dst, count, background, VF_FORMAT_RGB888, false, true, true);
        else
            inner_body(w, img, iw, u, v, du, dv, dst, count, background, VF_FORMAT_RGB888, false, true, false);
        break;
    case VF_FORMAT_RGB565:
        if (w->have_bg)
            inner_body(w, img, iw, u, v, du, dv, dst, count, background, VF_FORMAT_RGB565, true, true, false);
        else if (w->grey)
            inner_body(w, img, iw, u, v, du, dv, dst, count, background, VF_FORMAT_RGB565, false, true, true);
        else
            inner_body(w, img, iw, u, v, du, dv, dst, count, background, VF_FORMAT_RGB565, false, true, false);
        break;
    default:
        if (w->have_bg)
            inner_body(w, img, iw, u, v, du, dv, dst, count, background, VF_FORMAT_XRGB8888, true, true, false);
        else if (w->grey)
            inner_body(w, img, iw, u, v, du, dv, dst, count, background, VF_FORMAT_XRGB8888, false, true, true);
        else
            inner_body(w, img, iw, u, v, du, dv, dst, count, background, VF_FORMAT_XRGB8888, false, true, false);
        break;
    }
}

/* count pixels of the background from dst, a loop for each format: 24 bytes (8, 12 or 6 pixels) a step as three
 * words where the compiler can be told the words may be unaligned and alias the bytes (VF_SPECIAL_LOOPS), then the
 * rest byte by byte. */
static VF_ALWAYS_INLINE void fill_as(unsigned char *dst, uint32_t count, const unsigned char *background,
                                     vf_format_t format)
{
    const uint32_t bpp = format_bytes(format);
    unsigned char bytes[4]; /* a copy the stores cannot alias, kept in registers */
    for (uint32_t k = 0; k < bpp; k++)
        bytes[k] = background[k];
    uint32_t x = 0;
#if defined(__GNUC__) && VF_SPECIAL_LOOPS
    typedef uint64_t __attribute__((__may_alias__, __aligned__(1))) byte_word_t;
    const uint32_t step = 24 / bpp;
    if (count >= step) {
        unsigned char pattern[24];
        for (uint32_t k = 0; k < 24; k++)
            pattern[k] = bytes[k % bpp];
        const uint64_t w0 = *(const byte_word_t *)(const void *)pattern,
                       w1 = *(const byte_word_t *)(const void *)(pattern + 8),
                       w2 = *(const byte_word_t *)(const void *)(pattern + 16);
        for (; x + step <= count; x += step, dst += 24) {
            *(byte_word_t *)(void *)dst = w0;
            *(byte_word_t *)(void *)(dst + 8) = w1;
            *(byte_word_t *)(void *)(dst + 16) = w2;
        }
    }
#endif
    for (; x < count; x++, dst += bpp)
        for (uint32_t k = 0; k < bpp; k++)
            dst[k] = bytes[k];
}

void vfi_warp_fill(unsigned char *dst, uint32_t count, const unsigned char *background, vf_format_t format)
{
    switch (format) {
    case VF_FORMAT_RGB888:
        fill_as(dst, count, background, VF_FORMAT_RGB888);
        break;
    case VF_FORMAT_RGB565:
        fill_as(dst, count, background, VF_FORMAT_RGB565);
        break;
    default:
        fill_as(dst, count, background, VF_FORMAT_XRGB8888);
        break;
    }
}

/* Bilinear, with pixels outside the intermediate image transparent (for the pixels near its edges). */
void vfi_warp_edge(const vfi_warp_row_t *w, int64_t u_q32, int64_t v_q32, unsigned char *dst)
{
    const vf_renderer_t *r = w->r;
    const int64_t iw = r->factor.int_w, ih = r->factor.int_h;
    /* Shifted by one pixel, the support (-1, w) x (-1, h) is positive, and shifts act as floor. */
    int64_t us = u_q32 + VFI_ONE_Q32, vs = v_q32 + VFI_ONE_Q32;
    if (!(us > 0 && vs > 0 && us < (iw + 1) * VFI_ONE_Q32 && vs < (ih + 1) * VFI_ONE_Q32)) {
        store_pixel(w, dst, transparent);
        return;
    }
    const int64_t iu = (us >> 32) - 1, iv = (vs >> 32) - 1;
    const uint32_t fx = (uint32_t)(us >> 16) & w->fraction_mask, fy = (uint32_t)(vs >> 16) & w->fraction_mask;
    uint64_t t[4];
    for (int n = 0; n < 4; n++) {
        const int64_t pu = iu + (n & 1), pv = iv + (n >> 1);
        t[n] = pu < 0 || pv < 0 || pu >= iw || pv >= ih ? 0 : load_pixel(r->intermediate + (pv * iw + pu) * 4);
    }
    uint32_t px[4];
    bilinear(t[0], t[1], t[2], t[3], fx, fy, px);
    store_pixel(w, dst, px);
}

/* C + (1 - A) background, packed: store_as for any format, outside the inner loop. */
static void store_pixel(const vfi_warp_row_t *w, unsigned char *dst, const uint32_t px[4])
{
    store_as(w, dst, px, w->format, w->have_bg);
}

void vfi_warp_background(const vfi_warp_row_t *w, unsigned char *dst)
{
    store_pixel(w, dst, transparent);
}
