/* SPDX-License-Identifier: MIT */
/*
 * test_slices_runs.c: the window (core/slices.c: vfi_window_scalar), the three standard-order slice copies, and
 * the run-length encoding of visible cells (core/runs.c) against brute force.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "arena.h"
#include "check.h"
#include "renderer.h"

static uint64_t rng_state = 0x13198A2E03707344u;
static uint32_t rnd(uint32_t n)
{
    return check_mod(&rng_state, n);
}

/* s = clamp(round((v - lo) 255 / (hi - lo)), 0, 255), round half up, exactly. v, lo and hi are int32 values, so
 * |num| < 2^41 and every step is exact in int64 (32-bit targets have no __int128). */
static int spec_window(int64_t v, int64_t lo, int64_t hi)
{
    int64_t num = (v - lo) * 255, den = hi - lo;
    if (den < 0) {
        num = -num;
        den = -den;
    }
    /* floor((2 num + den) / (2 den)) with floor division */
    int64_t a = 2 * num + den, b = 2 * den;
    int64_t q = a / b;
    if (a % b != 0 && a < 0)
        q--;
    return q < 0 ? 0 : q > 255 ? 255 : (int)q;
}

static const vf_window_t windows[] = {
    {0, 255},         {0, 65535},          {-32768, 32767},      {-1024, 3071},        {-160, 240},
    {255, 0},         {100, 99},           {0, 1},               {1, 0},               {-2147483647, 2147483647},
    {INT32_MIN, INT32_MAX}, {2147483647, -2147483647}, {INT32_MAX, INT32_MIN}, {5, 4000000}, {-3, 4194300},
    {-3, 4194301},    {4194301, -3},       {1000, 1255},         {-128, 127},          {127, -128},
    {-50000, 70000},  {0, 510},            {0, 2},               {0, 3},
};

static void window_all_values(void)
{
    for (size_t w = 0; w < sizeof windows / sizeof windows[0]; w++) {
        vf_window_t win = windows[w];
        for (int32_t v = -32768; v <= 65535; v++) /* every u8, i8, u16 and i16 value */
            CHECK_MSG(vfi_window_scalar(v, win) == spec_window(v, win.lo, win.hi), "window (%d, %d) value %d: %u, want %d",
                      win.lo, win.hi, v, vfi_window_scalar(v, win), spec_window(v, win.lo, win.hi));
        const int32_t extremes[] = {INT32_MIN, INT32_MIN + 1, INT32_MAX, INT32_MAX - 1, win.lo, win.hi};
        for (size_t e = 0; e < 6; e++)
            CHECK_EQ(vfi_window_scalar(extremes[e], win), spec_window(extremes[e], win.lo, win.hi));
    }
    /* random windows and values over the whole int32 range */
    for (int t = 0; t < 2000000; t++) {
        vf_window_t win = {(int32_t)(uint32_t)check_rand64(&rng_state), (int32_t)(uint32_t)check_rand64(&rng_state)};
        if (t % 3 == 0) {
            int64_t hi = (int64_t)win.lo + (int64_t)rnd(5000) - 2500;
            win.hi = (int32_t)(hi < INT32_MIN ? INT32_MIN : hi > INT32_MAX ? INT32_MAX : hi);
        }
        if (win.lo == win.hi)
            continue;
        int64_t near = (int64_t)win.lo + (int64_t)rnd(20000) - 10000;
        int32_t v = t % 2 ? (int32_t)(uint32_t)check_rand64(&rng_state)
                          : (int32_t)(near < INT32_MIN ? INT32_MIN : near > INT32_MAX ? INT32_MAX : near);
        CHECK_MSG(vfi_window_scalar(v, win) == spec_window(v, win.lo, win.hi), "window (%d, %d) value %d", win.lo,
                  win.hi, v);
    }
    /* half-way values round up: (0, 2) maps 1 to 127.5 -> 128; descending (2, 0) maps 1 to 127.5 -> 128 */
    CHECK_EQ(vfi_window_scalar(1, (vf_window_t){0, 2}), 128);
    CHECK_EQ(vfi_window_scalar(1, (vf_window_t){2, 0}), 128);
    CHECK_EQ(vfi_window_scalar(7, (vf_window_t){0, 255}), 7);
}

