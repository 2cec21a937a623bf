/* SPDX-License-Identifier: MIT */
/*
 * test_preint.c: pre-integration as a whole (issue 3): the two triangles of the table are the two directions
 * of a slab; a constant transfer function gives the closed form whatever the slab length, with either
 * correction, and a pre-integrated table equal to the point table; every combination of options renders within
 * the foundation's bounds of the double reference run with the same options; and the differences between lut
 * and rebuild, slice and image buffers are reported (slice and image must be identical).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "imgcmp.h"
#include "io/pngio.h"
#include "scene.h"

static uint16_t table_a[256 * 256 * 4], table_b[256 * 256 * 4];
static unsigned char scratch_buf[1 << 20];

/* A colour ramp at constant opacity: the back of a slab is brighter than its front when the scalar rises, so
 * compositing front to back weights the darker front more: C(f, b) < C(b, f) for f < b, opacity the same. */
static void triangles_are_reversals(void)
{
    vf_tf_point_t pts[2] = {{0, 0, 0, 0, 20000}, {255 * 256, 65535, 65535, 65535, 20000}};
    vf_tf_t tf = {pts, 2};
    vf_arena_t arena;
    vf_arena_init(&arena, scratch_buf, sizeof scratch_buf);
    CHECK_EQ(vf_table_preint(&tf, 64, 3 << 16, VF_BUILDER_INCREMENTAL, &arena, table_a), VF_OK);
    int checked = 0;
    for (uint32_t f = 0; f < 64; f++)
        for (uint32_t b = f + 2; b < 64; b++) {
            const uint16_t *up = table_a + ((size_t)f * 64 + b) * 4, *down = table_a + ((size_t)b * 64 + f) * 4;
            CHECK_MSG(abs((int)up[3] - (int)down[3]) <= 1, "opacity of (%u,%u) %u vs %u", f, b, up[3], down[3]);
            for (int c = 0; c < 3; c++)
                CHECK_MSG(up[c] < down[c], "entry (%u,%u) colour %u not below (%u,%u) %u", f, b, up[c], b, f, down[c]);
            checked++;
        }
    CHECK(checked > 1000);
}

/* A constant transfer function: every entry of the pre-integrated table is the point table's (the scalar
 * does not matter), within 1 LSB. */
static void constant_tf_preint_is_point(void)
{
    vf_tf_point_t pts[1] = {{0, 52428, 32768, 13107, 6553}};
    vf_tf_t tf = {pts, 1};
    vf_arena_t arena;
    vf_arena_init(&arena, scratch_buf, sizeof scratch_buf);
    for (uint32_t slab = 65536; slab <= 3 * 65536; slab += 40000) {
        CHECK_EQ(vf_table_point(&tf, 128, slab, &arena, table_b), VF_OK);
        CHECK_EQ(vf_table_preint(&tf, 128, slab, VF_BUILDER_INCREMENTAL, &arena, table_a), VF_OK);
        for (uint32_t e = 0; e < 128 * 128; e++)
            for (int c = 0; c < 4; c++)
                CHECK_MSG(abs((int)table_a[e * 4 + c] - (int)table_b[(e / 128) * 4 + c]) <= 1,
                          "slab %u entry %u channel %d: %u vs point %u", slab, e, c, table_a[e * 4 + c],
                          table_b[(e / 128) * 4 + c]);
    }
}

/* A uniform cube under a constant transfer function: the centre pixel is c (1 - exp(-tau d segments)) for
 * every view, although the slab length d changes with it, with rebuilt tables and with the lut correction. */
static void constant_tf_slab_length_independent(void)
{
    enum { N = 17 };
    static uint8_t voxels[N * N * N];
    memset(voxels, 100, sizeof voxels);
    vf_volume_t vol = {{N, N, N}, {65536, 65536, 65536}, VF_VOXEL_U8, voxels};
    vf_tf_point_t pts[1] = {{0, 52428, 32768, 13107, 3277}}; /* colour 0.8 0.5 0.2, opacity 0.05 per voxel */
    vf_tf_t tf = {pts, 1};
    const double tau = -log(1 - 3277.0 / 65535), colour[3] = {52428 / 65535.0, 0.5, 13107 / 65535.0};
    static unsigned char arena_buf[4 << 20];
    for (int mode = 0; mode < 2; mode++)
        for (int corr = 0; corr < 2; corr++)
            for (int deg = 0; deg <= 40; deg += 10) {
                vf_params_t p;
                vf_params_default(&p);
                p.mode = mode ? VF_MODE_PREINT1 : VF_MODE_POINT;
                p.correction = corr ? VF_CORRECTION_LUT : VF_CORRECTION_REBUILD;
                vf_arena_t arena;
                vf_arena_init(&arena, arena_buf, sizeof arena_buf);
                vf_renderer_t *r;
                CHECK_EQ(vf_renderer_create(&r, &p, &vol, &arena), VF_OK);
                CHECK_EQ(vf_renderer_set_window(r, (vf_window_t){0, 255}), VF_OK);
                CHECK_EQ(vf_renderer_set_tf(r, &tf), VF_OK);
                uint8_t rgb[33 * 33 * 3];
                vf_image_t img = {rgb, 33, 33, 33 * 3, VF_FORMAT_RGB888};
                vf_view_t view = {(int32_t)lround(deg * 65536.0 / 360), 0, 0, 65536};
                CHECK_EQ(vf_renderer_draw(r, &view, &img, scratch_buf, sizeof scratch_buf), VF_OK);
                double d = vf_renderer_factor(r)->slab_q16 / 65536.0;
                double segments = mode ? N - 1 : N, alpha = 1 - exp(-tau * d * segments);
                const uint8_t *centre = rgb + (16 * 33 + 16) * 3;
                for (int c = 0; c < 3; c++)
                    CHECK_MSG(abs(centre[c] - (int)lround(255 * colour[c] * alpha)) <= 1,
                              "%s %s at %d degrees (slab %.4f): channel %d is %d, closed form %.2f",
                              mode ? "preint1" : "point", corr ? "lut" : "rebuild", deg, d, c, centre[c],
                              255 * colour[c] * alpha);
            }
}

