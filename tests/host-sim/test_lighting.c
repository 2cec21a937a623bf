/* SPDX-License-Identifier: MIT */
/*
 * test_lighting.c: lighting in the simulator (docs/algorithm.md section 7, and its "Lit truth"):
 *   - the acceptance figures: the fixed-point core against the double reference, lit, on engine, brainsmall,
 *     neghip, cthead and headsq at views 30,20 45,0 135,70 in point, preclass and preint1 (256x256): at most 2
 *     levels and PSNR >= 50 dB each; lit preint1 closer to the lit truth than lit point on Marschner-Lobb 41^3,
 *     neghip, engine and bucky with the sharp preset (the dB printed);
 *   - the reference's parts against section 7 written out here: normal codes and magnitudes of a small volume,
 *     the shade of a normal, the mean depth t(x) and a uniform slab's front-weighted values in closed form, the
 *     front-weighted table against the core's builder;
 *   - wiring: a material of ka 1, kd 0, ks 0 lights nothing, so the reference and the truth give their unlit
 *     images to the bit; the lit truth of a sphere is brightest where it faces the headlight; a gradient-opacity
 *     ramp above every magnitude leaves the truth empty.
 * The acceptance cases cost about 40 s with two threads for the core (engine and cthead most of it).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "imgcmp.h"
#include "io/pngio.h"
#include "scene.h"
#include "truth/truth.h"

static const char *data_dir(void)
{
    return getenv("VOLFIX_DATA") ? getenv("VOLFIX_DATA") : "../shared/data";
}

/* A scene from volfix-sim's options (the volume first); 0, or -1 with the reason in err. */
static int load_scene(sim_scene_t *s, int argc, char **argv, char *err, size_t errlen)
{
    sim_opts_t o;
    if (sim_parse(&o, argc, argv, SIM_OPT_SCENE, "")) {
        snprintf(err, errlen, "bad options");
        return -1;
    }
    return sim_scene_load(s, &o, err, errlen) ? -1 : 0;
}

/* The core's and the reference's (or the truth's) images of a scene compared: 0 with d, or -1 with err. */
static int compare(const sim_scene_t *s, int truth, sim_diff_t *d, char *err, size_t errlen)
{
    vf_image_t core, other;
    vf_factor_t factor;
    if (sim_render_core(s, &core, &factor, err, errlen))
        return -1;
    if (truth ? sim_render_truth(s, &other, err, errlen) : sim_render_reference(s, &factor, &other, err, errlen)) {
        sim_image_free(&core);
        return -1;
    }
    const size_t pixels = (size_t)s->width * s->height;
    uint8_t *a = malloc(pixels * 3), *b = malloc(pixels * 3);
    int rc = -1;
    if (a && b) {
        vfp_image_to_rgb(&core, a);
        vfp_image_to_rgb(&other, b);
        sim_diff(a, b, pixels, d);
        rc = 0;
    } else {
        snprintf(err, errlen, "out of memory");
    }
    free(a);
    free(b);
    sim_image_free(&core);
    sim_image_free(&other);
    return rc;
}

/* ---- the acceptance figures -------------------------------------------------------------------------- */

/* One volume, lit with its preset, at the three views in the three modes: at most 2 levels, PSNR >= 50 dB. */
static void fixed_vs_double(const char *file, const char *preset)
{
    char path[1024], err[VFP_ERR_LEN];
    snprintf(path, sizeof path, "%s/%s", data_dir(), file);
    char *argv[] = {path, "--preset", (char *)preset, "--shade", "phong", "--size", "256x256", "--threads", "2"};
    sim_scene_t s;
    CHECK_MSG(load_scene(&s, 9, argv, err, sizeof err) == 0, "%s: %s", file, err);
    static const double views[3][2] = {{30, 20}, {45, 0}, {135, 70}};
    static const vf_mode_t modes[3] = {VF_MODE_POINT, VF_MODE_PRECLASS, VF_MODE_PREINT1};
    int worst_max = 0;
    double worst_psnr = 1e9;
    for (int v = 0; v < 3; v++)
        for (int m = 0; m < 3; m++) {
            s.view = sim_view(views[v][0], views[v][1], 0, 1);
            s.params.mode = modes[m];
            sim_diff_t d;
            if (compare(&s, 0, &d, err, sizeof err)) {
                sim_scene_free(&s);
                CHECK_MSG(0, "%s: %s", file, err);
            }
            printf("# lit %s %s %g,%g %s: PSNR %.2f dB, max %d\n", file, preset, views[v][0], views[v][1],
                   vf_mode_name(modes[m]), d.psnr_db, d.max_abs[3]);
            worst_max = d.max_abs[3] > worst_max ? d.max_abs[3] : worst_max;
            worst_psnr = d.psnr_db < worst_psnr ? d.psnr_db : worst_psnr;
        }
    sim_scene_free(&s);
    CHECK_MSG(worst_max <= 2 && worst_psnr >= 50, "%s: worst %d levels, %.2f dB (bound: 2 levels, 50 dB)", file,
              worst_max, worst_psnr);
}

