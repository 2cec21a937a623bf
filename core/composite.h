/* SPDX-License-Identifier: MIT */
/*
 * composite.h: what the compositing files share (docs/algorithm.md, sections 4 and 4b). composite.c runs a band:
 * it places each slice in the intermediate image, merges the run-length encoding's visible runs of a row and hands
 * each row to composite_order0.c (point, preclass: one slice; unlit preclass's plain loop in composite_preclass.c) or
 * composite_order1.c (preint1: one slab).
 *
 * Samples are bilinear in the slice and exact: the slice offsets lie on the 2^-16 grid, so a sample is a multiple
 * of 2^-32 and fits Q8.32, and its nearest table entry is the one the double reference picks.
 */
#ifndef VF_COMPOSITE_H
#define VF_COMPOSITE_H

#include "segment.h"

/* Where a standard slice lands in the intermediate image. With R rays per voxel, pixel u samples the slice at column
 * x = u / R - ou, in Q16.16 u * step - ou with step = 2^16 / R (exact: the offsets are on the 2^-16 grid). */
typedef struct slice_place {
    const uint8_t *data;        /* the slice in the standard-order copy */
    int32_t ou, ov;             /* the slice's offset, Q16.16 voxels */
    int32_t cu, cv;             /* the first pixel (row) whose sample is inside: its column (row) 0 */
    uint32_t fx, fy;            /* Q0.16: the fractions at cu, cv; with R = 1 at every pixel (row) */
    int32_t u_lo, u_hi;         /* pixels whose sample is inside the slice, inclusive (u_lo = cu) */
    int32_t v_lo, v_hi;
} slice_place_t;

/* A row's visible runs as intervals of pixels: the run list of one cell row (runs.h) of a slice at offset ou. Cells
 * [c0, c1) hold the samples of pixels [px(c0), px(c1)), px(c) = ceil((c 2^16 + ou) / step); with one ray per voxel
 * that is c + cu, and the stream counts in pixels (shift 0). */
typedef struct run_stream {
    const uint16_t *p, *end;
    int32_t pos;                /* the next cell, or (one ray) its pixel */
    int32_t ou_up;              /* ou + step - 1 */
    uint32_t shift;             /* step = 2^shift; 0 for one ray per voxel */
} run_stream_t;

/* The union of a front and a back run stream (order 0: the front stream alone), as ascending disjoint
 * intervals. Each stream's current interval is [a, b); an exhausted stream's is [RUN_END, RUN_END). */
typedef struct run_merge {
    run_stream_t s[2];
    int32_t a0, b0, a1, b1;
} run_merge_t;

#define VFI_RUN_END INT32_MAX

/* Pixels [a, b) of an intermediate row. */
typedef struct vfi_span {
    uint32_t a, b;
} vfi_span_t;

/* Where the pixels from u on stop being all buffered or all unbuffered: the last slab's spans (last[count],
 * ascending) say which of them hold the previous slice's samples. k is the first span that may reach u, and moves
 * on as u does; the answer is at most b. */
static inline uint32_t vfi_buffered_until(const vfi_span_t *last, uint32_t count, uint32_t *k, uint32_t u, uint32_t b,
                                          bool *buffered)
{
    while (*k < count && last[*k].b <= u)
        (*k)++;
    *buffered = *k < count && last[*k].a <= u;
    const uint32_t y = *buffered ? last[*k].b : *k < count ? last[*k].a : b;
    return y < b ? y : b;
}

/* The runs of one intermediate row that a slab walked, so that the next slab knows where the buffered back samples
 * are its front samples (composite_order1.c). */
typedef struct row_visits {
    uint32_t slab;              /* the slab that walked them; UINT32_MAX before any */
    uint32_t count;
    vfi_span_t *span;           /* [count], ascending, disjoint */
} row_visits_t;