/* Render a scene with the core and the reference; 0 and the difference, or -1. */
static int compare_view(const char *volume, const char *preset, const vf_params_t *params, const char *size,
                        const char *view, sim_diff_t *d, uint8_t **core_rgb)
{
    char err[VFP_ERR_LEN];
    char *argv[] = {(char *)volume, "--preset", (char *)preset, "--size", (char *)size, "--view", (char *)view};
    sim_opts_t o;
    sim_parse(&o, 7, argv, SIM_OPT_SCENE, "");
    o.params = *params;
    sim_scene_t s;
    vf_image_t core, ref;
    vf_factor_t factor;
    if (sim_scene_load(&s, &o, err, sizeof err) || sim_render_core(&s, &core, &factor, err, sizeof err)) {
        printf("# %s\n", err);
        return -1;
    }
    int status = sim_render_reference(&s, &factor, &ref, err, sizeof err);
    if (status == 0) {
        size_t pixels = (size_t)s.width * s.height;
        uint8_t *a = malloc(pixels * 3), *b = malloc(pixels * 3);
        vfp_image_to_rgb(&core, a);
        vfp_image_to_rgb(&ref, b);
        sim_diff(a, b, pixels, d);
        if (core_rgb)
            *core_rgb = a;
        else
            free(a);
        free(b);
        sim_image_free(&ref);
    } else {
        printf("# %s\n", err);
    }
    sim_image_free(&core);
    sim_scene_free(&s);
    return status ? -1 : 0;
}

static int compare(const char *volume, const char *preset, const vf_params_t *params, const char *size,
                   sim_diff_t *d, uint8_t **core_rgb)
{
    return compare_view(volume, preset, params, size, "60,-35", d, core_rgb);
}

/* Every combination of mode, lookup, table bits, correction and buffer against the reference with the same
 * options, on a narrow-peaked transfer function: PSNR >= 50 dB and at most 2 of 255. */
static void every_option_against_reference(void)
{
    char path[1024];
    const char *volume = check_data("neghip.nhdr", path, sizeof path);
    CHECK_MSG(volume, "%s", path);
    int count = 0;
    for (int mode = 0; mode <= VF_MODE_PRECLASS; mode++) /* preint2's: test_order2_frames.c */
        for (int lookup = 0; lookup <= VF_LOOKUP_BILINEAR; lookup++)
            for (int bits = 8; bits <= 16; bits += 8)
                for (int corr = 0; corr < VF_CORRECTION_COUNT; corr++)
                    for (int buf = 0; buf < VF_BUFFER_COUNT; buf++) {
                        if (mode != VF_MODE_PREINT1 && buf == VF_BUFFER_IMAGE)
                            continue; /* buffers exist in preint1 only */
                        vf_params_t p;
                        vf_params_default(&p);
                        p.mode = (vf_mode_t)mode;
                        p.lookup = (vf_lookup_t)lookup;
                        p.table_bits = (uint32_t)bits;
                        p.correction = (vf_correction_t)corr;
                        p.buffer = (vf_buffer_t)buf;
                        sim_diff_t d;
                        CHECK(compare(volume, "sharp", &p, "192x192", &d, NULL) == 0);
                        CHECK_MSG(d.psnr_db >= 50 && d.max_abs[3] <= 2, "%s %s %d-bit %s %s: PSNR %.1f, max %d",
                                  vf_mode_name(p.mode), vf_lookup_name(p.lookup), bits,
                                  vf_correction_name(p.correction), vf_buffer_name(p.buffer), d.psnr_db, d.max_abs[3]);
                        count++;
                    }
    printf("# %d option combinations within PSNR 50 dB and 2 levels of the reference\n", count);
    CHECK_EQ(count, 32);
}

