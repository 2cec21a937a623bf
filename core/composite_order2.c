/* SPDX-License-Identifier: MIT */
/*
 * composite_order2.c: a band of preint2 (docs/algorithm.md, section 8): slabs of two slices, k = 0, 2, 4, ..., each
 * open pixel of the visible runs taking the order-2 entry of its front, middle and back sample; and, when the
 * volume has an odd number of slabs, the last slab of one slice, an order-1 slab (composite_order1.c).
 *
 * Empty space. Each entry's curve stays within its three scalars (section 8), so a slab's segment is exactly zero
 * unless the cells around its three samples (slab k's cell of the front sample, slab k's of the middle one and
 * slab k + 1's of the back one, which share voxels in that chain: |shear| <= 1) hold a visible entry; the run
 * encoding counts the entries an order-2 sample can reach through its table entries' scalars
 * (vfi_order2_scalar_entries). A row's pixels are the union of those three run streams.
 *
 * Buffers. A slab's back sample is the next slab's front sample: its table position is buffered as preint1
 * buffers its back sample's, and whether a pixel's buffered position is this slab's front is known per run, from
 * the runs the last slab walked (composite_order1.c says why that is exact). The middle sample is the slab's own.
 */
#include "composite.h"

#if VF_ORDER2

#define MIN(a, b) ((a) < (b) ? (a) : (b))
#define MAX(a, b) ((a) > (b) ? (a) : (b))

/* One slab's rows: preint1's job (front and back slices, buffers, pixels) with the middle slice and the 3D table. */
typedef struct order2_job {
    row_job_t *job;
    const slice_place_t *mid;
    const uint8_t *mid_row_data;
    uint32_t mid_fy;
    vfi_lookup2_t t2;
    bool trilinear;
} order2_job_t;

/* Where a sample s (Q8.32) goes in the 3D table: its nearest entry, or (trilinear) its position in Q.16; for
 * precision studies rounded first, as vfi_position_of does. */
static inline uint32_t position2(const order2_job_t *o, uint64_t s)
{
    const uint32_t shift = o->job->sample_shift;
    if (shift)
        s = ((s + (UINT64_C(1) << (shift - 1))) >> shift) << shift;
    return o->trilinear ? vfi_position_of_sample_n(o->t2.n2, s) : vfi_entry_of_sample_n(o->t2.n2, s);
}

/* The sample of slice sl at pixel u of the row whose slice row is data (fraction fy to the next), and the voxel it
 * starts at (for its shade). */
static inline uint64_t sample_at(const row_job_t *job, const slice_place_t *sl, const uint8_t *data, uint32_t fy,
                                 uint32_t u, bool one_ray, const uint8_t **voxel, uint32_t *fx)
{
    uint32_t x_fx, i = one_ray ? u - (uint32_t)sl->cu : vfi_column(sl, job->step, u, &x_fx);
    *fx = one_ray ? sl->fx : x_fx;
    *voxel = data + i;
    return vfi_sample_at(*voxel, job->row, *fx, fy);
}

