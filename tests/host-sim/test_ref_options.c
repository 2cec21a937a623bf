/* SPDX-License-Identifier: MIT */
/*
 * test_ref_options.c: the options of docs/algorithm.md section 4b in the reference, proved on their own terms:
 * bilinear lookup against hand values and a table that is bilinear in its indices, 8-bit tables against the
 * rounding rule, the lut correction against the exact F and G and against rebuilt tables where it must agree
 * with them, preclass against point where they must agree and by hand where they must not, and bad arguments.
 * REF_VERBOSE=1 prints the measured differences.
 */
#include "check.h"
#include "ref_fixtures.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static uint32_t g_seed = 4242;

static double rnd(void)
{
    return rf_uniform(&g_seed);
}

static int verbose(void)
{
    return getenv("REF_VERBOSE") != NULL;
}

static int const_100(int x, int y, int z) { (void)x, (void)y, (void)z; return 100; }
static int ramp_x(int x, int y, int z) { (void)y, (void)z; return 255 * x; }
static int random_scalar(int x, int y, int z) { (void)x, (void)y, (void)z; return (int)(rnd() * 256); }

static ref_params_t params(ref_mode_t mode, int N)
{
    return (ref_params_t){mode, N, {0, 0, 0}, NULL, 0, 0, REF_LOOKUP_NEAREST, 16, REF_CORRECTION_REBUILD, 0, 1, NULL,
                          0};
}

static const ref_mode_t modes[3] = {REF_MODE_POINT, REF_MODE_PREINT1, REF_MODE_PRECLASS};

/* ---- bilinear lookup ----------------------------------------------------------------------------------- */

/* N = 5: entries at s = 0, 63.75, 127.5, 191.25, 255, so x = s (N - 1) / 255 is exact at those and halfway. One
 * entry past the table holds NaN: reading it (i not clamped at N - 2 for x = N - 1) would poison the result. */
static void lookup_point_by_hand(void)
{
    enum { N = 5 };
    double *T = malloc(sizeof(double) * 4 * (N + 1)), out[4], near[4];
    for (int i = 0; i < N; i++)
        for (int c = 0; c < 4; c++)
            T[4 * i + c] = (i + 1) * (c + 1) + 0.5 * i * i; /* not linear in i */
    for (int c = 0; c < 4; c++)
        T[4 * N + c] = NAN;
    for (int i = 0; i < N; i++) { /* on an entry: bilinear is nearest, exactly */
        ref_lookup_point(T, N, REF_LOOKUP_BILINEAR, i * 63.75, out);
        ref_lookup_point(T, N, REF_LOOKUP_NEAREST, i * 63.75, near);
        for (int c = 0; c < 4; c++)
            CHECK_MSG(out[c] == near[c] && out[c] == T[4 * i + c], "entry %d channel %d: %.17g vs %.17g", i, c,
                      out[c], near[c]);
    }
    for (int i = 0; i + 1 < N; i++) { /* halfway: the mean */
        ref_lookup_point(T, N, REF_LOOKUP_BILINEAR, (i + 0.5) * 63.75, out);
        for (int c = 0; c < 4; c++)
            CHECK_NEAR(out[c], (T[4 * i + c] + T[4 * (i + 1) + c]) / 2, 1e-15);
    }
    /* s = 255: x = N - 1, i = N - 2, f = 1 */
    ref_lookup_point(T, N, REF_LOOKUP_BILINEAR, 255, out);
    for (int c = 0; c < 4; c++)
        CHECK_MSG(out[c] == T[4 * (N - 1) + c], "s = 255 channel %d: %.17g", c, out[c]);
    /* s = 200: x = 800 / 255 = 3 + 35 / 255 */
    ref_lookup_point(T, N, REF_LOOKUP_BILINEAR, 200, out);
    for (int c = 0; c < 4; c++)
        CHECK_NEAR(out[c], (220.0 / 255) * T[12 + c] + (35.0 / 255) * T[16 + c], 1e-14);
    ref_lookup_point(T, N, REF_LOOKUP_NEAREST, 200, out); /* nearest: round(3.137) = 3 */
    CHECK(out[0] == T[12]);
    free(T);

    /* N = 256 (x = s) and N = 2 (x = s / 255) */
    double *U = malloc(sizeof(double) * 4 * 256);
    for (int i = 0; i < 256; i++)
        for (int c = 0; c < 4; c++)
            U[4 * i + c] = sin(i * 0.1 + c);
    ref_lookup_point(U, 256, REF_LOOKUP_BILINEAR, 100.25, out);
    for (int c = 0; c < 4; c++)
        CHECK_NEAR(out[c], 0.75 * U[400 + c] + 0.25 * U[404 + c], 1e-15);
    ref_lookup_point(U, 256, REF_LOOKUP_BILINEAR, 255, out);
    CHECK(out[1] == U[4 * 255 + 1]);
    ref_lookup_point(U, 2, REF_LOOKUP_BILINEAR, 51, out);
    for (int c = 0; c < 4; c++)
        CHECK_NEAR(out[c], 0.8 * U[c] + 0.2 * U[4 + c], 1e-15);
    ref_lookup_point(U, 2, REF_LOOKUP_BILINEAR, 255, out);
    CHECK(out[2] == U[6]);
    free(U);
}

