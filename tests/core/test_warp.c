/* SPDX-License-Identifier: MIT */
/*
 * test_warp.c: the warp (core/warp.c) against its definition in integers, to the bit: every output pixel of a
 * frame is Q0.16 bilinear of the intermediate image (pixels outside it transparent, fractions kept to warp_bits),
 * rounded, put over the background, clamped and packed into the format. The specialised loops (two channels a
 * word, the fast store without a clamp, the background fill, the culling by the row extents) must give exactly
 * that, for every format, with and without a background, at 16 and fewer warp bits.
 *
 * The intermediate image of a real frame is overwritten with patterns that reach every path: transparent
 * blocks and rows (the empty test and the culling), channels of 32768 and above (the clamped path), opaque and
 * faint pixels, noise; its row extents are made again from it as compositing makes them. Grey frames (a grey
 * transfer function: the warp then sums one colour for three) are checked the same way, their patterns grey, and
 * as composited every pixel's r = g = b, which the grey warp relies on.
 */
#include <string.h>

#include "check.h"
#include "renderer.h"
#include "scene_fixture.h"

static uint64_t rng_state = 0x452821E638D01377u;
static uint8_t vox[24 * 24 * 24];
static _Alignas(16) unsigned char arena_buf[1 << 22];
static _Alignas(16) unsigned char scratch[1 << 20];
static unsigned char got[160 * 160 * 4 + 64], want[160 * 160 * 4 + 64];

static uint32_t rnd(uint32_t n)
{
    return check_below(&rng_state, n);
}

/* The definition: output pixel (x, y) of the frame as the format's bytes. */
static void spec_pixel(const vf_renderer_t *r, uint32_t x, uint32_t y, vf_format_t format, unsigned char *dst)
{
    const vf_factor_t *f = &r->factor;
    const int64_t iw = f->int_w, ih = f->int_h;
    const int64_t u = f->u0_q32 + (int64_t)x * f->du_dx_q32 + (int64_t)y * f->du_dy_q32;
    const int64_t v = f->v0_q32 + (int64_t)x * f->dv_dx_q32 + (int64_t)y * f->dv_dy_q32;
    const int64_t iu = u >> 32, iv = v >> 32; /* floors */
    const uint32_t bits = r->params.warp_bits, mask = (0xFFFFu >> (16 - bits)) << (16 - bits);
    const uint32_t fx = (uint32_t)(u >> 16) & mask, fy = (uint32_t)(v >> 16) & mask;
    const uint32_t w11 = (fx * fy + 0x8000u) >> 16;
    const uint32_t weight[4] = {65536u - fx - fy + w11, fx - w11, fy - w11, w11};
    uint64_t acc[4] = {0x8000u, 0x8000u, 0x8000u, 0x8000u};
    for (int n = 0; n < 4; n++) {
        const int64_t pu = iu + (n & 1), pv = iv + (n >> 1);
        if (pu < 0 || pv < 0 || pu >= iw || pv >= ih)
            continue;
        for (int c = 0; c < 4; c++)
            acc[c] += (uint64_t)r->intermediate[((size_t)pv * (size_t)iw + (size_t)pu) * 4 + c] * weight[n];
    }
    uint32_t px[4], c8[3];
    for (int c = 0; c < 4; c++)
        px[c] = (uint32_t)(acc[c] >> 16);
    for (int c = 0; c < 3; c++) {
        const uint32_t bg = ((uint32_t)r->params.background[c] * 32768u + 32767u) / 65535u;
        const uint32_t t = 32768u - (px[3] > 32768u ? 32768u : px[3]);
        uint32_t val = px[c] + ((t * bg + 0x4000u) >> 15);
        val = val > 32768u ? 32768u : val;
        c8[c] = val;
    }
    switch (format) {
    case VF_FORMAT_RGB888:
        for (int c = 0; c < 3; c++)
            dst[c] = (unsigned char)((c8[c] * 255u + 0x4000u) >> 15);
        break;
    case VF_FORMAT_RGB565: {
        const uint32_t word = ((c8[0] * 31u + 0x4000u) >> 15) << 11 | ((c8[1] * 63u + 0x4000u) >> 15) << 5 |
                              ((c8[2] * 31u + 0x4000u) >> 15);
        dst[0] = (unsigned char)(word & 0xFF);
        dst[1] = (unsigned char)(word >> 8);
        break;
    }
    default:
        for (int c = 0; c < 3; c++)
            dst[c] = (unsigned char)((c8[2 - c] * 255u + 0x4000u) >> 15);
        dst[3] = 0xFF;
        break;
    }
}

/* One intermediate pixel of a pattern: 0 transparent, 1 faint, 2 opaque below 32768, 3 any Q1.15 (32768 too),
 * 4 any 16-bit values (beyond what compositing writes: the clamps must hold); grey: its g and b set to its r. */
