/* SPDX-License-Identifier: MIT */
/*
 * composite.c: slabs front to back into the intermediate image, one band of intermediate rows at a time
 * (docs/algorithm.md, sections 4 and 4b): the band's script. For each slice (order 0) and each row of the band it
 * merges the run-length encoding's visible runs under the row and hands them to composite_order0.c; each slab
 * (preint1) it hands to composite_order1.c, rows and all. Both walk only those runs and only pixels that are not
 * yet opaque (skip links). Partial slabs' pixels at the side faces go to composite_partial.c.
 *
 * Scratch per band (the caller's memory, so that bands can run on threads at once):
 *   next     [rows][int_w + 1]      skip links: next[u] == u for an open pixel, else a pixel further right
 *   preint1 only:
 *   buffers  the back samples' table positions, for the next slab: slice-sized, two of [rows][R (n_i + 1) + 1]
 *            indexed by R + the pixel's place in the slice, u - cu (front, back), or image-sized, one of
 *            [rows][int_w] indexed by pixel, updated in place
 *   shades   lit frames (the plain loop): the back samples' shades for the next slab, as the buffers, right after
 *            them (the same index, a fixed distance on)
 *   visits   [2][rows] the runs each row's last two slabs walked (row_visits_t), each with room for the most runs a
 *            row can have, (int_w + 1) / 2 + 1
 */
#include "arena.h"
#include "composite.h"

#define SCRATCH_ALIGN 16

#define MIN(a, b) ((a) < (b) ? (a) : (b))
#define MAX(a, b) ((a) > (b) ? (a) : (b))

static void faces_around(const row_job_t *job, int32_t v, int32_t lo, int32_t hi, int32_t inner_lo, int32_t inner_hi,
                         bool preclass);
static unsigned char *align_up(unsigned char *p);
static void row_extents(const vf_renderer_t *r, uint32_t v0, uint32_t v1);

static size_t visits_capacity(uint32_t width)
{
    return (size_t)(width + 1) / 2 + 1;
}

size_t vfi_band_scratch_bytes(const vf_renderer_t *r, uint32_t rows)
{
    size_t bytes = 2 * SCRATCH_ALIGN + sizeof(uint16_t) * rows * ((size_t)r->max_int_w + 1);
    if (VF_SPECIAL_LOOPS && r->params.mode == VF_MODE_PRECLASS) { /* the plain loops' classes, a slice's terms,
                                                                    * lit: two rows of lit voxels and their stamps */
        const size_t lit = VF_LIGHTING && r->params.lighting ? 2 * ((size_t)r->max_ni + 1) : 0;
        return bytes + SCRATCH_ALIGN + sizeof(uint64_t) * (VFI_PRECLASS_CLASSES + VFI_PRECLASS_TERMS + 2 * lit) +
               sizeof(uint32_t) * lit;
    }
    if (r->params.mode != VF_MODE_PREINT1 && r->params.mode != VF_MODE_PREINT2) /* preint2: preint1's buffers */
        return bytes;
    const size_t copies = VF_LIGHTING && r->params.lighting ? 2 : 1; /* the buffers, and for lighting their shades */
    if (r->params.buffer == VF_BUFFER_IMAGE)
        bytes += SCRATCH_ALIGN + copies * sizeof(uint32_t) * rows * (size_t)r->max_int_w;
    else
        bytes += SCRATCH_ALIGN + copies * 2 * sizeof(uint32_t) * rows * ((size_t)r->params.rays * (r->max_ni + 1) + 1);
    return bytes + 2 * SCRATCH_ALIGN + 2 * rows * (sizeof(row_visits_t) + sizeof(vfi_span_t) * visits_capacity(r->max_int_w));
}

