/* SPDX-License-Identifier: MIT */
/*
 * tables.h: the lookup tables compositing reads, built from a classification for one slab length
 * (docs/algorithm.md, section 2). An entry is four values, premultiplied r, g, b and opacity a, either Q1.15
 * (1.0 = 32768) or 8 bits (1.0 = 255). The 2D table is indexed [front * N + back].
 */
#ifndef VF_TABLES_H
#define VF_TABLES_H

#include "arena.h"
#include "classify.h"
#include "fixmath.h"

#define VFI_ONE_Q15 32768u

/* Where a builder writes: exactly one of q15 and u8 is set. grid_bits (10 or 12, else 0) puts Q1.15 values on
 * the grid of round((2^B - 1) x) / (2^B - 1), for precision studies.
 * The front-weighted (lit) outputs of docs/algorithm.md section 7: NULL (both), or one of lit_q15 and lit_u8,
 * four values an entry at the main table's entry index: D_f r, g, b (premultiplied front-weighted diffuse colour)
 * and S_f (front-weighted specular weight), rounded as the main table's values are (grid_bits too). With both NULL
 * a builder does what it does without them, to the bit; with one set it also needs scratch from
 * vfi_table_scratch_alloc_lit (the incremental builder's). */
typedef struct vfi_table_out {
    uint16_t *q15;
    uint8_t *u8;
    uint32_t grid_bits;
    uint16_t *lit_q15; /* the front-weighted table (docs/algorithm.md, section 7) in the same format, or both NULL */
    uint8_t *lit_u8;
    /* Order 2 (preint2.h): the pieces' table in Q.30 as the builder has it, not rounded (q15 and u8 then NULL),
     * and its front-weighted values the same way (lit_q15 and lit_u8 then NULL). NULL in every other build. */
    uint32_t *q30;
    uint32_t *lit_q30;
} vfi_table_out_t;

/* Whether a builder is asked for lit outputs: never in builds without them (vf_config.h, VF_LIT_TABLES), whose
 * lit code is then dead and left out. */
static inline bool vfi_table_out_lit(vfi_table_out_t out)
{
    return VF_LIT_TABLES && (out.lit_q15 || out.lit_u8 || (VF_ORDER2 && out.lit_q30));
}

/* What compositing reads: one table (point or 2D) in one of the two formats, and the lut correction. */
typedef struct vfi_lookup_ctx {
    const uint16_t *q15;   /* the table with 16-bit entries, or NULL */
    const uint8_t *u8;     /* the table with 8-bit entries, or NULL */
    uint32_t n;            /* entries per table axis */
    const uint16_t *lut_f; /* lut correction: F(a) at a = k / 1024, Q1.15, or NULL for none */
    const uint32_t *lut_g; /* G(a) = F(a) / a at the same knots, Q16.16 */
    const uint16_t *lit_q15; /* lighting: the front-weighted table D_f r, g, b and S_f, as q15 and u8; else NULL */
    const uint8_t *lit_u8;
} vfi_lookup_ctx_t;

#define VFI_LUT_KNOTS 1025

/* The lut correction for slab length rho = d / d0 (Q16.16): F(a) = 1 - (1 - a)^rho and G(a) = F(a) / a at
 * a = k / 1024, k = 0..1024 (docs/algorithm.md, section 4b). */
void vfi_correction_lut(uint32_t rho_q16, uint16_t *f_q15, uint32_t *g_q16);

/* A view table: the lut (knots lut_f, lut_g) applied once to each entry of a 16-bit table, the numbers a segment
 * with that entry is given when corrected by itself (segment.h, vfi_correct), so that compositing with the view
 * table and no lut gives the same pixels for a fraction of the work. Entries [0, count); or, in part part of
 * parts of an n x n table, those of the diagonals vfi_preint_table_part builds in that part. */
void vfi_view_table(const uint16_t *lut_f, const uint32_t *lut_g, const uint16_t *table, uint16_t *view,
                    size_t count);
void vfi_view_table_part(const uint16_t *lut_f, const uint32_t *lut_g, const uint16_t *table, uint16_t *view,
                         uint32_t n, uint32_t part, uint32_t parts);
/* The same with the front-weighted table lit (16 bits, the entry index of table): view as vfi_view_table makes it,
 * to the bit, and lit_view = lit with the colour factor G(a) of the entry's opacity a on D_f and S_f alike (they
 * are colours, premultiplied by the part of a they weight). One lut look-up an entry for both. */
void vfi_view_table_lit(const uint16_t *lut_f, const uint32_t *lut_g, const uint16_t *table, const uint16_t *lit,
                        uint16_t *view, uint16_t *lit_view, size_t count);
void vfi_view_table_lit_part(const uint16_t *lut_f, const uint32_t *lut_g, const uint16_t *table, const uint16_t *lit,
                             uint16_t *view, uint16_t *lit_view, uint32_t n, uint32_t part, uint32_t parts);

/* A segment's opacity and premultiplied colour while the point table and the brute force are built, Q.30. */
typedef struct vfi_seg {
    uint32_t r, g, b, a;
} vfi_seg_t;

