/*
 * composite.c: slabs front to back into the intermediate image, one band of intermediate rows at a time
 * (docs/algorithm.md, sections 4 and 4b).
 *
 * For each slab (or slice, in the order-0 modes) each row of the band is walked only where the run-length
 * encoding says a cell is visible, and only over pixels that are not yet opaque (skip links). Samples are
 * bilinear in the slice and exact: the slice offsets lie on the 2^-16 grid, so a sample is a multiple of 2^-32
 * and fits Q8.32, and its nearest table entry is the one the double reference picks. The back sample's table
 * position is kept in a buffer and reused as the next slab's front sample.
 *
 * Scratch per band (caller's memory, so that bands can run on threads at once):
 *   next     [rows][int_w + 1]      skip links: next[u] == u for an open pixel, else a pixel further right
 *   buffers  preint1 only: slice-sized, two of [rows][n_i + 1] indexed by slice column (front, back), or
 *            image-sized, one of [rows][int_w] indexed by pixel and updated in place
 */
#include "arena.h"
#include "segment.h"

#define SCRATCH_ALIGN 16

/* Where a standard slice lands in the intermediate image. */
typedef struct slice_place {
    const uint8_t *data;        /* the slice in the standard-order copy */
    int32_t cu, cv;             /* pixel u = cu + i samples column i at fraction fx (likewise v, rows) */
    uint32_t fx, fy;            /* Q0.16: the exact fractions (the offsets are on the 2^-16 grid) */
    int32_t u_lo, u_hi;         /* pixels whose sample is inside the slice, inclusive */
    int32_t v_lo, v_hi;
} slice_place_t;

/* A row's visible runs as intervals of pixels. */
typedef struct run_stream {
    const uint16_t *p, *end;
    int32_t pos;                /* pixel of the next cell */
} run_stream_t;

/* The union of a front and a back run stream. */
typedef struct run_merge {
    run_stream_t s[2];
    int32_t a[2], b[2];         /* each stream's current interval [a, b) */
    bool live[2];
} run_merge_t;

/* What one row of one slab (or slice) needs. */
typedef struct row_job {
    const slice_place_t *front, *back; /* back is NULL in the order-0 modes */
    const uint8_t *row_data;           /* the front (order 0: the) slice's row under this intermediate row */
    const uint8_t *back_row_data;
    uint32_t row;                      /* bytes per slice row */
    uint32_t t;                        /* standard slice (order 0) or slab (preint1) */
    const vfi_classify_t *cls;
    vfi_lookup_ctx_t lookup;
    bool plain;                        /* nearest lookup, 16-bit table, no lut, full precision: the fast path */
    bool bilinear;
    uint32_t sample_shift;             /* precision studies: samples rounded to 32 - shift fraction bits (0: exact) */
    uint32_t inter_shift;              /* precision studies: accumulators rounded to multiples of 2^shift in Q1.15 */
    vfi_sample_t *front_buf, *back_buf;
    int32_t front_shift, back_shift;   /* buffer index = u - shift */
    uint16_t *next;
    uint16_t *pixels;
} row_job_t;

static void place_slice(const vf_renderer_t *r, uint32_t t, slice_place_t *p);
static void merge_init(run_merge_t *m, const uint16_t *p0, const uint16_t *e0, int32_t pos0, const uint16_t *p1,
                       const uint16_t *e1, int32_t pos1);
static bool merge_next(run_merge_t *m, int32_t *a, int32_t *b);
static void row_order0(const row_job_t *job, run_merge_t *m, bool preclass);
static void row_preint1(const row_job_t *job, run_merge_t *m);
static unsigned char *align_up(unsigned char *p);

size_t vfi_band_scratch_bytes(const vf_renderer_t *r, uint32_t rows)
{
    size_t bytes = 2 * SCRATCH_ALIGN + sizeof(uint16_t) * rows * ((size_t)r->max_int_w + 1);
    if (r->params.mode != VF_MODE_PREINT1)
        return bytes;
    if (r->params.buffer == VF_BUFFER_IMAGE)
        return bytes + SCRATCH_ALIGN + sizeof(vfi_sample_t) * rows * (size_t)r->max_int_w;
    return bytes + SCRATCH_ALIGN + 2 * sizeof(vfi_sample_t) * rows * ((size_t)r->max_ni + 1);
}

