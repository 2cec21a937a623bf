/* SPDX-License-Identifier: MIT */
/*
 * test_ref_rays.c: the reference's rays per voxel column (docs/algorithm.md section 4b, ref_params_t.rays). R = 1
 * is the image of one ray per voxel column; R = 2^n puts the R = 1 rays at the pixels (R U, R V) and adds the rays
 * between them; a constant volume stays constant wherever a ray crosses the whole box; the warp reads the R-scaled
 * image at (R u, R v); bad R are refused. On Marschner-Lobb 41^3 with `sharp` (512x512, view 30,20) R = 4 brings
 * preint1 closer to the ground truth, and study_floor's floor (the truth's exact integrals at the intermediate
 * pixels, warped) rises with R.
 */
#include "check.h"
#include "io/pngio.h"
#include "ref_fixtures.h"
#include "study.h"
#include "truth/truth.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const int all_rays[] = {1, 2, 4, 8, 16};

static int blob(int x, int y, int z)
{
    return (int)(127.5 + 120 * sin(0.7 * x + 0.2) * cos(0.45 * y - 0.5 * z));
}

/* Peaks, so that neighbouring rays differ, and a ramp, so that nothing terminates everywhere. */
static const ref_tf_point_t blob_tf[] = {
    {0, 0, 0, 0, 0}, {70, 0.2, 0.1, 0.8, 0}, {90, 0.2, 0.1, 0.8, 0.6}, {110, 0.2, 0.1, 0.8, 0},
    {150, 1, 0.5, 0.1, 0.1}, {255, 1, 1, 1, 0.5},
};
static const ref_tf_point_t const_tf = {0, 0.3, 0.6, 0.9, 0.05};

/* Views with every principal axis, both flips and shears of both signs. */
static const ref_view_t views[] = {
    {3000, 2000, 500, 1}, {20000, -7000, 0, 1}, {9000, 12000, 0, 1}, {-25000, 30000, 4000, 1.2},
    {24576, 12743, 0, 1}, {0, 0, 0, 1},
};
#define NVIEWS ((int)(sizeof views / sizeof views[0]))

/* The table a mode composites with (point and preclass: the point table) for f's slab. */
static double *table_for(ref_mode_t mode, const ref_tf_point_t *tf, int np, int N, double slab)
{
    double *t = malloc(sizeof(double) * 4 * (size_t)N * (size_t)N);
    if (t && (mode == REF_MODE_PREINT1 ? ref_preint_table(tf, np, N, slab, t) : ref_point_table(tf, np, N, slab, t))) {
        free(t);
        return NULL;
    }
    return t;
}

/* The intermediate image of R rays (malloc'd; *w x *h), or NULL. */
static double *composite_rays(const ref_volume_t *vol, const ref_factor_t *f, ref_mode_t mode, int N,
                              const double *table, const ref_lut_t *lut, int partial, int rays, int *w, int *h)
{
    if (ref_rays_size(f, rays, w, h))
        return NULL;
    double *inter = malloc(sizeof(double) * 4 * (size_t)*w * (size_t)*h);
    if (inter && ref_composite_rays(vol, f, mode, REF_LOOKUP_NEAREST, N, table, lut, partial, rays, inter)) {
        free(inter);
        return NULL;
    }
    return inter;
}

/* ---- the R-scaled intermediate image ----------------------------------------------------------------------- */

/* R = 1 through every entry point is one image: ref_composite_rays(1) = ref_composite_sides, ref_params_t.rays
 * 0 = 1, ref_warp_rays(1) = ref_warp. The sizes of section 3. */