vf_status_t vfi_composite_band(const vf_renderer_t *r, uint32_t v0, uint32_t v1, void *scratch, size_t bytes,
                               const vfi_demand_t *own)
{
    const vf_factor_t *f = &r->factor;
    const vfi_layout_t *l = &r->layout[f->k_axis];
    const uint32_t rows = v1 - v0, width = f->int_w;
    const bool image_buffer = r->params.buffer == VF_BUFFER_IMAGE;
    if (bytes < vfi_band_scratch_bytes(r, rows))
        return VF_ERR_NOMEM;

    row_job_t job;
    vfi_zero(&job, sizeof job);
    /* Carve the scratch; open every pixel; no row walked by any slab yet; clear the band. */
    uint16_t *next = (uint16_t *)align_up(scratch);
    for (uint32_t y = 0; y < rows; y++)
        for (uint32_t u = 0; u <= width; u++)
            next[(size_t)y * (width + 1) + u] = (uint16_t)u;
    uint32_t *buf[2] = {NULL, NULL};
    row_visits_t *visits = NULL;
    /* a slice buffer's row has R elements before the slice's first pixel: a front slice starts at most R pixels
     * to the right of the back one (|shear| <= 1), and the plain loops address both from the back's */
    const uint32_t rays = r->params.rays;
    const size_t buf_row = image_buffer ? width : (size_t)rays * (l->ni + 1) + 1, buf_first = image_buffer ? 0 : rays;
    if (r->params.mode == VF_MODE_PREINT1 || r->params.mode == VF_MODE_PREINT2) {
        buf[0] = (uint32_t *)align_up((unsigned char *)(next + (size_t)rows * (width + 1)));
        buf[1] = image_buffer ? buf[0] : buf[0] + rows * buf_row;
        /* lighting's shades a fixed distance after the buffers (composite_order1.c's plain loop) */
        job.shade_offset = VF_LIGHTING && r->params.lighting ? (size_t)(buf[1] + rows * buf_row - buf[0]) : 0;
        visits = (row_visits_t *)align_up((unsigned char *)(buf[1] + rows * buf_row + job.shade_offset));
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

    job.cls = &r->cls;
    job.row = l->row;
    job.lookup = r->lookup;
#if VF_TABLE_ON_DEMAND
    if (own) { /* a thread's copy of the table: the shared table's format, in other memory */
        job.lookup.q15 = own->out.q15;
        job.lookup.lit_q15 = own->out.lit_q15;
    }
#endif
    job.bilinear = r->params.lookup != VF_LOOKUP_NEAREST; /* preint2's trilinear: its last slab's 2D lookup */
    job.sample_shift = r->params.sample_bits ? 32 - r->params.sample_bits : 0;
    job.inter_shift = 16 - r->params.intermediate_bits;
    job.step = VF_MAX_RAYS == 1 ? 65536u : 65536u / rays;
    job.step_shift = 16;
    while ((1u << job.step_shift) > job.step)
        job.step_shift--;
#if VF_LIGHTING
    job.shading = vfi_lit(r) ? &r->shading : NULL;
#endif
    const bool plain = !r->general_loops && vfi_plain_path(job.bilinear, job.lookup.q15, job.lookup.lut_f, job.sample_shift, job.inter_shift,
                                      rays);
    job.plain = plain && !(VF_LIGHTING && job.shading);
    job.plain_lit = plain && VF_LIGHTING && job.shading && job.shading->shade && !job.shading->ramp;
    job.grey = r->tf_grey;
    const vfi_runs_t *runs = &r->runs[f->k_axis];
    const bool partial = VF_PARTIAL_SLABS && r->params.partial_slabs; /* constant 0 in builds without them */
    job.ni = l->ni;
    job.nj = l->nj;
    job.slab_q16 = f->slab_q16;
    job.depth_from_tau = job.lookup.q15 && r->params.table_bits == 16 && r->params.correction != VF_CORRECTION_LUT;
#if VF_TABLE_ON_DEMAND
    job.demand = r->table_unbuilt ? &r->demand : NULL; /* only for the plain loop without partial slabs */
    if (own) /* the thread's copy (its lookup set above) */
        job.demand = own;
#else
    (void)own;
#endif
    slice_place_t place[3];

#if VF_ORDER2
    if (r->params.mode == VF_MODE_PREINT2) { /* slabs of two slices: composite_order2.c */
        vfi_band_t b;
        b.v0 = v0, b.v1 = v1;
        b.next = next;
        b.buf[0] = buf[0], b.buf[1] = buf[1];
        b.buf_row = buf_row, b.buf_first = buf_first;
        b.visits = visits;
        vfi_band_order2(r, &job, &b);
        row_extents(r, v0, v1);
        return VF_OK;
    }
#endif
    if (r->params.mode != VF_MODE_PREINT1) {
        const bool preclass = r->params.mode == VF_MODE_PRECLASS;
        uint64_t *classes = NULL, *terms = NULL; /* preclass's plain loops (composite_preclass.c) */
        if (VF_SPECIAL_LOOPS && preclass && (job.plain || job.plain_lit)) {
            classes = (uint64_t *)align_up((unsigned char *)(next + (size_t)rows * (width + 1)));
            terms = classes + VFI_PRECLASS_CLASSES;
            vfi_preclass_classes(&job, classes);
            job.preclass_classes = classes;
            if (job.plain_lit) {
                job.preclass_cols = r->max_ni + 1;
                job.preclass_lit = terms + VFI_PRECLASS_TERMS;
                job.preclass_stamp = (uint32_t *)(job.preclass_lit + 4 * (size_t)job.preclass_cols);
                for (uint32_t n = 0; n < 2 * job.preclass_cols; n++)
                    job.preclass_stamp[n] = VFI_PRECLASS_NO_ROW;
            }
        }
        for (uint32_t t = 0; t < l->nk; t++) {
            slice_place_t *sl = &place[0];
            vfi_place_slice(r, t, sl);
            job.before = job.after = NULL;
            if (partial && t > 0)
                vfi_place_slice(r, t - 1, &place[1]), job.before = &place[1];
            if (partial && t + 1 < l->nk)
                vfi_place_slice(r, t + 1, &place[2]), job.after = &place[2];
            /* with partial slabs, the pixels whose neighbours' samples are inside take a whole slab as always;
             * the others, and all of the first and last slice, a length of their own (vfi_faces_order0) */
            slice_place_t whole = *sl;
            if (partial && (!job.before || !job.after)) {
                whole.u_hi = whole.u_lo - 1, whole.v_hi = whole.v_lo - 1;
            } else if (partial) {
                for (int n = 1; n <= 2; n++) {
                    whole.u_lo = MAX(whole.u_lo, place[n].u_lo), whole.u_hi = MIN(whole.u_hi, place[n].u_hi);
                    whole.v_lo = MAX(whole.v_lo, place[n].v_lo), whole.v_hi = MIN(whole.v_hi, place[n].v_hi);
                }
            }
            uint32_t ks = f->k_flip ? l->nk - 1 - t : t;
            uint32_t kc = ks < l->nk - 1 ? ks : l->nk - 2; /* the cell slab that has slice ks as a face */
            const int32_t lo = MAX(sl->v_lo, (int32_t)v0), hi = MIN(sl->v_hi, (int32_t)v1 - 1);
            job.front = sl;
            job.t = t;
            bool terms_due = VF_SPECIAL_LOOPS && classes && job.plain; /* built for the slice's first visible row */
            for (int32_t v = lo; v <= hi; v++) {
                uint32_t j;
                job.row_data = vfi_slice_row(sl, job.row, job.step, v, &j, &job.front_fy);
                job.next = next + (size_t)(v - (int32_t)v0) * (width + 1);
                job.pixels = r->intermediate + (size_t)v * width * 4;
                const bool whole_row = v >= whole.v_lo && v <= whole.v_hi && whole.u_lo <= whole.u_hi;
                if (whole_row) {
                    const uint16_t *end, *p = vfi_runs_row(runs, kc, j, &end);
                    if (p != end) { /* a row with no visible cell costs nothing more */
                        run_merge_t m;
                        vfi_merge_init(&m, job.step_shift, p, end, sl, NULL, NULL, NULL);
                        job.clip_lo = whole.u_lo;
                        job.clip_hi = whole.u_hi;
                        if (terms_due)
                            vfi_preclass_terms(classes, sl->fx, job.grey, terms), job.preclass_terms = terms;
                        terms_due = false;
                        vfi_row_order0(&job, &m, preclass);
                    }
                }
                if (partial)
                    faces_around(&job, v, sl->u_lo, sl->u_hi, whole_row ? whole.u_lo : sl->u_hi + 1, whole.u_hi,
                                 preclass);
            }
        }
        row_extents(r, v0, v1);
        return VF_OK;
    }

    vfi_place_slice(r, 0, &place[0]);
    for (uint32_t t = 0; t + 1 < l->nk; t++) {
        const slice_place_t *front = &place[t & 1];
        slice_place_t *back = &place[(t + 1) & 1];
        vfi_place_slice(r, t + 1, back);
        uint32_t kc = f->k_flip ? l->nk - 2 - t : t;
        /* rows and pixels where both samples are inside */
        const int32_t lo = MAX(MAX(front->v_lo, back->v_lo), (int32_t)v0);
        const int32_t hi = MIN(MIN(front->v_hi, back->v_hi), (int32_t)v1 - 1);
        const int32_t u_lo = MAX(front->u_lo, back->u_lo), u_hi = MIN(front->u_hi, back->u_hi);
        job.front = front;
        job.back = back;
        job.t = t;
        job.front_shift = image_buffer ? 0 : front->cu;
        job.back_shift = image_buffer ? 0 : back->cu;
        if (partial) { /* the pixels around those both slices cover, and the rows only one covers: other pixels than
                        * the whole slabs below, so they can go first */
            const int32_t first = MIN(front->u_lo, back->u_lo), last = MAX(front->u_hi, back->u_hi);
            const int32_t v_hi = MIN(MAX(front->v_hi, back->v_hi), (int32_t)v1 - 1);
            for (int32_t v = MAX(MIN(front->v_lo, back->v_lo), (int32_t)v0); v <= v_hi; v++) {
                const bool whole_row = v >= lo && v <= hi && u_lo <= u_hi;
                job.next = next + (size_t)(v - (int32_t)v0) * (width + 1);
                job.pixels = r->intermediate + (size_t)v * width * 4;
                faces_around(&job, v, first, last, whole_row ? u_lo : last + 1, u_hi, false);
            }
        }
        if (lo > hi || u_lo > u_hi)
            continue;
        const size_t band_row = (size_t)(lo - (int32_t)v0);
        vfi_slab_rows_t s;
        s.v_lo = lo, s.v_hi = hi;
        s.runs = runs;
        s.kc = kc;
        s.next = next + band_row * (width + 1);
        s.next_stride = width + 1;
        s.pixels = r->intermediate + (size_t)lo * width * 4;
        s.pixel_stride = (size_t)width * 4;
        s.front_buf = buf[image_buffer ? 0 : t & 1] + band_row * buf_row + buf_first;
        s.back_buf = buf[image_buffer ? 0 : (t + 1) & 1] + band_row * buf_row + buf_first;
        s.buf_stride = buf_row;
        s.last = t > 0 ? &visits[((t + 1) & 1) * rows + band_row] : NULL;
        s.now = &visits[(t & 1) * rows + band_row];
        vfi_slab_preint1(&job, &s);
    }
    row_extents(r, v0, v1);
    return VF_OK;
}

void vfi_place_slice(const vf_renderer_t *r, uint32_t t, slice_place_t *p)
{
    const vf_factor_t *f = &r->factor;
    const vfi_layout_t *l = &r->layout[f->k_axis];
    const int32_t step = (int32_t)(65536u / r->params.rays);
    p->ou = vf_factor_offset_u(f, t); /* >= 0, Q16.16 */
    p->ov = vf_factor_offset_v(f, t);
    /* inside when 0 <= u / R - ou <= n - 1: from ceil(ou / step) to floor((ou + (n - 1) 2^16) / step) */
    p->cu = (p->ou + step - 1) / step;
    p->cv = (p->ov + step - 1) / step;
    p->fx = (uint32_t)(p->cu * step - p->ou);
    p->fy = (uint32_t)(p->cv * step - p->ov);
    p->u_lo = p->cu;
    p->u_hi = (p->ou + (int32_t)(l->ni - 1) * 65536) / step;
    p->v_lo = p->cv;
    p->v_hi = (p->ov + (int32_t)(l->nj - 1) * 65536) / step;
    /* with R > 1 a slice can reach up to R - 1 pixels past the image, which ends at the last whole voxel
     * (vf_factor_rays): those points have no pixel (docs/algorithm.md, section 3) */
    p->u_hi = MIN(p->u_hi, (int32_t)f->int_w - 1);
    p->v_hi = MIN(p->v_hi, (int32_t)f->int_h - 1);
    uint32_t ks = f->k_flip ? l->nk - 1 - t : t;
    p->data = r->slices[f->k_axis] + (size_t)ks * l->slice;
}

/* Partial slabs in row v: pixels [lo, hi] but [inner_lo, inner_hi] (empty when inner_lo > inner_hi), which the
 * whole-slab rows take. */
static void faces_around(const row_job_t *job, int32_t v, int32_t lo, int32_t hi, int32_t inner_lo, int32_t inner_hi,
                         bool preclass)
{
    const bool preint = job->back != NULL;
    if (inner_lo > inner_hi)
        inner_lo = hi + 1, inner_hi = hi;
    const int32_t spans[2][2] = {{lo, MIN(inner_lo - 1, hi)}, {MAX(inner_hi + 1, lo), hi}};
    for (int n = 0; n < 2; n++) {
        if (spans[n][0] > spans[n][1])
            continue;
        if (preint)
            vfi_faces_preint1(job, v, (uint32_t)spans[n][0], (uint32_t)spans[n][1] + 1);
        else
            vfi_faces_order0(job, v, (uint32_t)spans[n][0], (uint32_t)spans[n][1] + 1, preclass);
    }
}

/* Rows [v0, v1)'s extents (renderer.h): from either end to the first pixel with a value other than 0, so that the
 * scan costs the empty margins only. A speed-up alone, for VF_SPECIAL_LOOPS builds. */
static void row_extents(const vf_renderer_t *r, uint32_t v0, uint32_t v1)
{
    if (!VF_SPECIAL_LOOPS)
        return; /* the warp takes the whole image */
    const uint32_t width = r->factor.int_w;
    for (uint32_t v = v0; v < v1; v++) {
        const uint16_t *row = r->intermediate + (size_t)v * width * 4;
        uint32_t lo = 0, hi = width;
        while (lo < width && !(row[lo * 4] | row[lo * 4 + 1] | row[lo * 4 + 2] | row[lo * 4 + 3]))
            lo++;
        while (hi > lo && !(row[hi * 4 - 4] | row[hi * 4 - 3] | row[hi * 4 - 2] | row[hi * 4 - 1]))
            hi--;
        r->row_extent[2 * v] = (uint16_t)(lo < hi ? lo : 0);
        r->row_extent[2 * v + 1] = (uint16_t)hi;
    }
}

static unsigned char *align_up(unsigned char *p)
{
    uintptr_t x = (uintptr_t)p;
    return p + ((SCRATCH_ALIGN - x % SCRATCH_ALIGN) % SCRATCH_ALIGN);
}