/* What one row of one slab (or slice) needs. */
typedef struct row_job {
    const slice_place_t *front, *back; /* back is NULL in the order-0 modes */
    const uint8_t *row_data;           /* the front (order 0: the) slice's row under this intermediate row */
    const uint8_t *back_row_data;
    uint32_t front_fy, back_fy;        /* their fractions to the next slice row, Q0.16 */
    uint32_t row;                      /* bytes per slice row */
    uint32_t step, step_shift;         /* 2^16 / rays = 2^step_shift: a pixel's width in Q16.16 voxels */
    uint32_t ni, nj;                   /* slice size, voxels */
    int32_t clip_lo, clip_hi;          /* order 0: the pixels of the row to composite here, inclusive */
    /* partial slabs (composite_partial.c) */
    const slice_place_t *before, *after; /* order 0: slices t - 1 and t + 1, NULL beyond the first and last */
    uint32_t slab_q16;                 /* the view's slab length */
    bool depth_from_tau;               /* shorten with the entries' optical depths from the classification
                                        * (16-bit tables), not from the segment's opacity */
    uint32_t t;                        /* standard slice (order 0) or slab (preint1) */
    const vfi_classify_t *cls;
    vfi_lookup_ctx_t lookup;
    bool plain;                        /* nearest lookup, 16-bit table, no lut, full precision: the fast path */
    bool plain_lit;                    /* the same for a lit frame without gradient opacity: the lit fast loops */
    bool grey;                         /* the transfer function is grey: every entry's three colours are equal */
    size_t shade_offset;               /* lit preint1: a back sample's shade is buffered this many elements after
                                        * its table position, to be the next slab's front shade */
    bool bilinear;
    uint32_t sample_shift;             /* precision studies: samples rounded to 32 - shift fraction bits (0: exact) */
    uint32_t inter_shift;              /* precision studies: accumulators rounded to multiples of 2^shift in Q1.15 */
    uint16_t *next;                    /* skip links: next[u] == u for an open pixel, else a pixel further right */
    uint16_t *pixels;                  /* the intermediate row, r, g, b, a in Q1.15 */
    /* preint1: the buffered table positions (nearest: entry times N, the front entry's row in the 2D table, and
     * in the plain path that times 8, the row's byte offset; bilinear: Q.16), buffer index = u - shift (a slice
     * buffer's row has one element before index 0). A frame reads them in the path that wrote them. */
    uint32_t *front_buf, *back_buf;
    int32_t front_shift, back_shift;
    const vfi_demand_t *demand;        /* the 2D table is built as it is read (tables.h), or NULL */
    const vfi_shading_t *shading;      /* lit frames (shade.h), which take the general loops; else NULL */
    /* preclass's plain loops (composite_preclass.c) */
    const uint64_t *preclass_terms;    /* unlit: the slice's terms, else NULL */
    const uint64_t *preclass_classes;  /* lit: the band's classes */
    uint64_t *preclass_lit;            /* lit: two slice rows' lerps across, [2][cols][2], row j's at j & 1 */
    uint32_t *preclass_stamp;          /* lit: [2][cols], which slice row's lerp a column holds */
    uint32_t preclass_cols;            /* max_ni + 1 */
} row_job_t;

void vfi_row_order0(const row_job_t *job, run_merge_t *m, bool preclass);

/* Unlit preclass on the plain path (composite_preclass.c, VF_SPECIAL_LOOPS builds): the band's classes, 8-bit
 * scalar s's entry of the point table as classes[2 s] = r | b << 32 (grey: r | a << 32) and classes[2 s + 1] =
 * g | a << 32; a slice's terms, [4][256] from the classes at the slice's fx (grey: [0] and [2] alone); one row of
 * the slice (job->preclass_terms set). */
#define VFI_PRECLASS_CLASSES 512
#define VFI_PRECLASS_TERMS 1024
void vfi_preclass_classes(const row_job_t *job, uint64_t *classes);
void vfi_preclass_terms(const uint64_t *classes, uint32_t fx, bool grey, uint64_t *terms);
void vfi_row_preclass(const row_job_t *job, run_merge_t *m);
/* Lit preclass on the plain path (plain_lit): a voxel lit about once a slice row, a row's lerps across kept for the
 * next row. */
