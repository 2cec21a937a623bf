/* SPDX-License-Identifier: MIT */
/*
 * composite_order1.c: the rows of one slab in preint1 (docs/algorithm.md, sections 4 and 4b), all in one call: each
 * open pixel of the visible runs takes the pre-integrated entry of its front and back sample.
 *
 * A slab's back sample is the next slab's front sample, so its table position is buffered. Whether a pixel's
 * buffered position is this slab's front is known per run rather than per pixel: it is exactly when the last slab
 * walked the pixel, that is when the pixel lies in one of the runs the last slab walked in this row (an open pixel
 * now was open then, and every open pixel of a walked run was given its back sample). So each run is cut where the
 * last slab's runs begin and end, into spans whose fronts are all in the buffer or all sampled here, and the loops
 * over pixels test nothing per pixel: cheaper than a slice tag in every buffered word tested per pixel, above all
 * on long runs (docs/performance.md).
 */
#include "composite.h"

#define MIN(a, b) ((a) < (b) ? (a) : (b))
#define MAX(a, b) ((a) > (b) ? (a) : (b))


/* What the plain loop reads for one row. The slice rows and buffers are addressed by c = u - cu, the back slice's
 * column of pixel u (the slice buffer's rows have one element before column 0, for a front slice one column to the
 * right of the back one), the pixels by u; a sampled front at u - front_cu of its slice row. span_plain's loop works
 * on a copy of loop, a local of its own: then the stores to the buffer and the pixels cannot make the compiler read
 * these again (read through the caller's struct, they would be read again after every store wherever span_plain is
 * out of line, as at -Os). */
typedef struct plain_loop {
    const uint8_t *top, *bottom;     /* the back sample's two slice rows */
    const uint32_t *front_buf;
    uint32_t *back_buf;
    const uint16_t *table;
    uint16_t *next, *pixels;         /* the intermediate row's skip links and pixels, by u */
    uint32_t cu;                     /* the back slice's first pixel */
    uint32_t fx, fy, n;              /* the back sample's fractions (Q0.16, the same for every row of a slab) */
} plain_loop_t;

typedef struct plain_row {
    plain_loop_t loop;
    const uint8_t *front;            /* the front sample's first slice row */
    /* the same for every row of a slab */
    uint32_t front_cu, front_fx, front_fy, row; /* Q0.16 fractions; bytes per slice row */
    const vfi_demand_t *demand;      /* the 2D table is built as it is read (tables.h), or NULL */
    const vfi_shading_t *shading;    /* lit frames: the shades, and the front-weighted table beside the table */
    const uint16_t *lit;
    size_t shade_offset;             /* a buffered shade's distance from its buffered position */
    const uint16_t *front_codes;     /* nearest shades: the front sample's voxel code at [u], the back's at [c] */
    const uint16_t *back_codes;
    bool nearest_shade, grey;
} plain_row_t;

/* Entry e of a table built as read (tables.h), found unbuilt: the block of its diagonal that holds it built. Out
 * of line: the loop meets one per block at most. */
static VF_NOINLINE void build_entry(const vfi_demand_t *demand, const uint16_t *table, uint32_t n, const uint16_t *e)
{
    const uint32_t k = (uint32_t)(e - table) / 4;
    vfi_preint_demand_entry(demand, k / n, k % n);
}

/* Pixel u's entry: its front position from the buffer (buffered) or sampled here (pr's fields), its back position
 * sampled and stored for the next slab. A 256-entry table's rounding is folded into the lerps (vfi_entry_rows) only
 * with VF_SPECIAL_LOOPS: it saves two instructions a sample on x86-64 but costs the Cortex-M4 at -Os more than it
 * saves (docs/performance.md), and the MCU build leaves the special loops out. */
