/* SPDX-License-Identifier: MIT */
/*
 * test_table_demand.c: a frame composited on one thread whose 2D table is built as compositing reads it
 * (vf_frame_t.one_thread; core/preint.c, composite_order1.c): its intermediate image and picture equal
 * vf_render's to the bit, for table sizes from the smallest to the largest, the 10-, 12- and 16-bit formats, both
 * buffers, bands one after another, views with the same slab length (the table kept, more diagonals built) and a
 * transfer function changed between frames; the table is not handed out while diagonals are unbuilt, and a frame
 * begun for threads afterwards builds it whole; the options it does not cover build the whole table;
 * threads' copies of the table (vf_frame_t.thread_tables), bands taking turns between two copies that copy
 * diagonals from each other: the same pictures, each diagonal built once, and the calls' errors.
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


/* Two threads' copies of the table, the bands taking turns between them on this thread: each copy asks the other
 * for a diagonal before building it (vf_thread_table_t.fill), as render_mt.c's threads do through their claims. */
typedef struct copy_ctx {
    vf_renderer_t *r;
    const vf_thread_table_t *tables;
    int self;
    int *owner;            /* per diagonal: 1 + the copy that built it, 0 none */
    bool has[1024];        /* the diagonals this copy built or copied */
    int builds, copies, twice; /* twice: asked for a diagonal it has, or built one built already */
} copy_ctx_t;

static bool fill_from_other(void *context, uint32_t d)
{
    copy_ctx_t *c = context;
    if (!c->owner[d])
        return false;
    c->twice += c->owner[d] - 1 == c->self;
    c->copies++;
    c->has[d] = true;
    return vf_renderer_copy_diagonal(c->r, &c->tables[c->owner[d] - 1], &c->tables[c->self], d) == VF_OK;
}

static void note_built(void *context, uint32_t d)
{
    copy_ctx_t *c = context;
    c->twice += c->owner[d] != 0;
    c->owner[d] = 1 + c->self;
    c->has[d] = true;
    c->builds++;
}