#define VFI_PRECLASS_NO_ROW UINT32_MAX /* a stamp that names no slice row */
void vfi_row_preclass_lit(const row_job_t *job, run_merge_t *m);

/* The rows [v_lo, v_hi] of a slab where both its slices are inside, in one call (composite_order1.c): what they
 * share. The slab is job's (front, back, t, the buffers' shifts); the arrays are row v_lo's, row v_lo + k's are k
 * strides further. */
typedef struct vfi_slab_rows {
    int32_t v_lo, v_hi;
    const vfi_runs_t *runs;
    uint32_t kc;                     /* the cell slab between the slices */
    uint16_t *next, *pixels;         /* skip links and intermediate pixels */
    size_t next_stride, pixel_stride;
    uint32_t *front_buf, *back_buf;  /* the buffered positions, pixel u's at [u - job shift] */
    size_t buf_stride;
    const row_visits_t *last;        /* the runs walked by the slab before (theirs when .slab says so), or NULL */
    row_visits_t *now;               /* and by this one */
} vfi_slab_rows_t;

void vfi_slab_preint1(row_job_t *job, const vfi_slab_rows_t *slab);

/* Where standard slice t lands in the intermediate image of the frame begun (composite.c). */
void vfi_place_slice(const vf_renderer_t *r, uint32_t t, slice_place_t *p);

/* preint2 (composite_order2.c): a band's slabs of two slices, and the last slab of one when the slab count is odd,
 * with the scratch composite.c carved as for preint1 (next, the two buffers and their row layout, the visits) and
 * job set up as for preint1 (the 2D table's lookup, for that last slab). */
typedef struct vfi_band {
    uint32_t v0, v1;
    uint16_t *next;
    uint32_t *buf[2];
    size_t buf_row, buf_first;
    row_visits_t *visits;
} vfi_band_t;

void vfi_band_order2(const vf_renderer_t *r, row_job_t *job, const vfi_band_t *band);

/* The slice row that intermediate row v (inside the slice) samples, its index j and fraction fy to the next. */
static inline const uint8_t *vfi_slice_row(const slice_place_t *sl, uint32_t row_bytes, uint32_t step, int32_t v,
                                           uint32_t *j, uint32_t *fy)
{
    uint32_t y = (uint32_t)v * step - (uint32_t)sl->ov;
    *j = y >> 16;
    *fy = y & 0xFFFFu;
    return sl->data + (size_t)*j * row_bytes;
}

/* Partial slabs (docs/algorithm.md, section 4c), composite_partial.c: row v's pixels [x, y) that a slab crosses
 * through a side face (preint1), or whose slice has a neighbour whose sample is outside (order 0). */
void vfi_faces_preint1(const row_job_t *job, int32_t v, uint32_t x, uint32_t y);
void vfi_faces_order0(const row_job_t *job, int32_t v, uint32_t x, uint32_t y, bool preclass);


/* The bilinear sample between p (column i of a slice row) and q (the same column of the next row) with fractions
 * fx, fy (Q0.16), exactly, in Q8.32, plus bias 2^16 (bias in Q8.16, added to both rows' lerps, reaches the sample
 * whole): lerps as a + (b - a) f, three multiplications. vfi_sample_at: q = p + row. */
static inline uint64_t vfi_sample_rows_biased(const uint8_t *p, const uint8_t *q, uint32_t fx, uint32_t fy,
                                              int32_t bias)
{
    int32_t top = (int32_t)(p[0] << 16) + bias + ((int32_t)p[1] - (int32_t)p[0]) * (int32_t)fx; /* Q8.16 */
    int32_t bottom = (int32_t)(q[0] << 16) + bias + ((int32_t)q[1] - (int32_t)q[0]) * (int32_t)fx;
    return (uint64_t)((int64_t)top * 65536 + (int64_t)(bottom - top) * (int64_t)fy);
}

static inline uint64_t vfi_sample_rows(const uint8_t *p, const uint8_t *q, uint32_t fx, uint32_t fy)
{
    return vfi_sample_rows_biased(p, q, fx, fy, 0);
}

