/*
 * tables.c: point and pre-integrated tables (docs/algorithm.md, section 2), integer only.
 *
 * Accumulation is Q.30 (1.0 = 2^30) so that compositing hundreds of intervals loses nothing visible; the
 * entries are rounded to their format once, at the end.
 */
#include "arena.h"
#include "fixmath.h"
#include "tables.h"

#define ONE_Q30 (UINT64_C(1) << 30)
#define HALF_Q30 (UINT64_C(1) << 29)

static vfi_seg_t point_seg(const vfi_classify_t *cls, uint32_t i, uint32_t slab_q16);
static uint32_t opacity_q30(uint64_t tau_length_q28);
static void intervals_for_length(const vfi_classify_t *cls, uint64_t length_q28, vfi_seg_t *out);
static void block_composites(const vfi_table_scratch_t *scratch, uint32_t count, uint32_t r);
static inline void store(vfi_table_out_t out, size_t entry, const vfi_seg_t *s);

size_t vfi_table_scratch_bytes(uint32_t n)
{
    return 5 * vfi_arena_block(sizeof(vfi_seg_t) * (n - 1)) + vfi_arena_block(sizeof(uint16_t) * n);
}

vf_status_t vfi_table_scratch_alloc(vfi_table_scratch_t *scratch, uint32_t n, vf_arena_t *arena)
{
    scratch->interval = vfi_arena_alloc(arena, sizeof(vfi_seg_t) * (n - 1));
    scratch->prefix = vfi_arena_alloc(arena, sizeof(vfi_seg_t) * (n - 1));
    scratch->suffix = vfi_arena_alloc(arena, sizeof(vfi_seg_t) * (n - 1));
    scratch->back_prefix = vfi_arena_alloc(arena, sizeof(vfi_seg_t) * (n - 1));
    scratch->back_suffix = vfi_arena_alloc(arena, sizeof(vfi_seg_t) * (n - 1));
    scratch->visible_below = vfi_arena_alloc(arena, sizeof(uint16_t) * n);
    return scratch->interval && scratch->prefix && scratch->suffix && scratch->back_prefix && scratch->back_suffix &&
                   scratch->visible_below
               ? VF_OK
               : VF_ERR_NOMEM;
}

/* Front to back: x in front of y. */
static inline vfi_seg_t over(const vfi_seg_t *x, const vfi_seg_t *y)
{
    uint64_t t = ONE_Q30 - x->a;
    vfi_seg_t s;
    s.r = x->r + (uint32_t)((t * y->r + HALF_Q30) >> 30);
    s.g = x->g + (uint32_t)((t * y->g + HALF_Q30) >> 30);
    s.b = x->b + (uint32_t)((t * y->b + HALF_Q30) >> 30);
    s.a = x->a + (uint32_t)((t * y->a + HALF_Q30) >> 30);
    return s;
}

void vfi_point_table(const vfi_classify_t *cls, uint32_t slab_q16, vfi_table_out_t out)
{
    for (uint32_t i = 0; i < cls->n; i++) {
        vfi_seg_t s = point_seg(cls, i, slab_q16);
        store(out, i, &s);
    }
}

/* The oracle: docs/algorithm.md section 2 read literally, each entry on its own. It shares nothing with the
 * incremental builder but the exponential and the classification, so that a slip in how that one groups or
 * evaluates intervals cannot hide in both. */
