/* SPDX-License-Identifier: MIT */
/*
 * tables.c: the point table, the brute-force pre-integrated table (the oracle of the incremental builder in
 * preint.c), the lut correction and the public table entry points (docs/algorithm.md, section 2), integer only.
 *
 * Accumulation is Q.30 (1.0 = 2^30) so that compositing hundreds of intervals loses nothing visible; the
 * entries are rounded to their format once, at the end (table_store.h).
 */
#include "arena.h"
#include "fixmath.h"
#include "segment.h"
#include "table_store.h"
#include "tables.h"

#define ONE_Q30 (UINT64_C(1) << 30)
#define HALF_Q30 (UINT64_C(1) << 29)

static vfi_seg_t point_seg(const vfi_classify_t *cls, uint32_t i, uint32_t slab_q16);
static vfi_seg_t point_lit_seg(const vfi_classify_t *cls, uint32_t i, uint32_t slab_q16, const vfi_seg_t *s);
static uint64_t point_depth_q28(const vfi_classify_t *cls, uint32_t i, uint32_t slab_q16);
static uint32_t opacity_q30(uint64_t tau_length_q28);
static inline void store(vfi_table_out_t out, size_t entry, const vfi_seg_t *s);
static inline void store_lit(vfi_table_out_t out, size_t entry, const vfi_seg_t *s);

/* x's sums with y's added, y seen through transmittance t (Q.30): over() below, and the lit builders'
 * front-weighted sums, each of which then stays at most its C or A term by term. */
static inline vfi_seg_t add_behind(const vfi_seg_t *x, uint64_t t, const vfi_seg_t *y)
{
    vfi_seg_t s;
    s.r = x->r + (uint32_t)((t * y->r + HALF_Q30) >> 30);
    s.g = x->g + (uint32_t)((t * y->g + HALF_Q30) >> 30);
    s.b = x->b + (uint32_t)((t * y->b + HALF_Q30) >> 30);
    s.a = x->a + (uint32_t)((t * y->a + HALF_Q30) >> 30);
    return s;
}

/* Front to back: x in front of y. Every value stays at most 1.0, the bound table_store.h needs: if C <= A <= 1
 * for x and y, then A' = A_x + round((1 - A_x) A_y) <= A_x + (1 - A_x) = 1 (the rounded value of a number at
 * most the integer 1 - A_x is at most it) and C' = C_x + round((1 - A_x) C_y) <= A' (rounding is monotonic).
 * point_seg's and the brute force's intervals start with C = round(c a) <= a <= 1, since c, w <= 1. */
static inline vfi_seg_t over(const vfi_seg_t *x, const vfi_seg_t *y)
{
    return add_behind(x, ONE_Q30 - x->a, y);
}

void vfi_point_table(const vfi_classify_t *cls, uint32_t slab_q16, vfi_table_out_t out)
{
    vfi_point_entries(cls, slab_q16, out, 1);
}

void vfi_point_entries(const vfi_classify_t *cls, uint32_t slab_q16, vfi_table_out_t out, size_t stride)
{
    if (!vfi_table_out_lit(out)) {
        for (uint32_t i = 0; i < cls->n; i++) {
            vfi_seg_t s = point_seg(cls, i, slab_q16);
            store(out, i * stride, &s);
        }
        return;
    }
    for (uint32_t i = 0; i < cls->n; i++) {
        vfi_seg_t s = point_seg(cls, i, slab_q16), l = point_lit_seg(cls, i, slab_q16, &s);
        store(out, i * stride, &s);
        store_lit(out, i * stride, &l);
    }
}

#if VF_TABLE_ORACLE
static void bruteforce_lit(const vfi_classify_t *cls, uint32_t slab_q16, vfi_table_out_t out);

/* The oracle: docs/algorithm.md section 2 read literally, each entry on its own. It shares nothing with the
 * incremental builder (preint.c) but the exponential, the classification and the final rounding (table_store.h),
 * so that a slip in how that one groups or evaluates intervals cannot hide in both. */
