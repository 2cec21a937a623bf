/* SPDX-License-Identifier: MIT */
/*
 * test_truth_smooth.c: the truth's smooth reconstructions (host-sim/truth/truth_smooth.c) reconstruct what they
 * say: Catmull-Rom interpolates the voxels and reproduces quadratics, the B-spline is the 1-4-1 blend at grid
 * points, both reproduce linear data up to the faces, every value lies within the cell bound the walk skips on,
 * a phantom's function equals its voxels within their rounding, the walk integrates to the accuracy of much
 * finer settings, and a render against the smooth truth equals the trilinear truth where the two fields agree
 * (linear data) and differs where they do not (Marschner-Lobb).
 */
#include "check.h"
#include "io/volume.h"
#include "truth/truth.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const ref_tf_point_t sharp[] = {{0, 0, 0, 0, 0},      {74, 1, .5, .1, 0},  {76.5, 1, .5, .1, .9},
                                       {79, 1, .5, .1, 0},   {138, .2, 1, .3, 0}, {140.5, .2, 1, .3, .9},
                                       {143, .2, 1, .3, 0},  {201, 1, 1, 1, 0},   {204, 1, 1, 1, 1},
                                       {207, 1, 1, 1, 0}};

static double unit(uint64_t *seed)
{
    return (check_rand64(seed) >> 11) * (1.0 / 9007199254740992.0);
}

static uint8_t *random_volume(int n, uint64_t seed)
{
    uint8_t *v = malloc((size_t)n * n * n);
    for (int i = 0; v && i < n * n * n; i++)
        v[i] = (uint8_t)check_below(&seed, 256);
    return v;
}

static void catmull_rom_interpolates(void)
{
    const int n = 7;
    uint8_t *v = random_volume(n, 11);
    ref_volume_t vol = {{n, n, n}, {1, 1, 1}, v};
    truth_field_t f;
    CHECK_EQ(truth_field_init(&f, &vol, TRUTH_FILTER_CATMULL_ROM, NULL, 0, 255), 0);
    for (int z = 0; z < n; z++)
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++) {
                double p[3] = {x, y, z};
                CHECK_NEAR(truth_field_sample(&f, p), v[x + n * (y + n * z)], 1e-9);
            }
    truth_field_free(&f);
    free(v);
}

/* Inside (every 4^3 neighbourhood real) Catmull-Rom is exact for quadratics; up to the faces both cubic
 * filters are exact for linear data (the ghosts are extrapolated linearly). */
static void reproduces_polynomials(void)
{
    const int n = 7;
    uint8_t quad[7 * 7 * 7], lin[7 * 7 * 7];
    for (int z = 0; z < n; z++)
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++) {
                quad[x + n * (y + n * z)] = (uint8_t)(x * x + y * y + 2 * z * z + x * y + 3);
                lin[x + n * (y + n * z)] = (uint8_t)(3 * x + 5 * y + 7 * z + 10);
            }
    ref_volume_t vq = {{n, n, n}, {1, 1, 1}, quad}, vl = {{n, n, n}, {1, 1, 1}, lin};
    truth_field_t cq, cl, bl;
    CHECK_EQ(truth_field_init(&cq, &vq, TRUTH_FILTER_CATMULL_ROM, NULL, 0, 255), 0);
    CHECK_EQ(truth_field_init(&cl, &vl, TRUTH_FILTER_CATMULL_ROM, NULL, 0, 255), 0);
    CHECK_EQ(truth_field_init(&bl, &vl, TRUTH_FILTER_BSPLINE, NULL, 0, 255), 0);
    uint64_t seed = 5;
    for (int t = 0; t < 2000; t++) {
        double in[3], any[3];
        for (int a = 0; a < 3; a++) {
            in[a] = 1 + (n - 3) * unit(&seed);
            any[a] = (n - 1) * unit(&seed);
        }
        double x = in[0], y = in[1], z = in[2];
        CHECK_NEAR(truth_field_sample(&cq, in), x * x + y * y + 2 * z * z + x * y + 3, 1e-9);
        double want = 3 * any[0] + 5 * any[1] + 7 * any[2] + 10;
        CHECK_NEAR(truth_field_sample(&cl, any), want, 1e-9);
        CHECK_NEAR(truth_field_sample(&bl, any), want, 1e-9);
    }
    truth_field_free(&cq), truth_field_free(&cl), truth_field_free(&bl);
}