static VF_ALWAYS_INLINE const uint16_t *plain_entry(const plain_loop_t *l, const plain_row_t *pr,
                                                    vfi_row_sampler_t *back, uint32_t u, bool buffered, bool n256)
{
    const uint32_t c = u - l->cu, n = l->n;
    const bool fold = VF_SPECIAL_LOOPS && n256;
    uint32_t row_f; /* front entry times N */
    if (buffered) {
        row_f = l->front_buf[c];
    } else {
        const uint8_t *p = pr->front + (u - pr->front_cu);
        row_f = n * vfi_entry_rows(p, p + pr->row, pr->front_fx, pr->front_fy, n, fold);
    }
    const uint32_t pos_b = back ? vfi_sampler_entry(back, u, n, fold)
                                : vfi_entry_rows(l->top + c, l->bottom + c, l->fx, l->fy, n, fold);
    l->back_buf[c] = pos_b * n;
    return l->table + ((size_t)row_f + pos_b) * 4;
}

/* Pixel u composited with entry e; in a table built as read, e's diagonal is built first if it is unbuilt. grey:
 * the table is grey (vfi_blend_entry). */
static VF_ALWAYS_INLINE void plain_blend(const plain_loop_t *l, const plain_row_t *pr, uint32_t u, const uint16_t *e,
                                         bool grey)
{
    if (VF_TABLE_ON_DEMAND && !e[3] && e[0] == VFI_UNBUILT_Q15) /* only ever in a table built as read */
        build_entry(pr->demand, l->table, l->n, e);
    vfi_blend_entry(l->pixels + (size_t)u * 4, l->next, u, e, grey);
}

/* The default path (nearest lookup, 16-bit table, no lut, full precision), where preint1 frames spend their time:
 * the open pixels from u, which is open, to y, their front entries from the buffer (buffered) or sampled here.
 * With VF_LOOK_AHEAD each pixel's entry is looked up one open pixel ahead of its blend, so that the branches on the
 * entry (seen, opaque) do not wait for its load, which is mostly from L2 (a 512 KB table): fewer milliseconds for
 * a few more instructions (docs/performance.md; point's loop does the same, composite_order0.c). In a table built as
 * read an unbuilt entry's diagonal is built where the loop meets it: with the image-sized buffer the look-ahead has
 * stored the next pixel's back position over its front one, so the loop may not leave there and come back.
 * Returns the first open pixel at or after y. */
static VF_ALWAYS_INLINE uint32_t span_plain(const plain_row_t *pr, uint32_t u, uint32_t y, bool buffered, bool n256,
                                            bool grey)
{
    plain_loop_t l = pr->loop;
    if (n256)
        l.n = 256;
    vfi_row_sampler_t back; /* the back samples by pixel: the slice rows from column -cu */
    vfi_sampler_init(&back, l.top - l.cu, pr->row, l.fx, l.fy, VF_SPECIAL_LOOPS && n256);
    if (!VF_LOOK_AHEAD) {
        for (; u < y; u = vfi_next_open(l.next, u + 1))
            plain_blend(&l, pr, u, plain_entry(&l, pr, &back, u, buffered, n256), grey);
        return u;
    }
    if (u >= y)
        return u;
    const uint16_t *e = plain_entry(&l, pr, &back, u, buffered, n256);
    for (;;) {
        const uint32_t u_next = vfi_next_open(l.next, u + 1); /* a blend closes only the pixel it blends */
        if (u_next >= y) { /* the span's last: one test a pixel, where the look-up ahead and the exit each had one */
            plain_blend(&l, pr, u, e, grey);
            return u_next;
        }
        const uint16_t *e_next = plain_entry(&l, pr, &back, u_next, buffered, n256);
        plain_blend(&l, pr, u, e, grey);
        u = u_next, e = e_next;
    }
}

/* A lit frame's plain loop (docs/algorithm.md, section 7): span_plain's entries, each lit with its front and back
 * samples' shades and the front-weighted values beside it, without the look-ahead (the lighting's own loads and
 * products give the entry's load time enough). A back sample's shade is buffered, packed as the shade table holds
 * it, to be the next slab's front one. nearest: each sample's shade is its nearest voxel's, read through code rows
 * with the slab's rounding folded in (plain_row_t); else the four voxels' interpolated. grey: the transfer function
 * is grey, so one colour channel is worked out for all three. */