static void one_ray_is_the_old_image(void)
{
    int dims[3] = {12, 10, 9};
    uint8_t *s = rf_volume_of(dims, blob);
    ref_volume_t vol = {{12, 10, 9}, {1, 1.5, 1.25}, s};
    for (int n = 0; n < NVIEWS; n++) {
        ref_factor_t f;
        CHECK_EQ(ref_factor(&vol, &views[n], 24, 20, &f), 0);
        for (int r = 0; r < 5; r++) {
            int w, h;
            CHECK_EQ(ref_rays_size(&f, all_rays[r], &w, &h), 0);
            CHECK(w == all_rays[r] * (f.int_w - 1) + 1 && h == all_rays[r] * (f.int_h - 1) + 1);
        }
        for (int m = 0; m < 3; m++) {
            double *table = table_for((ref_mode_t)m, blob_tf, 6, 64, f.slab);
            CHECK(table != NULL);
            for (int partial = 0; partial < 2; partial++) {
                int w, h;
                double *a = composite_rays(&vol, &f, (ref_mode_t)m, 64, table, NULL, partial, 1, &w, &h);
                double *b = malloc(sizeof(double) * 4 * (size_t)w * (size_t)h);
                CHECK(a && b && w == f.int_w && h == f.int_h);
                CHECK_EQ(ref_composite_sides(&vol, &f, (ref_mode_t)m, REF_LOOKUP_NEAREST, 64, table, NULL, partial, b),
                         0);
                CHECK(memcmp(a, b, sizeof(double) * 4 * (size_t)w * (size_t)h) == 0);
                free(a);
                free(b);
            }
            free(table);
        }
        static double rgb[3][24 * 20 * 3];
        for (int q = 0; q < 3; q++) {
            ref_params_t p = {REF_MODE_PREINT1, 64, {0.1, 0.2, 0.3}, NULL, 0, 0, REF_LOOKUP_NEAREST, 16,
                              REF_CORRECTION_REBUILD, n & 1, q == 2 ? 2 : q, NULL, 0}; /* rays 0, 1 and 2 */
            CHECK_EQ(ref_render(&vol, blob_tf, 6, &p, &views[n], 24, 20, rgb[q], NULL), 0);
        }
        CHECK(memcmp(rgb[0], rgb[1], sizeof rgb[0]) == 0);
        CHECK(memcmp(rgb[1], rgb[2], sizeof rgb[0]) != 0);
    }
    free(s);
}

/* Pixel (R U, R V) of the R-ray image is the ray through (U, V): bit for bit the R = 1 image's pixel, for point,
 * preint1 and preclass, with and without partial slabs, with and without the lut correction. */
static void rays_keep_the_voxel_rays(void)
{
    int dims[3] = {12, 10, 9};
    uint8_t *s = rf_volume_of(dims, blob);
    ref_volume_t vol = {{12, 10, 9}, {1, 1.5, 1.25}, s};
    ref_lut_t *lut = malloc(sizeof *lut);
    CHECK(lut != NULL);
    int compared = 0;
    for (int n = 0; n < NVIEWS; n++) {
        ref_factor_t f;
        CHECK_EQ(ref_factor(&vol, &views[n], 24, 20, &f), 0);
        CHECK_EQ(ref_lut_init(lut, f.slab), 0);
        for (int m = 0; m < 3; m++) {
            int with_lut = n % 3 == 2; /* tables for d0 = 1, every segment corrected */
            double *table = table_for((ref_mode_t)m, blob_tf, 6, 64, with_lut ? 1.0 : f.slab);
            CHECK(table != NULL);
            for (int partial = 0; partial < 2; partial++) {
                int w1, h1;
                double *one = composite_rays(&vol, &f, (ref_mode_t)m, 64, table, with_lut ? lut : NULL, partial, 1,
                                             &w1, &h1);
                CHECK(one != NULL);
                for (int r = 1; r < 5; r++) {
                    int R = all_rays[r], w, h;
                    double *many = composite_rays(&vol, &f, (ref_mode_t)m, 64, table, with_lut ? lut : NULL, partial,
                                                  R, &w, &h);
                    CHECK(many != NULL);
                    for (int v = 0; v < h1; v++)
                        for (int u = 0; u < w1; u++)
                            for (int c = 0; c < 4; c++) {
                                double a = one[4 * (v * w1 + u) + c], b = many[4 * ((R * v) * w + R * u) + c];
                                CHECK_MSG(a == b, "view %d mode %d partial %d R %d (%d,%d) channel %d: %.17g, %.17g",
                                          n, m, partial, R, u, v, c, a, b);
                                compared += a > 0;
                            }
                    free(many);
                }
                free(one);
            }
            free(table);
        }
    }
    CHECK(compared > 1000);
    free(lut);
    free(s);
}