static void bspline_blends(void)
{
    const int n = 6;
    uint8_t *v = random_volume(n, 23);
    ref_volume_t vol = {{n, n, n}, {1, 1, 1}, v};
    truth_field_t f;
    CHECK_EQ(truth_field_init(&f, &vol, TRUTH_FILTER_BSPLINE, NULL, 0, 255), 0);
    const double w[3] = {1.0 / 6, 4.0 / 6, 1.0 / 6};
    for (int z = 1; z < n - 1; z++)
        for (int y = 1; y < n - 1; y++)
            for (int x = 1; x < n - 1; x++) {
                double want = 0, p[3] = {x, y, z};
                for (int c = 0; c < 27; c++) {
                    int dx = c % 3 - 1, dy = c / 3 % 3 - 1, dz = c / 9 - 1;
                    want += w[dx + 1] * w[dy + 1] * w[dz + 1] * v[(x + dx) + n * ((y + dy) + n * (z + dz))];
                }
                CHECK_NEAR(truth_field_sample(&f, p), want, 1e-9);
            }
    truth_field_free(&f);
    free(v);
}

/* The walk skips a cell when the transfer function is clear on its bound: every value in it must lie inside. */
static void cell_bounds_hold(void)
{
    const int n = 9;
    uint8_t *v = random_volume(n, 77);
    ref_volume_t vol = {{n, n, n}, {1, 1, 1}, v};
    for (int filter = TRUTH_FILTER_CATMULL_ROM; filter <= TRUTH_FILTER_BSPLINE; filter++) {
        truth_field_t f;
        CHECK_EQ(truth_field_init(&f, &vol, (truth_filter_t)filter, NULL, 0, 255), 0);
        uint64_t seed = 99;
        int tight = 0;
        for (int t = 0; t < 20000; t++) {
            double p[3];
            int c[3];
            for (int a = 0; a < 3; a++) {
                c[a] = (int)check_below(&seed, (uint32_t)(n - 1));
                p[a] = c[a] + unit(&seed);
            }
            size_t at = (size_t)c[0] + (size_t)(n - 1) * (c[1] + (size_t)(n - 1) * c[2]);
            double s = truth_field_sample(&f, p);
            CHECK_MSG(s >= f.cell_lo[at] && s <= f.cell_hi[at], "%s: %.3f outside [%d, %d]",
                      truth_filter_name((truth_filter_t)filter), s, f.cell_lo[at], f.cell_hi[at]);
            tight += f.cell_hi[at] - f.cell_lo[at] < 255;
        }
        CHECK(tight > 0 || filter == TRUTH_FILTER_CATMULL_ROM); /* random data: the B-spline's bounds still bite */
        truth_field_free(&f);
    }
    free(v);
}

