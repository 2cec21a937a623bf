/* SPDX-License-Identifier: MIT */
/*
 * test_faults.c: SQLite-style fault loops over the renderer's memory (core/renderer.c with core/arena.c).
 *
 * Every run with an arena that fails after N allocations, or that is N bytes long, must give either the right
 * result or VF_ERR_NOMEM, never a crash or a half-built renderer, and what follows a failure must either work
 * or say VF_ERR_STATE. Operations that could crash run in a child process, so that a crash is a failed case and
 * not the end of the suite.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"
#include "frame.h"
#include "scene_fixture.h"
#include "volfix.h"
#include "volfix_internal.h"

#define NX 9
#define NY 7
#define NZ 6
static uint8_t vox[NX * NY * NZ];
static _Alignas(16) unsigned char arena_buf[1 << 20];
static _Alignas(16) unsigned char fresh_buf[1 << 20];
static _Alignas(16) unsigned char scratch[1 << 16];
static unsigned char pixels[2][32 * 32 * 3];

static const vf_volume_t volume = {{NX, NY, NZ}, {65536, 65536, 65536}, VF_VOXEL_U8, vox};

/* A ball of high values in a low background. */
static int ball(int x, int y, int z)
{
    return (x - 4) * (x - 4) + (y - 3) * (y - 3) + (z - 3) * (z - 3) <= 6 ? 200 : 40;
}

/* The ball with 5 bits of noise. */
static void fill_volume(void)
{
    scene_fill_shape(vox, volume.dims, ball, 12345, 5);
}

static vf_params_t params_of(vf_mode_t mode)
{
    vf_params_t p;
    vf_params_default(&p);
    p.mode = mode;
    p.table_size = 64;
    p.table2_size = 16; /* preint2: its 3D table, pieces and 2D table in the arena too */
    return p;
}

/* The fault loops' modes: point, preint1, preint2. */
static vf_mode_t mode_of(int m)
{
    return m == 0 ? VF_MODE_POINT : m == 1 ? VF_MODE_PREINT1 : VF_MODE_PREINT2;
}

/* A dense transfer function (many runs) and a sparse one (few). */
static const vf_tf_point_t dense_pts[4] = {
    {0, 65535, 0, 0, 0}, {60 * 256, 65535, 30000, 0, 3000}, {150 * 256, 0, 65535, 0, 0}, {220 * 256, 0, 0, 65535, 9000}};
static const vf_tf_point_t sparse_pts[3] = {{222 * 256, 0, 0, 0, 0}, {226 * 256, 65535, 65535, 65535, 20000}, {230 * 256, 0, 0, 0, 0}};
static const vf_tf_t dense = {dense_pts, 4};
static const vf_tf_t sparse = {sparse_pts, 3};

static const vf_view_t view_z = {1000, 2000, 300, 65536};  /* principal axis z */
static const vf_view_t view_x = {16384, 500, 0, 65536};    /* principal axis x */

/* Run fn(arg) in a child process: its vf_status_t, or -1 when the child died (a signal, or a sanitizer's exit);
 * the child's stderr goes to /dev/null so that a crash report does not clutter the suite's output. */
static int in_child(int (*fn)(void *), void *arg)
{
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid < 0)
        return -1000;
    if (pid == 0) {
        if (!freopen("/dev/null", "w", stderr))
            _exit(99);
        _exit(100 + fn(arg));
    }
    int status = 0;
    if (waitpid(pid, &status, 0) != pid)
        return -1001;
    if (WIFEXITED(status) && WEXITSTATUS(status) >= 100)
        return WEXITSTATUS(status) - 100;
    return -1;
}

