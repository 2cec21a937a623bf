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

/* One diagonal of the 2D table while the incremental builder makes it: windows of r intervals, whose pieces
 * are all d / r long. */
typedef struct diagonal {
    const vfi_seg_t *iv;       /* [n - 1] the intervals for pieces of that length */
    const uint16_t *visible;   /* which intervals can be seen at all, ascending */
    vfi_seg_t *suf, *back_suf; /* a block's suffix composites, by position in visible */
    uint32_t n, r, last_f;     /* entries a table axis; intervals a window; where the last window starts */
    vfi_table_out_t out;
} diagonal_t;

static vfi_seg_t point_seg(const vfi_classify_t *cls, uint32_t i, uint32_t slab_q16);
static uint32_t opacity_q30(uint64_t tau_length_q28);
static uint32_t list_visible(const vfi_classify_t *cls, vfi_seg_t *iv, uint16_t *visible);
static void intervals_for_length(const vfi_classify_t *cls, uint64_t length_q28, const uint16_t *visible,
                                 uint32_t visible_count, vfi_seg_t *out);
static uint64_t piece_length_q28(uint32_t slab_q16, uint32_t r);
static void block_suffixes(const diagonal_t *d, uint32_t k_lo, uint32_t k_hi);
static void join_block(const diagonal_t *d, uint32_t s0, uint32_t k_lo, uint32_t k_hi);
static inline void store(vfi_table_out_t out, size_t entry, const vfi_seg_t *s);
static inline void store_pair(vfi_table_out_t out, size_t up, size_t down, const vfi_seg_t *s, const vfi_seg_t *back_s);
static inline void copy_pair(vfi_table_out_t out, size_t up, size_t down, size_t distance);

size_t vfi_table_scratch_bytes(uint32_t n)
{
    return 3 * vfi_arena_block(sizeof(vfi_seg_t) * (n - 1)) + vfi_arena_block(sizeof(uint16_t) * n);
}

vf_status_t vfi_table_scratch_alloc(vfi_table_scratch_t *scratch, uint32_t n, vf_arena_t *arena)
{
    scratch->interval = vfi_arena_alloc(arena, sizeof(vfi_seg_t) * (n - 1));
    scratch->suffix = vfi_arena_alloc(arena, sizeof(vfi_seg_t) * (n - 1));
    scratch->back_suffix = vfi_arena_alloc(arena, sizeof(vfi_seg_t) * (n - 1));
    scratch->visible = vfi_arena_alloc(arena, sizeof(uint16_t) * n);
    return scratch->interval && scratch->suffix && scratch->back_suffix && scratch->visible ? VF_OK : VF_ERR_NOMEM;
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
    for (uint32_t i = 0; i < n; i++) {
        vfi_seg_t s = point_seg(cls, i, slab_q16);
        store(out, (size_t)i * n + i, &s);
    }
    const uint32_t visible_count = list_visible(cls, scratch->interval, scratch->visible);
    diagonal_t d;
    d.iv = scratch->interval;
    d.visible = scratch->visible;
    d.suf = scratch->suffix;
    d.back_suf = scratch->back_suffix;
    d.n = n;
    d.out = out;
    for (uint32_t r = 1; r < n; r++) {
        intervals_for_length(cls, piece_length_q28(slab_q16, r), scratch->visible, visible_count, scratch->interval);
        d.r = r;
        d.last_f = count - r;
        /* The windows of r intervals, f .. f+r-1, start at f = 0 .. count - r. Cut into blocks of r, each block
         * that holds a window's start is whole. k_lo .. k_hi - 1: where the block's visible intervals are listed. */
        for (uint32_t s0 = 0, k_lo = 0; s0 <= d.last_f; s0 += r) {
            uint32_t k_hi = k_lo;
            while (k_hi < visible_count && d.visible[k_hi] < s0 + r)
                k_hi++;
            block_suffixes(&d, k_lo, k_hi);
            join_block(&d, s0, k_lo, k_hi);
            k_lo = k_hi;
        }
    }
}

/* The composites of the block's visible intervals k_lo .. k_hi - 1 (positions in the list) from each to the
 * block's end: suffix[k] front to back and back_suffix[k] back to front. The block's other intervals are zero
 * and leave a composite as it is (see join_block), so skipping them changes no bit; for transfer functions
 * with narrow peaks that is most of the work. */
