/* SPDX-License-Identifier: MIT */
/*
 * test_prebuilt.c: renderers over prebuilt storage (vf_renderer_export, vf_renderer_create_prebuilt; core/renderer.c,
 * runs.c): the same frames, to the bit, as the renderer whose storage they adopt, for point, preint1 and lit preint1;
 * nothing of the slices, normals or adopted run lists in the arena; a new transfer function's run lists encoded in
 * the arena (VF_ERR_NOMEM with the bytes needed when it is short, the prebuilt ones adopted again after); another
 * window refused; an intermediate image for the views asked for; and every size and run list checked at create.
 */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "frame.h"
#include "render_scene.h"
#include "volfix.h"

static _Alignas(16) unsigned char prebuilt_buf[1 << 22];

/* A renderer over the scene's own storage (s, with window (0, 255) and tf, lit when asked), its export in *pre. */
static void make_source(scene_t *s, vf_mode_t mode, bool lit, const vf_tf_t *tf, vf_prebuilt_t *pre)
{
    vf_params_default(&s->params);
    s->params.mode = mode;
    s->params.table_size = 64;
    s->params.lighting = lit;
    vf_arena_init(&s->arena, arena_buf, sizeof arena_buf);
    CHECK_EQ(vf_renderer_export(NULL, pre), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_create(&s->r, &s->params, &s->vol, &s->arena), VF_OK);
    CHECK_EQ(vf_renderer_export(s->r, pre), VF_ERR_STATE); /* nothing built yet */
    CHECK_EQ(scene_ready(s, tf), VF_OK);
    CHECK_EQ(vf_renderer_export(s->r, pre), VF_OK);
}

/* A renderer over pre in the second arena (arena_bytes of it), with the source's parameters. */
static vf_status_t make_prebuilt(const scene_t *src, const vf_prebuilt_t *pre, size_t arena_bytes, vf_arena_t *arena,
                                 vf_renderer_t **r)
{
    vf_arena_init(arena, prebuilt_buf, arena_bytes);
    return vf_renderer_create_prebuilt(r, &src->params, &src->vol, pre, arena);
}

static bool same_frame(vf_renderer_t *a, vf_renderer_t *b, const vf_view_t *view)
{
    vf_image_t ia = image_of(0, 37, 29, VF_FORMAT_RGB888), ib = image_of(1, 37, 29, VF_FORMAT_RGB888);
    memset(ib.pixels, 0x5A, (size_t)ib.stride * ib.height);
    const size_t bytes = sizeof scratch;
    return vf_renderer_draw(a, view, &ia, scratch, bytes) == VF_OK &&
           vf_renderer_draw(b, view, &ib, scratch, bytes) == VF_OK &&
           memcmp(ia.pixels, ib.pixels, (size_t)ia.stride * ia.height) == 0;
}

static void same_frames(void)
{
    static const vf_mode_t modes[] = {VF_MODE_POINT, VF_MODE_PREINT1, VF_MODE_PREINT1};
    for (int t = 0; t < 12; t++) {
        const int m = t % 3;
        const bool lit = m == 2;
        scene_t s;
        s.vol = volume_of(5 + rnd(12), 5 + rnd(12), 5 + rnd(12));
        fill_random(&s.vol);
        vf_tf_t tf = random_tf();
        vf_prebuilt_t pre;
        make_source(&s, modes[m], lit, &tf, &pre);
        vf_arena_t arena;
        vf_renderer_t *r = NULL;
        CHECK_EQ(make_prebuilt(&s, &pre, sizeof prebuilt_buf, &arena, &r), VF_OK);
        CHECK_EQ(vf_renderer_set_window(r, (vf_window_t){0, 255}), VF_OK);
        CHECK_EQ(vf_renderer_set_tf(r, &tf), VF_OK);
        vf_memory_t mem;
        vf_renderer_memory(r, &mem);
        CHECK_EQ(mem.slices, 0);
        CHECK_EQ(mem.runs, 0);
        CHECK(arena.used < s.arena.used);
        size_t bytes = 0;
        CHECK_EQ(vf_renderer_prebuilt_bytes(&s.params, &s.vol, &pre, &bytes), VF_OK);
        CHECK(arena.peak <= bytes);
        for (int v = 0; v < 3; v++) {
            vf_view_t view = {(int32_t)rnd(65536), (int32_t)rnd(65536), (int32_t)rnd(65536), 65536};
            CHECK(same_frame(s.r, r, &view));
        }
    }
}