/* The reference picture: a renderer with plenty of memory. */
static void render_reference(vf_mode_t mode, const vf_tf_t *tf, const vf_view_t *view, unsigned char *out)
{
    vf_params_t p = params_of(mode);
    vf_arena_t arena;
    vf_renderer_t *r;
    vf_image_t im = {out, 32, 32, 96, VF_FORMAT_RGB888};
    if (scene_renderer(&r, &arena, fresh_buf, sizeof fresh_buf, &p, &volume, tf) ||
        vf_renderer_draw(r, view, &im, scratch, sizeof scratch))
        check_fail(__FILE__, __LINE__, "reference render failed");
}

/* Draws r's frame of view into pixels[0] and compares it with the reference picture: false, with the case
 * failed, when the draw fails or a pixel differs. */
static bool draws_reference(vf_renderer_t *r, vf_mode_t mode, const vf_tf_t *tf, const vf_view_t *view)
{
    vf_image_t im = {pixels[0], 32, 32, 96, VF_FORMAT_RGB888};
    vf_status_t s = vf_renderer_draw(r, view, &im, scratch, sizeof scratch);
    if (s != VF_OK) {
        check_fail(__FILE__, __LINE__, "draw: %s", vf_status_text(s));
        return false;
    }
    render_reference(mode, tf, view, pixels[1]);
    if (memcmp(pixels[0], pixels[1], sizeof pixels[0]) != 0) {
        check_fail(__FILE__, __LINE__, "%s: the picture differs from a fresh renderer's", vf_mode_name(mode));
        return false;
    }
    return !check_failed;
}

/* ---- (a) create ----------------------------------------------------------------------------------- */

static void create_fault_loop(void)
{
    fill_volume();
    for (int m = 0; m < 3; m++) {
        vf_params_t p = params_of(mode_of(m));
        int succeeded = 0;
        for (uint32_t fail = 1; fail < 100 && !succeeded; fail++) {
            vf_arena_t arena;
            vf_arena_init(&arena, arena_buf, sizeof arena_buf);
            vfi_arena_fail_after(&arena, fail);
            vf_renderer_t *r = (vf_renderer_t *)&arena; /* must come back NULL on failure */
            vf_status_t s = vf_renderer_create(&r, &p, &volume, &arena);
            if (s == VF_OK) {
                CHECK(r != NULL);
                succeeded = 1;
                CHECK(fail >= 5); /* at least renderer, three slices and the tables */
                /* and it works */
                vfi_arena_fail_after(&arena, 0);
                CHECK_EQ(vf_renderer_set_window(r, (vf_window_t){0, 255}), VF_OK);
                CHECK_EQ(vf_renderer_set_tf(r, &dense), VF_OK);
                if (!draws_reference(r, p.mode, &dense, &view_z))
                    return;
            } else {
                CHECK_MSG(s == VF_ERR_NOMEM, "fail_after %u: %s", fail, vf_status_text(s));
                CHECK_MSG(r == NULL, "fail_after %u: *out not NULL after a failure", fail);
            }
        }
        CHECK(succeeded);
    }
}

/* Every buffer size from 0 to vf_renderer_bytes, aligned and misaligned: VF_OK or VF_ERR_NOMEM, success from
 * some size on, and always at vf_renderer_bytes itself. */
static void create_every_size(void)
{
    fill_volume();
    for (int m = 0; m < 3; m++) {
        vf_params_t p = params_of(mode_of(m));
        size_t bytes = 0;
        CHECK_EQ(vf_renderer_bytes(&p, &volume, &bytes), VF_OK);
        CHECK(bytes < sizeof arena_buf - 64);
        for (size_t off = 0; off < 16; off += 5) {
            int ok_seen = 0;
            for (size_t size = 0; size <= bytes + 16; size++) {
                vf_arena_t arena;
                vf_arena_init(&arena, arena_buf + off, size);
                vf_renderer_t *r = (vf_renderer_t *)&arena;
                vf_status_t s = vf_renderer_create(&r, &p, &volume, &arena);
                if (s == VF_OK) {
                    CHECK(r != NULL);
                    CHECK(arena.used <= size);
                    ok_seen = 1;
                } else {
                    CHECK_MSG(s == VF_ERR_NOMEM, "size %zu: %s", size, vf_status_text(s));
                    CHECK(r == NULL);
                    CHECK_MSG(!ok_seen, "size %zu fails after a smaller size succeeded", size);
                    CHECK_MSG(size < bytes, "vf_renderer_bytes (%zu) is not enough at offset %zu", bytes, off);
                }
            }
            CHECK(ok_seen);
        }
        /* one byte short, at every misalignment: never a crash, VF_OK or VF_ERR_NOMEM */
        for (size_t off = 0; off < 16; off++) {
            vf_arena_t arena;
            vf_arena_init(&arena, arena_buf + off, bytes - 1);
            vf_renderer_t *r = NULL;
            vf_status_t s = vf_renderer_create(&r, &p, &volume, &arena);
            CHECK(s == VF_OK || (s == VF_ERR_NOMEM && r == NULL));
        }
    }
}

