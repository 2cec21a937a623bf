/* SPDX-License-Identifier: MIT */
/*
 * test_ref.c: the reference's window and tables, proved on their own terms (independently of the core):
 * hand rules, closed forms, and the pre-integrated table against direct numerical integration of the
 * continuous model (tau and colour linear between table entries, DESIGN.md "The mathematics").
 */
#include "check.h"
#include "ref_fixtures.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define N_MAX 1024

static double g_tau[N_MAX], g_rgb[3 * N_MAX];

/* ---- window ---------------------------------------------------------------------------------------------- */

static void window_u8_identity(void)
{
    int dims[3] = {16, 4, 4};
    uint8_t raw[256], out[256];
    for (int n = 0; n < 256; n++)
        raw[n] = (uint8_t)n;
    CHECK_EQ(ref_window(raw, REF_VOXEL_U8, dims, 0, 255, out), 0);
    for (int n = 0; n < 256; n++)
        CHECK_EQ(out[n], n);
    /* descending: s = round((v - 255) * 255 / -255) = 255 - v */
    CHECK_EQ(ref_window(raw, REF_VOXEL_U8, dims, 255, 0, out), 0);
    for (int n = 0; n < 256; n++)
        CHECK_EQ(out[n], 255 - n);
}

static void window_rounding_and_clamp(void)
{
    int dims[3] = {2, 2, 2};
    int16_t raw[8] = {-1, 0, 1, 3, 509, 510, 511, -32768};
    uint8_t out[8];
    /* (v - 0) * 255 / 510 = v / 2: half up, clamped to 0..255 */
    CHECK_EQ(ref_window(raw, REF_VOXEL_I16, dims, 0, 510, out), 0);
    const uint8_t want[8] = {0, 0, 1, 2, 255, 255, 255, 0};
    for (int n = 0; n < 8; n++)
        CHECK_EQ(out[n], want[n]);
    /* descending window: s = -v / 2 */
    CHECK_EQ(ref_window(raw, REF_VOXEL_I16, dims, 0, -510, out), 0);
    const uint8_t want_desc[8] = {1, 0, 0, 0, 0, 0, 0, 255}; /* -1 -> 0.5 -> 1; 1 -> -0.5 -> 0 */
    for (int n = 0; n < 8; n++)
        CHECK_EQ(out[n], want_desc[n]);
    uint16_t raw16[8] = {0, 1000, 1100, 1150, 1200, 1300, 65535, 1101};
    CHECK_EQ(ref_window(raw16, REF_VOXEL_U16, dims, 1100, 1300, out), 0);
    const uint8_t want16[8] = {0, 0, 0, 64, 128, 255, 255, 1}; /* 63.75 -> 64, 127.5 -> 128, 1.275 -> 1 */
    for (int n = 0; n < 8; n++)
        CHECK_EQ(out[n], want16[n]);
    int8_t raw8[8] = {-128, -1, 0, 1, 127, 64, -64, 2};
    CHECK_EQ(ref_window(raw8, REF_VOXEL_I8, dims, -128, 127, out), 0);
    const uint8_t want8[8] = {0, 127, 128, 129, 255, 192, 64, 130};
    for (int n = 0; n < 8; n++)
        CHECK_EQ(out[n], want8[n]);
}

static void window_bad_arguments(void)
{
    int dims[3] = {2, 2, 2}, flat[3] = {2, 1, 2};
    uint8_t raw[8] = {0}, out[8];
    CHECK_EQ(ref_window(raw, REF_VOXEL_U8, dims, 7, 7, out), -1);
    CHECK_EQ(ref_window(raw, 4, dims, 0, 255, out), -1);
    CHECK_EQ(ref_window(raw, REF_VOXEL_U8, flat, 0, 255, out), -1);
    CHECK_EQ(ref_window(NULL, REF_VOXEL_U8, dims, 0, 255, out), -1);
}

/* ---- transfer function and classification ---------------------------------------------------------------- */