static void block_suffixes(const diagonal_t *d, uint32_t k_lo, uint32_t k_hi)
{
    const vfi_seg_t *iv = d->iv;
    const uint16_t *visible = d->visible;
    vfi_seg_t *suf = d->suf, *back_suf = d->back_suf;
    if (k_hi == k_lo)
        return;
    /* the running composites stay in registers: each step waits for the last, not for a store to it */
    vfi_seg_t acc = iv[visible[k_hi - 1]], back_acc = acc;
    suf[k_hi - 1] = back_suf[k_hi - 1] = acc;
    for (uint32_t k = k_hi - 1; k-- > k_lo;) {
        const vfi_seg_t *v = &iv[visible[k]];
        acc = over(v, &acc);
        back_acc = over(&back_acc, v);
        suf[k] = acc;
        back_suf[k] = back_acc;
    }
}

/* The entries of the windows that start in the block s0 .. s0+r-1: window f .. f+r-1 is the block's suffix from
 * f in front of the next block's prefix up to f+r-1, or the whole block when f = s0. The prefix grows by one
 * interval a window, so it lives in registers, front to back (pre) and back to front (back_pre); entry
 * (f, f+r) is the suffix in front of pre, entry (f+r, f) back_pre in front of the back suffix.
 * A composite has opacity 0 exactly when all its intervals have, and is then zero in every channel; over()
 * with a zero operand returns the other one exactly, so the joins below skip it without changing a bit. */
static void join_block(const diagonal_t *d, uint32_t s0, uint32_t k_lo, uint32_t k_hi)
{
    const vfi_seg_t *iv = d->iv, *suf = d->suf, *back_suf = d->back_suf;
    const uint16_t *visible = d->visible;
    const uint32_t n = d->n, r = d->r, end = s0 + r - 1 < d->last_f ? s0 + r - 1 : d->last_f;
    const vfi_table_out_t out = d->out;
    size_t up = (size_t)s0 * n + s0 + r, down = (size_t)(s0 + r) * n + s0; /* entries (f, f+r) and (f+r, f) */
    vfi_seg_t pre, back_pre, s, back_s;
    pre.r = pre.g = pre.b = pre.a = 0; /* field by field: a zero aggregate can compile to a memset call */
    back_pre = pre;
    uint32_t k = k_lo; /* where the first visible interval at or above f is listed (k_hi: none) */
    for (uint32_t f = s0;;) {
        while (k < k_hi && visible[k] < f)
            k++;
        const vfi_seg_t *w = &s, *back_w = &back_s;
        if (k == k_hi || suf[k].a == 0) {
            w = &pre;
            back_w = &back_pre;
        } else if (pre.a == 0) {
            w = &suf[k];
            back_w = &back_suf[k];
        } else {
            s = over(&suf[k], &pre);
            back_s = over(&back_pre, &back_suf[k]);
        }
        store_pair(out, up, down, w, back_w);
        /* The next window drops interval f and adds f + r. While both are empty its suffix composites to this
         * one's and its prefix is this one: the same entries. */
        for (; f < end && iv[f].a == 0 && iv[f + r].a == 0; f++) {
            up += n + 1;
            down += n + 1;
            copy_pair(out, up, down, n + 1);
        }
        if (f == end)
            break;
        const vfi_seg_t *v = &iv[f + r];
        if (v->a != 0) {
            pre = over(&pre, v);
            back_pre = over(v, &back_pre);
        }
        f++;
        up += n + 1;
        down += n + 1;
    }
}

/* d / r in Q.28 from d in Q16.16, rounded: (d 2^12 + r / 2) / r. Long division in 16-bit digits, so that each
 * step is a 32-bit division (remainder < r < 2^16, so remainder 2^16 + digit < 2^32) where vfi_udiv64 took
 * 64 shift-and-subtract steps; the quotient is the same. */
