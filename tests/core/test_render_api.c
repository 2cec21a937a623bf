/* SPDX-License-Identifier: MIT */
/*
 * test_render_api.c: the renderer's public API around a frame (core/renderer.c, composite.c, warp.c, status.c):
 * the order of calls (VF_ERR_STATE), every argument error, what a bad or changed transfer function does to the
 * picture, status texts, and two renderers side by side. Pictures themselves are checked in test_render.c.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "frame.h"
#include "render_scene.h"
#include "volfix.h"
#include "volfix_internal.h"

/* ---- state machine and arguments ------------------------------------------------------------------- */

static void state_machine(void)
{
    scene_t s;
    s.vol = volume_of(6, 5, 4);
    fill_random(&s.vol);
    CHECK_EQ(scene_create(&s, VF_MODE_PREINT1, 64), VF_OK);
    vf_view_t view = {100, 200, 300, 65536};
    vf_image_t im = image_of(0, 20, 10, VF_FORMAT_RGB888);
    size_t bytes = scratch_for(&s);
    /* nothing before a window and a transfer function */
    CHECK_EQ(vf_renderer_draw(s.r, &view, &im, scratch, bytes), VF_ERR_STATE);
    CHECK_EQ(begin_frame(s.r, &view, 20, 10, 0, false), VF_ERR_STATE);
    CHECK_EQ(vf_renderer_composite_band(s.r, 0, 1, scratch, bytes), VF_ERR_STATE);
    CHECK_EQ(vf_renderer_warp_band(s.r, &im, 0, 1), VF_ERR_STATE);
    CHECK(vf_renderer_factor(s.r) == NULL);
    CHECK(vfi_renderer_intermediate(s.r) == NULL);
    CHECK(vfi_renderer_preint_table(s.r) == NULL);
    CHECK(vfi_renderer_point_table(s.r) == NULL);
    CHECK_EQ(vf_renderer_set_window(s.r, (vf_window_t){0, 255}), VF_OK);
    CHECK_EQ(vf_renderer_draw(s.r, &view, &im, scratch, bytes), VF_ERR_STATE); /* window only */
    vf_tf_t tf = random_tf();
    CHECK_EQ(vf_renderer_set_tf(s.r, &tf), VF_OK);
    CHECK_EQ(vf_renderer_draw(s.r, &view, &im, scratch, bytes), VF_OK);
    CHECK(vf_renderer_factor(s.r) != NULL);
    CHECK(vfi_renderer_preint_table(s.r) != NULL);
    CHECK(vfi_renderer_point_table(s.r) == NULL); /* preint1 builds no separate point table */
    const vf_factor_t *f = vf_renderer_factor(s.r);
    uint32_t ih = f->int_h;
    /* bands out of range */
    CHECK_EQ(vf_renderer_composite_band(s.r, 0, 0, scratch, bytes), VF_ERR_ARG);
    CHECK_EQ(vf_renderer_composite_band(s.r, 3, 2, scratch, bytes), VF_ERR_ARG);
    CHECK_EQ(vf_renderer_composite_band(s.r, 0, ih + 1, scratch, bytes), VF_ERR_ARG);
    CHECK_EQ(vf_renderer_composite_band(s.r, ih, ih + 1, scratch, bytes), VF_ERR_ARG);
    CHECK_EQ(vf_renderer_composite_band(s.r, 0, ih, scratch, bytes), VF_OK);
    CHECK_EQ(vf_renderer_composite_band(s.r, ih - 1, ih, scratch, bytes), VF_OK);
    /* scratch too small: one byte short of what a band of the given rows needs */
    CHECK_EQ(vf_renderer_composite_band(s.r, 0, ih, scratch, vf_renderer_band_scratch_bytes(s.r, ih) - 1), VF_ERR_NOMEM);
    CHECK_EQ(vf_renderer_composite_band(s.r, 0, 1, scratch, vf_renderer_band_scratch_bytes(s.r, 1) - 1), VF_ERR_NOMEM);
    CHECK_EQ(vf_renderer_composite_band(s.r, 0, 1, scratch, 0), VF_ERR_NOMEM);
    CHECK_EQ(vf_renderer_draw(s.r, &view, &im, scratch, 10), VF_ERR_NOMEM);
    CHECK(vf_renderer_band_scratch_bytes(s.r, 2) > vf_renderer_band_scratch_bytes(s.r, 1));
    CHECK_EQ(vf_renderer_band_scratch_bytes(NULL, 5), 0);
    /* warp: the image must match the size given to begin, have a stride and a known format */
    CHECK_EQ(begin_frame(s.r, &view, 20, 10, 0, false), VF_OK);
    CHECK_EQ(vf_renderer_composite_band(s.r, 0, vf_renderer_factor(s.r)->int_h, scratch, bytes), VF_OK);
    vf_image_t bad = im;
    bad.width = 21;
    CHECK_EQ(vf_renderer_warp_band(s.r, &bad, 0, 10), VF_ERR_IMAGE);
    bad = im;
    bad.height = 9;
    CHECK_EQ(vf_renderer_warp_band(s.r, &bad, 0, 9), VF_ERR_IMAGE);
    bad = im;
    bad.stride = 59;
    CHECK_EQ(vf_renderer_warp_band(s.r, &bad, 0, 10), VF_ERR_IMAGE);
    bad = im;
    bad.format = VF_FORMAT_COUNT;
    CHECK_EQ(vf_renderer_warp_band(s.r, &bad, 0, 10), VF_ERR_IMAGE);
    bad.format = (vf_format_t)-1;
    CHECK_EQ(vf_renderer_warp_band(s.r, &bad, 0, 10), VF_ERR_IMAGE);
    bad = im;
    bad.pixels = NULL;
    CHECK_EQ(vf_renderer_warp_band(s.r, &bad, 0, 10), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_warp_band(s.r, &im, 0, 0), VF_ERR_ARG);
    CHECK_EQ(vf_renderer_warp_band(s.r, &im, 5, 4), VF_ERR_ARG);
    CHECK_EQ(vf_renderer_warp_band(s.r, &im, 0, 11), VF_ERR_ARG);
    CHECK_EQ(vf_renderer_warp_band(s.r, &im, 9, 10), VF_OK);
    bad = im;
    bad.width = 0;
    CHECK_EQ(vf_renderer_draw(s.r, &view, &bad, scratch, bytes), VF_ERR_IMAGE);
    /* a failed begin ends the frame: no compositing with the previous factorisation */
    vf_view_t zoomless = view;
    zoomless.zoom_q16 = 0;
    CHECK_EQ(begin_frame(s.r, &zoomless, 20, 10, 0, false), VF_ERR_ARG);
    CHECK_EQ(vf_renderer_composite_band(s.r, 0, 1, scratch, bytes), VF_ERR_STATE);
    CHECK_EQ(vf_renderer_warp_band(s.r, &im, 0, 1), VF_ERR_STATE);
    CHECK(vf_renderer_factor(s.r) == NULL);
    /* NULL pointers */
    CHECK_EQ(vf_renderer_draw(NULL, &view, &im, scratch, bytes), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_draw(s.r, NULL, &im, scratch, bytes), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_draw(s.r, &view, NULL, scratch, bytes), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_draw(s.r, &view, &im, NULL, bytes), VF_ERR_NULL);
    CHECK_EQ(begin_frame(NULL, &view, 20, 10, 0, false), VF_ERR_NULL);
    CHECK_EQ(begin_frame(s.r, NULL, 20, 10, 0, false), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_composite_band(NULL, 0, 1, scratch, bytes), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_warp_band(NULL, &im, 0, 1), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_warp_band(s.r, NULL, 0, 1), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_set_tf(NULL, &tf), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_set_tf(s.r, NULL), VF_ERR_NULL);
    CHECK(vf_renderer_factor(NULL) == NULL);
    CHECK(vfi_renderer_intermediate(NULL) == NULL);
    CHECK(vfi_renderer_point_table(NULL) == NULL);
    CHECK(vfi_renderer_preint_table(NULL) == NULL);
    CHECK(vf_renderer_params(NULL) == NULL);
    CHECK(vf_renderer_params(s.r) != NULL && vf_renderer_params(s.r)->table_size == 64);
    CHECK_EQ(vf_renderer_needed_bytes(NULL), 0);
    vf_memory_t mem;
    memset(&mem, 0x77, sizeof mem);
    vf_renderer_memory(NULL, &mem); /* no effect, no crash */
    vf_renderer_memory(s.r, NULL);
    vf_params_default(NULL);
    /* after all the errors a frame still renders */
    CHECK_EQ(vf_renderer_draw(s.r, &view, &im, scratch, bytes), VF_OK);
}

