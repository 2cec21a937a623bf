/* SPDX-License-Identifier: MIT */
/*
 * test_table_parts.c: a frame whose pre-integrated table is built in parts (vf_frame_t.table_parts,
 * vf_renderer_build_table_part; core/renderer.c, preint.c): in any number of parts, run in any order, the table and the
 * picture equal those of vf_renderer_draw to the bit; compositing before every part has run is refused; a part's
 * arguments and scratch are checked; a frame abandoned half built is rebuilt by the next. With the lut the parts
 * correct the view table (renderer.c), which must come out the same.
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

static uint64_t rng_state = 0x9E3779B97F4A7C15u;
static uint32_t rnd(uint32_t n)
{
    return check_below(&rng_state, n);
}

static uint8_t vox[12 * 11 * 10];
static _Alignas(16) unsigned char arena_buf[1 << 24];
static _Alignas(16) unsigned char scratch[VF_MAX_TABLE_PARTS][1 << 18];
static unsigned char want_px[W * H * 3], got_px[W * H * 3], other_px[W * H * 3];
static uint16_t want_table[1024 * 1024 * 4];

typedef struct scene {
    vf_volume_t vol;
    vf_params_t params;
    vf_arena_t arena;
    vf_renderer_t *r;
    vf_tf_point_t pts[4];
} scene_t;

/* A blob in noise, and a transfer function with a narrow peak and a wide ramp: entries far off the diagonal
 * differ from zero, so a diagonal left unbuilt shows. */
static vf_status_t scene_create(scene_t *s, vf_mode_t mode, uint32_t table_size, uint32_t table_bits,
                                vf_correction_t correction)
{
    s->vol = (vf_volume_t){{12, 11, 10}, {65536, 65536, 65536}, VF_VOXEL_U8, vox};
    for (size_t i = 0; i < sizeof vox; i++)
        vox[i] = (uint8_t)(rnd(4) == 0 ? rnd(256) : 60 + (i % 12) * 10 + rnd(20));
    vf_params_default(&s->params);
    s->params.mode = mode;
    s->params.table_size = table_size;
    s->params.table_bits = table_bits;
    s->params.correction = correction;
    vf_arena_init(&s->arena, arena_buf, sizeof arena_buf);
    s->r = NULL;
    vf_status_t st = vf_renderer_create(&s->r, &s->params, &s->vol, &s->arena);
    if (st != VF_OK)
        return st;
    s->pts[0] = (vf_tf_point_t){0, 65535, 20000, 0, 0};
    s->pts[1] = (vf_tf_point_t){90 * 256, 0, 65535, 30000, 3000};
    s->pts[2] = (vf_tf_point_t){100 * 256, 65535, 65535, 65535, 60000};
    s->pts[3] = (vf_tf_point_t){110 * 256, 10000, 0, 65535, 20000};
    vf_tf_t tf = {s->pts, 4};
    st = vf_renderer_set_window(s->r, (vf_window_t){0, 255});
    return st == VF_OK ? vf_renderer_set_tf(s->r, &tf) : st;
}

static size_t band_bytes(const scene_t *s)
{
    return vf_renderer_band_scratch_bytes(s->r, 64);
}

/* Composite in one band and warp: the picture of a frame that has begun. */
static vf_status_t finish(const scene_t *s, unsigned char *px)
{
    vf_image_t im = {px, W, H, W * 3, VF_FORMAT_RGB888};
    vf_status_t st = vf_renderer_composite_band(s->r, 0, vf_renderer_factor(s->r)->int_h, scratch[0], band_bytes(s));
    return st == VF_OK ? vf_renderer_warp_band(s->r, &im, 0, H) : st;
}

/* Every part of the frame begun, in a shuffled order, each with its own scratch. */
static vf_status_t run_parts(const scene_t *s, uint32_t parts)
{
    uint32_t order[VF_MAX_TABLE_PARTS];
    for (uint32_t p = 0; p < parts; p++)
        order[p] = p;
    for (uint32_t p = parts; p > 1; p--) {
        uint32_t k = rnd(p), t = order[p - 1];
        order[p - 1] = order[k], order[k] = t;
    }
    for (uint32_t p = 0; p < parts; p++) {
        vf_status_t st = vf_renderer_build_table_part(s->r, order[p], scratch[order[p]], vf_renderer_table_part_bytes(s->r));
        if (st != VF_OK)
            return st;
    }
    return VF_OK;
}

/* The same table and picture as vf_render, for table sizes from the smallest to the largest, both formats, both
 * corrections and 1 .. VF_MAX_TABLE_PARTS parts (more parts than diagonals included). */