static void fixed_engine(void)
{
    fixed_vs_double("engine.nhdr", "ct-bone");
}
static void fixed_brainsmall(void)
{
    fixed_vs_double("brainsmall.nhdr", "mr-brain");
}
static void fixed_neghip(void)
{
    fixed_vs_double("neghip.nhdr", "sharp");
}
static void fixed_cthead(void)
{
    fixed_vs_double("cthead.nhdr", "ct-skin-bone");
}
static void fixed_headsq(void)
{
    fixed_vs_double("headsq.nhdr", "ct-bone");
}

/* Lit preint1 against lit point, both against the lit truth, sharp preset, 256x256, view 30,20. */
static void truth_case(const char *volume)
{
    char err[VFP_ERR_LEN];
    char *argv[] = {(char *)volume, "--preset", "sharp", "--shade", "phong", "--size", "256x256", "--threads", "2"};
    sim_scene_t s;
    CHECK_MSG(load_scene(&s, 9, argv, err, sizeof err) == 0, "%s: %s", volume, err);
    sim_diff_t d[2];
    for (int m = 0; m < 2; m++) {
        s.params.mode = m ? VF_MODE_PREINT1 : VF_MODE_POINT;
        if (compare(&s, 1, &d[m], err, sizeof err)) {
            sim_scene_free(&s);
            CHECK_MSG(0, "%s: %s", volume, err);
        }
    }
    sim_scene_free(&s);
    printf("# lit truth %s sharp 30,20: point %.2f dB, preint1 %.2f dB (%+.2f dB)\n", volume, d[0].psnr_db,
           d[1].psnr_db, d[1].psnr_db - d[0].psnr_db);
    CHECK_MSG(d[1].psnr_db > d[0].psnr_db, "%s: lit preint1 %.2f dB from the truth, lit point %.2f dB", volume,
              d[1].psnr_db, d[0].psnr_db);
}

static void truth_ml41(void)
{
    truth_case("phantom:marschner-lobb:41");
}

static void truth_shared(const char *file)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", data_dir(), file);
    truth_case(path);
}
static void truth_neghip(void)
{
    truth_shared("neghip.nhdr");
}
static void truth_engine(void)
{
    truth_shared("engine.nhdr");
}
static void truth_bucky(void)
{
    truth_shared("bucky.nhdr");
}

/* ---- the reference's parts ----------------------------------------------------------------------------- */

/* A default lighting for raw 8-bit voxels. */
static ref_lighting_t lighting_of(const void *raw, double ka, double kd, double ks)
{
    ref_lighting_t l;
    memset(&l, 0, sizeof l);
    l.shade = 1;
    l.light_count = 1;
    l.ka = ka, l.kd = kd, l.ks = ks;
    l.shininess = 10;
    l.normal_bits = 14;
    l.shade_lookup = REF_LOOKUP_BILINEAR;
    l.raw = raw;
    l.raw_type = REF_VOXEL_U8;
    return l;
}

