/* SPDX-License-Identifier: MIT */
/*
 * test_table_demand.c: a frame composited on one thread whose 2D table is built as compositing reads it
 * (vf_frame_t.one_thread; core/preint.c, composite_order1.c): its intermediate image and picture equal
 * vf_render's to the bit, for table sizes from the smallest to the largest, the 10-, 12- and 16-bit formats, both
 * buffers, bands one after another, views with the same slab length (the table kept, more diagonals built) and a
 * transfer function changed between frames; the table is not handed out while diagonals are unbuilt, and a frame
 * begun for threads afterwards builds it whole; the options it does not cover build the whole table.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "frame.h"
#include "volfix.h"
#include "volfix_internal.h"

#define W 31
#define H 27
#define NI 12
#define NJ 11
#define NK 10

static uint64_t rng_state = 0x2545F4914F6CDD1Du;
static uint32_t rnd(uint32_t n)
{
    return check_below(&rng_state, n);
}

static uint8_t vox[NI * NJ * NK];
static _Alignas(16) unsigned char arena_want[1 << 24], arena_got[1 << 24];
static _Alignas(16) unsigned char scratch[1 << 18];
static unsigned char want_px[W * H * 3], got_px[W * H * 3];
static uint16_t want_inter[1 << 16], want_table[1024 * 1024 * 4];

static const vf_view_t views[] = {
    {9000, 4000, 0, 65536}, {9000, 4000, 0, 65536}, /* the same view: the table kept */
    {-9000, 4000, 0, 65536},                        /* mirrored: the same slab length, other entries read */
    {-3000, 12000, 700, 65536}, {20000, -7000, 300, 80000}, {300, 200, 0, 65536},
};

/* Noise over a ramp (samples far apart across a slab, so that long diagonals are read), or the ramp alone. */
static void fill_volume(bool noisy)
{
    for (size_t i = 0; i < sizeof vox; i++) {
        const size_t x = i % NI, y = i / NI % NJ, z = i / (NI * NJ);
        vox[i] = (uint8_t)(noisy && rnd(3) == 0 ? rnd(256) : 40 + x * 6 + y * 5 + z * 4);
    }
}

static vf_status_t create(vf_renderer_t **r, vf_arena_t *arena, unsigned char *buf, const vf_params_t *p,
                          const vf_volume_t *vol, const vf_tf_t *tf)
{
    *r = NULL;
    vf_arena_init(arena, buf, 1 << 24);
    vf_status_t st = vf_renderer_create(r, p, vol, arena);
    if (st == VF_OK)
        st = vf_renderer_set_window(*r, (vf_window_t){0, 255});
    return st == VF_OK ? vf_renderer_set_tf(*r, tf) : st;
}

/* The frame begun, composited in `bands` bands one after another, then warped. */
static vf_status_t finish(vf_renderer_t *r, unsigned char *px, uint32_t bands)
{
    const uint32_t h = vf_renderer_factor(r)->int_h;
    for (uint32_t b = 0; b < bands; b++) {
        const uint32_t v0 = h * b / bands, v1 = h * (b + 1) / bands;
        if (v0 == v1)
            continue;
        vf_status_t st = vf_renderer_composite_band(r, v0, v1, scratch, vf_renderer_band_scratch_bytes(r, v1 - v0));
        if (st != VF_OK)
            return st;
    }
    vf_image_t im = {px, W, H, W * 3, VF_FORMAT_RGB888};
    return vf_renderer_warp_band(r, &im, 0, H);
}

static size_t inter_values(const vf_renderer_t *r)
{
    const vf_factor_t *f = vf_renderer_factor(r);
    return (size_t)f->int_w * f->int_h * 4;
}

/* vf_render's frames against the same frames begun on one thread, view after view, with a new transfer function
 * half way: the intermediate image (Q1.15) and the picture to the bit. */
