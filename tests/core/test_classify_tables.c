/* SPDX-License-Identifier: MIT */
/*
 * test_classify_tables.c: classification (core/classify.c), the point table, the brute-force and incremental
 * pre-integrated tables and the lut correction (core/tables.c) against docs/algorithm.md sections 2 and 4b,
 * written here again in double.
 *
 * Bounds asserted (measured in the comments):
 *   tau_i               within 1.2e-8 + 7e-10 / (1 - a0) of -ln(1 - a0) (the a0 rounding to Q.30 scaled by 1/(1-a0);
 *                       measured: 0.68 of that)
 *   colour_i            within 1e-9
 *   point table         within 1 LSB of Q1.15 of round(32768 x) (measured 1)
 *   brute force         within 1 LSB of Q1.15 (measured 1, at 0.13% of the values; 99.87% exact)
 *   incremental         within 1 LSB of the brute force and of the spec (measured 1 and 1); in the 8-bit and
 *                       the 10- and 12-bit grid formats within one level of the brute force's (measured 0, 0, 8)
 *   8-bit tables        within 0.51 of 255 x
 *   no clamp            1.0 + VFI_STORE_SLACK_Q30 rounds to 1.0 in every format; an opaque white 1024-entry
 *                       table stays at most 1.0 everywhere (table_store.h, preint.c)
 *   lut correction      F within 1 LSB of Q1.15, G within 2^-12 relative
 * and the exact properties: diagonal == point table, invisible ranges exactly zero, exact entry rounding.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arena.h"
#include "check.h"
#include "classify.h"
#include "table_store.h"
#include "tables.h"
#include "tables_spec.h"

static uint64_t rng_state = 0xB7E151628AED2A6Bu;

/* Tables of up to 1024 entries (the 2D table: 8 MiB). */
static uint16_t table2d[1024 * 1024 * 4];
static uint16_t table1d[1024 * 4];

static vfi_table_out_t q15_out(uint16_t *table)
{
    vfi_table_out_t out = {table, NULL, 0, NULL, NULL, NULL, NULL};
    return out;
}

/* ---- the spec in double ------------------------------------------------------------------------------ */

static void spec_point(uint32_t i, double d, double out[4])
{
    double a = -expm1(-spec.tau[i] * d);
    for (int c = 0; c < 3; c++)
        out[c] = spec.col[i][c] * a;
    out[3] = a;
}

/* Entry (f, b) of the pre-integrated table for slab length d, r, g, b, a. */
static void spec_preint(uint32_t f, uint32_t b, double d, double out[4])
{
    if (f == b) {
        spec_point(f, d, out);
        return;
    }
    uint32_t r = f < b ? b - f : f - b;
    double L = d / r, A = 0, C[3] = {0, 0, 0};
    for (uint32_t q = 0; q < r; q++) {
        uint32_t m = f < b ? f + q : f - 1 - q;
        double t0 = spec.tau[m], t1 = spec.tau[m + 1];
        double alpha = -expm1(-L * (t0 + t1) / 2);
        for (int c = 0; c < 3; c++) {
            double c0 = spec.col[m][c], c1 = spec.col[m + 1][c];
            double w = t0 + t1 == 0 ? (c0 + c1) / 2
                                    : (2 * t0 * c0 + t0 * c1 + t1 * c0 + 2 * t1 * c1) / (3 * (t0 + t1));
            C[c] += (1 - A) * w * alpha;
        }
        A += (1 - A) * alpha;
    }
    out[0] = C[0];
    out[1] = C[1];
    out[2] = C[2];
    out[3] = A;
}

/* ---- transfer functions ------------------------------------------------------------------------------ */

static vf_tf_point_t pts_buf[VF_MAX_TF_POINTS + 2];

static vf_tf_t random_tf(void)
{
    return spec_random_tf(pts_buf, false, check_mod, &rng_state);
}

/* ---- classification ---------------------------------------------------------------------------------- */

static void check_classification(const vfi_classify_t *cls, const vf_tf_t *tf)
{
    spec_classify(tf, cls->n);
    for (uint32_t i = 0; i < cls->n; i++) {
        double a0 = fmin(spec.a0[i], 1 - 1.0 / 65536);
        double tau = cls->tau_q28[i] / 268435456.0;
        double bound = 1.2e-8 + 7e-10 / (1 - a0);
        if (fabs(tau - spec.tau[i]) > bound) {
            check_fail(__FILE__, __LINE__, "N %u entry %u: tau %.12g, spec %.12g (a0 %.9g)", cls->n, i, tau,
                       spec.tau[i], spec.a0[i]);
            return;
        }
        if (spec.a0[i] == 0 && cls->tau_q28[i] != 0) {
            check_fail(__FILE__, __LINE__, "entry %u: a0 = 0 but tau > 0", i);
            return;
        }
        if (spec.a0[i] >= 1.0 / (1 << 27) && cls->tau_q28[i] == 0) {
            check_fail(__FILE__, __LINE__, "entry %u: a0 = %g but tau == 0", i, spec.a0[i]);
            return;
        }
        for (int c = 0; c < 3; c++)
            if (fabs(cls->colour_q30[i * 3 + c] / 1073741824.0 - spec.col[i][c]) > 1e-9) {
                check_fail(__FILE__, __LINE__, "entry %u colour %d: %.12f, spec %.12f", i, c,
                           cls->colour_q30[i * 3 + c] / 1073741824.0, spec.col[i][c]);
                return;
            }
        /* visible_before[i] counts entries below i with tau > 0 */
        uint32_t count = 0;
        for (uint32_t e = 0; e < i; e++)
            count += cls->tau_q28[e] > 0;
        if (cls->visible_before[i] != count) {
            check_fail(__FILE__, __LINE__, "visible_before[%u] = %u, want %u", i, cls->visible_before[i], count);
            return;
        }
    }
    uint32_t all = 0;
    for (uint32_t e = 0; e < cls->n; e++)
        all += cls->tau_q28[e] > 0;
    if (cls->visible_before[cls->n] != all)
        check_fail(__FILE__, __LINE__, "visible_before[n]");
    /* visible_from[lo]: the smallest hi >= lo whose range [lo, hi] touches an entry with tau > 0 (brute force) */
    for (uint32_t lo = 0; lo < 256; lo++) {
        uint32_t want = 256;
        for (uint32_t hi = lo; hi < 256 && want == 256; hi++)
            for (uint32_t e = cls->first_of_scalar[lo]; e < cls->end_of_scalar[hi]; e++)
                if (cls->tau_q28[e] > 0) {
                    want = hi;
                    break;
                }
        if (cls->visible_from[lo] != want) {
            check_fail(__FILE__, __LINE__, "visible_from[%u] = %u, want %u (n %u)", lo, cls->visible_from[lo], want,
                       cls->n);
            return;
        }
    }
    /* solid_until[lo]: the smallest s >= lo whose scalar alone touches no entry with tau > 0 (brute force); made
     * only for the run encoder's bricks */
    for (uint32_t lo = 0; VF_RUN_BRICKS && lo < 256; lo++) {
        uint32_t want = 256;
        for (uint32_t s = lo; s < 256 && want == 256; s++) {
            bool alone = false;
            for (uint32_t e = cls->first_of_scalar[s]; e < cls->end_of_scalar[s]; e++)
                alone = alone || cls->tau_q28[e] > 0;
            if (!alone)
                want = s;
        }
        if (cls->solid_until[lo] != want) {
            check_fail(__FILE__, __LINE__, "solid_until[%u] = %u, want %u (n %u)", lo, cls->solid_until[lo], want,
                       cls->n);
            return;
        }
    }
}