/* A bad transfer function leaves the previous one in force: the next frame is the same picture. */
static void bad_tf_keeps_picture(void)
{
    scene_t s;
    s.vol = volume_of(9, 8, 7);
    fill_random(&s.vol);
    CHECK_EQ(scene_create(&s, VF_MODE_PREINT1, 256), VF_OK);
    vf_tf_t tf = random_tf();
    tf_pts[0].a = 20000;
    CHECK_EQ(scene_ready(&s, &tf), VF_OK);
    vf_view_t view = {5000, 3000, 0, 65536};
    vf_image_t a = image_of(0, 25, 25, VF_FORMAT_RGB888), b = image_of(1, 25, 25, VF_FORMAT_RGB888);
    CHECK_EQ(vf_renderer_draw(s.r, &view, &a, scratch, scratch_for(&s)), VF_OK);
    vf_tf_point_t dec[2] = {{300, 1, 1, 1, 65535}, {200, 1, 1, 1, 65535}};
    vf_tf_t bad = {dec, 2};
    CHECK_EQ(vf_renderer_set_tf(s.r, &bad), VF_ERR_TF);
    bad.count = 0;
    CHECK_EQ(vf_renderer_set_tf(s.r, &bad), VF_ERR_TF);
    dec[1].scalar_q8 = 65281;
    bad.count = 2;
    CHECK_EQ(vf_renderer_set_tf(s.r, &bad), VF_ERR_TF);
    CHECK_EQ(vf_renderer_draw(s.r, &view, &b, scratch, scratch_for(&s)), VF_OK);
    CHECK(memcmp(pixels[0], pixels[1], 25 * 25 * 3) == 0);
}