static void demand_equals_whole(void)
{
    static const struct {
        uint32_t size, bits;
        vf_buffer_t buffer;
        uint32_t bands;
    } cases[] = {{2, 16, VF_BUFFER_SLICE, 1},   {7, 16, VF_BUFFER_IMAGE, 1}, {64, 16, VF_BUFFER_SLICE, 3},
                 {255, 16, VF_BUFFER_IMAGE, 1}, {256, 16, VF_BUFFER_SLICE, 1}, {256, 16, VF_BUFFER_IMAGE, 4},
                 {256, 12, VF_BUFFER_SLICE, 1}, {256, 10, VF_BUFFER_IMAGE, 2}, {1000, 16, VF_BUFFER_SLICE, 1},
                 {1024, 16, VF_BUFFER_IMAGE, 1}};
    fill_volume(true);
    const vf_volume_t vol = {{NI, NJ, NK}, {65536, 65536, 65536}, VF_VOXEL_U8, vox};
    vf_tf_point_t pts[2][3] = {
        {{0, 65535, 20000, 0, 0}, {100 * 256, 0, 65535, 30000, 30000}, {255 * 256, 65535, 0, 65535, 9000}},
        {{0, 0, 0, 0, 0}, {150 * 256, 65535, 65535, 65535, 50000}, {255 * 256, 0, 9000, 65535, 0}}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        vf_params_t p;
        vf_params_default(&p);
        p.mode = VF_MODE_PREINT1;
        p.table_size = cases[c].size;
        p.table_bits = cases[c].bits;
        p.buffer = cases[c].buffer;
        vf_tf_t tf = {pts[0], 3};
        vf_arena_t aw, ag;
        vf_renderer_t *want, *got;
        CHECK_EQ(create(&want, &aw, arena_want, &p, &vol, &tf), VF_OK);
        CHECK_EQ(create(&got, &ag, arena_got, &p, &vol, &tf), VF_OK);
        for (size_t v = 0; v < sizeof views / sizeof views[0]; v++) {
            if (v == 4) { /* a new transfer function: the tables of both go stale */
                tf.points = pts[1];
                CHECK_EQ(vf_renderer_set_tf(want, &tf), VF_OK);
                CHECK_EQ(vf_renderer_set_tf(got, &tf), VF_OK);
            }
            vf_image_t im = {want_px, W, H, W * 3, VF_FORMAT_RGB888};
            CHECK_EQ(vf_renderer_draw(want, &views[v], &im, scratch, vf_renderer_band_scratch_bytes(want, H * 4)), VF_OK);
            memcpy(want_inter, vfi_renderer_intermediate(want), inter_values(want) * sizeof want_inter[0]);
            CHECK_EQ(begin_frame(got, &views[v], W, H, 0, true), VF_OK);
            memset(got_px, 0, sizeof got_px);
            CHECK_EQ(finish(got, got_px, cases[c].bands), VF_OK);
            CHECK_EQ(inter_values(got), inter_values(want));
            CHECK_MSG(memcmp(want_inter, vfi_renderer_intermediate(got), inter_values(got) * sizeof want_inter[0]) == 0,
                      "table %u x %u bits, view %zu: intermediate images differ", cases[c].size, cases[c].bits, v);
            CHECK_MSG(memcmp(want_px, got_px, sizeof got_px) == 0, "table %u x %u bits, view %zu: pictures differ",
                      cases[c].size, cases[c].bits, v);
        }
        /* a frame begun for threads after one built as read: the whole table, vf_render's */
        const size_t entries = (size_t)cases[c].size * cases[c].size * 4;
        memcpy(want_table, vfi_renderer_preint_table(want), entries * sizeof want_table[0]);
        CHECK_EQ(begin_frame(got, &views[5], W, H, 1, false), VF_OK);
        const uint16_t *table = vfi_renderer_preint_table(got);
        CHECK(table != NULL);
        if (table)
            CHECK_MSG(memcmp(want_table, table, entries * sizeof *table) == 0, "table %u: whole table differs",
                      cases[c].size);
    }
}

/* A smooth volume reads only diagonals near the middle of a 256-entry table: the table is not handed out while the
 * others are unbuilt; a frame not on one thread then builds it whole, and the next frame on one thread keeps it whole. */
