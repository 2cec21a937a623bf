/*
 * tables.h: the lookup tables compositing reads, built from a classification for one slab length
 * (docs/algorithm.md, section 2). An entry is four values, premultiplied r, g, b and opacity a, either Q1.15
 * (1.0 = 32768) or 8 bits (1.0 = 255). The 2D table is indexed [front * N + back].
 */
#ifndef VF_TABLES_H
#define VF_TABLES_H

#include "classify.h"

#define VFI_ONE_Q15 32768u

/* Where a builder writes: exactly one of q15 and u8 is set. grid_bits (10 or 12, else 0) puts Q1.15 values on
 * the grid of round((2^B - 1) x) / (2^B - 1), for precision studies. */
typedef struct vfi_table_out {
    uint16_t *q15;
    uint8_t *u8;
    uint32_t grid_bits;
    uint16_t *lit_q15; /* the front-weighted table (docs/algorithm.md, section 7) in the same format, or both NULL */
    uint8_t *lit_u8;
} vfi_table_out_t;

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
} vfi_table_scratch_t;

size_t vfi_table_scratch_bytes(uint32_t n);
vf_status_t vfi_table_scratch_alloc(vfi_table_scratch_t *scratch, uint32_t n, vf_arena_t *arena);

/* Order 0: entry i = (c_i a_i, a_i), a_i = 1 - exp(-tau_i d). n entries. */
void vfi_point_table(const vfi_classify_t *cls, uint32_t slab_q16, vfi_table_out_t out);
/* The same entries at i * stride (the diagonal of a 2D table: stride n + 1). */
void vfi_point_entries(const vfi_classify_t *cls, uint32_t slab_q16, vfi_table_out_t out, size_t stride);

/* Order 1, n x n entries. Both give the table of docs/algorithm.md section 2; they differ in how they group the
 * compositing of intervals, so in rounding (at most 1 LSB of Q1.15 apart).
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
 * opacity 0, which no entry has (values are at most 1.0, 32768). A reader that meets such an entry asks for the
 * diagonal |b - f| of entry (f, b), which vfi_preint_demand_diagonal builds whole, both triangles, to the bit as
 * vfi_preint_table_part would. 16-bit tables (out.q15) only. */
#define VFI_UNBUILT_Q15 0xFFFFu
typedef struct vfi_demand {
    const vfi_classify_t *cls;
    const vfi_table_scratch_t *scratch; /* its intervals listed for this table, and room for a block's suffixes */
    vfi_table_out_t out;
    uint32_t slab_q16, visible_count;
    bool grey;                          /* every interval's weight grey: preint.c builds one colour channel */
} vfi_demand_t;
void vfi_preint_demand_begin(vfi_demand_t *demand, const vfi_classify_t *cls, uint32_t slab_q16,
                             const vfi_table_scratch_t *scratch, vfi_table_out_t out);
void vfi_preint_demand_diagonal(const vfi_demand_t *demand, uint32_t f, uint32_t b);

static inline void vfi_preint_table_incremental(const vfi_classify_t *cls, uint32_t slab_q16,
                                                const vfi_table_scratch_t *scratch, vfi_table_out_t out)
{
    vfi_preint_table_part(cls, slab_q16, scratch, out, 0, 1);
}

#endif
