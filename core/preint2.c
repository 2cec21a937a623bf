/* SPDX-License-Identifier: MIT */
/*
 * preint2.c: the order-2 table from first-order pieces (docs/algorithm.md section 8, preint2.h), integer only. Its
 * oracle is the double reference's build (host-sim/ref/ref_order2.c), entry by entry.
 *
 * Piece ends, exactly. Entry (f, m, b) stands for the scalars s = 255 x / (n2 - 1), x = f, m, b, so with t_i = i / K
 * (K = 16) P(t_i) = 255 X_i / (256 (n2 - 1)), X_i = 256 f + 16 i (4m - 3f - b) + i^2 (2f - 4m + 2b), an integer.
 * Clamped to the entry's own scalars, X_i lies in [256 min(f, m, b), 256 max(f, m, b)], and its nearest entry of
 * the n-entry 2D table, round(P (n - 1) / 255), is floor((2 X_i (n - 1) + D) / 2D) with D = 256 (n2 - 1): the
 * numerator is below 2^27 (n <= 1024, n2 <= 128), so one multiplication by ceil(2^(27 + l) / 2D), 2^l >= 2D, and a
 * shift by 27 + l give the quotient exactly (Granlund and Montgomery 1994, theorem 4.2). The double reference
 * works out the same integers, so both pick the same pieces.
 *
 * Compositing. Entry (b, m, f) is the curve of (f, m, b) from the other end (P(1 - t)): its pieces are the same
 * ends in the other order, each the 2D table's transposed entry, of the same opacity. So one pass over the pieces
 * of (f, m, b), i = 0 .. K - 1, composites both: the front one front to back (C += T C_i, T *= 1 - a_i), the back
 * one with each piece in front of what it has (C' = C'_i + (1 - a_i) C'). Both are Q.30, rounded at each step, and
 * rounded into the table's format once. Opacity is 1 - T for both.
 *
 * The bound. A piece is the incremental builder's Q.30 value, within a few hundred Q.30 LSB of the exact one
 * (about 2^-22: tests/core/test_order2.c measures), a step's rounding half a Q.30 LSB, and T and 1 - a_i are at
 * most 1, so the K-piece composite is within about K 2^-22 = 2^-18 of section 8's value: an eighth of an LSB of
 * Q1.15, and the rounded entry is one of the two nearest Q1.15 values to the exact one, within 1 LSB.
 *
 * Lighting (section 8): W_f = sum_i T_i (phi_f(t_i) D_i + phi_f(t_{i+1}) (C_i - D_i)), W_b the same with phi_b,
 * and the specular S_f', S_b' with S_i and a_i. phi_f(t_i) = (8 - i) / 8 for i <= 8, else 0; phi_b(t_i) =
 * (i - 8) / 8 for i >= 8, else 0: eighths, so each piece adds an integer combination of D_i and C_i - D_i, times
 * T_i / 8. Seen from the back, phi_f and phi_b trade places (phi_f(1 - t) = phi_b(t)) and the transposed entry's
 * D' is front-weighted towards e_{i+1}. The values are clamped to W_f <= C and W_b <= C - W_f (S_f' <= A,
 * S_b' <= A - S_f') in Q.30, where they hold exactly but for roundings.
 */
#include "arena.h"
#include "fixmath.h"
#include "preint2.h"
#include "table_store.h"

#if VF_ORDER2

#define ONE_Q30 (UINT32_C(1) << 30)
#define HALF_Q30 (UINT64_C(1) << 29)
#define K VFI_ORDER2_PIECES

/* How a clamped X becomes its entry of the 2D table: entry = ((2 X (n - 1) + D) mul) >> shift. */
typedef struct ends_rule {
    uint32_t n1, d;   /* n - 1; D = 256 (n2 - 1) */
    uint64_t mul;
    uint32_t shift;
} ends_rule_t;

static ends_rule_t ends_rule(uint32_t n, uint32_t n2)
{
    ends_rule_t e;
    e.n1 = n - 1;
    e.d = 256u * (n2 - 1);
    const uint32_t den = 2 * e.d;
    uint32_t l = 0;
    while ((UINT32_C(1) << l) < den)
        l++;
    e.shift = 27 + l;
    e.mul = vfi_udiv64((UINT64_C(1) << e.shift) + den - 1, den);
    return e;
}