/* The 3D entry (and with lighting its eight weighted values) of positions pf, pm, pb; corrected by the lut. */
static VF_ALWAYS_INLINE void segment2(const order2_job_t *o, uint32_t pf, uint32_t pm, uint32_t pb, uint32_t seg[4],
                                      uint32_t lit[8], bool with_lit)
{
    const vfi_lookup2_t *c = &o->t2;
    const size_t n2 = c->n2;
    if (o->trilinear) {
        uint32_t i, fi, j, fj, k, fk, w4[4];
        vfi_split_position(c->n2, pf, &i, &fi);
        vfi_split_position(c->n2, pm, &j, &fj);
        vfi_split_position(c->n2, pb, &k, &fk);
        vfi_weights(fi, fj, w4); /* w00 w10 w01 w11 over (front, middle) */
        uint32_t acc[4] = {0x8000u, 0x8000u, 0x8000u, 0x8000u}, lacc[8];
        for (int q = 0; q < 8; q++)
            lacc[q] = 0x8000u;
        for (int corner = 0; corner < 4; corner++) {
            /* the corner's weight split over back entries k and k + 1, summing to it exactly */
            const uint32_t whi = (uint32_t)(((uint64_t)w4[corner] * fk + 0x8000u) >> 16), wlo = w4[corner] - whi;
            const size_t e = ((i + (corner & 1)) * n2 + j + (corner >> 1)) * n2 + k;
            uint32_t v[4], l[4];
            for (int side = 0; side < 2; side++) {
                const uint32_t w = side ? whi : wlo;
                vfi_fetch_from(c->q15, c->u8, e + (size_t)side, v);
                for (int q = 0; q < 4; q++) /* at most 32768 * 65536 in all */
                    acc[q] += v[q] * w;
                if (with_lit)
                    for (int h = 0; h < 2; h++) {
                        vfi_fetch_from(c->lit_q15, c->lit_u8, 2 * (e + (size_t)side) + (size_t)h, l);
                        for (int q = 0; q < 4; q++)
                            lacc[4 * h + q] += l[q] * w;
                    }
            }
        }
        for (int q = 0; q < 4; q++)
            seg[q] = acc[q] >> 16;
        if (with_lit)
            for (int q = 0; q < 8; q++)
                lit[q] = lacc[q] >> 16;
    } else {
        const size_t e = ((size_t)pf * n2 + pm) * n2 + pb;
        vfi_fetch_from(c->q15, c->u8, e, seg);
        if (with_lit) {
            vfi_fetch_from(c->lit_q15, c->lit_u8, 2 * e, lit);
            vfi_fetch_from(c->lit_q15, c->lit_u8, 2 * e + 1, lit + 4);
        }
    }
    const vfi_lookup_ctx_t *lc = &o->job->lookup;
    if (lc->lut_f) { /* the lut of preint1's 2D table: both are built for d0 and corrected for d / d0 */
        uint32_t fa;
        const uint64_t g = vfi_lut_at(lc->lut_f, lc->lut_g, seg[3], &fa);
        for (int q = 0; q < 3; q++)
            seg[q] = vfi_lut_colour(seg[q], g);
        if (with_lit)
            for (int q = 0; q < 8; q++)
                lit[q] = vfi_lut_colour(lit[q], g);
        seg[3] = fa;
    }
}

/* A slab lit with its three samples' shades (section 8): C' = L_df W_f + L_dm (C - W_f - W_b) + L_db W_b and the
 * same for the specular with a, clamped to [0, a], then times (g_f + 2 g_m + g_b) / 4. The middle weight is taken
 * at least 0: the table keeps W_f + W_b <= C but for the rounding of each, a part of an LSB. Every term is then
 * non-negative and the sum, at most 3 C + 2 a in Q2.14 x Q1.15, fits 32 bits. */
static inline void light_slab2(uint32_t seg[4], const uint32_t w[8], vfi_shade_t f, vfi_shade_t m, vfi_shade_t b)
{
    const uint32_t a = seg[3];
    const uint32_t s_mid = a > w[3] + w[7] ? a - w[3] - w[7] : 0;
    const uint32_t specular = f.s * w[3] + m.s * s_mid + b.s * w[7];
    for (int c = 0; c < 3; c++) {
        const uint32_t mid = seg[c] > w[c] + w[4 + c] ? seg[c] - w[c] - w[4 + c] : 0;
        const uint32_t v = (f.d * w[c] + m.d * mid + b.d * w[4 + c] + specular + 0x2000u) >> 14;
        seg[c] = v < a ? v : a;
    }
    const uint32_t g = (f.g + 2 * m.g + b.g + 2) >> 2;
    if (g != 32768u)
        for (int c = 0; c < 4; c++)
            seg[c] = (seg[c] * g + 0x4000u) >> 15;
}

/* The open pixels from u, which is open, to y: their front positions from the buffer (buffered) or sampled here,
 * the middle and back sampled, the back buffered. Returns the first open pixel at or after y. */