/* Changing the transfer function between vf_renderer_begin and the bands: the bands must either refuse
 * (VF_ERR_STATE, as for every other out-of-order call) or composite the new transfer function. CORE BUG if they
 * composite the old tables over the new run lists: vf_renderer_set_tf does not end the frame (have_frame stays
 * true) and the tables are rebuilt only in vf_renderer_begin. */
static void tf_change_inside_frame(void)
{
    scene_t s;
    s.vol = volume_of(9, 8, 7);
    fill_random(&s.vol);
    CHECK_EQ(scene_create(&s, VF_MODE_PREINT1, 256), VF_OK);
    vf_tf_point_t p1[2] = {{0, 65535, 0, 0, 0}, {100 * 256, 65535, 0, 0, 30000}};
    vf_tf_point_t p2[2] = {{0, 0, 65535, 0, 30000}, {100 * 256, 0, 65535, 0, 0}};
    vf_tf_t tf1 = {p1, 2}, tf2 = {p2, 2};
    CHECK_EQ(scene_ready(&s, &tf2), VF_OK);
    vf_view_t view = {5000, 3000, 0, 65536};
    vf_image_t want = image_of(0, 25, 25, VF_FORMAT_RGB888), got = image_of(1, 25, 25, VF_FORMAT_RGB888);
    CHECK_EQ(vf_renderer_draw(s.r, &view, &want, scratch, scratch_for(&s)), VF_OK); /* the picture of tf2 */
    CHECK_EQ(vf_renderer_set_tf(s.r, &tf1), VF_OK);
    CHECK_EQ(begin_frame(s.r, &view, 25, 25, 0, false), VF_OK); /* tables of tf1 */
    uint32_t rows = vf_renderer_factor(s.r)->int_h;
    CHECK_EQ(vf_renderer_set_tf(s.r, &tf2), VF_OK);         /* runs of tf2 */
    CHECK(vf_renderer_factor(s.r) == NULL);                   /* the frame is over */
    vf_status_t st = vf_renderer_composite_band(s.r, 0, rows, scratch, scratch_for(&s));
    if (st == VF_ERR_STATE)
        return; /* refused: fine */
    CHECK_EQ(st, VF_OK);
    CHECK_EQ(vf_renderer_warp_band(s.r, &got, 0, 25), VF_OK);
    CHECK_MSG(memcmp(pixels[0], pixels[1], 25 * 25 * 3) == 0,
              "vf_renderer_composite_band after vf_renderer_set_tf returned VF_OK with a picture of neither transfer function");
}