/* The K + 1 piece ends of entry (f, m, b): entries of the 2D table. */
static inline void piece_ends(const ends_rule_t *rule, uint32_t f, uint32_t m, uint32_t b, uint32_t end[K + 1])
{
    const int32_t lin = 16 * (4 * (int32_t)m - 3 * (int32_t)f - (int32_t)b);
    const int32_t quad = 2 * (int32_t)f - 4 * (int32_t)m + 2 * (int32_t)b;
    const uint32_t lo3 = f < m ? (f < b ? f : b) : (m < b ? m : b), hi3 = f > m ? (f > b ? f : b) : (m > b ? m : b);
    const int32_t lo = 256 * (int32_t)lo3, hi = 256 * (int32_t)hi3, base = 256 * (int32_t)f;
    for (int32_t i = 0; i <= (int32_t)K; i++) {
        int32_t x = base + i * lin + i * i * quad;
        x = x < lo ? lo : x > hi ? hi : x;
        end[i] = (uint32_t)(((uint64_t)(2u * (uint32_t)x * rule->n1 + rule->d) * rule->mul) >> rule->shift);
    }
}

static inline uint32_t mul_q30(uint32_t a, uint32_t b)
{
    return (uint32_t)(((uint64_t)a * b + HALF_Q30) >> 30);
}

static inline uint32_t min_u32(uint32_t a, uint32_t b)
{
    return a < b ? a : b;
}

/* x D + y (C - D) for eighths x, y (C - D kept at least 0: the builders keep D <= C but a rounding). Below 2^34. */
static inline uint64_t mix(uint32_t x, uint32_t y, uint32_t d, uint32_t c)
{
    return (uint64_t)x * d + (uint64_t)y * (c > d ? c - d : 0);
}

/* An entry and its mirror (the same curve from the back) as composited: colours C (the entry's, Q.60 sums of
 * T_i C_i, unrounded) and C' (the mirror's, Q.30), the transmittance T (Q.30); lit, the weighted sums W_f, W_b
 * (r, g, b, specular) of each, the entry's in eighths of Q.60 (sums of T_i times mix), the mirror's in Q.30. */
typedef struct pair2 {
    uint64_t c[3];
    uint32_t rc[3], t;
    uint64_t wf[4], wb[4];
    uint32_t rwf[4], rwb[4];
} pair2_t;

/* The pieces of entry end[] front to back, and of its mirror each in front of what it has (preint2.c's header):
 * the entry's colour as exact Q.60 sums, one product a channel and piece; the mirror's needs the product of the
 * piece's transmittance with its sum so far, rounded to Q.30 each step. */
static VF_ALWAYS_INLINE void composite_pieces(const uint32_t *table, uint32_t n, const uint32_t end[K + 1],
                                              bool mirror, pair2_t *x)
{
    uint32_t t_acc = ONE_Q30, r0 = 0, r1 = 0, r2 = 0;
    uint64_t c0 = 0, c1 = 0, c2 = 0;
    for (uint32_t i = 0; i < K; i++) {
        const uint32_t *p = table + ((size_t)end[i] * n + end[i + 1]) * 4;
        const uint32_t a = min_u32(p[3], ONE_Q30), t = ONE_Q30 - a;
        c0 += (uint64_t)t_acc * p[0];
        c1 += (uint64_t)t_acc * p[1];
        c2 += (uint64_t)t_acc * p[2];
        if (mirror) {
            const uint32_t *q = table + ((size_t)end[i + 1] * n + end[i]) * 4;
            r0 = q[0] + mul_q30(t, r0);
            r1 = q[1] + mul_q30(t, r1);
            r2 = q[2] + mul_q30(t, r2);
        }
        t_acc = mul_q30(t_acc, t);
    }
    x->c[0] = c0, x->c[1] = c1, x->c[2] = c2;
    x->rc[0] = r0, x->rc[1] = r1, x->rc[2] = r2;
    x->t = t_acc;
}

/* The lit sums of the same pieces (section 8's W_f, W_b): the entry's piece i adds T_i mix / 8 to W_f (i < K / 2:
 * phi_f(t_i) = (8 - i) / 8, phi_f(t_{i+1}) = (7 - i) / 8) or W_b (phi_b: (i - 8) / 8, (i - 7) / 8); the mirror's,
 * the transposed entry's D' (front-weighted towards end[i + 1]) with phi_f and phi_b traded. */