/* A constant volume and transfer function: every ray that crosses the whole box between the front and back slices
 * (each slice's sample inside) gets the same value, for every R, mode and side-face rule (bit for bit where the
 * scalar is interpolated, which is exact; within rounding for preclass, which interpolates classified entries in
 * double); and there are about R^2 times as many such rays. */
static void constant_volume_is_constant_inside(void)
{
    int dims[3] = {9, 7, 5};
    uint8_t *s = rf_volume_of(dims, rf_const_200);
    ref_volume_t vol = {{9, 7, 5}, {1, 1.5, 1}, s};
    const ref_view_t flat[] = {{3000, 2000, 500, 1}, {-2500, 1500, 0, 1}, {16384 + 3000, -2000, 0, 1}};
    for (int n = 0; n < 3; n++) {
        ref_factor_t f;
        CHECK_EQ(ref_factor(&vol, &flat[n], 16, 16, &f), 0);
        for (int m = 0; m < 3; m++) {
            double *table = table_for((ref_mode_t)m, &const_tf, 1, 256, f.slab);
            CHECK(table != NULL);
            for (int partial = 0; partial < 2; partial++) {
                double value[4] = {-1, -1, -1, -1}; /* order 0's front and back slices differ with partial slabs */
                int count_one = 0;
                for (int r = 0; r < 5; r++) {
                    int R = all_rays[r], w, h, count = 0;
                    double *inter = composite_rays(&vol, &f, (ref_mode_t)m, 256, table, NULL, partial, R, &w, &h);
                    CHECK(inter != NULL);
                    for (int V = 0; V < h; V++)
                        for (int U = 0; U < w; U++) {
                            int through = 1;
                            for (int k = 0; k < f.nk && through; k++) {
                                double ou, ov, x, y;
                                ref_factor_offset(&f, k, &ou, &ov);
                                x = (double)U / R - ou, y = (double)V / R - ov;
                                through = x >= 0 && x <= f.ni - 1 && y >= 0 && y <= f.nj - 1;
                            }
                            if (!through)
                                continue;
                            const double *pix = inter + 4 * ((size_t)V * w + U);
                            if (value[3] < 0)
                                memcpy(value, pix, sizeof value);
                            double tolerance = m == REF_MODE_PRECLASS ? 1e-14 : 0;
                            for (int c = 0; c < 4; c++)
                                CHECK_MSG(fabs(pix[c] - value[c]) <= tolerance,
                                          "view %d mode %d partial %d R %d (%d,%d): %.17g vs %.17g", n, m, partial, R,
                                          U, V, pix[c], value[c]);
                            count++;
                        }
                    if (R == 1)
                        count_one = count;
                    CHECK_MSG(count_one > 0 && count >= R * R * count_one / 2,
                              "view %d R %d: %d rays through (R = 1: %d)", n, R, count, count_one);
                    free(inter);
                }
                CHECK(value[3] > 0.1 && value[3] < 0.5); /* 1 - 0.95^(slabs d): a few slabs of opacity 0.05 */
            }
            free(table);
        }
    }
    free(s);
}

/* Partial slabs with R rays: in a uniform volume with a constant transfer function preint1's every ray has the
 * truth's opacity 1 - (1 - a0)^L, L its length inside the box (as test_ref_view's R = 1 case), at the rays between
 * the voxel columns too. */
