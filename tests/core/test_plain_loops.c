/* SPDX-License-Identifier: MIT */
/*
 * test_plain_loops.c: the plain compositing loops (core/composite_order0.c, composite_order1.c: the fast paths of
 * point and preint1, unlit and lit) against the general loops, which every option takes: the same intermediate
 * image, to the bit, over modes, table sizes (256 and not), buffers, nearest and bilinear shades, grey and coloured
 * transfer functions, random volumes, views and lights; and the pieces of the grey and column-wise loops against
 * what they stand for: vfi_blend_grey against vfi_blend_rgba, vfi_sampler_entry against vfi_entry_rows.
 */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "composite.h"
#include "scene_fixture.h"
#include "volfix.h"
#include "volfix_internal.h"

#define MAXD 24
static uint8_t vox[MAXD * MAXD * MAXD];
static _Alignas(16) unsigned char arena_buf[2][1 << 23];
static _Alignas(16) unsigned char scratch[1 << 21];
static unsigned char pixels[96 * 96 * 3];
static uint64_t seed = 0x9E3779B97F4A7C15u;

static void random_volume(uint32_t n[3])
{
    for (int a = 0; a < 3; a++)
        n[a] = 6 + check_below(&seed, MAXD - 6);
    static const scene_blob_t blob = {.rad_min = 3, .rad_span = 6, .inside = 170, .outside = 20, .noise = 60,
                                      .salt = 10};
    scene_fill_blob(vox, n, &blob, check_below, &seed);
}

static vf_tf_point_t points[6];

static vf_tf_t random_tf(bool grey)
{
    uint32_t count = 2 + check_below(&seed, 4), s = check_below(&seed, 20000);
    for (uint32_t p = 0; p < count; p++) {
        s += p ? check_below(&seed, 16000) : 0;
        const uint16_t r = (uint16_t)check_below(&seed, 65536);
        points[p] = (vf_tf_point_t){(uint16_t)(s > 65280 ? 65280 : s), r, grey ? r : (uint16_t)check_below(&seed, 65536),
                                    grey ? r : (uint16_t)check_below(&seed, 65536), (uint16_t)check_below(&seed, 40000)};
    }
    return (vf_tf_t){points, count};
}

/* The frame's intermediate image with the plain loops (general false) or the general ones, into inter. */
static vf_status_t frame(int k, const vf_params_t *p, const vf_volume_t *vol, const vf_tf_t *tf,
                         const vf_lighting_t *l, const vf_view_t *view, bool general, uint16_t **inter, size_t *values)
{
    vf_arena_t arena;
    vf_renderer_t *r;
    vf_status_t s = scene_renderer(&r, &arena, arena_buf[k], sizeof arena_buf[k], p, vol, tf);
    if (s == VF_OK && p->lighting)
        s = vf_renderer_set_lighting(r, l);
    vfi_renderer_general_loops(r, general);
    const vf_image_t im = {pixels, 96, 96, 96 * 3, VF_FORMAT_RGB888};
    if (s == VF_OK)
        s = vf_renderer_draw(r, view, &im, scratch, sizeof scratch);
    if (s == VF_OK) {
        const vf_factor_t *f = vf_renderer_factor(r);
        *values = (size_t)f->int_w * f->int_h * 4;
        *inter = (uint16_t *)vfi_renderer_intermediate(r);
    }
    return s;
}

static void plain_equals_general(void)
{
    int compared = 0;
    for (int t = 0; t < 160; t++) {
        uint32_t n[3];
        random_volume(n);
        const vf_volume_t vol = {{n[0], n[1], n[2]}, {65536, 65536 + 65536 * (t % 3 == 0), 65536}, VF_VOXEL_U8, vox};
        vf_params_t p;
        vf_params_default(&p);
        const vf_mode_t modes[] = {VF_MODE_POINT, VF_MODE_PREINT1, VF_MODE_PRECLASS};
        p.mode = modes[t % 3];
        p.table_size = t % 4 == 1 ? 64 + check_below(&seed, 100) : 256;
        p.buffer = t % 5 == 2 ? VF_BUFFER_IMAGE : VF_BUFFER_SLICE;
        p.lighting = t % 2 == 0;
        p.shade_lookup = t % 4 < 2 ? VF_LOOKUP_NEAREST : VF_LOOKUP_BILINEAR;
        p.normal_bits = 8 + 2 * check_below(&seed, 5);
        const vf_tf_t tf = random_tf((t / 3) % 3 != 1); /* grey and coloured in every mode */
        vf_lighting_t l;
        vf_lighting_default(&l);
        l.light_count = 1 + check_below(&seed, 2);
        for (uint32_t k = 0; k < l.light_count; k++)
            l.lights[k] = (vf_light_t){(int32_t)check_below(&seed, 65536), (int32_t)check_below(&seed, 32768) - 16384};
        l.ks = (uint16_t)check_below(&seed, 65536);
        if (t % 7 == 3) /* gradient opacity: the general loops in both, still checked */
            l.gradient_lo = 5, l.gradient_hi = 90;
        const vf_view_t view = {(int32_t)check_below(&seed, 65536), (int32_t)check_below(&seed, 65536) - 32768,
                                (int32_t)check_below(&seed, 65536), 65536};
        uint16_t *plain, *general;
        size_t values, values2;
        CHECK_EQ(frame(0, &p, &vol, &tf, &l, &view, false, &plain, &values), VF_OK);
        CHECK_EQ(frame(1, &p, &vol, &tf, &l, &view, true, &general, &values2), VF_OK);
        CHECK_EQ(values, values2);
        size_t diff = 0;
        while (diff < values && plain[diff] == general[diff])
            diff++;
        CHECK_MSG(diff == values, "case %d (mode %s, %u entries, %s buffer, lighting %d, %s shades): value %zu, plain %u "
                  "general %u", t, vf_mode_name(p.mode), p.table_size, vf_buffer_name(p.buffer), (int)p.lighting,
                  vf_lookup_name(p.shade_lookup), diff, plain[diff], general[diff]);
        compared++;
    }
    CHECK_EQ(compared, 160);
}

