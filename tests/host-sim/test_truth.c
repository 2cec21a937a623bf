/* SPDX-License-Identifier: MIT */
/*
 * test_truth.c: the ground-truth ray caster (host-sim/truth) against closed forms and against an independent
 * numerical integration of the emission-absorption integral (adaptive Simpson, nested for the optical depth,
 * with the transfer function evaluated by the reference's ref_tf_eval), plus its camera against the
 * reference's factorisation, misses, stopping, symmetry and thread independence.
 */
#include "check.h"
#include "truth/truth.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define A0_MAX (1.0 - 1.0 / 65536.0)

/* ---- an independent integration of one ray along which the scalar is linear ------------------------------ */

typedef struct line_ray {
    const ref_tf_point_t *tf;
    int npoints;
    double s0, ds;    /* scalar s(t) = s0 + ds t */
    double lo, hi;    /* the current piece: the transfer function is smooth for t strictly inside */
    double depth0;    /* optical depth at lo */
    int channel;
} line_ray_t;

static void tf_at(const line_ray_t *r, double t, double *tau, double rgb[3])
{
    /* evaluate just inside the piece: at a step the piece's own side of it counts */
    double span = r->hi - r->lo, tt = fmin(fmax(t, r->lo + 1e-13 * span), r->hi - 1e-13 * span), v[4];
    ref_tf_eval(r->tf, r->npoints, r->s0 + r->ds * tt, v);
    double a = fmin(fmax(v[3], 0.0), A0_MAX);
    *tau = -log1p(-a);
    if (rgb)
        memcpy(rgb, v, sizeof(double) * 3);
}

typedef double (*fn_t)(const line_ray_t *r, double t);

static double simpson_step(fn_t f, const line_ray_t *r, double a, double b, double fa, double fm, double fb,
                           double whole, double eps, int depth)
{
    double m = (a + b) / 2, lm = (a + m) / 2, rm = (m + b) / 2, flm = f(r, lm), frm = f(r, rm);
    double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
    if (depth <= 0 || fabs(left + right - whole) <= 15 * eps)
        return left + right + (left + right - whole) / 15;
    return simpson_step(f, r, a, m, fa, flm, fm, left, eps / 2, depth - 1) +
           simpson_step(f, r, m, b, fm, frm, fb, right, eps / 2, depth - 1);
}

static double simpson(fn_t f, const line_ray_t *r, double a, double b, double eps)
{
    if (b <= a)
        return 0;
    double fa = f(r, a), fb = f(r, b), fm = f(r, (a + b) / 2);
    return simpson_step(f, r, a, b, fa, fm, fb, (b - a) / 6 * (fa + 4 * fm + fb), eps, 30);
}

static double tau_fn(const line_ray_t *r, double t)
{
    double tau;
    tf_at(r, t, &tau, NULL);
    return tau;
}

static double emission_fn(const line_ray_t *r, double t)
{
    double tau, rgb[3];
    tf_at(r, t, &tau, rgb);
    double depth = r->depth0 + simpson(tau_fn, r, r->lo, t, 1e-12);
    return tau * rgb[r->channel] * exp(-depth);
}

/* rgba = premultiplied colour and opacity of t in [0, L] with s(t) = s0 + ds t. */
static void integrate_line(const ref_tf_point_t *tf, int npoints, double s0, double ds, double L, double rgba[4])
{
    /* pieces between the places where s crosses a control point's scalar */
    double cut[2 * REF_MAX_TF_POINTS + 2];
    int ncut = 0;
    cut[ncut++] = 0;
    for (int p = 0; p < npoints; p++) {
        double t = ds != 0 ? (tf[p].s - s0) / ds : -1;
        if (t > 0 && t < L)
            cut[ncut++] = t;
    }
    cut[ncut++] = L;
    for (int i = 1; i < ncut; i++) /* insertion sort: a handful of cuts */
        for (int j = i; j > 0 && cut[j] < cut[j - 1]; j--) {
            double x = cut[j];
            cut[j] = cut[j - 1];
            cut[j - 1] = x;
        }
    line_ray_t r = {tf, npoints, s0, ds, 0, 0, 0, 0};
    double C[3] = {0, 0, 0};
    for (int i = 0; i + 1 < ncut; i++) {
        if (!(cut[i + 1] > cut[i]))
            continue;
        r.lo = cut[i];
        r.hi = cut[i + 1];
        for (int c = 0; c < 3; c++) {
            r.channel = c;
            C[c] += simpson(emission_fn, &r, r.lo, r.hi, 1e-10);
        }
        r.depth0 += simpson(tau_fn, &r, r.lo, r.hi, 1e-12);
    }
    for (int c = 0; c < 3; c++)
        rgba[c] = C[c];
    rgba[3] = -expm1(-r.depth0);
}