static void tf_piecewise_linear_and_steps(void)
{
    const ref_tf_point_t tf[] = {
        {50, 0.0, 0.2, 1.0, 0.0}, {100, 1.0, 0.2, 0.0, 0.5}, {100, 0.0, 0.0, 0.0, 0.9}, {100, 0.5, 0.5, 0.5, 0.25},
        {200, 0.5, 0.5, 0.5, 0.75},
    };
    double v[4];
    ref_tf_eval(tf, 5, 0, v); /* constant before the first point */
    CHECK(v[0] == 0.0 && v[2] == 1.0 && v[3] == 0.0);
    ref_tf_eval(tf, 5, 75, v);
    CHECK_NEAR(v[0], 0.5, 1e-15);
    CHECK_NEAR(v[3], 0.25, 1e-15);
    ref_tf_eval(tf, 5, 99.999, v); /* left of the step: the earlier segment */
    CHECK_NEAR(v[3], 0.49999, 1e-12);
    ref_tf_eval(tf, 5, 100, v); /* at the step: the last point sharing the scalar */
    CHECK_EQ(v[3] == 0.25, 1);
    ref_tf_eval(tf, 5, 150, v);
    CHECK_NEAR(v[3], 0.5, 1e-15);
    ref_tf_eval(tf, 5, 255, v); /* constant after the last point */
    CHECK(v[0] == 0.5 && v[3] == 0.75);
    const ref_tf_point_t one = {10, 0.1, 0.2, 0.3, 0.4};
    ref_tf_eval(&one, 1, 200, v);
    CHECK(v[0] == 0.1 && v[1] == 0.2 && v[2] == 0.3 && v[3] == 0.4);
}

static void classify_entries(void)
{
    /* N = 3: entries at s = 0, 127.5, 255; a0 = s / 255 clamped to 1 - 2^-16 */
    const ref_tf_point_t tf[] = {{0, 0, 0, 0, 0}, {255, 1, 0.5, 0.25, 1}};
    CHECK_EQ(ref_classify(tf, 2, 3, g_tau, g_rgb), 0);
    CHECK(g_tau[0] == 0.0);
    CHECK_NEAR(g_tau[1], log(2.0), 1e-15);
    CHECK_NEAR(g_tau[2], 16 * log(2.0), 1e-12);
    CHECK_NEAR(g_rgb[3], 0.5, 1e-15);
    CHECK_NEAR(g_rgb[4], 0.25, 1e-15);
    CHECK_NEAR(g_rgb[8], 0.25, 1e-15);
    /* nearest-entry lookup, half up */
    CHECK_EQ(ref_table_index(100.5, 256), 101);
    CHECK_EQ(ref_table_index(100.49, 256), 100);
    CHECK_EQ(ref_table_index(63.75, 3), 1);
    CHECK_EQ(ref_table_index(63.7, 3), 0);
    CHECK_EQ(ref_table_index(255, 1024), 1023);
    CHECK_EQ(ref_table_index(0, 2), 0);
    /* bad transfer functions and sizes */
    const ref_tf_point_t down[] = {{10, 0, 0, 0, 0}, {9, 0, 0, 0, 0}};
    CHECK_EQ(ref_classify(down, 2, 256, g_tau, g_rgb), -1);
    CHECK_EQ(ref_classify(tf, 0, 256, g_tau, g_rgb), -1);
    CHECK_EQ(ref_classify(tf, 2, 1, g_tau, g_rgb), -1);
    CHECK_EQ(ref_classify(tf, 2, 1025, g_tau, g_rgb), -1);
    static double table[4 * 256];
    CHECK_EQ(ref_point_table(tf, 2, 256, 0.0, table), -1);
    CHECK_EQ(ref_preint_table(tf, 2, 256, -1.0, table), -1);
}

/* ---- tables: closed forms ----------------------------------------------------------------------------- */

static double *g_table; /* N_MAX * N_MAX * 4 doubles, shared by the table tests */

static const double *entry(int N, int f, int b)
{
    return g_table + 4 * ((size_t)f * (size_t)N + (size_t)b);
}

static void point_table_closed_form(void)
{
    ref_tf_point_t tf[33];
    int np = rf_smooth_tf(tf, 0.9);
    static double point[4 * 256];
    CHECK_EQ(ref_point_table(tf, np, 256, 1.3, point), 0);
    for (int i = 0; i < 256; i++) {
        double v[4];
        ref_tf_eval(tf, np, i, v); /* N = 256: s_i = i */
        double a = 1 - exp(1.3 * log(1 - v[3])); /* 1 - (1 - a0)^d */
        CHECK_NEAR(point[4 * i], a, 1e-14);
        for (int c = 0; c < 3; c++)
            CHECK_NEAR(point[4 * i + 1 + c], v[c] * a, 1e-14);
    }
}

