/*
 * composite.c: slabs front to back into the intermediate image, one band of intermediate rows at a time
 * (docs/algorithm.md, section 4).
 *
 * For each slab (or slice, in point mode), each row of the band is walked only where the run-length encoding
 * says a cell is visible, and only over pixels that are not yet opaque (skip links). Samples are bilinear in
 * the slice and exact: the slice offsets lie on the 2^-16 grid, so a sample is a multiple of 2^-32 and fits
 * Q8.32, and its table entry is the one the double reference picks. The back sample's entry is kept in a buffer
 * slice and reused as the front sample's entry of the next slab.
 *
 * Scratch per band (caller's memory, so that bands can run on threads at once):
 *   next      [rows][int_w + 1]    skip links: next[u] == u for an open pixel, else a pixel further right
 *   buffers   2 x [rows][n_i + 1]  buffer slices of the current front and back slice (preint1 only)
 */
#include "arena.h"
#include "render.h"

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

/* What one row of one slab needs. */
typedef struct row_job {
    const slice_place_t *front, *back; /* back is NULL in point mode */
    uint32_t t;                 /* standard slice (point) or slab (preint1) */
    const uint16_t *table;
    const vfi_classify_t *cls;
    uint32_t n;                 /* table entries */
    uint32_t row;               /* bytes per slice row */
    const uint8_t *row_data;    /* the front (point: the) slice's row under this intermediate row */
    const uint8_t *back_row_data;
    vfi_sample_t *front_buf, *back_buf;
    uint16_t *next;
    uint16_t *pixels;
} row_job_t;

static void place_slice(const vf_renderer_t *r, uint32_t t, slice_place_t *p);
static void merge_init(run_merge_t *m, const uint16_t *p0, const uint16_t *e0, int32_t pos0, const uint16_t *p1,
                       const uint16_t *e1, int32_t pos1);
static bool merge_next(run_merge_t *m, int32_t *a, int32_t *b);
static void row_point(const row_job_t *job, run_merge_t *m);
static void row_preint1(const row_job_t *job, run_merge_t *m);
static unsigned char *align_up(unsigned char *p);

size_t vfi_band_scratch_bytes(const vf_renderer_t *r, uint32_t rows)
{
    size_t bytes = 2 * SCRATCH_ALIGN + sizeof(uint16_t) * rows * ((size_t)r->max_int_w + 1);
    if (r->params.mode == VF_MODE_PREINT1)
        bytes += 2 * sizeof(vfi_sample_t) * rows * ((size_t)r->max_ni + 1) + SCRATCH_ALIGN;
    return bytes;
}