/* N = 4 (entries at s = 85 i). A table bilinear in its indices, T[i][j] = (1 + c)(2 + 3i + 5j + 7ij), is
 * reproduced exactly at any (x, y); a table that is not, by hand at chosen points; (front, back) is not
 * (back, front). A NaN row past the table catches a front index not clamped at N - 2. */
static void lookup_preint_by_hand(void)
{
    enum { N = 4 };
    double *L = malloc(sizeof(double) * 4 * N * (N + 1)), *Q = malloc(sizeof(double) * 4 * N * (N + 1));
    for (int i = 0; i <= N; i++)
        for (int j = 0; j < N; j++)
            for (int c = 0; c < 4; c++) {
                L[4 * (i * N + j) + c] = i < N ? (1 + c) * (2 + 3 * i + 5 * j + 7 * i * j) : NAN;
                Q[4 * (i * N + j) + c] = i < N ? (1 + c) * (i * i + 10 * j * j) + 100 * (i > j) : NAN;
            }
    double out[4], near[4];
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            ref_lookup_preint(Q, N, REF_LOOKUP_BILINEAR, 85 * i, 85 * j, out);
            ref_lookup_preint(Q, N, REF_LOOKUP_NEAREST, 85 * i, 85 * j, near);
            for (int c = 0; c < 4; c++)
                CHECK(out[c] == near[c] && out[c] == Q[4 * (i * N + j) + c]);
        }
    for (int n = 0; n < 200; n++) {
        double sf = n < 3 ? 255.0 * n / 2 : rnd() * 255, sb = n < 3 ? 255 : rnd() * 255;
        double x = sf * 3 / 255, y = sb * 3 / 255;
        ref_lookup_preint(L, N, REF_LOOKUP_BILINEAR, sf, sb, out);
        for (int c = 0; c < 4; c++)
            CHECK_NEAR(out[c], (1 + c) * (2 + 3 * x + 5 * y + 7 * x * y), 1e-12);
    }
    /* front 85 (x = 1), back 127.5 (y = 1.5): half of (1, 1) and (1, 2) */
    ref_lookup_preint(Q, N, REF_LOOKUP_BILINEAR, 85, 127.5, out);
    CHECK_NEAR(out[0], (Q[4 * 5] + Q[4 * 6]) / 2, 1e-15);
    /* front 42.5 (x = 0.5), back 255 (y = 3: j = 2, g = 1): half of (0, 3) and (1, 3) */
    ref_lookup_preint(Q, N, REF_LOOKUP_BILINEAR, 42.5, 255, out);
    CHECK_NEAR(out[1], (Q[4 * 3 + 1] + Q[4 * 7 + 1]) / 2, 1e-15);
    /* front 255, back 0 and the reverse: the corners (3, 0) and (0, 3) */
    ref_lookup_preint(Q, N, REF_LOOKUP_BILINEAR, 255, 0, out);
    CHECK(out[0] == Q[4 * 12] && out[0] == 109);
    ref_lookup_preint(Q, N, REF_LOOKUP_BILINEAR, 0, 255, out);
    CHECK(out[0] == Q[4 * 3] && out[0] == 90);
    /* front 200 (x = 600/255: i = 2, f = 90/255), back 30 (y = 90/255: j = 0, g = 90/255) */
    double f = 90.0 / 255, g = 90.0 / 255;
    ref_lookup_preint(Q, N, REF_LOOKUP_BILINEAR, 200, 30, out);
    for (int c = 0; c < 4; c++) {
        double t00 = (1 + c) * 4 + 100, t10 = (1 + c) * 9 + 100, t01 = (1 + c) * 14 + 100, t11 = (1 + c) * 19 + 100;
        CHECK_NEAR(out[c], (1 - f) * (1 - g) * t00 + f * (1 - g) * t10 + (1 - f) * g * t01 + f * g * t11, 1e-13);
    }
    free(L);
    free(Q);
}

/* Bilinear lookup in ref_render: a 2x2x2 volume of 100 seen head on (2 slices, 1 slab, slab length 1), N = 3:
 * x = 200 / 255, i = 0, f = 200 / 255. Nearest would be entry 1. */
static void lookup_bilinear_render(void)
{
    int dims[3] = {2, 2, 2};
    uint8_t *s = rf_volume_of(dims, const_100);
    ref_volume_t vol = {{2, 2, 2}, {1, 1, 1}, s};
    const ref_tf_point_t tf[] = {{0, 1, 0, 0, 0.1}, {127.5, 0, 1, 0, 0.7}, {255, 0, 0, 1, 0.3}};
    ref_view_t view = {0, 0, 0, sqrt(3.0) / 4}; /* scale 1: final pixels 1..2 are intermediate pixels 0..1 */
    double P[4 * 3], T[4 * 9], f = 200.0 / 255, rgb[4 * 4 * 3];
    CHECK_EQ(ref_point_table(tf, 3, 3, 1.0, P), 0);
    CHECK_EQ(ref_preint_table(tf, 3, 3, 1.0, T), 0);
    for (int m = 0; m < 2; m++) {
        ref_params_t p = params(m ? REF_MODE_PREINT1 : REF_MODE_POINT, 3);
        p.lookup = REF_LOOKUP_BILINEAR;
        CHECK_EQ(ref_render(&vol, tf, 3, &p, &view, 4, 4, rgb, NULL), 0);
        double seg[4];
        for (int c = 0; c < 4; c++)
            seg[c] = m ? (1 - f) * (1 - f) * T[c] + f * (1 - f) * (T[12 + c] + T[4 + c]) + f * f * T[16 + c]
                       : (1 - f) * P[c] + f * P[4 + c];
        double A = m ? seg[0] : seg[0] + (1 - seg[0]) * seg[0];
        for (int c = 0; c < 3; c++) {
            double C = m ? seg[1 + c] : seg[1 + c] * (2 - seg[0]);
            CHECK_NEAR(rgb[3 * (4 * 1 + 1) + c], C, 1e-15);
            CHECK_NEAR(rgb[3 * (4 * 2 + 2) + c], C, 1e-15);
        }
        CHECK(A > 0 && fabs(A - (m ? T[16] : 1 - (1 - P[4]) * (1 - P[4]))) > 0.05); /* not nearest */
    }
    free(s);
}