static void create_arguments(void)
{
    vf_volume_t vol = volume_of(5, 6, 7);
    vf_params_t p;
    vf_params_default(&p);
    CHECK_EQ(p.mode, VF_MODE_PREINT1);
    CHECK_EQ(p.table_size, VF_DEFAULT_TABLE);
    vf_arena_t arena;
    vf_arena_init(&arena, arena_buf, sizeof arena_buf);
    vf_renderer_t *r = (vf_renderer_t *)&arena; /* not NULL: must be set to NULL on failure */
    size_t bytes;
    CHECK_EQ(vf_renderer_create(NULL, &p, &vol, &arena), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_create(&r, NULL, &vol, &arena), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_create(&r, &p, NULL, &arena), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_create(&r, &p, &vol, NULL), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_bytes(NULL, &vol, &bytes), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_bytes(&p, NULL, &bytes), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_bytes(&p, &vol, NULL), VF_ERR_NULL);
    const uint32_t bad_tables[] = {0, 1, VF_MAX_TABLE + 1, UINT32_MAX};
    for (int n = 0; n < 4; n++) {
        vf_params_t q = p;
        q.table_size = bad_tables[n];
        r = (vf_renderer_t *)&arena;
        CHECK_EQ(vf_renderer_create(&r, &q, &vol, &arena), VF_ERR_ARG);
        CHECK(r == NULL);
        CHECK_EQ(vf_renderer_bytes(&q, &vol, &bytes), VF_ERR_ARG);
    }
    vf_params_t q = p;
    q.mode = VF_MODE_COUNT;
    CHECK_EQ(vf_renderer_create(&r, &q, &vol, &arena), VF_ERR_ARG);
    q.mode = (vf_mode_t)-1;
    CHECK_EQ(vf_renderer_create(&r, &q, &vol, &arena), VF_ERR_ARG);
    vf_volume_t v = vol;
    v.voxels = NULL;
    CHECK_EQ(vf_renderer_create(&r, &p, &v, &arena), VF_ERR_NULL);
    v = vol;
    v.type = (vf_voxel_t)4;
    CHECK_EQ(vf_renderer_create(&r, &p, &v, &arena), VF_ERR_ARG);
    v = vol;
    v.dims[1] = 1;
    CHECK_EQ(vf_renderer_create(&r, &p, &v, &arena), VF_ERR_DIMS);
    v.dims[1] = VF_MAX_DIM + 1;
    CHECK_EQ(vf_renderer_bytes(&p, &v, &bytes), VF_ERR_DIMS);
    v = vol;
    v.spacing_q16[2] = 0;
    CHECK_EQ(vf_renderer_create(&r, &p, &v, &arena), VF_ERR_SPACING);
    v.spacing_q16[2] = 65536 * 65;
    CHECK_EQ(vf_renderer_create(&r, &p, &v, &arena), VF_ERR_SPACING);
    CHECK_EQ(arena.used, 0); /* nothing taken by refused calls */
    /* the largest volume is refused by size before anything is allocated, not by overflow */
    v = vol;
    v.dims[0] = v.dims[1] = v.dims[2] = VF_MAX_DIM;
    vf_status_t st = vf_renderer_bytes(&p, &v, &bytes);
    CHECK(st == VF_OK || st == VF_ERR_DIMS);
    if (st == VF_OK)
        CHECK(bytes > (size_t)3 * VF_MAX_DIM * VF_MAX_DIM * VF_MAX_DIM);
    /* with a 32-bit size_t (32-bit ARM) three copies of 4097^3 voxels cannot be addressed: VF_ERR_DIMS, the same
     * answer from both calls; with a 64-bit one the size is computed and the small arena refuses it */
    CHECK_EQ(st, (uint64_t)SIZE_MAX / 4 < (uint64_t)(VF_MAX_DIM + 1) * (VF_MAX_DIM + 1) * (VF_MAX_DIM + 1)
                     ? VF_ERR_DIMS : VF_OK);
    CHECK_EQ(vf_renderer_create(&r, &p, &v, &arena), st == VF_OK ? VF_ERR_NOMEM : VF_ERR_DIMS);
    CHECK(r == NULL);
    /* table sizes at both ends work */
    q = p;
    q.table_size = VF_MIN_TABLE;
    vf_arena_init(&arena, arena_buf, sizeof arena_buf);
    CHECK_EQ(vf_renderer_create(&r, &q, &vol, &arena), VF_OK);
    q.table_size = VF_MAX_TABLE;
    q.mode = VF_MODE_POINT;
    vf_arena_init(&arena, arena_buf, sizeof arena_buf);
    CHECK_EQ(vf_renderer_create(&r, &q, &vol, &arena), VF_OK);
}

