/* SPDX-License-Identifier: MIT */
/*
 * test_lit_tables.c: the front-weighted (lit) pre-integrated tables (core/preint.c, core/tables.c) against
 * docs/algorithm.md section 7, written here again in double: D_f = sum_k T_k C_k (1 - theta_k) per channel and
 * S_f = sum_k T_k alpha_k (1 - theta_k), theta_k = (k + t(x_k)) / max(r, 1), t(x) = 1 / x - exp(-x) / (1 - exp(-x)).
 *
 * Bounds asserted (measured in the comments; VOLFIX_SHOW=1 prints them):
 *   alpha t(x)           vfi_emission_depth_q30 within 24 LSB of Q.30 of the double value for the core's own
 *                        exp(-x) above x = 1/16 (measured 14.0) and within 2 LSB below (measured 0.89)
 *   lit entries          incremental and brute force within 1 LSB of Q1.15 of the spec, every entry, both
 *                        triangles, N = 2 .. 256, slabs 0.3 .. 5 (measured 1 and 1; before the spec's rounding
 *                        0.506 and 0.503 LSB, 99.93% of the values the spec's rounded); r = 0 also against the
 *                        closed form S_f = 1 - (1 - exp(-x)) / x, D_f = c S_f
 *   incremental          within 1 LSB of the brute force (measured 1); in 8 bits and on the 10- and 12-bit
 *                        grids within a level of it (measured 1 of 255; 32 and 9 LSB of Q1.15, a level of each grid)
 *   8 bits, grids        every lit value within 0.51 of a level of the spec's exact value, as the main table's
 * and the exact properties: D_f <= C and S_f <= a in every entry and format; the main table the same to the bit
 * with the lit outputs asked for or not; parts (1, 2, 3, 7) and diagonals built on demand equal to the whole
 * build to the bit; a grey transfer function's lit table (one channel worked out) the three-channel one's to the bit;
 * the lit view table equal to the lut's correction of each entry; no value above 1.0 at the extremes (1024 entries
 * of opaque white, slabs from 1/1024 to 128).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arena.h"
#include "check.h"
#include "classify.h"
#include "segment.h"
#include "table_store.h"
#include "tables.h"
#include "tables_spec.h"

static uint64_t rng_state = 0x6A09E667F3BCC908u;
static uint32_t rnd(uint32_t n)
{
    return check_below(&rng_state, n);
}

static bool show(void)
{
    return getenv("VOLFIX_SHOW") != NULL;
}

#define MAX_N 1024

static _Alignas(16) unsigned char part_buf[7][1 << 17];
/* main and lit tables of up to 1024 entries, built two ways */
static uint16_t main_a[MAX_N * MAX_N * 4], lit_a[MAX_N * MAX_N * 4];
static uint16_t main_b[MAX_N * MAX_N * 4], lit_b[MAX_N * MAX_N * 4];

static vfi_table_out_t q15_out(uint16_t *table, uint16_t *lit)
{
    vfi_table_out_t out = {table, NULL, 0, lit, NULL, NULL, NULL};
    return out;
}

/* ---- the spec in double ------------------------------------------------------------------------------ */

/* t(x): the mean depth of a uniform piece's emission, in piece lengths, from the face it is entered by. */
static double mean_depth(double x)
{
    if (x < 1e-4)
        return 0.5 - x / 12 + x * x * x / 720;
    return 1 / x - 1 / expm1(x);
}

/* Entry (f, b) for slab length d: e[0..3] = C r, g, b and A (section 2), e[4..7] = D_f r, g, b and S_f
 * (section 7), the sums as written there. */
static void spec_entry(uint32_t f, uint32_t b, double d, double e[8])
{
    uint32_t r = f < b ? b - f : f - b, pieces = r ? r : 1;
    double L = d / pieces, T = 1;
    for (int c = 0; c < 8; c++)
        e[c] = 0;
    for (uint32_t k = 0; k < pieces; k++) {
        double x, w[3];
        if (r == 0) {
            x = spec.tau[f] * d;
            for (int c = 0; c < 3; c++)
                w[c] = spec.col[f][c];
        } else {
            uint32_t m = f < b ? f + k : f - 1 - k;
            double t0 = spec.tau[m], t1 = spec.tau[m + 1];
            x = L * (t0 + t1) / 2;
            for (int c = 0; c < 3; c++) {
                double c0 = spec.col[m][c], c1 = spec.col[m + 1][c];
                w[c] = t0 + t1 == 0 ? (c0 + c1) / 2
                                    : (2 * t0 * c0 + t0 * c1 + t1 * c0 + 2 * t1 * c1) / (3 * (t0 + t1));
            }
        }
        double alpha = -expm1(-x), theta = (k + mean_depth(x)) / pieces;
        for (int c = 0; c < 3; c++) {
            e[c] += T * w[c] * alpha;
            e[4 + c] += T * w[c] * alpha * (1 - theta);
        }
        e[3] += T * alpha;
        e[7] += T * alpha * (1 - theta);
        T *= exp(-x);
    }
}

static int lsb_diff(uint16_t got, double want)
{
    return abs((int)got - (int)lround(want * 32768));
}