/* Samples on entries (head on, integer scalars, N = 256): bilinear and nearest give the same image. */
static void lookup_bilinear_on_entries_is_nearest(void)
{
    int dims[3] = {6, 5, 4};
    uint8_t *s = rf_volume_of(dims, random_scalar);
    ref_volume_t vol = {{6, 5, 4}, {1, 1, 1}, s};
    ref_tf_point_t tf[33];
    int np = rf_smooth_tf(tf, 0.6);
    ref_view_t view = {0, 0, 0, 1};
    static double a[20 * 20 * 3], b[20 * 20 * 3];
    for (int m = 0; m < 2; m++) {
        ref_params_t p = params(m ? REF_MODE_PREINT1 : REF_MODE_POINT, 256);
        CHECK_EQ(ref_render(&vol, tf, np, &p, &view, 20, 20, a, NULL), 0);
        p.lookup = REF_LOOKUP_BILINEAR;
        CHECK_EQ(ref_render(&vol, tf, np, &p, &view, 20, 20, b, NULL), 0);
        CHECK(memcmp(a, b, sizeof a) == 0);
    }
    free(s);
}

/* ---- 8-bit tables -------------------------------------------------------------------------------------- */

static void table_bits_rounding(void)
{
    ref_tf_point_t tf[33];
    int np = rf_smooth_tf(tf, 0.9);
    enum { NP = 256, NI = 64 };
    static double t16[4 * NI * NI + 4 * NP], t8[4 * NI * NI + 4 * NP];
    CHECK_EQ(ref_point_table(tf, np, NP, 1.3, t16), 0);
    CHECK_EQ(ref_preint_table(tf, np, NI, 1.3, t16 + 4 * NP), 0);
    size_t count = sizeof t16 / sizeof t16[0];
    memcpy(t8, t16, sizeof t8);
    CHECK_EQ(ref_table_bits(t8, count, 16), 0);
    CHECK(memcmp(t8, t16, sizeof t8) == 0);
    CHECK_EQ(ref_table_bits(t8, count, 0), 0); /* 0: the default, 16 */
    CHECK(memcmp(t8, t16, sizeof t8) == 0);
    CHECK_EQ(ref_table_bits(t8, count, 8), 0);
    size_t changed = 0;
    for (size_t n = 0; n < count; n++) {
        double q = t8[n] * 255, k = floor(t16[n] * 255 + 0.5);
        CHECK_MSG(q == floor(q) && t8[n] == k / 255, "value %zu: %.17g (from %.17g)", n, t8[n], t16[n]);
        CHECK_MSG(fabs(t8[n] - t16[n]) <= 0.5 / 255 + 1e-16, "value %zu moved by %.3g", n, t8[n] - t16[n]);
        changed += t8[n] != t16[n];
    }
    CHECK(changed > count / 2);
    memcpy(t16, t8, sizeof t8); /* idempotent */
    CHECK_EQ(ref_table_bits(t8, count, 8), 0);
    CHECK(memcmp(t8, t16, sizeof t8) == 0);
    double half[3] = {2.5 / 255 + 1e-12, 2.5 / 255 - 1e-12, 1.0};
    CHECK_EQ(ref_table_bits(half, 3, 8), 0);
    CHECK(half[0] == 3.0 / 255 && half[1] == 2.0 / 255 && half[2] == 1.0);
    const int bad[] = {1, 7, 9, 12, 15, 32, -8, 24};
    for (int n = 0; n < 8; n++)
        CHECK_EQ(ref_table_bits(t8, count, bad[n]), -1);
    CHECK(memcmp(t8, t16, sizeof t8) == 0);
}

/* 8-bit tables in ref_render, by hand: a 2x2x2 constant volume head on, constant TF a0 = 0.35: a = 89.25 / 255
 * rounds to 89 / 255, C = (17.85, 44.625, 80.325) / 255 to (18, 45, 80) / 255. */
static void table_bits_render_by_hand(void)
{
    int dims[3] = {2, 2, 2};
    uint8_t *s = rf_volume_of(dims, rf_const_200);
    ref_volume_t vol = {{2, 2, 2}, {1, 1, 1}, s};
    const ref_tf_point_t tf = {0, 0.2, 0.5, 0.9, 0.35};
    ref_view_t view = {0, 0, 0, sqrt(3.0) / 4};
    double rgb[4 * 4 * 3], a = 89.0 / 255, C[3] = {18.0 / 255, 45.0 / 255, 80.0 / 255};
    for (int m = 0; m < 3; m++) {
        ref_params_t p = params(modes[m], 256);
        p.table_bits = 8;
        p.background[0] = 0.25;
        CHECK_EQ(ref_render(&vol, &tf, 1, &p, &view, 4, 4, rgb, NULL), 0);
        double A = modes[m] == REF_MODE_PREINT1 ? a : 1 - (1 - a) * (1 - a);
        for (int c = 0; c < 3; c++) {
            double want = (modes[m] == REF_MODE_PREINT1 ? C[c] : C[c] * (2 - a)) + (c ? 0 : 0.25 * (1 - A));
            CHECK_NEAR(rgb[3 * (4 * 2 + 1) + c], want, 1e-15);
        }
        p.table_bits = 16;
        double rgb16[4 * 4 * 3];
        CHECK_EQ(ref_render(&vol, &tf, 1, &p, &view, 4, 4, rgb16, NULL), 0);
        CHECK(fabs(rgb16[3 * (4 * 2 + 1) + 1] - rgb[3 * (4 * 2 + 1) + 1]) > 1e-4);
    }
    free(s);
}