static void pattern_pixel(uint16_t *p, uint32_t kind, bool grey)
{
    switch (kind) {
    case 0:
        memset(p, 0, 8);
        break;
    case 1:
        for (int c = 0; c < 4; c++)
            p[c] = (uint16_t)rnd(64);
        break;
    case 2:
        for (int c = 0; c < 3; c++)
            p[c] = (uint16_t)rnd(32768);
        p[3] = 32768;
        break;
    case 3:
        for (int c = 0; c < 4; c++)
            p[c] = (uint16_t)(rnd(4) == 0 ? 32768 : rnd(32769));
        break;
    default:
        for (int c = 0; c < 4; c++)
            p[c] = (uint16_t)rnd(65536);
        break;
    }
    if (grey)
        p[1] = p[2] = p[0];
}

/* Overwrite the frame's intermediate image: style 0 leaves it as composited, 1 transparent blocks in noise, 2
 * one kind a row with empty rows between (and a single pixel now and then), 3 only the borders, 4 everything
 * empty but one pixel. Then the row extents as compositing makes them. */
static void repaint(vf_renderer_t *r, int style, bool grey)
{
    const uint32_t iw = r->factor.int_w, ih = r->factor.int_h;
    uint16_t *img = r->intermediate;
    if (style != 0) {
        const uint32_t bu = 1 + rnd(6), bv = 1 + rnd(6), one = rnd(iw * ih);
        for (uint32_t v = 0; v < ih; v++) {
            const uint32_t row_kind = rnd(5);
            for (uint32_t u = 0; u < iw; u++) {
                uint16_t *p = img + ((size_t)v * iw + u) * 4;
                uint32_t kind;
                if (style == 1)
                    kind = ((u / bu + v / bv) % 3 == 0) ? 0 : 1 + rnd(4);
                else if (style == 2)
                    kind = v % 3 == 1 ? 0 : rnd(8) == 0 ? 0 : row_kind;
                else if (style == 3)
                    kind = (u == 0 || v == 0 || u + 1 == iw || v + 1 == ih) ? 1 + rnd(4) : 0;
                else
                    kind = (size_t)v * iw + u == one ? 4 : 0;
                pattern_pixel(p, kind, grey);
            }
        }
    }
    for (uint32_t v = 0; v < ih; v++) {
        const uint16_t *row = img + (size_t)v * iw * 4;
        uint32_t lo = 0, hi = iw;
        while (lo < iw && !(row[lo * 4] | row[lo * 4 + 1] | row[lo * 4 + 2] | row[lo * 4 + 3]))
            lo++;
        while (hi > lo && !(row[hi * 4 - 4] | row[hi * 4 - 3] | row[hi * 4 - 2] | row[hi * 4 - 1]))
            hi--;
        if (r->row_extent) {
            r->row_extent[2 * v] = (uint16_t)(lo < hi ? lo : 0);
            r->row_extent[2 * v + 1] = (uint16_t)hi;
        }
    }
}

/* Warp the frame into an image of format (in bands of random height, with a padded stride) and compare it
 * with the definition, and the padding with what it was. */
static void warp_matches(vf_renderer_t *r, vf_format_t format, const char *what)
{
    const vf_factor_t *f = &r->factor;
    const uint32_t w = f->out_w, h = f->out_h, bpp = vf_format_bytes(format), stride = w * bpp + rnd(5);
    vf_image_t image = {got, w, h, stride, format};
    memset(got, 0xA5, sizeof got);
    for (uint32_t y = 0; y < h;) {
        const uint32_t rows = 1 + rnd(h), y1 = h - y < rows ? h : y + rows;
        CHECK_EQ(vf_renderer_warp_band(r, &image, y, y1), VF_OK);
        y = y1;
    }
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            const unsigned char *g = got + (size_t)y * stride + (size_t)x * bpp;
            spec_pixel(r, x, y, format, want);
            if (memcmp(g, want, bpp) != 0) {
                uint32_t k = 0;
                while (g[k] == want[k])
                    k++;
                check_fail(__FILE__, __LINE__,
                           "%s: format %d background (%u, %u, %u) warp_bits %u %ux%u: pixel (%u, %u) byte %u: %u, "
                           "definition %u",
                           what, (int)format, r->params.background[0], r->params.background[1],
                           r->params.background[2], r->params.warp_bits, w, h, x, y, k, g[k], want[k]);
                return;
            }
        }
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t b = w * bpp; b < stride; b++)
            CHECK_EQ(got[(size_t)y * stride + b], 0xA5);
}

/* A random frame of a ball in noise, its image repainted in style, warped in every format, with and without a
 * background, at 16 warp bits and fewer. view_kind: 0 random, 1 multiples of 90 degrees (fractions 0: taps of
 * weight 0 on the image's last row and column), 2 a zoom so small or large that the image misses most pixels or
 * each intermediate pixel covers many. grey: a grey transfer function (every point's r = g = b). */