/* ---- (b) set_tf short of memory ----------------------------------------------------------------------- */

typedef struct frame_job {
    vf_renderer_t *r;
} frame_job_t;

static int job_composite(void *arg)
{
    frame_job_t *job = arg;
    const vf_factor_t *f = vf_renderer_factor(job->r);
    uint32_t rows = f ? f->int_h : 1;
    return vf_renderer_composite_band(job->r, 0, rows, scratch, sizeof scratch);
}

static int job_render(void *arg)
{
    frame_job_t *job = arg;
    vf_image_t im = {pixels[0], 32, 32, 96, VF_FORMAT_RGB888};
    return vf_renderer_draw(job->r, &view_x, &im, scratch, sizeof scratch);
}

/* Allocation-failure points inside vf_renderer_set_tf (the run lists), for both principal axes of the frame
 * that was in progress. */
static void set_tf_fault_loop(void)
{
    fill_volume();
    for (int m = 0; m < 3; m++)
        for (int v = 0; v < 2; v++) {
            const vf_view_t *view = v ? &view_x : &view_z;
            vf_params_t p = params_of(mode_of(m));
            int succeeded = 0;
            for (uint32_t extra = 0; extra < 50 && !succeeded; extra++) {
                vf_arena_t arena;
                vf_renderer_t *r;
                CHECK_EQ(scene_renderer(&r, &arena, arena_buf, sizeof arena_buf, &p, &volume, &sparse), VF_OK);
                CHECK_EQ(begin_frame(r, view, 32, 32, 0, false), VF_OK); /* a frame in progress */
                vfi_arena_fail_after(&arena, arena.allocs + extra);
                vf_status_t s = vf_renderer_set_tf(r, &dense);
                if (s == VF_OK) {
                    succeeded = 1;
                    continue;
                }
                CHECK_MSG(s == VF_ERR_NOMEM, "extra %u: %s", extra, vf_status_text(s));
                /* no half-built picture: a whole frame says VF_ERR_STATE ... */
                frame_job_t job = {r};
                int rc = in_child(job_render, &job);
                CHECK_MSG(rc == VF_ERR_STATE, "%s, axis %s, fail after %u more: vf_render after VF_ERR_NOMEM gave %d%s",
                          vf_mode_name(p.mode), v ? "x" : "z", extra, rc, rc < 0 ? " (crashed)" : "");
                /* ... and so do the bands of the frame begun before the failure (CORE BUG if they composite
                 * with the half-built run lists: vf_renderer_set_tf does not end the frame) */
                CHECK_EQ(begin_frame(r, view, 32, 32, 0, false), VF_ERR_STATE);
                rc = in_child(job_composite, &job);
                CHECK_MSG(rc == VF_ERR_STATE, "composite after a failed begin gave %d", rc);
            }
            CHECK(succeeded);
        }
}