static void partial_slabs_match_truth_between_voxels(void)
{
    int dims[3] = {9, 7, 5};
    uint8_t *s = rf_volume_of(dims, rf_const_200);
    ref_volume_t vol = {{9, 7, 5}, {1, 1.5, 1}, s};
    const ref_view_t oblique[] = {{3000, 2000, 500, 1}, {20000, -7000, 0, 1}, {9000, 12000, 0, 1}};
    for (int n = 0; n < 3; n++) {
        ref_factor_t f;
        CHECK_EQ(ref_factor(&vol, &oblique[n], 16, 16, &f), 0);
        double *table = table_for(REF_MODE_PREINT1, &const_tf, 1, 256, f.slab);
        CHECK(table != NULL);
        int w, h, seen = 0, R = 4;
        double *inter = composite_rays(&vol, &f, REF_MODE_PREINT1, 256, table, NULL, 1, R, &w, &h);
        CHECK(inter != NULL);
        double worst = 0, det = f.du_dx * f.dv_dy - f.du_dy * f.dv_dx, ou0, ov0;
        ref_factor_offset(&f, 0, &ou0, &ov0);
        for (int V = 0; V < h; V++)
            for (int U = 0; U < w; U++) {
                double u = (double)U / R, v = (double)V / R, rgba[4];
                if ((f.si == 0 && (u - ou0 == 0 || u - ou0 == f.ni - 1)) ||
                    (f.sj == 0 && (v - ov0 == 0 || v - ov0 == f.nj - 1)))
                    continue; /* a ray along a side face: in or out is down to rounding */
                double a = u - f.u0, b = v - f.v0;
                double px = (a * f.dv_dy - b * f.du_dy) / det, py = (f.du_dx * b - f.dv_dx * a) / det;
                CHECK_EQ(truth_ray(&vol, &const_tf, 1, &oblique[n], 16, 16, px, py, rgba), 0);
                seen += rgba[3] > 0;
                worst = fmax(worst, fabs(inter[4 * ((size_t)V * w + U) + 3] - rgba[3]));
            }
        CHECK(seen > R * R * 9 * 7 / 2);
        CHECK_MSG(worst < 1e-4, "view %d: preint1 with partial slabs and 4 rays %.3g from the truth", n, worst);
        free(inter);
        free(table);
    }
    free(s);
}

static int ramp_xy(int x, int y, int z)
{
    (void)z;
    return 10 + 20 * x + 4 * y;
}

/* Partial slabs' face scalars with R rays: in a volume linear in x and y (which bilinear and trilinear
 * interpolation reproduce), the rays that enter or leave through a side face between voxel columns see the scalar
 * the truth sees there, so preint1's colour stays within the nearest-entry lookup's error of the truth's. */
static void face_scalars_between_voxels(void)
{
    int dims[3] = {9, 7, 5};
    uint8_t *s = rf_volume_of(dims, ramp_xy);
    ref_volume_t vol = {{9, 7, 5}, {1, 1, 1}, s};
    const ref_tf_point_t tf[] = {{0, 0, 0, 1, 0.3}, {255, 1, 0, 0, 0.3}};
    const ref_view_t oblique[] = {{3000, 2000, 500, 1}, {-5000, 7000, 0, 1}, {6000, -9000, 0, 1}};
    for (int n = 0; n < 3; n++) {
        ref_factor_t f;
        CHECK_EQ(ref_factor(&vol, &oblique[n], 16, 16, &f), 0);
        double *table = table_for(REF_MODE_PREINT1, tf, 2, 256, f.slab);
        CHECK(table != NULL);
        int w, h, seen = 0, R = 4;
        double *inter = composite_rays(&vol, &f, REF_MODE_PREINT1, 256, table, NULL, 1, R, &w, &h);
        CHECK(inter != NULL);
        double worst = 0, det = f.du_dx * f.dv_dy - f.du_dy * f.dv_dx;
        for (int V = 0; V < h; V++)
            for (int U = 0; U < w; U++) {
                double u = (double)U / R, v = (double)V / R, rgba[4], ou, ov;
                int in_front, in_back;
                ref_factor_offset(&f, 0, &ou, &ov);
                in_front = u - ou >= 0 && u - ou <= f.ni - 1 && v - ov >= 0 && v - ov <= f.nj - 1;
                ref_factor_offset(&f, f.nk - 1, &ou, &ov);
                in_back = u - ou >= 0 && u - ou <= f.ni - 1 && v - ov >= 0 && v - ov <= f.nj - 1;
                if ((in_front && in_back) || U % R == 0 || V % R == 0)
                    continue; /* the rays between voxel columns that cross a side face */
                double a = u - f.u0, b = v - f.v0;
                double px = (a * f.dv_dy - b * f.du_dy) / det, py = (f.du_dx * b - f.dv_dx * a) / det;
                CHECK_EQ(truth_ray(&vol, tf, 2, &oblique[n], 16, 16, px, py, rgba), 0);
                if (!(rgba[3] > 0.05))
                    continue;
                seen++;
                for (int c = 0; c < 4; c++)
                    worst = fmax(worst, fabs(inter[4 * ((size_t)V * w + U) + c] - rgba[c]));
            }
        printf("# view %d: %d rays, worst %.3g\n", n, seen, worst);
        CHECK(seen > 20);
        CHECK_MSG(worst < 2e-3, "view %d: %.3g from the truth", n, worst);
        free(inter);
        free(table);
    }
    free(s);
}

