/* SPDX-License-Identifier: MIT */
/* test_preview.c: what the viewer's preview and its level and width knobs stand on: downsampled volumes
 * (port/io/volume_downsample.c), vfp_tf_move (tf.c), and renderers that take a new transfer function or window
 * without rebuilding more than that (render_mt.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "render/render_mt.h"
#include "input/controls.h"
#include "io/tf.h"
#include "volume_fixtures.h"

/* A 5 x 4 x 3 int16 raw volume with negative values, loaded with and without downsampling. */
static const char *write_int16(int16_t *v)
{
    for (int i = 0; i < 60; i++)
        v[i] = (int16_t)((i * 37) % 101 - 50);
    return fx_write("d.raw", NULL, v, sizeof(int16_t) * 60);
}

static void downsample_averages_blocks_and_scales_spacing(void)
{
    int16_t v[60];
    const char *path = write_int16(v);
    vfp_load_opts_t o = {.have_dims = 1, .dims = {5, 4, 3}, .have_type = 1, .type = VF_VOXEL_I16,
                         .have_spacing = 1, .spacing = {1, 1, 2}, .downsample = 2};
    vfp_volume_t vol;
    char err[VFP_ERR_LEN];
    CHECK_MSG(vfp_volume_load(&vol, path, &o, err, sizeof err) == 0, "%s", err);
    CHECK_EQ(vol.core.dims[0], 3); /* 5 -> 3: the last block is one voxel wide */
    CHECK_EQ(vol.core.dims[1], 2);
    CHECK_EQ(vol.core.dims[2], 2);
    CHECK_NEAR(vol.spacing[0], 2, 0);
    CHECK_NEAR(vol.spacing[2], 4, 0); /* the --spacing given, times the factor */
    CHECK_EQ(vol.core.spacing_q16[2], 2 * 65536);
    const int16_t *d = vol.data;
    for (int z = 0; z < 2; z++)
        for (int y = 0; y < 2; y++)
            for (int x = 0; x < 3; x++) {
                long sum = 0, n = 0;
                for (int zz = 2 * z; zz < 2 * z + 2 && zz < 3; zz++)
                    for (int yy = 2 * y; yy < 2 * y + 2; yy++)
                        for (int xx = 2 * x; xx < 2 * x + 2 && xx < 5; xx++, n++)
                            sum += v[(zz * 4 + yy) * 5 + xx];
                long want = lround((double)sum / (double)n); /* half away from zero, as lround */
                CHECK_MSG(d[(z * 2 + y) * 3 + x] == want, "block %d,%d,%d: %d, expected %ld", x, y, z,
                          d[(z * 2 + y) * 3 + x], want);
            }
    CHECK(vol.raw_min >= -50 && vol.raw_max <= 50);

    /* The in-memory copy the viewer makes is the same volume. */
    vfp_volume_t full, copy;
    o.downsample = 0;
    CHECK(vfp_volume_load(&full, path, &o, err, sizeof err) == 0);
    CHECK_MSG(vfp_volume_downsampled(&copy, &full, 2, err, sizeof err) == 0, "%s", err);
    CHECK(memcmp(copy.core.dims, vol.core.dims, sizeof vol.core.dims) == 0);
    CHECK(memcmp(copy.data, vol.data, 12 * sizeof(int16_t)) == 0);
    CHECK(memcmp(copy.core.spacing_q16, vol.core.spacing_q16, sizeof vol.core.spacing_q16) == 0);
    CHECK_EQ(full.core.dims[0], 5); /* the source is left as it was */
    vfp_volume_free(&copy);
    vfp_volume_free(&full);
    vfp_volume_free(&vol);
}