vf_status_t vfi_composite_band(const vf_renderer_t *r, uint32_t v0, uint32_t v1, void *scratch, size_t bytes)
{
    const vf_factor_t *f = &r->factor;
    const vfi_layout_t *l = &r->layout[f->k_axis];
    const uint32_t rows = v1 - v0, width = f->int_w;
    const bool image_buffer = r->params.buffer == VF_BUFFER_IMAGE;
    if (bytes < vfi_band_scratch_bytes(r, rows))
        return VF_ERR_NOMEM;

    /* Carve the scratch; open every pixel; no buffered sample belongs to any slice yet; clear the band. */
    uint16_t *next = (uint16_t *)align_up(scratch);
    for (uint32_t y = 0; y < rows; y++)
        for (uint32_t u = 0; u <= width; u++)
            next[(size_t)y * (width + 1) + u] = (uint16_t)u;
    vfi_sample_t *buf[2] = {NULL, NULL};
    size_t buf_row = image_buffer ? width : l->ni + 1;
    if (r->params.mode == VF_MODE_PREINT1) {
        buf[0] = (vfi_sample_t *)align_up((unsigned char *)(next + (size_t)rows * (width + 1)));
        buf[1] = image_buffer ? buf[0] : buf[0] + rows * buf_row;
        for (size_t e = 0; e < (image_buffer ? 1u : 2u) * rows * buf_row; e++)
            buf[0][e] = VFI_NO_SLICE;
    }
    uint16_t *band = r->intermediate + (size_t)v0 * width * 4;
    for (size_t e = 0; e < (size_t)rows * width * 4; e++)
        band[e] = 0;

    row_job_t job;
    vfi_zero(&job, sizeof job);
    job.cls = &r->cls;
    job.row = l->row;
    job.lookup = r->lookup;
    job.bilinear = r->params.lookup == VF_LOOKUP_BILINEAR;
    job.sample_shift = r->params.sample_bits ? 32 - r->params.sample_bits : 0;
    job.inter_shift = 16 - r->params.intermediate_bits;
    job.plain = !job.bilinear && job.lookup.q15 && !job.lookup.lut_f && !job.sample_shift && !job.inter_shift;
    const vfi_runs_t *runs = &r->runs[f->k_axis];
    slice_place_t place[2];

    if (r->params.mode != VF_MODE_PREINT1) {
        const bool preclass = r->params.mode == VF_MODE_PRECLASS;
        for (uint32_t t = 0; t < l->nk; t++) {
            place_slice(r, t, &place[0]);
            uint32_t ks = f->k_flip ? l->nk - 1 - t : t;
            uint32_t kc = ks < l->nk - 1 ? ks : l->nk - 2; /* the cell slab that has slice ks as a face */
            int32_t lo = place[0].v_lo > (int32_t)v0 ? place[0].v_lo : (int32_t)v0;
            int32_t hi = place[0].v_hi < (int32_t)v1 - 1 ? place[0].v_hi : (int32_t)v1 - 1;
            job.front = &place[0];
            job.t = t;
            for (int32_t v = lo; v <= hi; v++) {
                const uint16_t *end, *p = vfi_runs_row(runs, kc, (uint32_t)(v - place[0].cv), &end);
                run_merge_t m;
                merge_init(&m, p, end, place[0].cu, NULL, NULL, 0);
                job.next = next + (size_t)(v - (int32_t)v0) * (width + 1);
                job.pixels = r->intermediate + (size_t)v * width * 4;
                job.row_data = place[0].data + (size_t)(v - place[0].cv) * l->row;
                row_order0(&job, &m, preclass);
            }
        }
        return VF_OK;
    }

    place_slice(r, 0, &place[0]);
    for (uint32_t t = 0; t + 1 < l->nk; t++) {
        const slice_place_t *front = &place[t & 1];
        slice_place_t *back = &place[(t + 1) & 1];
        place_slice(r, t + 1, back);
        uint32_t kc = f->k_flip ? l->nk - 2 - t : t;
        int32_t lo = front->v_lo > back->v_lo ? front->v_lo : back->v_lo;
        int32_t hi = front->v_hi < back->v_hi ? front->v_hi : back->v_hi;
        lo = lo > (int32_t)v0 ? lo : (int32_t)v0;
        hi = hi < (int32_t)v1 - 1 ? hi : (int32_t)v1 - 1;
        job.front = front;
        job.back = back;
        job.t = t;
        job.front_shift = image_buffer ? 0 : front->cu;
        job.back_shift = image_buffer ? 0 : back->cu;
        for (int32_t v = lo; v <= hi; v++) {
            const uint16_t *end_f, *p_f = vfi_runs_row(runs, kc, (uint32_t)(v - front->cv), &end_f);
            const uint16_t *end_b, *p_b = vfi_runs_row(runs, kc, (uint32_t)(v - back->cv), &end_b);
            run_merge_t m;
            merge_init(&m, p_f, end_f, front->cu, p_b, end_b, back->cu);
            size_t band_row = (size_t)(v - (int32_t)v0);
            job.next = next + band_row * (width + 1);
            job.pixels = r->intermediate + (size_t)v * width * 4;
            job.front_buf = buf[image_buffer ? 0 : t & 1] + band_row * buf_row;
            job.back_buf = buf[image_buffer ? 0 : (t + 1) & 1] + band_row * buf_row;
            job.row_data = front->data + (size_t)(v - front->cv) * l->row;
            job.back_row_data = back->data + (size_t)(v - back->cv) * l->row;
            row_preint1(&job, &m);
        }
    }
    return VF_OK;
}