static VF_ALWAYS_INLINE uint32_t span_body(const order2_job_t *o, uint32_t u, uint32_t y, bool buffered, bool one_ray,
                                           bool lit)
{
    const row_job_t *job = o->job;
    for (; u < y; u = vfi_next_open(job->next, u + 1)) {
        const uint8_t *vf = NULL, *vm, *vb;
        uint32_t fx_f = 0, fx_m, fx_b, pos_f;
        if (buffered)
            pos_f = job->front_buf[u - (uint32_t)job->front_shift];
        else
            pos_f = position2(o, sample_at(job, job->front, job->row_data, job->front_fy, u, one_ray, &vf, &fx_f));
        const uint32_t pos_m = position2(o, sample_at(job, o->mid, o->mid_row_data, o->mid_fy, u, one_ray, &vm, &fx_m));
        const uint32_t pos_b =
            position2(o, sample_at(job, job->back, job->back_row_data, job->back_fy, u, one_ray, &vb, &fx_b));
        job->back_buf[u - (uint32_t)job->back_shift] = pos_b;
        uint32_t seg[4], w[8];
        if (VF_LIGHTING && lit) { /* the front's shade taken again from its voxels when its position was buffered */
            segment2(o, pos_f, pos_m, pos_b, seg, w, true);
            if (buffered)
                (void)sample_at(job, job->front, job->row_data, job->front_fy, u, one_ray, &vf, &fx_f);
            const vfi_shading_t *sh = job->shading;
            light_slab2(seg, w, vfi_sample_shade(sh, vf, job->row, fx_f, job->front_fy),
                        vfi_sample_shade(sh, vm, job->row, fx_m, o->mid_fy),
                        vfi_sample_shade(sh, vb, job->row, fx_b, job->back_fy));
        } else {
            segment2(o, pos_f, pos_m, pos_b, seg, w, false);
        }
        if (vfi_composite_segment(job, job->pixels + (size_t)u * 4, seg))
            job->next[u] = (uint16_t)(u + 1);
    }
    return u;
}

static uint32_t span(const order2_job_t *o, uint32_t u, uint32_t y, bool buffered)
{
    const bool one_ray = VF_MAX_RAYS == 1 || o->job->step == 65536, lit = VF_LIGHTING && o->job->shading;
    if (lit)
        return one_ray ? (buffered ? span_body(o, u, y, true, true, true) : span_body(o, u, y, false, true, true))
                       : (buffered ? span_body(o, u, y, true, false, true) : span_body(o, u, y, false, false, true));
    return one_ray ? (buffered ? span_body(o, u, y, true, true, false) : span_body(o, u, y, false, true, false))
                   : (buffered ? span_body(o, u, y, true, false, false) : span_body(o, u, y, false, false, false));
}

/* The default path (nearest lookup, 16-bit tables, full precision, one ray, unlit; with or without the lut, which
 * preint2 corrects each segment by: it has no view table), where preint2 frames spend their time: what the loop
 * reads for one row, set up once a row. Each slice's samples
 * are at column u - cu of its row with the slice's one fraction; the buffered positions are the back entries times
 * N2^2, the front entry's offset in the 3D table (the general loop buffers the entries themselves: a frame reads
 * them in the path that wrote them). */
typedef struct plain2 {
    const uint8_t *front, *mid, *back; /* the three samples' first slice rows */
    uint32_t front_cu, mid_cu, back_cu;
    uint32_t front_fx, front_fy, mid_fx, mid_fy, back_fx, back_fy, row, n2;
    const uint32_t *front_buf;         /* by u - front_shift, as the general loop's */
    uint32_t *back_buf;                /* by u - back_shift */
    uint32_t front_shift, back_shift;
    const uint16_t *table;
    uint16_t *next, *pixels;
    const uint16_t *lut_f;             /* the lut, or NULL */
    const uint32_t *lut_g;
} plain2_t;

static VF_ALWAYS_INLINE uint32_t plain_entry2(const uint8_t *p, uint32_t row, uint32_t fx, uint32_t fy, uint32_t n2)
{
    return vfi_entry_of_sample_n(n2, vfi_sample_rows(p, p + row, fx, fy));
}

/* The open pixels from u, which is open, to y, their front entries from the buffer (buffered) or sampled here; the
 * first open pixel at or after y. A copy of the row's record in a local, as composite_order1.c's span_plain keeps
 * one, so that the stores cannot make the compiler read it again. */