/* ---- lut correction ------------------------------------------------------------------------------------ */

static double exact_F(double a, double rho) { return 1 - pow(1 - a, rho); }

static void lut_knots_and_between(void)
{
    const double rhos[] = {0.55, 1.0, 1.7, 2.9, 64 * sqrt(3.0)};
    for (int r = 0; r < 5; r++) {
        double rho = rhos[r];
        static ref_lut_t lut;
        CHECK_EQ(ref_lut_init(&lut, rho), 0);
        CHECK(lut.rho == rho && lut.G[0] == rho && lut.F[0] == 0 && lut.F[REF_LUT_KNOTS] == 1);
        for (int k = 0; k <= REF_LUT_KNOTS; k++) {
            double a = k / 1024.0, F = exact_F(a, rho), G = k ? F / a : rho, seg[4] = {a, 0.25, 0.5, 1};
            CHECK_NEAR(lut.F[k], F, 1e-16);
            CHECK_NEAR(lut.G[k], G, 1e-15 * G);
            ref_lut_correct(&lut, seg); /* at a knot: the knot values */
            CHECK_MSG(fabs(seg[0] - F) <= 1e-16, "rho %g knot %d: F %.17g vs %.17g", rho, k, seg[0], F);
            CHECK_NEAR(seg[1], 0.25 * G, 1e-15 * G);
            CHECK_NEAR(seg[3], G, 4e-15 * G);
        }
        /* between knots: the chord, below the concave F (rho > 1), above the convex one (rho < 1), within
         * h^2 / 8 max |F''| (h = 1/1024, F'' = -rho (rho - 1) (1 - a)^(rho - 2)) */
        for (int k = 0; k < REF_LUT_KNOTS; k += 7) {
            double a = (k + 0.25) / 1024.0, seg[4] = {a, 1, 1, 1};
            ref_lut_correct(&lut, seg);
            double chord = 0.75 * lut.F[k] + 0.25 * lut.F[k + 1], G = 0.75 * lut.G[k] + 0.25 * lut.G[k + 1];
            CHECK_NEAR(seg[0], chord, 4e-16);
            CHECK_NEAR(seg[1], G, 1e-15 * G);
            double Fa = exact_F(a, rho), edge = rho < 2 ? (k + 1) / 1024.0 : k / 1024.0;
            double bound = fabs(rho * (rho - 1)) * pow(1 - edge, rho - 2) / (8.0 * 1024 * 1024);
            if (k + 1 < REF_LUT_KNOTS || rho >= 2)
                CHECK_MSG(fabs(seg[0] - Fa) <= bound * 1.0001 + 1e-16, "rho %g a %g: %.3g > %.3g", rho, a,
                          fabs(seg[0] - Fa), bound);
            if (rho > 1)
                CHECK(seg[0] <= Fa + 1e-16);
            else if (rho < 1)
                CHECK(seg[0] >= Fa - 1e-16);
        }
        double seg[4] = {1, 0.5, 0.5, 0.5}; /* a = 1: F = G = 1; a clamped to [0, 1] */
        ref_lut_correct(&lut, seg);
        CHECK(seg[0] == 1 && seg[1] == 0.5);
        double over[4] = {1.5, 0.5, 0.5, 0.5}, under[4] = {-0.1, 0.5, 0.5, 0.5};
        ref_lut_correct(&lut, over);
        ref_lut_correct(&lut, under);
        CHECK(over[0] == 1 && under[0] == 0 && under[1] == 0.5 * rho);
    }
    static ref_lut_t bad;
    CHECK_EQ(ref_lut_init(&bad, 0), -1);
    CHECK_EQ(ref_lut_init(&bad, -1), -1);
    CHECK_EQ(ref_lut_init(&bad, INFINITY), -1);
    CHECK_EQ(ref_lut_init(&bad, NAN), -1);
    CHECK_EQ(ref_lut_init(NULL, 1), -1);
}

static void lut_rho_one_is_identity(void)
{
    static ref_lut_t lut;
    CHECK_EQ(ref_lut_init(&lut, 1.0), 0);
    int exact = 0;
    for (int n = 0; n < 100000; n++) {
        double a = n < 1025 ? n / 1024.0 : rnd(), seg[4] = {a, a * rnd(), a * rnd(), a * rnd()}, was[4];
        memcpy(was, seg, sizeof seg);
        ref_lut_correct(&lut, seg);
        for (int c = 0; c < 4; c++)
            CHECK_NEAR(seg[c], was[c], 1e-12);
        exact += memcmp(seg, was, sizeof seg) == 0;
    }
    if (verbose())
        printf("# rho = 1: %d of 100000 segments bit-identical after the correction\n", exact);
}

