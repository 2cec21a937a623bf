/* SPDX-License-Identifier: MIT */
/*
 * render_scene.h: the scenes of test_render.c and test_render_api.c, two halves of one suite that draw from one
 * seed: a random ball in noise of up to MAXD^3 voxels (or a long thin one), a random transfer function, a renderer
 * over a 4 MiB arena, band scratch and three output images. Header-only, included once by each of the two.
 */
#ifndef TESTS_CORE_RENDER_SCENE_H
#define TESTS_CORE_RENDER_SCENE_H

#include "check.h"
#include "scene_fixture.h"

#define MAXD 20
static uint64_t rng_state = 0xA4093822299F31D0u;
static uint8_t vox[300 * 3 * 2 * 2 + MAXD * MAXD * MAXD];
static _Alignas(16) unsigned char arena_buf[1 << 22];
static _Alignas(16) unsigned char scratch[1 << 20];
static unsigned char pixels[3][200 * 200 * 4];
static vf_tf_point_t tf_pts[8];

static inline uint32_t rnd(uint32_t n)
{
    return check_mod(&rng_state, n);
}

typedef struct scene {
    vf_volume_t vol;
    vf_params_t params;
    vf_arena_t arena;
    vf_renderer_t *r;
} scene_t;

static inline vf_volume_t volume_of(uint32_t nx, uint32_t ny, uint32_t nz)
{
    vf_volume_t v = {{nx, ny, nz}, {65536, 65536, 65536}, VF_VOXEL_U8, vox};
    return v;
}

static inline void fill_random(const vf_volume_t *v)
{
    static const scene_blob_t blob = {.rad_min = 2, .rad_span = 6, .inside = 180, .outside = 30, .noise = 50,
                                      .salt = 12};
    scene_fill_blob(vox, v->dims, &blob, check_mod, &rng_state);
}

static inline vf_tf_t random_tf(void)
{
    static const scene_tf_style_t style = {.step = 15000, .zeros = 1, .faint = 2000};
    return scene_random_tf(tf_pts, &style, check_mod, &rng_state);
}

static inline vf_status_t scene_create(scene_t *s, vf_mode_t mode, uint32_t table_size)
{
    vf_params_default(&s->params);
    s->params.mode = mode;
    s->params.table_size = table_size;
    vf_arena_init(&s->arena, arena_buf, sizeof arena_buf);
    s->r = NULL;
    return vf_renderer_create(&s->r, &s->params, &s->vol, &s->arena);
}

/* The window (0, 255) and tf: the renderer is then ready to draw. */
static inline vf_status_t scene_ready(scene_t *s, const vf_tf_t *tf)
{
    vf_status_t st = vf_renderer_set_window(s->r, (vf_window_t){0, 255});
    return st == VF_OK ? vf_renderer_set_tf(s->r, tf) : st;
}

static inline vf_image_t image_of(int n, uint32_t w, uint32_t h, vf_format_t format)
{
    vf_image_t im = {pixels[n], w, h, w * vf_format_bytes(format), format};
    return im;
}

/* Band scratch for the largest band a frame of the scene's volume can ask for. */
static inline size_t scratch_for(const scene_t *s)
{
    return vf_renderer_band_scratch_bytes(s->r, s->vol.dims[0] + s->vol.dims[1] + s->vol.dims[2]);
}

/* Draws the scene's frame of view into image n, w x h RGB888. */
static inline vf_status_t scene_draw(const scene_t *s, const vf_view_t *view, int n, uint32_t w, uint32_t h)
{
    vf_image_t im = image_of(n, w, h, VF_FORMAT_RGB888);
    return vf_renderer_draw(s->r, view, &im, scratch, scratch_for(s));
}

#endif