/* ---- volumes --------------------------------------------------------------------------------------------- */

/* S = a x + b y + c z + d, which trilinear interpolation reproduces exactly. */
static uint8_t *linear_volume(const int dims[3], double a, double b, double c, double d)
{
    uint8_t *v = malloc((size_t)dims[0] * dims[1] * dims[2]);
    for (int z = 0; z < dims[2]; z++)
        for (int y = 0; y < dims[1]; y++)
            for (int x = 0; x < dims[0]; x++) {
                double s = a * x + b * y + c * z + d;
                v[x + dims[0] * (y + dims[1] * z)] = (uint8_t)s;
            }
    return v;
}

static const ref_tf_point_t g_tf[] = {
    {0, 0.0, 0.0, 0.0, 0.0},    {40, 0.9, 0.1, 0.1, 0.0},   {80, 0.9, 0.6, 0.1, 0.35}, {110, 0.2, 0.8, 0.3, 0.05},
    {110, 0.3, 0.3, 1.0, 0.6},  {150, 1.0, 1.0, 1.0, 1.0},  {170, 0.5, 0.5, 0.9, 0.1}, {230, 0.1, 0.9, 0.2, 0.02},
};
#define G_TF_POINTS ((int)(sizeof g_tf / sizeof g_tf[0]))

/* ---- cases ----------------------------------------------------------------------------------------------- */

static void constant_volume_closed_form(void)
{
    int dims[3] = {9, 8, 7};
    uint8_t *v = malloc(9 * 8 * 7);
    memset(v, 123, 9 * 8 * 7);
    ref_volume_t vol = {{9, 8, 7}, {1.0, 1.25, 1.5}, v};
    ref_view_t view = {0, 0, 0, 1.0};
    double rgba[4], tf_v[4];
    /* head on, the central ray runs the whole z extent: L = (n_z - 1) Sr_z world units */
    CHECK_EQ(truth_ray(&vol, g_tf, G_TF_POINTS, &view, 64, 48, 31.5, 23.5, rgba), 0);
    ref_tf_eval(g_tf, G_TF_POINTS, 123, tf_v);
    double L = (dims[2] - 1) * 1.5, A = -expm1(L * log1p(-tf_v[3]));
    CHECK_NEAR(rgba[3], A, 1e-6);
    for (int c = 0; c < 3; c++)
        CHECK_NEAR(rgba[c], tf_v[c] * A, 1e-6);
    /* an off-centre ray, head on too: the same length */
    CHECK_EQ(truth_ray(&vol, g_tf, G_TF_POINTS, &view, 64, 48, 25.25, 20.0, rgba), 0);
    CHECK_NEAR(rgba[3], A, 1e-12);
    free(v);
}

static void check_line(const ref_volume_t *vol, const ref_view_t *view, int w, int h, double px, double py,
                       double ga, double gb, double gc, double gd, double *worst)
{
    truth_camera_t cam;
    double o[3], d[3], t_in, t_out, got[4], want[4];
    CHECK_EQ(truth_camera(vol, view, w, h, &cam), 0);
    CHECK(truth_camera_ray(&cam, px, py, o, d, &t_in, &t_out));
    CHECK(t_out - t_in > 2);
    double s0 = ga * (o[0] + t_in * d[0]) + gb * (o[1] + t_in * d[1]) + gc * (o[2] + t_in * d[2]) + gd;
    double ds = ga * d[0] + gb * d[1] + gc * d[2];
    integrate_line(g_tf, G_TF_POINTS, s0, ds, t_out - t_in, want);
    CHECK_EQ(truth_ray(vol, g_tf, G_TF_POINTS, view, w, h, px, py, got), 0);
    CHECK(want[3] > 0.3); /* the ray meets enough of the transfer function to be a test */
    for (int c = 0; c < 4; c++) {
        CHECK_NEAR(got[c], want[c], 1e-6);
        *worst = fmax(*worst, fabs(got[c] - want[c]));
    }
}

