/*
 * composite.c: slabs front to back into the intermediate image, one band of intermediate rows at a time
 * (docs/algorithm.md, sections 4 and 4b): the band's script. For each slice (order 0) or slab (preint1) and each row
 * of the band it merges the run-length encoding's visible runs under the row and hands them to the row functions of
 * composite_order0.c and composite_order1.c, which walk only those runs and only pixels that are not yet opaque
 * (skip links).
 *
 * Scratch per band (the caller's memory, so that bands can run on threads at once):
 *   next     [rows][int_w + 1]      skip links: next[u] == u for an open pixel, else a pixel further right
 *   preint1 only:
 *   buffers  the back samples' table positions, for the next slab: slice-sized, two of [rows][n_i + 2] indexed by
 *            slice column + 1 (front, back), or image-sized, one of [rows][int_w] indexed by pixel, updated in place
 *   visits   [2][rows] the runs each row's last two slabs walked (row_visits_t), each with room for the most runs a
 *            row can have, (int_w + 1) / 2 + 1
 */
#include "arena.h"
#include "composite.h"

#define SCRATCH_ALIGN 16

static void place_slice(const vf_renderer_t *r, uint32_t t, slice_place_t *p);
static unsigned char *align_up(unsigned char *p);

static size_t visits_capacity(uint32_t width)
{
    return (size_t)(width + 1) / 2 + 1;
}

size_t vfi_band_scratch_bytes(const vf_renderer_t *r, uint32_t rows)
{
    size_t bytes = 2 * SCRATCH_ALIGN + sizeof(uint16_t) * rows * ((size_t)r->max_int_w + 1);
    if (r->params.mode != VF_MODE_PREINT1)
        return bytes;
    if (r->params.buffer == VF_BUFFER_IMAGE)
        bytes += SCRATCH_ALIGN + sizeof(uint32_t) * rows * (size_t)r->max_int_w;
    else
        bytes += SCRATCH_ALIGN + 2 * sizeof(uint32_t) * rows * ((size_t)r->max_ni + 2);
    return bytes + 2 * SCRATCH_ALIGN + 2 * rows * (sizeof(row_visits_t) + sizeof(vfi_span_t) * visits_capacity(r->max_int_w));
}

vf_status_t vfi_composite_band(const vf_renderer_t *r, uint32_t v0, uint32_t v1, void *scratch, size_t bytes)
{
    const vf_factor_t *f = &r->factor;
    const vfi_layout_t *l = &r->layout[f->k_axis];
    const uint32_t rows = v1 - v0, width = f->int_w;
    const bool image_buffer = r->params.buffer == VF_BUFFER_IMAGE;
    if (bytes < vfi_band_scratch_bytes(r, rows))
        return VF_ERR_NOMEM;

    /* Carve the scratch; open every pixel; no row walked by any slab yet; clear the band. */
    uint16_t *next = (uint16_t *)align_up(scratch);
    for (uint32_t y = 0; y < rows; y++)
        for (uint32_t u = 0; u <= width; u++)
            next[(size_t)y * (width + 1) + u] = (uint16_t)u;
    uint32_t *buf[2] = {NULL, NULL};
    row_visits_t *visits = NULL;
    const size_t buf_row = image_buffer ? width : l->ni + 2, buf_first = image_buffer ? 0 : 1;
    if (r->params.mode == VF_MODE_PREINT1) {
        buf[0] = (uint32_t *)align_up((unsigned char *)(next + (size_t)rows * (width + 1)));
        buf[1] = image_buffer ? buf[0] : buf[0] + rows * buf_row;
        visits = (row_visits_t *)align_up((unsigned char *)(buf[1] + rows * buf_row));
        vfi_span_t *spans = (vfi_span_t *)align_up((unsigned char *)(visits + 2 * rows));
        for (uint32_t n = 0; n < 2 * rows; n++) {
            visits[n].slab = UINT32_MAX;
            visits[n].count = 0;
            visits[n].span = spans + n * visits_capacity(width);
        }
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
                vfi_merge_init(&m, p, end, place[0].cu, NULL, NULL, 0);
                job.next = next + (size_t)(v - (int32_t)v0) * (width + 1);
                job.pixels = r->intermediate + (size_t)v * width * 4;
                job.row_data = place[0].data + (size_t)(v - place[0].cv) * l->row;
                vfi_row_order0(&job, &m, preclass);
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
            vfi_merge_init(&m, p_f, end_f, front->cu, p_b, end_b, back->cu);
            const size_t band_row = (size_t)(v - (int32_t)v0);
            row_visits_t *last = &visits[((t + 1) & 1) * rows + band_row], *now = &visits[(t & 1) * rows + band_row];
            now->slab = t;
            job.last = t > 0 && last->slab == t - 1 ? last : NULL;
            job.visits = now;
            job.next = next + band_row * (width + 1);
            job.pixels = r->intermediate + (size_t)v * width * 4;
            job.front_buf = buf[image_buffer ? 0 : t & 1] + band_row * buf_row + buf_first;
            job.back_buf = buf[image_buffer ? 0 : (t + 1) & 1] + band_row * buf_row + buf_first;
            job.row_data = front->data + (size_t)(v - front->cv) * l->row;
            job.back_row_data = back->data + (size_t)(v - back->cv) * l->row;
            vfi_row_preint1(&job, &m);
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

static unsigned char *align_up(unsigned char *p)
{
    uintptr_t x = (uintptr_t)p;
    return p + ((SCRATCH_ALIGN - x % SCRATCH_ALIGN) % SCRATCH_ALIGN);
}