/* ---- a renderer over a generated volume ------------------------------------------------------------- */

static _Alignas(16) unsigned char arena_buf[1 << 22];
static uint8_t vox8[32 * 32 * 32];
static uint16_t vox16[32 * 32 * 32];

/* A volume with structure: a few blobs plus noise, so that visible runs start and stop inside rows. */
static vf_volume_t random_volume(vf_voxel_t type, uint32_t maxdim)
{
    vf_volume_t v;
    for (int a = 0; a < 3; a++) {
        v.dims[a] = 2 + rnd(maxdim - 1);
        v.spacing_q16[a] = 65536;
    }
    v.type = type;
    uint32_t nx = v.dims[0], ny = v.dims[1], nz = v.dims[2];
    int cx = (int)rnd(nx), cy = (int)rnd(ny), cz = (int)rnd(nz), rad = 1 + (int)rnd(6);
    for (uint32_t z = 0; z < nz; z++)
        for (uint32_t y = 0; y < ny; y++)
            for (uint32_t x = 0; x < nx; x++) {
                int d2 = ((int)x - cx) * ((int)x - cx) + ((int)y - cy) * ((int)y - cy) + ((int)z - cz) * ((int)z - cz);
                uint32_t base = d2 < rad * rad ? 200 : 20;
                uint32_t val = base + rnd(40);
                if (rnd(10) == 0)
                    val = rnd(256);
                size_t at = ((size_t)z * ny + y) * nx + x;
                vox8[at] = (uint8_t)val;
                vox16[at] = (uint16_t)(val * 257 + rnd(257));
            }
    v.voxels = type == VF_VOXEL_U8 || type == VF_VOXEL_I8 ? (const void *)vox8 : (const void *)vox16;
    return v;
}

static int32_t raw_value(const vf_volume_t *v, size_t at)
{
    switch (v->type) {
    case VF_VOXEL_U8: return ((const uint8_t *)v->voxels)[at];
    case VF_VOXEL_I8: return (int8_t)((const uint8_t *)v->voxels)[at];
    case VF_VOXEL_U16: return ((const uint16_t *)v->voxels)[at];
    default: return (int16_t)((const uint16_t *)v->voxels)[at];
    }
}

static vf_tf_point_t tf_pts[8];

/* Random: a peak or a plateau somewhere, or several */
static vf_tf_t random_tf(void)
{
    uint32_t count = 1 + rnd(6), s = rnd(50000);
    for (uint32_t p = 0; p < count; p++) {
        if (p)
            s += rnd(20000);
        tf_pts[p] = (vf_tf_point_t){(uint16_t)(s > 65280 ? 65280 : s), 65535, 30000, 1000,
                                    (uint16_t)(rnd(3) == 0 ? 0 : rnd(65536))};
    }
    return (vf_tf_t){tf_pts, count};
}

static vf_renderer_t *make_renderer(const vf_volume_t *vol, uint32_t table_size, vf_arena_t *arena)
{
    vf_params_t params;
    vf_params_default(&params);
    params.table_size = table_size;
    if (table_size > 256)
        params.mode = VF_MODE_POINT; /* the runs do not depend on the mode; keep the arena small */
    vf_arena_init(arena, arena_buf, sizeof arena_buf);
    vf_renderer_t *r = NULL;
    if (vf_renderer_create(&r, &params, vol, arena) != VF_OK)
        return NULL;
    return r;
}