static void linear_ramp_head_on(void)
{
    int dims[3] = {6, 5, 12};
    uint8_t *v = linear_volume(dims, 0, 0, 20, 10); /* 10 .. 230 along z */
    ref_volume_t vol = {{6, 5, 12}, {1, 1, 1}, v};
    ref_view_t view = {0, 0, 0, 1.0};
    double worst = 0;
    check_line(&vol, &view, 40, 40, 19.5, 19.5, 0, 0, 20, 10, &worst);
    if (!check_failed)
        check_line(&vol, &view, 40, 40, 17.3, 22.1, 0, 0, 20, 10, &worst);
    vol.spacing[2] = 0.75; /* anisotropic: the z voxel is the d_ref now, x and y are longer */
    if (!check_failed)
        check_line(&vol, &view, 40, 40, 19.5, 19.5, 0, 0, 20, 10, &worst);
    /* looking back along -z (azimuth 180): the scalar falls along the ray */
    view.azimuth = 32768;
    if (!check_failed)
        check_line(&vol, &view, 40, 40, 21.0, 18.0, 0, 0, 20, 10, &worst);
    printf("# linear ramp head on: largest |truth - Simpson| %.3g\n", worst);
    free(v);
}

static void linear_ramp_oblique(void)
{
    int dims[3] = {12, 10, 9};
    uint8_t *v = linear_volume(dims, 3, 5, 7, 20); /* 20 .. 174 */
    ref_volume_t vol = {{12, 10, 9}, {1.0, 1.5, 0.8}, v};
    double worst = 0;
    const ref_view_t views[] = {{5461, 3641, 0, 1.0}, {-12000, 9000, 2000, 1.3}, {20000, -15000, -7000, 0.8}};
    for (int n = 0; n < 3 && !check_failed; n++) {
        check_line(&vol, &views[n], 50, 40, 24.5, 19.5, 3, 5, 7, 20, &worst);
        if (!check_failed)
            check_line(&vol, &views[n], 50, 40, 21.2, 17.7, 3, 5, 7, 20, &worst);
    }
    printf("# linear ramp oblique: largest |truth - Simpson| %.3g\n", worst);
    free(v);
}

/* The ray through a final pixel crosses standard slice 0 where the reference's warp says it does. */
static void camera_matches_reference_warp(void)
{
    int dims[3] = {20, 14, 9};
    uint8_t *v = calloc(20 * 14 * 9, 1);
    ref_volume_t vol = {{20, 14, 9}, {1.0, 2.0, 1.5}, v};
    const ref_view_t views[] = {{0, 0, 0, 1.0}, {5461, 3641, 0, 1.0}, {30000, -9000, 4000, 1.7},
                                {-20000, 14000, -3000, 0.6}, {16384, 0, 0, 1.0}};
    for (int n = 0; n < 5; n++) {
        truth_camera_t cam;
        ref_factor_t f;
        CHECK_EQ(truth_camera(&vol, &views[n], 64, 48, &cam), 0);
        CHECK_EQ(ref_factor(&vol, &views[n], 64, 48, &f), 0);
        for (double py = 3; py < 48; py += 11)
            for (double px = 5; px < 64; px += 13) {
                double o[3], d[3], t_in, t_out, u, w;
                truth_camera_ray(&cam, px, py, o, d, &t_in, &t_out);
                /* the t where standard k is 0 */
                double plane = f.k_flip ? dims[f.k_axis] - 1 : 0, t = (plane - o[f.k_axis]) / d[f.k_axis];
                ref_factor_warp(&f, px, py, &u, &w);
                CHECK_NEAR(o[f.i_axis] + t * d[f.i_axis], u - f.ti, 1e-9);
                CHECK_NEAR(o[f.j_axis] + t * d[f.j_axis], w - f.tj, 1e-9);
            }
    }
    free(v);
}