/* The same, with the band of the frame in progress composited right after the failure (no new begin). Every
 * failure point of the run lists, both modes, a frame along z and one along x; the outcomes are collected so
 * that one message lists them all. CORE BUG (renderer.c, vf_renderer_set_tf / encode_runs): the failure leaves
 * have_frame true, so vf_renderer_composite_band goes on with run lists that are half-built (a NULL pairs array, or
 * row indices over memory the rewind gave back): VF_OK with a wrong picture, or a crash. */
static void set_tf_failure_inside_frame(void)
{
    fill_volume();
    char report[1024] = "";
    int bad = 0;
    for (int m = 0; m < 3; m++)
        for (int v = 0; v < 2; v++) {
            const vf_view_t *view = v ? &view_x : &view_z;
            vf_params_t p = params_of(mode_of(m));
            for (uint32_t extra = 0; extra < 6; extra++) {
                vf_arena_t arena;
                vf_renderer_t *r;
                CHECK_EQ(scene_renderer(&r, &arena, arena_buf, sizeof arena_buf, &p, &volume, &sparse), VF_OK);
                CHECK_EQ(begin_frame(r, view, 32, 32, 0, false), VF_OK);
                vfi_arena_fail_after(&arena, arena.allocs + extra);
                if (vf_renderer_set_tf(r, &dense) == VF_OK)
                    break;
                frame_job_t job = {r};
                int rc = in_child(job_composite, &job);
                if (rc != VF_ERR_STATE) {
                    bad++;
                    size_t len = strlen(report);
                    snprintf(report + len, sizeof report - len, " [%s %s alloc %u: %s]", vf_mode_name(p.mode),
                             v ? "x" : "z", extra + 1,
                             rc < 0 ? "crash" : rc == VF_OK ? "VF_OK" : vf_status_text((vf_status_t)rc));
                }
            }
        }
    CHECK_MSG(bad == 0, "vf_renderer_composite_band after vf_renderer_set_tf failed inside a frame, expected VF_ERR_STATE:%s",
              report);
}

/* An arena too small for the run lists: VF_ERR_NOMEM, a needed size with which a fresh renderer succeeds, and
 * VF_ERR_STATE for a frame; then (c) a transfer function that fits, or a larger arena, gives the right picture. */
static void set_tf_short_arena(void)
{
    fill_volume();
    for (int m = 0; m < 3; m++) {
        vf_params_t p = params_of(mode_of(m));
        size_t bytes = 0;
        CHECK_EQ(vf_renderer_bytes(&p, &volume, &bytes), VF_OK);
        for (size_t spare = 0; spare < 4096; spare += 97) {
            vf_arena_t arena;
            vf_arena_init(&arena, arena_buf, bytes + spare);
            vf_renderer_t *r = NULL;
            CHECK_EQ(vf_renderer_create(&r, &p, &volume, &arena), VF_OK);
            vf_status_t s = vf_renderer_set_window(r, (vf_window_t){0, 255});
            if (s == VF_OK)
                s = vf_renderer_set_tf(r, &dense);
            if (s == VF_OK) {
                CHECK(vf_renderer_needed_bytes(r) <= bytes + spare + 16);
                continue;
            }
            CHECK_EQ(s, VF_ERR_NOMEM);
            size_t needed = vf_renderer_needed_bytes(r);
            CHECK_MSG(needed > arena.size - 16 || needed > bytes, "needed %zu with an arena of %zu", needed, arena.size);
            /* no picture from a half-built renderer */
            frame_job_t job = {r};
            CHECK_EQ(in_child(job_render, &job), VF_ERR_STATE);
            /* a fresh renderer in exactly the reported size succeeds, at any alignment */
            for (size_t off = 0; off < 16; off += 3) {
                vf_arena_t fresh;
                vf_arena_init(&fresh, fresh_buf + off, needed);
                vf_renderer_t *r2 = NULL;
                CHECK_EQ(vf_renderer_create(&r2, &p, &volume, &fresh), VF_OK);
                CHECK_EQ(vf_renderer_set_window(r2, (vf_window_t){0, 255}), VF_OK);
                CHECK_MSG(vf_renderer_set_tf(r2, &dense) == VF_OK, "needed %zu is not enough at offset %zu", needed,
                          off);
            }
            /* (c) the failed renderer recovers: first a transfer function whose runs fit ... */
            s = vf_renderer_set_tf(r, &sparse);
            if (s == VF_OK) {
                if (!draws_reference(r, p.mode, &sparse, &view_z))
                    return;
            } else {
                CHECK_EQ(s, VF_ERR_NOMEM);
            }
            /* ... then the dense one again after the caller grows the arena (same buffer, larger size) */
            arena.size = needed;
            CHECK_EQ(vf_renderer_set_tf(r, &dense), VF_OK);
            if (!draws_reference(r, p.mode, &dense, &view_x))
                return;
        }
    }
}