static void classify_random(void)
{
    const uint32_t sizes[] = {2, 3, 16, 64, 255, 256, 257, 1000, 1024};
    for (size_t sn = 0; sn < sizeof sizes / sizeof sizes[0]; sn++) {
        fixture_t fx;
        CHECK(fixture_init(&fx, sizes[sn], false));
        for (int t = 0; t < 40; t++) {
            vf_tf_t tf = random_tf();
            CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
            check_classification(&fx.cls, &tf);
            if (check_failed)
                return;
        }
    }
}

static void classify_special(void)
{
    fixture_t fx;
    CHECK(fixture_init(&fx, 256, false));
    /* a single point: constant everywhere */
    vf_tf_point_t one = {30000, 65535, 32768, 0, 20000};
    vf_tf_t tf = {&one, 1};
    CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
    check_classification(&fx.cls, &tf);
    for (uint32_t i = 1; i < 256; i++) {
        CHECK_EQ(fx.cls.tau_q28[i], fx.cls.tau_q28[0]);
        CHECK_EQ(fx.cls.colour_q30[i * 3], fx.cls.colour_q30[0]);
    }
    CHECK_EQ(fx.cls.colour_q30[0], 1u << 30); /* 65535 is exactly 1.0 */
    CHECK_EQ(fx.cls.colour_q30[2], 0);

    /* a step at scalar 100: entry 100 (s = 100 exactly for N = 256) takes the later point */
    vf_tf_point_t step[2] = {{100 * 256, 0, 0, 0, 0}, {100 * 256, 65535, 65535, 65535, 65535}};
    tf = (vf_tf_t){step, 2};
    CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
    check_classification(&fx.cls, &tf);
    CHECK_EQ(fx.cls.tau_q28[99], 0);
    CHECK(fx.cls.tau_q28[100] > 0);
    CHECK_EQ(fx.cls.visible_before[100], 0);
    CHECK_EQ(fx.cls.visible_before[256], 156);

    /* a0 = 1 is clamped to 1 - 2^-16: tau = 16 ln 2 */
    CHECK_NEAR(fx.cls.tau_q28[200] / 268435456.0, 16 * M_LN2, 1e-8);

    /* points outside the range actually used: both beyond 255 is impossible, so both far left */
    vf_tf_point_t left[2] = {{0, 0, 0, 0, 0}, {256, 65535, 0, 0, 65535}};
    tf = (vf_tf_t){left, 2};
    CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
    check_classification(&fx.cls, &tf);
    CHECK_EQ(fx.cls.tau_q28[0], 0);
    for (uint32_t i = 1; i < 256; i++)
        CHECK_EQ(fx.cls.tau_q28[i], fx.cls.tau_q28[255]);
    /* first point right of every entry but the last: everything left of it takes its value */
    vf_tf_point_t right[2] = {{65280, 0, 65535, 0, 1000}, {65280, 0, 0, 65535, 0}};
    tf = (vf_tf_t){right, 2};
    CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
    check_classification(&fx.cls, &tf);
    CHECK(fx.cls.tau_q28[254] > 0);
    CHECK_EQ(fx.cls.tau_q28[255], 0); /* at 255 exactly the later point wins */
    CHECK_EQ(fx.cls.colour_q30[254 * 3 + 1], 1u << 30);

    /* a ramp 0 -> 65535 over the whole range: interpolation is exact at the entries */
    vf_tf_point_t ramp[2] = {{0, 0, 0, 0, 0}, {65280, 65535, 65535, 65535, 65535}};
    tf = (vf_tf_t){ramp, 2};
    CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
    check_classification(&fx.cls, &tf);
    for (uint32_t i = 0; i < 256; i++)
        CHECK_NEAR(fx.cls.colour_q30[i * 3] / 1073741824.0, i / 255.0, 1e-9);

    /* VF_MAX_TF_POINTS points, all at the same scalar: the last one rules from there on */
    for (uint32_t p = 0; p < VF_MAX_TF_POINTS; p++)
        pts_buf[p] = (vf_tf_point_t){5000, (uint16_t)p, 0, 0, (uint16_t)(p * 60)};
    tf = (vf_tf_t){pts_buf, VF_MAX_TF_POINTS};
    CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
    check_classification(&fx.cls, &tf);
}