static void miss_gives_background(void)
{
    uint8_t *v = malloc(8 * 8 * 8);
    memset(v, 123, 8 * 8 * 8); /* opaque and orange */
    ref_volume_t vol = {{8, 8, 8}, {1, 1, 1}, v};
    ref_view_t view = {5461, 3641, 0, 1.0};
    double rgba[4], bg[3] = {0.25, 0.5, 0.75}, *rgb = malloc(sizeof(double) * 3 * 32 * 32);
    CHECK_EQ(truth_ray(&vol, g_tf, G_TF_POINTS, &view, 32, 32, -40, 10, rgba), 0);
    CHECK(rgba[0] == 0 && rgba[1] == 0 && rgba[2] == 0 && rgba[3] == 0);
    CHECK_EQ(truth_render(&vol, g_tf, G_TF_POINTS, bg, &view, 32, 32, 2, rgb), 0);
    /* zoom 1 fits the bounding sphere: the corners lie outside it */
    for (int c = 0; c < 3; c++) {
        CHECK(rgb[c] == bg[c]);
        CHECK(rgb[3 * (32 * 32 - 1) + c] == bg[c]);
    }
    CHECK(fabs(rgb[3 * (16 * 32 + 16)] - bg[0]) > 0.1); /* the centre sees the volume */
    free(rgb);
    free(v);
}

/* Opaque red in front, green behind: a ray that stops at opacity 1 - 1e-9 never takes any green. */
static void stops_at_opacity(void)
{
    uint8_t *v = malloc(5 * 5 * 12);
    for (int z = 0; z < 12; z++)
        memset(v + 25 * z, z < 6 ? 200 : 50, 25);
    const ref_tf_point_t tf[] = {{50, 0, 1, 0, 1}, {200, 1, 0, 0, 1}};
    ref_volume_t vol = {{5, 5, 12}, {1, 1, 1}, v};
    ref_view_t view = {0, 0, 0, 1.0};
    double rgba[4];
    CHECK_EQ(truth_ray(&vol, tf, 2, &view, 33, 33, 16, 16, rgba), 0);
    CHECK(rgba[3] >= TRUTH_STOP_OPACITY && rgba[3] <= 1);
    CHECK(rgba[1] == 0 && rgba[2] == 0);
    CHECK_NEAR(rgba[0], rgba[3], 1e-15);
    free(v);
}

static double *radial_image(int threads, const ref_view_t *view, int w, int h)
{
    int n = 17;
    uint8_t *v = malloc((size_t)n * n * n);
    for (int z = 0; z < n; z++)
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++) {
                double r = sqrt((x - 8.0) * (x - 8.0) + (y - 8.0) * (y - 8.0) + (z - 8.0) * (z - 8.0));
                v[x + n * (y + n * z)] = (uint8_t)fmax(0, 250 - 24 * r);
            }
    ref_volume_t vol = {{n, n, n}, {1, 1, 1}, v};
    double bg[3] = {0.1, 0.2, 0.3}, *rgb = malloc(sizeof(double) * 3 * w * h);
    int status = truth_render(&vol, g_tf, G_TF_POINTS, bg, view, w, h, threads, rgb);
    free(v);
    if (status) {
        free(rgb);
        return NULL;
    }
    return rgb;
}

/* A radial volume viewed along z (and along x) gives an image symmetric in both image axes and the diagonal;
 * 1 and 3 threads give the same image. */
static void symmetric_and_thread_independent(void)
{
    const int w = 40, h = 40;
    const ref_view_t views[] = {{0, 0, 0, 1.0}, {16384, 0, 0, 1.2}};
    for (int n = 0; n < 2; n++) {
        double *one = radial_image(1, &views[n], w, h), *three = radial_image(3, &views[n], w, h);
        CHECK(one && three);
        double worst = 0;
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
                for (int c = 0; c < 3; c++) {
                    double p = one[3 * (y * w + x) + c];
                    worst = fmax(worst, fabs(p - one[3 * (y * w + (w - 1 - x)) + c]));
                    worst = fmax(worst, fabs(p - one[3 * ((h - 1 - y) * w + x) + c]));
                    worst = fmax(worst, fabs(p - one[3 * (x * w + y) + c]));
                    CHECK(p == three[3 * (y * w + x) + c]);
                }
        CHECK_MSG(worst < 1e-9, "view %d: asymmetry %.3g", n, worst);
        CHECK(fabs(one[3 * (20 * w + 20)] - 0.1) > 0.05); /* something was seen */
        free(one);
        free(three);
    }
}

