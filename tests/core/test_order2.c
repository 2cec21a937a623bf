/* SPDX-License-Identifier: MIT */
/*
 * test_order2.c: preint2's table (core/preint2.c) and frames (core/composite_order2.c), docs/algorithm.md section 8.
 *   - the table against the double reference's brute-force build (host-sim/ref/ref_order2.c: the pieces of its
 *     O(N^3) 2D table, each entry composited on its own) at N2 = 16, 32 and 64, N = 256 and 64, random transfer
 *     functions, several slab lengths: every value within 1 LSB of Q1.15 (the rounding's half, and the Q.30
 *     pieces' error, about an eighth of an LSB: preint2.c's header);
 *   - its lighting values against section 8 in double from section 7's pieces worked out here;
 *   - in parts, the whole table to the bit; mirrors share their opacity; every value at most 1.0;
 *   - on a line (the middle sample halfway) the order-1 entry for 2d, where the pieces' ends fall on entries;
 *   - frames: the general loops' pixels are the default's, 1, 2 and 4 threads give the same pixels, an odd slab
 *     count composites its last slab, and what preint2 does not take is refused.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "frame.h"
#include "ref/ref.h"
#include "scene_fixture.h"
#include "render/render_mt.h"
#include "io/volume.h"
#include "volfix.h"
#include "volfix_internal.h"

#define MAX_N2 64
#define MAX_N 256
#define K 16

static uint64_t seed = 0x2545F4914F6CDD1Du;
static vf_tf_point_t points[8];
static ref_tf_point_t ref_points[8];
static uint16_t table2[MAX_N2 * MAX_N2 * MAX_N2 * 4], other2[MAX_N2 * MAX_N2 * MAX_N2 * 4];
static uint16_t lit2[MAX_N2 * MAX_N2 * MAX_N2 * 8], other_lit2[MAX_N2 * MAX_N2 * MAX_N2 * 8];
static double want2[MAX_N2 * MAX_N2 * MAX_N2 * 4];
static uint16_t table1[MAX_N * MAX_N * 4];

/* A transfer function of 2..8 points: steps, narrow peaks and ramps, coloured, as the core and the reference get it. */
static vf_tf_t random_tf(uint32_t *count)
{
    uint32_t n = 2 + check_below(&seed, 7), s = check_below(&seed, 12000);
    for (uint32_t p = 0; p < n; p++) {
        s += p ? check_below(&seed, 3) == 0 ? 0 : check_below(&seed, 20000) : 0; /* a step now and then */
        const uint16_t a = check_below(&seed, 3) == 0 ? 0 : (uint16_t)check_below(&seed, 65536);
        points[p] = (vf_tf_point_t){(uint16_t)(s > 65280 ? 65280 : s), (uint16_t)check_below(&seed, 65536),
                                    (uint16_t)check_below(&seed, 65536), (uint16_t)check_below(&seed, 65536), a};
        ref_points[p] = (ref_tf_point_t){points[p].scalar_q8 / 256.0, points[p].r / 65535.0, points[p].g / 65535.0,
                                         points[p].b / 65535.0, points[p].a / 65535.0};
    }
    *count = n;
    return (vf_tf_t){points, n};
}

static void *scratch_for(uint32_t n, bool lit, vf_arena_t *arena)
{
    const size_t bytes = vf_table2_scratch_bytes(n, lit);
    void *buf = malloc(bytes);
    vf_arena_init(arena, buf, bytes);
    return buf;
}

/* The largest difference of a Q1.15 (bits 16) or 8-bit table from double values (a, r, g, b as the reference
 * stores them), in LSB of that format. */
static double worst_lsb(const uint16_t *got, const double *want, size_t entries, int bits)
{
    double worst = 0;
    for (size_t e = 0; e < entries; e++)
        for (int c = 0; c < 4; c++) {
            const double exact = want[e * 4 + (c + 1) % 4];
            const double d = bits == 8 ? fabs(((const uint8_t *)got)[e * 4 + c] - exact * 255)
                                       : fabs(got[e * 4 + c] - exact * 32768);
            worst = d > worst ? d : worst;
        }
    return worst;
}