/* round(s) of that sample s, the nearest entry of a 256-entry table (vfi_entry_of_sample_n): the half (2^31) as the
 * lerps' bias, (s + 2^31) >> 32 to the bit, without a 64-bit constant that a loop would keep in a register. */
static inline uint32_t vfi_entry256_rows(const uint8_t *p, const uint8_t *q, uint32_t fx, uint32_t fy)
{
    return (uint32_t)(vfi_sample_rows_biased(p, q, fx, fy, 32768) >> 32);
}

static inline uint64_t vfi_sample_at(const uint8_t *p, uint32_t row, uint32_t fx, uint32_t fy)
{
    return vfi_sample_rows(p, p + row, fx, fy);
}

/* The nearest entry of an n-entry table for the sample between slice rows p and q with fractions fx, fy; n256 (n
 * is 256): by vfi_entry256_rows, the same entry with the rounding folded into the lerps. The plain loops' look-up. */
static VF_ALWAYS_INLINE uint32_t vfi_entry_rows(const uint8_t *p, const uint8_t *q, uint32_t fx, uint32_t fy,
                                                uint32_t n, bool n256)
{
    return n256 ? vfi_entry256_rows(p, q, fx, fy) : vfi_entry_of_sample_n(n, vfi_sample_rows(p, q, fx, fy));
}

/* The plain loops' samples along a row by columns (one ray per voxel: pixel u samples column c = u - cu of its two
 * slice rows at the row's one fx and fy): each voxel column lerped down by fy, in Q8.16 plus the bias as in
 * vfi_sample_rows_biased, then a sample the lerp across of its left and right columns. The same products as the
 * lerps across then down, added in another order, all exact: the same sample to the bit. A pixel right after the
 * last one sampled takes that one's right column as its left: one column a pixel where a run's pixels follow each
 * other, where the lerps across then down take four voxels and three products a pixel. */
typedef struct vfi_row_sampler {
    const uint8_t *top, *bottom;  /* the two slice rows, by column */
    int64_t fx;                   /* Q0.16 */
    int32_t fy;
    int32_t bias;                 /* 32768 for a 256-entry table's rounding (vfi_entry256_rows), else 0 */
    uint32_t last;                /* the column sampled last (UINT32_MAX - 1: none) */
    int32_t right;                /* its right column's lerp down */
} vfi_row_sampler_t;

static VF_ALWAYS_INLINE void vfi_sampler_init(vfi_row_sampler_t *s, const uint8_t *top, uint32_t row, uint32_t fx,
                                              uint32_t fy, bool n256)
{
    s->top = top, s->bottom = top + row, s->fx = fx, s->fy = (int32_t)fy, s->bias = n256 ? 32768 : 0;
    s->last = UINT32_MAX - 1, s->right = 0;
}

static VF_ALWAYS_INLINE int32_t vfi_sampler_down(const vfi_row_sampler_t *s, uint32_t c)
{
    const int32_t p = s->top[c], q = s->bottom[c];
    return p * 65536 + s->bias + (q - p) * s->fy;
}

/* The nearest entry of an n-entry table (n256: 256, s->bias 32768) for column c's sample: vfi_entry_rows's. */
static VF_ALWAYS_INLINE uint32_t vfi_sampler_entry(vfi_row_sampler_t *s, uint32_t c, uint32_t n, bool n256)
{
    const int32_t left = c == s->last + 1 ? s->right : vfi_sampler_down(s, c);
    const int32_t right = vfi_sampler_down(s, c + 1);
    s->last = c, s->right = right;
    const uint64_t x = (uint64_t)((int64_t)left * 65536 + (int64_t)(right - left) * s->fx);
    return n256 ? (uint32_t)(x >> 32) : vfi_entry_of_sample_n(n, x);
}

/* The column of slice sl that pixel u samples, and its fraction fx (Q0.16). */
static inline uint32_t vfi_column(const slice_place_t *sl, uint32_t step, uint32_t u, uint32_t *fx)
{
    uint32_t x = u * step - (uint32_t)sl->ou; /* u * step < 2^32: u < 2^16 */
    *fx = x & 0xFFFFu;
    return x >> 16;
}