static void thread_copies(void)
{
    static const struct {
        uint32_t size, bits;
        vf_buffer_t buffer;
    } cases[] = {{2, 16, VF_BUFFER_SLICE}, {64, 16, VF_BUFFER_IMAGE}, {256, 16, VF_BUFFER_SLICE},
                 {256, 12, VF_BUFFER_IMAGE}, {1024, 16, VF_BUFFER_SLICE}};
    static unsigned char copy_mem[2][(1024 * 1024 * 4 * 2) + (1 << 20)];
    fill_volume(true);
    const vf_volume_t vol = {{NI, NJ, NK}, {65536, 65536, 65536}, VF_VOXEL_U8, vox};
    vf_tf_point_t pts[3] = {{0, 65535, 20000, 0, 0}, {100 * 256, 0, 65535, 30000, 30000},
                            {255 * 256, 65535, 0, 65535, 9000}};
    vf_tf_t tf = {pts, 3};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        vf_params_t p;
        vf_params_default(&p);
        p.table_size = cases[c].size;
        p.table_bits = cases[c].bits;
        p.buffer = cases[c].buffer;
        vf_arena_t aw, ag;
        vf_renderer_t *want, *got;
        CHECK_EQ(create(&want, &aw, arena_want, &p, &vol, &tf), VF_OK);
        CHECK_EQ(create(&got, &ag, arena_got, &p, &vol, &tf), VF_OK);
        const size_t bytes = vf_renderer_thread_table_bytes(got);
        CHECK(bytes > 0 && bytes <= sizeof copy_mem[0]);
        static int owner[1024];
        copy_ctx_t ctx[2];
        vf_thread_table_t tables[2];
        for (int t = 0; t < 2; t++) {
            memset(&ctx[t], 0, sizeof ctx[t]);
            ctx[t].r = got, ctx[t].tables = tables, ctx[t].self = t, ctx[t].owner = owner;
            tables[t] = (vf_thread_table_t){copy_mem[t], bytes, fill_from_other, note_built, &ctx[t]};
        }
        for (size_t v = 0; v < sizeof views / sizeof views[0]; v++) {
            vf_image_t im = {want_px, W, H, W * 3, VF_FORMAT_RGB888};
            CHECK_EQ(vf_renderer_draw(want, &views[v], &im, scratch, vf_renderer_band_scratch_bytes(want, H * 4)), VF_OK);
            const vf_frame_t frame = {.view = views[v], .width = W, .height = H, .table_parts = 2, .thread_tables = true};
            CHECK_EQ(vf_renderer_begin(got, &frame), VF_OK);
            CHECK_EQ(vf_renderer_table_parts(got), 0); /* nothing to build before the bands */
            memset(owner, 0, sizeof owner);
            for (int t = 0; t < 2; t++) {
                ctx[t].builds = ctx[t].copies = 0;
                memset(ctx[t].has, 0, sizeof ctx[t].has);
                CHECK_EQ(vf_renderer_thread_table_begin(got, &tables[t]), VF_OK);
            }
            const uint32_t h = vf_renderer_factor(got)->int_h;
            CHECK_EQ(vf_renderer_composite_band(got, 0, h, scratch, sizeof scratch), VF_ERR_STATE); /* shared: stale */
            for (uint32_t v0 = 0, b = 0; v0 < h; v0 += 3, b++) {
                const uint32_t v1 = v0 + 3 < h ? v0 + 3 : h;
                CHECK_EQ(vf_renderer_composite_band_in(got, v0, v1, scratch, sizeof scratch, &tables[b % 2]), VF_OK);
            }
            memset(got_px, 0, sizeof got_px);
            vf_image_t gim = {got_px, W, H, W * 3, VF_FORMAT_RGB888};
            CHECK_EQ(vf_renderer_warp_band(got, &gim, 0, H), VF_OK);
            CHECK_MSG(memcmp(want_px, got_px, sizeof got_px) == 0, "table %u x %u bits, view %zu: pictures differ",
                      cases[c].size, cases[c].bits, v);
            CHECK_EQ(ctx[0].twice + ctx[1].twice, 0); /* each diagonal built once, asked for by a copy without it */
            /* every diagonal a copy has, built or copied, is the whole table's (want's, built whole for this view) */
            const uint32_t n = cases[c].size;
            CHECK_EQ(begin_frame(want, &views[v], W, H, 1, false), VF_OK);
            const uint16_t *whole = vfi_renderer_preint_table(want);
            CHECK(whole != NULL);
            for (int t = 0; t < 2 && whole; t++) {
                const uint16_t *mine = vfi_renderer_thread_table(got, &tables[t]);
                CHECK(mine != NULL);
                int wrong = 0;
                for (uint32_t f = 0; mine && f < n; f++)
                    for (uint32_t b = 0; b < n; b++)
                        if (ctx[t].has[f > b ? f - b : b - f] || f == b)
                            wrong += memcmp(mine + ((size_t)f * n + b) * 4, whole + ((size_t)f * n + b) * 4, 8) != 0;
                CHECK_MSG(wrong == 0, "table %u, view %zu, copy %d: %d entries differ", n, v, t, wrong);
            }
            if (cases[c].size >= 64) /* both copies worked, and shared */
                CHECK_MSG(ctx[0].builds > 0 && ctx[1].builds + ctx[1].copies > 0 && ctx[0].copies + ctx[1].copies > 0,
                          "table %u, view %zu: builds %d, %d, copies %d, %d", cases[c].size, v, ctx[0].builds,
                          ctx[1].builds, ctx[0].copies, ctx[1].copies);
        }
        /* the next frame without copies builds the shared table: vf_render's */
        CHECK_EQ(begin_frame(got, &views[5], W, H, 0, false), VF_OK);
        CHECK_EQ(finish(got, got_px, 2), VF_OK);
        CHECK(memcmp(want_px, got_px, sizeof got_px) == 0);
    }
}

