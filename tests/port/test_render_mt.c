/* SPDX-License-Identifier: MIT */
/*
 * test_render_mt.c: port/render/render_mt.c, the renderer with its worker pool:
 *   - 1, 2, 3 and 4 threads give the same pixels, frame after frame (each view a new slab length, so a new table:
 *     built as read on one thread, in parts with more), for every mode, lit and unlit, the table options that take
 *     other paths (bilinear lookup, the lut's view table, 8-bit entries, the image-sized buffer, rays, partial
 *     slabs), and every pixel format; a transfer-function change and a window change between frames included;
 *   - a transfer function moved step by step, its run lists encoded in parts on the threads: the frames and run
 *     lists' memory of one thread after every move;
 *   - renderers opened and closed in a loop, with and without frames, start and join their workers (a hang or a
 *     leak shows here, under the sanitizers).
 */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/tf.h"
#include "io/volume.h"
#include "render/image.h"
#include "render/render_mt.h"

#define W 77 /* odd sizes: bands and table parts that do not divide the rows evenly */
#define H 61
#define FRAMES 4

typedef struct variant {
    const char *name;
    vf_mode_t mode;
    bool lighting;
    vf_lookup_t lookup, shade_lookup;
    vf_correction_t correction;
    vf_buffer_t buffer;
    uint32_t table_bits, rays, table2_size;
    bool partial_slabs;
} variant_t;

static const variant_t variants[] = {
    {"preint1", VF_MODE_PREINT1, false, VF_LOOKUP_NEAREST, VF_LOOKUP_NEAREST, VF_CORRECTION_REBUILD, VF_BUFFER_SLICE,
     16, 1, 0, false},
    {"preint1 lit", VF_MODE_PREINT1, true, VF_LOOKUP_NEAREST, VF_LOOKUP_NEAREST, VF_CORRECTION_REBUILD,
     VF_BUFFER_SLICE, 16, 1, 0, false},
    {"preint1 lit bilinear shade, image buffer", VF_MODE_PREINT1, true, VF_LOOKUP_NEAREST, VF_LOOKUP_BILINEAR,
     VF_CORRECTION_REBUILD, VF_BUFFER_IMAGE, 16, 1, 0, false},
    {"preint1 bilinear lookup", VF_MODE_PREINT1, false, VF_LOOKUP_BILINEAR, VF_LOOKUP_NEAREST, VF_CORRECTION_REBUILD,
     VF_BUFFER_SLICE, 16, 1, 0, false},
    {"preint1 lut", VF_MODE_PREINT1, false, VF_LOOKUP_NEAREST, VF_LOOKUP_NEAREST, VF_CORRECTION_LUT, VF_BUFFER_SLICE,
     16, 1, 0, false},
    {"preint1 lit lut", VF_MODE_PREINT1, true, VF_LOOKUP_NEAREST, VF_LOOKUP_NEAREST, VF_CORRECTION_LUT,
     VF_BUFFER_SLICE, 16, 1, 0, false},
    {"preint1 8-bit table", VF_MODE_PREINT1, false, VF_LOOKUP_NEAREST, VF_LOOKUP_NEAREST, VF_CORRECTION_REBUILD,
     VF_BUFFER_SLICE, 8, 1, 0, false},
    {"preint1 rays 2, partial slabs", VF_MODE_PREINT1, false, VF_LOOKUP_NEAREST, VF_LOOKUP_NEAREST,
     VF_CORRECTION_REBUILD, VF_BUFFER_SLICE, 16, 2, 0, true},
    {"point", VF_MODE_POINT, false, VF_LOOKUP_NEAREST, VF_LOOKUP_NEAREST, VF_CORRECTION_REBUILD, VF_BUFFER_SLICE, 16,
     1, 0, false},
    {"point lit", VF_MODE_POINT, true, VF_LOOKUP_NEAREST, VF_LOOKUP_NEAREST, VF_CORRECTION_REBUILD, VF_BUFFER_SLICE,
     16, 1, 0, false},
    {"preclass", VF_MODE_PRECLASS, false, VF_LOOKUP_NEAREST, VF_LOOKUP_NEAREST, VF_CORRECTION_REBUILD,
     VF_BUFFER_SLICE, 16, 1, 0, false},
    {"preint2", VF_MODE_PREINT2, false, VF_LOOKUP_NEAREST, VF_LOOKUP_NEAREST, VF_CORRECTION_REBUILD, VF_BUFFER_SLICE,
     16, 1, 24, false},
    {"preint2 lit trilinear", VF_MODE_PREINT2, true, VF_LOOKUP_TRILINEAR, VF_LOOKUP_NEAREST, VF_CORRECTION_REBUILD,
     VF_BUFFER_SLICE, 16, 1, 24, false},
};

static const vf_format_t formats[] = {VF_FORMAT_RGB888, VF_FORMAT_RGB565, VF_FORMAT_XRGB8888};

static vfp_volume_t g_vol;
static vf_tf_point_t g_points[2][VF_MAX_TF_POINTS];
static uint32_t g_counts[2];
static vf_window_t g_window, g_narrow;

