/*
 * composite_order0.c: the rows of one slice in the order-0 modes (docs/algorithm.md, sections 4 and 4b): each open
 * pixel of the visible runs takes its sample's point-table entry (point) or the interpolation of its four voxels'
 * entries (preclass).
 */
#include "composite.h"

/* A slice sample's entry (point), or the interpolation of its four voxels' entries (preclass): the sample at p with
 * fractions fx, fy. */
void vfi_segment_order0(const row_job_t *job, const uint8_t *p, uint32_t fx, uint32_t fy, bool preclass,
                        uint32_t seg[4])
{
    const vfi_lookup_ctx_t *c = &job->lookup;
    if (preclass) {
        uint32_t e[4][4];
        const uint16_t *entry = job->cls->entry_of_scalar;
        vfi_fetch(c, entry[p[0]], e[0]);
        vfi_fetch(c, entry[p[1]], e[1]);
        vfi_fetch(c, entry[p[job->row]], e[2]);
        vfi_fetch(c, entry[p[job->row + 1]], e[3]);
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
}

/* point with the default table and one ray per voxel column: the loop on its own, everything it reads in locals */
static void row_point_plain(const row_job_t *job, run_merge_t *m)
{
    const slice_place_t *sl = job->front;
    const uint32_t row = job->row, cu = (uint32_t)sl->cu, fx = sl->fx, fy = job->front_fy;
    const uint16_t *table = job->lookup.q15;
    const vfi_classify_t *cls = job->cls;
    const uint8_t *data = job->row_data;
    uint16_t *next = job->next, *pixels = job->pixels;
    int32_t a, b;
    while (vfi_merge_next(m, &a, &b)) {
        a = a > job->clip_lo ? a : job->clip_lo;
        b = b < job->clip_hi + 1 ? b : job->clip_hi + 1;
        for (uint32_t u = a < b ? vfi_next_open(next, (uint32_t)a) : (uint32_t)b; u < (uint32_t)b;
             u = vfi_next_open(next, u + 1)) {
            uint64_t s = vfi_sample_at(data + (u - cu), row, fx, fy);
            const uint16_t *e = table + (size_t)vfi_entry_of_sample(cls, s) * 4;
            if (e[3] && vfi_blend_q15(pixels + (size_t)u * 4, e))
                next[u] = (uint16_t)(u + 1);
        }
    }
}

void vfi_row_order0(const row_job_t *job, run_merge_t *m, bool preclass)
{
    const slice_place_t *sl = job->front;
    if (job->plain && !preclass) {
        row_point_plain(job, m);
        return;
    }
    int32_t a, b;
    while (vfi_merge_next(m, &a, &b)) {
        a = a > job->clip_lo ? a : job->clip_lo;
        b = b < job->clip_hi + 1 ? b : job->clip_hi + 1;
        if (a >= b)
            continue;
        for (uint32_t u = vfi_next_open(job->next, (uint32_t)a); u < (uint32_t)b; u = vfi_next_open(job->next, u + 1)) {
            uint32_t fx, seg[4];
            const uint32_t i = vfi_column(sl, job->step, u, &fx);
            vfi_segment_order0(job, job->row_data + i, fx, job->front_fy, preclass, seg);
            if (vfi_composite_segment(job, job->pixels + (size_t)u * 4, seg))
                job->next[u] = (uint16_t)(u + 1);
        }
    }
}
