/* SPDX-License-Identifier: MIT */
/*
 * test_ref_view.c: the reference's factorisation, compositing and warp, proved on their own terms: volume
 * corners projected directly (the camera of docs/algorithm.md section 3, written out here again) and through
 * the shear-warp path; tiny volumes with hand-computed pixels; opacities of a constant transfer function
 * counted analytically; symmetries of the whole frame.
 */
#include "check.h"
#include "ref_fixtures.h"
#include "truth/truth.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static uint32_t g_seed = 12345;

static double rnd(void)
{
    return rf_uniform(&g_seed);
}

/* The camera of section 3, independently of ref_factor.c: R = Rz(roll) Rx(elevation) Ry(azimuth). */
static void spec_rotation(const ref_view_t *v, double R[3][3])
{
    double a = v->azimuth * 2 * PI / 65536, e = v->elevation * 2 * PI / 65536, r = v->roll * 2 * PI / 65536;
    double ry[3][3] = {{cos(a), 0, sin(a)}, {0, 1, 0}, {-sin(a), 0, cos(a)}};
    double rx[3][3] = {{1, 0, 0}, {0, cos(e), -sin(e)}, {0, sin(e), cos(e)}};
    double rz[3][3] = {{cos(r), -sin(r), 0}, {sin(r), cos(r), 0}, {0, 0, 1}};
    double t[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            t[i][j] = rx[i][0] * ry[0][j] + rx[i][1] * ry[1][j] + rx[i][2] * ry[2][j];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            R[i][j] = rz[i][0] * t[0][j] + rz[i][1] * t[1][j] + rz[i][2] * t[2][j];
}

/* Final-image position of object point p: px = scale e_x + (W - 1) / 2, e = R Sr (p - c). */
static void spec_project(const ref_volume_t *vol, const ref_view_t *v, int W, int H, const double p[3],
                         double *px, double *py)
{
    double R[3][3], Sr[3], w[3], diag = 0, spmin = fmin(vol->spacing[0], fmin(vol->spacing[1], vol->spacing[2]));
    spec_rotation(v, R);
    for (int a = 0; a < 3; a++) {
        Sr[a] = vol->spacing[a] / spmin;
        w[a] = Sr[a] * (p[a] - (vol->dims[a] - 1) / 2.0);
        diag += pow(Sr[a] * (vol->dims[a] - 1), 2);
    }
    double scale = v->zoom * (W < H ? W : H) / sqrt(diag);
    *px = scale * (R[0][0] * w[0] + R[0][1] * w[1] + R[0][2] * w[2]) + (W - 1) / 2.0;
    *py = scale * (R[1][0] * w[0] + R[1][1] * w[1] + R[1][2] * w[2]) + (H - 1) / 2.0;
}

/* Principal axis by the spec's rule: largest |R[2][a] / Sr_a|, ties within 2^-20 to the lowest axis. */
static int spec_principal_axis(const ref_volume_t *vol, const ref_view_t *v, int *flip)
{
    double R[3][3], d[3], m = 0, spmin = fmin(vol->spacing[0], fmin(vol->spacing[1], vol->spacing[2]));
    spec_rotation(v, R);
    for (int a = 0; a < 3; a++) {
        d[a] = R[2][a] / (vol->spacing[a] / spmin);
        m = fmax(m, fabs(d[a]));
    }
    for (int a = 0; a < 3; a++)
        if (fabs(d[a]) >= m * (1 - ldexp(1, -20))) {
            *flip = d[a] < 0;
            return a;
        }
    return -1;
}

/* ---- factorisation ------------------------------------------------------------------------------------ */

static const ref_view_t special_views[] = {
    {0, 0, 0, 1}, {BAU(45), 0, 0, 1}, {BAU(90), 0, 0, 1}, {BAU(30), BAU(20), 0, 1}, {BAU(60), BAU(-35), 0, 1},
    {BAU(135), BAU(70), 0, 1}, {BAU(180), 0, 0, 1}, {0, BAU(90), 0, 1}, {0, BAU(-90), BAU(30), 1.5},
    {BAU(-100), BAU(10), BAU(200), 0.7}, {BAU(45), BAU(35.2644), 0, 1}, {70000, -70000, 123456, 2.5},
};

static void factor_projects_corners(void)
{
    const struct { int dims[3]; double sp[3]; } vols[] = {
        {{5, 7, 3}, {1, 1, 1}}, {{40, 30, 20}, {3.2, 3.2, 1.5}}, {{10, 10, 10}, {1, 1, 2}}, {{2, 2, 2}, {1, 1, 1}},
        {{64, 9, 33}, {0.7, 2.1, 1.3}},
    };
    const int sizes[][2] = {{64, 48}, {512, 512}, {7, 13}};
    int nspecial = (int)(sizeof special_views / sizeof special_views[0]);
    for (int n = 0; n < nspecial + 300; n++) {
        ref_view_t view = n < nspecial ? special_views[n]
                                       : (ref_view_t){(int32_t)(rnd() * 65536), (int32_t)(rnd() * 65536) - 32768,
                                                      (int32_t)(rnd() * 65536), 0.3 + 3 * rnd()};
        ref_volume_t vol = {{0}, {0}, NULL};
        memcpy(vol.dims, vols[n % 5].dims, sizeof vol.dims);
        memcpy(vol.spacing, vols[n % 5].sp, sizeof vol.spacing);
        int W = sizes[n % 3][0], H = sizes[n % 3][1], flip = -1;
        ref_factor_t f;
        CHECK_EQ(ref_factor(&vol, &view, W, H, &f), 0);
        CHECK_EQ(f.k_axis, spec_principal_axis(&vol, &view, &flip));
        CHECK_EQ(f.k_flip, flip);
        CHECK(f.i_axis == (f.k_axis + 1) % 3 && f.j_axis == (f.k_axis + 2) % 3);
        CHECK(fabs(f.si) <= 1 + 1e-5 && fabs(f.sj) <= 1 + 1e-5);
        /* the slab is the ray's length between consecutive slices: Sr_k / |R[2][k]| */
        double R[3][3];
        spec_rotation(&view, R);
        CHECK_NEAR(f.slab, f.Sr[f.k_axis] / fabs(R[2][f.k_axis]), 1e-12 * f.slab);
        /* the forward warp (intermediate -> final) is the inverse of the warp map */
        double det = f.du_dx * f.dv_dy - f.du_dy * f.dv_dx;
        double snap_px = ldexp(1, -17) * (fabs(f.dv_dy) + fabs(f.du_dy) + fabs(f.dv_dx) + fabs(f.du_dx)) / fabs(det);
        for (int c = 0; c < 8; c++) {
            double p[3] = {(c & 1) * (vol.dims[0] - 1.0), ((c >> 1) & 1) * (vol.dims[1] - 1.0),
                           (c >> 2) * (vol.dims[2] - 1.0)};
            double px, py, ou, ov;
            spec_project(&vol, &view, W, H, p, &px, &py);
            int i = (int)p[f.i_axis], j = (int)p[f.j_axis], k = (int)p[f.k_axis];
            if (f.k_flip)
                k = f.nk - 1 - k;
            ref_factor_offset(&f, k, &ou, &ov);
            double u = i + f.ti + f.si * k, v = j + f.tj + f.sj * k; /* before snapping */
            CHECK(fabs(ou - (f.ti + f.si * k)) <= ldexp(1, -17) && fabs(ov - (f.tj + f.sj * k)) <= ldexp(1, -17));
            CHECK(i + ou >= 0 && i + ou < f.int_w && j + ov >= 0 && j + ov < f.int_h); /* within the last centre + 1 */
            for (int snapped = 0; snapped < 2; snapped++) {
                double du = (snapped ? i + ou : u) - f.u0, dv = (snapped ? j + ov : v) - f.v0;
                double qx = (f.dv_dy * du - f.du_dy * dv) / det, qy = (f.du_dx * dv - f.dv_dx * du) / det;
                double tol = 1e-9 + (snapped ? snap_px : 0);
                CHECK_MSG(fabs(qx - px) <= tol && fabs(qy - py) <= tol,
                          "view %d corner %d (snapped %d): (%.9f, %.9f) vs direct (%.9f, %.9f)", n, c, snapped, qx,
                          qy, px, py);
            }
            double uw, vw;
            ref_factor_warp(&f, px, py, &uw, &vw);
            CHECK_NEAR(uw, u, 1e-9);
            CHECK_NEAR(vw, v, 1e-9);
        }
        /* the intermediate image is tight: its first and last columns and rows are covered by some slice */
        double umin = INFINITY, vmin = INFINITY, umax = -INFINITY, vmax = -INFINITY;
        for (int k = 0; k < f.nk; k++) {
            double ou, ov;
            ref_factor_offset(&f, k, &ou, &ov);
            umin = fmin(umin, ceil(ou));
            vmin = fmin(vmin, ceil(ov));
            umax = fmax(umax, floor(ou + f.ni - 1));
            vmax = fmax(vmax, floor(ov + f.nj - 1));
        }
        CHECK(umin == 0 && vmin == 0 && umax == f.int_w - 1 && vmax == f.int_h - 1);
    }
}

static void factor_principal_axis_and_ties(void)
{
    ref_volume_t vol = {{8, 8, 8}, {1, 1, 1}, NULL};
    const struct { int32_t az, el; int k, flip; double si, sj; } cases[] = {
        {0, 0, 2, 0, 0, 0},            /* i = x, j = y */
        {BAU(45), 0, 0, 1, 0, -1},     /* x and z tie: x; i = y, j = z; d = (-s, 0, c) */
        {BAU(45) - 1, 0, 2, 0, 1, 0},  /* just short of 45: z; si = tan(a) */
        {BAU(45) + 1, 0, 0, 1, 0, -1}, /* just past: x */
        {BAU(90), 0, 0, 1, 0, 0},  {BAU(180), 0, 2, 1, 0, 0}, {BAU(-90), 0, 0, 0, 0, 0},
        {0, BAU(90), 1, 0, 0, 0},      /* i = z, j = x */
        {0, BAU(-90), 1, 1, 0, 0}, {0, BAU(45), 1, 0, -1, 0}, /* y and z tie: y; d = (0, s, c), i = z */
    };
    for (size_t n = 0; n < sizeof cases / sizeof cases[0]; n++) {
        ref_view_t view = {cases[n].az, cases[n].el, 0, 1};
        ref_factor_t f;
        CHECK_EQ(ref_factor(&vol, &view, 16, 16, &f), 0);
        CHECK_MSG(f.k_axis == cases[n].k && f.k_flip == cases[n].flip, "case %zu: axis %d flip %d", n, f.k_axis,
                  f.k_flip);
        CHECK_NEAR(f.si, cases[n].si, 2e-3);
        CHECK_NEAR(f.sj, cases[n].sj, 2e-3);
    }
    /* the band: x's |d| below z's by a relative 2^-22 is still a tie (x wins), by 2^-18 it is not */
    ref_view_t view = {BAU(45), 0, 0, 1};
    ref_factor_t f;
    vol.spacing[0] = 1 + ldexp(1, -22);
    CHECK_EQ(ref_factor(&vol, &view, 16, 16, &f), 0);
    CHECK_EQ(f.k_axis, 0);
    vol.spacing[0] = 1 + ldexp(1, -18);
    CHECK_EQ(ref_factor(&vol, &view, 16, 16, &f), 0);
    CHECK_EQ(f.k_axis, 2);
    /* head on: slab is the k spacing relative to the smallest; at 45 degrees sqrt 2 */
    vol.spacing[0] = 1;
    vol.spacing[2] = 2;
    view.azimuth = 0;
    CHECK_EQ(ref_factor(&vol, &view, 16, 16, &f), 0);
    CHECK(f.k_axis == 2 && f.slab == 2 && f.si == 0 && f.sj == 0 && f.ti == 0 && f.tj == 0);
    CHECK(f.int_w == 8 && f.int_h == 8);
    vol.spacing[2] = 1;
    view.azimuth = BAU(45);
    CHECK_EQ(ref_factor(&vol, &view, 16, 16, &f), 0);
    CHECK_NEAR(f.slab, sqrt(2.0), 1e-15);
    CHECK_NEAR(f.tj, 7, 1e-14);
    CHECK(f.int_w == 8 && f.int_h == 15);
}

static void factor_bad_arguments(void)
{
    ref_volume_t vol = {{8, 8, 8}, {1, 1, 1}, NULL};
    ref_view_t view = {0, 0, 0, 1};
    ref_factor_t f;
    CHECK_EQ(ref_factor(&vol, &view, 0, 16, &f), -1);
    view.zoom = 0;
    CHECK_EQ(ref_factor(&vol, &view, 16, 16, &f), -1);
    view.zoom = 1;
    vol.dims[1] = 1;
    CHECK_EQ(ref_factor(&vol, &view, 16, 16, &f), -1);
    vol.dims[1] = 8;
    vol.spacing[2] = 64.01;
    CHECK_EQ(ref_factor(&vol, &view, 16, 16, &f), -1);
    vol.spacing[2] = 64;
    CHECK_EQ(ref_factor(&vol, &view, 16, 16, &f), 0);
    vol.spacing[2] = 0;
    CHECK_EQ(ref_factor(&vol, &view, 16, 16, &f), -1);
}

/* Another renderer's offsets are adopted only when they belong to the same axis and flip and lie within one
 * 2^-16 grid step of the reference's own: this is how a wrong core factorisation still shows. */
static void factor_adopts_only_close_offsets(void)
{
    ref_volume_t vol = {{12, 10, 9}, {1, 1.5, 1}, NULL};
    ref_view_t view = {5461, 3641, 0, 1}; /* 30, 20 degrees */
    ref_factor_t f;
    CHECK_EQ(ref_factor(&vol, &view, 64, 64, &f), 0);
    int32_t given[2 * 12];
    for (int k = 0; k < f.nk; k++) {
        double ou, ov;
        ref_factor_offset(&f, k, &ou, &ov);
        given[2 * k] = (int32_t)lround(ou * 65536) + (k & 1); /* one grid step off on odd slices: accepted */
        given[2 * k + 1] = (int32_t)lround(ov * 65536);
    }
    ref_factor_t g = f;
    CHECK_EQ(ref_factor_adopt_offsets(&g, given, f.k_axis, f.k_flip), 0);
    double ou, ov;
    ref_factor_offset(&g, 1, &ou, &ov);
    CHECK_EQ(lround(ou * 65536), given[2]);
    g = f;
    CHECK_EQ(ref_factor_adopt_offsets(&g, given, (f.k_axis + 1) % 3, f.k_flip), -2);
    CHECK(g.given_offsets_q16 == NULL);
    g = f;
    CHECK_EQ(ref_factor_adopt_offsets(&g, given, f.k_axis, !f.k_flip), -2);
    given[2 * 3 + 1] += 2; /* two grid steps: a different factorisation */
    g = f;
    CHECK_EQ(ref_factor_adopt_offsets(&g, given, f.k_axis, f.k_flip), -2);
    CHECK(g.given_offsets_q16 == NULL);
}

/* ---- compositing on tiny volumes ---------------------------------------------------------------------- */

/* Tables for f's slab and the intermediate image; returns 0 on success. inter: int_w * int_h * 4. */
static int composite_with(const ref_volume_t *vol, const ref_view_t *view, const ref_tf_point_t *tf, int np,
                          ref_mode_t mode, int N, ref_factor_t *f, double **inter, double **table)
{
    if (ref_factor(vol, view, 16, 16, f))
        return -1;
    *table = malloc(sizeof(double) * 4 * (size_t)N * (size_t)N);
    *inter = malloc(sizeof(double) * 4 * (size_t)f->int_w * (size_t)f->int_h);
    if (!*table || !*inter)
        return -1;
    int rc = mode == REF_MODE_POINT ? ref_point_table(tf, np, N, f->slab, *table)
                                    : ref_preint_table(tf, np, N, f->slab, *table);
    return rc ? rc : ref_composite(vol, f, mode, N, *table, *inter);
}

/* A volume of exactly dims voxels (so that AddressSanitizer sees any read past the last one). */
static int red_then_blue(int x, int y, int z) { (void)x, (void)y; return z ? 255 : 0; }
static int oblique_slices(int x, int y, int z) { (void)y; return z ? 255 * x : 40 + 100 * x; }
static int random_scalar(int x, int y, int z) { (void)x, (void)y, (void)z; return (int)(rnd() * 256); }

static void composite_head_on_closed_form(void)
{
    int dims[3] = {2, 2, 2};
    uint8_t *s = rf_volume_of(dims, rf_const_200);
    ref_volume_t vol = {{2, 2, 2}, {1, 1, 1}, s};
    const ref_tf_point_t tf = {0, 0.2, 0.5, 0.9, 0.3};
    /* scale 1 (zoom sqrt 3 / 4 on 4 x 4): final pixels 1..2 are intermediate pixels 0..1, 0 and 3 outside */
    ref_view_t view = {0, 0, 0, sqrt(3.0) / 4};
    ref_params_t p = {REF_MODE_POINT, 256, {0.1, 0.2, 0.3}, NULL, 0, 0,
                      REF_LOOKUP_NEAREST, 16, REF_CORRECTION_REBUILD, 0, 1, NULL, 0};
    double rgb[4 * 4 * 3], col[3] = {0.2, 0.5, 0.9};
    for (int m = 0; m < 2; m++) {
        p.mode = m ? REF_MODE_PREINT1 : REF_MODE_POINT;
        double A = m ? 0.3 : 1 - 0.7 * 0.7; /* preint1: 1 slab; point: 2 slices */
        ref_factor_t f;
        CHECK_EQ(ref_render(&vol, &tf, 1, &p, &view, 4, 4, rgb, &f), 0);
        CHECK(f.int_w == 2 && f.int_h == 2 && f.slab == 1);
        CHECK_NEAR(f.scale, 1, 1e-15);
        for (int py = 0; py < 4; py++) {
            for (int px = 0; px < 4; px++) {
                int in = px >= 1 && px <= 2 && py >= 1 && py <= 2;
                for (int c = 0; c < 3; c++)
                    CHECK_NEAR(rgb[3 * (4 * py + px) + c], in ? col[c] * A + (1 - A) * p.background[c]
                                                              : p.background[c], 1e-13);
            }
        }
    }
    free(s);
}

static void composite_order_follows_view(void)
{
    int dims[3] = {2, 2, 2};
    uint8_t *s = rf_volume_of(dims, red_then_blue); /* slice z = 0 scalar 0 (red), z = 1 scalar 255 (blue) */
    ref_volume_t vol = {{2, 2, 2}, {1, 1, 1}, s};
    const ref_tf_point_t tf[] = {{0, 1, 0, 0, 0.5}, {255, 0, 0, 1, 0.5}};
    for (int m = 0; m < 2; m++) {
        for (int back = 0; back < 2; back++) {
            ref_view_t view = {back ? BAU(180) : 0, 0, 0, 1};
            ref_factor_t f;
            double *inter = NULL, *table = NULL;
            CHECK_EQ(composite_with(&vol, &view, tf, 2, m ? REF_MODE_PREINT1 : REF_MODE_POINT, 256, &f, &inter,
                                    &table), 0);
            CHECK(f.k_axis == 2 && f.k_flip == back && f.int_w == 2 && f.int_h == 2);
            /* point: 0.5 front, 0.5 of the rest behind; preint1: the table entry (front, back) */
            const double *want = m ? table + 4 * (back ? 255 * 256 + 0 : 0 * 256 + 255) : NULL;
            double pw[4] = {back ? 0.25 : 0.5, 0, back ? 0.5 : 0.25, 0.75};
            for (int n = 0; n < 4; n++)
                for (int c = 0; c < 4; c++)
                    CHECK_NEAR(inter[4 * n + c], m ? want[(c + 1) % 4] : pw[c], 1e-15);
            if (m)
                CHECK((back ? inter[2] > inter[0] : inter[0] > inter[2]));
            free(inter);
            free(table);
        }
    }
    free(s);
}

/* 22.5 degrees azimuth: si = tan 22.5, slice 1 at ou_1 = round(65536 tan 22.5) / 65536; pixel u = 0 sees only
 * slice 0, u = 1 sees slice 0 at x = 1 (the last voxel, weight 0 beyond) and slice 1 at x = 1 - ou_1. */
static void composite_oblique_by_hand(void)
{
    int dims[3] = {2, 2, 2};
    uint8_t *s = rf_volume_of(dims, oblique_slices);
    ref_volume_t vol = {{2, 2, 2}, {1, 1, 1}, s};
    const ref_tf_point_t tf[] = {{0, 0, 1, 0.5, 0}, {255, 1, 0, 0.5, 0.8}};
    ref_view_t view = {BAU(22.5), 0, 0, 1};
    double ou1 = floor(tan(PI / 8) * 65536 + 0.5) / 65536, fx = 1 - ou1;
    int back = (int)floor(255 * fx + 0.5); /* N = 256: idx(s) = round(s) */
    CHECK_EQ(back, 149);
    for (int m = 0; m < 2; m++) {
        ref_factor_t f;
        double *inter = NULL, *table = NULL, ou, ov;
        CHECK_EQ(composite_with(&vol, &view, tf, 2, m ? REF_MODE_PREINT1 : REF_MODE_POINT, 256, &f, &inter, &table),
                 0);
        ref_factor_offset(&f, 1, &ou, &ov);
        CHECK(f.k_axis == 2 && !f.k_flip && ou == ou1 && ov == 0 && f.int_w == 2 && f.int_h == 2);
        for (int v = 0; v < 2; v++) {
            const double *p0 = inter + 4 * (2 * v), *p1 = inter + 4 * (2 * v + 1);
            if (m) {
                const double *e = table + 4 * (140 * 256 + back);
                CHECK(p0[0] == 0 && p0[1] == 0 && p0[2] == 0 && p0[3] == 0);
                for (int c = 0; c < 4; c++)
                    CHECK_NEAR(p1[c], e[(c + 1) % 4], 1e-15);
            } else {
                const double *e0 = table + 4 * 40, *e1 = table + 4 * 140, *e2 = table + 4 * back;
                for (int c = 0; c < 4; c++) {
                    CHECK_NEAR(p0[c], e0[(c + 1) % 4], 1e-15);
                    CHECK_NEAR(p1[c], e1[(c + 1) % 4] + (1 - e1[0]) * e2[(c + 1) % 4], 1e-15);
                }
            }
        }
        free(inter);
        free(table);
    }
    free(s);
}

static void composite_early_termination(void)
{
    int dims[3] = {2, 2, 10};
    uint8_t *s = rf_volume_of(dims, rf_const_200);
    ref_volume_t vol = {{2, 2, 10}, {1, 1, 1}, s};
    ref_view_t view = {0, 0, 0, 1};
    /* a0 0.95: A after 2 segments 0.9975 < 1 - 2^-10 <= 0.999875 after 3, so 3 segments, not 10 (or 9) */
    /* a0 0.4: 0.6^10 > 2^-10, never terminated */
    const double a0[2] = {0.95, 0.4};
    for (int t = 0; t < 2; t++) {
        const ref_tf_point_t tf = {0, 1, 1, 1, a0[t]};
        for (int m = 0; m < 2; m++) {
            ref_factor_t f;
            double *inter = NULL, *table = NULL;
            CHECK_EQ(composite_with(&vol, &view, &tf, 1, m ? REF_MODE_PREINT1 : REF_MODE_POINT, 64, &f, &inter,
                                    &table), 0);
            double A = 1 - pow(1 - a0[t], t == 0 ? 3 : m ? 9 : 10);
            for (int n = 0; n < 4; n++)
                CHECK_NEAR(inter[4 * n + 3], A, 1e-13);
            free(inter);
            free(table);
        }
    }
    free(s);
}

/* A constant TF: every inside sample gives the same entry, so a pixel's opacity is 1 - (1 - a0)^(slab n) with n
 * its number of inside slices (point) or slabs with both slices inside (preint1); the two counts differ by one. */
static void composite_constant_tf_counts(void)
{
    int dims[3] = {9, 7, 5};
    uint8_t *s = rf_volume_of(dims, random_scalar);
    ref_volume_t vol = {{9, 7, 5}, {1, 1.5, 1}, s};
    const ref_tf_point_t tf = {0, 0.3, 0.6, 0.9, 0.05};
    const ref_view_t views[] = {{3000, 2000, 500, 1}, {20000, -7000, 0, 1}, {9000, 12000, 0, 1}, {0, 0, 0, 1}};
    for (int n = 0; n < 4; n++) {
        ref_factor_t f;
        double *inter[2] = {NULL, NULL}, *table[2] = {NULL, NULL};
        for (int m = 0; m < 2; m++)
            CHECK_EQ(composite_with(&vol, &views[n], &tf, 1, m ? REF_MODE_PREINT1 : REF_MODE_POINT, 256, &f,
                                    &inter[m], &table[m]), 0);
        int seen = 0;
        for (int v = 0; v < f.int_h; v++) {
            for (int u = 0; u < f.int_w; u++) {
                int n_in = 0, n_slab = 0, prev = 0;
                for (int k = 0; k < f.nk; k++) {
                    double ou, ov;
                    ref_factor_offset(&f, k, &ou, &ov);
                    int in = u - ou >= 0 && u - ou <= f.ni - 1 && v - ov >= 0 && v - ov <= f.nj - 1;
                    n_in += in;
                    n_slab += in && prev;
                    prev = in;
                }
                CHECK(n_slab == (n_in ? n_in - 1 : 0));
                seen += n_in > 0;
                for (int m = 0; m < 2; m++) {
                    const double *pix = inter[m] + 4 * (v * f.int_w + u);
                    double A = 1 - pow(0.95, f.slab * (m ? n_slab : n_in));
                    CHECK_NEAR(pix[3], A, 1e-13);
                    CHECK_NEAR(pix[0], 0.3 * A, 1e-13);
                    CHECK_NEAR(pix[2], 0.9 * A, 1e-13);
                }
            }
        }
        CHECK(seen > 9 * 7 / 2);
        for (int m = 0; m < 2; m++) {
            free(inter[m]);
            free(table[m]);
        }
    }
    free(s);
}

/* Partial slabs (ref_params_t.partial_slabs): in a uniform volume with a constant TF a ray's opacity is
 * 1 - (1 - a0)^L, L its length inside the box, which the ground truth integrates. With partial slabs every
 * intermediate pixel's ray must match it (preint1: all of it; point: all but the rays that cross a corner of the
 * box within one slab, which order 0 has no sample for); with section 4's rule the rays that enter or leave
 * through a side face lose up to a slab. */
static void composite_partial_slabs_match_truth(void)
{
    int dims[3] = {9, 7, 5};
    uint8_t *s = rf_volume_of(dims, rf_const_200);
    ref_volume_t vol = {{9, 7, 5}, {1, 1.5, 1}, s};
    const ref_tf_point_t tf = {0, 0.3, 0.6, 0.9, 0.05};
    const ref_view_t views[] = {{3000, 2000, 500, 1}, {20000, -7000, 0, 1}, {9000, 12000, 0, 1}, {0, 0, 0, 1}};
    for (int n = 0; n < 4; n++) {
        for (int m = 0; m < 2; m++) {
            ref_mode_t mode = m ? REF_MODE_PREINT1 : REF_MODE_POINT;
            ref_factor_t f;
            double *inter[2] = {NULL, NULL}, *table = NULL;
            CHECK_EQ(composite_with(&vol, &views[n], &tf, 1, mode, 256, &f, &inter[0], &table), 0);
            inter[1] = malloc(sizeof(double) * 4 * (size_t)f.int_w * (size_t)f.int_h);
            CHECK(inter[1] != NULL);
            CHECK_EQ(ref_composite_sides(&vol, &f, mode, REF_LOOKUP_NEAREST, 256, table, NULL, 1, inter[1]), 0);
            double worst[2] = {0, 0}, det = f.du_dx * f.dv_dy - f.du_dy * f.dv_dx;
            int off = 0, seen = 0;
            for (int v = 0; v < f.int_h; v++) {
                for (int u = 0; u < f.int_w; u++) {
                    double ou, ov;
                    ref_factor_offset(&f, 0, &ou, &ov);
                    if ((f.si == 0 && (u - ou == 0 || u - ou == f.ni - 1)) ||
                        (f.sj == 0 && (v - ov == 0 || v - ov == f.nj - 1)))
                        continue; /* a ray along a side face: in or out is down to rounding */
                    /* the final-image point whose ray runs through intermediate pixel (u, v) */
                    double a = u - f.u0, b = v - f.v0, rgba[4];
                    double px = (a * f.dv_dy - b * f.du_dy) / det, py = (f.du_dx * b - f.dv_dx * a) / det;
                    CHECK_EQ(truth_ray(&vol, &tf, 1, &views[n], 16, 16, px, py, rgba), 0);
                    seen += rgba[3] > 0;
                    for (int q = 0; q < 2; q++) {
                        const double *pix = inter[q] + 4 * (v * f.int_w + u);
                        double e = fabs(pix[3] - rgba[3]);
                        worst[q] = fmax(worst[q], e);
                        if (q == 1) {
                            off += e > 1e-4;
                            CHECK_NEAR(pix[0], 0.3 * pix[3], 1e-12); /* a constant colour, whatever the length */
                        }
                    }
                }
            }
            double one_slab = 1 - pow(0.95, f.slab);
            CHECK(seen > 9 * 7 / 2);
            if (n < 3 || !m) /* head on (view 3) no ray crosses a side face; point's slices still add a slab */
                CHECK_MSG(worst[0] > 0.3 * one_slab, "view %d mode %d: section 4's rule off %.3g only", n, m,
                          worst[0]);
            if (m) {
                CHECK_MSG(worst[1] < 1e-4, "view %d: preint1 with partial slabs %.3g from the truth", n, worst[1]);
            } else {
                CHECK_MSG(worst[1] < one_slab, "view %d: point with partial slabs %.3g from the truth", n, worst[1]);
                CHECK_MSG(off * 10 <= seen, "view %d: point: %d of %d rays off", n, off, seen);
            }
            free(inter[0]);
            free(inter[1]);
            free(table);
        }
    }
    free(s);
}

/* ---- the whole frame ------------------------------------------------------------------------------------- */

static int sphere(int x, int y, int z)
{
    double r = sqrt((x - 7.5) * (x - 7.5) + (y - 7.5) * (y - 7.5) + (z - 7.5) * (z - 7.5));
    return r < 7 ? (int)(255 * (1 - r / 7)) : 0;
}

static int smooth_blob(int x, int y, int z)
{
    return (int)(127.5 + 120 * sin(0.5 * x + 0.2) * cos(0.3 * y - 0.4 * z) * (z < 9 ? 1 : 0.5));
}

static const ref_tf_point_t blob_tf[] = {
    {0, 0, 0, 0, 0}, {60, 0.2, 0.1, 0.8, 0}, {140, 1, 0.5, 0.1, 0.3}, {255, 1, 1, 1, 0.9},
};

static void render_symmetric_sphere_axis_views(void)
{
    int dims[3] = {16, 16, 16};
    uint8_t *s = rf_volume_of(dims, sphere);
    ref_volume_t vol = {{16, 16, 16}, {1, 1, 1}, s};
    const ref_view_t views[] = {{0, 0, 0, 1.2}, {16384, 0, 0, 1.2}, {32768, 0, 0, 1.2}, {-16384, 0, 0, 1.2},
                                {0, 16384, 0, 1.2}, {0, -16384, 0, 1.2}, {32768, 16384, 16384, 1.2}};
    static double ref_img[31 * 31 * 3], img[31 * 31 * 3];
    for (int m = 0; m < 2; m++) {
        ref_params_t p = {m ? REF_MODE_PREINT1 : REF_MODE_POINT, 256, {0, 0, 0}, NULL, 0, 0,
                          REF_LOOKUP_NEAREST, 16, REF_CORRECTION_REBUILD, 0, 1, NULL, 0};
        CHECK_EQ(ref_render(&vol, blob_tf, 4, &p, &views[0], 31, 31, ref_img, NULL), 0);
        for (int n = 1; n < 7; n++) {
            ref_factor_t f;
            CHECK_EQ(ref_render(&vol, blob_tf, 4, &p, &views[n], 31, 31, img, &f), 0);
            for (int q = 0; q < 31 * 31 * 3; q++)
                CHECK_MSG(fabs(img[q] - ref_img[q]) < 1e-12, "view %d axis %d: %g vs %g", n, f.k_axis, img[q],
                          ref_img[q]);
        }
        double centre = ref_img[3 * (15 * 31 + 15)];
        CHECK(centre > 0.1);
    }
    free(s);
}

/* Roll does not change the intermediate image; a quarter roll turns the final image a quarter:
 * the point at (px, py) moves to (W - 1 - py, px). */
static void render_roll_turns_image(void)
{
    int dims[3] = {20, 17, 13};
    uint8_t *s = rf_volume_of(dims, smooth_blob);
    ref_volume_t vol = {{20, 17, 13}, {1, 1.25, 1.5}, s};
    enum { W = 24 };
    static double a[W * W * 3], b[W * W * 3];
    for (int m = 0; m < 2; m++) {
        ref_params_t p = {m ? REF_MODE_PREINT1 : REF_MODE_POINT, 128, {0.25, 0.5, 0.75}, NULL, 0, 0,
                          REF_LOOKUP_NEAREST, 16, REF_CORRECTION_REBUILD, 0, 1, NULL, 0};
        ref_view_t v0 = {1234, 567, 0, 1.3}, v1 = {1234, 567, 16384, 1.3};
        ref_factor_t f0, f1;
        CHECK_EQ(ref_render(&vol, blob_tf, 4, &p, &v0, W, W, a, &f0), 0);
        CHECK_EQ(ref_render(&vol, blob_tf, 4, &p, &v1, W, W, b, &f1), 0);
        CHECK(f0.si == f1.si && f0.sj == f1.sj && f0.int_w == f1.int_w && f0.slab == f1.slab);
        for (int py = 0; py < W; py++)
            for (int px = 0; px < W; px++)
                for (int c = 0; c < 3; c++)
                    CHECK_NEAR(b[3 * (px * W + (W - 1 - py)) + c], a[3 * (py * W + px) + c], 1e-9);
    }
    free(s);
}

static void render_random_views_in_range(void)
{
    int dims[3] = {20, 17, 13};
    uint8_t *s = rf_volume_of(dims, smooth_blob);
    ref_volume_t vol = {{20, 17, 13}, {1.5, 1, 2.5}, s};
    static double img[40 * 30 * 3];
    int background_pixels = 0, volume_pixels = 0;
    for (int n = 0; n < 40; n++) {
        ref_params_t p = {n & 1 ? REF_MODE_PREINT1 : REF_MODE_POINT, 2 + (int)(rnd() * 300), {0.2, 0.4, 0.6},
                          NULL, 0, 0, REF_LOOKUP_NEAREST, 16, REF_CORRECTION_REBUILD, 0, 1, NULL, 0};
        ref_view_t v = {(int32_t)(rnd() * 65536), (int32_t)(rnd() * 65536), (int32_t)(rnd() * 65536),
                        0.5 + rnd()};
        CHECK_EQ(ref_render(&vol, blob_tf, 4, &p, &v, 40, 30, img, NULL), 0);
        for (int q = 0; q < 40 * 30; q++) {
            int bg = 1;
            for (int c = 0; c < 3; c++) {
                CHECK(img[3 * q + c] >= 0 && img[3 * q + c] <= 1 + 1e-12);
                bg &= img[3 * q + c] == p.background[c];
            }
            background_pixels += bg;
            volume_pixels += !bg;
        }
    }
    CHECK(background_pixels > 0 && volume_pixels > 0);
    /* bad arguments */
    ref_params_t p = {REF_MODE_POINT, 1, {0, 0, 0}, NULL, 0, 0, REF_LOOKUP_NEAREST, 16, REF_CORRECTION_REBUILD, 0, 1,
                      NULL, 0};
    ref_view_t v = {0, 0, 0, 1};
    CHECK_EQ(ref_render(&vol, blob_tf, 4, &p, &v, 40, 30, img, NULL), -1);
    p.table_size = 1025;
    CHECK_EQ(ref_render(&vol, blob_tf, 4, &p, &v, 40, 30, img, NULL), -1);
    p.table_size = 256;
    p.mode = (ref_mode_t)7;
    CHECK_EQ(ref_render(&vol, blob_tf, 4, &p, &v, 40, 30, img, NULL), -1);
    p.mode = REF_MODE_PREINT1;
    CHECK_EQ(ref_render(&vol, blob_tf, 0, &p, &v, 40, 30, img, NULL), -1);
    CHECK_EQ(ref_render(&vol, blob_tf, 4, &p, &v, 40, 0, img, NULL), -1);
    vol.scalars = NULL;
    CHECK_EQ(ref_render(&vol, blob_tf, 4, &p, &v, 40, 30, img, NULL), -1);
    free(s);
}

CHECK_CASES(CHECK_CASE(factor_projects_corners), CHECK_CASE(factor_principal_axis_and_ties),
            CHECK_CASE(factor_bad_arguments), CHECK_CASE(factor_adopts_only_close_offsets),
            CHECK_CASE(composite_head_on_closed_form), CHECK_CASE(composite_order_follows_view),
            CHECK_CASE(composite_oblique_by_hand), CHECK_CASE(composite_early_termination),
            CHECK_CASE(composite_constant_tf_counts), CHECK_CASE(composite_partial_slabs_match_truth),
            CHECK_CASE(render_symmetric_sphere_axis_views), CHECK_CASE(render_roll_turns_image),
            CHECK_CASE(render_random_views_in_range));
CHECK_RUN("ref_view")