/* Bad transfer functions are refused before anything is written: the previous classification stands. */
static void classify_bad_keeps_previous(void)
{
    fixture_t fx;
    CHECK(fixture_init(&fx, 256, false));
    vf_tf_t good = random_tf();
    for (uint32_t p = 0; p < good.count; p++)
        pts_buf[p].a = 30000;
    CHECK_EQ(vfi_classify(&fx.cls, &good), VF_OK);
    static uint32_t tau[256], col[768], wgt[765];
    static uint16_t vis[257];
    memcpy(tau, fx.cls.tau_q28, sizeof tau);
    memcpy(col, fx.cls.colour_q30, sizeof col);
    memcpy(wgt, fx.cls.weight_q30, sizeof wgt);
    memcpy(vis, fx.cls.visible_before, sizeof vis);

    static vf_tf_point_t bad[VF_MAX_TF_POINTS + 1];
    for (uint32_t p = 0; p <= VF_MAX_TF_POINTS; p++)
        bad[p] = (vf_tf_point_t){(uint16_t)(p * 60), 1, 2, 3, 65535};
    struct {
        vf_tf_t tf;
        vf_status_t want;
    } cases[] = {
        {{bad, 0}, VF_ERR_TF},                     /* no points */
        {{bad, VF_MAX_TF_POINTS + 1}, VF_ERR_TF},  /* too many */
        {{bad, UINT32_MAX}, VF_ERR_TF},            /* far too many */
        {{NULL, 3}, VF_ERR_NULL},                  /* no array */
    };
    for (size_t n = 0; n < sizeof cases / sizeof cases[0]; n++)
        CHECK_EQ(vfi_classify(&fx.cls, &cases[n].tf), cases[n].want);
    CHECK_EQ(vfi_classify(&fx.cls, NULL), VF_ERR_NULL);
    /* decreasing scalars, at the start, the middle and the very end */
    vf_tf_point_t dec[4] = {{100, 1, 1, 1, 65535}, {200, 1, 1, 1, 65535}, {300, 1, 1, 1, 65535}, {400, 1, 1, 1, 65535}};
    for (int at = 1; at < 4; at++) {
        vf_tf_point_t d[4];
        memcpy(d, dec, sizeof d);
        d[at].scalar_q8 = (uint16_t)(d[at - 1].scalar_q8 - 1);
        vf_tf_t tf = {d, 4};
        CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_ERR_TF);
    }
    /* scalar beyond 255 (Q8.8 65280), at every position */
    for (int at = 0; at < 4; at++) {
        vf_tf_point_t d[4];
        memcpy(d, dec, sizeof d);
        for (int q = at; q < 4; q++)
            d[q].scalar_q8 = 65281;
        vf_tf_t tf = {d, 4};
        CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_ERR_TF);
        d[3].scalar_q8 = 65535;
        CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_ERR_TF);
    }
    CHECK(memcmp(tau, fx.cls.tau_q28, sizeof tau) == 0);
    CHECK(memcmp(col, fx.cls.colour_q30, sizeof col) == 0);
    CHECK(memcmp(wgt, fx.cls.weight_q30, sizeof wgt) == 0);
    CHECK(memcmp(vis, fx.cls.visible_before, sizeof vis) == 0);
    /* the limits themselves are fine */
    vf_tf_t max_points = {bad, VF_MAX_TF_POINTS};
    for (uint32_t p = 0; p < VF_MAX_TF_POINTS; p++)
        bad[p].scalar_q8 = (uint16_t)(p * 63);
    CHECK_EQ(vfi_classify(&fx.cls, &max_points), VF_OK);
    vf_tf_point_t top = {65280, 1, 1, 1, 1};
    vf_tf_t top_tf = {&top, 1};
    CHECK_EQ(vfi_classify(&fx.cls, &top_tf), VF_OK);
}

/* ---- entries of samples ------------------------------------------------------------------------------ */

/* round(S (N - 1) / (255 2^32)) for a Q8.32 sample S, exactly, half up. Exact in 64 bits (no __int128, which
 * 32-bit targets lack): S <= 255 2^32 < 2^40 and N <= 1024, so the numerator is below 2^52. */
static uint32_t exact_entry(uint64_t s, uint32_t n)
{
    uint64_t num = s * (n - 1) * 2 + (uint64_t)255 * ((uint64_t)1 << 32);
    return (uint32_t)(num / ((uint64_t)510 << 32));
}

static void entry_of_sample_exact(void)
{
    const uint32_t sizes[] = {2, 64, 255, 256, 257, 1000, 1024};
    const uint64_t top = (uint64_t)255 << 32;
    for (size_t sn = 0; sn < sizeof sizes / sizeof sizes[0]; sn++) {
        uint32_t n = sizes[sn];
        vfi_classify_t cls;
        memset(&cls, 0, sizeof cls);
        cls.n = n;
        for (int t = 0; t < 200000; t++) {
            uint64_t s = check_rand64(&rng_state) % (top + 1);
            CHECK_MSG(vfi_entry_of_sample(&cls, s) == exact_entry(s, n), "N %u sample %llu", n,
                      (unsigned long long)s);
        }
        /* exactly half-way samples: S (N - 1) / (255 2^32) = m + 1/2, i.e. S = (2m + 1) 255 2^31 / (N - 1),
         * when that is an integer, and their neighbours */
        int halfway = 0;
        for (uint64_t m = 0; m + 1 < n; m++) {
            uint64_t num = (2 * m + 1) * 255 * ((uint64_t)1 << 31); /* < 2^11 2^8 2^31: fits */
            if (num % (n - 1))
                continue;
            uint64_t s = (uint64_t)(num / (n - 1));
            halfway++;
            CHECK_MSG(vfi_entry_of_sample(&cls, s) == m + 1, "N %u: half-way sample %llu gives %u, want %llu", n,
                      (unsigned long long)s, vfi_entry_of_sample(&cls, s), (unsigned long long)(m + 1));
            CHECK_EQ(vfi_entry_of_sample(&cls, s - 1), m);
            CHECK_EQ(vfi_entry_of_sample(&cls, s + 1), m + 1);
        }
        CHECK(halfway > 0); /* every listed N has some (N - 1 divides 255 2^31 (2m + 1) for some m) */
        /* the ends and every integer scalar */
        CHECK_EQ(vfi_entry_of_sample(&cls, 0), 0);
        CHECK_EQ(vfi_entry_of_sample(&cls, top), n - 1);
        for (uint64_t v = 0; v < 256; v++)
            CHECK_EQ(vfi_entry_of_sample(&cls, v << 32), exact_entry(v << 32, n));
    }
}