/* One hot voxel in a 5^3 volume: its neighbours' central differences and codes, the magnitudes' scale. */
static void normals_of_a_volume(void)
{
    uint8_t v[125] = {0};
    v[2 + 5 * 2 + 25 * 2] = 100; /* the centre */
    ref_volume_t vol = {{5, 5, 5}, {1, 1, 1}, v};
    int32_t codes[125];
    uint8_t mag[125];
    CHECK_EQ(ref_normals(&vol, v, REF_VOXEL_U8, 14, codes, mag), 0);
    const int L = ref_normal_levels(14), half = (L - 1) / 2;
    CHECK_EQ(L, 127);
    /* the centre has no gradient: code L^2, magnitude 0; its neighbour at +x has D_x = 0 - 100 over 2 steps, so
     * the gradient is (-100 2^13, 0, 0): the code of -x, and the largest magnitude (gm 255) */
    CHECK_EQ(codes[62], L * L);
    CHECK_EQ(mag[62], 0);
    CHECK_EQ(codes[63], half * L);
    CHECK_EQ(mag[63], 255);
    CHECK_EQ(codes[61], half * L + L - 1); /* -x neighbour: +x */
    CHECK_EQ(codes[62 + 25], (L - 1) * L + L - 1); /* +z neighbour: -z, folded onto the map's corner */
    int64_t G[3];
    ref_gradient(&vol, v, REF_VOXEL_U8, 2, 2, 3, G, NULL);
    CHECK(G[0] == 0 && G[1] == 0 && G[2] == -100 * 8192);
    CHECK_EQ(ref_gradient_most(&vol, v, REF_VOXEL_U8), 100 * 8192);
    double n[3];
    ref_normal_decode(half * L + half, L, n);
    CHECK(n[0] == 0 && n[1] == 0 && n[2] == 1);
    ref_normal_decode((L - 1) * L + L - 1, L, n);
    CHECK(n[0] == 0 && n[1] == 0 && n[2] == -1);
    /* an anisotropic spacing scales each axis: q = round(2^14 / (c sp_a / sp_min)) */
    ref_volume_t wide = {{5, 5, 5}, {2, 1, 1}, v};
    ref_gradient(&wide, v, REF_VOXEL_U8, 3, 2, 2, G, NULL);
    CHECK_EQ(G[0], -100 * 4096);
}

/* -z folds onto the corners: every code of the lower hemisphere decodes to n_z <= 0, and the code of a
 * gradient is the same for any positive multiple of it. */
static void codes_fold(void)
{
    uint32_t seed = 7;
    const int L = ref_normal_levels(10);
    for (int t = 0; t < 5000; t++) {
        int64_t G[3], K[3];
        for (int a = 0; a < 3; a++) {
            seed = seed * 1664525u + 1013904223u;
            G[a] = (int64_t)(seed >> 20) - 2048;
            K[a] = G[a] * 7;
        }
        const int code = ref_normal_code(G, L);
        CHECK_EQ(code, ref_normal_code(K, L));
        double n[3];
        ref_normal_decode(code, L, n);
        CHECK_MSG(G[2] >= 0 || n[2] <= 1e-12, "gradient z %lld decodes to n_z %g", (long long)G[2], n[2]);
        CHECK_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1, 1e-12);
    }
}

/* The shade of a normal: facing the headlight, turned round when it faces away, ambient without one; two lights
 * add; the gradient factor's ramp. */