/* Another transfer function: its run lists in the arena, as the source renderer would have them; short of arena,
 * VF_ERR_NOMEM with the bytes needed; the prebuilt transfer function adopted again in the short arena. */
static void tf_change(void)
{
    scene_t s;
    s.vol = volume_of(14, 11, 9);
    fill_random(&s.vol);
    vf_tf_t tf = random_tf();
    vf_prebuilt_t pre;
    make_source(&s, VF_MODE_PREINT1, false, &tf, &pre);
    vf_tf_point_t points[2] = {{0, 0, 0, 0, 0}, {255 << 8, 65535, 30000, 1000, 20000}}; /* a ramp: another visibility */
    vf_tf_t other = {points, 2};
    size_t bytes = 0;
    CHECK_EQ(vf_renderer_prebuilt_bytes(&s.params, &s.vol, &pre, &bytes), VF_OK);
    vf_arena_t arena;
    vf_renderer_t *r = NULL;
    CHECK_EQ(make_prebuilt(&s, &pre, bytes, &arena, &r), VF_OK);
    CHECK_EQ(vf_renderer_set_window(r, (vf_window_t){0, 255}), VF_OK);
    CHECK_EQ(vf_renderer_set_tf(r, &other), VF_ERR_NOMEM);
    CHECK(vf_renderer_needed_bytes(r) > bytes);
    const size_t needed = vf_renderer_needed_bytes(r);
    CHECK_EQ(vf_renderer_set_tf(r, &tf), VF_OK); /* the prebuilt run lists again */
    const vf_view_t view = {9000, 4000, 0, 65536};
    CHECK(same_frame(s.r, r, &view));
    /* with the arena it asked for, the other function's frame is the source renderer's */
    CHECK_EQ(make_prebuilt(&s, &pre, needed, &arena, &r), VF_OK);
    CHECK_EQ(vf_renderer_set_window(r, (vf_window_t){0, 255}), VF_OK);
    CHECK_EQ(vf_renderer_set_tf(r, &other), VF_OK);
    vf_memory_t mem;
    vf_renderer_memory(r, &mem);
    CHECK(mem.runs > 0);
    CHECK_EQ(vf_renderer_set_tf(s.r, &other), VF_OK);
    CHECK(same_frame(s.r, r, &view));
    /* the slices are of one window */
    CHECK_EQ(vf_renderer_set_window(r, (vf_window_t){0, 254}), VF_ERR_UNSUPPORTED);
    CHECK_EQ(vf_renderer_set_window(r, (vf_window_t){0, 255}), VF_OK);
}

/* An intermediate image for one view: that view renders, a view with a larger intermediate image does not. */
static void intermediate_for_views(void)
{
    scene_t s;
    s.vol = volume_of(16, 12, 10);
    fill_random(&s.vol);
    vf_tf_t tf = random_tf();
    vf_prebuilt_t pre;
    make_source(&s, VF_MODE_PREINT1, false, &tf, &pre);
    const vf_view_t straight = {0, 0, 0, 65536}, oblique = {8000, 6000, 0, 65536};
    CHECK_EQ(begin_frame(s.r, &straight, 37, 29, 0, false), VF_OK);
    const vf_factor_t *f = vf_renderer_factor(s.r);
    pre.intermediate_pixels = f->int_w * f->int_h;
    size_t small = 0, any = 0;
    CHECK_EQ(vf_renderer_prebuilt_bytes(&s.params, &s.vol, &pre, &small), VF_OK);
    vf_prebuilt_t pre_any = pre;
    pre_any.intermediate_pixels = 0;
    CHECK_EQ(vf_renderer_prebuilt_bytes(&s.params, &s.vol, &pre_any, &any), VF_OK);
    CHECK(small < any);
    vf_arena_t arena;
    vf_renderer_t *r = NULL;
    CHECK_EQ(make_prebuilt(&s, &pre, small, &arena, &r), VF_OK);
    CHECK_EQ(scene_ready(&(scene_t){.r = r}, &tf), VF_OK);
    CHECK(same_frame(s.r, r, &straight));
    CHECK_EQ(begin_frame(r, &oblique, 37, 29, 0, false), VF_ERR_NOMEM);
}