void vfi_preint_table_bruteforce(const vfi_classify_t *cls, uint32_t slab_q16, const vfi_table_scratch_t *scratch,
                                 vfi_table_out_t out)
{
    const uint32_t n = cls->n;
    (void)scratch;
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

void vfi_preint_table_incremental(const vfi_classify_t *cls, uint32_t slab_q16, const vfi_table_scratch_t *scratch,
                                  vfi_table_out_t out)
{
    const uint32_t n = cls->n, count = n - 1; /* count intervals */
    const vfi_seg_t *pre = scratch->prefix, *suf = scratch->suffix;
    const vfi_seg_t *back_pre = scratch->back_prefix, *back_suf = scratch->back_suffix;
    for (uint32_t i = 0; i < n; i++) {
        vfi_seg_t s = point_seg(cls, i, slab_q16);
        store(out, (size_t)i * n + i, &s);
    }
    /* visible_below[m]: intervals below m with some extinction; a window without one is exactly zero */
    uint16_t *below = scratch->visible_below;
    below[0] = 0;
    for (uint32_t m = 0; m < count; m++)
        below[m + 1] = (uint16_t)(below[m] + ((cls->tau_q28[m] | cls->tau_q28[m + 1]) != 0));

    for (uint32_t r = 1; r < n; r++) {
        intervals_for_length(cls, vfi_udiv64(((uint64_t)slab_q16 << 12) + r / 2, r), scratch->interval);
        block_composites(scratch, count, r);
        /* The window of intervals f .. f+r-1 is the suffix of f's block in front of the prefix of the next block
         * up to f+r-1 (or, starting on a block boundary, one whole block); met from the back (front entry f + r,
         * back entry f) it is the back prefix of that next block in front of the back suffix of f's block. */
        for (uint32_t f = 0, in_block = 0; f + r < n; f++, in_block = in_block + 1 == r ? 0 : in_block + 1) {
            vfi_seg_t up, down;
            uint32_t split = f + r - in_block; /* where the next block starts (f + r when f starts one) */
            if (below[f + r] == below[f]) {
                /* field by field: copying a zero aggregate can compile to a memset call (gcc -Os, Cortex-M4) */
                up.r = up.g = up.b = up.a = 0;
                down = up;
            } else if (in_block == 0 || below[f + r] == below[split]) { /* nothing visible in the prefix part */
                up = suf[f];
                down = back_suf[f];
            } else if (below[split] == below[f]) { /* nothing visible in the suffix part */
                up = pre[f + r - 1];
                down = back_pre[f + r - 1];
            } else {
                up = over(&suf[f], &pre[f + r - 1]);
                down = over(&back_pre[f + r - 1], &back_suf[f]);
            }
            store(out, (size_t)f * n + f + r, &up);
            store(out, (size_t)(f + r) * n + f, &down);
        }
    }
}

/* One step of the suffix chains (from the block's end down to m) and of the prefix chains (from the block's start
 * up to m). An empty interval (opacity 0, so colour 0) leaves a composite as it was: no arithmetic, which is
 * most of the work saved for transfer functions with narrow peaks. */
static inline void chain_down(const vfi_seg_t *iv, vfi_seg_t *suf, vfi_seg_t *back_suf, uint32_t m)
{
    if (iv[m].a == 0) {
        suf[m] = suf[m + 1];
        back_suf[m] = back_suf[m + 1];
    } else {
        suf[m] = over(&iv[m], &suf[m + 1]);
        back_suf[m] = over(&back_suf[m + 1], &iv[m]);
    }
}

static inline void chain_up(const vfi_seg_t *iv, vfi_seg_t *pre, vfi_seg_t *back_pre, uint32_t m)
{
    if (iv[m].a == 0) {
        pre[m] = pre[m - 1];
        back_pre[m] = back_pre[m - 1];
    } else {
        pre[m] = over(&pre[m - 1], &iv[m]);
        back_pre[m] = over(&iv[m], &back_pre[m - 1]);
    }
}

/* In blocks of r intervals, for m in a block: suffix[m] = m .. end-1 front to back and back_suffix[m] = end-1 .. m
 * back to front; prefix[m] = start .. m and back_prefix[m] = m .. start. Windows start in a block (suffixes) and
 * end in the next (prefixes), so suffixes are needed only in blocks that start at or below the last window's
 * start, n - 1 - r, and prefixes only from the second block on: about half of each. A block's suffixes and the
 * next block's prefixes are four independent chains, run in one loop so that the processor overlaps them. */
static void block_composites(const vfi_table_scratch_t *sc, uint32_t count, uint32_t r)
{
    const vfi_seg_t *iv = sc->interval;
    vfi_seg_t *pre = sc->prefix, *suf = sc->suffix, *back_pre = sc->back_prefix, *back_suf = sc->back_suffix;
    const uint32_t last_start = count - r; /* the last window starts here (n - 1 - r) */
    for (uint32_t s0 = 0; s0 <= last_start; s0 += r) {
        uint32_t s_len = s0 + r < count ? r : count - s0; /* suffixes of this block */
        uint32_t p0 = s0 + r, p_len = p0 < count ? (p0 + r < count ? r : count - p0) : 0; /* prefixes of the next */
        uint32_t top = s0 + s_len - 1;
        suf[top] = back_suf[top] = iv[top];
        if (p_len)
            pre[p0] = back_pre[p0] = iv[p0];
        uint32_t both = p_len < s_len ? p_len : s_len, k = 1;
        for (; k < both; k++) {
            uint32_t down = top - k, up = p0 + k;
            chain_down(iv, suf, back_suf, down);
            chain_up(iv, pre, back_pre, up);
        }
        for (uint32_t j = k; j < s_len; j++)
            chain_down(iv, suf, back_suf, top - j);
        for (uint32_t j = k; j < p_len; j++)
            chain_up(iv, pre, back_pre, p0 + j);
    }
}

/* 1 - exp(-x), x in Q.28; Q.30. */
static uint32_t opacity_q30(uint64_t tau_length_q28)
{
    return (uint32_t)(ONE_Q30 - vfi_exp_neg_q28(tau_length_q28));
}

/* Entry i of the point table: a = 1 - exp(-tau_i d), C = c_i a. */
static vfi_seg_t point_seg(const vfi_classify_t *cls, uint32_t i, uint32_t slab_q16)
{
    vfi_seg_t s;
    s.a = opacity_q30(((uint64_t)cls->tau_q28[i] * slab_q16 + (1u << 15)) >> 16);
    s.r = (uint32_t)(((uint64_t)cls->colour_q30[i * 3 + 0] * s.a + HALF_Q30) >> 30);
    s.g = (uint32_t)(((uint64_t)cls->colour_q30[i * 3 + 1] * s.a + HALF_Q30) >> 30);
    s.b = (uint32_t)(((uint64_t)cls->colour_q30[i * 3 + 2] * s.a + HALF_Q30) >> 30);
    return s;
}

/* Opacity and premultiplied colour of every interval for pieces of the given length (Q.28 in d_ref). */
static void intervals_for_length(const vfi_classify_t *cls, uint64_t length_q28, vfi_seg_t *out)
{
    for (uint32_t m = 0; m + 1 < cls->n; m++) {
        /* mean extinction (t0 + t1) / 2 in Q.24 times the length in Q.28: Q.52, back to Q.28 */
        uint64_t mean_q24 = ((uint64_t)cls->tau_q28[m] + cls->tau_q28[m + 1] + 16) >> 5;
        if (mean_q24 == 0) { /* invisible interval: no exp needed */
            out[m].r = out[m].g = out[m].b = out[m].a = 0;
            continue;
        }
        uint32_t a = opacity_q30((mean_q24 * length_q28 + (UINT64_C(1) << 23)) >> 24);
        out[m].a = a;
        out[m].r = (uint32_t)(((uint64_t)cls->weight_q30[m * 3 + 0] * a + HALF_Q30) >> 30);
        out[m].g = (uint32_t)(((uint64_t)cls->weight_q30[m * 3 + 1] * a + HALF_Q30) >> 30);
        out[m].b = (uint32_t)(((uint64_t)cls->weight_q30[m * 3 + 2] * a + HALF_Q30) >> 30);
    }
}

static inline uint16_t q30_to_q15(uint32_t v)
{
    uint32_t q = (v + (1u << 14)) >> 15;
    return (uint16_t)(q > VFI_ONE_Q15 ? VFI_ONE_Q15 : q);
}

static inline uint8_t q30_to_u8(uint32_t v)
{
    uint64_t q = ((uint64_t)v * 255 + HALF_Q30) >> 30; /* round(255 x) */
    return (uint8_t)(q > 255 ? 255 : q);
}

/* round((2^B - 1) x) / (2^B - 1), back in Q1.15 */
static inline uint16_t q30_to_grid(uint32_t v, uint32_t bits)
{
    uint64_t levels = (UINT64_C(1) << bits) - 1;
    uint64_t q = ((uint64_t)v * levels + HALF_Q30) >> 30;
    q = q > levels ? levels : q;
    return (uint16_t)((q * VFI_ONE_Q15 + levels / 2) / levels);
}

static inline void store(vfi_table_out_t out, size_t entry, const vfi_seg_t *s)
{
    if (out.q15 && out.grid_bits) {
        uint16_t *e = out.q15 + entry * 4;
        e[0] = q30_to_grid(s->r, out.grid_bits);
        e[1] = q30_to_grid(s->g, out.grid_bits);
        e[2] = q30_to_grid(s->b, out.grid_bits);
        e[3] = q30_to_grid(s->a, out.grid_bits);
    } else if (out.q15) {
        uint16_t *e = out.q15 + entry * 4;
        e[0] = q30_to_q15(s->r);
        e[1] = q30_to_q15(s->g);
        e[2] = q30_to_q15(s->b);
        e[3] = q30_to_q15(s->a);
    } else {
        uint8_t *e = out.u8 + entry * 4;
        e[0] = q30_to_u8(s->r);
        e[1] = q30_to_u8(s->g);
        e[2] = q30_to_u8(s->b);
        e[3] = q30_to_u8(s->a);
    }
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

/* ---------------------------------------------------------------------------------------------------------- */
/* The public entry points (volfix.h): tables on their own, classification and scratch from the caller's arena. */

size_t vf_table_scratch_bytes(uint32_t n)
{
    if (n < VF_MIN_TABLE || n > VF_MAX_TABLE)
        return 0;
    return VFI_ALIGN + vfi_classify_bytes(n) + vfi_table_scratch_bytes(n);
}

static vf_status_t build(const vf_tf_t *tf, uint32_t n, uint32_t slab_q16, int which, vf_arena_t *arena,
                         uint16_t *out)
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
        s = vfi_table_scratch_alloc(&scratch, n, arena);
    if (s == VF_OK)
        s = vfi_classify(&cls, tf);
    if (s == VF_OK) {
        vfi_table_out_t to = {out, NULL, 0};
        if (which == 0)
            vfi_point_table(&cls, slab_q16, to);
        else if (which == 1 + VF_BUILDER_INCREMENTAL)
            vfi_preint_table_incremental(&cls, slab_q16, &scratch, to);
        else
            vfi_preint_table_bruteforce(&cls, slab_q16, &scratch, to);
    }
    vfi_arena_rewind(arena, mark);
    return s;
}

vf_status_t vf_point_table(const vf_tf_t *tf, uint32_t n, uint32_t slab_q16, vf_arena_t *scratch, uint16_t *out)
{
    return build(tf, n, slab_q16, 0, scratch, out);
}

vf_status_t vf_preint_table(const vf_tf_t *tf, uint32_t n, uint32_t slab_q16, vf_builder_t builder,
                            vf_arena_t *scratch, uint16_t *out)
{
    if ((unsigned)builder >= VF_BUILDER_COUNT)
        return VF_ERR_ARG;
    return build(tf, n, slab_q16, 1 + (int)builder, scratch, out);
}