/* A pixel front to back through a run of segments: vfi_blend_grey against vfi_blend_rgba with r = g = b, the four
 * channels to the bit and the opaque answers, from grey pixels and from pixels whose colours differ (the blend adds
 * the same sum to each whatever they hold), with colours up to alpha and a rounding above it and segments at the
 * ends of the range. */
static void blend_grey_equals_rgba(void)
{
    int blends = 0;
    for (int t = 0; t < 4000; t++) {
        uint16_t a[4], b[4];
        const uint32_t a0 = check_below(&seed, 32769);
        a[3] = (uint16_t)a0;
        for (int c = 0; c < 3; c++)
            a[c] = (uint16_t)(t % 2 ? a0 : check_below(&seed, a0 + 1)); /* odd: grey; even: the colours differ */
        memcpy(b, a, sizeof a);
        for (int k = 0; k < 40; k++) {
            const uint32_t kind = check_below(&seed, 8);
            const uint32_t alpha = kind == 0 ? 0 : kind == 1 ? 32768 : check_below(&seed, 32769);
            uint32_t colour = kind == 2 ? alpha : check_below(&seed, alpha + 1);
            if (kind == 3 && colour < 32768)
                colour++; /* a rounding above alpha */
            const bool ga = vfi_blend_grey(a, colour, alpha), gb = vfi_blend_rgba(b, colour, colour, colour, alpha);
            CHECK_MSG(ga == gb && !memcmp(a, b, sizeof a), "case %d, segment %d (c %u, a %u): grey %u %u %u %u, rgba %u %u "
                      "%u %u", t, k, colour, alpha, a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]);
            blends++;
        }
    }
    CHECK_EQ(blends, 160000);
}

/* Samples along a row by columns, pixels in runs with gaps (the left column taken over or worked out), against the
 * lerps across then down, for both roundings (a 256-entry table's folded bias, and n entries), with fractions and
 * voxels at their ends. */
static void sampler_equals_rows(void)
{
    enum { COLS = 64 };
    uint8_t rows[2 * (COLS + 1)];
    int samples = 0;
    for (int t = 0; t < 2000; t++) {
        for (int i = 0; i < 2 * (COLS + 1); i++)
            rows[i] = (uint8_t)(t % 5 == 0 ? 255 * check_below(&seed, 2) : check_below(&seed, 256));
        const uint32_t ends[] = {0, 1, 32768, 65535};
        const uint32_t fx = t % 3 ? check_below(&seed, 65536) : ends[check_below(&seed, 4)];
        const uint32_t fy = t % 4 ? check_below(&seed, 65536) : ends[check_below(&seed, 4)];
        const bool n256 = t % 2 == 0;
        const uint32_t n = n256 ? 256 : 2 + check_below(&seed, 1023);
        vfi_row_sampler_t smp;
        vfi_sampler_init(&smp, rows, COLS + 1, fx, fy, n256);
        for (uint32_t c = check_below(&seed, 4); c < COLS; c += 1 + (check_below(&seed, 4) == 0) * check_below(&seed, 5)) {
            const uint32_t got = vfi_sampler_entry(&smp, c, n, n256);
            const uint32_t want = vfi_entry_rows(rows + c, rows + COLS + 1 + c, fx, fy, n, n256);
            CHECK_MSG(got == want, "case %d, column %u (fx %u, fy %u, n %u): %u, the rows' lerps %u", t, c, fx, fy, n, got,
                      want);
            samples++;
        }
    }
    CHECK(samples > 40000);
}

CHECK_CASES({"plain loops equal the general ones", plain_equals_general},
            {"the grey blend equals the four-channel one", blend_grey_equals_rgba},
            {"samples by columns equal the rows' lerps", sampler_equals_rows});
CHECK_RUN("plain-loops")