/* ---- transfer functions ------------------------------------------------------------------------------ */

static vf_tf_point_t pts_buf[VF_MAX_TF_POINTS];

static vf_tf_t random_tf(bool grey)
{
    return spec_random_tf(pts_buf, grey, check_below, &rng_state);
}

/* ---- alpha t(x) -------------------------------------------------------------------------------------- */

/* vfi_emission_depth_q30 against alpha t(x) in double, for the core's own transmittance of x (so that the bound
 * is the function's, not the exponential's): x from 2^-28 to 1500 on a geometric grid, and densely around the
 * switch at 1/16. Also the exact cases: 0 for t = 1, at most (alpha + 1) / 2. */
static void emission_depth(void)
{
    double worst_series = 0, worst_division = 0;
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < 20000; i++) {
            uint64_t x_q28;
            if (pass == 0)
                x_q28 = (uint64_t)llround(pow(2.0, -28 + 39.0 * i / 19999) * 268435456.0);
            else
                x_q28 = (UINT64_C(1) << 24) - 10000 + (uint64_t)i;
            if (x_q28 == 0)
                x_q28 = 1;
            const uint32_t t = vfi_exp_neg_q28(x_q28), alpha = (UINT32_C(1) << 30) - t;
            const uint32_t g = vfi_emission_depth_q30(x_q28, t);
            const double x = x_q28 / 268435456.0, a = alpha / 1073741824.0;
            const double want = a * mean_depth(x) * 1073741824.0;
            const double err = fabs(g - want);
            CHECK_MSG(g <= (alpha + 1) / 2, "x %.9g: g %u above (alpha + 1) / 2, alpha %u", x, g, alpha);
            if (x_q28 < (UINT64_C(1) << 24))
                worst_series = fmax(worst_series, err);
            else
                worst_division = fmax(worst_division, err);
        }
    if (show())
        printf("# alpha t(x) against double: %.2f LSB of Q.30 below x = 1/16, %.2f above\n", worst_series,
               worst_division);
    CHECK(worst_series <= 2);
    CHECK(worst_division <= 24);
    CHECK_EQ(vfi_emission_depth_q30(0, UINT32_C(1) << 30), 0);
    CHECK_EQ(vfi_emission_depth_q30(3, UINT32_C(1) << 30), 0); /* a piece that changes no bit */
    /* past exp's range (t = 0): 1 / x */
    CHECK_NEAR(vfi_emission_depth_q30((uint64_t)1000 << 28, 0), 1073741824.0 / 1000, 1);
}

/* ---- tables against the spec ------------------------------------------------------------------------- */

typedef struct worst {
    int spec_incremental, spec_bruteforce, between;
    double unrounded[2]; /* the largest |value - 32768 x| of each builder, in LSB: 0.5 is exact rounding */
    long entries, exact[2];
} worst_t;

/* Build the main and lit tables of the classification with both builders, check them against the spec, each
 * other and the exact properties; fold the largest differences into *w. Returns 0 after a failure. */
static int check_lit_tables(fixture_t *fx, const vf_tf_t *tf, double d, bool bruteforce, worst_t *w)
{
    const uint32_t n = fx->cls.n;
    const uint32_t slab_q16 = (uint32_t)lround(d * 65536);
    d = slab_q16 / 65536.0; /* the spec table is for the same quantised length */
    spec_classify(tf, n);
    static uint16_t unlit[256 * 256 * 4];
    for (int builder = 0; builder < (bruteforce ? 2 : 1); builder++) {
        void (*build)(const vfi_classify_t *, uint32_t, const vfi_table_scratch_t *, vfi_table_out_t) =
            builder ? vfi_preint_table_bruteforce : vfi_preint_table_incremental;
        uint16_t *m = builder ? main_b : main_a;
        build(&fx->cls, slab_q16, &fx->scratch, q15_out(m, builder ? lit_b : lit_a));
        /* the main table is the same to the bit with the lit outputs asked for or not */
        if (n <= 256) {
            build(&fx->cls, slab_q16, &fx->scratch, q15_out(unlit, NULL));
            if (memcmp(unlit, m, (size_t)n * n * 4 * sizeof unlit[0]) != 0) {
                check_fail(__FILE__, __LINE__, "N %u d %g: the %s main table differs with the lit outputs asked for",
                           n, d, builder ? "brute force's" : "incremental");
                return 0;
            }
        }
    }
    for (uint32_t f = 0; f < n; f++)
        for (uint32_t b = 0; b < n; b++) {
            const size_t at = ((size_t)f * n + b) * 4;
            double e[8];
            spec_entry(f, b, d, e);
            for (int builder = 0; builder < (bruteforce ? 2 : 1); builder++) {
                const uint16_t *m = (builder ? main_b : main_a) + at, *l = (builder ? lit_b : lit_a) + at;
                int *worst = builder ? &w->spec_bruteforce : &w->spec_incremental;
                for (int c = 0; c < 4; c++) {
                    const int diff = lsb_diff(l[c], e[4 + c]);
                    *worst = diff > *worst ? diff : *worst;
                    w->unrounded[builder] = fmax(w->unrounded[builder], fabs(l[c] - e[4 + c] * 32768));
                    w->exact[builder] += diff == 0;
                    w->entries += builder == 0;
                    if (diff > 1 || l[c] > m[c]) {
                        check_fail(__FILE__, __LINE__,
                                   "N %u d %g %s entry (%u, %u) channel %d: lit %u, spec %.3f; main %u, spec %.3f", n,
                                   d, builder ? "brute force" : "incremental", f, b, c, l[c], e[4 + c] * 32768, m[c],
                                   e[c] * 32768);
                        return 0;
                    }
                }
            }
            if (bruteforce)
                for (int c = 0; c < 4; c++) {
                    const int diff = abs((int)lit_a[at + c] - (int)lit_b[at + c]);
                    w->between = diff > w->between ? diff : w->between;
                    if (diff > 1) {
                        check_fail(__FILE__, __LINE__, "N %u d %g entry (%u, %u) channel %d: incremental %u, brute %u",
                                   n, d, f, b, c, lit_a[at + c], lit_b[at + c]);
                        return 0;
                    }
                }
            if (f == b) { /* the closed form of the uniform slab */
                const double x = spec.tau[f] * d, s_f = x > 0 ? 1 + expm1(-x) / x : 0;
                for (int c = 0; c < 4; c++)
                    if (lsb_diff(lit_a[at + c], c < 3 ? spec.col[f][c] * s_f : s_f) > 1) {
                        check_fail(__FILE__, __LINE__, "N %u d %g entry %u channel %d: %u, closed form %.3f", n, d, f,
                                   c, lit_a[at + c], (c < 3 ? spec.col[f][c] * s_f : s_f) * 32768);
                        return 0;
                    }
            }
        }
    return 1;
}