/* Where a sample s (Q8.32) goes in the table: its nearest entry, or (bilinear) its position in Q.16; for
 * precision studies the sample is first rounded to fewer fraction bits. */
static inline uint32_t vfi_position_of(const row_job_t *job, uint64_t s)
{
    if (job->sample_shift)
        s = ((s + (UINT64_C(1) << (job->sample_shift - 1))) >> job->sample_shift) << job->sample_shift;
    return job->bilinear ? vfi_position_of_sample(job->cls, s) : vfi_entry_of_sample(job->cls, s);
}

/* The same for the sample at p with fractions fx, fy. */
static inline uint32_t vfi_table_position(const row_job_t *job, const uint8_t *p, uint32_t fx, uint32_t fy)
{
    return vfi_position_of(job, vfi_sample_at(p, job->row, fx, fy));
}

/* Composite a segment; for precision studies keep the accumulators on a coarser grid. True when the pixel became
 * opaque. */
static inline bool vfi_composite_segment(const row_job_t *job, uint16_t *px, const uint32_t seg[4])
{
    if (!seg[3])
        return false;
    bool opaque = vfi_blend(px, seg);
    if (job->inter_shift) {
        const uint32_t half = 1u << (job->inter_shift - 1);
        for (int c = 0; c < 4; c++) {
            uint32_t v = ((px[c] + half) >> job->inter_shift) << job->inter_shift;
            px[c] = (uint16_t)(v > VFI_ONE_Q15 ? VFI_ONE_Q15 : v);
        }
        opaque = px[3] >= VFI_OPAQUE_Q15;
    }
    return opaque;
}

/* The 2D entry of a slab from its front and back table positions (any lookup, table format, correction). */
static VF_ALWAYS_INLINE void vfi_segment_preint1(const row_job_t *job, uint32_t pos_f, uint32_t pos_b,
                                                uint32_t seg[4])
{
    const vfi_lookup_ctx_t *c = &job->lookup;
    const size_t n = c->n;
    if (job->bilinear) {
        uint32_t i, fi, j, fj, w[4], e[4][4];
        vfi_split_position(c->n, pos_f, &i, &fi);
        vfi_split_position(c->n, pos_b, &j, &fj);
        vfi_weights(fi, fj, w);
        vfi_fetch(c, i * n + j, e[0]);
        vfi_fetch(c, (i + 1) * n + j, e[1]);
        vfi_fetch(c, i * n + j + 1, e[2]);
        vfi_fetch(c, (i + 1) * n + j + 1, e[3]);
        for (int k = 0; k < 4; k++) /* at most 32768 * 65536 in all */
            seg[k] = (e[0][k] * w[0] + e[1][k] * w[1] + e[2][k] * w[2] + e[3][k] * w[3] + 0x8000u) >> 16;
    } else {
        vfi_fetch(c, pos_f * n + pos_b, seg);
    }
    if (c->lut_f)
        vfi_correct(c, seg);
}

/* The 2D entry of a lit slab and its front-weighted values (docs/algorithm.md, section 7), looked up and corrected
 * alike. */
static VF_ALWAYS_INLINE void vfi_segment_preint1_lit(const row_job_t *job, uint32_t pos_f, uint32_t pos_b,
                                                    uint32_t seg[4], uint32_t lit[4])
{
    const vfi_lookup_ctx_t *c = &job->lookup;
    const size_t n = c->n;
    if (job->bilinear) {
        uint32_t i, fi, j, fj, w[4], e[4][4], l[4][4];
        vfi_split_position(c->n, pos_f, &i, &fi);
        vfi_split_position(c->n, pos_b, &j, &fj);
        vfi_weights(fi, fj, w);
        const size_t at[4] = {i * n + j, (i + 1) * n + j, i * n + j + 1, (i + 1) * n + j + 1};
        for (int k = 0; k < 4; k++) {
            vfi_fetch(c, at[k], e[k]);
            vfi_fetch_from(c->lit_q15, c->lit_u8, at[k], l[k]);
        }
        for (int k = 0; k < 4; k++) {
            seg[k] = (e[0][k] * w[0] + e[1][k] * w[1] + e[2][k] * w[2] + e[3][k] * w[3] + 0x8000u) >> 16;
            lit[k] = (l[0][k] * w[0] + l[1][k] * w[1] + l[2][k] * w[2] + l[3][k] * w[3] + 0x8000u) >> 16;
        }
    } else {
        vfi_fetch(c, pos_f * n + pos_b, seg);
        vfi_fetch_from(c->lit_q15, c->lit_u8, pos_f * n + pos_b, lit);
    }
    if (c->lut_f)
        vfi_correct_lit(c, seg, lit);
}