/* Every element of each copy is the windowed voxel of the object position it claims; padding repeats. */
static void check_copies(const vf_renderer_t *r, const vf_volume_t *vol, vf_window_t win)
{
    for (int ka = 0; ka < 3; ka++) {
        const vfi_layout_t *l = &r->layout[ka];
        const uint8_t *copy = r->slices[ka];
        if (l->i_axis != (ka + 1) % 3 || l->j_axis != (ka + 2) % 3 || l->ni != vol->dims[l->i_axis] ||
            l->nj != vol->dims[l->j_axis] || l->nk != vol->dims[ka] || l->row != l->ni + 1 ||
            l->slice != l->row * (l->nj + 1)) {
            check_fail(__FILE__, __LINE__, "layout of axis %d", ka);
            return;
        }
        for (uint32_t k = 0; k < l->nk; k++)
            for (uint32_t j = 0; j <= l->nj; j++)
                for (uint32_t i = 0; i <= l->ni; i++) {
                    uint32_t p[3];
                    p[ka] = k;
                    p[l->i_axis] = i < l->ni ? i : l->ni - 1;
                    p[l->j_axis] = j < l->nj ? j : l->nj - 1;
                    size_t at = ((size_t)p[2] * vol->dims[1] + p[1]) * vol->dims[0] + p[0];
                    int want = spec_window(raw_value(vol, at), win.lo, win.hi);
                    uint8_t got = copy[(size_t)k * l->slice + (size_t)j * l->row + i];
                    if (got != want) {
                        check_fail(__FILE__, __LINE__, "axis %d element (%u, %u, %u): %u, want %d", ka, i, j, k, got,
                                   want);
                        return;
                    }
                }
    }
}

static void slice_copies(void)
{
    const vf_voxel_t types[] = {VF_VOXEL_U8, VF_VOXEL_I8, VF_VOXEL_U16, VF_VOXEL_I16};
    const vf_window_t wins[] = {{0, 255}, {255, 0}, {-128, 127}, {0, 65535}, {-32768, 32767}, {30, 40}, {5000, 200}};
    for (int t = 0; t < 40; t++) {
        vf_volume_t vol = random_volume(types[t % 4], 12);
        vf_arena_t arena;
        vf_renderer_t *r = make_renderer(&vol, 256, &arena);
        CHECK(r != NULL);
        vf_window_t win = wins[rnd(7)];
        CHECK_EQ(vf_renderer_set_window(r, win), VF_OK);
        check_copies(r, &vol, win);
        if (check_failed)
            return;
        /* a second window replaces the first everywhere */
        vf_window_t win2 = wins[rnd(7)];
        CHECK_EQ(vf_renderer_set_window(r, win2), VF_OK);
        check_copies(r, &vol, win2);
        if (check_failed)
            return;
    }
    /* a flat 2x2x2 and a long thin volume */
    vf_volume_t thin = {{32, 2, 2}, {65536, 65536, 65536}, VF_VOXEL_U8, vox8};
    for (int n = 0; n < 128; n++)
        vox8[n] = (uint8_t)(n * 2);
    vf_arena_t arena;
    vf_renderer_t *r = make_renderer(&thin, 256, &arena);
    CHECK(r != NULL);
    CHECK_EQ(vf_renderer_set_window(r, (vf_window_t){0, 255}), VF_OK);
    check_copies(r, &thin, (vf_window_t){0, 255});
}

static void window_rejects_empty(void)
{
    vf_volume_t vol = random_volume(VF_VOXEL_U16, 6);
    vf_arena_t arena;
    vf_renderer_t *r = make_renderer(&vol, 256, &arena);
    CHECK(r != NULL);
    CHECK_EQ(vf_renderer_set_window(r, (vf_window_t){0, 1000}), VF_OK);
    const vf_window_t empty[] = {{0, 0}, {500, 500}, {INT32_MIN, INT32_MIN}, {INT32_MAX, INT32_MAX}, {-7, -7}};
    for (size_t n = 0; n < 5; n++)
        CHECK_EQ(vf_renderer_set_window(r, empty[n]), VF_ERR_WINDOW);
    CHECK_EQ(vf_renderer_set_window(NULL, (vf_window_t){0, 1}), VF_ERR_NULL);
    /* the slices from before stand */
    check_copies(r, &vol, (vf_window_t){0, 1000});
}