static void phantom_functions(void)
{
    const char *specs[] = {"phantom:marschner-lobb:41", "phantom:sphere:24", "phantom:cube:8"};
    for (int s = 0; s < 3; s++) {
        vfp_volume_t pv;
        char err[256];
        CHECK_MSG(vfp_volume_load(&pv, specs[s], NULL, err, sizeof err) == VFP_OK, "%s", err);
        const vf_volume_t *cv = &pv.core;
        ref_volume_t vol = {{(int)cv->dims[0], (int)cv->dims[1], (int)cv->dims[2]}, {1, 1, 1}, cv->voxels};
        truth_field_t f;
        CHECK_EQ(truth_field_init(&f, &vol, TRUTH_FILTER_SMOOTH, specs[s], 0, 255), 0);
        CHECK_EQ(f.filter, TRUTH_FILTER_ANALYTIC);
        double worst = 0;
        for (int z = 0; z < vol.dims[2]; z++)
            for (int y = 0; y < vol.dims[1]; y++)
                for (int x = 0; x < vol.dims[0]; x++) {
                    double p[3] = {x, y, z};
                    const uint8_t *v = vol.scalars;
                    worst = fmax(worst, fabs(truth_field_sample(&f, p) - v[x + vol.dims[0] * (y + vol.dims[1] * z)]));
                }
        CHECK_MSG(worst <= 0.5 + 1e-9, "%s: %.6f from its voxels", specs[s], worst);
        /* windowed like the voxels: window 64..192 maps the raw 128 to 127.5 */
        truth_field_free(&f);
        CHECK_EQ(truth_field_init(&f, &vol, TRUTH_FILTER_ANALYTIC, specs[s], 64, 192), 0);
        double p[3] = {3.25, 2.5, 1.75}, raw = f.analytic(p, vol.dims);
        CHECK_NEAR(truth_field_sample(&f, p), fmin(fmax((raw - 64) * 255 / 128, 0), 255), 1e-9);
        truth_field_free(&f);
        vfp_volume_free(&pv);
    }
    /* shepp-logan has jumps and no smooth function: smooth means Catmull-Rom there, analytic is refused */
    uint8_t v[8] = {0};
    ref_volume_t vol = {{2, 2, 2}, {1, 1, 1}, v};
    truth_field_t f;
    CHECK_EQ(truth_field_init(&f, &vol, TRUTH_FILTER_SMOOTH, "phantom:shepp-logan:2", 0, 255), 0);
    CHECK_EQ(f.filter, TRUTH_FILTER_CATMULL_ROM);
    truth_field_free(&f);
    CHECK_EQ(truth_field_init(&f, &vol, TRUTH_FILTER_ANALYTIC, "/data/x.nhdr", 0, 255), -2);
    CHECK(truth_phantom_fn("phantom:marschner-lobb:41") != NULL);
    CHECK(truth_phantom_fn("phantom:shepp-logan:41") == NULL);
}

/* Images of a smooth volume with the sharp peaks: the defaults against 1/128-voxel steps and a 1e-6
 * tolerance with no relaxation, per filter. */
static void walk_accuracy(void)
{
    const int n = 16;
    uint8_t *v = malloc((size_t)n * n * n);
    for (int z = 0; z < n; z++)
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++)
                v[x + n * (y + n * z)] = (uint8_t)(127.5 + 120 * sin(0.7 * x) * cos(0.5 * y + 0.3 * z));
    ref_volume_t vol = {{n, n, n}, {1, 1, 1}, v};
    ref_view_t view = {5461, 3641, 0, 1.0};
    for (int filter = TRUTH_FILTER_CATMULL_ROM; filter <= TRUTH_FILTER_BSPLINE; filter++) {
        truth_field_t f;
        CHECK_EQ(truth_field_init(&f, &vol, (truth_filter_t)filter, NULL, 0, 255), 0);
        truth_opts_t dflt = TRUTH_OPTS_DEFAULT, fine = {1.0 / 128, 1e-6, 0, &f};
        dflt.field = &f;
        double worst = 0, seen = 0;
        for (double py = 6; py < 48; py += 7.7)
            for (double px = 6; px < 48; px += 6.3) {
                double a[4], b[4];
                CHECK_EQ(truth_ray_ex(&vol, sharp, 10, &view, 48, 48, px, py, &dflt, a), 0);
                CHECK_EQ(truth_ray_ex(&vol, sharp, 10, &view, 48, 48, px, py, &fine, b), 0);
                for (int c = 0; c < 4; c++)
                    worst = fmax(worst, fabs(a[c] - b[c]));
                seen = fmax(seen, b[3]);
            }
        printf("# %s: defaults against 1/128-voxel steps, tolerance 1e-6, steep 0: largest difference %.3g\n",
               truth_filter_name((truth_filter_t)filter), worst);
        CHECK(seen > 0.5); /* the rays meet the peaks */
        CHECK_MSG(worst < 1e-3, "%s: default vs fine %.3g", truth_filter_name((truth_filter_t)filter), worst);
        truth_field_free(&f);
    }
    free(v);
}