static void parts_equal_whole(void)
{
    static const struct {
        uint32_t size, bits;
        vf_correction_t correction;
    } cases[] = {{2, 16, VF_CORRECTION_REBUILD},   {7, 16, VF_CORRECTION_REBUILD},  {64, 8, VF_CORRECTION_REBUILD},
                 {255, 16, VF_CORRECTION_REBUILD}, {256, 16, VF_CORRECTION_LUT},    {256, 8, VF_CORRECTION_LUT},
                 {512, 16, VF_CORRECTION_LUT},     {1024, 16, VF_CORRECTION_REBUILD}, {1024, 16, VF_CORRECTION_LUT}};
    static const uint32_t part_counts[] = {1, 2, 3, 5, 64};
    const vf_view_t a = {9000, 4000, 0, 65536}, b = {-3000, 12000, 700, 65536};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        scene_t s;
        CHECK_EQ(scene_create(&s, VF_MODE_PREINT1, cases[c].size, cases[c].bits, cases[c].correction), VF_OK);
        const size_t entries = (size_t)cases[c].size * cases[c].size * 4;
        vf_image_t im = {want_px, W, H, W * 3, VF_FORMAT_RGB888}, other = {other_px, W, H, W * 3, VF_FORMAT_RGB888};
        CHECK_EQ(vf_renderer_draw(s.r, &b, &im, scratch[0], band_bytes(&s)), VF_OK);
        const uint16_t *table = vfi_renderer_preint_table(s.r);
        CHECK((table != NULL) == (cases[c].bits == 16));
        if (table)
            memcpy(want_table, table, entries * sizeof *table);
        for (size_t k = 0; k < sizeof part_counts / sizeof part_counts[0]; k++) {
            const uint32_t parts = part_counts[k];
            CHECK_EQ(vf_renderer_draw(s.r, &a, &other, scratch[0], band_bytes(&s)), VF_OK); /* another slab length */
            CHECK_EQ(begin_frame(s.r, &b, W, H, parts, false), VF_OK);
            /* the lut correction builds its table once: after the first frame the parts correct the view table
             * (16 bits, up to 512 entries), or nothing is pending (no view table) */
            const bool no_view = cases[c].correction == VF_CORRECTION_LUT && (cases[c].bits == 8 || cases[c].size > 512);
            const uint32_t pending = no_view || parts == 1 ? 0 : parts;
            CHECK_EQ(vf_renderer_table_parts(s.r), pending);
            CHECK_EQ(run_parts(&s, parts), VF_OK);
            CHECK_EQ(vf_renderer_table_parts(s.r), 0);
            memset(got_px, 0, sizeof got_px);
            CHECK_EQ(finish(&s, got_px), VF_OK);
            CHECK_MSG(memcmp(want_px, got_px, sizeof got_px) == 0, "table %u x %u bits, %u parts: pictures differ",
                      cases[c].size, cases[c].bits, parts);
            table = vfi_renderer_preint_table(s.r);
            if (table)
                CHECK_MSG(memcmp(want_table, table, entries * sizeof *table) == 0,
                          "table %u, %u parts: tables differ", cases[c].size, parts);
        }
    }
}