/* The 8-bit scalar table of the classification uses the same rounding as samples. */
static void entry_of_scalar_table(void)
{
    const uint32_t sizes[] = {2, 3, 64, 255, 256, 257, 1000, 1024};
    for (size_t sn = 0; sn < sizeof sizes / sizeof sizes[0]; sn++) {
        fixture_t fx;
        CHECK(fixture_init(&fx, sizes[sn], false));
        for (uint64_t v = 0; v < 256; v++) {
            CHECK_EQ(fx.cls.entry_of_scalar[v], exact_entry(v << 32, sizes[sn]));
            CHECK_EQ(fx.cls.entry_of_scalar[v], vfi_entry_of_sample(&fx.cls, v << 32));
        }
    }
}

/* ---- tables ------------------------------------------------------------------------------------------ */

static int lsb_diff(uint16_t got, double want)
{
    long w = lround(want * 32768);
    return abs((int)((long)got - w));
}

/* Compare the core's tables with the spec; returns the largest error in LSB (or -1 after a failure). */
static int check_tables(fixture_t *fx, const vf_tf_t *tf, double d, int bound)
{
    uint32_t n = fx->cls.n;
    uint32_t slab_q16 = (uint32_t)lround(d * 65536);
    d = slab_q16 / 65536.0; /* the slab length is an input: the spec table is for the same (quantised) d */
    spec_classify(tf, n);
    vfi_point_table(&fx->cls, slab_q16, q15_out(table1d));
    vfi_preint_table_bruteforce(&fx->cls, slab_q16, &fx->scratch, q15_out(table2d));
    int worst = 0;
    for (uint32_t i = 0; i < n; i++) {
        double e[4];
        spec_point(i, d, e);
        for (int c = 0; c < 4; c++) {
            int diff = lsb_diff(table1d[i * 4 + c], e[c]);
            worst = diff > worst ? diff : worst;
            if (diff > bound) {
                check_fail(__FILE__, __LINE__, "N %u d %g point entry %u channel %d: %u, spec %.3f", n, d, i, c,
                           table1d[i * 4 + c], e[c] * 32768);
                return -1;
            }
            /* the diagonal of the 2D table is the point table, exactly */
            if (table2d[((size_t)i * n + i) * 4 + c] != table1d[i * 4 + c]) {
                check_fail(__FILE__, __LINE__, "diagonal %u differs from the point table", i);
                return -1;
            }
        }
    }
    for (uint32_t f = 0; f < n; f++)
        for (uint32_t b = 0; b < n; b++) {
            const uint16_t *got = table2d + ((size_t)f * n + b) * 4;
            double e[4];
            spec_preint(f, b, d, e);
            bool visible = false;
            for (uint32_t q = f < b ? f : b; q <= (f < b ? b : f); q++)
                visible |= spec.a0[q] > 0;
            for (int c = 0; c < 4; c++) {
                int diff = lsb_diff(got[c], e[c]);
                worst = diff > worst ? diff : worst;
                if (diff > bound || (!visible && got[c] != 0)) {
                    check_fail(__FILE__, __LINE__, "N %u d %g entry (%u, %u) channel %d: %u, spec %.3f%s", n, d, f,
                               b, c, got[c], e[c] * 32768, visible ? "" : " (invisible range)");
                    return -1;
                }
            }
            if (got[3] > 32768 || got[0] > 32768 || got[1] > 32768 || got[2] > 32768) {
                check_fail(__FILE__, __LINE__, "entry (%u, %u) above 1.0", f, b);
                return -1;
            }
        }
    return worst;
}

static void tables_random(void)
{
    const double lengths[] = {1.0, 0.37, 1.0130158, 1.7320508, 3.2, 20.5, 110.851};
    const uint32_t sizes[] = {2, 3, 17, 64};
    int worst = 0;
    for (size_t sn = 0; sn < sizeof sizes / sizeof sizes[0]; sn++) {
        fixture_t fx;
        CHECK(fixture_init(&fx, sizes[sn], false));
        for (int t = 0; t < 12; t++) {
            vf_tf_t tf = random_tf();
            CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
            for (size_t ln = 0; ln < sizeof lengths / sizeof lengths[0]; ln++) {
                int w = check_tables(&fx, &tf, lengths[ln], 1);
                if (check_failed)
                    return;
                worst = w > worst ? w : worst;
            }
        }
    }
    CHECK(worst <= 1); /* measured: 1 LSB */
}

static void tables_full_size(void)
{
    const double lengths[] = {1.0, 1.2247449};
    const uint32_t sizes[] = {256, 300};
    for (size_t sn = 0; sn < sizeof sizes / sizeof sizes[0]; sn++) {
        fixture_t fx;
        CHECK(fixture_init(&fx, sizes[sn], false));
        for (int t = 0; t < 2; t++) {
            vf_tf_t tf = random_tf();
            CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
            check_tables(&fx, &tf, lengths[t], 1);
            if (check_failed)
                return;
        }
    }
}

/* A constant transfer function: every entry, whatever its r, composites to the point entry (within 1 LSB). */
static void tables_constant_tf(void)
{
    const uint16_t alphas[] = {1, 300, 20000, 65535};
    for (size_t an = 0; an < 4; an++) {
        fixture_t fx;
        CHECK(fixture_init(&fx, 256, false));
        vf_tf_point_t p = {1234, 50000, 20000, 65535, alphas[an]};
        vf_tf_t tf = {&p, 1};
        CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
        vfi_preint_table_bruteforce(&fx.cls, 65536 + 4321, &fx.scratch, q15_out(table2d));
        const uint16_t *diag = table2d;
        for (size_t e = 0; e < (size_t)256 * 256; e++)
            for (int c = 0; c < 4; c++)
                CHECK_MSG(abs((int)table2d[e * 4 + c] - (int)diag[c]) <= 1, "a0 %u entry (%zu, %zu) channel %d: %u vs %u",
                          alphas[an], e / 256, e % 256, c, table2d[e * 4 + c], diag[c]);
    }
}