static double log_g(double a0, double a1, double u)
{
    return -log1p(-(a0 + (a1 - a0) * u));
}

/* Gauss-Legendre (5 points) on [lo, hi] split where 1 - a halves, so that the log near the opaque end is
 * gentle on every part: an independent quadrature of the mean of -ln(1 - a). */
static double depth_quadrature(double a0, double a1)
{
    static const double x[5] = {0.046910077030668004, 0.23076534494715845, 0.5, 0.76923465505284155,
                                0.95308992296933200};
    static const double w[5] = {0.11846344252809454, 0.23931433524968324, 0.28444444444444444,
                                0.23931433524968324, 0.11846344252809454};
    double sum = 0, lo = 0;
    while (lo < 1) {
        double g = 1 - (a0 + (a1 - a0) * lo), hi = 1;
        if (a1 > a0) /* the next u where g is half of what it is at lo, or 1 */
            hi = fmin(1.0, lo + 0.5 * g / (a1 - a0));
        for (int part = 0; part < 64; part++)
            for (int j = 0; j < 5; j++) {
                double p0 = lo + (hi - lo) * part / 64, p1 = lo + (hi - lo) * (part + 1) / 64;
                sum += w[j] * (p1 - p0) * log_g(a0, a1, p0 + (p1 - p0) * x[j]);
            }
        lo = hi;
    }
    return sum;
}

/* The optical depth's closed form against a direct quadrature of -ln(1 - a), incl. near-equal ends and the
 * opaque clamp. */
static void depth_closed_form(void)
{
    const double ends[][2] = {{0.3, 0.3}, {0.3, 0.3000001}, {0.0, 0.9}, {0.9, 0.0}, {1e-5, 2e-5}, {0.5, A0_MAX},
                              {A0_MAX, 0.01}, {0.2, 0.2005}};
    for (int n = 0; n < 8; n++) {
        double a0 = ends[n][0], a1 = ends[n][1];
        /* the quadrature runs from the transparent end so that the halving steps reach the opaque one */
        double want = a0 <= a1 ? depth_quadrature(a0, a1) : depth_quadrature(a1, a0);
        CHECK_MSG(fabs(truth_depth(a0, a1, 2.5) - 2.5 * want) <= 1e-12 * fmax(1, want), "a %g..%g: %.17g vs %.17g",
                  a0, a1, truth_depth(a0, a1, 2.5), 2.5 * want);
    }
}

/* Cell skipping: opacity zero on [lo, hi] exactly when the transfer function says so, steps included; and the
 * steepness that sets the sub-step tolerance. */
static void tf_clear_ranges(void)
{
    const ref_tf_point_t tf[] = {{60, 1, 1, 1, 0}, {80, 1, 1, 1, 0.5}, {90, 1, 1, 1, 0}, {120, 1, 1, 1, 0},
                                 {120, 1, 1, 1, 0.4}, {140, 1, 1, 1, 0.4}, {140, 1, 1, 1, 0}};
    truth_tf_t *t = malloc(sizeof *t);
    CHECK_EQ(truth_tf_init(t, tf, 7), 0);
    CHECK(truth_tf_clear(t, 0, 60));
    CHECK(!truth_tf_clear(t, 0, 61));
    CHECK(truth_tf_clear(t, 90, 119));
    CHECK(!truth_tf_clear(t, 90, 120)); /* the step up at 120 holds at 120 */
    CHECK(!truth_tf_clear(t, 120, 120));
    CHECK(!truth_tf_clear(t, 139, 139));
    CHECK(!truth_tf_clear(t, 139, 140)); /* the left limit at 140 is 0.4 */
    CHECK(truth_tf_clear(t, 140, 140)); /* the step down at 140 holds at 140 */
    CHECK(truth_tf_clear(t, 140, 255));
    /* steepness: how much a scalar error matters, infinite across a step */
    CHECK_NEAR(truth_tf_steepness(t, 60, 70), 0.5 / 20, 1e-15);
    CHECK_NEAR(truth_tf_steepness(t, 85, 95), 0.5 / 10, 1e-15);
    CHECK(truth_tf_steepness(t, 121, 139) == 0);
    CHECK(isinf(truth_tf_steepness(t, 118, 121)));
    CHECK(isinf(truth_tf_steepness(t, 135, 141)));
    free(t);
}