/* The warp reads the R-ray image at (R u, R v): an R-ray image made by bilinear interpolation of an R = 1 image
 * (which reproduces the bilinear function inside every cell) warps to the R = 1 image's final pixels wherever the
 * final pixel sees a point of [0, int_w - 1] x [0, int_h - 1] (outside, the two fade to transparent over one
 * pixel of their own). */
static void warp_reads_the_scaled_image(void)
{
    int dims[3] = {12, 10, 9};
    uint8_t *s = rf_volume_of(dims, blob);
    ref_volume_t vol = {{12, 10, 9}, {1, 1.5, 1.25}, s};
    enum { W = 40, H = 32 };
    static double one_rgb[W * H * 3], many_rgb[W * H * 3];
    const double bg[3] = {0.1, 0.2, 0.3};
    for (int n = 0; n < NVIEWS; n++) {
        ref_factor_t f;
        CHECK_EQ(ref_factor(&vol, &views[n], W, H, &f), 0);
        double *table = table_for(REF_MODE_PREINT1, blob_tf, 6, 64, f.slab);
        int w1, h1;
        double *one = composite_rays(&vol, &f, REF_MODE_PREINT1, 64, table, NULL, 0, 1, &w1, &h1);
        CHECK(table && one);
        ref_warp(&f, one, bg, one_rgb);
        for (int r = 1; r < 5; r++) {
            int R = all_rays[r], w, h, inside = 0;
            CHECK_EQ(ref_rays_size(&f, R, &w, &h), 0);
            double *many = malloc(sizeof(double) * 4 * (size_t)w * (size_t)h);
            CHECK(many != NULL);
            for (int V = 0; V < h; V++)
                for (int U = 0; U < w; U++) {
                    int u0 = U / R, v0 = V / R, u1 = u0 + (u0 + 1 < w1), v1 = v0 + (v0 + 1 < h1);
                    double fu = (double)(U % R) / R, fv = (double)(V % R) / R;
                    for (int c = 0; c < 4; c++)
                        many[4 * (V * w + U) + c] = (1 - fu) * (1 - fv) * one[4 * (v0 * w1 + u0) + c] +
                                                    fu * (1 - fv) * one[4 * (v0 * w1 + u1) + c] +
                                                    (1 - fu) * fv * one[4 * (v1 * w1 + u0) + c] +
                                                    fu * fv * one[4 * (v1 * w1 + u1) + c];
                }
            CHECK_EQ(ref_warp_rays(&f, R, many, bg, many_rgb), 0);
            for (int py = 0; py < H; py++)
                for (int px = 0; px < W; px++) {
                    double u, v;
                    ref_factor_warp(&f, px, py, &u, &v);
                    if (u < 0 || v < 0 || u > f.int_w - 1 || v > f.int_h - 1)
                        continue;
                    inside++;
                    for (int c = 0; c < 3; c++)
                        CHECK_NEAR(many_rgb[3 * (py * W + px) + c], one_rgb[3 * (py * W + px) + c], 1e-12);
                }
            CHECK(inside > W * H / 4);
            free(many);
        }
        free(one);
        free(table);
    }
    free(s);
}