static VF_ALWAYS_INLINE uint32_t span_plain2(const plain2_t *pl, uint32_t u, uint32_t y, bool buffered, bool lut)
{
    const plain2_t l = *pl;
    const uint32_t n2 = l.n2, plane = n2 * n2;
    for (; u < y; u = vfi_next_open(l.next, u + 1)) {
        const uint32_t f = buffered ? l.front_buf[u - l.front_shift]
                                    : plane * plain_entry2(l.front + (u - l.front_cu), l.row, l.front_fx, l.front_fy, n2);
        const uint32_t m = plain_entry2(l.mid + (u - l.mid_cu), l.row, l.mid_fx, l.mid_fy, n2);
        const uint32_t b = plain_entry2(l.back + (u - l.back_cu), l.row, l.back_fx, l.back_fy, n2);
        l.back_buf[u - l.back_shift] = b * plane;
        const uint16_t *e = l.table + ((size_t)f + m * n2 + b) * 4;
        if (!lut) {
            vfi_blend_entry(l.pixels + (size_t)u * 4, l.next, u, e, false);
        } else if (e[3]) { /* segment.h's vfi_correct, written out */
            uint32_t seg[4], fa;
            const uint64_t g = vfi_lut_at(l.lut_f, l.lut_g, e[3], &fa);
            for (int c = 0; c < 3; c++)
                seg[c] = vfi_lut_colour(e[c], g);
            seg[3] = fa;
            if (vfi_blend(l.pixels + (size_t)u * 4, seg))
                l.next[u] = (uint16_t)(u + 1);
        }
    }
    return u;
}

static VF_NOINLINE uint32_t span_plain2_buffered(const plain2_t *pl, uint32_t u, uint32_t y)
{
    return pl->lut_f ? span_plain2(pl, u, y, true, true) : span_plain2(pl, u, y, true, false);
}

static VF_NOINLINE uint32_t span_plain2_sampled(const plain2_t *pl, uint32_t u, uint32_t y)
{
    return pl->lut_f ? span_plain2(pl, u, y, false, true) : span_plain2(pl, u, y, false, false);
}

/* The union of a merge of two streams and a third stream, clipped to pixels [lo, hi], into walked; how many. */
static uint32_t merge_three(run_merge_t *m, run_stream_t *s, int32_t lo, int32_t hi, vfi_span_t *walked)
{
    int32_t a0, b0, a1, b1;
    if (!vfi_merge_next(m, &a0, &b0))
        a0 = b0 = VFI_RUN_END;
    vfi_stream_next(s, &a1, &b1);
    uint32_t count = 0;
    for (;;) {
        int32_t a, b;
        if (a0 <= a1) {
            if (a0 == VFI_RUN_END)
                break;
            a = a0, b = b0;
            if (!vfi_merge_next(m, &a0, &b0))
                a0 = b0 = VFI_RUN_END;
        } else {
            a = a1, b = b1;
            vfi_stream_next(s, &a1, &b1);
        }
        for (;;) { /* take every interval that overlaps or touches [a, b) */
            if (a0 <= b) {
                b = MAX(b, b0);
                if (!vfi_merge_next(m, &a0, &b0))
                    a0 = b0 = VFI_RUN_END;
            } else if (a1 <= b) {
                b = MAX(b, b1);
                vfi_stream_next(s, &a1, &b1);
            } else {
                break;
            }
        }
        a = MAX(a, lo);
        b = MIN(b, hi + 1);
        if (a < b) {
            walked[count].a = (uint32_t)a;
            walked[count].b = (uint32_t)b;
            count++;
        }
    }
    return count;
}

/* A row's walked spans, each cut into spans whose fronts are all buffered (the last slab walked them) or all
 * sampled here, as composite_order1.c's row() cuts them. */