static double image_mean_diff(const double *a, const double *b, size_t count)
{
    double sum = 0;
    for (size_t i = 0; i < count; i++)
        sum += fabs(a[i] - b[i]);
    return sum / count;
}

static void render_against_trilinear(void)
{
    const int w = 40, h = 40;
    const double bg[3] = {0, 0, 0};
    ref_view_t view = {5461, 3641, 0, 1.0};
    double *tri = malloc(sizeof(double) * 3 * w * h), *smooth = malloc(sizeof(double) * 3 * w * h);
    CHECK(tri && smooth);
    /* linear data: trilinear, Catmull-Rom and the B-spline are the same field, so the same image */
    const int n = 12;
    uint8_t lin[12 * 12 * 12];
    for (int z = 0; z < n; z++)
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++)
                lin[x + n * (y + n * z)] = (uint8_t)(6 * x + 7 * y + 8 * z + 2);
    ref_volume_t vl = {{n, n, n}, {1, 1, 1}, lin};
    CHECK_EQ(truth_render(&vl, sharp, 10, bg, &view, w, h, 2, tri), 0);
    double worst = 0;
    for (int filter = TRUTH_FILTER_CATMULL_ROM; filter <= TRUTH_FILTER_BSPLINE; filter++) {
        truth_field_t f;
        CHECK_EQ(truth_field_init(&f, &vl, (truth_filter_t)filter, NULL, 0, 255), 0);
        truth_opts_t o = TRUTH_OPTS_DEFAULT;
        o.field = &f;
        CHECK_EQ(truth_render_ex(&vl, sharp, 10, bg, &view, w, h, 2, &o, smooth), 0);
        for (int i = 0; i < 3 * w * h; i++)
            worst = fmax(worst, fabs(tri[i] - smooth[i]));
        truth_field_free(&f);
    }
    CHECK_MSG(worst < 2e-3, "linear data: smooth and trilinear truths %.3g apart", worst);
    double mean_tri = 0;
    for (int i = 0; i < 3 * w * h; i++)
        mean_tri += tri[i];
    CHECK(mean_tri / (3 * w * h) > 0.05); /* the peaks are crossed */

    /* Marschner-Lobb: its function bends between voxels, where trilinear goes straight */
    vfp_volume_t pv;
    char err[256];
    CHECK_MSG(vfp_volume_load(&pv, "phantom:marschner-lobb:21", NULL, err, sizeof err) == VFP_OK, "%s", err);
    ref_volume_t vm = {{21, 21, 21}, {1, 1, 1}, pv.core.voxels};
    truth_field_t f;
    CHECK_EQ(truth_field_init(&f, &vm, TRUTH_FILTER_SMOOTH, "phantom:marschner-lobb:21", 0, 255), 0);
    truth_opts_t o = TRUTH_OPTS_DEFAULT;
    o.field = &f;
    CHECK_EQ(truth_render(&vm, sharp, 10, bg, &view, w, h, 2, tri), 0);
    CHECK_EQ(truth_render_ex(&vm, sharp, 10, bg, &view, w, h, 2, &o, smooth), 0);
    double d = image_mean_diff(tri, smooth, (size_t)3 * w * h);
    printf("# marschner-lobb 21^3, sharp: analytic against trilinear truth, mean difference %.4f\n", d);
    CHECK_MSG(d > 0.01, "analytic and trilinear truths only %.4g apart", d);
    truth_field_free(&f);
    vfp_volume_free(&pv);
    free(tri), free(smooth);
}

CHECK_CASES({"catmull_rom_interpolates", catmull_rom_interpolates}, {"reproduces_polynomials", reproduces_polynomials},
            {"bspline_blends", bspline_blends}, {"cell_bounds_hold", cell_bounds_hold},
            {"phantom_functions", phantom_functions}, {"walk_accuracy", walk_accuracy},
            {"render_against_trilinear", render_against_trilinear});
CHECK_RUN("host-sim/truth_smooth")