static void place_slice(const vf_renderer_t *r, uint32_t t, slice_place_t *p)
{
    const vf_factor_t *f = &r->factor;
    const vfi_layout_t *l = &r->layout[f->k_axis];
    int32_t ou = vf_factor_offset_u(f, t), ov = vf_factor_offset_v(f, t); /* >= 0, Q16.16 */
    p->cu = (ou + 0xFFFF) >> 16;
    p->cv = (ov + 0xFFFF) >> 16;
    p->fx = (uint32_t)(p->cu * 65536 - ou);
    p->fy = (uint32_t)(p->cv * 65536 - ov);
    /* inside when 0 <= i and i + fraction <= n - 1 */
    p->u_lo = p->cu;
    p->u_hi = p->cu + (int32_t)l->ni - 1 - (p->fx != 0);
    p->v_lo = p->cv;
    p->v_hi = p->cv + (int32_t)l->nj - 1 - (p->fy != 0);
    uint32_t ks = f->k_flip ? l->nk - 1 - t : t;
    p->data = r->slices[f->k_axis] + (size_t)ks * l->slice;
}

/* The bilinear sample at p (column i of a slice row), exactly, in Q8.32: lerps as a + (b - a) f, three
 * multiplications. */
static inline uint64_t sample_q32(const uint8_t *p, uint32_t row, const slice_place_t *sl)
{
    int32_t top = (int32_t)(p[0] << 16) + ((int32_t)p[1] - (int32_t)p[0]) * (int32_t)sl->fx; /* Q8.16 */
    int32_t bottom = (int32_t)(p[row] << 16) + ((int32_t)p[row + 1] - (int32_t)p[row]) * (int32_t)sl->fx;
    return (uint64_t)((int64_t)top * 65536 + (int64_t)(bottom - top) * (int64_t)sl->fy);
}

/* Where a sample goes in the table: its nearest entry, or (bilinear) its position in Q.16; for precision
 * studies the sample is first rounded to fewer fraction bits. */
static inline uint32_t table_position(const row_job_t *job, const uint8_t *p, const slice_place_t *sl)
{
    uint64_t s = sample_q32(p, job->row, sl);
    if (job->sample_shift)
        s = ((s + (UINT64_C(1) << (job->sample_shift - 1))) >> job->sample_shift) << job->sample_shift;
    return job->bilinear ? vfi_position_of_sample(job->cls, s) : vfi_entry_of_sample(job->cls, s);
}

/* Composite a segment; for precision studies keep the accumulators on a coarser grid. */
static inline bool composite_segment(const row_job_t *job, uint16_t *px, const uint32_t seg[4])
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

/* The first open pixel at or after u; halves the path it walked, so that runs of opaque pixels cost
 * almost nothing on the next slab. next[width] is always open. */
static inline uint32_t next_open(uint16_t *next, uint32_t u)
{
    while (next[u] != u) {
        uint32_t n = next[u];
        next[u] = next[n];
        u = n;
    }
    return u;
}

/* Order 0: a slice sample's entry (point), or the interpolation of its four voxels' entries (preclass). */
static void segment_order0(const row_job_t *job, const uint8_t *p, bool preclass, uint32_t seg[4])
{
    const vfi_lookup_ctx_t *c = &job->lookup;
    const slice_place_t *sl = job->front;
    if (preclass) {
        uint32_t e[4][4];
        const uint16_t *entry = job->cls->entry_of_scalar;
        vfi_fetch(c, entry[p[0]], e[0]);
        vfi_fetch(c, entry[p[1]], e[1]);
        vfi_fetch(c, entry[p[job->row]], e[2]);
        vfi_fetch(c, entry[p[job->row + 1]], e[3]);
        vfi_lerp(e[0], e[1], sl->fx);
        vfi_lerp(e[2], e[3], sl->fx);
        vfi_lerp(e[0], e[2], sl->fy);
        for (int k = 0; k < 4; k++)
            seg[k] = e[0][k];
    } else if (job->bilinear) {
        uint32_t i, f, next_entry[4];
        vfi_split_position(c->n, table_position(job, p, sl), &i, &f);
        vfi_fetch(c, i, seg);
        vfi_fetch(c, i + 1, next_entry);
        vfi_lerp(seg, next_entry, f);
    } else {
        vfi_fetch(c, table_position(job, p, sl), seg);
    }
    if (c->lut_f)
        vfi_correct(c, seg);
}