static void row(const order2_job_t *o, const plain2_t *pl, const vfi_span_t *walked, uint32_t count,
                const row_visits_t *last_row)
{
    const vfi_span_t *last = last_row ? last_row->span : NULL;
    const uint32_t last_count = last_row ? last_row->count : 0;
    uint16_t *next = o->job->next;
    uint32_t k = 0;
    for (uint32_t w = 0; w < count; w++) {
        const uint32_t b = walked[w].b;
        for (uint32_t u = vfi_next_open(next, walked[w].a); u < b;) {
            bool buffered;
            const uint32_t y = vfi_buffered_until(last, last_count, &k, u, b, &buffered);
            if (pl)
                u = buffered ? span_plain2_buffered(pl, u, y) : span_plain2_sampled(pl, u, y);
            else
                u = span(o, u, y, buffered);
        }
    }
}

/* The cell slab between standard slices t and t + 1, in the copy's order. */
static inline uint32_t cell_slab(const vf_factor_t *f, uint32_t t)
{
    return f->k_flip ? f->nk - 2 - t : t;
}

void vfi_band_order2(const vf_renderer_t *r, row_job_t *job, const vfi_band_t *band)
{
    const vf_factor_t *f = &r->factor;
    const vfi_layout_t *l = &r->layout[f->k_axis];
    const uint32_t rows = band->v1 - band->v0, width = f->int_w, nk = l->nk;
    const bool image_buffer = r->params.buffer == VF_BUFFER_IMAGE;
    const vfi_runs_t *runs = &r->runs[f->k_axis];
    order2_job_t o;
    o.job = job;
    o.t2 = r->lookup2;
    o.trilinear = r->params.lookup == VF_LOOKUP_TRILINEAR;
    /* the plain loop: composite.c's plain path, but for the lut, which it takes too */
    const bool plain = !r->general_loops && !o.trilinear && o.t2.q15 && !job->sample_shift && !job->inter_shift &&
                       job->step == 65536 && !(VF_LIGHTING && job->shading);
    slice_place_t place[3];
    vfi_place_slice(r, 0, &place[0]);
    uint32_t q = 0; /* the order-2 slab's number; slab q spans slices 2q .. 2q + 2 */
    for (uint32_t t = 0; t + 2 < nk; t += 2, q++) {
        const slice_place_t *front = &place[0];
        slice_place_t *mid = &place[1], *back = &place[2];
        vfi_place_slice(r, t + 1, mid);
        vfi_place_slice(r, t + 2, back);
        /* rows and pixels where all three samples are inside */
        const int32_t lo = MAX(MAX(MAX(front->v_lo, mid->v_lo), back->v_lo), (int32_t)band->v0);
        const int32_t hi = MIN(MIN(MIN(front->v_hi, mid->v_hi), back->v_hi), (int32_t)band->v1 - 1);
        const int32_t u_lo = MAX(MAX(front->u_lo, mid->u_lo), back->u_lo);
        const int32_t u_hi = MIN(MIN(front->u_hi, mid->u_hi), back->u_hi);
        job->front = front;
        job->back = back;
        job->t = t;
        job->front_shift = image_buffer ? 0 : front->cu;
        job->back_shift = image_buffer ? 0 : back->cu;
        o.mid = mid;
        const uint32_t *row_start = runs->row_start;
        const uint32_t kc0 = cell_slab(f, t) * runs->nj, kc1 = cell_slab(f, t + 1) * runs->nj;
        for (int32_t v = lo; v <= hi && u_lo <= u_hi; v++) {
            const size_t band_row = (size_t)(v - (int32_t)band->v0);
            uint32_t j_f, j_m, j_b;
            job->row_data = vfi_slice_row(front, job->row, job->step, v, &j_f, &job->front_fy);
            o.mid_row_data = vfi_slice_row(mid, job->row, job->step, v, &j_m, &o.mid_fy);
            job->back_row_data = vfi_slice_row(back, job->row, job->step, v, &j_b, &job->back_fy);
            const uint32_t *rf = row_start + kc0 + j_f, *rm = row_start + kc0 + j_m, *rb = row_start + kc1 + j_b;
            if (rf[0] == rf[1] && rm[0] == rm[1] && rb[0] == rb[1])
                continue; /* nothing visible: the row is not walked, and the next slab samples its fronts */
            job->front_buf = band->buf[image_buffer ? 0 : q & 1] + band_row * band->buf_row + band->buf_first;
            job->back_buf = band->buf[image_buffer ? 0 : (q + 1) & 1] + band_row * band->buf_row + band->buf_first;
            job->next = band->next + band_row * (width + 1);
            job->pixels = r->intermediate + (size_t)v * width * 4;
            const row_visits_t *last = &band->visits[((q + 1) & 1) * rows + band_row];
            row_visits_t *now = &band->visits[(q & 1) * rows + band_row];
            if (q == 0 || last->slab + 1 != q)
                last = NULL;
            now->slab = q;
            run_merge_t m;
            run_stream_t s3;
            const uint16_t *pairs = runs->pairs;
            vfi_merge_init(&m, job->step_shift, pairs + rf[0], pairs + rf[1], front, pairs + rm[0], pairs + rm[1],
                           mid);
            vfi_stream_init(&s3, pairs + rb[0], pairs + rb[1], back, job->step_shift);
            now->count = merge_three(&m, &s3, u_lo, u_hi, now->span);
            plain2_t pl;
            if (plain) {
                pl.front = job->row_data, pl.mid = o.mid_row_data, pl.back = job->back_row_data;
                pl.front_cu = (uint32_t)front->cu, pl.mid_cu = (uint32_t)mid->cu, pl.back_cu = (uint32_t)back->cu;
                pl.front_fx = front->fx, pl.mid_fx = mid->fx, pl.back_fx = back->fx;
                pl.front_fy = job->front_fy, pl.mid_fy = o.mid_fy, pl.back_fy = job->back_fy;
                pl.row = job->row, pl.n2 = o.t2.n2;
                pl.front_buf = job->front_buf, pl.back_buf = job->back_buf;
                pl.front_shift = (uint32_t)job->front_shift, pl.back_shift = (uint32_t)job->back_shift;
                pl.table = o.t2.q15;
                pl.next = job->next, pl.pixels = job->pixels;
                pl.lut_f = job->lookup.lut_f, pl.lut_g = job->lookup.lut_g;
            }
            row(&o, plain ? &pl : NULL, now->span, now->count, last);
        }
        place[0] = place[2];
    }
    if (nk % 2 == 1)
        return; /* n_k - 1 slabs, even: all of them in twos */
    /* the last slab, slices n_k - 2 and n_k - 1: an order-1 slab (section 8), its front sampled here */
    const uint32_t t = nk - 2;
    slice_place_t *front = &place[0], *back = &place[1];
    vfi_place_slice(r, t + 1, back);
    const int32_t lo = MAX(MAX(front->v_lo, back->v_lo), (int32_t)band->v0);
    const int32_t hi = MIN(MIN(front->v_hi, back->v_hi), (int32_t)band->v1 - 1);
    if (lo > hi || MAX(front->u_lo, back->u_lo) > MIN(front->u_hi, back->u_hi))
        return;
    job->front = front;
    job->back = back;
    job->t = t;
    job->front_shift = image_buffer ? 0 : front->cu;
    job->back_shift = image_buffer ? 0 : back->cu;
    const size_t band_row = (size_t)(lo - (int32_t)band->v0);
    vfi_slab_rows_t s;
    s.v_lo = lo, s.v_hi = hi;
    s.runs = runs;
    s.kc = cell_slab(f, t);
    s.next = band->next + band_row * (width + 1);
    s.next_stride = width + 1;
    s.pixels = r->intermediate + (size_t)lo * width * 4;
    s.pixel_stride = (size_t)width * 4;
    s.front_buf = band->buf[image_buffer ? 0 : q & 1] + band_row * band->buf_row + band->buf_first;
    s.back_buf = band->buf[image_buffer ? 0 : (q + 1) & 1] + band_row * band->buf_row + band->buf_first;
    s.buf_stride = band->buf_row;
    s.last = NULL; /* the buffers hold order-2 positions */
    s.now = &band->visits[(q & 1) * rows + band_row];
    vfi_slab_preint1(job, &s);
}

#endif /* VF_ORDER2 */