static void lit_against_spec(void)
{
    static const struct {
        uint32_t n, tfs;
        bool bruteforce;
    } sizes[] = {{2, 40, true}, {3, 40, true}, {5, 30, true}, {16, 20, true}, {64, 8, true}, {256, 1, true},
                 {256, 2, false}};
    const double lengths[] = {0.3, 1.0, 1.7, 5.0};
    worst_t w = {0, 0, 0, {0, 0}, 0, {0, 0}};
    for (size_t sn = 0; sn < sizeof sizes / sizeof sizes[0]; sn++) {
        fixture_t fx;
        CHECK(fixture_init(&fx, sizes[sn].n, true));
        for (uint32_t t = 0; t < sizes[sn].tfs; t++)
            for (int grey = 0; grey < 2; grey++) {
                const vf_tf_t tf = random_tf(grey);
                CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
                /* at 256 entries one slab length a transfer function, taken in turn */
                for (size_t ln = 0; ln < 4; ln++) {
                    if (sizes[sn].n == 256 && ln != (t * 2 + (uint32_t)grey + (sizes[sn].bruteforce ? 0 : 1)) % 4)
                        continue;
                    if (!check_lit_tables(&fx, &tf, lengths[ln], sizes[sn].bruteforce, &w))
                        return;
                }
            }
    }
    if (show())
        printf("# lit tables against the spec: incremental %d, brute force %d LSB (%.4f and %.4f before the spec's "
               "rounding; %.3f%% of the incremental's values the spec's rounded, %ld values); between them %d\n",
               w.spec_incremental, w.spec_bruteforce, w.unrounded[0], w.unrounded[1],
               100.0 * (double)w.exact[0] / (double)w.entries, w.entries, w.between);
    CHECK(w.spec_incremental <= 1 && w.spec_bruteforce <= 1 && w.between <= 1);
}

/* Transfer functions that stress the moments: a constant one (every entry the uniform slab, whatever r), an
 * opaque white one (C = a), a single narrow peak in empty space (sparse blocks whose windows slide the peak
 * through every position) and a step. */
static void lit_special(void)
{
    vf_tf_point_t constant = {1234, 50000, 20000, 65535, 20000};
    vf_tf_point_t white = {0, 65535, 65535, 65535, 65535};
    vf_tf_point_t peak[3] = {{100 * 256, 0, 0, 0, 0}, {102 * 256, 65535, 30000, 0, 65535}, {104 * 256, 0, 0, 0, 0}};
    vf_tf_point_t step[2] = {{150 * 256, 0, 0, 65535, 100}, {150 * 256, 65535, 65535, 0, 65535}};
    const vf_tf_t tfs[] = {{&constant, 1}, {&white, 1}, {peak, 3}, {step, 2}};
    worst_t w = {0, 0, 0, {0, 0}, 0, {0, 0}};
    fixture_t fx;
    CHECK(fixture_init(&fx, 64, true));
    for (size_t t = 0; t < sizeof tfs / sizeof tfs[0]; t++) {
        CHECK_EQ(vfi_classify(&fx.cls, &tfs[t]), VF_OK);
        for (double d = 0.3; d < 6; d *= 2.3)
            if (!check_lit_tables(&fx, &tfs[t], d, true, &w))
                return;
    }
    CHECK(w.spec_incremental <= 1 && w.spec_bruteforce <= 1 && w.between <= 1);
}