/* An interval while the incremental builder runs: its transmittance for pieces of one length (Q.30), its mean
 * extinction (Q.24) and colour weights (classify.h, Q.30), and two per-table constants of preint.c's steps in
 * Q.60 (preint.c says what they are), side by side so that a step reads one record. */
typedef struct vfi_interval {
    uint32_t t, mean_q24;
    uint32_t w[3];
    uint32_t g; /* lit builds, listed intervals: vfi_emission_depth_q30 of a piece, Q.30 (in the padding) */
    int64_t step[3];
    uint64_t w_q60[3];
} vfi_interval_t;

/* A block's suffix as the incremental builder keeps it for the joins: its colour seen from the front in Q.60
 * (with half an LSB of Q1.15 added: preint.c), from the back in Q.30, and its transmittance. */
typedef struct vfi_suffix {
    uint64_t front_q60[3];
    uint32_t back[3], t;
} vfi_suffix_t;

/* Scratch the incremental builder needs besides its output, for n entries (the brute force needs none): the
 * intervals (n + 1 records: interval m at m + 1, between a colourless record before the first and one after the
 * last); the intervals that can be seen at all (visible, ascending) and, for each m = 0..n-1, where the first
 * visible interval at or above m is listed (first_visible); one block's suffixes. About 116 bytes an entry (on a
 * 64-bit host; 30 KB for 256 entries), the price of reading the steps' constants where the old builder worked
 * them out (50 bytes an entry). */
typedef struct vfi_table_scratch {
    vfi_interval_t *interval; /* [n + 1] */
    vfi_suffix_t *suffix;     /* [n - 1] */
    uint16_t *visible;        /* [n - 1] */
    uint16_t *first_visible;  /* [n] */
    struct vfi_suffix_lit *suffix_lit; /* [n - 1] for lit builds (vfi_table_scratch_alloc_lit), else NULL */
} vfi_table_scratch_t;

/* A block's suffix's emission-position moments for the lit outputs (preint.c): D_f r, g, b and S_f's sums
 * T_k C_k (k + t(x_k)) and T_k alpha_k (k + t(x_k)), k counted in intervals from the end the run is seen from,
 * seen from its front and from its back, Q.22 (they reach r < 2^10). */
typedef struct vfi_suffix_lit {
    uint64_t front[4], back[4];
} vfi_suffix_lit_t;

size_t vfi_table_scratch_bytes(uint32_t n);
vf_status_t vfi_table_scratch_alloc(vfi_table_scratch_t *scratch, uint32_t n, vf_arena_t *arena);

/* The scratch of a lit build: the above and the suffixes' moments, 64 bytes an entry more (16 KB for 256
 * entries), so that unlit renderers need no more than before. Inline: no code in builds that never ask. */
static inline size_t vfi_table_scratch_lit_bytes(uint32_t n)
{
    return vfi_table_scratch_bytes(n) + vfi_arena_block(sizeof(vfi_suffix_lit_t) * (n - 1));
}

static inline vf_status_t vfi_table_scratch_alloc_lit(vfi_table_scratch_t *scratch, uint32_t n, vf_arena_t *arena)
{
    vf_status_t s = vfi_table_scratch_alloc(scratch, n, arena);
    if (s == VF_OK) {
        scratch->suffix_lit = vfi_arena_alloc(arena, sizeof(vfi_suffix_lit_t) * (n - 1));
        s = scratch->suffix_lit ? VF_OK : VF_ERR_NOMEM;
    }
    return s;
}

/* alpha t(x) for a piece of optical depth x (Q.28) and transmittance t = exp(-x) (Q.30, as the builders have it):
 * t(x) = 1 / x - exp(-x) / (1 - exp(-x)) is the mean depth, in piece lengths, of the light a uniform piece sends
 * out, from the face it is entered by (docs/algorithm.md section 7), so that alpha (1 - t(x)) is the piece's
 * front-weighted opacity. Q.30, 0 <= g <= (alpha + 1) / 2 (t(x) <= 1/2), and 0 where t is exactly 1 (a piece that
 * changes no bit of a composite changes none of the lit sums either).
 * alpha t = alpha / x - exp(-x) loses to cancellation as x falls (the error of alpha, 1.25 LSB, divided by x), so
 * below x = 1/16 it is the series sum_{j>=1} (-1)^(j+1) j x^j / (j+1)! = x (1/2 - x (1/3 - x (1/8 - x (1/30 -
 * x (1/144 - x / 840))))), whose first term left out is below 2^-40 there; Horner in Q.32. Above, one division:
 * within 1.25 * 16 + 2 LSB of Q.30 (tests/core/test_lit_tables.c measures 0.89 and 14.0 LSB against double). */