void vfi_preint_table_bruteforce(const vfi_classify_t *cls, uint32_t slab_q16, const vfi_table_scratch_t *scratch,
                                 vfi_table_out_t out)
{
    const uint32_t n = cls->n;
    (void)scratch;
    if (vfi_table_out_lit(out)) {
        bruteforce_lit(cls, slab_q16, out);
        return;
    }
    for (uint32_t f = 0; f < n; f++)
        for (uint32_t b = 0; b < n; b++) {
            vfi_seg_t acc;
            if (f == b) {
                acc = point_seg(cls, f, slab_q16);
            } else {
                uint32_t r = f < b ? b - f : f - b;
                uint64_t length_q28 = vfi_udiv64(((uint64_t)slab_q16 << 12) + r / 2, r); /* d / r */
                acc.r = acc.g = acc.b = acc.a = 0;
                for (uint32_t k = 0; k < r; k++) { /* the intervals from f towards b, front to back */
                    uint32_t m = f < b ? f + k : f - 1 - k;
                    uint64_t mean_q24 = ((uint64_t)cls->tau_q28[m] + cls->tau_q28[m + 1] + 16) >> 5;
                    vfi_seg_t iv;
                    iv.a = mean_q24 ? opacity_q30((mean_q24 * length_q28 + (UINT64_C(1) << 23)) >> 24) : 0;
                    iv.r = (uint32_t)(((uint64_t)cls->weight_q30[m * 3 + 0] * iv.a + HALF_Q30) >> 30);
                    iv.g = (uint32_t)(((uint64_t)cls->weight_q30[m * 3 + 1] * iv.a + HALF_Q30) >> 30);
                    iv.b = (uint32_t)(((uint64_t)cls->weight_q30[m * 3 + 2] * iv.a + HALF_Q30) >> 30);
                    acc = over(&acc, &iv);
                }
            }
            store(out, (size_t)f * n + b, &acc);
        }
}

/* The same with docs/algorithm.md section 7's front-weighted sums (and alpha t(x), tables.h, shared with the
 * incremental builder as the exponential is): piece k of r adds T_k C_k (1 - theta_k) and T_k alpha_k
 * (1 - theta_k), with alpha_k (1 - theta_k) = ((r - k) alpha_k - alpha_k t(x_k)) / r rounded once, at most
 * alpha_k. Apart from the unlit loop so that the oracle's speed is as it was; its main values are that loop's. */
static void bruteforce_lit(const vfi_classify_t *cls, uint32_t slab_q16, vfi_table_out_t out)
{
    const uint32_t n = cls->n;
    for (uint32_t f = 0; f < n; f++)
        for (uint32_t b = 0; b < n; b++) {
            vfi_seg_t acc, front;
            if (f == b) {
                acc = point_seg(cls, f, slab_q16);
                front = point_lit_seg(cls, f, slab_q16, &acc);
            } else {
                uint32_t r = f < b ? b - f : f - b;
                uint64_t length_q28 = vfi_udiv64(((uint64_t)slab_q16 << 12) + r / 2, r); /* d / r */
                acc.r = acc.g = acc.b = acc.a = 0;
                front = acc;
                for (uint32_t k = 0; k < r; k++) {
                    uint32_t m = f < b ? f + k : f - 1 - k;
                    uint64_t mean_q24 = ((uint64_t)cls->tau_q28[m] + cls->tau_q28[m + 1] + 16) >> 5;
                    const uint64_t x = (mean_q24 * length_q28 + (UINT64_C(1) << 23)) >> 24;
                    vfi_seg_t iv, piece;
                    iv.a = mean_q24 ? opacity_q30(x) : 0;
                    piece.a = (uint32_t)vfi_udiv64((uint64_t)(r - k) * iv.a -
                                                       vfi_emission_depth_q30(x, (uint32_t)(ONE_Q30 - iv.a)) + r / 2,
                                                   r);
                    iv.r = (uint32_t)(((uint64_t)cls->weight_q30[m * 3 + 0] * iv.a + HALF_Q30) >> 30);
                    iv.g = (uint32_t)(((uint64_t)cls->weight_q30[m * 3 + 1] * iv.a + HALF_Q30) >> 30);
                    iv.b = (uint32_t)(((uint64_t)cls->weight_q30[m * 3 + 2] * iv.a + HALF_Q30) >> 30);
                    piece.r = (uint32_t)(((uint64_t)cls->weight_q30[m * 3 + 0] * piece.a + HALF_Q30) >> 30);
                    piece.g = (uint32_t)(((uint64_t)cls->weight_q30[m * 3 + 1] * piece.a + HALF_Q30) >> 30);
                    piece.b = (uint32_t)(((uint64_t)cls->weight_q30[m * 3 + 2] * piece.a + HALF_Q30) >> 30);
                    front = add_behind(&front, ONE_Q30 - acc.a, &piece);
                    acc = over(&acc, &iv);
                }
            }
            store(out, (size_t)f * n + b, &acc);
            store_lit(out, (size_t)f * n + b, &front);
        }
}
#endif