static void preint_diagonal_and_zero_range(void)
{
    /* a0 = 0 up to s = 100, then rising: entries 0..100 have tau = 0, 101.. have tau > 0 */
    const ref_tf_point_t tf[] = {{0, 1, 0, 0, 0}, {100, 1, 1, 0, 0}, {255, 0, 0, 1, 0.8}};
    const int N = 256;
    static double point[4 * 256];
    double d = 0.7;
    CHECK_EQ(ref_preint_table(tf, 3, N, d, g_table), 0);
    CHECK_EQ(ref_point_table(tf, 3, N, d, point), 0);
    CHECK_EQ(ref_classify(tf, 3, N, g_tau, g_rgb), 0);
    for (int i = 0; i < N; i++) {
        CHECK_NEAR(entry(N, i, i)[0], 1 - exp(-g_tau[i] * d), 1e-15);
        for (int c = 0; c < 4; c++)
            CHECK(entry(N, i, i)[c] == point[4 * i + c]);
    }
    for (int f = 0; f < N; f++) {
        for (int b = 0; b < N; b++) {
            const double *e = entry(N, f, b);
            if ((f > b ? f : b) <= 100)
                CHECK_MSG(e[0] == 0 && e[1] == 0 && e[2] == 0 && e[3] == 0, "entry (%d, %d) not exactly 0", f, b);
            else
                CHECK_MSG(e[0] > 0, "entry (%d, %d) reaches a visible entry but is 0", f, b);
        }
    }
}

static void preint_constant_tf_equals_diagonal(void)
{
    const ref_tf_point_t tf[] = {{0, 0.2, 0.6, 0.9, 0.35}};
    const int N = 128;
    double d = 1.7, a = 1 - pow(0.65, d);
    CHECK_EQ(ref_preint_table(tf, 1, N, d, g_table), 0);
    for (int f = 0; f < N; f++) {
        for (int b = 0; b < N; b++) {
            const double *e = entry(N, f, b);
            CHECK_NEAR(e[0], a, 1e-13);
            CHECK_NEAR(e[1], 0.2 * a, 1e-13);
            CHECK_NEAR(e[2], 0.6 * a, 1e-13);
            CHECK_NEAR(e[3], 0.9 * a, 1e-13);
        }
    }
}

static void preint_ramp_is_front_weighted(void)
{
    /* constant opacity, red rising with s: seen from the low end the colour leans to the low (dark) front */
    const ref_tf_point_t tf[] = {{0, 0, 0.5, 1, 0.4}, {255, 1, 0.5, 0, 0.4}};
    const int N = 256;
    double d = 1.0, a = 0.4;
    CHECK_EQ(ref_preint_table(tf, 2, N, d, g_table), 0);
    for (int f = 0; f < N; f += 3) {
        for (int b = f + 1; b < N; b += (b == f + 1 ? 1 : 5)) {
            const double *fb = entry(N, f, b), *bf = entry(N, b, f);
            CHECK_NEAR(fb[0], bf[0], 1e-15);
            CHECK_NEAR(fb[0], a, 1e-13);
            if (b == f + 1) {
                /* one interval: its colour weight has no direction, both entries are the same */
                CHECK(fb[1] == bf[1] && fb[3] == bf[3]);
                continue;
            }
            CHECK_MSG(fb[1] < bf[1], "red (%d,%d) %.17g !< (%d,%d) %.17g", f, b, fb[1], b, f, bf[1]);
            CHECK(fb[3] > bf[3]);
            /* between the end colours and on the mean's far side from the back */
            CHECK(fb[1] > a * f / 255.0 && fb[1] < a * (f + b) / 2 / 255.0);
            CHECK(bf[1] < a * b / 255.0 && bf[1] > a * (f + b) / 2 / 255.0);
            CHECK_NEAR(fb[1] + bf[1], a * (f + b) / 255.0, 1e-13); /* symmetric ramp: deviations cancel */
        }
    }
}