static VF_ALWAYS_INLINE void lit_pieces(const uint32_t *table, const uint32_t *lit, uint32_t n,
                                        const uint32_t end[K + 1], bool mirror, pair2_t *x)
{
    uint32_t t_acc = ONE_Q30, t_back = ONE_Q30; /* t_back: the back half's transmittance, for the mirror */
    for (int c = 0; c < 4; c++)
        x->wf[c] = x->wb[c] = 0, x->rwf[c] = x->rwb[c] = 0;
    for (uint32_t i = 0; i < K; i++) {
        const size_t at = ((size_t)end[i] * n + end[i + 1]) * 4;
        const uint32_t *p = table + at, *d = lit + at;
        const uint32_t a = min_u32(p[3], ONE_Q30), t = ONE_Q30 - a;
        const bool front_half = i < K / 2;
        const uint32_t x0 = front_half ? 8 - i : i - 8, y0 = front_half ? 7 - i : i - 7;
        uint64_t *w = front_half ? x->wf : x->wb;
        for (int c = 0; c < 3; c++)
            w[c] += t_acc * mix(x0, y0, d[c], p[c]);
        w[3] += t_acc * mix(x0, y0, d[3], a);
        if (mirror) {
            /* The mirror's piece K - 1 - i: its phi_f at its front (t_{i+1} here) and back, (i - 7) / 8 and
             * (i - 8) / 8, in the back half; its phi_b, (7 - i) / 8 and (8 - i) / 8, in the front half. Its W_b
             * gathers the front half's pieces, each in front of the last, and is then seen through the back half
             * (t_back) once; its W_f gathers the back half's. */
            const size_t back = ((size_t)end[i + 1] * n + end[i]) * 4;
            const uint32_t *q = table + back, *e = lit + back;
            const uint32_t x1 = front_half ? 7 - i : i - 7, y1 = front_half ? 8 - i : i - 8;
            uint32_t *rw = front_half ? x->rwb : x->rwf;
            for (int c = 0; c < 4; c++)
                rw[c] = (uint32_t)((mix(x1, y1, e[c], c < 3 ? q[c] : a) + 4) >> 3) + mul_q30(t, rw[c]);
            if (!front_half)
                t_back = mul_q30(t_back, t);
        }
        t_acc = mul_q30(t_acc, t);
    }
    if (mirror)
        for (int c = 0; c < 4; c++)
            x->rwb[c] = mul_q30(t_back, x->rwb[c]);
}

/* Entry e of the table (and its lit values) from Q.30 values: colours at most 1.0 (the pieces' roundings can take a
 * sum a few Q.30 LSB past it, which the formats' conversions do not allow for), W_f <= C, W_b <= C - W_f, likewise
 * the specular with A. */
static inline void store_entry(vfi_table_out_t out, size_t e, const uint32_t c[3], uint32_t alpha,
                               const uint32_t *wf, const uint32_t *wb, bool with_lit)
{
    uint32_t v[3];
    for (int k = 0; k < 3; k++)
        v[k] = min_u32(c[k], ONE_Q30);
    vfi_store_values_q30(out.q15, out.u8, out.grid_bits, e, v[0], v[1], v[2], alpha);
    if (!with_lit)
        return;
    uint32_t f[4], b[4];
    const uint32_t whole[4] = {v[0], v[1], v[2], alpha};
    for (int k = 0; k < 4; k++) {
        f[k] = min_u32(wf[k], whole[k]);
        b[k] = min_u32(wb[k], whole[k] - f[k]);
    }
    vfi_store_values_q30(out.lit_q15, out.lit_u8, out.grid_bits, 2 * e, f[0], f[1], f[2], f[3]);
    vfi_store_values_q30(out.lit_q15, out.lit_u8, out.grid_bits, 2 * e + 1, b[0], b[1], b[2], b[3]);
}

/* A Q.60 sum in Q.30, rounded; at most 1.0 in Q.30 plus what 2^34 more would round to (below 2^32). */
static inline uint32_t q30_of_q60(uint64_t v)
{
    const uint64_t r = (v + HALF_Q30) >> 30;
    return r > UINT32_MAX ? UINT32_MAX : (uint32_t)r;
}