/* Renders with black and with white behind: colour C from the first, opacity A = 1 - (white - black). */
static int render_CA(const ref_volume_t *vol, const ref_tf_point_t *tf, int np, ref_params_t p,
                     const ref_view_t *view, int W, int H, double *C, double *A, ref_factor_t *f)
{
    double *white = malloc(sizeof(double) * 3 * (size_t)W * (size_t)H);
    p.background[0] = p.background[1] = p.background[2] = 0;
    int rc = white ? ref_render(vol, tf, np, &p, view, W, H, C, f) : -1;
    p.background[0] = p.background[1] = p.background[2] = 1;
    if (rc == 0)
        rc = ref_render(vol, tf, np, &p, view, W, H, white, NULL);
    for (int n = 0; rc == 0 && n < W * H; n++)
        A[n] = 1 - (white[3 * n] - C[3 * n]);
    free(white);
    return rc;
}

/* A constant transfer function: every segment is the point entry of slab length d, which the lut reaches from
 * d0 = 1 exactly (F(a) = 1 - (1 - a)^rho, C G(a) = c F(a)) but for the linear interpolation between knots: per
 * segment at most h^2 / 8 |F''| = rho (rho - 1) (1 - a)^(rho - 2) / 2^23, about 2.7e-7 here (rho <= 2.13), of
 * the same sign in every segment, so it adds up over the slices. Measured (REF_VERBOSE=1), every mode, both
 * lookups, four views with slab lengths 1.16..2.13: opacity 1.47e-6 (a0 0.02, where 6..9 segments add up),
 * 2.6e-7 (0.35), 2.7e-7 (0.9); colour 1.8e-7, 3.9e-7, 2.2e-7. */
static void lut_matches_rebuild_constant_tf(void)
{
    int dims[3] = {9, 7, 6};
    uint8_t *s = rf_volume_of(dims, random_scalar);
    ref_volume_t vol = {{9, 7, 6}, {1, 1.3, 2.1}, s};
    const ref_view_t views[] = {{BAU(30), BAU(20), 0, 1}, {BAU(200), BAU(-50), BAU(10), 1.3},
                                {BAU(41), BAU(-35), BAU(77), 0.9}, {BAU(120), BAU(5), 0, 1.1}};
    const double a0s[] = {0.02, 0.35, 0.9};
    enum { W = 24, H = 20 };
    static double Cr[W * H * 3], Ar[W * H], Cl[W * H * 3], Al[W * H];
    double worst_a = 0, worst_c = 0, dmin = INFINITY, dmax = 0;
    for (int t = 0; t < 3; t++) {
        const ref_tf_point_t tf = {0, 0.2, 0.6, 0.9, a0s[t]};
        double tf_a = 0, tf_c = 0;
        for (int v = 0; v < 4; v++)
            for (int m = 0; m < 3; m++)
                for (int l = 0; l < 2; l++) {
                    ref_params_t p = params(modes[m], l ? 64 : 256);
                    p.lookup = l ? REF_LOOKUP_BILINEAR : REF_LOOKUP_NEAREST;
                    ref_factor_t f;
                    CHECK_EQ(render_CA(&vol, &tf, 1, p, &views[v], W, H, Cr, Ar, &f), 0);
                    p.correction = REF_CORRECTION_LUT;
                    CHECK_EQ(render_CA(&vol, &tf, 1, p, &views[v], W, H, Cl, Al, NULL), 0);
                    dmin = fmin(dmin, f.slab);
                    dmax = fmax(dmax, f.slab);
                    double ea = 0, ec = 0, sum = 0;
                    for (int n = 0; n < W * H; n++) {
                        ea = fmax(ea, fabs(Al[n] - Ar[n]));
                        sum += Ar[n];
                        for (int c = 0; c < 3; c++)
                            ec = fmax(ec, fabs(Cl[3 * n + c] - Cr[3 * n + c]));
                    }
                    CHECK(sum > 1); /* something is drawn */
                    worst_a = fmax(worst_a, ea);
                    worst_c = fmax(worst_c, ec);
                    tf_a = fmax(tf_a, ea);
                    tf_c = fmax(tf_c, ec);
                }
        if (verbose())
            printf("# constant TF a0 %.2f: lut - rebuild, opacity %.3g, colour %.3g\n", a0s[t], tf_a, tf_c);
    }
    if (verbose())
        printf("# constant TF, slab %.3f..%.3f: lut - rebuild, opacity %.3g, colour %.3g\n", dmin, dmax, worst_a,
               worst_c);
    CHECK(dmin > 1.05 && dmax > 2);
    CHECK_MSG(worst_a < 3e-6 && worst_c < 1e-6, "lut vs rebuild: opacity %.3g, colour %.3g", worst_a, worst_c);
    free(s);
}

/* Not constant: the colour correction is exact only for a constant slab, so preint1 (and bilinear lookup, which
 * corrects a mix of entries) differ from rebuild; the point table is F of an entry and stays within the
 * interpolation error. This is what makes the bound above mean something. */