/* point with the default table: the loop on its own, everything it reads in locals (as row_preint1_plain) */
static void row_point_plain(const row_job_t *job, run_merge_t *m)
{
    const slice_place_t *sl = job->front;
    const uint32_t row = job->row, cu = (uint32_t)sl->cu;
    const uint16_t *table = job->lookup.q15;
    const vfi_classify_t *cls = job->cls;
    const uint8_t *data = job->row_data;
    uint16_t *next = job->next, *pixels = job->pixels;
    int32_t a, b;
    while (merge_next(m, &a, &b)) {
        a = a > sl->u_lo ? a : sl->u_lo;
        b = b < sl->u_hi + 1 ? b : sl->u_hi + 1;
        for (uint32_t u = a < b ? next_open(next, (uint32_t)a) : (uint32_t)b; u < (uint32_t)b; u = next_open(next, u + 1)) {
            const uint16_t *e = table + (size_t)vfi_entry_of_sample(cls, sample_q32(data + (u - cu), row, sl)) * 4;
            if (e[3] && vfi_blend_q15(pixels + (size_t)u * 4, e))
                next[u] = (uint16_t)(u + 1);
        }
    }
}

static void row_order0(const row_job_t *job, run_merge_t *m, bool preclass)
{
    const slice_place_t *sl = job->front;
    if (job->plain && !preclass) {
        row_point_plain(job, m);
        return;
    }
    int32_t a, b;
    while (merge_next(m, &a, &b)) {
        a = a > sl->u_lo ? a : sl->u_lo;
        b = b < sl->u_hi + 1 ? b : sl->u_hi + 1;
        if (a >= b)
            continue;
        for (uint32_t u = next_open(job->next, (uint32_t)a); u < (uint32_t)b; u = next_open(job->next, u + 1)) {
            uint32_t seg[4];
            segment_order0(job, job->row_data + (u - (uint32_t)sl->cu), preclass, seg);
            if (composite_segment(job, job->pixels + (size_t)u * 4, seg))
                job->next[u] = (uint16_t)(u + 1);
        }
    }
}

/* Order 1: the 2D entry of a slab from its front and back table positions. */
static void segment_preint1(const row_job_t *job, uint32_t pos_f, uint32_t pos_b, uint32_t seg[4])
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

/* The default path (nearest lookup, 16-bit table, no lut) on its own, with everything it reads in locals: this
 * loop is where preint1 frames spend their time. */
static void row_preint1_plain(const row_job_t *job, run_merge_t *m, int32_t lo, int32_t hi)
{
    const slice_place_t *fr = job->front, *bk = job->back;
    const uint64_t front_slice = job->t, back_tag = (uint64_t)(job->t + 1) << 32;
    const uint32_t n = job->lookup.n, row = job->row;
    const uint16_t *table = job->lookup.q15;
    const vfi_classify_t *cls = job->cls;
    const uint8_t *front_row = job->row_data, *back_row = job->back_row_data;
    const uint32_t front_cu = (uint32_t)fr->cu, back_cu = (uint32_t)bk->cu;
    const uint32_t front_shift = (uint32_t)job->front_shift, back_shift = (uint32_t)job->back_shift;
    vfi_sample_t *front_buf = job->front_buf, *back_buf = job->back_buf;
    uint16_t *next = job->next, *pixels = job->pixels;
    int32_t a, b;
    while (merge_next(m, &a, &b)) {
        a = a > lo ? a : lo;
        b = b < hi + 1 ? b : hi + 1;
        for (uint32_t u = a < b ? next_open(next, (uint32_t)a) : (uint32_t)b; u < (uint32_t)b; u = next_open(next, u + 1)) {
            vfi_sample_t front = front_buf[u - front_shift];
            uint32_t row_f = (uint32_t)front; /* front entry times N */
            if ((front >> 32) != front_slice)
                row_f = n * vfi_entry_of_sample(cls, sample_q32(front_row + (u - front_cu), row, fr));
            uint32_t pos_b = vfi_entry_of_sample(cls, sample_q32(back_row + (u - back_cu), row, bk));
            back_buf[u - back_shift] = back_tag | (pos_b * n);
            const uint16_t *e = table + ((size_t)row_f + pos_b) * 4;
            if (e[3] && vfi_blend_q15(pixels + (size_t)u * 4, e))
                next[u] = (uint16_t)(u + 1);
        }
    }
}