static void demand_table_state(void)
{
    fill_volume(false);
    const vf_volume_t vol = {{NI, NJ, NK}, {65536, 65536, 65536}, VF_VOXEL_U8, vox};
    vf_tf_point_t pts[2] = {{0, 65535, 65535, 65535, 0}, {255 * 256, 65535, 30000, 0, 65535}};
    vf_tf_t tf = {pts, 2};
    vf_params_t p;
    vf_params_default(&p);
    p.mode = VF_MODE_PREINT1;
    vf_arena_t aw, ag;
    vf_renderer_t *want, *got;
    CHECK_EQ(create(&want, &aw, arena_want, &p, &vol, &tf), VF_OK);
    CHECK_EQ(create(&got, &ag, arena_got, &p, &vol, &tf), VF_OK);
    vf_image_t im = {want_px, W, H, W * 3, VF_FORMAT_RGB888};
    CHECK_EQ(vf_renderer_draw(want, &views[0], &im, scratch, vf_renderer_band_scratch_bytes(want, H * 4)), VF_OK);
    memcpy(want_table, vfi_renderer_preint_table(want), (size_t)256 * 256 * 4 * sizeof want_table[0]);
    CHECK_EQ(begin_frame(NULL, &views[0], W, H, 0, true), VF_ERR_NULL);
    CHECK_EQ(begin_frame(got, NULL, W, H, 0, true), VF_ERR_NULL);
    CHECK_EQ(begin_frame(got, &views[0], W, H, 0, true), VF_OK);
    CHECK(vfi_renderer_preint_table(got) == NULL); /* unbuilt diagonals */
    CHECK_EQ(finish(got, got_px, 1), VF_OK);
    CHECK(vfi_renderer_preint_table(got) == NULL); /* the frame read only some of them */
    CHECK_MSG(memcmp(want_px, got_px, sizeof got_px) == 0, "smooth volume: pictures differ");
    CHECK_EQ(begin_frame(got, &views[1], W, H, 0, false), VF_OK); /* the same slab length, every entry now */
    const uint16_t *table = vfi_renderer_preint_table(got);
    CHECK(table != NULL && memcmp(want_table, table, (size_t)256 * 256 * 4 * sizeof *table) == 0);
    CHECK_EQ(begin_frame(got, &views[1], W, H, 0, true), VF_OK);
    CHECK(vfi_renderer_preint_table(got) == table); /* up to date and whole: kept */
}

/* The options whose loops read the table elsewhere build it whole, on one thread too. */
static void demand_not_asked(void)
{
    fill_volume(true);
    const vf_volume_t vol = {{NI, NJ, NK}, {65536, 65536, 65536}, VF_VOXEL_U8, vox};
    vf_tf_point_t pts[2] = {{0, 65535, 65535, 65535, 0}, {255 * 256, 65535, 30000, 0, 65535}};
    vf_tf_t tf = {pts, 2};
    for (int k = 0; k < 5; k++) {
        vf_params_t p;
        vf_params_default(&p);
        p.mode = VF_MODE_PREINT1;
        if (k == 0)
            p.lookup = VF_LOOKUP_BILINEAR;
        else if (k == 1)
            p.rays = 2;
        else if (k == 2)
            p.sample_bits = 8;
        else if (k == 3)
            p.intermediate_bits = 12;
        else
            p.partial_slabs = true;
        vf_arena_t ag;
        vf_renderer_t *got;
        CHECK_EQ(create(&got, &ag, arena_got, &p, &vol, &tf), VF_OK);
        CHECK_EQ(begin_frame(got, &views[0], W, H, 0, true), VF_OK);
        CHECK_MSG(vfi_renderer_preint_table(got) != NULL, "option %d: the table is not whole", k);
    }
}

CHECK_CASES(CHECK_CASE(demand_equals_whole), CHECK_CASE(demand_table_state), CHECK_CASE(demand_not_asked));
CHECK_RUN("core/table_demand")
