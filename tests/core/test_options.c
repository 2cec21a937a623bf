/* SPDX-License-Identifier: MIT */
/*
 * test_options.c: every renderer option (docs/algorithm.md section 4b: mode point / preint1 / preclass, lookup
 * nearest / bilinear, table bits 16 / 8, correction rebuild / lut, buffer slice / image, rays 1 / 2 / 4) composites
 * exactly what sections 4 and 4b say, pixel for pixel, whatever the run-length encoding, the skip links and the
 * buffers skip.
 *
 * The reference here walks every intermediate pixel and every slice, skipping nothing but terminated pixels. It
 * takes the segment arithmetic (table fetch, 8-bit expansion, bilinear weights, lut correction, blend) from the
 * core's own inline helpers (segment.h, classify.h), because what is under test is the skipping and buffering,
 * not that arithmetic (tables and sampling are checked against double in the other suites, and the whole
 * renderer against the double reference in host-sim). So the intermediate images must be bit-identical.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "frame.h"
#include "scene_fixture.h"
#include "segment.h"
#include "volfix_internal.h"

static uint64_t rng_state = 0x082EFA98EC4E6C89u;
static uint32_t rnd(uint32_t n)
{
    return check_mod(&rng_state, n);
}

#define MAXD 18
static uint8_t vox[MAXD * MAXD * MAXD];
static _Alignas(16) unsigned char arena_buf[1 << 22];
static _Alignas(16) unsigned char scratch[1 << 20];
static unsigned char pixels[2][64 * 64 * 3];
#define MAX_RAYS 4
static uint16_t ref_img[(MAX_RAYS * 2 * MAXD) * (MAX_RAYS * 2 * MAXD) * 4];

static void fill_random(const vf_volume_t *v)
{
    static const scene_blob_t blob = {.rad_min = 2, .rad_span = 5, .inside = 170, .outside = 30, .noise = 60,
                                      .salt = 10};
    scene_fill_blob(vox, v->dims, &blob, check_mod, &rng_state);
}

static vf_tf_point_t tf_pts[8];

/* Narrow peaks and plateaus, so that most cells are invisible and the skipping matters. */
static vf_tf_t random_tf(void)
{
    static const scene_tf_style_t style = {.step = 12000, .zeros = 2, .faint = 3000};
    return scene_random_tf(tf_pts, &style, check_mod, &rng_state);
}

/* A volume of 2..MAXD voxels a side over vox, unit spacing, not yet filled. */
static vf_volume_t random_dims(void)
{
    vf_volume_t vol = {{2 + rnd(MAXD - 1), 2 + rnd(MAXD - 1), 2 + rnd(MAXD - 1)}, {65536, 65536, 65536},
                       VF_VOXEL_U8, vox};
    return vol;
}

/* A frame of vol with p, tf and view drawn by a fresh renderer into out, 64 x 48 RGB888; *slab_q16 its slab. */
static vf_status_t draw_fresh(unsigned char *out, const vf_params_t *p, const vf_volume_t *vol, const vf_tf_t *tf,
                              const vf_view_t *view, uint32_t *slab_q16)
{
    vf_arena_t arena;
    vf_renderer_t *r;
    vf_status_t s = scene_renderer(&r, &arena, arena_buf, sizeof arena_buf, p, vol, tf);
    vf_image_t im = {out, 64, 48, 64 * 3, VF_FORMAT_RGB888};
    if (s == VF_OK)
        s = vf_renderer_draw(r, view, &im, scratch, sizeof scratch);
    if (s == VF_OK)
        *slab_q16 = vf_renderer_factor(r)->slab_q16;
    return s;
}