static VF_ALWAYS_INLINE void table_part(const vfi_order2_pieces_t *pieces, uint32_t n2, vfi_table_out_t out,
                                        uint32_t part, uint32_t parts, bool with_lit)
{
    const uint32_t n = pieces->n;
    const ends_rule_t rule = ends_rule(n, n2);
    const size_t plane = (size_t)n2 * n2;
    for (uint32_t f = part; f < n2; f += parts)
        for (uint32_t m = 0; m < n2; m++)
            for (uint32_t b = f; b < n2; b++) {
                uint32_t end[K + 1], c[3], wf[4], wb[4]; /* wf, wb: set and read only with_lit */
                pair2_t x;
                piece_ends(&rule, f, m, b, end);
                const bool mirror = b != f;
                composite_pieces(pieces->table, n, end, mirror, &x);
                if (with_lit)
                    lit_pieces(pieces->table, pieces->lit, n, end, mirror, &x);
                const uint32_t alpha = ONE_Q30 - x.t;
                for (int k = 0; k < 3; k++)
                    c[k] = q30_of_q60(x.c[k]);
                if (with_lit)
                    for (int k = 0; k < 4; k++) /* eighths of Q.60 */
                        wf[k] = q30_of_q60((x.wf[k] + 4) >> 3), wb[k] = q30_of_q60((x.wb[k] + 4) >> 3);
                store_entry(out, f * plane + (size_t)m * n2 + b, c, alpha, wf, wb, with_lit);
                if (mirror)
                    store_entry(out, b * plane + (size_t)m * n2 + f, x.rc, alpha, x.rwf, x.rwb, with_lit);
            }
}

