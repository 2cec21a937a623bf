/* SPDX-License-Identifier: MIT */
/*
 * test_runs_parts.c: a transfer function's run lists encoded in parts (core/runs_parts.c, vf_renderer_set_tf_begin)
 * against the whole encoding of vf_renderer_set_tf: the same index and pairs to the byte, at the same places in
 * the arena, with the same memory figures, for every axis, for slab ranges that divide the slabs unevenly or
 * outnumber them, parts run in any order or left to end; and the same failures (an arena short for the run
 * lists, a part's region too short for its pairs, an injected allocation fault).
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "arena.h"
#include "check.h"
#include "renderer.h"
#include "volfix_internal.h"

static uint64_t rng_state = 0x5BE0CD19137E2179u;
static uint32_t rnd(uint32_t n)
{
    return check_below(&rng_state, n);
}

#define ARENA_BYTES (1u << 22)
static _Alignas(16) unsigned char whole_buf[ARENA_BYTES], parts_buf[ARENA_BYTES];
static uint8_t vox[40 * 40 * 40];

/* Up to max a side (odd sizes among them): blobs on a background with noise, so that rows hold several runs. */
static vf_volume_t random_volume(uint32_t max)
{
    vf_volume_t v;
    for (int a = 0; a < 3; a++) {
        v.dims[a] = 2 + rnd(max - 1);
        v.spacing_q16[a] = 65536;
    }
    v.type = VF_VOXEL_U8;
    const uint32_t nx = v.dims[0], ny = v.dims[1], nz = v.dims[2];
    const int cx = (int)rnd(nx), cy = (int)rnd(ny), cz = (int)rnd(nz), rad = 2 + (int)rnd(10);
    for (uint32_t z = 0; z < nz; z++)
        for (uint32_t y = 0; y < ny; y++)
            for (uint32_t x = 0; x < nx; x++) {
                const int d2 = ((int)x - cx) * ((int)x - cx) + ((int)y - cy) * ((int)y - cy) +
                               ((int)z - cz) * ((int)z - cz);
                uint32_t val = (d2 < rad * rad ? 180 : 30) + rnd(50);
                if (rnd(8) == 0)
                    val = rnd(256);
                vox[((size_t)z * ny + y) * nx + x] = (uint8_t)val;
            }
    v.voxels = vox;
    return v;
}

static vf_tf_point_t tf_pts[6];

/* 0: nothing visible; 1: everything; 2: a step (the blobs); else random peaks and plateaus. */
static vf_tf_t make_tf(int kind)
{
    if (kind == 0 || kind == 1) {
        tf_pts[0] = (vf_tf_point_t){0, 65535, 65535, 65535, (uint16_t)kind};
        return (vf_tf_t){tf_pts, 1};
    }
    if (kind == 2) {
        tf_pts[0] = (vf_tf_point_t){0, 65535, 65535, 65535, 0};
        tf_pts[1] = (vf_tf_point_t){150 * 256, 65535, 65535, 65535, 0};
        tf_pts[2] = (vf_tf_point_t){160 * 256, 65535, 30000, 1000, 20000};
        return (vf_tf_t){tf_pts, 3};
    }
    uint32_t count = 1 + rnd(6), s = rnd(50000);
    for (uint32_t p = 0; p < count; p++) {
        if (p)
            s += rnd(20000);
        tf_pts[p] = (vf_tf_point_t){(uint16_t)(s > 65280 ? 65280 : s), 65535, 30000, 1000,
                                    (uint16_t)(rnd(3) == 0 ? 0 : rnd(65536))};
    }
    return (vf_tf_t){tf_pts, count};
}

/* A renderer with its window in an arena of `bytes` over buf; NULL if it could not be made. */
static vf_renderer_t *make(const vf_volume_t *vol, vf_mode_t mode, unsigned char *buf, size_t bytes, vf_arena_t *arena)
{
    vf_params_t params;
    vf_params_default(&params);
    params.mode = mode; /* the runs do not depend on the mode; point keeps the arena small */
    vf_arena_init(arena, buf, bytes);
    vf_renderer_t *r = NULL;
    if (vf_renderer_create(&r, &params, vol, arena) != VF_OK ||
        vf_renderer_set_window(r, (vf_window_t){0, 255}) != VF_OK)
        return NULL;
    return r;
}