static VF_ALWAYS_INLINE uint32_t span_plain_lit(const plain_row_t *pr, uint32_t u, uint32_t y, bool buffered, bool n256,
                                                bool nearest, bool grey)
{
    plain_loop_t l = pr->loop;
    if (n256)
        l.n = 256;
    const vfi_shading_t *sh = pr->shading;
    const uint64_t *shade = sh->shade;
    /* the rows, buffers and codes by pixel rather than by the back slice's column (from column -cu): one register
     * fewer in a loop short of them */
    const size_t off = pr->shade_offset, back_at = (size_t)(l.top - sh->slices) - l.cu;
    /* code rows only with nearest shades (else NULL, which takes no offset) */
    const uint16_t *back_codes = nearest ? pr->back_codes - l.cu : NULL, *lit = pr->lit;
    l.top -= l.cu, l.bottom -= l.cu, l.front_buf -= l.cu, l.back_buf -= l.cu, l.cu = 0;
    uint64_t right = 0;          /* bilinear: the last pixel's right column, the left one of the pixel after it */
    uint32_t last_c = UINT32_MAX - 1;
    for (; u < y; u = vfi_next_open(l.next, u + 1)) {
        const uint32_t c = u;
        /* the front shade read before the back one is stored: an image-sized buffer holds both in one place */
        uint32_t front = buffered ? l.front_buf[c + off] : 0, back;
        const uint16_t *e = plain_entry(&l, pr, NULL, u, buffered, n256);
        if (VF_TABLE_ON_DEMAND && !e[3] && e[0] == VFI_UNBUILT_Q15) /* its block, the lit values with it */
            build_entry(pr->demand, l.table, l.n, e);
        if (nearest) {
            back = vfi_shade_pack(shade[back_codes[c]]);
        } else {
            const uint64_t left = c == last_c + 1 ? right : vfi_shade_column(sh, back_at + c, pr->row, l.fy);
            right = vfi_shade_column(sh, back_at + c + 1, pr->row, l.fy);
            last_c = c;
            back = vfi_shade_pack(vfi_lanes_lerp(left, right, l.fx));
        }
        l.back_buf[c + off] = back; /* the next slab's front shade, as its position is */
        const uint32_t a = e[3];
        if (!a)
            continue;
        if (!buffered && nearest) {
            front = vfi_shade_pack(shade[pr->front_codes[u]]);
        } else if (!buffered) {
            const vfi_shade_t f = vfi_sample_shade(sh, pr->front + (u - pr->front_cu), pr->row, pr->front_fx,
                                                   pr->front_fy);
            front = f.d | f.s << 16;
        }
        const vfi_shade_t f = {front & 0xFFFFu, front >> 16, 32768u}, b = {back & 0xFFFFu, back >> 16, 32768u};
        const uint16_t *d = lit + (e - l.table);
        const uint32_t specular = vfi_lit_specular(a, d[3], f, b);
        const uint32_t r = vfi_lit_channel(e[0], d[0], a, specular, f, b);
        const uint32_t g = grey ? r : vfi_lit_channel(e[1], d[1], a, specular, f, b);
        const uint32_t bl = grey ? r : vfi_lit_channel(e[2], d[2], a, specular, f, b);
        uint16_t *px = l.pixels + (size_t)u * 4;
        if (grey ? vfi_blend_grey(px, r, a) : vfi_blend_rgba(px, r, g, bl, a))
            l.next[u] = (uint16_t)(u + 1);
    }
    return u;
}

/* span_plain_lit for the frame's shade lookup and colours: out of line, so that a row does not pay for its registers */
#if VF_SPECIAL_LOOPS
/* The default lit frame of a grey transfer function (nearest shades, a 256-entry table) with the table's size a
 * constant: span_lit's other variants take it as it comes, a test and the general rounding a pixel */
static VF_NOINLINE uint32_t span_lit_grey256(const plain_row_t *pr, uint32_t u, uint32_t y, bool buffered)
{
    return buffered ? span_plain_lit(pr, u, y, true, true, true, true)
                    : span_plain_lit(pr, u, y, false, true, true, true);
}
#endif