/* The order of calls: no band before every part; parts and their arguments checked; a frame left half built. */
static void parts_state(void)
{
    scene_t s;
    CHECK_EQ(scene_create(&s, VF_MODE_PREINT1, 64, 16, VF_CORRECTION_REBUILD), VF_OK);
    const vf_view_t a = {9000, 4000, 0, 65536}, b = {-3000, 12000, 700, 65536};
    vf_image_t im = {want_px, W, H, W * 3, VF_FORMAT_RGB888};
    const size_t part_bytes = vf_renderer_table_part_bytes(s.r);
    CHECK(part_bytes > 0 && part_bytes <= sizeof scratch[0]);
    CHECK_EQ(vf_renderer_table_part_bytes(NULL), 0);
    CHECK_EQ(vf_renderer_table_parts(NULL), 0);
    CHECK_EQ(vf_renderer_table_parts(s.r), 0); /* no frame */
    CHECK_EQ(vf_renderer_build_table_part(s.r, 0, scratch[0], part_bytes), VF_ERR_STATE);
    CHECK_EQ(vf_renderer_draw(s.r, &b, &im, scratch[0], band_bytes(&s)), VF_OK);
    /* parts out of range, or with the table built as compositing reads it (which needs one thread) */
    CHECK_EQ(begin_frame(s.r, &a, W, H, VF_MAX_TABLE_PARTS + 1, false), VF_ERR_ARG);
    CHECK(vf_renderer_factor(s.r) == NULL);
    CHECK_EQ(begin_frame(s.r, &a, W, H, 2, true), VF_ERR_ARG);
    CHECK_EQ(begin_frame(NULL, &a, W, H, 2, false), VF_ERR_NULL);
    CHECK_EQ(begin_frame(s.r, NULL, W, H, 2, false), VF_ERR_NULL);
    /* a new slab length in 3 parts: no band until all three have run */
    CHECK_EQ(begin_frame(s.r, &a, W, H, 3, false), VF_OK);
    CHECK_EQ(vf_renderer_table_parts(s.r), 3);
    CHECK(vfi_renderer_preint_table(s.r) == NULL);
    CHECK_EQ(vf_renderer_composite_band(s.r, 0, 1, scratch[0], band_bytes(&s)), VF_ERR_STATE);
    CHECK_EQ(vf_renderer_build_table_part(s.r, 3, scratch[0], part_bytes), VF_ERR_ARG);
    CHECK_EQ(vf_renderer_build_table_part(NULL, 0, scratch[0], part_bytes), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_build_table_part(s.r, 0, NULL, part_bytes), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_build_table_part(s.r, 0, scratch[0], part_bytes - 1), VF_ERR_NOMEM);
    CHECK_EQ(vf_renderer_build_table_part(s.r, 0, scratch[0], part_bytes), VF_OK);
    CHECK_EQ(vf_renderer_build_table_part(s.r, 0, scratch[0], part_bytes), VF_OK); /* again: nothing to do */
    CHECK_EQ(vf_renderer_build_table_part(s.r, 2, scratch[2], part_bytes), VF_OK);
    CHECK_EQ(vf_renderer_composite_band(s.r, 0, 1, scratch[0], band_bytes(&s)), VF_ERR_STATE); /* part 1 missing */
    /* abandoned: the next frame, on one thread, builds the whole table again */
    CHECK_EQ(vf_renderer_draw(s.r, &a, &im, scratch[0], band_bytes(&s)), VF_OK);
    CHECK_EQ(begin_frame(s.r, &b, W, H, 2, false), VF_OK);
    CHECK_EQ(vf_renderer_build_table_part(s.r, 1, scratch[1], part_bytes), VF_OK);
    CHECK_EQ(vf_renderer_draw(s.r, &a, &im, scratch[0], band_bytes(&s)), VF_OK); /* abandoned again */
    CHECK_EQ(begin_frame(s.r, &a, W, H, 4, false), VF_OK);
    CHECK_EQ(vf_renderer_table_parts(s.r), 0); /* the table of a is whole: nothing to build */
    CHECK_EQ(vf_renderer_build_table_part(s.r, 3, scratch[3], part_bytes), VF_OK);
    CHECK_EQ(finish(&s, got_px), VF_OK);
    CHECK(memcmp(want_px, got_px, sizeof got_px) == 0);
    /* a transfer function set between the parts ends the frame */
    CHECK_EQ(begin_frame(s.r, &b, W, H, 2, false), VF_OK);
    vf_tf_t tf = {s.pts, 3};
    CHECK_EQ(vf_renderer_set_tf(s.r, &tf), VF_OK);
    CHECK_EQ(vf_renderer_build_table_part(s.r, 0, scratch[0], part_bytes), VF_ERR_STATE);
    CHECK_EQ(vf_renderer_table_parts(s.r), 0);
    /* the lut: a frame that leaves the view table half corrected is corrected again by the next */
    scene_t l;
    CHECK_EQ(scene_create(&l, VF_MODE_PREINT1, 200, 16, VF_CORRECTION_LUT), VF_OK);
    CHECK_EQ(vf_renderer_draw(l.r, &b, &im, scratch[0], band_bytes(&l)), VF_OK);
    CHECK_EQ(vf_renderer_draw(l.r, &a, &im, scratch[0], band_bytes(&l)), VF_OK);
    CHECK_EQ(begin_frame(l.r, &b, W, H, 3, false), VF_OK);
    CHECK_EQ(vf_renderer_table_parts(l.r), 3);
    CHECK_EQ(vf_renderer_build_table_part(l.r, 1, scratch[1], vf_renderer_table_part_bytes(l.r)), VF_OK);
    CHECK_EQ(vf_renderer_composite_band(l.r, 0, 1, scratch[0], band_bytes(&l)), VF_ERR_STATE);
    CHECK_EQ(begin_frame(l.r, &a, W, H, 2, false), VF_OK); /* abandoned, back at a's slab length */
    CHECK_EQ(vf_renderer_table_parts(l.r), 2);
    CHECK_EQ(run_parts(&l, 2), VF_OK);
    CHECK_EQ(finish(&l, got_px), VF_OK);
    CHECK(memcmp(want_px, got_px, sizeof got_px) == 0); /* vf_render's picture of a, above */
    /* order 0: the point table is built in begin whatever the parts */
    scene_t p;
    CHECK_EQ(scene_create(&p, VF_MODE_POINT, 256, 16, VF_CORRECTION_REBUILD), VF_OK);
    CHECK_EQ(vf_renderer_draw(p.r, &b, &im, scratch[0], band_bytes(&p)), VF_OK);
    CHECK_EQ(begin_frame(p.r, &a, W, H, 8, false), VF_OK);
    CHECK_EQ(vf_renderer_table_parts(p.r), 0);
    CHECK(vfi_renderer_point_table(p.r) != NULL);
    CHECK_EQ(vf_renderer_build_table_part(p.r, 7, scratch[7], vf_renderer_table_part_bytes(p.r)), VF_OK);
    CHECK_EQ(vf_renderer_build_table_part(p.r, 8, scratch[0], vf_renderer_table_part_bytes(p.r)), VF_ERR_ARG);
    CHECK_EQ(finish(&p, got_px), VF_OK);
}

CHECK_CASES(CHECK_CASE(parts_equal_whole), CHECK_CASE(parts_state));
CHECK_RUN("core/table_parts")