static void load_scene(void)
{
    if (g_counts[0])
        return;
    char err[VFP_ERR_LEN];
    vfp_load_opts_t o;
    memset(&o, 0, sizeof o);
    int loaded = vfp_volume_load(&g_vol, "phantom:marschner-lobb:20", &o, err, sizeof err) == VFP_OK;
    CHECK_MSG(loaded, "%s", err);
    if (!loaded)
        exit(1);
    g_window = vfp_default_window(&g_vol);
    g_narrow = (vf_window_t){g_window.lo + (g_window.hi - g_window.lo) / 8, g_window.hi};
    static const char *const presets[2] = {"sharp", "ramp"};
    for (int t = 0; t < 2; t++) {
        vfp_tf_t tf;
        CHECK_MSG(vfp_tf_preset(&tf, presets[t], err, sizeof err) == VFP_OK, "%s", err);
        g_counts[t] = vfp_tf_to_core(&tf, &g_vol, g_window, g_points[t]);
    }
}

static vf_params_t params_of(const variant_t *v)
{
    vf_params_t p;
    vf_params_default(&p);
    p.mode = v->mode;
    p.lighting = v->lighting;
    p.lookup = v->lookup;
    p.shade_lookup = v->shade_lookup;
    p.correction = v->correction;
    p.buffer = v->buffer;
    p.table_bits = v->table_bits;
    p.rays = v->rays;
    p.partial_slabs = v->partial_slabs;
    if (v->table2_size)
        p.table2_size = v->table2_size;
    return p;
}

/* The views of a sequence: a turn, a tilt and a zoom, each a new slab length. */
static vf_view_t view_at(int frame)
{
    return (vf_view_t){5000 + 4100 * frame, 3000 - 1700 * frame, 900 * frame, 65536 + 9000 * (frame % 2)};
}

/* FRAMES frames, then the other transfer function, then a narrower window: the hashes of all of them, and how
 * many pixels were not background (the frames must show something for the comparison to mean anything). */
static int render_sequence(const variant_t *v, vf_format_t format, int threads, uint64_t *hashes, long *drawn,
                           char *err, size_t errlen)
{
    vf_params_t p = params_of(v);
    vfp_render_t r;
    vf_image_t img;
    if (vfp_image_alloc(&img, W, H, format) != VFP_OK) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    int status = vfp_render_open(&r, &p, &g_vol.core, threads, err, errlen) == VFP_OK &&
                         vfp_render_set_window(&r, g_window, err, errlen) == VFP_OK &&
                         vfp_render_set_tf(&r, g_points[0], g_counts[0], err, errlen) == VFP_OK
                     ? 0
                     : -1;
    *drawn = 0;
    for (int f = 0; f < FRAMES + 2 && status == 0; f++) {
        if (f == FRAMES && vfp_render_set_tf(&r, g_points[1], g_counts[1], err, errlen) != VFP_OK)
            status = -1;
        if (f == FRAMES + 1 && vfp_render_set_window(&r, g_narrow, err, errlen) != VFP_OK)
            status = -1;
        const vf_view_t view = view_at(f % FRAMES);
        if (status == 0 && vfp_render_frame(&r, &view, &img, err, errlen) != VFP_OK)
            status = -1;
        if (status == 0) {
            hashes[f] = vfp_image_hash(&img);
            const unsigned char *px = img.pixels;
            for (size_t i = 0; i < (size_t)img.stride * H; i++)
                *drawn += px[i] != 0 && px[i] != 0xff;
        }
    }
    vfp_render_close(&r);
    vfp_image_free(&img);
    return status;
}

static void same_pixels_for_any_thread_count(void)
{
    load_scene();
    static const int threads[] = {2, 3, 4};
    for (size_t v = 0; v < sizeof variants / sizeof variants[0]; v++)
        for (size_t fm = 0; fm < sizeof formats / sizeof formats[0]; fm++) {
            char err[VFP_ERR_LEN];
            uint64_t one[FRAMES + 2], many[FRAMES + 2];
            long drawn = 0, drawn_many = 0;
            int ok = render_sequence(&variants[v], formats[fm], 1, one, &drawn, err, sizeof err) == 0;
            CHECK_MSG(ok, "%s, format %zu, 1 thread: %s", variants[v].name, fm, err);
            if (!ok)
                continue;
            CHECK_MSG(drawn > 1000, "%s: only %ld bytes drawn", variants[v].name, drawn);
            for (size_t t = 0; t < sizeof threads / sizeof threads[0]; t++) {
                ok = render_sequence(&variants[v], formats[fm], threads[t], many, &drawn_many, err, sizeof err) == 0;
                CHECK_MSG(ok, "%s, format %zu, %d threads: %s", variants[v].name, fm, threads[t], err);
                for (int f = 0; ok && f < FRAMES + 2; f++)
                    CHECK_MSG(many[f] == one[f], "%s, format %zu, frame %d: %d threads %016llx, 1 thread %016llx",
                              variants[v].name, fm, f, threads[t], (unsigned long long)many[f],
                              (unsigned long long)one[f]);
            }
        }
}