static void shade_of_a_normal(void)
{
    uint8_t raw[8] = {0};
    ref_lighting_t l = lighting_of(raw, 0.1, 0.7, 0.2);
    const double R[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    ref_lights_t lights;
    CHECK_EQ(ref_lights_init(&lights, &l, R), 0);
    double d, s;
    const double toward[3] = {0, 0, -1}, away[3] = {0, 0, 1}, none[3] = {0, 0, 0}, side[3] = {1, 0, 0};
    ref_shade_normal(&lights, toward, &d, &s);
    CHECK_NEAR(d, 0.8, 1e-15);
    CHECK_NEAR(s, 0.2, 1e-15);
    ref_shade_normal(&lights, away, &d, &s); /* two-sided */
    CHECK_NEAR(d, 0.8, 1e-15);
    ref_shade_normal(&lights, none, &d, &s);
    CHECK(d == 0.1 && s == 0);
    ref_shade_normal(&lights, side, &d, &s);
    CHECK_NEAR(d, 0.1, 1e-15);
    /* a light from 45 degrees right: diffuse cos 45, the half vector at 22.5 degrees */
    l.light_azimuth[0] = 65536 / 8;
    CHECK_EQ(ref_lights_init(&lights, &l, R), 0);
    ref_shade_normal(&lights, toward, &d, &s);
    CHECK_NEAR(d, 0.1 + 0.7 * cos(M_PI / 4), 1e-12);
    CHECK_NEAR(s, 0.2 * pow(cos(M_PI / 8), 10), 1e-12);
    l.light_count = 2; /* the second a headlight */
    CHECK_EQ(ref_lights_init(&lights, &l, R), 0);
    ref_shade_normal(&lights, toward, &d, &s);
    CHECK_NEAR(d, 0.1 + 0.7 * (1 + cos(M_PI / 4)), 1e-12);
    l.shade = 0;
    ref_shade_normal(&lights, toward, &d, &s);
    CHECK(d == 1 && s == 0);
    l.gradient_lo = 10, l.gradient_hi = 30;
    CHECK(ref_gradient_factor(&l, 5) == 0 && ref_gradient_factor(&l, 20) == 0.5 && ref_gradient_factor(&l, 40) == 1);
    l.gradient_lo = l.gradient_hi = 0;
    CHECK(ref_gradient_factor(&l, 0) == 1);
    l.shininess = 0;
    CHECK_EQ(ref_lights_init(&lights, &l, R), -1);
}

/* t(x) and a uniform slab's front-weighted values in closed form: S_f = alpha (1 - t(x)) = 1 - (1 - exp(-x)) / x,
 * the integral of (1 - u) x exp(-x u) over the slab. */
static void front_weighted_closed_form(void)
{
    CHECK_NEAR(ref_mean_depth(0), 0.5, 0);
    for (double x = 1e-6; x < 40; x *= 1.7) {
        const double alpha = -expm1(-x), sf = alpha * (1 - ref_mean_depth(x)), exact = 1 + expm1(-x) / x;
        CHECK_NEAR(sf, exact, 1e-14);
    }
    /* a constant transfer function: every entry is the uniform slab */
    ref_tf_point_t tf[1] = {{0, 0.25, 0.5, 1, 0.3}};
    const int N = 8;
    double lit[4 * 64], plain[4 * 64];
    CHECK_EQ(ref_lit_table(tf, 1, N, 2.0, lit), 0);
    CHECK_EQ(ref_preint_table(tf, 1, N, 2.0, plain), 0);
    const double x = -log1p(-0.3) * 2, sf = 1 + expm1(-x) / x;
    for (int e = 0; e < N * N; e++) {
        CHECK_NEAR(lit[4 * e], sf, 1e-13);
        CHECK_NEAR(lit[4 * e + 3], sf, 1e-13);        /* blue 1 */
        CHECK_NEAR(lit[4 * e + 1], 0.25 * sf, 1e-13); /* red 0.25 */
        CHECK(lit[4 * e] <= plain[4 * e] && lit[4 * e + 1] <= plain[4 * e + 1] + 1e-15);
    }
}

/* The reference's front-weighted table against the core's (vf_table_preint_lit): within 1 LSB of Q1.15 on a
 * transfer function with steps, ramps and colour. */
static void front_weighted_against_core(void)
{
    const uint32_t n = 64;
    vf_tf_point_t pts[6] = {{0, 0, 0, 0, 0},          {60 * 256, 65535, 0, 0, 0},     {90 * 256, 65535, 30000, 0, 50000},
                            {90 * 256, 0, 65535, 0, 9000}, {200 * 256, 0, 0, 65535, 60000}, {255 * 256, 65535, 65535, 65535, 0}};
    vf_tf_t tf = {pts, 6};
    ref_tf_point_t rtf[6];
    for (int p = 0; p < 6; p++)
        rtf[p] = (ref_tf_point_t){pts[p].scalar_q8 / 256.0, pts[p].r / 65535.0, pts[p].g / 65535.0,
                                  pts[p].b / 65535.0, pts[p].a / 65535.0};
    size_t bytes = vf_table_scratch_bytes(n);
    void *scratch = malloc(bytes);
    uint16_t *plain = malloc(n * n * 8), *lit = malloc(n * n * 8);
    double *ref = malloc(sizeof(double) * 4 * n * n);
    CHECK(scratch && plain && lit && ref);
    vf_arena_t arena;
    vf_arena_init(&arena, scratch, bytes);
    const double slabs[3] = {0.5, 1.0, 1.7};
    double worst = 0;
    for (int k = 0; k < 3; k++) {
        const uint32_t slab_q16 = (uint32_t)lround(slabs[k] * 65536);
        CHECK_EQ(vf_table_preint_lit(&tf, n, slab_q16, VF_BUILDER_INCREMENTAL, &arena, plain, lit), VF_OK);
        CHECK_EQ(ref_lit_table(rtf, 6, (int)n, slab_q16 / 65536.0, ref), 0);
        for (size_t e = 0; e < (size_t)n * n; e++)
            for (int c = 0; c < 4; c++) { /* the core's r, g, b, S_f; the reference's S_f, r, g, b */
                const double lsb = fabs(lit[4 * e + c] / 32768.0 - ref[4 * e + (c + 1) % 4]) * 32768;
                if (lsb > worst) /* not fmax: aarch64 gcc 12 fails (an internal error) vectorising that reduction */
                    worst = lsb;
            }
    }
    free(scratch);
    free(plain);
    free(lit);
    free(ref);
    printf("# front-weighted table: the core within %.3f LSB of the reference\n", worst);
    CHECK_MSG(worst <= 1, "%.3f LSB", worst);
}

/* ---- wiring -------------------------------------------------------------------------------------------- */

static int blob(int x, int y, int z)
{
    const double r = sqrt((x - 7.5) * (x - 7.5) + (y - 6.0) * (y - 6.0) + (z - 8.5) * (z - 8.5));
    return (int)fmax(0, 250 - 22 * r);
}

/* A material of ka 1, kd 0, ks 0 makes L_d = 1 and L_s = 0 everywhere: the reference's lit frames are its unlit
 * ones in every mode and lookup (to 1e-12: section 7's clamp of C to a catches the last bit of a white entry's
 * colour weight, which double rounding can put a hair above 1), and the truth's to the bit. (Not with the lut
 * correction, whose colour factor, interpolated apart from the opacity's, takes C above a, where the clamp
 * holds it.) */
static double largest_difference(const double *a, const double *b, size_t n)
{
    double most = 0;
    for (size_t i = 0; i < n; i++)
        most = fmax(most, fabs(a[i] - b[i]));
    return most;
}

static void neutral_material_is_unlit(void)
{
    const int dims[3] = {16, 13, 18};
    uint8_t *v = malloc(16 * 13 * 18);
    CHECK(v);
    for (int z = 0; z < 18; z++)
        for (int y = 0; y < 13; y++)
            for (int x = 0; x < 16; x++)
                v[(z * 13 + y) * 16 + x] = (uint8_t)blob(x, y, z);
    ref_volume_t vol = {{dims[0], dims[1], dims[2]}, {1, 1.25, 1}, v};
    ref_tf_point_t tf[4] = {{0, 1, 0.5, 0, 0}, {100, 1, 0.5, 0, 0.1}, {160, 0.2, 1, 0.4, 0.8}, {255, 1, 1, 1, 0.2}};
    ref_lighting_t l = lighting_of(v, 1, 0, 0);
    const ref_view_t view = {65536 / 12, 65536 / 18, 0, 1};
    double lit[40 * 40 * 3], unlit[40 * 40 * 3];
    for (int mode = 0; mode < 3; mode++)
        for (int bilinear = 0; bilinear < 2; bilinear++) {
            ref_params_t p;
            memset(&p, 0, sizeof p);
            p.mode = (ref_mode_t)mode;
            p.table_size = 64;
            p.lookup = bilinear ? REF_LOOKUP_BILINEAR : REF_LOOKUP_NEAREST;
            p.table_bits = bilinear ? 8 : 16;
            CHECK_EQ(ref_render(&vol, tf, 4, &p, &view, 40, 40, unlit, NULL), 0);
            p.lighting = &l;
            CHECK_EQ(ref_render(&vol, tf, 4, &p, &view, 40, 40, lit, NULL), 0);
            const double most = largest_difference(lit, unlit, 40 * 40 * 3);
            CHECK_MSG(most <= 1e-12, "mode %d, bilinear %d: lit differs from unlit by %g", mode, bilinear, most);
        }
    const double bg[3] = {0.1, 0.2, 0.3};
    CHECK_EQ(truth_render(&vol, tf, 4, bg, &view, 40, 40, 1, unlit), 0);
    CHECK_EQ(truth_render_lit(&vol, tf, 4, bg, &view, 40, 40, 1, NULL, &l, lit), 0);
    CHECK_MSG(memcmp(lit, unlit, sizeof lit) == 0, "the truth: lit differs from unlit");
    /* partial slabs refuse lighting */
    ref_params_t p;
    memset(&p, 0, sizeof p);
    p.mode = REF_MODE_PREINT1;
    p.table_size = 64;
    p.partial_slabs = 1;
    p.lighting = &l;
    CHECK_EQ(ref_render(&vol, tf, 4, &p, &view, 40, 40, lit, NULL), -1);
    free(v);
}

/* The lit truth of a sphere under the headlight: its middle (facing the light) brighter than near its rim; the
 * gradient-opacity ramp takes light away, the more the higher it starts. */
static void truth_sphere(void)
{
    const int n = 24;
    uint8_t *v = malloc((size_t)n * n * n);
    CHECK(v);
    for (int z = 0; z < n; z++)
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++) {
                const double r = sqrt((x - 11.5) * (x - 11.5) + (y - 11.5) * (y - 11.5) + (z - 11.5) * (z - 11.5));
                v[(z * n + y) * n + x] = (uint8_t)fmin(255, fmax(0, 128 + 40 * (8 - r)));
            }
    ref_volume_t vol = {{n, n, n}, {1, 1, 1}, v};
    ref_tf_point_t tf[3] = {{0, 1, 1, 1, 0}, {120, 1, 1, 1, 0}, {136, 1, 1, 1, 1}};
    ref_lighting_t l = lighting_of(v, 0.1, 0.9, 0);
    const ref_view_t view = {0, 0, 0, 1};
    const int w = 41;
    double rgb[41 * 41 * 3];
    const double bg[3] = {0, 0, 0};
    CHECK_EQ(truth_render_lit(&vol, tf, 3, bg, &view, w, w, 2, NULL, &l, rgb), 0);
    /* the sphere's radius 8 of the diagonal 23 sqrt(3) spans 41 * 8 / 39.8 = 8.2 pixels */
    const double middle = rgb[3 * (20 * w + 20)], rim = rgb[3 * (20 * w + 27)];
    printf("# lit sphere: middle %.3f, near the rim %.3f\n", middle, rim);
    CHECK_MSG(middle > 0.9 && rim < 0.75 * middle, "middle %.3f, rim %.3f", middle, rim);
    l.shade = 0; /* unshaded, and translucent, so that only the gradient opacity changes the light */
    const ref_tf_point_t thin[3] = {{0, 1, 1, 1, 0}, {120, 1, 1, 1, 0}, {136, 1, 1, 1, 0.05}};
    double total[3] = {0, 0, 0};
    const int ramps[3][2] = {{0, 0}, {0, 255}, {200, 255}};
    for (int k = 0; k < 3; k++) {
        l.gradient_lo = ramps[k][0], l.gradient_hi = ramps[k][1];
        CHECK_EQ(truth_render_lit(&vol, thin, 3, bg, &view, w, w, 2, NULL, &l, rgb), 0);
        for (int i = 0; i < w * w * 3; i++)
            total[k] += rgb[i];
    }
    printf("# lit sphere, light in the image: no ramp %.1f, ramp 0,255 %.1f, ramp 200,255 %.1f\n", total[0],
           total[1], total[2]);
    CHECK(total[0] > total[1] && total[1] > total[2] && total[2] > 0);
    free(v);
}

static void have_data(void)
{
    struct stat st;
    CHECK_MSG(stat(data_dir(), &st) == 0, "the shared volumes are not at %s (set VOLFIX_DATA)", data_dir());
}

CHECK_CASES({"normals of a volume", normals_of_a_volume}, {"codes fold and scale", codes_fold},
            {"shade of a normal", shade_of_a_normal}, {"front-weighted values in closed form", front_weighted_closed_form},
            {"front-weighted table against the core", front_weighted_against_core},
            {"a neutral material lights nothing", neutral_material_is_unlit}, {"lit truth of a sphere", truth_sphere},
            {"shared volumes", have_data}, {"fixed vs double lit: engine", fixed_engine},
            {"fixed vs double lit: brainsmall", fixed_brainsmall}, {"fixed vs double lit: neghip", fixed_neghip},
            {"fixed vs double lit: cthead", fixed_cthead}, {"fixed vs double lit: headsq", fixed_headsq},
            {"lit preint1 closer to the truth: ml41", truth_ml41}, {"lit preint1 closer to the truth: neghip", truth_neghip},
            {"lit preint1 closer to the truth: engine", truth_engine},
            {"lit preint1 closer to the truth: bucky", truth_bucky});
CHECK_RUN("lighting")