static uint64_t piece_length_q28(uint32_t slab_q16, uint32_t r)
{
    uint64_t num = ((uint64_t)slab_q16 << 12) + r / 2, q = 0;
    uint32_t rem = 0;
    for (int shift = 48; shift >= 0; shift -= 16) {
        uint32_t cur = (rem << 16) | (uint32_t)((num >> shift) & 0xFFFFu);
        q = (q << 16) | (cur / r);
        rem = cur % r;
    }
    return q;
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

/* Mean extinction of interval m, (t0 + t1) / 2 in Q.24. */
static inline uint64_t mean_q24(const vfi_classify_t *cls, uint32_t m)
{
    return ((uint64_t)cls->tau_q28[m] + cls->tau_q28[m + 1] + 16) >> 5;
}

/* An interval whose mean extinction rounds to 0 is zero at every length: set it once here, and list the others
 * for intervals_for_length. Returns how many are listed. */
static uint32_t list_visible(const vfi_classify_t *cls, vfi_seg_t *iv, uint16_t *visible)
{
    uint32_t count = 0;
    for (uint32_t m = 0; m + 1 < cls->n; m++) {
        if (mean_q24(cls, m) != 0)
            visible[count++] = (uint16_t)m;
        else
            iv[m].r = iv[m].g = iv[m].b = iv[m].a = 0;
    }
    return count;
}

/* Opacity and premultiplied colour of the listed intervals for pieces of the given length (Q.28 in d_ref). */
static void intervals_for_length(const vfi_classify_t *cls, uint64_t length_q28, const uint16_t *visible,
                                 uint32_t visible_count, vfi_seg_t *out)
{
    for (uint32_t k = 0; k < visible_count; k++) {
        uint32_t m = visible[k];
        /* the mean extinction in Q.24 times the length in Q.28: Q.52, back to Q.28 */
        uint32_t a = opacity_q30((mean_q24(cls, m) * length_q28 + (UINT64_C(1) << 23)) >> 24);
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

static inline void store_q15(uint16_t *e, const vfi_seg_t *s)
{
    e[0] = q30_to_q15(s->r);
    e[1] = q30_to_q15(s->g);
    e[2] = q30_to_q15(s->b);
    e[3] = q30_to_q15(s->a);
}

static inline void store_grid(uint16_t *e, const vfi_seg_t *s, uint32_t bits)
{
    e[0] = q30_to_grid(s->r, bits);
    e[1] = q30_to_grid(s->g, bits);
    e[2] = q30_to_grid(s->b, bits);
    e[3] = q30_to_grid(s->a, bits);
}

static inline void store_u8(uint8_t *e, const vfi_seg_t *s)
{
    e[0] = q30_to_u8(s->r);
    e[1] = q30_to_u8(s->g);
    e[2] = q30_to_u8(s->b);
    e[3] = q30_to_u8(s->a);
}

static inline void store(vfi_table_out_t out, size_t entry, const vfi_seg_t *s)
{
    if (out.q15 && out.grid_bits)
        store_grid(out.q15 + entry * 4, s, out.grid_bits);
    else if (out.q15)
        store_q15(out.q15 + entry * 4, s);
    else
        store_u8(out.u8 + entry * 4, s);
}

/* Entries up and down, the format decided once for the two (two store() calls measured a third more
 * instructions for the whole builder: the compiler does not merge their tests). */
static inline void store_pair(vfi_table_out_t out, size_t up, size_t down, const vfi_seg_t *s, const vfi_seg_t *back_s)
{
    if (out.q15 && out.grid_bits) {
        store_grid(out.q15 + up * 4, s, out.grid_bits);
        store_grid(out.q15 + down * 4, back_s, out.grid_bits);
    } else if (out.q15) {
        store_q15(out.q15 + up * 4, s);
        store_q15(out.q15 + down * 4, back_s);
    } else {
        store_u8(out.u8 + up * 4, s);
        store_u8(out.u8 + down * 4, back_s);
    }
}

/* Entry `entry` from the one `distance` entries before it, four values of any width. */
static inline void copy_u16(uint16_t *values, size_t entry, size_t distance)
{
    uint16_t *to = values + entry * 4;
    const uint16_t *from = to - distance * 4;
    uint16_t v[4] = {from[0], from[1], from[2], from[3]}; /* all read before any is written: one word moved */
    for (int c = 0; c < 4; c++)
        to[c] = v[c];
}

static inline void copy_u8(uint8_t *values, size_t entry, size_t distance)
{
    uint8_t *to = values + entry * 4;
    const uint8_t *from = to - distance * 4;
    uint8_t v[4] = {from[0], from[1], from[2], from[3]}; /* all read before any is written: one word moved */
    for (int c = 0; c < 4; c++)
        to[c] = v[c];
}

/* Entries up and down from the entries distance before each: a window's entries equal to the previous one's. */
static inline void copy_pair(vfi_table_out_t out, size_t up, size_t down, size_t distance)
{
    if (out.q15) {
        copy_u16(out.q15, up, distance);
        copy_u16(out.q15, down, distance);
    } else {
        copy_u8(out.u8, up, distance);
        copy_u8(out.u8, down, distance);
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