/* vf_renderer_set_window rebuilds the runs too: the same contract when it runs short. */
static void set_window_short_arena(void)
{
    fill_volume();
    vf_params_t p = params_of(VF_MODE_PREINT1);
    size_t bytes = 0;
    CHECK_EQ(vf_renderer_bytes(&p, &volume, &bytes), VF_OK);
    vf_arena_t arena;
    vf_arena_init(&arena, arena_buf, bytes);
    vf_renderer_t *r = NULL;
    CHECK_EQ(vf_renderer_create(&r, &p, &volume, &arena), VF_OK);
    CHECK_EQ(vf_renderer_set_tf(r, &dense), VF_OK); /* no window yet: nothing to encode */
    vf_status_t s = vf_renderer_set_window(r, (vf_window_t){0, 255});
    CHECK_EQ(s, VF_ERR_NOMEM);
    frame_job_t job = {r};
    CHECK_EQ(in_child(job_render, &job), VF_ERR_STATE);
    arena.size = vf_renderer_needed_bytes(r);
    CHECK_EQ(vf_renderer_set_window(r, (vf_window_t){0, 255}), VF_OK);
    draws_reference(r, p.mode, &dense, &view_x);
}

/* Memory reports add up. */
static void memory_report(void)
{
    fill_volume();
    vf_params_t p = params_of(VF_MODE_PREINT1);
    size_t bytes = 0;
    CHECK_EQ(vf_renderer_bytes(&p, &volume, &bytes), VF_OK);
    vf_arena_t arena;
    vf_renderer_t *r;
    CHECK_EQ(scene_renderer(&r, &arena, arena_buf, sizeof arena_buf, &p, &volume, &dense), VF_OK);
    vf_memory_t mem;
    vf_renderer_memory(r, &mem);
    CHECK_EQ(mem.total, arena.used);
    CHECK_EQ(mem.renderer + mem.slices + mem.classify + mem.tables + mem.intermediate + mem.runs, arena.used);
    CHECK(bytes >= arena.used - mem.runs);
    CHECK(vf_renderer_needed_bytes(r) >= arena.used);
    /* a sparser transfer function needs fewer run bytes, and the arena is reused (rewound), not grown */
    size_t dense_runs = mem.runs;
    CHECK_EQ(vf_renderer_set_tf(r, &sparse), VF_OK);
    vf_renderer_memory(r, &mem);
    CHECK(mem.runs < dense_runs);
    CHECK_EQ(mem.total, arena.used);
    for (int n = 0; n < 50; n++)
        CHECK_EQ(vf_renderer_set_tf(r, n % 2 ? &dense : &sparse), VF_OK);
    CHECK(arena.peak <= bytes + dense_runs + 16);
}

CHECK_CASES(CHECK_CASE(create_fault_loop), CHECK_CASE(create_every_size), CHECK_CASE(set_tf_fault_loop),
            CHECK_CASE(set_tf_failure_inside_frame), CHECK_CASE(set_tf_short_arena), CHECK_CASE(set_window_short_arena),
            CHECK_CASE(memory_report));
CHECK_RUN("core/faults")