vf_status_t vfi_composite_band(const vf_renderer_t *r, uint32_t v0, uint32_t v1, void *scratch, size_t bytes)
{
    const vf_factor_t *f = &r->factor;
    const vfi_layout_t *l = &r->layout[f->k_axis];
    const uint32_t rows = v1 - v0, width = f->int_w;
    if (bytes < vfi_band_scratch_bytes(r, rows))
        return VF_ERR_NOMEM;

    /* Carve the scratch; open every pixel; clear the band of the intermediate image. */
    uint16_t *next = (uint16_t *)align_up(scratch);
    for (uint32_t y = 0; y < rows; y++)
        for (uint32_t u = 0; u <= width; u++)
            next[(size_t)y * (width + 1) + u] = (uint16_t)u;
    vfi_sample_t *buf[2] = {NULL, NULL};
    if (r->params.mode == VF_MODE_PREINT1) {
        size_t per = (size_t)rows * (l->ni + 1);
        buf[0] = (vfi_sample_t *)align_up((unsigned char *)(next + (size_t)rows * (width + 1)));
        buf[1] = buf[0] + per;
        for (size_t e = 0; e < 2 * per; e++)
            buf[0][e].slice = VFI_NO_SLICE;
    }
    uint16_t *band = r->intermediate + (size_t)v0 * width * 4;
    for (size_t e = 0; e < (size_t)rows * width * 4; e++)
        band[e] = 0;

    row_job_t job;
    vfi_zero(&job, sizeof job);
    job.cls = &r->cls;
    job.n = r->cls.n;
    job.row = l->row;
    const vfi_runs_t *runs = &r->runs[f->k_axis];
    slice_place_t place[2];

    if (r->params.mode == VF_MODE_POINT) {
        job.table = r->point_table;
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
                row_point(&job, &m);
            }
        }
        return VF_OK;
    }

    job.table = r->preint_table;
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
        for (int32_t v = lo; v <= hi; v++) {
            const uint16_t *end_f, *p_f = vfi_runs_row(runs, kc, (uint32_t)(v - front->cv), &end_f);
            const uint16_t *end_b, *p_b = vfi_runs_row(runs, kc, (uint32_t)(v - back->cv), &end_b);
            run_merge_t m;
            merge_init(&m, p_f, end_f, front->cu, p_b, end_b, back->cu);
            size_t band_row = (size_t)(v - (int32_t)v0);
            job.next = next + band_row * (width + 1);
            job.pixels = r->intermediate + (size_t)v * width * 4;
            job.front_buf = buf[t & 1] + band_row * (l->ni + 1);
            job.back_buf = buf[(t + 1) & 1] + band_row * (l->ni + 1);
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

/* Table entry of the bilinear sample at p (column i of a slice row): the sample exactly, in Q8.32. */
static inline uint32_t sample_entry(const vfi_classify_t *cls, const uint8_t *p, uint32_t row,
                                    const slice_place_t *sl)
{
    uint32_t top = p[0] * (65536u - sl->fx) + p[1] * sl->fx;             /* Q8.16 */
    uint32_t bottom = p[row] * (65536u - sl->fx) + p[row + 1] * sl->fx;
    uint64_t s = (uint64_t)top * (65536u - sl->fy) + (uint64_t)bottom * sl->fy; /* Q8.32 */
    return vfi_entry_of_sample(cls, s);
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

/* Front to back: C += (1 - A) C_seg, A += (1 - A) a_seg. True when the pixel became opaque. */
static inline bool blend(uint16_t *px, const uint16_t *e)
{
    uint32_t t = VFI_ONE_Q15 - px[3];
    px[0] = (uint16_t)(px[0] + ((t * e[0] + 0x4000u) >> 15));
    px[1] = (uint16_t)(px[1] + ((t * e[1] + 0x4000u) >> 15));
    px[2] = (uint16_t)(px[2] + ((t * e[2] + 0x4000u) >> 15));
    px[3] = (uint16_t)(px[3] + ((t * e[3] + 0x4000u) >> 15));
    return px[3] >= VFI_OPAQUE_Q15;
}

static void row_point(const row_job_t *job, run_merge_t *m)
{
    const slice_place_t *sl = job->front;
    int32_t a, b;
    while (merge_next(m, &a, &b)) {
        a = a > sl->u_lo ? a : sl->u_lo;
        b = b < sl->u_hi + 1 ? b : sl->u_hi + 1;
        if (a >= b)
            continue;
        for (uint32_t u = next_open(job->next, (uint32_t)a); u < (uint32_t)b; u = next_open(job->next, u + 1)) {
            const uint8_t *p = job->row_data + (u - (uint32_t)sl->cu);
            const uint16_t *e = job->table + sample_entry(job->cls, p, job->row, sl) * 4;
            if (e[3] && blend(job->pixels + (size_t)u * 4, e))
                job->next[u] = (uint16_t)(u + 1);
        }
    }
}

static void row_preint1(const row_job_t *job, run_merge_t *m)
{
    const slice_place_t *fr = job->front, *bk = job->back;
    const uint16_t front_slice = (uint16_t)job->t, back_slice = (uint16_t)(job->t + 1);
    int32_t a, b;
    int32_t lo = fr->u_lo > bk->u_lo ? fr->u_lo : bk->u_lo;
    int32_t hi = fr->u_hi < bk->u_hi ? fr->u_hi : bk->u_hi;
    while (merge_next(m, &a, &b)) {
        a = a > lo ? a : lo;
        b = b < hi + 1 ? b : hi + 1;
        if (a >= b)
            continue;
        for (uint32_t u = next_open(job->next, (uint32_t)a); u < (uint32_t)b; u = next_open(job->next, u + 1)) {
            uint32_t i_f = u - (uint32_t)fr->cu, i_b = u - (uint32_t)bk->cu;
            const vfi_sample_t *fs = &job->front_buf[i_f];
            uint32_t ef = fs->slice == front_slice ? fs->entry : sample_entry(job->cls, job->row_data + i_f, job->row, fr);
            uint32_t eb = sample_entry(job->cls, job->back_row_data + i_b, job->row, bk);
            job->back_buf[i_b].entry = (uint16_t)eb;
            job->back_buf[i_b].slice = back_slice;
            uint32_t entry = ef * job->n + eb;
            const uint16_t *e = job->table + (size_t)entry * 4;
            if (e[3] && blend(job->pixels + (size_t)u * 4, e))
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
    m->s[0] = (run_stream_t){p0, e0, pos0};
    m->s[1] = (run_stream_t){p1, e1, pos1};
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