/* R other than 1, 2, 4, 8, 16 (and 0, for ref_params_t) is refused everywhere. */
static void bad_rays_refused(void)
{
    int dims[3] = {6, 5, 4};
    uint8_t *s = rf_volume_of(dims, blob);
    ref_volume_t vol = {{6, 5, 4}, {1, 1, 1}, s};
    ref_view_t view = {3000, 2000, 0, 1};
    ref_factor_t f;
    CHECK_EQ(ref_factor(&vol, &view, 8, 8, &f), 0);
    static double table[4 * 64 * 64], inter[4 * 64 * 64], rgb[8 * 8 * 3]; /* inter: never written, R is bad */
    CHECK_EQ(ref_preint_table(blob_tf, 6, 64, f.slab, table), 0);
    const int bad[] = {-1, 3, 5, 6, 7, 12, 15, 17, 32, 64, 1 << 16};
    for (size_t b = 0; b < sizeof bad / sizeof bad[0]; b++) {
        int w = -7, h = -7;
        CHECK_EQ(ref_rays_size(&f, bad[b], &w, &h), -1);
        CHECK(w == -7 && h == -7);
        CHECK_EQ(ref_composite_rays(&vol, &f, REF_MODE_PREINT1, REF_LOOKUP_NEAREST, 64, table, NULL, 0, bad[b], inter),
                 -1);
        CHECK_EQ(ref_warp_rays(&f, bad[b], inter, (double[3]){0, 0, 0}, rgb), -1);
        ref_params_t p = {REF_MODE_PREINT1, 64, {0, 0, 0}, NULL, 0, 0, REF_LOOKUP_NEAREST, 16, REF_CORRECTION_REBUILD,
                          0, bad[b], NULL, 0};
        CHECK_EQ(ref_render(&vol, blob_tf, 6, &p, &view, 8, 8, rgb, NULL), -1);
    }
    CHECK_EQ(ref_rays_size(&f, 0, &(int){0}, &(int){0}), -1); /* 0 means 1 in ref_params_t only */
    CHECK_EQ(ref_composite_rays(&vol, &f, REF_MODE_PREINT1, REF_LOOKUP_NEAREST, 64, table, NULL, 0, 0, inter), -1);
    for (int r = 0; r < 5; r++) {
        ref_params_t p = {REF_MODE_PREINT1, 64, {0, 0, 0}, NULL, 0, 0, REF_LOOKUP_NEAREST, 16, REF_CORRECTION_REBUILD,
                          1, all_rays[r], NULL, 0};
        CHECK_EQ(ref_render(&vol, blob_tf, 6, &p, &view, 8, 8, rgb, NULL), 0);
    }
    free(s);
}

/* ---- Marschner-Lobb 41^3, sharp, 512x512, view 30,20 ------------------------------------------------------- */

/* One study for both cases: the truth image is rendered once (study_truth caches it). */
static study_t *ml_study(int *scene)
{
    static study_t *st;
    static int index = -1;
    if (!st) {
        char err[VFP_ERR_LEN];
        st = calloc(1, sizeof *st);
        if (!st)
            return NULL;
        st->threads = 2;
        index = study_add_scene(st, "ml41-sharp", "phantom:marschner-lobb:41", "sharp", 30, 20, 1, 512, err,
                                sizeof err);
        if (index < 0 || !study_truth(st, index, err, sizeof err)) {
            printf("# %s\n", err);
            return NULL;
        }
    }
    *scene = index;
    return st;
}