/* A transfer function that is zero everywhere: all-zero tables. Visible only at one entry: zero elsewhere. */
static void tables_invisible(void)
{
    fixture_t fx;
    CHECK(fixture_init(&fx, 64, false));
    vf_tf_point_t zero = {0, 65535, 65535, 65535, 0};
    vf_tf_t tf = {&zero, 1};
    CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
    memset(table2d, 0xFF, sizeof(uint16_t) * 64 * 64 * 4);
    vfi_preint_table_bruteforce(&fx.cls, 65536, &fx.scratch, q15_out(table2d));
    for (size_t e = 0; e < 64 * 64 * 4; e++)
        CHECK_EQ(table2d[e], 0);
    /* a narrow peak at entry 40 only (s = 40 * 255 / 63) */
    uint32_t s40 = (uint32_t)((40 * 65280 + 31) / 63); /* Q8.8, rounded */
    vf_tf_point_t peak[3] = {{(uint16_t)(s40 - 100), 0, 0, 0, 0}, {(uint16_t)s40, 65535, 0, 0, 65535},
                             {(uint16_t)(s40 + 100), 0, 0, 0, 0}};
    tf = (vf_tf_t){peak, 3};
    CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
    CHECK_EQ(fx.cls.visible_before[64] - fx.cls.visible_before[0], 1);
    check_tables(&fx, &tf, 1.0, 1);
    vfi_preint_table_bruteforce(&fx.cls, 65536, &fx.scratch, q15_out(table2d));
    for (uint32_t f = 0; f < 64; f++)
        for (uint32_t b = 0; b < 64; b++) {
            bool spans = (f <= 40 && b >= 40) || (b <= 40 && f >= 40);
            for (int c = 0; c < 4; c++) {
                if (!spans)
                    CHECK_EQ(table2d[((size_t)f * 64 + b) * 4 + c], 0);
            }
            if (spans)
                CHECK(table2d[((size_t)f * 64 + b) * 4 + 3] > 0);
        }
}

/* The O(N^2) incremental builder (Lum et al.) against the brute-force oracle (tables.h: at most 1 LSB apart) and
 * against the spec in double; diagonal and invisible ranges exactly as the oracle's. Every other transfer function
 * is grey (r = g = b everywhere), for which the builder works out one colour channel and copies it (preint.c,
 * block_dense_grey): its table has three equal colours and is to the bit the table of the three-channel path, which
 * a twin takes whose last interval's blue weight is 1 LSB of Q.30 off; every entry (f, b) with f, b <= n - 3
 * composites only intervals, and reads only neighbours' weights, that the twin shares. */
static uint16_t oracle2d[256 * 256 * 4], twin2d[256 * 256 * 4];

/* The twin of a grey classification's table: its last interval's blue weight moved by one, then put back. */
static void build_twin(vfi_classify_t *cls, uint32_t slab_q16, const vfi_table_scratch_t *scratch)
{
    uint32_t *blue = &cls->weight_q30[(cls->n - 2) * 3 + 2];
    const uint32_t grey = *blue;
    *blue = grey > 0 ? grey - 1 : 1;
    vfi_preint_table_incremental(cls, slab_q16, scratch, q15_out(twin2d));
    *blue = grey;
}

static void tables_incremental(void)
{
    const double lengths[] = {1.0, 0.37, 1.7320508, 20.5};
    const uint32_t sizes[] = {2, 3, 4, 5, 17, 64, 256};
    int worst_oracle = 0, worst_spec = 0;
    for (size_t sn = 0; sn < sizeof sizes / sizeof sizes[0]; sn++) {
        uint32_t n = sizes[sn];
        fixture_t fx;
        CHECK(fixture_init(&fx, n, false));
        for (int t = 0; t < (n == 256 ? 2 : 10); t++) {
            vf_tf_t tf = random_tf();
            const bool grey = t % 2 == 1;
            for (uint32_t p = 0; grey && p < tf.count; p++)
                pts_buf[p].g = pts_buf[p].b = pts_buf[p].r;
            CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
            spec_classify(&tf, n);
            for (size_t ln = 0; ln < sizeof lengths / sizeof lengths[0]; ln++) {
                uint32_t slab_q16 = (uint32_t)lround(lengths[ln] * 65536);
                double d = slab_q16 / 65536.0;
                vfi_preint_table_bruteforce(&fx.cls, slab_q16, &fx.scratch, q15_out(oracle2d));
                vfi_preint_table_incremental(&fx.cls, slab_q16, &fx.scratch, q15_out(table2d));
                if (grey)
                    build_twin(&fx.cls, slab_q16, &fx.scratch);
                for (uint32_t f = 0; f < n; f++)
                    for (uint32_t b = 0; b < n; b++) {
                        const size_t at = ((size_t)f * n + b) * 4;
                        const uint16_t *got = table2d + at, *want = oracle2d + at, *twin = twin2d + at;
                        CHECK_MSG(!grey || (got[1] == got[0] && got[2] == got[0]),
                                  "N %u entry (%u, %u): colour %u %u %u", n, f, b, got[0], got[1], got[2]);
                        CHECK_MSG(!grey || f + 3 > n || b + 3 > n || memcmp(got, twin, 8) == 0,
                                  "N %u d %g entry (%u, %u): grey path %u %u, three channels %u %u", n, d, f, b, got[0],
                                  got[3], twin[0], twin[3]);
                        double e[4];
                        spec_preint(f, b, d, e);
                        for (int c = 0; c < 4; c++) {
                            int dor = abs((int)got[c] - (int)want[c]), dsp = lsb_diff(got[c], e[c]);
                            worst_oracle = dor > worst_oracle ? dor : worst_oracle;
                            worst_spec = dsp > worst_spec ? dsp : worst_spec;
                            CHECK_MSG(dor <= 1 && dsp <= 1 && (f != b || dor == 0) && (want[c] != 0 || got[c] == 0),
                                      "N %u d %g entry (%u, %u) channel %d: incremental %u, brute force %u, spec %.3f", n,
                                      d, f, b, c, got[c], want[c], e[c] * 32768);
                        }
                    }
            }
        }
    }
    CHECK(worst_oracle <= 1 && worst_spec <= 1); /* measured: 1 and 1 */
}