/* A level knob turning: the transfer function moved step by step (through nothing visible and everything visible
 * on the way), a frame after each move. With threads the run lists are encoded in parts on them; the frames and
 * the run lists' memory are those of one thread, move after move. */
static void tf_moves_on_threads(void)
{
    char err[VFP_ERR_LEN];
    vfp_volume_t vol;
    vfp_load_opts_t o;
    memset(&o, 0, sizeof o);
    CHECK_MSG(vfp_volume_load(&vol, "phantom:shepp-logan:37", &o, err, sizeof err) == VFP_OK, "%s", err);
    const vf_window_t window = vfp_default_window(&vol);
    enum { MOVES = 9 };
    uint64_t hashes[5][MOVES];
    size_t runs[5][MOVES];
    vf_image_t img;
    CHECK(vfp_image_alloc(&img, W, H, VF_FORMAT_RGB565) == VFP_OK);
    for (int threads = 1; threads <= 4 && !check_failed; threads++) {
        vf_params_t p;
        vf_params_default(&p);
        vfp_render_t r;
        CHECK_MSG(vfp_render_open(&r, &p, &vol.core, threads, err, sizeof err) == VFP_OK &&
                      vfp_render_set_window(&r, window, err, sizeof err) == VFP_OK,
                  "%d threads: %s", threads, err);
        for (int m = 0; m < MOVES && !check_failed; m++) {
            vf_tf_point_t points[VF_MAX_TF_POINTS];
            uint32_t count;
            if (m == 3 || m == 6) { /* nothing visible, then everything */
                points[0] = (vf_tf_point_t){0, 65535, 65535, 65535, (uint16_t)(m == 3 ? 0 : 3000)};
                count = 1;
            } else {
                vfp_tf_t tf;
                CHECK(vfp_tf_preset(&tf, m % 2 ? "ramp" : "sharp", err, sizeof err) == VFP_OK);
                vfp_tf_move(&tf, &vol, window, 0.06 * (m - 4), 1.0 + 0.1 * (m % 3));
                count = vfp_tf_to_core(&tf, &vol, window, points);
            }
            CHECK_MSG(vfp_render_set_tf(&r, points, count, err, sizeof err) == VFP_OK, "%s", err);
            CHECK_MSG(threads == 1 ? r.tf_parts == 0 : r.tf_parts >= 6, "%d threads, move %d: %u parts", threads, m,
                      r.tf_parts);
            const vf_view_t view = view_at(m % FRAMES);
            CHECK_MSG(vfp_render_frame(&r, &view, &img, err, sizeof err) == VFP_OK, "%s", err);
            vf_memory_t mem;
            vf_renderer_memory(r.core, &mem);
            hashes[threads][m] = vfp_image_hash(&img);
            runs[threads][m] = mem.runs;
            if (threads > 1) {
                CHECK_MSG(hashes[threads][m] == hashes[1][m], "move %d: %d threads %016llx, 1 thread %016llx", m,
                          threads, (unsigned long long)hashes[threads][m], (unsigned long long)hashes[1][m]);
                CHECK_MSG(runs[threads][m] == runs[1][m], "move %d: run lists %zu bytes on %d threads, %zu on 1", m,
                          runs[threads][m], threads, runs[1][m]);
            }
        }
        vfp_render_close(&r);
    }
    /* the moves made different frames, the empty function an empty one */
    CHECK(hashes[1][0] != hashes[1][1] && hashes[1][3] != hashes[1][6]);
    vfp_image_free(&img);
    vfp_volume_free(&vol);
}

static void open_and_close_in_a_loop(void)
{
    load_scene();
    char err[VFP_ERR_LEN];
    vf_params_t p;
    vf_params_default(&p);
    vf_image_t img;
    CHECK(vfp_image_alloc(&img, 32, 24, VF_FORMAT_RGB565) == VFP_OK);
    uint64_t first = 0;
    for (int n = 0; n < 40; n++) {
        vfp_render_t r;
        const int threads = 1 + n % 5;
        CHECK_MSG(vfp_render_open(&r, &p, &g_vol.core, threads, err, sizeof err) == VFP_OK, "%s", err);
        if (n % 2) { /* every other one never renders: its workers are woken only to leave */
            CHECK(vfp_render_set_window(&r, g_window, err, sizeof err) == VFP_OK);
            CHECK(vfp_render_set_tf(&r, g_points[0], g_counts[0], err, sizeof err) == VFP_OK);
            const vf_view_t view = view_at(n % FRAMES);
            for (int f = 0; f < 3; f++)
                CHECK_MSG(vfp_render_frame(&r, &view, &img, err, sizeof err) == VFP_OK, "%s", err);
            if (n % FRAMES == 1 && !first)
                first = vfp_image_hash(&img);
            else if (n % FRAMES == 1)
                CHECK_EQ(vfp_image_hash(&img), first);
        }
        vfp_render_close(&r);
    }
    CHECK(first != 0);
    vfp_image_free(&img);
}

CHECK_CASES(CHECK_CASE(same_pixels_for_any_thread_count), CHECK_CASE(tf_moves_on_threads),
            CHECK_CASE(open_and_close_in_a_loop));
CHECK_RUN("port/render_mt")