/* 1 - exp(-x), x in Q.28; Q.30. */
static uint32_t opacity_q30(uint64_t tau_length_q28)
{
    return (uint32_t)(ONE_Q30 - vfi_exp_neg_q28(tau_length_q28));
}

/* The optical depth tau_i d of entry i's point segment, Q.28. */
static uint64_t point_depth_q28(const vfi_classify_t *cls, uint32_t i, uint32_t slab_q16)
{
    return ((uint64_t)cls->tau_q28[i] * slab_q16 + (1u << 15)) >> 16;
}

/* Entry i of the point table: a = 1 - exp(-tau_i d), C = c_i a. */
static vfi_seg_t point_seg(const vfi_classify_t *cls, uint32_t i, uint32_t slab_q16)
{
    vfi_seg_t s;
    s.a = opacity_q30(point_depth_q28(cls, i, slab_q16));
    s.r = (uint32_t)(((uint64_t)cls->colour_q30[i * 3 + 0] * s.a + HALF_Q30) >> 30);
    s.g = (uint32_t)(((uint64_t)cls->colour_q30[i * 3 + 1] * s.a + HALF_Q30) >> 30);
    s.b = (uint32_t)(((uint64_t)cls->colour_q30[i * 3 + 2] * s.a + HALF_Q30) >> 30);
    return s;
}

static inline void store(vfi_table_out_t out, size_t entry, const vfi_seg_t *s)
{
    vfi_store_entry(&out, entry, s->r, s->g, s->b, s->a);
}

/* Entry i's front-weighted values (docs/algorithm.md section 7), from its point segment s: the uniform slab of
 * depth x = tau_i d, S_f = a (1 - t(x)) = a - alpha t(x) exactly, D_f = c_i S_f. S_f <= a and D_f <= C, since c_i
 * times less rounds to no more. */
static vfi_seg_t point_lit_seg(const vfi_classify_t *cls, uint32_t i, uint32_t slab_q16, const vfi_seg_t *s)
{
    vfi_seg_t l;
    l.a = s->a - vfi_emission_depth_q30(point_depth_q28(cls, i, slab_q16), (uint32_t)(ONE_Q30 - s->a));
    l.r = (uint32_t)(((uint64_t)cls->colour_q30[i * 3 + 0] * l.a + HALF_Q30) >> 30);
    l.g = (uint32_t)(((uint64_t)cls->colour_q30[i * 3 + 1] * l.a + HALF_Q30) >> 30);
    l.b = (uint32_t)(((uint64_t)cls->colour_q30[i * 3 + 2] * l.a + HALF_Q30) >> 30);
    return l;
}

/* inline, unlike store(): no code in builds without lit tables, where the callers are dead */
static inline void store_lit(vfi_table_out_t out, size_t entry, const vfi_seg_t *s)
{
    vfi_store_lit_q30(out, entry, s->r, s->g, s->b, s->a);
}

void vfi_correction_lut(uint32_t rho_q16, uint16_t *f_q15, uint32_t *g_q16)
{
    for (uint32_t k = 0; k < VFI_LUT_KNOTS; k++) {
        /* F = 1 - exp(rho ln(1 - a)), a = k / 1024; 1 - a = (1024 - k) / 1024 is at least 2^-10 before the end */
        uint32_t f_q30 = (uint32_t)ONE_Q30;
        if (k < 1024) {
            uint64_t neg_ln_q28 = vfi_neg_ln_q32((uint64_t)(1024 - k) << 22);
            f_q30 = (uint32_t)(ONE_Q30 - vfi_exp_neg_q28((neg_ln_q28 * rho_q16 + (1u << 15)) >> 16));
        }
        f_q15[k] = (uint16_t)((f_q30 + (1u << 14)) >> 15);
        /* G = F / a = F 1024 / k, in Q16.16 F_q30 2^10 2^16 / (2^30 k) = F_q30 / (16 k); at a = 0 its limit, rho */
        g_q16[k] = k == 0 ? rho_q16 : (uint32_t)((f_q30 + 8u * k) / (16u * k));
    }
}