/* 8-bit tables: every value is round(255 x) of the spec's x (docs/algorithm.md section 4b), within one level
 * where the Q.30 value sits next to a rounding boundary; and the two formats come from the same Q.30 values. */
static uint8_t table2d_u8[256 * 256 * 4];

static void tables_8bit(void)
{
    const uint32_t sizes[] = {2, 17, 64, 256};
    for (size_t sn = 0; sn < sizeof sizes / sizeof sizes[0]; sn++) {
        uint32_t n = sizes[sn];
        fixture_t fx;
        CHECK(fixture_init(&fx, n, false));
        for (int t = 0; t < 4; t++) {
            vf_tf_t tf = random_tf();
            CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
            spec_classify(&tf, n);
            uint32_t slab_q16 = 65536 + (uint32_t)t * 9000;
            double d = slab_q16 / 65536.0;
            vfi_table_out_t u8 = {NULL, table2d_u8, 0, NULL, NULL, NULL, NULL};
            vfi_preint_table_incremental(&fx.cls, slab_q16, &fx.scratch, u8);
            vfi_preint_table_incremental(&fx.cls, slab_q16, &fx.scratch, q15_out(table2d));
            for (uint32_t f = 0; f < n; f++)
                for (uint32_t b = 0; b < n; b++) {
                    double e[4];
                    spec_preint(f, b, d, e);
                    for (int c = 0; c < 4; c++) {
                        size_t at = ((size_t)f * n + b) * 4 + c;
                        long want = lround(e[c] * 255);
                        CHECK_MSG(labs((long)table2d_u8[at] - want) <= 1 && (e[c] * 255 - table2d_u8[at]) < 0.51 &&
                                      (table2d_u8[at] - e[c] * 255) < 0.51,
                                  "N %u entry (%u, %u) channel %d: u8 %u, spec %.4f", n, f, b, c, table2d_u8[at],
                                  e[c] * 255);
                        CHECK(abs((int)table2d_u8[at] - (int)lround(table2d[at] * 255 / 32768.0)) <= 1);
                    }
                }
            vfi_point_table(&fx.cls, slab_q16, (vfi_table_out_t){NULL, table2d_u8, 0, NULL, NULL, NULL, NULL});
            for (uint32_t i = 0; i < n; i++) {
                double e[4];
                spec_point(i, d, e);
                for (int c = 0; c < 4; c++)
                    CHECK(fabs(table2d_u8[i * 4 + c] - e[c] * 255) < 0.51);
            }
        }
    }
}

/* The incremental builder against the oracle in the other formats (vfi_table_out_t): 8 bits, and the grid of
 * grid_bits 10 and 12 that the precision studies use. Every entry within one level of the oracle's (the two round
 * the same Q.30 values but for the grouping), the diagonal and the invisible ranges exactly the oracle's. */
static uint16_t oracle_grid[64 * 64 * 4], table_grid[64 * 64 * 4];
static uint8_t oracle_u8[64 * 64 * 4], table_u8[64 * 64 * 4];

static void tables_incremental_formats(void)
{
    const uint32_t sizes[] = {2, 3, 17, 64};
    const double lengths[] = {1.0, 0.37, 1.7320508, 20.5};
    int worst[3] = {0, 0, 0};
    for (size_t sn = 0; sn < sizeof sizes / sizeof sizes[0]; sn++) {
        uint32_t n = sizes[sn];
        fixture_t fx;
        CHECK(fixture_init(&fx, n, false));
        for (int t = 0; t < 8; t++) {
            vf_tf_t tf = random_tf();
            CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
            for (size_t ln = 0; ln < sizeof lengths / sizeof lengths[0]; ln++) {
                uint32_t slab_q16 = (uint32_t)lround(lengths[ln] * 65536);
                for (int format = 0; format < 3; format++) {
                    const uint32_t bits = format == 1 ? 10 : 12;
                    /* one level apart: 1 of 255, or 32768 / (2^bits - 1) rounded up in Q1.15 */
                    const int level = format == 0 ? 1 : (int)((32768 + (1u << bits) - 2) / ((1u << bits) - 1));
                    vfi_table_out_t want = {NULL, oracle_u8, 0, NULL, NULL, NULL, NULL},
                                    got = {NULL, table_u8, 0, NULL, NULL, NULL, NULL};
                    if (format > 0) {
                        want = (vfi_table_out_t){oracle_grid, NULL, bits, NULL, NULL, NULL, NULL};
                        got = (vfi_table_out_t){table_grid, NULL, bits, NULL, NULL, NULL, NULL};
                    }
                    vfi_preint_table_bruteforce(&fx.cls, slab_q16, &fx.scratch, want);
                    vfi_preint_table_incremental(&fx.cls, slab_q16, &fx.scratch, got);
                    for (size_t e = 0; e < (size_t)n * n * 4; e++) {
                        int w = format == 0 ? oracle_u8[e] : oracle_grid[e];
                        int g = format == 0 ? table_u8[e] : table_grid[e];
                        size_t f = e / 4 / n, b = e / 4 % n;
                        worst[format] = abs(g - w) > worst[format] ? abs(g - w) : worst[format];
                        CHECK_MSG(abs(g - w) <= level && (f != b || g == w) && (w != 0 || g == 0),
                                  "N %u d %g format %d entry (%zu, %zu) channel %zu: incremental %d, brute force %d",
                                  n, lengths[ln], format, f, b, e % 4, g, w);
                        if (check_failed)
                            return;
                    }
                }
            }
        }
    }
    if (getenv("VOLFIX_SHOW"))
        printf("# incremental against brute force: u8 %d, grid 10 %d, grid 12 %d\n", worst[0], worst[1], worst[2]);
    CHECK(worst[0] <= 1 && worst[1] <= 33 && worst[2] <= 9);
}