static void downsample_refuses_what_it_cannot_do(void)
{
    int16_t v[60];
    const char *path = write_int16(v);
    vfp_load_opts_t o = {.have_dims = 1, .dims = {5, 4, 3}, .have_type = 1, .type = VF_VOXEL_I16, .downsample = 2};
    vfp_volume_t vol;
    char err[VFP_ERR_LEN];
    o.downsample = 3; /* 3 voxels along z become 1: below the core's smallest side */
    CHECK(vfp_volume_load(&vol, path, &o, err, sizeof err) == VFP_ERR);
    CHECK_MSG(strstr(err, "d.raw: 3 voxels along z are too few to downsample 3 times (expected at least 4)"), "%s",
              err);
    o.downsample = 9;
    CHECK(vfp_volume_load(&vol, path, &o, err, sizeof err) == VFP_ERR);
    CHECK_MSG(strstr(err, "downsample factor 9 (expected 1 to 8)"), "%s", err);
    o.downsample = 1; /* 1: as stored */
    CHECK(vfp_volume_load(&vol, path, &o, err, sizeof err) == 0);
    CHECK_EQ(vol.core.dims[0], 5);
    vfp_volume_t small;
    CHECK(vfp_volume_downsampled(&small, &vol, 4, err, sizeof err) == VFP_ERR);
    CHECK(small.data == NULL);
    vfp_volume_free(&vol);
}

static void tf_move_shifts_and_stretches_about_the_window(void)
{
    vfp_tf_t tf;
    char err[256];
    CHECK(vfp_tf_preset(&tf, "ramp", err, sizeof err) == 0);
    vfp_tf_t moved = tf;
    vfp_tf_move(&moved, NULL, (vf_window_t){0, 255}, 0.1, 2);
    for (int i = 0; i < tf.count; i++)
        CHECK_NEAR(moved.points[i].s, 0.5 + 0.1 + (tf.points[i].s - 0.5) * 2, 1e-12);

    /* In data units the same move is in the window's data values: window raw 100..300, data = 2 raw - 1000. */
    vfp_volume_t vol;
    memset(&vol, 0, sizeof vol);
    vol.slope = 2;
    vol.inter = -1000;
    vfp_tf_t data = {.data_units = 1, .count = 2, .points = {{-800, 0, 0, 0, 0}, {-400, 1, 1, 1, 1}}};
    vfp_tf_move(&data, &vol, (vf_window_t){100, 300}, 0.25, 0.5);
    /* data window -800..-400, centre -600, width 400: -800 -> -600 + 100 - 100 = -600; -400 -> -400 */
    CHECK_NEAR(data.points[0].s, -600, 1e-9);
    CHECK_NEAR(data.points[1].s, -400, 1e-9);
    vfp_tf_move(&data, &vol, (vf_window_t){100, 300}, 0, 1); /* identity */
    CHECK_NEAR(data.points[0].s, -600, 1e-9);
}

/* A renderer given a new transfer function (or window) renders what a new renderer given the same renders. */
static void new_transfer_function_equals_a_fresh_renderer(void)
{
    vfp_volume_t vol;
    char err[VFP_ERR_LEN];
    CHECK(vfp_volume_load(&vol, "phantom:marschner-lobb:24", NULL, err, sizeof err) == 0);
    vf_params_t p;
    vf_params_default(&p);
    vfp_tf_t tf;
    vfp_tf_preset(&tf, "sharp", err, sizeof err);
    vf_window_t win = {0, 255}, narrow = {40, 200};
    vf_tf_point_t a[VF_MAX_TF_POINTS], b[VF_MAX_TF_POINTS];
    uint32_t na = vfp_tf_to_core(&tf, &vol, win, a);
    vfp_tf_move(&tf, &vol, win, 0.1, 1.5);
    uint32_t nb = vfp_tf_to_core(&tf, &vol, win, b);
    vf_view_t view = {5000, 3000, 0, 65536};
    uint8_t px1[48 * 48 * 3], px2[48 * 48 * 3];
    vf_image_t i1 = {px1, 48, 48, 48 * 3, VF_FORMAT_RGB888}, i2 = {px2, 48, 48, 48 * 3, VF_FORMAT_RGB888};

    vfp_render_t used, fresh;
    CHECK(vfp_render_open(&used, &p, &vol.core, 2, err, sizeof err) == 0);
    CHECK(vfp_render_set_window(&used, win, err, sizeof err) == 0);
    CHECK(vfp_render_set_tf(&used, a, na, err, sizeof err) == 0);
    CHECK(vfp_render_frame(&used, &view, &i1, err, sizeof err) == 0);
    CHECK(vfp_render_set_tf(&used, b, nb, err, sizeof err) == 0); /* the knob moved */
    CHECK(vfp_render_set_window(&used, narrow, err, sizeof err) == 0);
    CHECK(vfp_render_frame(&used, &view, &i1, err, sizeof err) == 0);

    CHECK(vfp_render_open(&fresh, &p, &vol.core, 1, err, sizeof err) == 0);
    CHECK(vfp_render_set_tf(&fresh, b, nb, err, sizeof err) == 0); /* the other order */
    CHECK(vfp_render_set_window(&fresh, narrow, err, sizeof err) == 0);
    CHECK(vfp_render_frame(&fresh, &view, &i2, err, sizeof err) == 0);
    int same = memcmp(px1, px2, sizeof px1) == 0, lit = 0;
    for (size_t i = 0; i < sizeof px1; i++)
        lit += px1[i] > 8;
    vfp_render_close(&used);
    vfp_render_close(&fresh);
    vfp_volume_free(&vol);
    CHECK(same);
    CHECK(lit > 100); /* and the picture is not empty */
}