/* Parts 0 .. n - 1 in an order that differs from theirs (threads finish in any order): reversed, or odd ones
 * first, or some left out for end to run. */
static vf_status_t run_parts(vf_renderer_t *r, int order)
{
    const uint32_t n = vf_renderer_encode_parts(r);
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t q = order == 0 ? n - 1 - i : order == 1 ? (i < n / 2 ? 2 * i + 1 : 2 * (i - n / 2)) : i;
        if (order == 2 && q % 3 == 1)
            continue; /* left to vf_renderer_set_tf_end */
        vf_status_t s = vf_renderer_encode_part(r, q);
        if (s != VF_OK)
            return s;
    }
    return VF_OK;
}

/* The two renderers' run lists are the same to the byte and lie at the same offsets of their arenas. */
static void same_runs(const vf_renderer_t *w, const vf_renderer_t *p, const char *what)
{
    CHECK_MSG(w->have_runs && p->have_runs, "%s: run lists missing (whole %d, parts %d)", what, w->have_runs,
              p->have_runs);
    CHECK_MSG(w->arena->used == p->arena->used && w->needed == p->needed && w->memory.runs == p->memory.runs,
              "%s: arena used %zu / %zu, needed %zu / %zu, runs %zu / %zu", what, w->arena->used, p->arena->used,
              w->needed, p->needed, w->memory.runs, p->memory.runs);
    for (int a = 0; a < 3; a++) {
        const vfi_layout_t *l = &w->layout[a];
        const size_t rows = (size_t)(l->nk - 1) * l->nj + 1, values = w->runs[a].row_start[rows - 1];
        const size_t wi = (size_t)((const unsigned char *)w->runs[a].row_start - w->arena->base),
                     pi = (size_t)((const unsigned char *)p->runs[a].row_start - p->arena->base),
                     wp = (size_t)((const unsigned char *)w->runs[a].pairs - w->arena->base),
                     pp = (size_t)((const unsigned char *)p->runs[a].pairs - p->arena->base);
        CHECK_MSG(wi == pi && wp == pp && w->runs[a].nj == p->runs[a].nj,
                  "%s axis %d: index at %zu / %zu, pairs at %zu / %zu", what, a, wi, pi, wp, pp);
        CHECK_MSG(memcmp(w->runs[a].row_start, p->runs[a].row_start, rows * sizeof(uint32_t)) == 0,
                  "%s axis %d (dims %u %u %u): the indices differ", what, a, w->volume.dims[0], w->volume.dims[1],
                  w->volume.dims[2]);
        CHECK_MSG(memcmp(w->runs[a].pairs, p->runs[a].pairs, values * sizeof(uint16_t)) == 0,
                  "%s axis %d: the pairs differ", what, a);
    }
}

/* Random volumes, transfer functions from empty to full, 2 to 16 ranges a principal axis (more than some axes
 * have slabs, and counts that divide none evenly), parts in three orders: every run list as the whole encoding's. */
static void parts_match_whole(void)
{
    const uint32_t ranges[] = {2, 3, 4, 5, 7, 16};
    int encoded = 0;
    for (int t = 0; t < 60 && !check_failed; t++) {
        vf_volume_t vol = random_volume(t % 4 == 0 ? 40 : 12);
        vf_arena_t wa, pa;
        vf_renderer_t *w = make(&vol, VF_MODE_POINT, whole_buf, ARENA_BYTES, &wa);
        vf_renderer_t *p = make(&vol, VF_MODE_POINT, parts_buf, ARENA_BYTES, &pa);
        CHECK(w && p);
        for (int f = 0; f < 5 && !check_failed; f++) {
            const vf_tf_t tf = make_tf(f == 4 ? 3 + t : (t + f) % 4);
            const uint32_t n = ranges[(t + f) % 6];
            char what[96];
            snprintf(what, sizeof what, "volume %d tf %d, %u ranges", t, f, n);
            CHECK_EQ(vf_renderer_set_tf(w, &tf), VF_OK);
            CHECK_EQ(vf_renderer_set_tf_begin(p, &tf, n), VF_OK);
            CHECK_MSG(vf_renderer_encode_parts(p) == 3 * n, "%s: %u parts", what, vf_renderer_encode_parts(p));
            CHECK_EQ(run_parts(p, (t + f) % 3), VF_OK);
            CHECK_EQ(vf_renderer_set_tf_end(p), VF_OK);
            CHECK_EQ(vf_renderer_encode_parts(p), 0);
            same_runs(w, p, what);
            encoded++;
        }
    }
    if (!check_failed)
        CHECK_EQ(encoded, 300);
}