/* By hand, N = 3, entries 0, 1, 2: interval formulas and the order of intervals for f < b and f > b. */
static void preint_small_table_by_hand(void)
{
    const ref_tf_point_t tf[] = {{0, 1, 0, 0, 0.2}, {127.5, 0, 1, 0, 0.5}, {255, 0, 0, 1, 0.9}};
    double d = 1.5, t[3] = {-log(0.8), -log(0.5), -log(0.1)}, L = d / 2;
    CHECK_EQ(ref_preint_table(tf, 3, 3, d, g_table), 0);
    /* interval 0 (entries 0-1): w = (2 t0 c0 + t0 c1 + t1 c0 + 2 t1 c1) / (3 (t0 + t1)) */
    double w0[3] = {(2 * t[0] + t[1]) / (3 * (t[0] + t[1])), (t[0] + 2 * t[1]) / (3 * (t[0] + t[1])), 0};
    double w1[3] = {0, (2 * t[1] + t[2]) / (3 * (t[1] + t[2])), (t[1] + 2 * t[2]) / (3 * (t[1] + t[2]))};
    double a0 = 1 - exp(-L * (t[0] + t[1]) / 2), a1 = 1 - exp(-L * (t[1] + t[2]) / 2);
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(entry(3, 0, 2)[1 + c], w0[c] * a0 + (1 - a0) * w1[c] * a1, 1e-15); /* 0 then 1 */
        CHECK_NEAR(entry(3, 2, 0)[1 + c], w1[c] * a1 + (1 - a1) * w0[c] * a0, 1e-15); /* 1 then 0 */
    }
    CHECK_NEAR(entry(3, 0, 2)[0], 1 - exp(-d * (t[0] + 2 * t[1] + t[2]) / 4), 1e-15);
    double b0 = 1 - exp(-d * (t[0] + t[1]) / 2);
    CHECK_NEAR(entry(3, 0, 1)[0], b0, 1e-15);
    CHECK_NEAR(entry(3, 1, 0)[2], w0[1] * b0, 1e-15);
}

/* ---- tables against the continuous model ------------------------------------------------------------- */

/* The continuous model of entry (f, b): along w in [0, 1] the index runs f -> b, tau and colour linear between
 * entries; a = 1 - exp(-d int tau), C = d int tau c exp(-d int_0^w tau). The r pieces are integrated by
 * composite Simpson with K panels each, the optical depth exactly (tau is linear in a piece). */
static void continuous_entry(int f, int b, double d, int K, double out[4])
{
    int r = abs(b - f), step = b > f ? 1 : -1;
    double L = r ? d / r : d, depth = 0, C[3] = {0, 0, 0};
    for (int q = 0; q < (r ? r : 1); q++) {
        int m0 = f + q * step, m1 = r ? m0 + step : m0;
        double t0 = g_tau[m0], dt = g_tau[m1] - t0;
        for (int n = 0; n <= 2 * K; n++) {
            double x = (double)n / (2 * K), wt = (n == 0 || n == 2 * K) ? 1 : (n & 1) ? 4 : 2;
            double tx = t0 + dt * x, att = exp(-(depth + L * (t0 * x + dt * x * x / 2)));
            for (int c = 0; c < 3; c++) {
                double col = g_rgb[3 * m0 + c] + (g_rgb[3 * m1 + c] - g_rgb[3 * m0 + c]) * x;
                C[c] += wt / (6.0 * K) * L * tx * col * att;
            }
        }
        depth += L * (t0 + g_tau[m1]) / 2;
    }
    out[0] = 1 - exp(-depth);
    for (int c = 0; c < 3; c++)
        out[1 + c] = C[c];
}

/* Largest |table - continuous| over the entries with |b - f| <= 4 and those whose f and b are multiples of
 * `stride` (the error hardly depends on |b - f|: see below). */
static double table_error(const ref_tf_point_t *tf, int np, int N, double d, int stride, double *err_a)
{
    double worst = 0;
    *err_a = 0;
    if (ref_preint_table(tf, np, N, d, g_table) || ref_classify(tf, np, N, g_tau, g_rgb))
        return INFINITY;
    for (int f = 0; f < N; f++) {
        for (int b = 0; b < N; b++) {
            if (abs(b - f) > 4 && (f % stride || b % stride))
                continue;
            double want[4];
            continuous_entry(f, b, d, 16, want);
            const double *e = entry(N, f, b);
            *err_a = fmax(*err_a, fabs(e[0] - want[0]));
            for (int c = 1; c < 4; c++)
                worst = fmax(worst, fabs(e[c] - want[c]));
        }
    }
    return worst;
}