/* A panel mounted a quarter turn clockwise: the viewer rolls the view back by as much (vfp_controls_view), and
 * the panel's turn must then stand the picture upright: exactly the unturned picture, pixel for pixel. */
static void panel_rotation_stands_the_picture_upright(void)
{
    vfp_volume_t vol;
    char err[VFP_ERR_LEN];
    CHECK(vfp_volume_load(&vol, "phantom:shepp-logan:32", NULL, err, sizeof err) == 0);
    vf_params_t p;
    vf_params_default(&p);
    vfp_tf_t tf;
    vfp_tf_preset(&tf, "ramp", err, sizeof err);
    vf_tf_point_t pts[VF_MAX_TF_POINTS];
    uint32_t n = vfp_tf_to_core(&tf, &vol, (vf_window_t){0, 255}, pts);
    vfp_render_t r;
    CHECK(vfp_render_open(&r, &p, &vol.core, 1, err, sizeof err) == 0);
    CHECK(vfp_render_set_window(&r, (vf_window_t){0, 255}, err, sizeof err) == 0);
    CHECK(vfp_render_set_tf(&r, pts, n, err, sizeof err) == 0);
    enum { W = 40, H = 40 };
    static uint8_t up[W * H * 3], panel[W * H * 3];
    vf_image_t iu = {up, W, H, W * 3, VF_FORMAT_RGB888}, ip = {panel, W, H, W * 3, VF_FORMAT_RGB888};
    vfp_controls_t c = {.azimuth = 30, .elevation = 20, .zoom = 1, .tf_scale = 1};
    vf_view_t v0 = vfp_controls_view(&c, 0), v90 = vfp_controls_view(&c, 90);
    CHECK(vfp_render_frame(&r, &v0, &iu, err, sizeof err) == 0);
    CHECK(vfp_render_frame(&r, &v90, &ip, err, sizeof err) == 0);
    vfp_render_close(&r);
    vfp_volume_free(&vol);
    int same = 1, lit = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) /* upright (x, y) is buffer (y, H - 1 - x) on a panel turned clockwise */
            for (int k = 0; k < 3; k++) {
                same &= up[(y * W + x) * 3 + k] == panel[((H - 1 - x) * W + y) * 3 + k];
                lit += up[(y * W + x) * 3 + k] > 8;
            }
    CHECK(lit > 50);
    CHECK(same);
}

CHECK_CASES({"panel_rotation_stands_the_picture_upright", panel_rotation_stands_the_picture_upright},
            {"downsample_averages_blocks_and_scales_spacing", downsample_averages_blocks_and_scales_spacing},
            {"downsample_refuses_what_it_cannot_do", downsample_refuses_what_it_cannot_do},
            {"tf_move_shifts_and_stretches_about_the_window", tf_move_shifts_and_stretches_about_the_window},
            {"new_transfer_function_equals_a_fresh_renderer", new_transfer_function_equals_a_fresh_renderer});
CHECK_RUN("port/preview")