/* Standard voxel (i, j) of standard slice k, i and j clamped to the slice (the padding repeats the edge). */
static uint32_t standard(const vf_volume_t *v, const vf_factor_t *f, uint32_t i, uint32_t j, uint32_t k)
{
    uint32_t p[3];
    p[f->i_axis] = i < f->ni ? i : f->ni - 1;
    p[f->j_axis] = j < f->nj ? j : f->nj - 1;
    p[f->k_axis] = f->k_flip ? f->nk - 1 - k : k;
    return ((const uint8_t *)v->voxels)[((size_t)p[2] * v->dims[1] + p[1]) * v->dims[0] + p[0]];
}

/* The sample of standard slice k at intermediate pixel (u, v), at slice position (u / R - ou_k, v / R - ov_k):
 * false when outside; else its exact value (Q8.32), the four voxels and the fractions. */
typedef struct sample {
    uint64_t s_q32;
    uint32_t vox[4]; /* (i0, j0), (i0 + 1, j0), (i0, j0 + 1), (i0 + 1, j0 + 1) */
    uint32_t fx, fy; /* Q0.16 */
} sample_t;

static bool sample_at(const vf_volume_t *vol, const vf_factor_t *f, uint32_t u, uint32_t v, uint32_t k, sample_t *s)
{
    const int64_t step = 65536 / f->rays;
    int64_t x = (int64_t)u * step - vf_factor_offset_u(f, k), y = (int64_t)v * step - vf_factor_offset_v(f, k);
    if (x < 0 || y < 0 || x > (int64_t)(f->ni - 1) * 65536 || y > (int64_t)(f->nj - 1) * 65536)
        return false;
    uint32_t i0 = (uint32_t)(x >> 16), j0 = (uint32_t)(y >> 16);
    s->fx = (uint32_t)(x & 0xFFFF);
    s->fy = (uint32_t)(y & 0xFFFF);
    for (int n = 0; n < 4; n++)
        s->vox[n] = standard(vol, f, i0 + (n & 1), j0 + (n >> 1), k);
    s->s_q32 = 0;
    for (int n = 0; n < 4; n++)
        s->s_q32 += (uint64_t)s->vox[n] * ((n & 1) ? s->fx : 65536 - s->fx) * ((n >> 1) ? s->fy : 65536 - s->fy);
    return true;
}

/* Section 4 / 4b segment of order 0 (point, preclass) for one sample. */
static void segment0(const vf_renderer_t *r, const sample_t *s, uint32_t seg[4])
{
    const vfi_lookup_ctx_t *c = &r->lookup;
    if (r->params.mode == VF_MODE_PRECLASS) {
        uint32_t e[4][4];
        for (int n = 0; n < 4; n++)
            vfi_fetch(c, r->cls.entry_of_scalar[s->vox[n]], e[n]);
        vfi_lerp(e[0], e[1], s->fx);
        vfi_lerp(e[2], e[3], s->fx);
        vfi_lerp(e[0], e[2], s->fy);
        memcpy(seg, e[0], sizeof e[0]);
    } else if (r->params.lookup == VF_LOOKUP_BILINEAR) {
        uint32_t i, f, nx[4];
        vfi_split_position(c->n, vfi_position_of_sample(&r->cls, s->s_q32), &i, &f);
        vfi_fetch(c, i, seg);
        vfi_fetch(c, i + 1, nx);
        vfi_lerp(seg, nx, f);
    } else {
        vfi_fetch(c, vfi_entry_of_sample(&r->cls, s->s_q32), seg);
    }
    if (c->lut_f)
        vfi_correct(c, seg);
}