/* The reference's final image (sim_render_reference: the CLI's path) against the truth. */
static double reference_db(study_t *st, int scene, vf_mode_t mode, int partial, int rays)
{
    sim_scene_t s = st->scenes[scene].scene; /* a copy: the volume is shared, not freed here */
    s.params.mode = mode;
    s.params.partial_slabs = partial != 0;
    s.params.rays = (uint32_t)rays;
    vf_image_t img;
    char err[VFP_ERR_LEN];
    if (sim_render_reference(&s, NULL, &img, err, sizeof err))
        return -1;
    size_t pixels = (size_t)s.width * s.height;
    uint8_t *rgb = malloc(3 * pixels);
    double db = -1;
    if (rgb) {
        vfp_image_to_rgb(&img, rgb);
        sim_diff_t d;
        sim_diff(rgb, st->scenes[scene].truth, pixels, &d);
        db = d.psnr_db;
    }
    free(rgb);
    sim_image_free(&img);
    return db;
}

/* Measured when this was written (256 entries): preint1 19.86 dB from the truth with one ray, 21.72 with 4 x 4
 * (partial slabs: 20.58, 22.80). Asserted: at least 1 dB closer. */
static void rays_bring_preint1_closer_to_truth(void)
{
    int scene;
    study_t *st = ml_study(&scene);
    CHECK(st != NULL);
    for (int partial = 0; partial < 2; partial++) {
        double one = reference_db(st, scene, VF_MODE_PREINT1, partial, 1);
        double four = reference_db(st, scene, VF_MODE_PREINT1, partial, 4);
        printf("# preint1, %s: %.3f dB from the truth with 1 ray, %.3f with 4 x 4\n",
               partial ? "partial slabs" : "whole slabs", one, four);
        CHECK(one > 10 && four > 10);
        CHECK_MSG(four > one + 1, "partial %d: R = 4 %.3f dB, R = 1 %.3f dB", partial, four, one);
    }
}

/* study_floor at R rays per voxel column: the exact integrals at more rays warp closer to the truth. Measured when this was
 * written: see the printed lines; asserted, each doubling of R at least 1 dB higher. */
static void floor_rises_with_rays(void)
{
    int scene;
    study_t *st = ml_study(&scene);
    CHECK(st != NULL);
    double last = 0;
    for (int r = 0; r < 3; r++) {
        study_floor_t fl;
        char err[VFP_ERR_LEN];
        int status = study_floor(st, scene, all_rays[r], 0, &fl, err, sizeof err);
        CHECK_MSG(status == 0, "R %d: %s", all_rays[r], err);
        printf("# R %d: %dx%d rays, floor %.3f dB; preint1 %.3f dB from the truth (partial slabs %.3f)\n",
               all_rays[r], fl.int_w, fl.int_h, fl.exact_db, fl.truth_db[REF_MODE_PREINT1][0],
               fl.truth_db[REF_MODE_PREINT1][1]);
        CHECK(fl.done && fl.rays == all_rays[r]);
        CHECK(fl.exact_db > fl.truth_db[REF_MODE_PREINT1][1]);
        if (r > 0)
            CHECK_MSG(fl.exact_db > last + 1, "R %d: floor %.3f dB, R %d: %.3f dB", all_rays[r], fl.exact_db,
                      all_rays[r - 1], last);
        last = fl.exact_db;
    }
}

CHECK_CASES(CHECK_CASE(one_ray_is_the_old_image), CHECK_CASE(rays_keep_the_voxel_rays),
            CHECK_CASE(constant_volume_is_constant_inside), CHECK_CASE(partial_slabs_match_truth_between_voxels),
            CHECK_CASE(face_scalars_between_voxels), CHECK_CASE(warp_reads_the_scaled_image),
            CHECK_CASE(bad_rays_refused), CHECK_CASE(rays_bring_preint1_closer_to_truth),
            CHECK_CASE(floor_rises_with_rays));
CHECK_RUN("ref_rays")