static VF_NOINLINE uint32_t span_lit(const plain_row_t *pr, uint32_t u, uint32_t y, bool buffered, bool n256)
{
#if VF_SPECIAL_LOOPS
    if (n256 && pr->nearest_shade && pr->grey)
        return span_lit_grey256(pr, u, y, buffered);
#endif
    if (pr->nearest_shade && pr->grey)
        return buffered ? span_plain_lit(pr, u, y, true, n256, true, true) : span_plain_lit(pr, u, y, false, n256, true, true);
    if (pr->nearest_shade)
        return buffered ? span_plain_lit(pr, u, y, true, n256, true, false)
                        : span_plain_lit(pr, u, y, false, n256, true, false);
    if (pr->grey)
        return buffered ? span_plain_lit(pr, u, y, true, n256, false, true)
                        : span_plain_lit(pr, u, y, false, n256, false, true);
    return buffered ? span_plain_lit(pr, u, y, true, n256, false, false) : span_plain_lit(pr, u, y, false, n256, false, false);
}

/* Any lookup, table format, correction, precision study or number of rays: the open pixels from u, which is open, to
 * y. Nearest positions are kept times N in the buffer (the front entry's row in the 2D table), bilinear ones as
 * they are. With one ray per voxel a pixel's column is u - cu at the slice's one fraction; with more each pixel
 * has its own. Returns the first open pixel at or after y. */
static VF_ALWAYS_INLINE uint32_t span_general_body(const row_job_t *job, uint32_t u, uint32_t y, bool buffered,
                                                   bool one_ray)
{
    const slice_place_t *fr = job->front, *bk = job->back;
    const uint32_t n = job->lookup.n, scale = job->bilinear ? 1 : n;
    for (; u < y; u = vfi_next_open(job->next, u + 1)) {
        uint32_t fx, i, pos_f;
        if (buffered) {
            pos_f = job->front_buf[u - (uint32_t)job->front_shift];
        } else {
            i = one_ray ? u - (uint32_t)fr->cu : vfi_column(fr, job->step, u, &fx);
            pos_f = scale * vfi_table_position(job, job->row_data + i, one_ray ? fr->fx : fx, job->front_fy);
        }
        uint32_t fx_b, i_b = one_ray ? u - (uint32_t)bk->cu : vfi_column(bk, job->step, u, &fx_b);
        fx_b = one_ray ? bk->fx : fx_b;
        uint32_t pos_b = vfi_table_position(job, job->back_row_data + i_b, fx_b, job->back_fy);
        job->back_buf[u - (uint32_t)job->back_shift] = pos_b * scale;
        uint32_t seg[4];
        if (VF_LIGHTING && job->shading) { /* lit: both samples' shades, the front's taken again from its voxels */
            uint32_t lit[4];
            vfi_segment_preint1_lit(job, job->bilinear ? pos_f : pos_f / n, pos_b, seg, lit);
            i = one_ray ? u - (uint32_t)fr->cu : vfi_column(fr, job->step, u, &fx);
            const vfi_shade_t front = vfi_sample_shade(job->shading, job->row_data + i, job->row,
                                                       one_ray ? fr->fx : fx, job->front_fy);
            const vfi_shade_t back = vfi_sample_shade(job->shading, job->back_row_data + i_b, job->row, fx_b,
                                                      job->back_fy);
            vfi_light_slab(seg, lit, front, back);
        } else {
            vfi_segment_preint1(job, job->bilinear ? pos_f : pos_f / n, pos_b, seg);
        }
        if (vfi_composite_segment(job, job->pixels + (size_t)u * 4, seg))
            job->next[u] = (uint16_t)(u + 1);
    }
    return u;
}

static uint32_t span_general(const row_job_t *job, uint32_t u, uint32_t y, bool buffered)
{
    if (VF_MAX_RAYS == 1 || job->step == 65536) /* constant in one-ray builds */
        return buffered ? span_general_body(job, u, y, true, true) : span_general_body(job, u, y, false, true);
    return buffered ? span_general_body(job, u, y, true, false) : span_general_body(job, u, y, false, false);
}