/* ---- runs ------------------------------------------------------------------------------------------- */

static uint8_t bitmap[32 * 33 * 33];

/* Decode the run lists of axis ka and compare them with a brute-force per-cell check. */
static void check_runs(const vf_renderer_t *r, int ka)
{
    const vfi_layout_t *l = &r->layout[ka];
    const vfi_runs_t *runs = &r->runs[ka];
    const vfi_classify_t *cls = &r->cls;
    const uint8_t *copy = r->slices[ka];
    uint32_t n = cls->n;
    if (runs->nj != l->nj) {
        check_fail(__FILE__, __LINE__, "runs nj");
        return;
    }
    memset(bitmap, 0, sizeof bitmap);
    for (uint32_t k = 0; k + 1 < l->nk; k++)
        for (uint32_t j = 0; j < l->nj; j++) {
            const uint16_t *end, *p = vfi_runs_row(runs, k, j, &end);
            if (end < p || (end - p) % 2) {
                check_fail(__FILE__, __LINE__, "row (%u, %u) has a broken pair list", k, j);
                return;
            }
            uint32_t pos = 0;
            for (; p < end; p += 2) {
                if (p[1] == 0 || (pos > 0 && p[0] == 0)) {
                    check_fail(__FILE__, __LINE__, "row (%u, %u): empty run or run not merged (%u, %u)", k, j, p[0],
                               p[1]);
                    return;
                }
                pos += p[0];
                if (pos + p[1] > l->ni) {
                    check_fail(__FILE__, __LINE__, "row (%u, %u) runs past the row", k, j);
                    return;
                }
                for (uint32_t i = pos; i < pos + p[1]; i++)
                    bitmap[((size_t)k * l->nj + j) * l->ni + i] = 1;
                pos += p[1];
            }
        }
    for (uint32_t k = 0; k + 1 < l->nk; k++)
        for (uint32_t j = 0; j < l->nj; j++)
            for (uint32_t i = 0; i < l->ni; i++) {
                uint32_t lo = 255, hi = 0;
                for (int c = 0; c < 8; c++) {
                    uint8_t v = copy[(size_t)(k + (c >> 2)) * l->slice + (size_t)(j + ((c >> 1) & 1)) * l->row + i +
                                     (c & 1)];
                    lo = v < lo ? v : lo;
                    hi = v > hi ? v : hi;
                }
                uint32_t e_lo = (lo * (n - 1) * 2 + 255) / 510, e_hi = (hi * (n - 1) * 2 + 255) / 510;
                bool visible = false;
                for (uint32_t e = e_lo; e <= e_hi; e++)
                    visible |= cls->tau_q28[e] > 0;
                if (visible != bitmap[((size_t)k * l->nj + j) * l->ni + i]) {
                    check_fail(__FILE__, __LINE__, "axis %d cell (%u, %u, %u): range %u..%u visible %d, runs say %d", ka,
                               i, j, k, lo, hi, visible, bitmap[((size_t)k * l->nj + j) * l->ni + i]);
                    return;
                }
            }
}