/* A grey transfer function's lit table (preint.c works out one colour channel, block_dense_grey_lit): three equal
 * colours, and to the bit the lit table of the three-channel path, which a twin takes whose last interval's blue
 * weight is 1 LSB of Q.30 off (every entry (f, b) with f, b <= n - 3 reads only intervals the twin shares, as in
 * test_classify_tables.c). */
static void lit_grey_twin(void)
{
    const uint32_t sizes[] = {5, 64, 256};
    for (size_t sn = 0; sn < sizeof sizes / sizeof sizes[0]; sn++) {
        const uint32_t n = sizes[sn];
        fixture_t fx;
        CHECK(fixture_init(&fx, n, true));
        for (int t = 0; t < 4; t++) {
            const vf_tf_t tf = random_tf(true);
            CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
            const uint32_t slab_q16 = 30000 + rnd(300000);
            vfi_preint_table_incremental(&fx.cls, slab_q16, &fx.scratch, q15_out(main_a, lit_a));
            uint32_t *blue = &fx.cls.weight_q30[(n - 2) * 3 + 2];
            const uint32_t grey = *blue;
            *blue = grey > 0 ? grey - 1 : 1;
            vfi_preint_table_incremental(&fx.cls, slab_q16, &fx.scratch, q15_out(main_b, lit_b));
            *blue = grey;
            for (uint32_t f = 0; f < n; f++)
                for (uint32_t b = 0; b < n; b++) {
                    const uint16_t *l = lit_a + ((size_t)f * n + b) * 4, *twin = lit_b + ((size_t)f * n + b) * 4;
                    CHECK_MSG(l[1] == l[0] && l[2] == l[0], "N %u entry (%u, %u): lit colour %u %u %u", n, f, b, l[0],
                              l[1], l[2]);
                    CHECK_MSG(f + 3 > n || b + 3 > n || memcmp(l, twin, 8) == 0,
                              "N %u entry (%u, %u): grey path %u %u, three channels %u %u", n, f, b, l[0], l[3],
                              twin[0], twin[3]);
                }
        }
    }
}

/* ---- parts and diagonals on demand ------------------------------------------------------------------- */

/* The incremental builder in 1, 2, 3 and 7 parts (run in a shuffled order, each with its own scratch), and
 * block by block as compositing would ask for them (random entries, some asked twice): main and lit tables equal
 * to the whole build's, to the bit; an entry asked for is built, and its diagonal's other blocks are not. */
static void lit_parts_and_demand(void)
{
    const uint32_t sizes[] = {2, 7, 64, 255, 256};
    for (size_t sn = 0; sn < sizeof sizes / sizeof sizes[0]; sn++) {
        const uint32_t n = sizes[sn];
        const size_t values = (size_t)n * n * 4;
        fixture_t fx;
        CHECK(fixture_init(&fx, n, true));
        for (int t = 0; t < 3; t++) {
            const vf_tf_t tf = random_tf(t == 1);
            CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
            const uint32_t slab_q16 = 40000 + rnd(200000);
            vfi_preint_table_incremental(&fx.cls, slab_q16, &fx.scratch, q15_out(main_a, lit_a));
            const uint32_t part_counts[] = {1, 2, 3, 7};
            for (size_t pc = 0; pc < 4; pc++) {
                const uint32_t parts = part_counts[pc];
                uint32_t order[7];
                for (uint32_t p = 0; p < parts; p++)
                    order[p] = p;
                for (uint32_t p = parts; p > 1; p--) {
                    uint32_t k = rnd(p), x = order[p - 1];
                    order[p - 1] = order[k], order[k] = x;
                }
                memset(main_b, 0xA5, values * sizeof main_b[0]);
                memset(lit_b, 0xA5, values * sizeof lit_b[0]);
                for (uint32_t p = 0; p < parts; p++) {
                    vf_arena_t arena;
                    vfi_table_scratch_t ts;
                    vf_arena_init(&arena, part_buf[order[p]], sizeof part_buf[0]);
                    CHECK_EQ(vfi_table_scratch_alloc_lit(&ts, n, &arena), VF_OK);
                    vfi_preint_table_part(&fx.cls, slab_q16, &ts, q15_out(main_b, lit_b), order[p], parts);
                }
                CHECK_MSG(memcmp(main_a, main_b, values * sizeof main_a[0]) == 0, "N %u, %u parts: main tables differ",
                          n, parts);
                CHECK_MSG(memcmp(lit_a, lit_b, values * sizeof lit_a[0]) == 0, "N %u, %u parts: lit tables differ", n,
                          parts);
            }
            memset(lit_b, 0xA5, values * sizeof lit_b[0]);
            vfi_demand_t demand;
            vfi_preint_demand_begin(&demand, &fx.cls, slab_q16, &fx.scratch, q15_out(main_b, lit_b));
            for (uint32_t i = 0; i < n; i++) /* the diagonal itself, in begin */
                CHECK(memcmp(lit_b + ((size_t)i * n + i) * 4, lit_a + ((size_t)i * n + i) * 4, 8) == 0);
            for (uint32_t asked = 0; asked < 3 * n; asked++) {
                const uint32_t f = rnd(n), b = rnd(n);
                const uint16_t *e = main_b + ((size_t)f * n + b) * 4;
                if (f != b && e[0] == VFI_UNBUILT_Q15 && e[3] == 0) {
                    const uint32_t r = f < b ? b - f : f - b, lo = f < b ? f : b, s0 = lo - lo % r;
                    /* the first entry of the block after this one's, if this block is its diagonal's first built */
                    const uint32_t next = s0 + r + r < n ? s0 + r : 0;
                    const bool next_unbuilt = next && main_b[((size_t)next * n + next + r) * 4] == VFI_UNBUILT_Q15;
                    vfi_preint_demand_entry(&demand, f, b);
                    CHECK(!(e[0] == VFI_UNBUILT_Q15 && e[3] == 0));
                    CHECK(!(main_b[((size_t)(lo + r) * n + lo) * 4] == VFI_UNBUILT_Q15 &&
                            main_b[((size_t)(lo + r) * n + lo) * 4 + 3] == 0));
                    if (next_unbuilt)
                        CHECK_MSG(main_b[((size_t)next * n + next + r) * 4] == VFI_UNBUILT_Q15,
                                  "N %u: entry (%u, %u) built another block too", n, f, b);
                }
                else if (rnd(8) == 0 && f != b)
                    vfi_preint_demand_entry(&demand, f, b); /* again: the same entries */
            }
            for (uint32_t k = 0; k < n * n; k++) /* the rest, as a frame reading everything would */
                if (main_b[(size_t)k * 4] == VFI_UNBUILT_Q15 && main_b[(size_t)k * 4 + 3] == 0)
                    vfi_preint_demand_entry(&demand, k / n, k % n);
            CHECK_MSG(memcmp(main_a, main_b, values * sizeof main_a[0]) == 0, "N %u on demand: main tables differ", n);
            CHECK_MSG(memcmp(lit_a, lit_b, values * sizeof lit_a[0]) == 0, "N %u on demand: lit tables differ", n);
        }
    }
}