#if VF_VIEW_TABLE
/* vfi_correct on one entry, written out so that nothing goes through memory but the entries */
static inline void correct_entry(const uint16_t *lut_f, const uint32_t *lut_g, const uint16_t *in, uint16_t *out)
{
    uint32_t fa;
    const uint64_t g = vfi_lut_at(lut_f, lut_g, in[3], &fa);
    for (int k = 0; k < 3; k++) { /* below 2^16 (C' = C a' / a, C <= a + a few LSB), but kept so regardless */
        const uint32_t c = vfi_lut_colour(in[k], g);
        out[k] = (uint16_t)(c > 0xFFFFu ? 0xFFFFu : c);
    }
    out[3] = (uint16_t)fa; /* at most 32768 */
}

void vfi_view_table(const uint16_t *lut_f, const uint32_t *lut_g, const uint16_t *table, uint16_t *view,
                    size_t count)
{
    for (size_t e = 0; e < count * 4; e += 4)
        correct_entry(lut_f, lut_g, table + e, view + e);
}

/* correct_entry with the entry's front-weighted values lit, which take the colour's factor G(a) */
static inline void correct_entry_lit(const uint16_t *lut_f, const uint32_t *lut_g, const uint16_t *in,
                                     const uint16_t *lit, uint16_t *out, uint16_t *lit_out)
{
    uint32_t fa;
    const uint64_t g = vfi_lut_at(lut_f, lut_g, in[3], &fa);
    for (int k = 0; k < 3; k++) {
        const uint32_t c = vfi_lut_colour(in[k], g);
        out[k] = (uint16_t)(c > 0xFFFFu ? 0xFFFFu : c);
    }
    out[3] = (uint16_t)fa;
    for (int k = 0; k < 4; k++) { /* at most their C or a times G, kept below 2^16 as those */
        const uint32_t c = vfi_lut_colour(lit[k], g);
        lit_out[k] = (uint16_t)(c > 0xFFFFu ? 0xFFFFu : c);
    }
}

void vfi_view_table_lit(const uint16_t *lut_f, const uint32_t *lut_g, const uint16_t *table, const uint16_t *lit,
                        uint16_t *view, uint16_t *lit_view, size_t count)
{
    for (size_t e = 0; e < count * 4; e += 4)
        correct_entry_lit(lut_f, lut_g, table + e, lit + e, view + e, lit_view + e);
}

#if VF_MAX_TABLE_PARTS > 1
void vfi_view_table_lit_part(const uint16_t *lut_f, const uint32_t *lut_g, const uint16_t *table, const uint16_t *lit,
                             uint16_t *view, uint16_t *lit_view, uint32_t n, uint32_t part, uint32_t parts)
{
    const size_t stride = ((size_t)n + 1) * 4;
    if (part == 0)
        for (size_t e = 0; e < (size_t)n * stride; e += stride)
            correct_entry_lit(lut_f, lut_g, table + e, lit + e, view + e, lit_view + e);
    for (uint32_t r = part + 1; r < n; r += parts) /* entries (f, f + r) and (f + r, f) */
        for (size_t f = 0, up = (size_t)r * 4, down = (size_t)r * n * 4; f < n - r; f++, up += stride, down += stride) {
            correct_entry_lit(lut_f, lut_g, table + up, lit + up, view + up, lit_view + up);
            correct_entry_lit(lut_f, lut_g, table + down, lit + down, view + down, lit_view + down);
        }
}