static void frame_once(int style, int view_kind, bool grey)
{
    const uint32_t dims[3] = {2 + rnd(22), 2 + rnd(22), 2 + rnd(22)};
    vf_volume_t vol = {{dims[0], dims[1], dims[2]}, {65536, 65536, 65536}, VF_VOXEL_U8, vox};
    const scene_blob_t blob = {2, 8, 120, 0, 40, 9};
    scene_fill_blob(vox, dims, &blob, check_below, &rng_state);
    vf_tf_point_t pts[6];
    const scene_tf_style_t tf_style = {9000, 1, 4000};
    vf_tf_t tf = scene_random_tf(pts, &tf_style, check_below, &rng_state);
    for (uint32_t i = 0; i < tf.count; i++) {
        if (grey)
            pts[i].g = pts[i].b = pts[i].r;
        else if (pts[i].g == pts[i].r && pts[i].b == pts[i].r) /* a colour somewhere, so the frame is not grey */
            pts[i].g = (uint16_t)(pts[i].r >= 32768u ? pts[i].r - 16384u : pts[i].r + 16384u);
    }
    vf_params_t p;
    vf_params_default(&p);
    vf_arena_t arena;
    vf_renderer_t *r;
    if (scene_renderer(&r, &arena, arena_buf, sizeof arena_buf, &p, &vol, &tf) != VF_OK) {
        check_fail(__FILE__, __LINE__, "renderer for %ux%ux%u", dims[0], dims[1], dims[2]);
        return;
    }
    vf_view_t view = {(int32_t)rnd(65536), (int32_t)rnd(65536) - 32768, (int32_t)rnd(65536), 32768 + rnd(4 * 65536)};
    if (view_kind == 1) {
        view.azimuth = (int32_t)rnd(4) * 16384;
        view.elevation = (int32_t)rnd(4) * 16384;
        view.roll = (int32_t)rnd(4) * 16384;
    } else if (view_kind == 2) {
        view.zoom_q16 = rnd(2) ? 4096 + rnd(16384) : (8 + rnd(24)) << 16;
    }
    const uint32_t w = 1 + rnd(150), h = 1 + rnd(150);
    vf_image_t image = {got, w, h, w * 3, VF_FORMAT_RGB888};
    vf_status_t s = vf_renderer_draw(r, &view, &image, scratch, sizeof scratch);
    if (s == VF_ERR_ARG) /* more than 256 voxels a pixel (factor.c): no frame to warp */
        return;
    if (s != VF_OK) {
        check_fail(__FILE__, __LINE__, "draw: %s", vf_status_text(s));
        return;
    }
    CHECK_EQ(r->tf_grey, grey);
    if (grey) { /* what the grey warp relies on: a grey transfer function composites grey pixels */
        for (size_t n = 0; n < (size_t)r->factor.int_w * r->factor.int_h; n++)
            if (r->intermediate[n * 4 + 1] != r->intermediate[n * 4] ||
                r->intermediate[n * 4 + 2] != r->intermediate[n * 4]) {
                check_fail(__FILE__, __LINE__, "grey transfer function: intermediate pixel %zu not grey", n);
                return;
            }
    }
    repaint(r, style, grey);
    static const uint16_t backgrounds[3][3] = {{0, 0, 0}, {65535, 65535, 65535}, {1000, 40000, 65535}};
    static const uint32_t bits[3] = {16, 12, 4};
    for (int b = 0; b < 3 && !check_failed; b++)
        for (int k = 0; k < 3 && !check_failed; k++)
            for (int fmt = 0; fmt < VF_FORMAT_COUNT && !check_failed; fmt++) {
                /* background and warp bits are read by the warp alone: set here, not through a new renderer */
                memcpy(r->params.background, backgrounds[b], sizeof backgrounds[b]);
                r->params.warp_bits = bits[k];
                warp_matches(r, (vf_format_t)fmt,
                             style == 0 ? (grey ? "grey, as composited" : "as composited")
                                        : (grey ? "grey, repainted" : "repainted"));
            }
}

static void warp_matches_definition_as_composited(void)
{
    for (int t = 0; t < 30 && !check_failed; t++)
        frame_once(0, t % 3, t % 2 == 1);
}

static void warp_matches_definition_blocks_and_clamps(void)
{
    for (int t = 0; t < 30 && !check_failed; t++)
        frame_once(1, t % 3, t % 2 == 1);
}

static void warp_matches_definition_empty_rows(void)
{
    for (int t = 0; t < 30 && !check_failed; t++)
        frame_once(2, t % 3, t % 2 == 1);
}

static void warp_matches_definition_borders_and_one_pixel(void)
{
    for (int t = 0; t < 40 && !check_failed; t++)
        frame_once(3 + t % 2, t % 3, t % 4 >= 2);
}

CHECK_CASES(CHECK_CASE(warp_matches_definition_as_composited), CHECK_CASE(warp_matches_definition_blocks_and_clamps),
            CHECK_CASE(warp_matches_definition_empty_rows), CHECK_CASE(warp_matches_definition_borders_and_one_pixel));
CHECK_RUN("core/warp")