/* One range or none is the whole encoding in begin, and so are renderers without a window yet. */
static void begin_without_parts(void)
{
    vf_volume_t vol = random_volume(12);
    vf_arena_t wa, pa;
    vf_renderer_t *w = make(&vol, VF_MODE_POINT, whole_buf, ARENA_BYTES, &wa);
    vf_renderer_t *p = make(&vol, VF_MODE_POINT, parts_buf, ARENA_BYTES, &pa);
    CHECK(w && p);
    for (uint32_t n = 0; n < 2; n++) {
        const vf_tf_t tf = make_tf(3);
        CHECK_EQ(vf_renderer_set_tf(w, &tf), VF_OK);
        CHECK_EQ(vf_renderer_set_tf_begin(p, &tf, n), VF_OK);
        CHECK_EQ(vf_renderer_encode_parts(p), 0);
        CHECK_EQ(vf_renderer_set_tf_end(p), VF_OK); /* nothing to join */
        same_runs(w, p, "one range");
    }
    /* no window: classification alone, then the window's encoding */
    vf_params_t params;
    vf_params_default(&params);
    params.mode = VF_MODE_POINT;
    vf_arena_init(&pa, parts_buf, ARENA_BYTES);
    CHECK_EQ(vf_renderer_create(&p, &params, &vol, &pa), VF_OK);
    const vf_tf_t tf = make_tf(2);
    CHECK_EQ(vf_renderer_set_tf(w, &tf), VF_OK);
    CHECK_EQ(vf_renderer_set_tf_begin(p, &tf, 4), VF_OK);
    CHECK_EQ(vf_renderer_encode_parts(p), 0);
    CHECK_EQ(vf_renderer_set_window(p, (vf_window_t){0, 255}), VF_OK);
    same_runs(w, p, "window after");
}

/* Arguments and state: too many ranges, a part out of range, a frame before end, a transfer function that
 * replaces one whose parts are pending. */
static void parts_state(void)
{
    vf_volume_t vol = random_volume(12);
    vf_arena_t wa, pa;
    vf_renderer_t *w = make(&vol, VF_MODE_POINT, whole_buf, ARENA_BYTES, &wa);
    vf_renderer_t *p = make(&vol, VF_MODE_POINT, parts_buf, ARENA_BYTES, &pa);
    CHECK(w && p);
    vf_tf_t tf = make_tf(2);
    CHECK_EQ(vf_renderer_set_tf_begin(p, &tf, VF_MAX_ENCODE_PARTS / 3 + 1), VF_ERR_ARG);
    CHECK_EQ(vf_renderer_set_tf_begin(NULL, &tf, 2), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_encode_part(NULL, 0), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_set_tf_end(NULL), VF_ERR_NULL);
    CHECK_EQ(vf_renderer_set_tf_begin(p, &tf, 3), VF_OK);
    CHECK_EQ(vf_renderer_encode_parts(p), 9);
    CHECK_EQ(vf_renderer_encode_part(p, 9), VF_ERR_ARG);
    CHECK_EQ(vf_renderer_encode_part(p, 4), VF_OK);
    CHECK_EQ(vf_renderer_encode_part(p, 4), VF_OK); /* again: nothing more to do */
    const vf_frame_t frame = {.view = {0, 0, 0, 65536}, .width = 32, .height = 32};
    CHECK_EQ(vf_renderer_begin(p, &frame), VF_ERR_STATE); /* the run lists are not joined yet */
    /* a new transfer function in the middle: its whole encoding, the parts forgotten */
    tf = make_tf(3);
    CHECK_EQ(vf_renderer_set_tf(p, &tf), VF_OK);
    CHECK_EQ(vf_renderer_encode_parts(p), 0);
    CHECK_EQ(vf_renderer_encode_part(p, 0), VF_ERR_ARG);
    CHECK_EQ(vf_renderer_set_tf(w, &tf), VF_OK);
    same_runs(w, p, "replaced");
    CHECK_EQ(vf_renderer_begin(p, &frame), VF_OK);
}