/* ---- 8 bits and the grids ---------------------------------------------------------------------------- */

static uint16_t grid_main[2][64 * 64 * 4], grid_lit[2][64 * 64 * 4];
static uint8_t u8_main[2][64 * 64 * 4], u8_lit[2][64 * 64 * 4];

/* The lit values in 8 bits and on the 10- and 12-bit grids: every value within 0.51 of a level of the spec's
 * exact value (round(L x) but where x sits next to a rounding boundary), as the main table's values are; the
 * incremental builder within a level of the brute force's in each format (the main table's rule), D_f <= C and
 * S_f <= a in each, and the diagonal and the zero entries exactly the brute force's. */
static void lit_formats(void)
{
    const uint32_t sizes[] = {2, 3, 17, 64};
    const double lengths[] = {0.3, 1.0, 1.7320508, 5.0};
    double worst_level[3] = {0, 0, 0};
    int worst_between[3] = {0, 0, 0};
    for (size_t sn = 0; sn < sizeof sizes / sizeof sizes[0]; sn++) {
        const uint32_t n = sizes[sn];
        fixture_t fx;
        CHECK(fixture_init(&fx, n, true));
        for (int t = 0; t < 6; t++) {
            const vf_tf_t tf = random_tf(t % 3 == 0);
            CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
            spec_classify(&tf, n);
            for (size_t ln = 0; ln < 4; ln++) {
                const uint32_t slab_q16 = (uint32_t)lround(lengths[ln] * 65536);
                const double d = slab_q16 / 65536.0;
                for (int format = 0; format < 3; format++) {
                    const uint32_t bits = format == 0 ? 8 : format == 1 ? 10 : 12, levels = (1u << bits) - 1;
                    const int level = format == 0 ? 1 : (int)((32768 + levels - 1) / levels);
                    for (int builder = 0; builder < 2; builder++) {
                        vfi_table_out_t out = {NULL, u8_main[builder], 0, NULL, u8_lit[builder], NULL, NULL};
                        if (format > 0)
                            out = (vfi_table_out_t){grid_main[builder], NULL, bits, grid_lit[builder], NULL, NULL,
                                                    NULL};
                        if (builder)
                            vfi_preint_table_bruteforce(&fx.cls, slab_q16, &fx.scratch, out);
                        else
                            vfi_preint_table_incremental(&fx.cls, slab_q16, &fx.scratch, out);
                    }
                    for (uint32_t f = 0; f < n; f++)
                        for (uint32_t b = 0; b < n; b++) {
                            double e[8];
                            spec_entry(f, b, d, e);
                            for (int c = 0; c < 8; c++) {
                                const size_t at = ((size_t)f * n + b) * 4 + (size_t)(c % 4);
                                int got[2];
                                for (int builder = 0; builder < 2; builder++) {
                                    /* the value as levels of its format */
                                    const int v = format == 0 ? (c < 4 ? u8_main : u8_lit)[builder][at]
                                                              : (c < 4 ? grid_main : grid_lit)[builder][at];
                                    got[builder] = format == 0 ? v : (int)lround(v * (double)levels / 32768);
                                    if (format > 0 && (uint16_t)lround(got[builder] * 32768.0 / levels) != v) {
                                        check_fail(__FILE__, __LINE__, "%u bits: %d is not on the grid", bits, v);
                                        return;
                                    }
                                    const double off = fabs(got[builder] - e[c] * levels);
                                    worst_level[format] = fmax(worst_level[format], off);
                                    if (off >= 0.51) {
                                        check_fail(__FILE__, __LINE__,
                                                   "N %u d %g %u bits %s entry (%u, %u) %s %d: %d, spec %.4f levels", n,
                                                   d, bits, builder ? "brute force" : "incremental", f, b,
                                                   c < 4 ? "main" : "lit", c % 4, got[builder], e[c] * levels);
                                        return;
                                    }
                                }
                                const int v0 = format == 0 ? (c < 4 ? u8_main : u8_lit)[0][at]
                                                           : (c < 4 ? grid_main : grid_lit)[0][at];
                                const int v1 = format == 0 ? (c < 4 ? u8_main : u8_lit)[1][at]
                                                           : (c < 4 ? grid_main : grid_lit)[1][at];
                                if (c >= 4 && abs(v0 - v1) > worst_between[format])
                                    worst_between[format] = abs(v0 - v1);
                                /* zero main values are the invisible ranges', exactly; lit values follow from
                                 * D_f <= C and S_f <= a (below) */
                                CHECK_MSG(abs(v0 - v1) <= level && (f != b || v0 == v1) &&
                                              (c >= 4 || v1 != 0 || v0 == 0),
                                          "N %u d %g %u bits entry (%u, %u) value %d: incremental %d, brute force %d",
                                          n, d, bits, f, b, c, v0, v1);
                            }
                            for (int builder = 0; builder < 2; builder++)
                                for (int c = 0; c < 4; c++) {
                                    const size_t at = ((size_t)f * n + b) * 4 + (size_t)c;
                                    const int m = format == 0 ? u8_main[builder][at] : grid_main[builder][at];
                                    const int l = format == 0 ? u8_lit[builder][at] : grid_lit[builder][at];
                                    CHECK_MSG(l <= m, "%u bits entry (%u, %u) channel %d: lit %d above main %d", bits,
                                              f, b, c, l, m);
                                }
                        }
                }
            }
        }
    }
    if (show())
        printf("# lit and main values against the spec in levels: u8 %.3f, grid 10 %.3f, grid 12 %.3f; lit "
               "incremental against brute force: %d, %d, %d\n",
               worst_level[0], worst_level[1], worst_level[2], worst_between[0], worst_between[1], worst_between[2]);
}