void vfi_view_table_part(const uint16_t *lut_f, const uint32_t *lut_g, const uint16_t *table, uint16_t *view,
                         uint32_t n, uint32_t part, uint32_t parts)
{
    const size_t stride = ((size_t)n + 1) * 4;
    if (part == 0)
        for (size_t e = 0; e < (size_t)n * stride; e += stride)
            correct_entry(lut_f, lut_g, table + e, view + e);
    for (uint32_t r = part + 1; r < n; r += parts) /* entries (f, f + r) and (f + r, f) */
        for (size_t f = 0, up = (size_t)r * 4, down = (size_t)r * n * 4; f < n - r; f++, up += stride, down += stride) {
            correct_entry(lut_f, lut_g, table + up, view + up);
            correct_entry(lut_f, lut_g, table + down, view + down);
        }
}
#endif
#endif

/* ---------------------------------------------------------------------------------------------------------- */
/* The public entry points (volfix.h): tables on their own, classification and scratch from the caller's arena. */

size_t vf_table_scratch_bytes(uint32_t n)
{
    if (n < VF_MIN_TABLE || n > VF_MAX_TABLE)
        return 0;
    /* the lit build's scratch, which holds the others' (tables.h), in builds with it */
    return VFI_ALIGN + vfi_classify_bytes(n) +
           (VF_LIT_TABLES ? vfi_table_scratch_lit_bytes(n) : vfi_table_scratch_bytes(n));
}

static vf_status_t build(const vf_tf_t *tf, uint32_t n, uint32_t slab_q16, int which, vf_arena_t *arena,
                         uint16_t *out, uint16_t *lit_out)
{
    if (!tf || !arena || !out)
        return VF_ERR_NULL;
    if (n < VF_MIN_TABLE || n > VF_MAX_TABLE || slab_q16 == 0 || slab_q16 > (UINT32_C(128) << 16))
        return VF_ERR_ARG;
    size_t mark = arena->used;
    vfi_classify_t cls;
    vfi_table_scratch_t scratch;
    vf_status_t s = vfi_classify_alloc(&cls, n, VF_LOOKUP_NEAREST, arena);
    if (s == VF_OK)
        s = VF_LIT_TABLES && lit_out ? vfi_table_scratch_alloc_lit(&scratch, n, arena)
                                     : vfi_table_scratch_alloc(&scratch, n, arena);
    if (s == VF_OK)
        s = vfi_classify(&cls, tf);
    if (s == VF_OK) {
        vfi_table_out_t to = {out, NULL, 0, lit_out, NULL, NULL, NULL};
        if (which == 0)
            vfi_point_table(&cls, slab_q16, to);
        else if (which == 1 + VF_BUILDER_INCREMENTAL)
            vfi_preint_table_incremental(&cls, slab_q16, &scratch, to);
#if VF_TABLE_ORACLE
        else
            vfi_preint_table_bruteforce(&cls, slab_q16, &scratch, to);
#endif
    }
    vfi_arena_rewind(arena, mark);
    return s;
}

vf_status_t vf_table_point(const vf_tf_t *tf, uint32_t n, uint32_t slab_q16, vf_arena_t *scratch, uint16_t *out)
{
    return build(tf, n, slab_q16, 0, scratch, out, NULL);
}

vf_status_t vf_table_preint(const vf_tf_t *tf, uint32_t n, uint32_t slab_q16, vf_builder_t builder,
                            vf_arena_t *scratch, uint16_t *out)
{
    if ((unsigned)builder >= VF_BUILDER_COUNT)
        return VF_ERR_ARG;
    if (builder == VF_BUILDER_BRUTEFORCE && !VF_TABLE_ORACLE)
        return VF_ERR_UNSUPPORTED;
    return build(tf, n, slab_q16, 1 + (int)builder, scratch, out, NULL);
}

vf_status_t vf_table_preint_lit(const vf_tf_t *tf, uint32_t n, uint32_t slab_q16, vf_builder_t builder,
                                vf_arena_t *scratch, uint16_t *out, uint16_t *lit_out)
{
    if (!lit_out)
        return VF_ERR_NULL;
    if ((unsigned)builder >= VF_BUILDER_COUNT)
        return VF_ERR_ARG;
    if ((builder == VF_BUILDER_BRUTEFORCE && !VF_TABLE_ORACLE) || !VF_LIT_TABLES)
        return VF_ERR_UNSUPPORTED;
    return build(tf, n, slab_q16, 1 + (int)builder, scratch, out, lit_out);
}