static void lut_differs_where_spec_says(void)
{
    int dims[3] = {9, 7, 6};
    uint8_t *s = rf_volume_of(dims, random_scalar);
    ref_volume_t vol = {{9, 7, 6}, {1, 1, 1}, s};
    ref_tf_point_t tf[33];
    int np = rf_smooth_tf(tf, 0.9);
    ref_view_t view = {BAU(35), BAU(30), 0, 1};
    enum { W = 24, H = 24 };
    static double r[W * H * 3], l[W * H * 3];
    double diff[3][2];
    for (int m = 0; m < 3; m++)
        for (int k = 0; k < 2; k++) {
            ref_params_t p = params(modes[m], 128);
            p.lookup = k ? REF_LOOKUP_BILINEAR : REF_LOOKUP_NEAREST;
            ref_factor_t f;
            CHECK_EQ(ref_render(&vol, tf, np, &p, &view, W, H, r, &f), 0);
            CHECK(f.slab > 1.4);
            p.correction = REF_CORRECTION_LUT;
            CHECK_EQ(ref_render(&vol, tf, np, &p, &view, W, H, l, NULL), 0);
            diff[m][k] = 0;
            for (int n = 0; n < W * H * 3; n++)
                diff[m][k] = fmax(diff[m][k], fabs(l[n] - r[n]));
            if (verbose())
                printf("# smooth TF, slab %.3f, mode %d, lookup %d: max |lut - rebuild| %.3g\n", f.slab, m, k,
                       diff[m][k]);
        }
    CHECK(diff[0][0] < 1e-6);            /* point, nearest: F and C G of a point entry */
    CHECK(diff[1][0] > 1e-3);            /* preint1: mixed slabs */
    CHECK(diff[0][1] > 1e-5);            /* bilinear: F of a mix is not the mix of F */
    CHECK(diff[2][0] > 1e-5);            /* preclass: likewise */
    free(s);
}

/* Slab length 1 (views along an axis, spacing 1): rho = 1, the tables are the same and the correction is the
 * identity, so the images are identical, whatever the TF, mode, lookup and table bits. */
static void lut_slab_one_identical(void)
{
    int dims[3] = {7, 6, 5};
    uint8_t *s = rf_volume_of(dims, random_scalar);
    ref_volume_t vol = {{7, 6, 5}, {1, 1, 1}, s};
    ref_tf_point_t tf[33];
    int np = rf_smooth_tf(tf, 0.9);
    const ref_view_t views[] = {{0, 0, 0, 1}, {BAU(180), 0, BAU(30), 1}, {0, BAU(90), 0, 1.2}, {BAU(-90), 0, 0, 1}};
    enum { W = 18, H = 16 };
    static double r[W * H * 3], l[W * H * 3];
    for (int v = 0; v < 4; v++)
        for (int m = 0; m < 3; m++)
            for (int k = 0; k < 2; k++)
                for (int b = 0; b < 2; b++) {
                    ref_params_t p = params(modes[m], 100);
                    p.lookup = k ? REF_LOOKUP_BILINEAR : REF_LOOKUP_NEAREST;
                    p.table_bits = b ? 8 : 16;
                    p.background[1] = 0.5;
                    ref_factor_t f;
                    CHECK_EQ(ref_render(&vol, tf, np, &p, &views[v], W, H, r, &f), 0);
                    CHECK(f.slab == 1);
                    p.correction = REF_CORRECTION_LUT;
                    CHECK_EQ(ref_render(&vol, tf, np, &p, &views[v], W, H, l, NULL), 0);
                    CHECK_MSG(memcmp(r, l, sizeof r) == 0, "view %d mode %d lookup %d bits %d", v, m, k, p.table_bits);
                }
    free(s);
}

/* The order of section 4b: lookup, table bits, then the correction. Head on with z spacing 1.5 (slab 1.5,
 * rho = 1.5), a constant volume and TF: every segment is (F(a8), C8 G(a8)) with a8, C8 the 8-bit entries of
 * the table for d0 = 1 and F, G interpolated between knots. Correcting first and rounding after differs. */
static void lut_after_table_bits_by_hand(void)
{
    int dims[3] = {2, 2, 2};
    uint8_t *s = rf_volume_of(dims, rf_const_200);
    ref_volume_t vol = {{2, 2, 2}, {1, 1, 1.5}, s};
    const ref_tf_point_t tf = {0, 0.2, 0.5, 0.9, 0.35};
    ref_view_t view = {0, 0, 0, sqrt(4.25) / 4}; /* scale 1: final pixels 1..2 are intermediate pixels 0..1 */
    double a8 = 89.0 / 255, C8[3] = {18.0 / 255, 45.0 / 255, 80.0 / 255}, rho = 1.5;
    double t = a8 * 1024, w = t - floor(t);
    int k = (int)floor(t);
    double F = (1 - w) * exact_F(k / 1024.0, rho) + w * exact_F((k + 1) / 1024.0, rho);
    double G = (1 - w) * exact_F(k / 1024.0, rho) / (k / 1024.0) +
               w * exact_F((k + 1) / 1024.0, rho) / ((k + 1) / 1024.0);
    double wrong = floor(255 * exact_F(0.35, rho) + 0.5) / 255; /* corrected, then rounded */
    CHECK(fabs(wrong - F) > 1e-4);
    double rgb[4 * 4 * 3];
    for (int m = 0; m < 3; m++) {
        ref_params_t p = params(modes[m], 256);
        p.table_bits = 8;
        p.correction = REF_CORRECTION_LUT;
        ref_factor_t f;
        CHECK_EQ(ref_render(&vol, &tf, 1, &p, &view, 4, 4, rgb, &f), 0);
        CHECK(f.slab == 1.5 && f.int_w == 2 && f.int_h == 2);
        int slices = modes[m] == REF_MODE_PREINT1 ? 1 : 2;
        for (int c = 0; c < 3; c++) {
            double want = C8[c] * G * (slices == 2 ? 2 - F : 1);
            CHECK_NEAR(rgb[3 * (4 * 1 + 2) + c], want, 1e-15);
        }
    }
    free(s);
}