/* Rays per voxel column and partial slabs (docs/algorithm.md, sections 4b and 4c) with every mode, lookup, table
 * width and buffer, on a volume visible up to its box (so that rays cross its side faces), against the reference
 * with the same options: PSNR >= 50 dB and at most 2 of 255. Partial slabs go with the rebuild correction only
 * (the core refuses them with the lut). */
static void rays_and_partial_slabs_against_reference(void)
{
    int count = 0;
    const char *views[] = {"60,-35", "200,40,10"};
    for (uint32_t rays = 1; rays <= 4; rays *= 2)
        for (int partial = 0; partial < 2; partial++)
            for (int mode = 0; mode <= VF_MODE_PRECLASS; mode++) /* preint2 has no partial slabs; its rays: */
                for (int lookup = 0; lookup <= VF_LOOKUP_BILINEAR; lookup++) /* test_order2_frames.c */
                    for (int variant = 0; variant < 3; variant++) { /* 16-bit; 8-bit; lut or image buffer */
                        if (rays == 1 && !partial)
                            continue; /* every_option_against_reference */
                        vf_params_t p;
                        vf_params_default(&p);
                        p.mode = (vf_mode_t)mode;
                        p.lookup = (vf_lookup_t)lookup;
                        p.rays = rays;
                        p.partial_slabs = partial;
                        p.table_bits = variant == 1 ? 8 : 16;
                        if (variant == 2 && mode == VF_MODE_PREINT1)
                            p.buffer = VF_BUFFER_IMAGE;
                        else if (variant == 2 && !partial)
                            p.correction = VF_CORRECTION_LUT;
                        else if (variant == 2)
                            continue;
                        sim_diff_t d;
                        CHECK(compare_view("phantom:marschner-lobb:20", "sharp", &p, "96x80", views[count % 2], &d,
                                           NULL) == 0);
                        CHECK_MSG(d.psnr_db >= 50 && d.max_abs[3] <= 2,
                                  "%s %s %u-bit %s %s buffer, rays %u, partial %d: PSNR %.1f, max %d",
                                  vf_mode_name(p.mode), vf_lookup_name(p.lookup), p.table_bits,
                                  vf_correction_name(p.correction), vf_buffer_name(p.buffer), rays, partial, d.psnr_db,
                                  d.max_abs[3]);
                        count++;
                    }
    printf("# %d combinations of rays and partial slabs within PSNR 50 dB and 2 levels of the reference\n", count);
    CHECK_EQ(count, 78);
}

/* Reported, not hidden: lut against rebuild and image against slice buffers, on the same scene. */
static void differences_reported(void)
{
    char path[1024];
    const char *volume = check_data("engine.nhdr", path, sizeof path);
    CHECK_MSG(volume, "%s", path);
    for (int preset = 0; preset < 2; preset++) {
        const char *name = preset ? "sharp" : "ramp";
        vf_params_t p;
        vf_params_default(&p);
        uint8_t *rebuild = NULL, *lut = NULL, *image = NULL;
        sim_diff_t d;
        CHECK(compare(volume, name, &p, "256x256", &d, &rebuild) == 0);
        p.correction = VF_CORRECTION_LUT;
        CHECK(compare(volume, name, &p, "256x256", &d, &lut) == 0);
        p.correction = VF_CORRECTION_REBUILD;
        p.buffer = VF_BUFFER_IMAGE;
        CHECK(compare(volume, name, &p, "256x256", &d, &image) == 0);
        sim_diff_t lut_vs_rebuild, image_vs_slice;
        sim_diff(lut, rebuild, 256 * 256, &lut_vs_rebuild);
        sim_diff(image, rebuild, 256 * 256, &image_vs_slice);
        printf("# %s, %s: lut vs rebuild PSNR %.1f dB, max %d, mean %.4f; image vs slice buffers: max %d\n", volume,
               name, lut_vs_rebuild.psnr_db, lut_vs_rebuild.max_abs[3], lut_vs_rebuild.mean_abs[3],
               image_vs_slice.max_abs[3]);
        CHECK_MSG(image_vs_slice.max_abs[3] == 0, "image and slice buffers differ");
        /* the lut corrects colour only approximately (exact for constant extinction and colour): it must still
         * be the same picture */
        CHECK_MSG(lut_vs_rebuild.psnr_db >= 35, "lut vs rebuild PSNR %.1f dB", lut_vs_rebuild.psnr_db);
        free(rebuild);
        free(lut);
        free(image);
    }
}

CHECK_CASES({"triangles_are_reversals", triangles_are_reversals},
            {"constant_tf_preint_is_point", constant_tf_preint_is_point},
            {"constant_tf_slab_length_independent", constant_tf_slab_length_independent},
            {"every_option_against_reference", every_option_against_reference},
            {"rays_and_partial_slabs_against_reference", rays_and_partial_slabs_against_reference},
            {"differences_reported", differences_reported});
CHECK_RUN("preint")