static void status_texts(void)
{
    for (int a = 0; a < VF_STATUS_COUNT; a++) {
        const char *ta = vf_status_text((vf_status_t)a);
        CHECK(ta != NULL && ta[0] != 0);
        for (int b = 0; b < a; b++)
            CHECK_MSG(strcmp(ta, vf_status_text((vf_status_t)b)) != 0, "statuses %d and %d share a text", a, b);
    }
    const int outside[] = {VF_STATUS_COUNT, VF_STATUS_COUNT + 1, -1, 1000000};
    for (int n = 0; n < 4; n++) {
        const char *t = vf_status_text((vf_status_t)outside[n]);
        CHECK(t != NULL && t[0] != 0);
        for (int b = 0; b < VF_STATUS_COUNT; b++)
            CHECK(strcmp(t, vf_status_text((vf_status_t)b)) != 0);
    }
    CHECK(strcmp(vf_mode_name(VF_MODE_POINT), "point") == 0);
    CHECK(strcmp(vf_mode_name(VF_MODE_PREINT1), "preint1") == 0);
    CHECK(vf_mode_name(VF_MODE_COUNT) != NULL);
    CHECK_EQ(vf_format_bytes(VF_FORMAT_RGB888), 3);
    CHECK_EQ(vf_format_bytes(VF_FORMAT_RGB565), 2);
    CHECK_EQ(vf_format_bytes(VF_FORMAT_XRGB8888), 4);
    CHECK_EQ(vf_format_bytes(VF_FORMAT_COUNT), 0);
    CHECK_EQ(vf_format_bytes((vf_format_t)-1), 0);
}