/* The defaults are converged: a much finer integration moves no channel of a hard case by more than 1e-4. */
static void converged_against_finer_steps(void)
{
    int n = 21;
    uint8_t *v = malloc((size_t)n * n * n);
    for (int z = 0; z < n; z++)
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++)
                v[x + n * (y + n * z)] = (uint8_t)(127.5 + 120 * sin(0.7 * x) * cos(0.5 * y + 0.3 * z));
    const ref_tf_point_t sharp[] = {{0, 0, 0, 0, 0},      {74, 1, .5, .1, 0},  {76.5, 1, .5, .1, .9},
                                    {79, 1, .5, .1, 0},   {138, .2, 1, .3, 0}, {140.5, .2, 1, .3, .9},
                                    {143, .2, 1, .3, 0},  {201, 1, 1, 1, 0},   {204, 1, 1, 1, 1},
                                    {207, 1, 1, 1, 0}};
    ref_volume_t vol = {{n, n, n}, {1, 1, 1}, v};
    ref_view_t view = {5461, 3641, 0, 1.0};
    truth_opts_t fine = {1.0 / 256, 1e-6, 0, NULL};
    double worst = 0;
    for (double py = 8; py < 64; py += 9.7)
        for (double px = 8; px < 64; px += 7.3) {
            double a[4], b[4];
            CHECK_EQ(truth_ray(&vol, sharp, 10, &view, 64, 64, px, py, a), 0);
            CHECK_EQ(truth_ray_ex(&vol, sharp, 10, &view, 64, 64, px, py, &fine, b), 0);
            for (int c = 0; c < 4; c++)
                worst = fmax(worst, fabs(a[c] - b[c]));
        }
    printf("# defaults against 1/256-voxel steps, a 1e-6 tolerance, steep 0: largest difference %.3g\n", worst);
    CHECK_MSG(worst < 1e-4, "default vs fine: %.3g", worst);
    free(v);
}

static void bad_arguments(void)
{
    uint8_t v[8] = {0};
    ref_volume_t vol = {{2, 2, 2}, {1, 1, 1}, v}, flat = {{2, 1, 2}, {1, 1, 1}, v};
    ref_view_t view = {0, 0, 0, 1.0}, zero = {0, 0, 0, 0};
    const ref_tf_point_t backwards[] = {{10, 0, 0, 0, 0}, {5, 0, 0, 0, 0}};
    double rgba[4], rgb[3 * 4], bg[3] = {0, 0, 0};
    CHECK_EQ(truth_ray(&flat, g_tf, G_TF_POINTS, &view, 2, 2, 0, 0, rgba), -1);
    CHECK_EQ(truth_ray(&vol, g_tf, G_TF_POINTS, &zero, 2, 2, 0, 0, rgba), -1);
    CHECK_EQ(truth_ray(&vol, backwards, 2, &view, 2, 2, 0, 0, rgba), -1);
    CHECK_EQ(truth_ray(&vol, g_tf, 0, &view, 2, 2, 0, 0, rgba), -1);
    CHECK_EQ(truth_render(&vol, g_tf, G_TF_POINTS, bg, &view, 2, 2, 0, rgb), -1);
    CHECK_EQ(truth_render(&vol, g_tf, G_TF_POINTS, bg, &view, 2, 2, 1, rgb), 0);
}

CHECK_CASES({"constant volume: closed form", constant_volume_closed_form},
            {"linear ramp head on: independent integration", linear_ramp_head_on},
            {"linear ramp oblique: independent integration", linear_ramp_oblique},
            {"camera matches the reference's warp", camera_matches_reference_warp},
            {"a miss gives the background", miss_gives_background},
            {"a ray stops at opacity 1 - 1e-9", stops_at_opacity},
            {"symmetric phantom, thread independent", symmetric_and_thread_independent},
            {"optical depth closed form", depth_closed_form},
            {"cell skipping ranges and steepness", tf_clear_ranges},
            {"defaults converged against finer steps", converged_against_finer_steps},
            {"bad arguments", bad_arguments});
CHECK_RUN("truth")