/* Section 4 / 4b segment of order 1 for a front and a back sample. */
static void segment1(const vf_renderer_t *r, const sample_t *front, const sample_t *back, uint32_t seg[4])
{
    const vfi_lookup_ctx_t *c = &r->lookup;
    const size_t n = c->n;
    if (r->params.lookup == VF_LOOKUP_BILINEAR) {
        uint32_t i, fi, j, fj, w[4], e[4][4];
        vfi_split_position(c->n, vfi_position_of_sample(&r->cls, front->s_q32), &i, &fi);
        vfi_split_position(c->n, vfi_position_of_sample(&r->cls, back->s_q32), &j, &fj);
        vfi_weights(fi, fj, w); /* one set of four weights, as the core */
        vfi_fetch(c, i * n + j, e[0]);
        vfi_fetch(c, (i + 1) * n + j, e[1]);
        vfi_fetch(c, i * n + j + 1, e[2]);
        vfi_fetch(c, (i + 1) * n + j + 1, e[3]);
        for (int k = 0; k < 4; k++)
            seg[k] = (e[0][k] * w[0] + e[1][k] * w[1] + e[2][k] * w[2] + e[3][k] * w[3] + 0x8000u) >> 16;
    } else {
        vfi_fetch(c, vfi_entry_of_sample(&r->cls, front->s_q32) * n + vfi_entry_of_sample(&r->cls, back->s_q32), seg);
    }
    if (c->lut_f)
        vfi_correct(c, seg);
}

/* Every pixel, every slice or slab, front to back; a segment is always blended (the spec's rule); a terminated
 * pixel takes nothing more. */
static void reference(const vf_renderer_t *r, const vf_volume_t *vol)
{
    const vf_factor_t *f = vf_renderer_factor(r);
    for (uint32_t v = 0; v < f->int_h; v++)
        for (uint32_t u = 0; u < f->int_w; u++) {
            uint16_t px[4] = {0, 0, 0, 0};
            sample_t front, back;
            bool have_front = sample_at(vol, f, u, v, 0, &front);
            if (r->params.mode != VF_MODE_PREINT1 && have_front) {
                uint32_t seg[4];
                segment0(r, &front, seg);
                vfi_blend(px, seg);
            }
            for (uint32_t k = 1; k < f->nk && px[3] < VFI_OPAQUE_Q15; k++) {
                bool have_back = sample_at(vol, f, u, v, k, &back);
                uint32_t seg[4];
                if (r->params.mode != VF_MODE_PREINT1) {
                    if (have_back) {
                        segment0(r, &back, seg);
                        vfi_blend(px, seg);
                    }
                } else if (have_front && have_back) {
                    segment1(r, &front, &back, seg);
                    vfi_blend(px, seg);
                }
                front = back;
                have_front = have_back;
            }
            memcpy(ref_img + ((size_t)v * f->int_w + u) * 4, px, sizeof px);
        }
}

static const char *describe(const vf_params_t *p)
{
    static char text[160];
    snprintf(text, sizeof text, "%s, N %u, %s, %u bits, %s, buffer %s, rays %u", vf_mode_name(p->mode),
             p->table_size, vf_lookup_name(p->lookup), p->table_bits, vf_correction_name(p->correction),
             vf_buffer_name(p->buffer), p->rays);
    return text;
}