/* Two renderers in one process share nothing: interleaved use gives the same pictures as separate use. */
static void two_renderers(void)
{
    static _Alignas(16) unsigned char buf2[1 << 21];
    scene_t s;
    s.vol = volume_of(8, 9, 10);
    fill_random(&s.vol);
    CHECK_EQ(scene_create(&s, VF_MODE_PREINT1, 128), VF_OK);
    vf_arena_t arena2;
    vf_arena_init(&arena2, buf2, sizeof buf2);
    vf_renderer_t *r2 = NULL;
    vf_params_t p2 = s.params;
    p2.mode = VF_MODE_POINT;
    CHECK_EQ(vf_renderer_create(&r2, &p2, &s.vol, &arena2), VF_OK);
    vf_tf_t tf = random_tf();
    tf_pts[0].a = 9000;
    CHECK_EQ(scene_ready(&s, &tf), VF_OK);
    vf_view_t view = {7000, -2000, 100, 65536};
    vf_image_t a = image_of(0, 30, 30, VF_FORMAT_RGB888), b = image_of(1, 30, 30, VF_FORMAT_RGB888);
    CHECK_EQ(vf_renderer_draw(s.r, &view, &a, scratch, scratch_for(&s)), VF_OK);
    CHECK_EQ(vf_renderer_set_window(r2, (vf_window_t){255, 0}), VF_OK);
    CHECK_EQ(vf_renderer_set_tf(r2, &tf), VF_OK);
    CHECK_EQ(vf_renderer_draw(r2, &view, &b, scratch, vf_renderer_band_scratch_bytes(r2, 64)), VF_OK);
    CHECK_EQ(vf_renderer_draw(s.r, &view, &b, scratch, scratch_for(&s)), VF_OK);
    CHECK(memcmp(pixels[0], pixels[1], 30 * 30 * 3) == 0);
}

/* The calls that return no status take NULL and out-of-range values without harm and say so in what they return:
 * 0, NULL, a name that is not another's, an output left as it was. */
static void null_and_range_safe(void)
{
    vf_arena_init(NULL, arena_buf, sizeof arena_buf);
    vf_arena_t arena;
    vf_arena_init(&arena, NULL, 1000); /* no buffer: no room */
    CHECK_EQ(arena.size, 0);
    vf_params_default(NULL);
    CHECK_EQ(vf_renderer_needed_bytes(NULL), 0);
    vf_memory_t m;
    memset(&m, 0xA5, sizeof m);
    vf_renderer_memory(NULL, &m);
    unsigned char *bytes = (unsigned char *)&m;
    for (size_t i = 0; i < sizeof m; i++)
        CHECK_EQ(bytes[i], 0xA5);
    CHECK(vf_renderer_params(NULL) == NULL);
    CHECK(vf_renderer_factor(NULL) == NULL);
    CHECK(vfi_renderer_intermediate(NULL) == NULL);
    CHECK(vfi_renderer_preint_table(NULL) == NULL);
    CHECK(vfi_renderer_point_table(NULL) == NULL);
    const char *names[] = {vf_lookup_name(VF_LOOKUP_COUNT), vf_correction_name(VF_CORRECTION_COUNT),
                           vf_buffer_name(VF_BUFFER_COUNT), vf_mode_name((vf_mode_t)-1)};
    for (int n = 0; n < 4; n++)
        CHECK(names[n] != NULL && names[n][0] != 0);
    CHECK(strcmp(vf_lookup_name(VF_LOOKUP_COUNT), vf_lookup_name(VF_LOOKUP_NEAREST)) != 0);
    CHECK(strcmp(vf_buffer_name(VF_BUFFER_COUNT), vf_buffer_name(VF_BUFFER_SLICE)) != 0);
    scene_t s;
    s.vol = volume_of(8, 9, 10);
    fill_random(&s.vol);
    CHECK_EQ(scene_create(&s, VF_MODE_PREINT1, 64), VF_OK);
    vf_renderer_memory(s.r, NULL);
    vf_renderer_memory(s.r, &m);
    CHECK(m.total > 0 && m.total <= s.arena.used);
}

CHECK_CASES(CHECK_CASE(null_and_range_safe), CHECK_CASE(state_machine), CHECK_CASE(bad_tf_keeps_picture),
            CHECK_CASE(tf_change_inside_frame), CHECK_CASE(create_arguments), CHECK_CASE(status_texts),
            CHECK_CASE(two_renderers));
CHECK_RUN("core/render_api")