/* The shade of one voxel (preclass lights each of a sample's four voxels with its own). */
static inline vfi_shade_t vfi_voxel_shade(const vfi_shading_t *sh, const uint8_t *p)
{
    return vfi_voxel_shade_at(sh, (size_t)(p - sh->slices));
}

/* A slice sample's entry (point), or the interpolation of its four voxels' entries (preclass): the sample at p with
 * fractions fx, fy; lit when the job is (each of preclass's voxels with its own shade). */
static VF_ALWAYS_INLINE void vfi_segment_order0(const row_job_t *job, const uint8_t *p, uint32_t fx, uint32_t fy,
                                      bool preclass, uint32_t seg[4])
{
    const vfi_lookup_ctx_t *c = &job->lookup;
    if (preclass) {
        uint32_t e[4][4];
        const uint16_t *entry = job->cls->entry_of_scalar;
        vfi_fetch(c, entry[p[0]], e[0]);
        vfi_fetch(c, entry[p[1]], e[1]);
        vfi_fetch(c, entry[p[job->row]], e[2]);
        vfi_fetch(c, entry[p[job->row + 1]], e[3]);
        if (VF_LIGHTING && job->shading) {
            const uint8_t *voxel[4] = {p, p + 1, p + job->row, p + job->row + 1};
            for (int k = 0; k < 4; k++) /* lit, then interpolated and corrected as unlit (docs/algorithm.md, 7) */
                vfi_light_point(e[k], vfi_voxel_shade(job->shading, voxel[k]));
        }
        vfi_lerp(e[0], e[1], fx);
        vfi_lerp(e[2], e[3], fx);
        vfi_lerp(e[0], e[2], fy);
        for (int k = 0; k < 4; k++)
            seg[k] = e[0][k];
    } else if (job->bilinear) {
        uint32_t i, f, next_entry[4];
        vfi_split_position(c->n, vfi_table_position(job, p, fx, fy), &i, &f);
        vfi_fetch(c, i, seg);
        vfi_fetch(c, i + 1, next_entry);
        vfi_lerp(seg, next_entry, f);
    } else {
        vfi_fetch(c, vfi_table_position(job, p, fx, fy), seg);
    }
    if (c->lut_f)
        vfi_correct(c, seg);
    if (VF_LIGHTING && job->shading && !preclass)
        vfi_light_point(seg, vfi_sample_shade(job->shading, p, job->row, fx, fy));
}

/* Pixel u (at px) blended with 16-bit table entry e, and closed in the skip links next once opaque: the plain
 * loops' step for a pixel. grey: the table is grey (r = g = b in every entry), one product for the three colours. */
static VF_ALWAYS_INLINE void vfi_blend_entry(uint16_t *px, uint16_t *next, uint32_t u, const uint16_t *e, bool grey)
{
    if (e[3] && (grey ? vfi_blend_grey(px, e[0], e[3]) : vfi_blend_q15(px, e)))
        next[u] = (uint16_t)(u + 1);
}

/* The first open pixel at or after u; halves the path it walked, so that runs of opaque pixels cost almost nothing
 * on the next slab. next[width] is always open. */
static inline uint32_t vfi_next_open(uint16_t *next, uint32_t u)
{
    while (next[u] != u) {
        uint32_t n = next[u];
        next[u] = next[n];
        u = n;
    }
    return u;
}