static void row_preint1(const row_job_t *job, run_merge_t *m)
{
    const slice_place_t *fr = job->front, *bk = job->back;
    const uint64_t front_slice = job->t, back_tag = (uint64_t)(job->t + 1) << 32;
    const uint32_t n = job->lookup.n;
    int32_t a, b;
    int32_t lo = fr->u_lo > bk->u_lo ? fr->u_lo : bk->u_lo;
    int32_t hi = fr->u_hi < bk->u_hi ? fr->u_hi : bk->u_hi;
    if (job->plain) {
        row_preint1_plain(job, m, lo, hi);
        return;
    }
    while (merge_next(m, &a, &b)) {
        a = a > lo ? a : lo;
        b = b < hi + 1 ? b : hi + 1;
        if (a >= b)
            continue;
        for (uint32_t u = next_open(job->next, (uint32_t)a); u < (uint32_t)b; u = next_open(job->next, u + 1)) {
            /* The front sample was buffered as the last slab's back sample, unless that slab skipped this
             * pixel; the slice tag says which. With an image-sized buffer front and back are the same word.
             * Nearest positions are kept times N: the front entry's row in the 2D table. */
            vfi_sample_t front = job->front_buf[(int32_t)u - job->front_shift];
            uint32_t pos_f = (uint32_t)front, pos_b;
            /* nearest positions are kept times N in the buffer (the front entry's row in the 2D table) */
            const uint32_t scale = job->bilinear ? 1 : n;
            if ((front >> 32) != front_slice)
                pos_f = scale * table_position(job, job->row_data + (u - (uint32_t)fr->cu), fr);
            pos_b = table_position(job, job->back_row_data + (u - (uint32_t)bk->cu), bk);
            job->back_buf[(int32_t)u - job->back_shift] = back_tag | (pos_b * scale);
            uint32_t seg[4];
            segment_preint1(job, job->bilinear ? pos_f : pos_f / n, pos_b, seg);
            if (composite_segment(job, job->pixels + (size_t)u * 4, seg))
                job->next[u] = (uint16_t)(u + 1);
        }
    }
}

static bool stream_next(run_stream_t *s, int32_t *a, int32_t *b)
{
    if (s->p == s->end)
        return false;
    *a = s->pos + s->p[0];
    *b = *a + s->p[1];
    s->pos = *b;
    s->p += 2;
    return true;
}

static void merge_init(run_merge_t *m, const uint16_t *p0, const uint16_t *e0, int32_t pos0, const uint16_t *p1,
                       const uint16_t *e1, int32_t pos1)
{
    m->s[0].p = p0, m->s[0].end = e0, m->s[0].pos = pos0;
    m->s[1].p = p1, m->s[1].end = e1, m->s[1].pos = pos1;
    m->live[0] = stream_next(&m->s[0], &m->a[0], &m->b[0]);
    m->live[1] = stream_next(&m->s[1], &m->a[1], &m->b[1]);
}

/* The next interval of the union, with overlapping and touching intervals joined. */
static bool merge_next(run_merge_t *m, int32_t *a, int32_t *b)
{
    if (!m->live[0] && !m->live[1])
        return false;
    int x = (!m->live[1] || (m->live[0] && m->a[0] <= m->a[1])) ? 0 : 1;
    int32_t lo = m->a[x], hi = m->b[x];
    m->live[x] = stream_next(&m->s[x], &m->a[x], &m->b[x]);
    for (;;) {
        if (m->live[0] && m->a[0] <= hi) {
            hi = m->b[0] > hi ? m->b[0] : hi;
            m->live[0] = stream_next(&m->s[0], &m->a[0], &m->b[0]);
        } else if (m->live[1] && m->a[1] <= hi) {
            hi = m->b[1] > hi ? m->b[1] : hi;
            m->live[1] = stream_next(&m->s[1], &m->a[1], &m->b[1]);
        } else {
            break;
        }
    }
    *a = lo;
    *b = hi;
    return true;
}

static unsigned char *align_up(unsigned char *p)
{
    uintptr_t x = (uintptr_t)p;
    return p + ((SCRATCH_ALIGN - x % SCRATCH_ALIGN) % SCRATCH_ALIGN);
}