/* No clamp where the builders round (table_store.h). Each conversion maps 1.0 + VFI_STORE_SLACK_Q30 to exactly
 * 1.0 of its format, and the q15 one would give more just above it (so the slack is the real limit, not a guess).
 * Then the builders at the extreme the bounds of tables.c and preint.c are about: an opaque white transfer
 * function (C = a everywhere), 1024 entries (windows of up to 1023 intervals), short and long slabs; every value
 * at most 1.0, and an 8-bit table all 255 where the opacity rounds to 1 (a value over 1.0 would wrap to 0). */
static uint8_t table1024_u8[1024 * 1024 * 4];

static void tables_no_clamp(void)
{
    const uint32_t top = (UINT32_C(1) << 30) + VFI_STORE_SLACK_Q30;
    CHECK_EQ(vfi_q30_to_q15(top), VFI_ONE_Q15);
    CHECK_EQ(vfi_q30_to_q15(top + 1), VFI_ONE_Q15 + 1);
    CHECK_EQ(vfi_q30_to_u8(top), 255);
    CHECK_EQ(vfi_q30_to_grid(top, 10), VFI_ONE_Q15);
    CHECK_EQ(vfi_q30_to_grid(top, 12), VFI_ONE_Q15);

    fixture_t fx;
    CHECK(fixture_init(&fx, 1024, false));
    vf_tf_point_t white = {0, 65535, 65535, 65535, 65535};
    vf_tf_t tf = {&white, 1};
    CHECK_EQ(vfi_classify(&fx.cls, &tf), VF_OK);
    const uint32_t slabs[] = {65536 / 1024, 65536, 3 * 65536, UINT32_C(128) << 16};
    for (size_t sl = 0; sl < sizeof slabs / sizeof slabs[0]; sl++) {
        vfi_preint_table_incremental(&fx.cls, slabs[sl], &fx.scratch, q15_out(table2d));
        vfi_preint_table_incremental(&fx.cls, slabs[sl], &fx.scratch,
                                     (vfi_table_out_t){NULL, table1024_u8, 0, NULL, NULL, NULL, NULL});
        for (size_t e = 0; e < (size_t)1024 * 1024; e++) {
            const uint16_t *q = table2d + e * 4;
            const uint8_t *u = table1024_u8 + e * 4;
            CHECK_MSG(q[0] <= VFI_ONE_Q15 && q[1] <= VFI_ONE_Q15 && q[2] <= VFI_ONE_Q15 && q[3] <= VFI_ONE_Q15,
                      "slab %u entry (%zu, %zu): %u %u %u %u", slabs[sl], e / 1024, e % 1024, q[0], q[1], q[2], q[3]);
            /* white: the colour is the opacity, to a level */
            CHECK(abs((int)q[0] - (int)q[3]) <= 1 && abs((int)u[0] - (int)u[3]) <= 1);
            if (q[3] == VFI_ONE_Q15)
                CHECK_MSG(u[0] == 255 && u[1] == 255 && u[2] == 255 && u[3] == 255, "slab %u entry (%zu, %zu): u8 %u %u %u %u",
                          slabs[sl], e / 1024, e % 1024, u[0], u[1], u[2], u[3]);
            if (check_failed)
                return;
        }
    }
}

/* The entries a sample between two 8-bit scalars can touch: exactly its nearest entries for nearest lookup; for
 * bilinear, which reads entries i = min(floor(x), N - 2) and i + 1 with weights 1 - f and f, every entry read
 * with a weight above zero. */
static void scalar_entry_ranges(void)
{
    const uint32_t sizes[] = {2, 3, 64, 255, 256, 257, 1000, 1024};
    for (size_t sn = 0; sn < sizeof sizes / sizeof sizes[0]; sn++) {
        uint32_t n = sizes[sn];
        for (int lk = 0; lk < 2; lk++) {
            vf_arena_t arena;
            vf_arena_init(&arena, arena_buf, sizeof arena_buf);
            vfi_classify_t cls;
            CHECK_EQ(vfi_classify_alloc(&cls, n, lk ? VF_LOOKUP_BILINEAR : VF_LOOKUP_NEAREST, &arena), VF_OK);
            for (uint64_t v = 0; v < 256; v++) {
                uint32_t e = exact_entry(v << 32, n);
                if (!lk) {
                    CHECK_EQ(cls.first_of_scalar[v], e);
                    CHECK_EQ(cls.end_of_scalar[v], e + 1);
                    continue;
                }
                /* bilinear: every sample s in [v - 1, v + 1] (between this scalar and its neighbours) */
                for (int64_t q = -64; q <= 64; q++) {
                    int64_t s_q32 = (int64_t)(v << 32) + q * (INT64_C(1) << 26);
                    if (s_q32 < 0 || s_q32 > (INT64_C(255) << 32))
                        continue;
                    /* x = s (N - 1) / 255 exactly as a fraction: whole part and whether there is a remainder */
                    uint64_t num = (uint64_t)s_q32 * (n - 1), den = (uint64_t)255 << 32; /* num < 2^50 */
                    uint32_t whole = (uint32_t)(num / den);
                    bool remainder = num % den != 0;
                    uint32_t i = whole < n - 2 ? whole : n - 2;
                    bool reads_i = whole == i;                    /* weight 1 - f > 0: x < i + 1 */
                    bool reads_next = remainder || whole > i;     /* weight f > 0: x > i */
                    uint32_t lowest = reads_i ? i : i + 1, highest = reads_next ? i + 1 : i;
                    /* a cell whose range ends at v (q <= 0) or starts at v (q >= 0) holds s: cover its entries */
                    if (q <= 0)
                        CHECK_MSG(cls.end_of_scalar[v] >= highest + 1, "N %u scalar %llu: end %u, sample reads %u", n,
                                  (unsigned long long)v, cls.end_of_scalar[v], highest);
                    if (q >= 0)
                        CHECK_MSG(cls.first_of_scalar[v] <= lowest, "N %u scalar %llu: first %u, sample reads %u", n,
                                  (unsigned long long)v, cls.first_of_scalar[v], lowest);
                }
                CHECK(cls.end_of_scalar[v] <= n);
            }
        }
    }
}

/* The lut correction (docs/algorithm.md section 4b): F(a) = 1 - (1 - a)^rho in Q1.15 and G(a) = F(a) / a
 * (G(0) = rho) in Q16.16, at a = k / 1024. Bounds: F within 1 LSB, G within 2^-12 relative plus 2 LSB. */