/* ---- the lit view table ------------------------------------------------------------------------------ */

static uint16_t view_a[256 * 256 * 4], view_b[256 * 256 * 4], lit_view[256 * 256 * 4];

/* vfi_view_table_lit: its view table is vfi_view_table's to the bit, and each lit value is the lut's colour
 * correction (segment.h, vfi_lut_at and vfi_lut_colour) with G(a) of its entry's opacity; in parts (those
 * vfi_preint_table_part would build) the same. */
static void lit_view_table(void)
{
    static uint16_t lut_f[VFI_LUT_KNOTS];
    static uint32_t lut_g[VFI_LUT_KNOTS];
    const uint32_t n = 256;
    const size_t count = (size_t)n * n;
    fixture_t fx;
    CHECK(fixture_init(&fx, n, true));
    for (int t = 0; t < 3; t++) {
        const vf_tf_t tf = random_tf(t == 2);
        CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
        vfi_preint_table_incremental(&fx.cls, 65536, &fx.scratch, q15_out(main_a, lit_a));
        const uint32_t rho_q16 = t == 0 ? 65536 : t == 1 ? 113512 : 20000; /* 1, sqrt(3), 0.31 */
        vfi_correction_lut(rho_q16, lut_f, lut_g);
        vfi_view_table(lut_f, lut_g, main_a, view_a, count);
        memset(lit_view, 0, sizeof lit_view);
        vfi_view_table_lit(lut_f, lut_g, main_a, lit_a, view_b, lit_view, count);
        CHECK(memcmp(view_a, view_b, count * 4 * sizeof view_a[0]) == 0);
        for (size_t e = 0; e < count; e++) {
            uint32_t fa;
            const uint64_t g = vfi_lut_at(lut_f, lut_g, main_a[e * 4 + 3], &fa);
            for (int c = 0; c < 4; c++) {
                uint32_t want = vfi_lut_colour(lit_a[e * 4 + c], g);
                want = want > 0xFFFFu ? 0xFFFFu : want;
                CHECK_MSG(lit_view[e * 4 + c] == want, "rho %u entry %zu channel %d: %u, want %u", rho_q16, e, c,
                          lit_view[e * 4 + c], want);
                CHECK(lit_view[e * 4 + c] <= (c < 3 ? view_a[e * 4 + c] : fa) + 1u); /* up to the rounding */
            }
        }
#if VF_MAX_TABLE_PARTS > 1
        memset(view_b, 0, sizeof view_b);
        memset(lit_b, 0, count * 4 * sizeof lit_b[0]);
        for (uint32_t p = 0; p < 3; p++)
            vfi_view_table_lit_part(lut_f, lut_g, main_a, lit_a, view_b, lit_b, n, p, 3);
        CHECK(memcmp(view_a, view_b, count * 4 * sizeof view_a[0]) == 0);
        CHECK(memcmp(lit_view, lit_b, count * 4 * sizeof lit_view[0]) == 0);
#endif
    }
}