static void runs_random(void)
{
    const uint32_t sizes[] = {256, 64, 2, 1000, 255};
    const vf_voxel_t types[] = {VF_VOXEL_U8, VF_VOXEL_I8, VF_VOXEL_U16, VF_VOXEL_I16};
    const vf_window_t wins[] = {{0, 255}, {-128, 127}, {0, 65535}, {-32768, 32767}};
    for (int t = 0; t < 60; t++) {
        vf_volume_t vol = random_volume(types[t % 4], 16);
        vf_arena_t arena;
        vf_renderer_t *r = make_renderer(&vol, sizes[t % 5], &arena);
        CHECK(r != NULL);
        /* window first or transfer function first: both orders build the runs */
        vf_tf_t tf = random_tf();
        if (t % 2) {
            CHECK_EQ(vf_renderer_set_window(r, wins[t % 4]), VF_OK);
            CHECK_EQ(vf_renderer_set_tf(r, &tf), VF_OK);
        } else {
            CHECK_EQ(vf_renderer_set_tf(r, &tf), VF_OK);
            CHECK_EQ(vf_renderer_set_window(r, wins[t % 4]), VF_OK);
        }
        for (int ka = 0; ka < 3 && !check_failed; ka++)
            check_runs(r, ka);
        if (check_failed)
            return;
        /* a new transfer function rebuilds them */
        tf = random_tf();
        CHECK_EQ(vf_renderer_set_tf(r, &tf), VF_OK);
        for (int ka = 0; ka < 3 && !check_failed; ka++)
            check_runs(r, ka);
        if (check_failed)
            return;
    }
}

static void runs_all_or_nothing(void)
{
    vf_volume_t vol = random_volume(VF_VOXEL_U8, 16);
    vf_arena_t arena;
    vf_renderer_t *r = make_renderer(&vol, 256, &arena);
    CHECK(r != NULL);
    CHECK_EQ(vf_renderer_set_window(r, (vf_window_t){0, 255}), VF_OK);
    vf_tf_point_t none = {0, 65535, 65535, 65535, 0};
    vf_tf_t tf = {&none, 1};
    CHECK_EQ(vf_renderer_set_tf(r, &tf), VF_OK);
    vf_memory_t mem;
    vf_renderer_memory(r, &mem);
    size_t index_bytes = 0;
    for (int ka = 0; ka < 3; ka++) {
        const vfi_layout_t *l = &r->layout[ka];
        index_bytes += vfi_runs_index_bytes(l);
        for (uint32_t row = 0; row <= (l->nk - 1) * l->nj; row++)
            CHECK_EQ(r->runs[ka].row_start[row], 0); /* every row empty */
        check_runs(r, ka);
    }
    CHECK_EQ(mem.runs, index_bytes + 3 * VFI_ALIGN); /* the row index, and the one-value block each axis keeps */

    vf_tf_point_t all = {0, 65535, 65535, 65535, 1};
    tf = (vf_tf_t){&all, 1};
    CHECK_EQ(vf_renderer_set_tf(r, &tf), VF_OK);
    for (int ka = 0; ka < 3; ka++) {
        const vfi_layout_t *l = &r->layout[ka];
        for (uint32_t k = 0; k + 1 < l->nk; k++)
            for (uint32_t j = 0; j < l->nj; j++) {
                const uint16_t *end, *p = vfi_runs_row(&r->runs[ka], k, j, &end);
                CHECK_EQ(end - p, 2);
                CHECK_EQ(p[0], 0);
                CHECK_EQ(p[1], l->ni);
            }
    }
}

/* The encoder's count-only pass and its filling pass agree (the renderer sizes memory with the first). */
static void runs_count_matches_fill(void)
{
    for (int t = 0; t < 20; t++) {
        vf_volume_t vol = random_volume(VF_VOXEL_U8, 16);
        vf_arena_t arena;
        vf_renderer_t *r = make_renderer(&vol, 256, &arena);
        CHECK(r != NULL);
        CHECK_EQ(vf_renderer_set_window(r, (vf_window_t){0, 255}), VF_OK);
        vf_tf_t tf = random_tf();
        CHECK_EQ(vf_renderer_set_tf(r, &tf), VF_OK);
        for (int ka = 0; ka < 3; ka++) {
            size_t count = vfi_runs_encode(r->slices[ka], &r->layout[ka], &r->cls, &r->bricks, NULL, NULL, 0);
            const vfi_layout_t *l = &r->layout[ka];
            CHECK_EQ(count, r->runs[ka].row_start[(l->nk - 1) * l->nj]);
        }
    }
}