/* A row's walked runs (vfi_merge_runs), each cut into spans whose fronts are all buffered or all sampled here. The
 * plain path takes its arrays from pr, the general one from job. */
static VF_ALWAYS_INLINE void row(const row_job_t *job, const plain_row_t *pr, const vfi_span_t *walked, uint32_t count,
                                 const row_visits_t *last_row, bool plain, bool n256, bool lit, bool grey)
{
    const vfi_span_t *last = last_row ? last_row->span : NULL;
    const uint32_t last_count = last_row ? last_row->count : 0;
    uint16_t *next = plain ? pr->loop.next : job->next;
    uint32_t k = 0; /* the first of the last slab's runs that may reach the current pixel */
    for (uint32_t w = 0; w < count; w++) {
        const uint32_t b = walked[w].b;
        /* each span starts at an open pixel, which the last span's loop found: pixels closed all the way cost
         * nothing but the step past them */
        for (uint32_t u = vfi_next_open(next, walked[w].a); u < b;) {
            bool buffered;
            const uint32_t y = vfi_buffered_until(last, last_count, &k, u, b, &buffered);
            if (!plain) {
                u = span_general(job, u, y, buffered);
                continue;
            }
            if (VF_LIGHTING && lit)
                u = span_lit(pr, u, y, buffered, n256);
            else
                u = buffered ? span_plain(pr, u, y, true, n256, grey) : span_plain(pr, u, y, false, n256, grey);
        }
    }
}

/* The runs the last slab walked in row v_lo + k, or NULL unless it was slab t - 1 */
static inline const row_visits_t *last_visits(const vfi_slab_rows_t *s, uint32_t k, uint32_t t)
{
    return s->last && s->last[k].slab + 1 == t ? &s->last[k] : NULL;
}

/* The slab's rows. The plain path has one ray per voxel: every intermediate row samples the next slice row at the
 * same fraction, so row v_lo + k's slice rows, runs and arrays are k rows, cell rows and strides after row v_lo's,
 * and what its loops read is set up once (pr). The general path sets job's row fields for each row (with more rays
 * the fraction and slice row are the row's own). */