/* ---- preclass ------------------------------------------------------------------------------------------ */

/* A constant volume: every voxel and every sample has the same entry, so preclass is point (up to the rounding of
 * interpolating equal values), for any TF, view, table size, table bits and correction. */
static void preclass_constant_volume_is_point(void)
{
    int dims[3] = {7, 6, 5};
    uint8_t *s = rf_volume_of(dims, rf_const_200);
    ref_volume_t vol = {{7, 6, 5}, {1, 1.2, 0.9}, s};
    ref_tf_point_t tf[33];
    int np = rf_smooth_tf(tf, 0.9);
    const ref_view_t views[] = {{BAU(30), BAU(20), 0, 1}, {BAU(200), BAU(-50), BAU(10), 1.6}, {0, 0, 0, 1}};
    enum { W = 20, H = 22 };
    static double a[W * H * 3], b[W * H * 3];
    double worst = 0;
    for (int v = 0; v < 3; v++)
        for (int n = 0; n < 4; n++) {
            ref_params_t p = params(REF_MODE_POINT, n & 1 ? 37 : 256);
            p.table_bits = n & 2 ? 8 : 16;
            p.correction = n & 2 ? REF_CORRECTION_LUT : REF_CORRECTION_REBUILD;
            p.background[2] = 0.4;
            CHECK_EQ(ref_render(&vol, tf, np, &p, &views[v], W, H, a, NULL), 0);
            p.mode = REF_MODE_PRECLASS;
            CHECK_EQ(ref_render(&vol, tf, np, &p, &views[v], W, H, b, NULL), 0);
            double sum = 0;
            for (int q = 0; q < W * H * 3; q++) {
                worst = fmax(worst, fabs(a[q] - b[q]));
                sum += fabs(a[q] - 0.4 * (q % 3 == 2));
            }
            CHECK(sum > 1);
        }
    if (verbose())
        printf("# constant volume: max |preclass - point| %.3g\n", worst);
    CHECK_MSG(worst < 1e-13, "preclass vs point %.3g", worst);
    free(s);
}

/* A 2-voxel gradient (scalar 255 x) seen at 22.5 degrees azimuth: intermediate pixel u = 1 sees slice 0 at
 * x = 1 (scalar 255) and slice 1 at x = 1 - ou_1 = 0.586. Preclass mixes the classified ends (entries 0 and 255,
 * opaque red and blue); point classifies the mixed scalar 149.4, near the transparent green middle. */
static void preclass_interpolates_classified_values(void)
{
    int dims[3] = {2, 2, 2};
    uint8_t *s = rf_volume_of(dims, ramp_x);
    ref_volume_t vol = {{2, 2, 2}, {1, 1, 1}, s};
    const ref_tf_point_t tf[] = {{0, 1, 0, 0, 0.6}, {127.5, 0, 1, 0, 0.02}, {255, 0, 0, 1, 0.6}};
    ref_view_t view = {BAU(22.5), 0, 0, 1};
    ref_factor_t f;
    CHECK_EQ(ref_factor(&vol, &view, 16, 16, &f), 0);
    double ou1, ov1, T[4 * 256];
    ref_factor_offset(&f, 1, &ou1, &ov1);
    CHECK(f.k_axis == 2 && !f.k_flip && ov1 == 0 && f.int_w == 2 && f.int_h == 2);
    CHECK_NEAR(ou1, tan(PI / 8), 1e-5);
    CHECK_EQ(ref_point_table(tf, 3, 256, f.slab, T), 0);
    double fx = 1 - ou1, mix[4], inter[2][4 * 4];
    for (int c = 0; c < 4; c++)
        mix[c] = (1 - fx) * T[c] + fx * T[4 * 255 + c];
    CHECK_EQ(ref_composite(&vol, &f, REF_MODE_PRECLASS, 256, T, inter[0]), 0);
    CHECK_EQ(ref_composite(&vol, &f, REF_MODE_POINT, 256, T, inter[1]), 0);
    const double *point_seg = T + 4 * 149; /* idx(255 fx) = round(149.38) */
    CHECK_EQ(ref_table_index(255 * fx, 256), 149);
    for (int v = 0; v < 2; v++) {
        const double *p0 = inter[0] + 4 * (2 * v), *p1 = inter[0] + 4 * (2 * v + 1), *q1 = inter[1] + 4 * (2 * v + 1);
        for (int c = 0; c < 4; c++) { /* pixels R, G, B, A; entries a, r, g, b */
            int e = (c + 1) % 4;
            CHECK_NEAR(p0[c], T[e], 1e-15); /* u = 0: slice 0 at x = 0 only */
            CHECK_NEAR(p1[c], T[4 * 255 + e] + (1 - T[4 * 255]) * mix[e], 1e-15);
            CHECK_NEAR(q1[c], T[4 * 255 + e] + (1 - T[4 * 255]) * point_seg[e], 1e-15);
        }
        CHECK(p1[3] - q1[3] > 0.1 && p1[0] - q1[0] > 0.05 && q1[1] - p1[1] > 1e-3); /* they do differ */
    }
    /* the lookup does not apply to preclass: the same intermediate image with bilinear */
    double again[4 * 4];
    CHECK_EQ(ref_composite_ex(&vol, &f, REF_MODE_PRECLASS, REF_LOOKUP_BILINEAR, 256, T, NULL, again), 0);
    CHECK(memcmp(again, inter[0], sizeof again) == 0);
    free(s);
}