/* ---- bricks ----------------------------------------------------------------------------------------- */

static uint16_t pairs_cells[32 * 33 * 33], pairs_bricks[32 * 33 * 33];
static uint32_t index_cells[32 * 33 + 1], index_bricks[32 * 33 + 1];

/* A value at or beside an edge of runs_bricks_match_cells's intervals (multiples of 32 and their neighbours),
 * where an off-by-one in a brick's test would show, or any value. */
static uint32_t edge_value(void)
{
    if (rnd(4) == 0)
        return rnd(256);
    const int v = 32 * (int)rnd(9) + (int)rnd(3) - 1;
    return v < 0 ? 0 : v > 255 ? 255 : (uint32_t)v;
}

/* A volume of up to 32 a side whose bricks come out empty, solid and mixed: plateaus of one value with a sphere
 * and a slab of others in them, edges between them soft or hard, and noise in some volumes only. */
static vf_volume_t brick_volume(void)
{
    vf_volume_t v;
    for (int a = 0; a < 3; a++) {
        v.dims[a] = 2 + rnd(31);
        v.spacing_q16[a] = 65536;
    }
    v.type = VF_VOXEL_U8;
    const uint32_t nx = v.dims[0], ny = v.dims[1], nz = v.dims[2];
    const int cx = (int)rnd(nx), cy = (int)rnd(ny), cz = (int)rnd(nz), rad = 1 + (int)rnd(14);
    const uint32_t outside = edge_value(), inside = edge_value(), slab = edge_value(), slab_z = rnd(nz),
                   noise = rnd(3);
    const uint32_t soft = rnd(2);
    for (uint32_t z = 0; z < nz; z++)
        for (uint32_t y = 0; y < ny; y++)
            for (uint32_t x = 0; x < nx; x++) {
                int d2 = ((int)x - cx) * ((int)x - cx) + ((int)y - cy) * ((int)y - cy) + ((int)z - cz) * ((int)z - cz);
                uint32_t val = d2 < rad * rad ? inside : outside;
                if (soft && d2 >= rad * rad && d2 < (rad + 2) * (rad + 2))
                    val = (inside + outside) / 2;
                if (z == slab_z)
                    val = slab;
                if (noise && rnd(400 / noise) == 0)
                    val = rnd(256);
                vox8[((size_t)z * ny + y) * nx + x] = (uint8_t)val;
            }
    v.voxels = vox8;
    return v;
}

/* The encoder with bricks gives every axis the run lists and row index of reading every cell. */
static void compare_bricks(const vf_renderer_t *r, const char *what, uint32_t a, uint32_t b)
{
    for (int ka = 0; ka < 3; ka++) {
        const vfi_layout_t *l = &r->layout[ka];
        const size_t rows = (size_t)(l->nk - 1) * l->nj + 1, capacity = sizeof pairs_cells / sizeof pairs_cells[0];
        const size_t want = vfi_runs_encode(r->slices[ka], l, &r->cls, NULL, index_cells, pairs_cells, capacity);
        const size_t got = vfi_runs_encode(r->slices[ka], l, &r->cls, &r->bricks, index_bricks, pairs_bricks, capacity);
        CHECK_MSG(got == want && want <= capacity, "%s %u..%u axis %d: %zu values with bricks, %zu cell by cell", what,
                  a, b, ka, got, want);
        CHECK_MSG(memcmp(index_cells, index_bricks, rows * sizeof index_cells[0]) == 0 &&
                      memcmp(pairs_cells, pairs_bricks, want * sizeof pairs_cells[0]) == 0,
                  "%s %u..%u axis %d (dims %u %u %u): the run lists differ", what, a, b, ka, r->volume.dims[0],
                  r->volume.dims[1], r->volume.dims[2]);
        if (check_failed)
            return;
    }
}