/* ---- the extremes ------------------------------------------------------------------------------------ */

static uint8_t main_u8[MAX_N * MAX_N * 4], lit_u8[MAX_N * MAX_N * 4];

/* Opaque white over 1024 entries (windows of up to 1023 intervals, the moments at their largest) for the
 * shortest and longest slabs and two between: no value above 1.0, D_f <= C, S_f <= a, in Q1.15 and in 8 bits
 * (where a value above 1.0 would wrap to 0), and the lit values within 1 LSB of the spec along a few rows. */
static void lit_extremes(void)
{
    fixture_t fx;
    CHECK(fixture_init(&fx, MAX_N, true));
    vf_tf_point_t white = {0, 65535, 65535, 65535, 65535};
    vf_tf_t tf = {&white, 1};
    CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
    spec_classify(&tf, MAX_N);
    const uint32_t slabs[] = {65536 / 1024, 65536, 3 * 65536, UINT32_C(128) << 16};
    for (size_t sl = 0; sl < sizeof slabs / sizeof slabs[0]; sl++) {
        vfi_preint_table_incremental(&fx.cls, slabs[sl], &fx.scratch, q15_out(main_a, lit_a));
        vfi_preint_table_incremental(&fx.cls, slabs[sl], &fx.scratch,
                                     (vfi_table_out_t){NULL, main_u8, 0, NULL, lit_u8, NULL, NULL});
        for (size_t e = 0; e < (size_t)MAX_N * MAX_N; e++)
            for (int c = 0; c < 4; c++) {
                const uint16_t m = main_a[e * 4 + c], l = lit_a[e * 4 + c];
                CHECK_MSG(m <= VFI_ONE_Q15 && l <= m && lit_u8[e * 4 + c] <= main_u8[e * 4 + c],
                          "slab %u entry (%zu, %zu) channel %d: main %u lit %u, u8 %u %u", slabs[sl], e / MAX_N,
                          e % MAX_N, c, m, l, main_u8[e * 4 + c], lit_u8[e * 4 + c]);
            }
        const uint32_t rows[] = {0, 511, 1000, 1023};
        for (size_t k = 0; k < 4; k++)
            for (uint32_t b = 0; b < MAX_N; b += 7) {
                double e[8];
                spec_entry(rows[k], b, slabs[sl] / 65536.0, e);
                for (int c = 0; c < 4; c++)
                    CHECK_MSG(lsb_diff(lit_a[((size_t)rows[k] * MAX_N + b) * 4 + c], e[4 + c]) <= 1,
                              "slab %u entry (%u, %u) channel %d: %u, spec %.3f", slabs[sl], rows[k], b, c,
                              lit_a[((size_t)rows[k] * MAX_N + b) * 4 + c], e[4 + c] * 32768);
            }
    }
}

/* Coloured transfer functions over 1024 entries, every entry against the exact properties and a few rows (both
 * triangles) against the spec. */
static void lit_large(void)
{
    fixture_t fx;
    CHECK(fixture_init(&fx, MAX_N, true));
    for (int t = 0; t < 3; t++) {
        const vf_tf_t tf = random_tf(false);
        CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
        spec_classify(&tf, MAX_N);
        const uint32_t slab_q16 = t == 0 ? 65536 : t == 1 ? 20000 : 400000;
        vfi_preint_table_incremental(&fx.cls, slab_q16, &fx.scratch, q15_out(main_a, lit_a));
        for (size_t e = 0; e < (size_t)MAX_N * MAX_N * 4; e++)
            CHECK_MSG(lit_a[e] <= main_a[e] && main_a[e] <= VFI_ONE_Q15, "entry (%zu, %zu) value %zu: lit %u, main %u",
                      e / 4 / MAX_N, e / 4 % MAX_N, e % 4, lit_a[e], main_a[e]);
        for (uint32_t k = 0; k < 6; k++) {
            const uint32_t f = rnd(MAX_N);
            for (uint32_t b = rnd(5); b < MAX_N; b += 5) {
                double e[8];
                spec_entry(f, b, slab_q16 / 65536.0, e);
                for (int c = 0; c < 4; c++)
                    CHECK_MSG(lsb_diff(lit_a[((size_t)f * MAX_N + b) * 4 + c], e[4 + c]) <= 1,
                              "slab %u entry (%u, %u) channel %d: %u, spec %.3f", slab_q16, f, b, c,
                              lit_a[((size_t)f * MAX_N + b) * 4 + c], e[4 + c] * 32768);
            }
        }
    }
}

/* ---- the public entry point -------------------------------------------------------------------------- */

/* vf_table_preint_lit: its main table is vf_table_preint's to the bit, its lit table the internal builders';
 * vf_table_scratch_bytes is enough for it, half of that is refused, every argument is checked, and the arena is
 * given back whatever happens. */