static void correction_lut(void)
{
    static uint16_t f[VFI_LUT_KNOTS];
    static uint32_t g[VFI_LUT_KNOTS];
    const double rhos[] = {1.0, 1.5, 0.5, 1.7320508, 0.25, 8.0, 64.0 * 1.7320508};
    for (size_t n = 0; n < sizeof rhos / sizeof rhos[0]; n++) {
        uint32_t rho_q16 = (uint32_t)lround(rhos[n] * 65536);
        double rho = rho_q16 / 65536.0;
        vfi_correction_lut(rho_q16, f, g);
        for (uint32_t k = 0; k < VFI_LUT_KNOTS; k++) {
            double a = k / 1024.0, F = 1 - pow(1 - a, rho), G = k ? F / a : rho;
            CHECK_MSG(fabs(f[k] - F * 32768) <= 1, "rho %g k %u: F %u, spec %.3f", rho, k, f[k], F * 32768);
            CHECK_MSG(fabs(g[k] - G * 65536) <= G * 65536 / 4096 + 2, "rho %g k %u: G %u (%.6f), spec %.6f", rho, k,
                      g[k], g[k] / 65536.0, G);
        }
    }
}

/* The public table API (vf_table_point, vf_table_preint) checks every argument, refuses a short scratch arena
 * and a bad transfer function, and takes nothing from the arena whatever happens. */
static void table_api_arguments(void)
{
    static _Alignas(16) unsigned char buf[1 << 20];
    static uint16_t out[64 * 64 * 4];
    vf_tf_point_t pts[2] = {{0, 65535, 0, 0, 0}, {65280, 0, 65535, 0, 40000}};
    vf_tf_t tf = {pts, 2};
    vf_arena_t arena;
    vf_arena_init(&arena, buf, sizeof buf);
    const uint32_t slab = 65536;
    CHECK_EQ(vf_table_point(NULL, 64, slab, &arena, out), VF_ERR_NULL);
    CHECK_EQ(vf_table_point(&tf, 64, slab, NULL, out), VF_ERR_NULL);
    CHECK_EQ(vf_table_point(&tf, 64, slab, &arena, NULL), VF_ERR_NULL);
    CHECK_EQ(vf_table_preint(NULL, 64, slab, VF_BUILDER_INCREMENTAL, &arena, out), VF_ERR_NULL);
    CHECK_EQ(vf_table_preint(&tf, 64, slab, VF_BUILDER_INCREMENTAL, NULL, out), VF_ERR_NULL);
    CHECK_EQ(vf_table_preint(&tf, 64, slab, VF_BUILDER_INCREMENTAL, &arena, NULL), VF_ERR_NULL);
    const uint32_t bad_n[] = {0, 1, VF_MAX_TABLE + 1, UINT32_MAX};
    for (int i = 0; i < 4; i++) {
        CHECK_EQ(vf_table_point(&tf, bad_n[i], slab, &arena, out), VF_ERR_ARG);
        CHECK_EQ(vf_table_preint(&tf, bad_n[i], slab, VF_BUILDER_BRUTEFORCE, &arena, out), VF_ERR_ARG);
        CHECK_EQ(vf_table_scratch_bytes(bad_n[i]), 0);
    }
    const uint32_t bad_slab[] = {0, (UINT32_C(128) << 16) + 1, UINT32_MAX};
    for (int i = 0; i < 3; i++)
        CHECK_EQ(vf_table_preint(&tf, 64, bad_slab[i], VF_BUILDER_INCREMENTAL, &arena, out), VF_ERR_ARG);
    CHECK_EQ(vf_table_preint(&tf, 64, slab, VF_BUILDER_COUNT, &arena, out), VF_ERR_ARG);
    CHECK_EQ(vf_table_preint(&tf, 64, slab, (vf_builder_t)-1, &arena, out), VF_ERR_ARG);
    vf_tf_point_t down[2] = {{300, 0, 0, 0, 0}, {200, 0, 0, 0, 0}};
    vf_tf_t bad = {down, 2};
    CHECK_EQ(vf_table_preint(&bad, 64, slab, VF_BUILDER_INCREMENTAL, &arena, out), VF_ERR_TF);
    bad.count = 0;
    CHECK_EQ(vf_table_point(&bad, 64, slab, &arena, out), VF_ERR_TF);
    CHECK_EQ(arena.used, 0);
    /* scratch: vf_table_scratch_bytes is enough even on a misaligned buffer (it counts the alignment); half of it
     * is refused */
    size_t need = vf_table_scratch_bytes(64);
    CHECK(need > 0);
    vf_arena_init(&arena, buf + 1, need);
    size_t start = arena.used; /* the bytes skipped to align */
    CHECK_EQ(vf_table_preint(&tf, 64, slab, VF_BUILDER_INCREMENTAL, &arena, out), VF_OK);
    CHECK_EQ(arena.used, start); /* the scratch is given back */
    vf_arena_init(&arena, buf, need / 2);
    CHECK_EQ(vf_table_preint(&tf, 64, slab, VF_BUILDER_INCREMENTAL, &arena, out), VF_ERR_NOMEM);
    CHECK_EQ(vf_table_point(&tf, 64, slab, &arena, out), VF_ERR_NOMEM);
    CHECK_EQ(arena.used, 0);
}

CHECK_CASES(CHECK_CASE(table_api_arguments), CHECK_CASE(classify_random), CHECK_CASE(classify_special),
            CHECK_CASE(classify_bad_keeps_previous), CHECK_CASE(entry_of_sample_exact),
            CHECK_CASE(entry_of_scalar_table), CHECK_CASE(tables_random), CHECK_CASE(tables_full_size),
            CHECK_CASE(tables_constant_tf), CHECK_CASE(tables_invisible), CHECK_CASE(tables_incremental),
            CHECK_CASE(tables_8bit), CHECK_CASE(tables_incremental_formats), CHECK_CASE(tables_no_clamp),
            CHECK_CASE(scalar_entry_ranges), CHECK_CASE(correction_lut));
CHECK_RUN("core/classify_tables")