/* Every size and array checked at create: each fault alone gives its status and no renderer. */
static void checked_at_create(void)
{
    scene_t s;
    s.vol = volume_of(9, 8, 7);
    fill_random(&s.vol);
    vf_tf_t tf = random_tf();
    vf_prebuilt_t good;
    make_source(&s, VF_MODE_PREINT1, true, &tf, &good);
    vf_arena_t arena;
    vf_renderer_t *r = NULL;
    CHECK_EQ(make_prebuilt(&s, &good, sizeof prebuilt_buf, &arena, &r), VF_OK);
    CHECK_EQ(vf_renderer_create_prebuilt(&r, &s.params, &s.vol, NULL, &arena), VF_ERR_NULL);
    CHECK(r == NULL);
    size_t bytes;
    CHECK_EQ(vf_renderer_prebuilt_bytes(&s.params, &s.vol, NULL, &bytes), VF_ERR_NULL);
    /* the run lists of axis 1 in writable copies, to spoil */
    const size_t rows = good.row_count[1], pairs = good.pair_count[1];
    uint32_t *row_start = malloc(sizeof *row_start * rows);
    uint16_t *pair = malloc(sizeof *pair * (pairs + 2));
    CHECK(row_start && pair && pairs >= 2);
    for (int fault = 0; fault < 13; fault++) {
        vf_prebuilt_t p = good;
        memcpy(row_start, good.row_start[1], sizeof *row_start * rows);
        memcpy(pair, good.pairs[1], sizeof *pair * pairs);
        p.row_start[1] = row_start;
        p.pairs[1] = pair;
        vf_status_t want = VF_ERR_ARG;
        switch (fault) {
        case 0: p.slices[2] = NULL, want = VF_ERR_NULL; break;
        case 1: p.slice_count[0]--; break;
        case 2: p.codes[1] = NULL, want = VF_ERR_NULL; break;
        case 3: p.unit = NULL, want = VF_ERR_NULL; break;
        case 4: p.unit_count += 3; break;
        case 5: p.row_count[1]--; break;
        case 6: p.pair_count[1] += 2; break;                /* the index ends elsewhere */
        case 7: row_start[rows / 2] = row_start[rows / 2 + 1] + 2; break; /* a row ends before it starts */
        case 8: pair[1] = (uint16_t)(s.vol.dims[2] + 1); break; /* more cells than the row has */
        case 9: p.pairs[0] = NULL, want = VF_ERR_NULL; break;
        case 10: p.window.hi = p.window.lo, want = VF_ERR_WINDOW; break;
        case 11: row_start[0] = 1; break;
        default: want = VF_OK; break; /* the copies unspoilt: accepted */
        }
        r = NULL;
        CHECK_EQ(make_prebuilt(&s, &p, sizeof prebuilt_buf, &arena, &r), want);
        CHECK((r != NULL) == (want == VF_OK));
        CHECK_EQ(vf_renderer_prebuilt_bytes(&s.params, &s.vol, &p, &bytes), want);
    }
    /* normals given to a renderer that does not light */
    vf_params_t unlit = s.params;
    unlit.lighting = false;
    vf_arena_init(&arena, prebuilt_buf, sizeof prebuilt_buf);
    CHECK_EQ(vf_renderer_create_prebuilt(&r, &unlit, &s.vol, &good, &arena), VF_ERR_ARG);
    free(row_start);
    free(pair);
}

CHECK_CASES(CHECK_CASE(same_frames), CHECK_CASE(tf_change), CHECK_CASE(intermediate_for_views),
            CHECK_CASE(checked_at_create));
CHECK_RUN("core/prebuilt")