void vfi_order2_table_part(const vfi_order2_pieces_t *pieces, uint32_t n2, vfi_table_out_t out, uint32_t part,
                           uint32_t parts)
{
    if (VF_MAX_TABLE_PARTS == 1)
        part = 0, parts = 1;
    if (VF_LIT_TABLES && pieces->lit && (out.lit_q15 || out.lit_u8))
        table_part(pieces, n2, out, part, parts, true);
    else
        table_part(pieces, n2, out, part, parts, false);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* The pieces. */

size_t vfi_order2_pieces_bytes(uint32_t n, bool lit)
{
    const size_t table = vfi_arena_block(sizeof(uint32_t) * 4 * (size_t)n * n);
    return vfi_arena_block(sizeof(uint32_t) * n) + table + (lit ? table : 0);
}

vf_status_t vfi_order2_pieces_alloc(vfi_order2_pieces_t *pieces, uint32_t n, bool lit, vf_arena_t *arena)
{
    vfi_zero(pieces, sizeof *pieces);
    pieces->n = n;
    pieces->tau = vfi_arena_alloc(arena, sizeof(uint32_t) * n);
    pieces->table = vfi_arena_alloc(arena, sizeof(uint32_t) * 4 * (size_t)n * n);
    if (lit)
        pieces->lit = vfi_arena_alloc(arena, sizeof(uint32_t) * 4 * (size_t)n * n);
    return pieces->tau && pieces->table && (!lit || pieces->lit) ? VF_OK : VF_ERR_NOMEM;
}

void vfi_order2_pieces_build(vfi_order2_pieces_t *pieces, const vfi_classify_t *cls, uint32_t slab_q16,
                             const vfi_table_scratch_t *scratch, bool lit)
{
    const uint32_t n = cls->n;
    /* The classification the builder reads (its n, extinctions, colours and weights), with the pieces' extinctions:
     * set field by field, as a copy of the whole, scalar arrays and all, would be a memcpy call, which the
     * freestanding core does not have. */
    vfi_classify_t piece_cls;
    piece_cls.n = n;
    piece_cls.tau_q28 = pieces->tau;
    piece_cls.colour_q30 = cls->colour_q30;
    piece_cls.weight_q30 = cls->weight_q30;
    for (uint32_t i = 0; i < n; i++) /* tau / (K / 2), rounded: the table for d is then the table for 2d / K */
        pieces->tau[i] = (cls->tau_q28[i] + K / 4) / (K / 2);
    vfi_table_out_t out;
    vfi_zero(&out, sizeof out);
    out.q30 = pieces->table;
    out.lit_q30 = VF_LIT_TABLES && lit ? pieces->lit : NULL;
    vfi_preint_table_incremental(&piece_cls, slab_q16, scratch, out);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* The run-length encoder's view of a preint2 renderer's samples. */

void vfi_order2_scalar_entries(vfi_classify_t *cls, uint32_t n2, bool interpolated)
{
    const uint32_t n1 = cls->n - 1, m1 = n2 - 1;
    for (uint32_t v = 0; v < 256; v++) {
        /* the order-2 entries of a sample of scalar v: round(x), or floor(x) and ceil(x), x = v (n2 - 1) / 255 */
        const uint32_t lo2 = interpolated ? v * m1 / 255 : (2 * v * m1 + 255) / 510;
        const uint32_t hi2 = interpolated ? (v * m1 + 254) / 255 : lo2;
        /* their scalars' nearest entries of the n-entry table: round(e (n - 1) / (n2 - 1)) */
        const uint32_t lo = (2 * lo2 * n1 + m1) / (2 * m1), hi = (2 * hi2 * n1 + m1) / (2 * m1);
        if (lo < cls->first_of_scalar[v])
            cls->first_of_scalar[v] = (uint16_t)lo;
        if (hi + 1 > cls->end_of_scalar[v])
            cls->end_of_scalar[v] = (uint16_t)(hi + 1);
    }
}

#endif /* VF_ORDER2 */

/* ---------------------------------------------------------------------------------------------------------- */
/* The public entry point (volfix.h): the classification, the builder's scratch and the pieces from the caller's
 * arena, rewound afterwards. */

size_t vf_table2_scratch_bytes(uint32_t n, bool lit)
{
    if (!VF_ORDER2 || n < VF_MIN_TABLE || n > VF_MAX_TABLE)
        return 0;
#if VF_ORDER2
    lit = lit && VF_LIT_TABLES;
    return VFI_ALIGN + vfi_classify_bytes(n) + (lit ? vfi_table_scratch_lit_bytes(n) : vfi_table_scratch_bytes(n)) +
           vfi_order2_pieces_bytes(n, lit);
#else
    (void)lit;
    return 0;
#endif
}

vf_status_t vf_table_order2(const vf_tf_t *tf, uint32_t n, uint32_t n2, uint32_t slab_q16, uint32_t part,
                            uint32_t parts, vf_arena_t *scratch, uint16_t *out, uint16_t *lit_out)
{
    if (!tf || !scratch || !out)
        return VF_ERR_NULL;
    if (n < VF_MIN_TABLE || n > VF_MAX_TABLE || n2 < VF_MIN_TABLE2 || n2 > VF_MAX_TABLE2 || slab_q16 == 0 ||
        slab_q16 > (UINT32_C(128) << 16) || parts == 0 || part >= parts)
        return VF_ERR_ARG;
#if VF_ORDER2
    if (lit_out && !VF_LIT_TABLES)
        return VF_ERR_UNSUPPORTED;
    const size_t mark = scratch->used;
    vfi_classify_t cls;
    vfi_table_scratch_t ts;
    vfi_order2_pieces_t pieces;
    const bool lit = lit_out != NULL;
    vf_status_t s = vfi_classify_alloc(&cls, n, VF_LOOKUP_NEAREST, scratch);
    if (s == VF_OK)
        s = lit ? vfi_table_scratch_alloc_lit(&ts, n, scratch) : vfi_table_scratch_alloc(&ts, n, scratch);
    if (s == VF_OK)
        s = vfi_order2_pieces_alloc(&pieces, n, lit, scratch);
    if (s == VF_OK)
        s = vfi_classify(&cls, tf);
    if (s == VF_OK) {
        vfi_order2_pieces_build(&pieces, &cls, slab_q16, &ts, lit);
        vfi_table_out_t to;
        vfi_zero(&to, sizeof to);
        to.q15 = out;
        to.lit_q15 = lit_out;
        vfi_order2_table_part(&pieces, n2, to, part, parts);
    }
    vfi_arena_rewind(scratch, mark);
    return s;
#else
    (void)lit_out;
    return VF_ERR_UNSUPPORTED;
#endif
}