static void table_against_double(void)
{
    static const struct {
        uint32_t n, n2;
    } sizes[] = {{256, 16}, {64, 16}, {256, 32}, {64, 32}, {256, 64}, {64, 64}};
    static const uint32_t slabs[] = {65536, 89759, 47800, 131072}; /* 1, 1.37, 0.73 and 2 voxels */
    double worst = 0;
    for (size_t z = 0; z < sizeof sizes / sizeof sizes[0]; z++)
        for (int t = 0; t < (sizes[z].n2 == 64 ? 2 : 4); t++) {
            uint32_t count;
            const vf_tf_t tf = random_tf(&count);
            const uint32_t slab = slabs[(z + (size_t)t) % 4], n = sizes[z].n, n2 = sizes[z].n2;
            const size_t entries = (size_t)n2 * n2 * n2;
            vf_arena_t arena;
            void *buf = scratch_for(n, false, &arena);
            CHECK_EQ(vf_table_order2(&tf, n, n2, slab, 0, 1, &arena, table2, NULL), VF_OK);
            free(buf);
            CHECK_EQ(ref_order2_table(ref_points, (int)count, (int)n, (int)n2, slab / 65536.0, want2), 0);
            const double w = worst_lsb(table2, want2, entries, 16);
            CHECK_MSG(w <= 1.0, "N %u, N2 %u, slab %u: %.3f LSB from the double build", n, n2, slab, w);
            worst = w > worst ? w : worst;
        }
    printf("# order-2 tables against the double build: at most %.3f LSB of Q1.15\n", worst);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Lighting: section 7's front-weighted pieces in double, then section 8's W_f and W_b. */

static double mean_depth(double x)
{
    return x < 1e-6 ? 0.5 - x / 12 : 1 / x - exp(-x) / -expm1(-x);
}

/* Section 7's entry (f, b) of length L: a, C[3], D_f[3], S_f. */
static void lit_piece(const double *tau, const double *rgb, int f, int b, double L, double out[8])
{
    const int r = abs(b - f);
    double T = 1, A = 0, C[3] = {0, 0, 0}, D[3] = {0, 0, 0}, S = 0;
    for (int k = 0; k < (r ? r : 1); k++) {
        double x, w[3];
        if (r == 0) {
            x = tau[f] * L;
            for (int c = 0; c < 3; c++)
                w[c] = rgb[3 * f + c];
        } else {
            const int m = f < b ? f + k : f - 1 - k;
            const double t0 = tau[m], t1 = tau[m + 1];
            x = (t0 + t1) / 2 * L / r;
            for (int c = 0; c < 3; c++) {
                const double c0 = rgb[3 * m + c], c1 = rgb[3 * (m + 1) + c];
                w[c] = t0 + t1 == 0 ? (c0 + c1) / 2 : (2 * t0 * c0 + t0 * c1 + t1 * c0 + 2 * t1 * c1) / (3 * (t0 + t1));
            }
        }
        const double alpha = -expm1(-x), theta = (k + mean_depth(x)) / (r ? r : 1);
        for (int c = 0; c < 3; c++) {
            C[c] += T * w[c] * alpha;
            D[c] += T * w[c] * alpha * (1 - theta);
        }
        A += T * alpha;
        S += T * alpha * (1 - theta);
        T *= 1 - alpha;
    }
    out[0] = A;
    for (int c = 0; c < 3; c++)
        out[1 + c] = C[c], out[4 + c] = D[c];
    out[7] = S;
}

static void lit_against_double(void)
{
    const uint32_t n = 64, n2 = 16, slab = 78000;
    uint32_t count;
    const vf_tf_t tf = random_tf(&count);
    vf_arena_t arena;
    void *buf = scratch_for(n, true, &arena);
    CHECK_EQ(vf_table_order2(&tf, n, n2, slab, 0, 1, &arena, table2, lit2), VF_OK);
    free(buf);
    static double tau[MAX_N], rgb[3 * MAX_N], pieces[MAX_N * MAX_N * 8];
    CHECK_EQ(ref_classify(ref_points, (int)count, (int)n, tau, rgb), 0);
    const double d = slab / 65536.0;
    for (int f = 0; f < (int)n; f++)
        for (int b = 0; b < (int)n; b++)
            lit_piece(tau, rgb, f, b, 2 * d / K, pieces + 8 * ((size_t)f * n + b));
    double worst = 0;
    for (int f = 0; f < (int)n2; f++)
        for (int m = 0; m < (int)n2; m++)
            for (int b = 0; b < (int)n2; b++) {
                int end[K + 1];
                ref_order2_ends((int)n, (int)n2, f, m, b, end);
                double T = 1, W[2][4] = {{0}};
                for (int i = 0; i < K; i++) {
                    const double *p = pieces + 8 * ((size_t)end[i] * n + end[i + 1]);
                    const double t0 = i / 16.0, t1 = (i + 1) / 16.0;
                    const double phi[2][2] = {{fmax(0, 1 - 2 * t0), fmax(0, 1 - 2 * t1)},
                                              {fmax(0, 2 * t0 - 1), fmax(0, 2 * t1 - 1)}};
                    for (int h = 0; h < 2; h++) {
                        for (int c = 0; c < 3; c++)
                            W[h][c] += T * (phi[h][0] * p[4 + c] + phi[h][1] * (p[1 + c] - p[4 + c]));
                        W[h][3] += T * (phi[h][0] * p[7] + phi[h][1] * (p[0] - p[7]));
                    }
                    T *= 1 - p[0];
                }
                const uint16_t *got = lit2 + 8 * (((size_t)f * n2 + m) * n2 + b);
                for (int h = 0; h < 2; h++)
                    for (int c = 0; c < 4; c++) {
                        const double e = fabs(got[4 * h + c] - W[h][c] * 32768);
                        worst = e > worst ? e : worst;
                    }
            }
    CHECK_MSG(worst <= 1.0, "lit values %.3f LSB from double", worst);
    printf("# order-2 lit values against double: at most %.3f LSB of Q1.15\n", worst);
}

/* ---------------------------------------------------------------------------------------------------------- */

/* Parts: every entry written by exactly one part, to the bit of the whole; more parts than fronts included. */
static void parts_equal_whole(void)
{
    static const uint32_t part_counts[] = {2, 3, 7, 20, 40};
    for (int lit = 0; lit < 2; lit++) {
        const uint32_t n = 48, n2 = 20;
        const size_t values = (size_t)n2 * n2 * n2 * 4;
        uint32_t count;
        const vf_tf_t tf = random_tf(&count);
        vf_arena_t arena;
        void *buf = scratch_for(n, lit, &arena);
        CHECK_EQ(vf_table_order2(&tf, n, n2, 70000, 0, 1, &arena, table2, lit ? lit2 : NULL), VF_OK);
        for (size_t k = 0; k < sizeof part_counts / sizeof part_counts[0]; k++) {
            memset(other2, 0xFF, values * 2); /* no entry has 0xFFFF */
            memset(other_lit2, 0xFF, values * 4);
            for (uint32_t part = 0; part < part_counts[k]; part++)
                CHECK_EQ(vf_table_order2(&tf, n, n2, 70000, part, part_counts[k], &arena, other2,
                                         lit ? other_lit2 : NULL),
                         VF_OK);
            CHECK(memcmp(table2, other2, values * 2) == 0);
            CHECK(!lit || memcmp(lit2, other_lit2, values * 4) == 0);
        }
        CHECK_EQ(vf_table_order2(&tf, n, n2, 70000, 3, 3, &arena, other2, NULL), VF_ERR_ARG);
        CHECK_EQ(vf_table_order2(&tf, n, 15, 70000, 0, 1, &arena, other2, NULL), VF_ERR_ARG);
        CHECK_EQ(vf_table_order2(&tf, n, 129, 70000, 0, 1, &arena, other2, NULL), VF_ERR_ARG);
        free(buf);
    }
}

/* Entry (f, m, b) and its mirror (b, m, f), the same curve from the other end, have the same opacity, to the bit;
 * no value exceeds 1.0; lit, W_f + W_b is at most C (and S_f' + S_b' at most a) but for one LSB of rounding each. */
static void mirrors_and_bounds(void)
{
    const uint32_t n = 256, n2 = 32;
    uint32_t count;
    const vf_tf_t tf = random_tf(&count);
    vf_arena_t arena;
    void *buf = scratch_for(n, true, &arena);
    CHECK_EQ(vf_table_order2(&tf, n, n2, 100000, 0, 1, &arena, table2, lit2), VF_OK);
    free(buf);
    for (uint32_t f = 0; f < n2; f++)
        for (uint32_t m = 0; m < n2; m++)
            for (uint32_t b = 0; b < n2; b++) {
                const size_t e = ((size_t)f * n2 + m) * n2 + b, mirror = ((size_t)b * n2 + m) * n2 + f;
                CHECK_EQ(table2[e * 4 + 3], table2[mirror * 4 + 3]);
                for (int c = 0; c < 4; c++) {
                    CHECK(table2[e * 4 + c] <= 32768);
                    CHECK(lit2[e * 8 + c] + lit2[e * 8 + 4 + c] <= table2[e * 4 + (c < 3 ? c : 3)] + 1);
                }
            }
}

/* On a line, the middle sample halfway between the others, the curve is a line and each piece joins two points on
 * it: with N = 256 and N2 = 52 the entries' scalars are 5 e, and when b - f is a multiple of 16 every piece's ends
 * are entries, each piece crosses |b - f| / 16 intervals of length 2d / |b - f|, and the entry is section 2's
 * order-1 entry (5f, 5b) for 2d, exactly: the two tables agree within their roundings. Elsewhere on a line the
 * pieces' ends are rounded to entries and the two differ by a little: at most 2% of opacity here. */
static void line_is_order1(void)
{
    const uint32_t n = 256, n2 = 52, slab = 81000;
    uint32_t count;
    vf_tf_t tf = random_tf(&count);
    vf_arena_t arena;
    void *buf = scratch_for(n, false, &arena);
    CHECK_EQ(vf_table_order2(&tf, n, n2, slab, 0, 1, &arena, table2, NULL), VF_OK);
    CHECK_EQ(vf_table_preint(&tf, n, 2 * slab, VF_BUILDER_INCREMENTAL, &arena, table1), VF_OK);
    free(buf);
    int exact = 0, worst_aligned = 0, worst_other = 0;
    for (uint32_t f = 0; f < n2; f++)
        for (uint32_t b = f % 2; b < n2; b += 2) {
            const uint32_t m = (f + b) / 2;
            const uint16_t *e2 = table2 + (((size_t)f * n2 + m) * n2 + b) * 4;
            const uint16_t *e1 = table1 + ((size_t)(5 * f) * n + 5 * b) * 4;
            const bool aligned = (f > b ? f - b : b - f) % 16 == 0;
            for (int c = 0; c < 4; c++) {
                const int d = abs((int)e2[c] - (int)e1[c]);
                if (aligned)
                    worst_aligned = d > worst_aligned ? d : worst_aligned;
                else
                    worst_other = d > worst_other ? d : worst_other;
            }
            exact += aligned;
        }
    CHECK(exact >= 52 + 2 * 36 + 2 * 20 + 2 * 4); /* f = b, and |b - f| = 16, 32, 48 */
    CHECK_MSG(worst_aligned <= 1, "aligned lines %d LSB from the order-1 entry", worst_aligned);
    CHECK_MSG(worst_other <= 655, "other lines %d LSB from the order-1 entry", worst_other);
    printf("# lines: %d LSB from order 1 where the pieces' ends are entries, %d elsewhere\n", worst_aligned,
           worst_other);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Frames. */

#define MAXD 20
static uint8_t vox[MAXD * MAXD * MAXD];
static _Alignas(16) unsigned char arena_buf[2][1 << 24];
static _Alignas(16) unsigned char scratch[1 << 21];

/* A blob in noise of random size (each side 5..19, so that both slab counts come up). */
static vf_volume_t random_volume(void)
{
    uint32_t n[3];
    for (int a = 0; a < 3; a++)
        n[a] = 5 + check_below(&seed, MAXD - 5);
    const int cx = (int)check_below(&seed, n[0]), cy = (int)check_below(&seed, n[1]), cz = (int)check_below(&seed, n[2]);
    for (uint32_t z = 0; z < n[2]; z++)
        for (uint32_t y = 0; y < n[1]; y++)
            for (uint32_t x = 0; x < n[0]; x++) {
                const int d2 = ((int)x - cx) * ((int)x - cx) + ((int)y - cy) * ((int)y - cy) + ((int)z - cz) * ((int)z - cz);
                vox[((size_t)z * n[1] + y) * n[0] + x] =
                    (uint8_t)(check_below(&seed, 9) == 0 ? check_below(&seed, 256) : (d2 < 16 ? 170 : 30) + check_below(&seed, 60));
            }
    return (vf_volume_t){{n[0], n[1], n[2]}, {65536, 65536, 65536 + 30000 * check_below(&seed, 2)}, VF_VOXEL_U8, vox};
}

/* The defaults in preint2. */
static vf_params_t preint2_params(void)
{
    vf_params_t p;
    vf_params_default(&p);
    p.mode = VF_MODE_PREINT2;
    return p;
}

/* A frame's intermediate image (copied into out), with the general loops or not, lit or not. */
static vf_status_t frame(int k, const vf_params_t *p, const vf_volume_t *vol, const vf_tf_t *tf, bool lit,
                         const vf_view_t *view, bool general, uint16_t *out, size_t *values, uint32_t *nk)
{
    vf_arena_t arena;
    vf_renderer_t *r;
    vf_status_t s = scene_renderer(&r, &arena, arena_buf[k], sizeof arena_buf[k], p, vol, tf);
    if (s == VF_OK && p->lighting) { /* a light from the right and, every other frame, gradient opacity */
        vf_lighting_t l;
        vf_lighting_default(&l);
        l.lights[0].azimuth = 5000;
        l.gradient_hi = vol->dims[0] % 2 ? 120 : 0;
        s = vf_renderer_set_lighting(r, lit ? &l : NULL);
    }
    vfi_renderer_general_loops(r, general);
    if (s == VF_OK)
        s = begin_frame(r, view, 40, 40, 0, !general);
    if (s == VF_OK)
        s = vf_renderer_composite_band(r, 0, vf_renderer_factor(r)->int_h, scratch, sizeof scratch);
    if (s == VF_OK) {
        const vf_factor_t *f = vf_renderer_factor(r);
        *values = (size_t)f->int_w * f->int_h * 4;
        *nk = f->nk;
        memcpy(out, vfi_renderer_intermediate(r), *values * sizeof *out);
    }
    return s;
}

static uint16_t inter[2][64 * 64 * 16 * 16 * 4];

/* The general loops against the default's (whose last slab of an odd count is preint1's plain loop), unlit and lit,
 * both buffers, nearest and trilinear, the lut; to the bit. */
static void general_equals_default(void)
{
    int odd = 0, even = 0;
    for (int n = 0; n < 40; n++) {
        const vf_volume_t vol = random_volume();
        uint32_t count;
        const vf_tf_t tf = random_tf(&count);
        vf_params_t p = preint2_params();
        p.table_size = n % 3 ? 256 : 100;
        p.table2_size = 16 + check_below(&seed, 40);
        p.buffer = n % 2 ? VF_BUFFER_IMAGE : VF_BUFFER_SLICE;
        p.lookup = n % 5 == 4 ? VF_LOOKUP_TRILINEAR : VF_LOOKUP_NEAREST;
        p.correction = n % 7 == 6 ? VF_CORRECTION_LUT : VF_CORRECTION_REBUILD;
        p.lighting = n % 4 == 3;
        const vf_view_t view = {(int32_t)check_below(&seed, 65536), (int32_t)check_below(&seed, 65536) - 32768, 0,
                                65536};
        size_t v0, v1;
        uint32_t nk;
        CHECK_EQ(frame(0, &p, &vol, &tf, p.lighting, &view, false, inter[0], &v0, &nk), VF_OK);
        CHECK_EQ(frame(1, &p, &vol, &tf, p.lighting, &view, true, inter[1], &v1, &nk), VF_OK);
        CHECK_EQ(v0, v1);
        CHECK_MSG(memcmp(inter[0], inter[1], v0 * sizeof inter[0][0]) == 0, "case %d", n);
        *(nk % 2 ? &even : &odd) += 1; /* n_k - 1 slabs */
    }
    CHECK(odd > 5 && even > 5);
}

/* 1, 2 and 4 threads (bands and the table in parts, port/render/render_mt.c): the same pixels, and a draw's. */
static void threads_identical(void)
{
    static unsigned char px[4][64 * 48 * 3];
    for (int n = 0; n < 6; n++) {
        const vf_volume_t vol = random_volume();
        uint32_t count;
        const vf_tf_t tf = random_tf(&count);
        vf_params_t p = preint2_params();
        p.table2_size = 24 + 8 * (uint32_t)n;
        p.lighting = n % 2 == 1;
        p.correction = n == 4 ? VF_CORRECTION_LUT : VF_CORRECTION_REBUILD;
        const vf_view_t view = {(int32_t)check_below(&seed, 65536), (int32_t)check_below(&seed, 30000), 0, 65536};
        static const int threads[3] = {1, 2, 4};
        for (int t = 0; t < 3; t++) {
            vfp_render_t rr;
            char err[VFP_ERR_LEN];
            vf_image_t im = {px[t], 64, 48, 64 * 3, VF_FORMAT_RGB888};
            CHECK_MSG(vfp_render_open(&rr, &p, &vol, threads[t], err, sizeof err) == VFP_OK, "%s", err);
            CHECK(vfp_render_set_window(&rr, (vf_window_t){0, 255}, err, sizeof err) == VFP_OK);
            CHECK(vfp_render_set_tf(&rr, points, count, err, sizeof err) == VFP_OK);
            CHECK_MSG(vfp_render_frame(&rr, &view, &im, err, sizeof err) == VFP_OK, "%s", err);
            vfp_render_close(&rr);
        }
        vf_arena_t arena;
        vf_arena_init(&arena, arena_buf[0], sizeof arena_buf[0]);
        vf_renderer_t *r;
        vf_image_t im = {px[3], 64, 48, 64 * 3, VF_FORMAT_RGB888};
        CHECK_EQ(vf_renderer_create(&r, &p, &vol, &arena), VF_OK);
        CHECK_EQ(vf_renderer_set_window(r, (vf_window_t){0, 255}), VF_OK);
        CHECK_EQ(vf_renderer_set_tf(r, &tf), VF_OK);
        CHECK_EQ(vf_renderer_draw(r, &view, &im, scratch, sizeof scratch), VF_OK);
        CHECK(memcmp(px[0], px[1], sizeof px[0]) == 0);
        CHECK(memcmp(px[0], px[2], sizeof px[0]) == 0);
        CHECK(memcmp(px[0], px[3], sizeof px[0]) == 0);
    }
}

/* Material in the last two slices only: with an odd slab count (n_k even) the last slab is order 1 and draws it;
 * with an even count the last order-2 slab does. Looking along +z (slice 0 in front), both show it. */
static void last_slab_composited(void)
{
    for (uint32_t nz = 6; nz <= 9; nz++) {
        for (uint32_t i = 0; i < 8 * 8 * nz; i++)
            vox[i] = i / 64 >= nz - 2 ? 200 : 0;
        const vf_volume_t vol = {{8, 8, nz}, {65536, 65536, 65536}, VF_VOXEL_U8, vox};
        vf_tf_point_t pts[2] = {{0, 0, 0, 0, 0}, {255 * 256, 65535, 65535, 65535, 65535}};
        const vf_tf_t tf = {pts, 2};
        vf_params_t p = preint2_params();
        const vf_view_t view = {0, 0, 0, 65536};
        size_t values;
        uint32_t nk;
        CHECK_EQ(frame(0, &p, &vol, &tf, false, &view, false, inter[0], &values, &nk), VF_OK);
        CHECK_EQ(nk, nz);
        uint32_t most = 0;
        for (size_t k = 3; k < values; k += 4)
            most = inter[0][k] > most ? inter[0][k] : most;
        CHECK_MSG(most > 16384, "n_z %u: opacity %u", nz, most); /* a slab of 200s is nearly opaque */
    }
}

/* Lighting, frames: a sphere of opaque white, lit from the upper right. A lighting renderer's unlit frame is a plain
 * renderer's to the bit; lit, preint2 is preint1's picture within a few levels (both integrate the same lit
 * field, with lighting interpolated across slabs of one slice or two), brightest towards the light. */
#define SPHERE 24
static void lit_sphere(void)
{
    static uint8_t ball[SPHERE * SPHERE * SPHERE];
    for (int z = 0; z < SPHERE; z++)
        for (int y = 0; y < SPHERE; y++)
            for (int x = 0; x < SPHERE; x++) {
                const double d = sqrt((x - 11.5) * (x - 11.5) + (y - 11.5) * (y - 11.5) + (z - 11.5) * (z - 11.5));
                ball[(z * SPHERE + y) * SPHERE + x] = (uint8_t)(d < 9 ? 200 : d < 10 ? 200 - 200 * (d - 9) : 0);
            }
    const vf_volume_t vol = {{SPHERE, SPHERE, SPHERE}, {65536, 65536, 65536}, VF_VOXEL_U8, ball};
    static const vf_tf_point_t white[] = {{0, 65535, 65535, 65535, 0}, {100 << 8, 65535, 65535, 65535, 65535}};
    const vf_tf_t tf = {white, 2};
    vf_lighting_t l;
    vf_lighting_default(&l);
    l.lights[0].azimuth = 65536 / 8, l.lights[0].elevation = 65536 / 16; /* 45 degrees right, 22.5 up */
    static unsigned char px[4][64 * 64 * 3];
    const vf_view_t view = {1000, 700, 0, 65536};
    for (int k = 0; k < 4; k++) { /* preint2 plain, preint2 lighting renderer unlit, preint2 lit, preint1 lit */
        vf_params_t p;
        vf_params_default(&p);
        p.mode = k == 3 ? VF_MODE_PREINT1 : VF_MODE_PREINT2;
        p.lighting = k > 0;
        vf_arena_t arena;
        vf_renderer_t *r;
        CHECK_EQ(scene_renderer(&r, &arena, arena_buf[0], sizeof arena_buf[0], &p, &vol, &tf), VF_OK);
        if (p.lighting)
            CHECK_EQ(vf_renderer_set_lighting(r, k == 1 ? NULL : &l), VF_OK);
        const vf_image_t im = {px[k], 64, 64, 64 * 3, VF_FORMAT_RGB888};
        CHECK_EQ(vf_renderer_draw(r, &view, &im, scratch, sizeof scratch), VF_OK);
    }
    CHECK(memcmp(px[0], px[1], sizeof px[0]) == 0);
    int worst = 0;
    for (size_t k = 0; k < sizeof px[0]; k++) {
        const int d = abs((int)px[2][k] - (int)px[3][k]);
        worst = d > worst ? d : worst;
    }
    const unsigned char *lit_side = px[2] + (24 * 64 + 42) * 3, *dark_side = px[2] + (40 * 64 + 22) * 3;
    CHECK_MSG(lit_side[0] > dark_side[0] + 40, "towards the light %u, away from it %u", lit_side[0], dark_side[0]);
    CHECK_MSG(worst <= 12, "lit preint2 %d levels from lit preint1", worst);
    printf("# lit sphere: preint2 at most %d levels from preint1\n", worst);
}

/* What preint2 does not take: partial slabs (unsupported), bilinear lookups (its own is trilinear) and trilinear
 * elsewhere, tables outside 16..128. */
static void refused(void)
{
    const vf_volume_t vol = {{4, 4, 4}, {65536, 65536, 65536}, VF_VOXEL_U8, vox};
    vf_params_t p;
    vf_params_default(&p);
    CHECK_EQ(p.table2_size, VF_DEFAULT_TABLE2);
    CHECK_EQ(p.lookup, VF_LOOKUP_NEAREST);
    /* the defaults with each row's mode, partial slabs, lookup and 3D table size */
    static const struct {
        vf_mode_t mode;
        bool partial;
        vf_lookup_t lookup;
        uint32_t table2_size;
        vf_status_t want;
    } rows[] = {
        {VF_MODE_PREINT2, false, VF_LOOKUP_NEAREST, VF_DEFAULT_TABLE2, VF_OK},
        {VF_MODE_PREINT2, true, VF_LOOKUP_NEAREST, VF_DEFAULT_TABLE2, VF_ERR_UNSUPPORTED},
        {VF_MODE_PREINT2, false, VF_LOOKUP_BILINEAR, VF_DEFAULT_TABLE2, VF_ERR_ARG},
        {VF_MODE_PREINT2, false, VF_LOOKUP_TRILINEAR, VF_DEFAULT_TABLE2, VF_OK},
        {VF_MODE_PREINT1, false, VF_LOOKUP_TRILINEAR, VF_DEFAULT_TABLE2, VF_ERR_ARG},
        {VF_MODE_PREINT2, false, VF_LOOKUP_NEAREST, 15, VF_ERR_ARG},
        {VF_MODE_PREINT2, false, VF_LOOKUP_NEAREST, 129, VF_ERR_ARG},
        {VF_MODE_POINT, false, VF_LOOKUP_NEAREST, 0, VF_OK}, /* the 3D table's size is ignored by the other modes */
    };
    for (size_t n = 0; n < sizeof rows / sizeof rows[0]; n++) {
        vf_params_default(&p);
        p.mode = rows[n].mode;
        p.partial_slabs = rows[n].partial;
        p.lookup = rows[n].lookup;
        p.table2_size = rows[n].table2_size;
        size_t bytes;
        const vf_status_t got = vf_renderer_bytes(&p, &vol, &bytes);
        CHECK_MSG(got == rows[n].want, "row %zu (%s, partial %d, %s, %u): %s, want %s", n, vf_mode_name(p.mode),
                  (int)p.partial_slabs, vf_lookup_name(p.lookup), p.table2_size, vf_status_text(got),
                  vf_status_text(rows[n].want));
    }
    CHECK(strcmp(vf_mode_name(VF_MODE_PREINT2), "preint2") == 0);
    CHECK(strcmp(vf_lookup_name(VF_LOOKUP_TRILINEAR), "trilinear") == 0);
}

CHECK_CASES(CHECK_CASE(table_against_double), CHECK_CASE(lit_against_double), CHECK_CASE(parts_equal_whole),
            CHECK_CASE(mirrors_and_bounds), CHECK_CASE(line_is_order1), CHECK_CASE(general_equals_default),
            CHECK_CASE(threads_identical), CHECK_CASE(last_slab_composited), CHECK_CASE(lit_sphere),
            CHECK_CASE(refused));
CHECK_RUN("order2")