static void one_scene(const vf_params_t *params)
{
    vf_volume_t vol = random_dims();
    if (rnd(3) == 0)
        for (int a = 0; a < 3; a++)
            vol.spacing_q16[a] = 40000 + rnd(3 * 65536);
    fill_random(&vol);
    vf_tf_t tf = random_tf();
    vf_arena_t arena;
    vf_renderer_t *r;
    vf_status_t st = scene_renderer(&r, &arena, arena_buf, sizeof arena_buf, params, &vol, &tf);
    if (st != VF_OK) {
        check_fail(__FILE__, __LINE__, "create, window, transfer function (%s): %s", describe(params),
                   vf_status_text(st));
        return;
    }
    for (int frame = 0; frame < 3; frame++) {
        vf_view_t view = {(int32_t)rnd(65536), (int32_t)rnd(65536), (int32_t)rnd(65536), 40000 + rnd(3 * 65536)};
        if (frame == 1) { /* 45-degree family: shears 0 and +-1, ties */
            view.azimuth = (int32_t)rnd(8) * 8192;
            view.elevation = (int32_t)rnd(8) * 8192;
        }
        vf_image_t im = {pixels[0], 64, 48, 64 * 3, VF_FORMAT_RGB888};
        /* bands of a random height, in reverse order */
        st = begin_frame(r, &view, im.width, im.height, 0, false);
        if (st != VF_OK) {
            check_fail(__FILE__, __LINE__, "begin: %s", vf_status_text(st));
            return;
        }
        const vf_factor_t *f = vf_renderer_factor(r);
        uint32_t rows = 1 + rnd(f->int_h);
        for (uint32_t top = (f->int_h - 1) / rows * rows;; top -= rows) {
            uint32_t bottom = top + rows < f->int_h ? top + rows : f->int_h;
            st = vf_renderer_composite_band(r, top, bottom, scratch, vf_renderer_band_scratch_bytes(r, bottom - top));
            if (st != VF_OK) {
                check_fail(__FILE__, __LINE__, "composite: %s", vf_status_text(st));
                return;
            }
            if (top == 0)
                break;
        }
        reference(r, &vol);
        const uint16_t *inter = vfi_renderer_intermediate(r);
        for (size_t e = 0; e < (size_t)f->int_w * f->int_h * 4; e++)
            if (inter[e] != ref_img[e]) {
                size_t p = e / 4;
                check_fail(__FILE__, __LINE__,
                           "%s; volume %ux%ux%u, view (%d, %d, %d): intermediate (%zu, %zu) channel %zu: core %u, "
                           "every-slice reference %u",
                           describe(params), vol.dims[0], vol.dims[1], vol.dims[2], view.azimuth, view.elevation,
                           view.roll, p % f->int_w, p / f->int_w, e % 4, inter[e], ref_img[e]);
                return;
            }
    }
}

static void all_options(void)
{
    const vf_mode_t modes[] = {VF_MODE_POINT, VF_MODE_PREINT1, VF_MODE_PRECLASS};
    const uint32_t sizes[] = {256, 64, 17, 2};
    for (int combo = 0; combo < 3 * 2 * 2 * 2 * 2; combo++) {
        vf_params_t p;
        vf_params_default(&p);
        p.mode = modes[combo % 3];
        p.lookup = (combo / 3) % 2 ? VF_LOOKUP_BILINEAR : VF_LOOKUP_NEAREST;
        p.table_bits = (combo / 6) % 2 ? 8 : 16;
        p.correction = (combo / 12) % 2 ? VF_CORRECTION_LUT : VF_CORRECTION_REBUILD;
        p.buffer = (combo / 24) % 2 ? VF_BUFFER_IMAGE : VF_BUFFER_SLICE;
        for (int t = 0; t < 6 && !check_failed; t++) {
            p.table_size = sizes[t % 4];
            p.rays = 1u << (t % 3); /* 1, 2, 4 */
            one_scene(&p);
        }
        if (check_failed)
            return;
    }
}

/* The buffer option changes no pixel (section 4b). */
static void buffers_identical(void)
{
    for (int t = 0; t < 20; t++) {
        vf_params_t p;
        vf_params_default(&p);
        p.lookup = t % 2 ? VF_LOOKUP_BILINEAR : VF_LOOKUP_NEAREST;
        vf_volume_t vol = random_dims();
        fill_random(&vol);
        vf_tf_t tf = random_tf();
        vf_view_t view = {(int32_t)rnd(65536), (int32_t)rnd(65536), (int32_t)rnd(65536), 65536};
        for (int b = 0; b < 2; b++) {
            p.buffer = b ? VF_BUFFER_IMAGE : VF_BUFFER_SLICE;
            uint32_t slab;
            CHECK_EQ(draw_fresh(pixels[b], &p, &vol, &tf, &view, &slab), VF_OK);
        }
        CHECK(memcmp(pixels[0], pixels[1], 64 * 48 * 3) == 0);
    }
}

/* With a slab of exactly 1 (isotropic voxels, straight down an axis), the lut correction has rho = 1: F(a) = a,
 * G(a) = 1, so every corrected segment is the segment itself (to rounding), and the picture is the rebuild
 * picture within a level or two. */