/* Opacity is exact in the interval model (tau is linear in an interval: the trapezoid is its integral). The
 * colour weight w_m ignores the attenuation inside an interval, so it misses the front weighting of the colour
 * change across one interval: about (c_{m+1} - c_m) (tau L / 12) per interval, and over the r intervals of an
 * entry about (dc/dentry) tau d / 12 whatever r is: first order in the entry spacing 255 / (N - 1). For this
 * TF (|dc/ds| <= 1/80, tau <= 2.3) the maxima measured (REF_VERBOSE=1) are 1.82e-3 (N 256, d 1), 3.05e-3
 * (N 256, d 1.7), 7.3e-4 (N 256, d 0.5), 1.21e-2 (N 64, d 1.7), 2.51e-2 (N 16, d 1); opacity <= 1.2e-15. */
static void preint_matches_continuous_model(void)
{
    ref_tf_point_t tf[33];
    int np = rf_smooth_tf(tf, 0.9);
    const struct { int N, stride; double d, bound; } runs[] = {
        {256, 5, 1.0, 2.5e-3}, {256, 7, 1.7, 4e-3}, {256, 9, 0.5, 1e-3}, {64, 1, 1.7, 1.5e-2}, {16, 1, 1.0, 3e-2},
    };
    double err[5];
    for (int n = 0; n < 5; n++) {
        double err_a;
        err[n] = table_error(tf, np, runs[n].N, runs[n].d, runs[n].stride, &err_a);
        if (getenv("REF_VERBOSE"))
            printf("# N %d d %.2f: opacity error %.3g, colour error %.3g\n", runs[n].N, runs[n].d, err_a, err[n]);
        CHECK_MSG(err_a < 1e-13, "N %d d %g: opacity error %.3g", runs[n].N, runs[n].d, err_a);
        CHECK_MSG(err[n] < runs[n].bound, "N %d d %g: colour error %.3g > %.3g", runs[n].N, runs[n].d, err[n],
                  runs[n].bound);
    }
    CHECK_MSG(err[3] / err[1] > 3 && err[3] / err[1] < 5, "N 64 -> 256: error ratio %.3g, expected about 4",
              err[3] / err[1]);
    /* an opaque TF (a0 up to the clamp 1 - 2^-16, tau up to 11) with a fine table: measured 3.6e-3 */
    const ref_tf_point_t hard[] = {{0, 0, 0, 1, 0}, {60, 1, 0, 0, 0}, {200, 0, 1, 0, 1}, {255, 1, 1, 1, 1}};
    double err_a, err_c = table_error(hard, 4, 512, 1.0, 15, &err_a);
    if (getenv("REF_VERBOSE"))
        printf("# opaque TF N 512: opacity error %.3g, colour error %.3g\n", err_a, err_c);
    CHECK_MSG(err_a < 1e-13 && err_c < 5e-3, "opaque TF: errors %.3g %.3g", err_a, err_c);
}

CHECK_CASES({"window_u8_identity", window_u8_identity}, {"window_rounding_and_clamp", window_rounding_and_clamp},
            {"window_bad_arguments", window_bad_arguments},
            {"tf_piecewise_linear_and_steps", tf_piecewise_linear_and_steps},
            {"classify_entries", classify_entries}, {"point_table_closed_form", point_table_closed_form},
            {"preint_diagonal_and_zero_range", preint_diagonal_and_zero_range},
            {"preint_constant_tf_equals_diagonal", preint_constant_tf_equals_diagonal},
            {"preint_ramp_is_front_weighted", preint_ramp_is_front_weighted},
            {"preint_small_table_by_hand", preint_small_table_by_hand},
            {"preint_matches_continuous_model", preint_matches_continuous_model});

int main(int argc, char **argv)
{
    g_table = malloc(sizeof(double) * 4 * N_MAX * N_MAX);
    if (!g_table)
        return 1;
    int rc = check_main("ref", check_cases_, (int)(sizeof check_cases_ / sizeof check_cases_[0]), argc, argv);
    free(g_table);
    return rc;
}