/* What the copies' calls refuse, and the options that never build a table as read: no copies, the shared table. */
static void thread_copies_refused(void)
{
    fill_volume(true);
    const vf_volume_t vol = {{NI, NJ, NK}, {65536, 65536, 65536}, VF_VOXEL_U8, vox};
    vf_tf_point_t pts[2] = {{0, 65535, 65535, 65535, 0}, {255 * 256, 65535, 30000, 0, 65535}};
    vf_tf_t tf = {pts, 2};
    vf_params_t p;
    vf_params_default(&p);
    vf_arena_t ag;
    vf_renderer_t *got;
    CHECK_EQ(create(&got, &ag, arena_got, &p, &vol, &tf), VF_OK);
    static unsigned char mem[2][256 * 256 * 8 + (1 << 18)];
    const size_t bytes = vf_renderer_thread_table_bytes(got);
    CHECK(bytes > 256 * 256 * 8 && bytes <= sizeof mem[0]);
    vf_thread_table_t t = {mem[0], bytes, NULL, NULL, NULL}, u = {mem[1], bytes, NULL, NULL, NULL};
    CHECK_EQ(vf_renderer_thread_table_begin(got, &t), VF_ERR_STATE); /* no frame yet */
    const vf_frame_t frame = {.view = views[0], .width = W, .height = H, .table_parts = 2, .thread_tables = true};
    CHECK_EQ(vf_renderer_begin(got, &frame), VF_OK);
    CHECK_EQ(vf_renderer_thread_table_begin(NULL, &t), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_thread_table_begin(got, NULL), VF_ERR_NULL);
    vf_thread_table_t small = {mem[0], bytes - 1, NULL, NULL, NULL};
    CHECK_EQ(vf_renderer_thread_table_begin(got, &small), VF_ERR_NOMEM);
    CHECK_EQ(vf_renderer_composite_band_in(got, 0, 1, scratch, sizeof scratch, &small), VF_ERR_NOMEM);
    CHECK_EQ(vf_renderer_thread_table_begin(got, &t), VF_OK);
    CHECK_EQ(vf_renderer_thread_table_begin(got, &u), VF_OK);
    CHECK_EQ(vf_renderer_copy_diagonal(got, &t, &u, 256), VF_ERR_ARG);
    CHECK_EQ(vf_renderer_copy_diagonal(got, &t, &u, 255), VF_OK);
    CHECK_EQ(vf_renderer_composite_band_in(got, 0, 0, scratch, sizeof scratch, &t), VF_ERR_ARG);
    /* a frame for one thread: the shared table, which the calls with a copy then read */
    CHECK_EQ(begin_frame(got, &views[0], W, H, 0, true), VF_OK);
    CHECK_EQ(vf_renderer_thread_table_begin(got, &t), VF_OK);
    CHECK_EQ(vf_renderer_copy_diagonal(got, &t, &u, 3), VF_ERR_STATE);
    CHECK_EQ(vf_renderer_composite_band_in(got, 0, vf_renderer_factor(got)->int_h, scratch, sizeof scratch, &t), VF_OK);
    for (int k = 0; k < 3; k++) { /* never built as read: no copies, and frames that ask for them share the table */
        vf_params_t q = p;
        if (k == 0)
            q.correction = VF_CORRECTION_LUT;
        else if (k == 1)
            q.table_bits = 8;
        else
            q.mode = VF_MODE_POINT;
        CHECK_EQ(create(&got, &ag, arena_got, &q, &vol, &tf), VF_OK);
        CHECK_EQ(vf_renderer_thread_table_bytes(got), 0);
    }
    p.lookup = VF_LOOKUP_BILINEAR; /* copies could be made, but this frame's loops read the table elsewhere */
    CHECK_EQ(create(&got, &ag, arena_got, &p, &vol, &tf), VF_OK);
    CHECK_EQ(vf_renderer_begin(got, &frame), VF_OK);
    CHECK_EQ(vf_renderer_table_parts(got), 2);
    CHECK_EQ(vf_renderer_thread_table_begin(got, &t), VF_OK); /* nothing to do */
    CHECK_EQ(vf_renderer_composite_band_in(got, 0, 1, scratch, sizeof scratch, &t), VF_ERR_STATE); /* parts first */
}

CHECK_CASES(CHECK_CASE(demand_equals_whole), CHECK_CASE(demand_table_state), CHECK_CASE(demand_not_asked),
            CHECK_CASE(thread_copies), CHECK_CASE(thread_copies_refused));
CHECK_RUN("core/table_demand")