/* Every transfer function that is visible on one interval of scalars [a, b] (opacity 0 outside, in steps or
 * in ramps), for every a <= b on a grid of 32 scalars and their neighbours, in tables of 256, 17 and 1000 entries
 * and both lookups: the bricks settle them all as reading every cell does. Then random transfer functions. */
static void runs_bricks_match_cells(void)
{
    const uint32_t sizes[] = {256, 17, 1000};
    const vf_lookup_t lookups[] = {VF_LOOKUP_NEAREST, VF_LOOKUP_BILINEAR};
    for (int t = 0; t < 24 && !check_failed; t++) {
        vf_volume_t vol = brick_volume();
        vf_params_t params;
        vf_params_default(&params);
        params.mode = VF_MODE_POINT; /* the runs do not depend on the mode; keep the arena small */
        params.table_size = sizes[t % 3];
        params.lookup = lookups[(t / 3) % 2];
        vf_arena_t arena;
        vf_arena_init(&arena, arena_buf, sizeof arena_buf);
        vf_renderer_t *r = NULL;
        CHECK_EQ(vf_renderer_create(&r, &params, &vol, &arena), VF_OK);
        CHECK_EQ(vf_renderer_set_window(r, (vf_window_t){0, 255}), VF_OK);
        if (check_failed)
            return;
        for (uint32_t a = 0; a < 256 && !check_failed; a += (a % 32 == 0 ? 1 : a % 32 == 1 ? 30 : 1)) {
            for (uint32_t b = a; b < 256 && !check_failed; b += (b % 32 == 0 ? 1 : b % 32 == 1 ? 30 : 1)) {
                const uint16_t lo = (uint16_t)(a * 256), hi = (uint16_t)(b * 256), ramp = (uint16_t)(t % 2 ? 256 : 1);
                vf_tf_point_t pts[4] = {{lo > ramp ? (uint16_t)(lo - ramp) : 0, 65535, 65535, 65535, 0},
                                        {lo, 65535, 65535, 65535, 40000},
                                        {hi, 65535, 65535, 65535, 40000},
                                        {hi < 65280 - ramp ? (uint16_t)(hi + ramp) : 65280, 65535, 65535, 65535, 0}};
                vf_tf_t tf = {pts, 4};
                CHECK_EQ(vfi_classify(&r->cls, &tf), VF_OK);
                compare_bricks(r, "interval", a, b);
            }
        }
        for (int u = 0; u < 40 && !check_failed; u++) {
            vf_tf_t tf = random_tf();
            CHECK_EQ(vfi_classify(&r->cls, &tf), VF_OK);
            compare_bricks(r, "random", (uint32_t)u, 0);
        }
    }
}

/* Bricks of the last window: a new window makes them again (the runs of the new slices are checked cell by cell). */
static void runs_bricks_follow_window(void)
{
    for (int t = 0; t < 10 && !check_failed; t++) {
        vf_volume_t vol = brick_volume();
        vf_arena_t arena;
        vf_renderer_t *r = make_renderer(&vol, 256, &arena);
        CHECK(r != NULL);
        vf_tf_t tf = random_tf();
        CHECK_EQ(vf_renderer_set_tf(r, &tf), VF_OK);
        const vf_window_t wins[] = {{0, 255}, {100, 140}, {255, 0}};
        for (int w = 0; w < 3 && !check_failed; w++) {
            CHECK_EQ(vf_renderer_set_window(r, wins[w]), VF_OK);
            for (int ka = 0; ka < 3 && !check_failed; ka++)
                check_runs(r, ka);
            compare_bricks(r, "window", (uint32_t)w, 0);
        }
    }
}

CHECK_CASES(CHECK_CASE(window_all_values), CHECK_CASE(slice_copies), CHECK_CASE(window_rejects_empty),
            CHECK_CASE(runs_random), CHECK_CASE(runs_all_or_nothing), CHECK_CASE(runs_count_matches_fill),
            CHECK_CASE(runs_bricks_match_cells), CHECK_CASE(runs_bricks_follow_window));
CHECK_RUN("core/slices_runs")