static void lit_public_api(void)
{
    static _Alignas(16) unsigned char buf[1 << 20];
    static uint16_t out[64 * 64 * 4], lit[64 * 64 * 4], plain[64 * 64 * 4];
    vf_tf_point_t pts[2] = {{0, 65535, 0, 0, 0}, {65280, 0, 65535, 0, 40000}};
    vf_tf_t tf = {pts, 2};
    vf_arena_t arena;
    const uint32_t slab = 70000;
    const size_t need = vf_table_scratch_bytes(64);
    CHECK(need > 0);
    for (int builder = 0; builder < VF_BUILDER_COUNT; builder++) {
        vf_arena_init(&arena, buf + 1, need); /* misaligned: the size counts the alignment */
        const size_t start = arena.used;
        CHECK_EQ(vf_table_preint_lit(&tf, 64, slab, (vf_builder_t)builder, &arena, out, lit), VF_OK);
        CHECK_EQ(arena.used, start);
        CHECK_EQ(vf_table_preint(&tf, 64, slab, (vf_builder_t)builder, &arena, plain), VF_OK);
        CHECK(memcmp(out, plain, sizeof out) == 0);
        fixture_t fx;
        CHECK(fixture_init(&fx, 64, true));
        CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
        if (builder == VF_BUILDER_INCREMENTAL)
            vfi_preint_table_incremental(&fx.cls, slab, &fx.scratch, q15_out(main_a, lit_a));
        else
            vfi_preint_table_bruteforce(&fx.cls, slab, &fx.scratch, q15_out(main_a, lit_a));
        CHECK(memcmp(lit, lit_a, sizeof lit) == 0);
    }
    vf_arena_init(&arena, buf, need / 2);
    CHECK_EQ(vf_table_preint_lit(&tf, 64, slab, VF_BUILDER_INCREMENTAL, &arena, out, lit), VF_ERR_NOMEM);
    CHECK_EQ(arena.used, 0);
    /* the lit build's scratch less its suffixes' moments: enough for the unlit build, not for this one */
    vf_arena_init(&arena, buf, need - vfi_arena_block(sizeof(vfi_suffix_lit_t) * 63));
    CHECK_EQ(vf_table_preint(&tf, 64, slab, VF_BUILDER_INCREMENTAL, &arena, out), VF_OK);
    CHECK_EQ(vf_table_preint_lit(&tf, 64, slab, VF_BUILDER_INCREMENTAL, &arena, out, lit), VF_ERR_NOMEM);
    vf_arena_init(&arena, buf, sizeof buf);
    CHECK_EQ(vf_table_preint_lit(NULL, 64, slab, VF_BUILDER_INCREMENTAL, &arena, out, lit), VF_ERR_NULL);
    CHECK_EQ(vf_table_preint_lit(&tf, 64, slab, VF_BUILDER_INCREMENTAL, NULL, out, lit), VF_ERR_NULL);
    CHECK_EQ(vf_table_preint_lit(&tf, 64, slab, VF_BUILDER_INCREMENTAL, &arena, NULL, lit), VF_ERR_NULL);
    CHECK_EQ(vf_table_preint_lit(&tf, 64, slab, VF_BUILDER_INCREMENTAL, &arena, out, NULL), VF_ERR_NULL);
    CHECK_EQ(vf_table_preint_lit(&tf, 1, slab, VF_BUILDER_INCREMENTAL, &arena, out, lit), VF_ERR_ARG);
    CHECK_EQ(vf_table_preint_lit(&tf, VF_MAX_TABLE + 1, slab, VF_BUILDER_INCREMENTAL, &arena, out, lit), VF_ERR_ARG);
    CHECK_EQ(vf_table_preint_lit(&tf, 64, 0, VF_BUILDER_INCREMENTAL, &arena, out, lit), VF_ERR_ARG);
    CHECK_EQ(vf_table_preint_lit(&tf, 64, (UINT32_C(128) << 16) + 1, VF_BUILDER_INCREMENTAL, &arena, out, lit),
             VF_ERR_ARG);
    CHECK_EQ(vf_table_preint_lit(&tf, 64, slab, VF_BUILDER_COUNT, &arena, out, lit), VF_ERR_ARG);
    vf_tf_point_t down[2] = {{300, 0, 0, 0, 0}, {200, 0, 0, 0, 0}};
    vf_tf_t bad = {down, 2};
    CHECK_EQ(vf_table_preint_lit(&bad, 64, slab, VF_BUILDER_INCREMENTAL, &arena, out, lit), VF_ERR_TF);
    CHECK_EQ(arena.used, 0);
}

CHECK_CASES(CHECK_CASE(emission_depth), CHECK_CASE(lit_against_spec), CHECK_CASE(lit_special),
            CHECK_CASE(lit_grey_twin), CHECK_CASE(lit_parts_and_demand), CHECK_CASE(lit_formats),
            CHECK_CASE(lit_view_table), CHECK_CASE(lit_extremes), CHECK_CASE(lit_large), CHECK_CASE(lit_public_api));
CHECK_RUN("core/lit_tables")