static inline uint32_t vfi_emission_depth_q30(uint64_t x_q28, uint32_t t_q30)
{
    const uint32_t one = UINT32_C(1) << 30, alpha = one - t_q30, most = (alpha + 1) >> 1;
    if (t_q30 >= one)
        return 0;
    uint64_t g;
    if (x_q28 < (UINT64_C(1) << 24)) {
        const uint64_t x = x_q28 << 4; /* Q.32, below 2^28 */
        uint64_t p = UINT64_C(5113057); /* 2^32 / 840 */
        p = UINT64_C(29826162) - ((x * p + (UINT64_C(1) << 31)) >> 32);  /* 2^32 / 144 */
        p = UINT64_C(143165577) - ((x * p + (UINT64_C(1) << 31)) >> 32); /* 2^32 / 30 */
        p = UINT64_C(536870912) - ((x * p + (UINT64_C(1) << 31)) >> 32); /* 2^32 / 8 */
        p = UINT64_C(1431655765) - ((x * p + (UINT64_C(1) << 31)) >> 32); /* 2^32 / 3 */
        p = UINT64_C(2147483648) - ((x * p + (UINT64_C(1) << 31)) >> 32); /* 2^32 / 2 */
        g = (x * p + (UINT64_C(1) << 33)) >> 34;
    } else {
        /* alpha / x in Q.30: (alpha 2^28 + x / 2) / x; at least exp(-x) (e^x - 1 >= x), so no wrap */
        g = vfi_udiv64(((uint64_t)alpha << 28) + (x_q28 >> 1), x_q28) - t_q30;
    }
    return g < most ? (uint32_t)g : most;
}

/* Order 0: entry i = (c_i a_i, a_i), a_i = 1 - exp(-tau_i d). n entries. */
void vfi_point_table(const vfi_classify_t *cls, uint32_t slab_q16, vfi_table_out_t out);
/* The same entries at i * stride (the diagonal of a 2D table: stride n + 1). */
void vfi_point_entries(const vfi_classify_t *cls, uint32_t slab_q16, vfi_table_out_t out, size_t stride);

/* Order 1, n x n entries. Both give the table of docs/algorithm.md section 2; they differ in how they group the
 * compositing of intervals, so in rounding (at most 1 LSB of Q1.15 apart); with lit outputs, section 7's
 * front-weighted values too (also at most 1 LSB apart, and D_f <= C, S_f <= a in every entry).
 * Brute force, O(N^3): every entry composites its |b - f| intervals one after another. The oracle.
 * Incremental subrange integration (Lum, Wilson and Ma 2004), O(N^2), in preint.c: along a diagonal |b - f| = r
 * every interval has length d / r; in blocks of r intervals, each entry joins a suffix of one block (kept in
 * scratch) with a prefix of the next (grown one interval an entry). */
#if VF_TABLE_ORACLE
void vfi_preint_table_bruteforce(const vfi_classify_t *cls, uint32_t slab_q16, const vfi_table_scratch_t *scratch,
                                 vfi_table_out_t out);
#endif
/* The incremental builder in parts: part (0 .. parts - 1) writes its share of the diagonals and no other entry, so
 * that parts may run side by side, each with its own scratch; all parts together give the whole table, to the
 * bit. vfi_preint_table_incremental is the one part of one. */
void vfi_preint_table_part(const vfi_classify_t *cls, uint32_t slab_q16, const vfi_table_scratch_t *scratch,
                           vfi_table_out_t out, uint32_t part, uint32_t parts);
/* A 2D table built as compositing reads it (a frame composited on one thread: vf_frame_t.one_thread): begin
 * builds the diagonal itself, lists the intervals and marks every other entry unbuilt, colour VFI_UNBUILT_Q15 and
 * opacity 0, which no entry has (values are at most 1.0, 32768). A reader that meets such an entry (f, b) asks for
 * it, and vfi_preint_demand_entry builds the block of its diagonal |b - f| that holds it (at most |b - f| entries
 * in each triangle, the ones that share its runs), to the bit as vfi_preint_table_part would. 16-bit tables (out.q15) only. With lit outputs, a diagonal's lit entries are
 * written with its entries, and hold nothing before (the marks are in out.q15 alone); scratch from
 * vfi_table_scratch_alloc_lit. */
#define VFI_UNBUILT_Q15 0xFFFFu
typedef struct vfi_demand {
    const vfi_classify_t *cls;
    const vfi_table_scratch_t *scratch; /* its intervals listed for this table, and room for a block's suffixes */
    vfi_table_out_t out;
    uint32_t slab_q16, visible_count;
    bool grey;                          /* every interval's weight grey: preint.c builds one colour channel */
    /* a thread's copy (vf_thread_table_t): asked first, told after a build; NULL otherwise (begin sets them so) */
    bool (*fill)(void *context, uint32_t diagonal);
    void (*built)(void *context, uint32_t diagonal);
    void *context;
} vfi_demand_t;
void vfi_preint_demand_begin(vfi_demand_t *demand, const vfi_classify_t *cls, uint32_t slab_q16,
                             const vfi_table_scratch_t *scratch, vfi_table_out_t out);
void vfi_preint_demand_entry(const vfi_demand_t *demand, uint32_t f, uint32_t b);

static inline void vfi_preint_table_incremental(const vfi_classify_t *cls, uint32_t slab_q16,
                                                const vfi_table_scratch_t *scratch, vfi_table_out_t out)
{
    vfi_preint_table_part(cls, slab_q16, scratch, out, 0, 1);
}

#endif