static void lut_at_unit_slab(void)
{
    for (int t = 0; t < 8; t++) {
        vf_params_t p;
        vf_params_default(&p);
        p.mode = t % 3 == 0 ? VF_MODE_POINT : t % 3 == 1 ? VF_MODE_PREINT1 : VF_MODE_PRECLASS;
        vf_volume_t vol = random_dims();
        fill_random(&vol);
        vf_tf_t tf = random_tf();
        tf_pts[0].a = 20000;
        vf_view_t view = {(int32_t)rnd(4) * 16384, 0, 0, 65536};
        for (int c = 0; c < 2; c++) {
            p.correction = c ? VF_CORRECTION_LUT : VF_CORRECTION_REBUILD;
            uint32_t slab;
            CHECK_EQ(draw_fresh(pixels[c], &p, &vol, &tf, &view, &slab), VF_OK);
            CHECK_EQ(slab, 65536);
        }
        for (size_t e = 0; e < 64 * 48 * 3; e++)
            CHECK_MSG(abs((int)pixels[0][e] - (int)pixels[1][e]) <= 2, "%s: pixel %zu channel %zu: rebuild %u, lut %u",
                      vf_mode_name(p.mode), e / 3, e % 3, pixels[0][e], pixels[1][e]);
    }
}

static void option_arguments(void)
{
    vf_volume_t vol = {{5, 5, 5}, {65536, 65536, 65536}, VF_VOXEL_U8, vox};
    vf_params_t p;
    vf_params_default(&p);
    CHECK_EQ(p.table_bits, 16);
    CHECK_EQ(p.lookup, VF_LOOKUP_NEAREST);
    CHECK_EQ(p.correction, VF_CORRECTION_REBUILD);
    CHECK_EQ(p.buffer, VF_BUFFER_SLICE);
    size_t bytes;
    vf_params_t q = p;
    const uint32_t bad_bits[] = {0, 1, 4, 7, 9, 11, 15, 17, 32}; /* 8, 10, 12 and 16 are valid */
    for (size_t n = 0; n < sizeof bad_bits / sizeof bad_bits[0]; n++) {
        q.table_bits = bad_bits[n];
        CHECK_EQ(vf_renderer_bytes(&q, &vol, &bytes), VF_ERR_ARG);
    }
    q = p;
    q.lookup = VF_LOOKUP_COUNT;
    CHECK_EQ(vf_renderer_bytes(&q, &vol, &bytes), VF_ERR_ARG);
    q = p;
    q.correction = VF_CORRECTION_COUNT;
    CHECK_EQ(vf_renderer_bytes(&q, &vol, &bytes), VF_ERR_ARG);
    q = p;
    q.buffer = VF_BUFFER_COUNT;
    CHECK_EQ(vf_renderer_bytes(&q, &vol, &bytes), VF_ERR_ARG);
    /* 8-bit tables take half the table memory */
    size_t b16, b8;
    q = p;
    CHECK_EQ(vf_renderer_bytes(&q, &vol, &b16), VF_OK);
    q.table_bits = 8;
    CHECK_EQ(vf_renderer_bytes(&q, &vol, &b8), VF_OK);
    CHECK(b16 - b8 >= (size_t)256 * 256 * 4 - 16);
    /* rays: 1, 2, 4, 8 or 16, one ray by default; the intermediate image, and so the memory, R^2 times larger;
     * too many for the skip links' 16 bits is an error of its own; partial slabs not with the lut */
    CHECK_EQ(p.rays, 1);
    CHECK(!p.partial_slabs);
    const uint32_t bad_rays[] = {0, 3, 5, 6, 7, 9, 12, 15, 17, 32, UINT32_MAX};
    for (size_t n = 0; n < sizeof bad_rays / sizeof bad_rays[0]; n++) {
        q = p;
        q.rays = bad_rays[n];
        CHECK_MSG(vf_renderer_bytes(&q, &vol, &bytes) == VF_ERR_ARG, "rays %u accepted", bad_rays[n]);
    }
    size_t b1, b4;
    q = p;
    CHECK_EQ(vf_renderer_bytes(&q, &vol, &b1), VF_OK);
    q.rays = 4;
    CHECK_EQ(vf_renderer_bytes(&q, &vol, &b4), VF_OK);
    CHECK(b4 > b1 + (size_t)8 * (4 * (5 + 5 - 2) + 1) * (4 * (5 + 5 - 2) + 1) - (size_t)8 * 9 * 9 - 64);
    vf_volume_t wide = {{4096, 2, 40}, {65536, 65536, 65536}, VF_VOXEL_U8, vox}; /* never read: sizes only */
    q.rays = 16;
    CHECK_EQ(vf_renderer_bytes(&q, &wide, &bytes), VF_ERR_INTERMEDIATE);
    q.rays = 8;
    CHECK_EQ(vf_renderer_bytes(&q, &wide, &bytes), VF_OK);
    q = p;
    q.partial_slabs = true;
    CHECK_EQ(vf_renderer_bytes(&q, &vol, &bytes), VF_OK);
    q.correction = VF_CORRECTION_LUT;
    CHECK_EQ(vf_renderer_bytes(&q, &vol, &bytes), VF_ERR_UNSUPPORTED);
    /* vf_factor_rays: the warp map scales exactly, the sizes keep the same intermediate points */
    vf_factor_t f1, f4;
    vf_view_t view = {3000, -7000, 500, 70000};
    CHECK_EQ(vf_factor(&f1, &vol, &view, 64, 48), VF_OK);
    f4 = f1;
    CHECK_EQ(vf_factor_rays(NULL, 4), VF_ERR_NULL);
    CHECK_EQ(vf_factor_rays(&f4, 3), VF_ERR_ARG);
    CHECK_EQ(vf_factor_rays(&f4, 4), VF_OK);
    CHECK_EQ(f4.rays, 4);
    CHECK_EQ(f4.int_w, 4 * (f1.int_w - 1) + 1);
    CHECK_EQ(f4.int_h, 4 * (f1.int_h - 1) + 1);
    CHECK(f4.u0_q32 == 4 * f1.u0_q32 && f4.du_dx_q32 == 4 * f1.du_dx_q32 && f4.dv_dy_q32 == 4 * f1.dv_dy_q32);
    CHECK(f4.si_q32 == f1.si_q32 && f4.slab_q16 == f1.slab_q16 && vf_factor_offset_u(&f4, 3) == vf_factor_offset_u(&f1, 3));
    CHECK_EQ(vf_factor_rays(&f4, 2), VF_ERR_ARG); /* only from one ray per voxel */
    CHECK(strcmp(vf_status_text(VF_ERR_INTERMEDIATE), vf_status_text(VF_ERR_ARG)) != 0);
    /* names */
    CHECK(vf_lookup_name(VF_LOOKUP_NEAREST) && vf_lookup_name(VF_LOOKUP_BILINEAR) && vf_lookup_name(VF_LOOKUP_COUNT));
    CHECK(strcmp(vf_lookup_name(VF_LOOKUP_NEAREST), vf_lookup_name(VF_LOOKUP_BILINEAR)) != 0);
    CHECK(strcmp(vf_correction_name(VF_CORRECTION_REBUILD), vf_correction_name(VF_CORRECTION_LUT)) != 0);
    CHECK(strcmp(vf_buffer_name(VF_BUFFER_SLICE), vf_buffer_name(VF_BUFFER_IMAGE)) != 0);
    CHECK(strcmp(vf_mode_name(VF_MODE_PRECLASS), vf_mode_name(VF_MODE_POINT)) != 0);
}

CHECK_CASES(CHECK_CASE(all_options), CHECK_CASE(buffers_identical), CHECK_CASE(lut_at_unit_slab),
            CHECK_CASE(option_arguments));
CHECK_RUN("core/options")