/* Arenas from too small for the run lists to roomy: where a part's pairs outgrow its region, end encodes the
 * whole, so that status, run lists and needed bytes are set_tf's at every size. */
static void parts_short_arena(void)
{
    int overflowed = 0, nomem = 0, fitted = 0;
    for (int t = 0; t < 12 && !check_failed; t++) {
        vf_volume_t vol = random_volume(24);
        vf_arena_t wa, pa;
        vf_renderer_t *w = make(&vol, VF_MODE_POINT, whole_buf, ARENA_BYTES, &wa);
        CHECK(w);
        const vf_tf_t tf = make_tf(3 + t);
        CHECK_EQ(vf_renderer_set_tf(w, &tf), VF_OK);
        const size_t full = wa.used, mark = w->runs_mark;
        /* sizes from a little below the run lists' need to twice it */
        for (size_t extra = 0; extra < 2 * (full - mark) + 64 && !check_failed; extra += (full - mark) / 23 + 16) {
            const size_t bytes = mark + extra;
            vf_renderer_t *ws = make(&vol, VF_MODE_POINT, whole_buf, bytes, &wa);
            vf_renderer_t *ps = make(&vol, VF_MODE_POINT, parts_buf, bytes, &pa);
            CHECK(ws && ps);
            const vf_status_t want = vf_renderer_set_tf(ws, &tf);
            vf_status_t got = vf_renderer_set_tf_begin(ps, &tf, 4);
            const uint32_t parts = vf_renderer_encode_parts(ps);
            if (got == VF_OK && parts) {
                CHECK_EQ(run_parts(ps, 1), VF_OK);
                for (uint32_t q = 0; q < parts; q++)
                    overflowed += ps->part_values[q] > ps->part_capacity;
                got = vf_renderer_set_tf_end(ps);
            }
            CHECK_MSG(got == want, "arena %zu: parts %s, whole %s", bytes, vf_status_text(got), vf_status_text(want));
            CHECK_EQ(vf_renderer_needed_bytes(ps), vf_renderer_needed_bytes(ws));
            CHECK_EQ(ps->have_runs, ws->have_runs);
            if (want == VF_OK) {
                same_runs(ws, ps, "short arena");
                fitted++;
            } else {
                nomem++;
            }
        }
    }
    /* the sizes tried reach all three outcomes */
    CHECK_MSG(overflowed > 0 && nomem > 0 && fitted > 0, "overflowed %d, nomem %d, fitted %d", overflowed, nomem,
              fitted);
}

/* An allocation that fails after n others (the arena's fault injection), for every n up to success: begin, the
 * parts and end give what set_tf gives. */
static void parts_fault_loop(void)
{
    vf_volume_t vol = random_volume(16);
    const vf_tf_t tf = make_tf(3);
    int succeeded = 0;
    for (uint32_t n = 0; n < 12 && !check_failed; n++) {
        vf_arena_t wa, pa;
        vf_renderer_t *w = make(&vol, VF_MODE_POINT, whole_buf, ARENA_BYTES, &wa);
        vf_renderer_t *p = make(&vol, VF_MODE_POINT, parts_buf, ARENA_BYTES, &pa);
        CHECK(w && p);
        vfi_arena_fail_after(&wa, wa.allocs + n);
        vfi_arena_fail_after(&pa, pa.allocs + n);
        const vf_status_t want = vf_renderer_set_tf(w, &tf);
        vf_status_t got = vf_renderer_set_tf_begin(p, &tf, 3);
        if (got == VF_OK) {
            CHECK_EQ(run_parts(p, 0), VF_OK);
            got = vf_renderer_set_tf_end(p);
        }
        CHECK_MSG(got == want, "fault after %u: parts %s, whole %s", n, vf_status_text(got), vf_status_text(want));
        CHECK_EQ(vf_renderer_needed_bytes(p), vf_renderer_needed_bytes(w));
        CHECK_EQ(p->have_runs, w->have_runs);
        if (want == VF_OK) {
            same_runs(w, p, "fault loop");
            succeeded++;
        }
    }
    CHECK(succeeded > 0);
}

CHECK_CASES(CHECK_CASE(parts_match_whole), CHECK_CASE(begin_without_parts), CHECK_CASE(parts_state),
            CHECK_CASE(parts_short_arena), CHECK_CASE(parts_fault_loop));
CHECK_RUN("core/runs_parts")