/* ---- bad arguments ------------------------------------------------------------------------------------- */

static void bad_arguments(void)
{
    int dims[3] = {3, 3, 3};
    uint8_t *s = rf_volume_of(dims, rf_const_200);
    ref_volume_t vol = {{3, 3, 3}, {1, 1, 1}, s};
    const ref_tf_point_t tf = {0, 0.2, 0.6, 0.9, 0.3};
    ref_view_t view = {BAU(10), BAU(10), 0, 1};
    double rgb[8 * 8 * 3], rgb16[8 * 8 * 3];
    ref_params_t p = params(REF_MODE_POINT, 64);
    CHECK_EQ(ref_render(&vol, &tf, 1, &p, &view, 8, 8, rgb16, NULL), 0);
    p.table_bits = 0; /* 0 is 16 */
    CHECK_EQ(ref_render(&vol, &tf, 1, &p, &view, 8, 8, rgb, NULL), 0);
    CHECK(memcmp(rgb, rgb16, sizeof rgb) == 0);
    const int bits[] = {1, 7, 9, 12, 15, 17, 24, 32, -8, -16};
    for (int n = 0; n < 10; n++) {
        p.table_bits = bits[n];
        CHECK_EQ(ref_render(&vol, &tf, 1, &p, &view, 8, 8, rgb, NULL), -1);
    }
    p = params(REF_MODE_POINT, 64);
    p.mode = (ref_mode_t)4; /* after REF_MODE_PREINT2 */
    CHECK_EQ(ref_render(&vol, &tf, 1, &p, &view, 8, 8, rgb, NULL), -1);
    p.mode = (ref_mode_t)-1;
    CHECK_EQ(ref_render(&vol, &tf, 1, &p, &view, 8, 8, rgb, NULL), -1);
    p = params(REF_MODE_PREINT1, 64);
    p.lookup = (ref_lookup_t)2;
    CHECK_EQ(ref_render(&vol, &tf, 1, &p, &view, 8, 8, rgb, NULL), -1);
    p.lookup = (ref_lookup_t)-1;
    CHECK_EQ(ref_render(&vol, &tf, 1, &p, &view, 8, 8, rgb, NULL), -1);
    p = params(REF_MODE_PRECLASS, 64);
    p.correction = (ref_correction_t)2;
    CHECK_EQ(ref_render(&vol, &tf, 1, &p, &view, 8, 8, rgb, NULL), -1);
    p.correction = (ref_correction_t)-1;
    CHECK_EQ(ref_render(&vol, &tf, 1, &p, &view, 8, 8, rgb, NULL), -1);
    /* every valid combination renders */
    for (int n = 0; n < 3 * 2 * 3 * 2; n++) {
        p = params(modes[n % 3], 64);
        p.lookup = (n / 3) % 2 ? REF_LOOKUP_BILINEAR : REF_LOOKUP_NEAREST;
        p.table_bits = (const int[]){0, 8, 16}[(n / 6) % 3];
        p.correction = n / 18 ? REF_CORRECTION_LUT : REF_CORRECTION_REBUILD;
        CHECK_EQ(ref_render(&vol, &tf, 1, &p, &view, 8, 8, rgb, NULL), 0);
    }
    ref_factor_t f;
    double table[4 * 64], inter[4 * 64];
    CHECK_EQ(ref_factor(&vol, &view, 8, 8, &f), 0);
    CHECK_EQ(ref_point_table(&tf, 1, 64, 1, table), 0);
    CHECK(f.int_w * f.int_h <= 64);
    CHECK_EQ(ref_composite_ex(&vol, &f, REF_MODE_POINT, REF_LOOKUP_BILINEAR, 64, table, NULL, inter), 0);
    CHECK_EQ(ref_composite_ex(&vol, &f, (ref_mode_t)3, REF_LOOKUP_NEAREST, 64, table, NULL, inter), -1);
    CHECK_EQ(ref_composite_ex(&vol, &f, REF_MODE_POINT, (ref_lookup_t)2, 64, table, NULL, inter), -1);
    CHECK_EQ(ref_composite(&vol, &f, (ref_mode_t)3, 64, table, inter), -1);
    free(s);
}

CHECK_CASES(CHECK_CASE(lookup_point_by_hand), CHECK_CASE(lookup_preint_by_hand), CHECK_CASE(lookup_bilinear_render),
            CHECK_CASE(lookup_bilinear_on_entries_is_nearest), CHECK_CASE(table_bits_rounding),
            CHECK_CASE(table_bits_render_by_hand), CHECK_CASE(lut_knots_and_between),
            CHECK_CASE(lut_rho_one_is_identity), CHECK_CASE(lut_matches_rebuild_constant_tf),
            CHECK_CASE(lut_differs_where_spec_says), CHECK_CASE(lut_slab_one_identical),
            CHECK_CASE(lut_after_table_bits_by_hand), CHECK_CASE(preclass_constant_volume_is_point),
            CHECK_CASE(preclass_interpolates_classified_values), CHECK_CASE(bad_arguments));
CHECK_RUN("ref_options")