/* Interval [*a, *b) of stream s, or [VFI_RUN_END, VFI_RUN_END) when it has none left. */
static inline void vfi_stream_next(run_stream_t *s, int32_t *a, int32_t *b)
{
    if (s->p == s->end) {
        *a = *b = VFI_RUN_END;
        return;
    }
    const int32_t from = s->pos + s->p[0], to = from + s->p[1];
    s->pos = to;
    s->p += 2;
    if (s->shift == 0) {
        *a = from, *b = to;
    } else { /* below 2^31: cells and offsets are below 2^14 voxels */
        *a = (int32_t)((uint32_t)(from * 65536 + s->ou_up) >> s->shift);
        *b = (int32_t)((uint32_t)(to * 65536 + s->ou_up) >> s->shift);
    }
}

static inline void vfi_stream_init(run_stream_t *s, const uint16_t *p, const uint16_t *end, const slice_place_t *sl,
                                   uint32_t step_shift)
{
    s->p = p, s->end = end;
    if (step_shift == 16) { /* one ray per voxel: count in pixels from the slice's first */
        s->shift = 0, s->pos = sl->cu, s->ou_up = 0;
    } else {
        s->shift = step_shift, s->pos = 0, s->ou_up = sl->ou + (int32_t)(1u << step_shift) - 1;
    }
}

/* Start a merge of the runs of slice sl0's cell row (p0, e0) and, unless p1 is NULL, slice sl1's. */
static inline void vfi_merge_init(run_merge_t *m, uint32_t step_shift, const uint16_t *p0, const uint16_t *e0,
                                  const slice_place_t *sl0, const uint16_t *p1, const uint16_t *e1,
                                  const slice_place_t *sl1)
{
    vfi_stream_init(&m->s[0], p0, e0, sl0, step_shift);
    vfi_stream_init(&m->s[1], p1, p1 ? e1 : p1, p1 ? sl1 : sl0, step_shift);
    vfi_stream_next(&m->s[0], &m->a0, &m->b0);
    vfi_stream_next(&m->s[1], &m->a1, &m->b1);
}

/* The next interval of the union, with overlapping and touching intervals joined; false when none is left. */
static VF_ALWAYS_INLINE bool vfi_merge_next(run_merge_t *m, int32_t *a, int32_t *b)
{
    int32_t lo, hi;
    if (m->a0 <= m->a1) {
        if (m->a0 == VFI_RUN_END)
            return false;
        lo = m->a0, hi = m->b0;
        vfi_stream_next(&m->s[0], &m->a0, &m->b0);
    } else {
        lo = m->a1, hi = m->b1;
        vfi_stream_next(&m->s[1], &m->a1, &m->b1);
    }
    for (;;) { /* an exhausted stream's a is VFI_RUN_END, above any hi */
        if (m->a0 <= hi) {
            hi = m->b0 > hi ? m->b0 : hi;
            vfi_stream_next(&m->s[0], &m->a0, &m->b0);
        } else if (m->a1 <= hi) {
            hi = m->b1 > hi ? m->b1 : hi;
            vfi_stream_next(&m->s[1], &m->a1, &m->b1);
        } else {
            break;
        }
    }
    *a = lo;
    *b = hi;
    return true;
}

/* The union of a row's runs, clipped to the pixels [lo, hi] where both samples are inside, into walked; returns how
 * many. A pass of its own, so that the merge's state has the registers to itself. */
static VF_ALWAYS_INLINE uint32_t vfi_merge_runs(run_merge_t *m, int32_t lo, int32_t hi, vfi_span_t *walked)
{
    uint32_t count = 0;
    int32_t a, b;
    while (vfi_merge_next(m, &a, &b)) {
        a = a > lo ? a : lo;
        b = b < hi + 1 ? b : hi + 1;
        if (a < b) {
            walked[count].a = (uint32_t)a;
            walked[count].b = (uint32_t)b;
            count++;
        }
    }
    return count;
}

#endif