static VF_ALWAYS_INLINE void slab_rows(row_job_t *job, const vfi_slab_rows_t *s, bool plain, bool n256, bool lit,
                                      bool grey)
{
    const slice_place_t *front = job->front, *back = job->back;
    const int32_t lo = MAX(front->u_lo, back->u_lo), hi = MIN(front->u_hi, back->u_hi);
    const uint32_t t = job->t, row_bytes = job->row, rows = (uint32_t)(s->v_hi - s->v_lo + 1);
    const uint32_t *runs = s->runs->row_start + s->kc * s->runs->nj;
    const uint16_t *pairs = s->runs->pairs;
    plain_row_t pr;
    uint32_t j_f, j_b;
    const uint8_t *front_data = vfi_slice_row(front, row_bytes, job->step, s->v_lo, &j_f, &pr.front_fy);
    const uint8_t *back_data = vfi_slice_row(back, row_bytes, job->step, s->v_lo, &j_b, &pr.loop.fy);
    if (plain) {
        pr.loop.cu = (uint32_t)back->cu;
        pr.loop.fx = back->fx;
        pr.loop.table = job->lookup.q15;
        pr.loop.n = job->lookup.n;
        pr.front_cu = (uint32_t)front->cu;
        pr.front_fx = front->fx;
        pr.row = row_bytes;
        pr.demand = job->demand;
        pr.shading = job->shading;
        pr.lit = job->lookup.lit_q15;
        pr.shade_offset = job->shade_offset;
        pr.nearest_shade = lit && !job->shading->bilinear;
        pr.grey = job->grey;
    }
    const uint32_t *runs_f0 = runs + j_f, *runs_b0 = runs + j_b; /* row v_lo's */
    /* the plain loops address the buffers by the back slice's column (a slice buffer's front one is -1, 0 or 1 off) */
    uint32_t *front_buf = s->front_buf + (plain ? back->cu - job->front_shift : 0);
    uint32_t *back_buf = s->back_buf + (plain ? back->cu - job->back_shift : 0);
    for (uint32_t k = 0; k < rows; k++) {
        if (!plain) {
            job->row_data = vfi_slice_row(front, row_bytes, job->step, s->v_lo + (int32_t)k, &j_f, &job->front_fy);
            job->back_row_data = vfi_slice_row(back, row_bytes, job->step, s->v_lo + (int32_t)k, &j_b, &job->back_fy);
        }
        const uint32_t *runs_f = plain ? runs_f0 + k : runs + j_f, *runs_b = plain ? runs_b0 + k : runs + j_b;
        if (runs_f[0] == runs_f[1] && runs_b[0] == runs_b[1])
            continue; /* nothing visible: the row is not walked, and the next slab samples its fronts */
        if (plain) {
            pr.loop.top = back_data + (size_t)k * row_bytes;
            pr.loop.bottom = pr.loop.top + row_bytes;
            pr.loop.front_buf = front_buf + (size_t)k * s->buf_stride;
            pr.loop.back_buf = back_buf + (size_t)k * s->buf_stride;
            pr.loop.next = s->next + (size_t)k * s->next_stride;
            pr.loop.pixels = s->pixels + (size_t)k * s->pixel_stride;
            pr.front = front_data + (size_t)k * row_bytes;
            if (VF_LIGHTING && lit && pr.nearest_shade) { /* the nearest voxel's codes, the rounding folded in */
                const vfi_shading_t *sh = job->shading;
                pr.back_codes = sh->codes + (pr.loop.top - sh->slices) + (pr.loop.fy >= 32768u ? row_bytes : 0) +
                                (pr.loop.fx >= 32768u ? 1 : 0);
                pr.front_codes = sh->codes + (pr.front - sh->slices) + (pr.front_fy >= 32768u ? row_bytes : 0) +
                                 (pr.front_fx >= 32768u ? 1 : 0) - pr.front_cu;
            }
        } else {
            job->front_buf = front_buf + (size_t)k * s->buf_stride;
            job->back_buf = back_buf + (size_t)k * s->buf_stride;
            job->next = s->next + (size_t)k * s->next_stride;
            job->pixels = s->pixels + (size_t)k * s->pixel_stride;
        }
        const row_visits_t *last = last_visits(s, k, t);
        row_visits_t *now = &s->now[k];
        now->slab = t;
        run_merge_t m; /* plain: one ray, step_shift 16, said as a constant so that the streams' test of it goes */
        vfi_merge_init(&m, plain ? 16 : job->step_shift, pairs + runs_f[0], pairs + runs_f[1], front,
                       pairs + runs_b[0], pairs + runs_b[1], back);
        now->count = vfi_merge_runs(&m, lo, hi, now->span);
        row(job, &pr, now->span, now->count, last, plain, n256, lit, grey);
    }
}

#if VF_LIGHTING
static VF_NOINLINE void slab_rows_lit(row_job_t *job, const vfi_slab_rows_t *s)
{
    if (job->lookup.n == 256)
        slab_rows(job, s, true, true, true, false);
    else
        slab_rows(job, s, true, false, true, false);
}
#endif

#if VF_SPECIAL_LOOPS
/* A grey transfer function's table (r = g = b in every entry): one colour product a pixel for three */
static VF_NOINLINE void slab_rows_grey(row_job_t *job, const vfi_slab_rows_t *s)
{
    slab_rows(job, s, true, true, false, true);
}
#endif

void vfi_slab_preint1(row_job_t *job, const vfi_slab_rows_t *s)
{
#if VF_LIGHTING
    if (job->plain_lit) {
        slab_rows_lit(job, s);
        return;
    }
#endif
#if VF_SPECIAL_LOOPS
    if (job->plain && job->lookup.n == 256 && job->grey) {
        slab_rows_grey(job, s);
        return;
    }
#endif
    if (!job->plain)
        slab_rows(job, s, false, false, false, false);
    else if (job->lookup.n == 256)
        slab_rows(job, s, true, true, false, false);
    else
        slab_rows(job, s, true, false, false, false);
}
