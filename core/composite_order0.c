/*
 * composite_order0.c: the rows of one slice in the order-0 modes (docs/algorithm.md, sections 4 and 4b): each open
 * pixel of the visible runs takes its sample's point-table entry (point) or the interpolation of its four voxels'
 * entries (preclass).
 */
#include "composite.h"


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

/* Any mode, lookup, table format, correction, precision study or number of rays. With one ray per voxel a pixel's
 * column is u - cu at the slice's one fraction; with more each pixel has its own. */
static VF_ALWAYS_INLINE void row_general(const row_job_t *job, run_merge_t *m, bool preclass, bool one_ray)
{
    const slice_place_t *sl = job->front;
    int32_t a, b;
    while (vfi_merge_next(m, &a, &b)) {
        a = a > job->clip_lo ? a : job->clip_lo;
        b = b < job->clip_hi + 1 ? b : job->clip_hi + 1;
        if (a >= b)
            continue;
        for (uint32_t u = vfi_next_open(job->next, (uint32_t)a); u < (uint32_t)b; u = vfi_next_open(job->next, u + 1)) {
            uint32_t fx = sl->fx, seg[4];
            const uint32_t i = one_ray ? u - (uint32_t)sl->cu : vfi_column(sl, job->step, u, &fx);
            vfi_segment_order0(job, job->row_data + i, fx, job->front_fy, preclass, seg);
            if (vfi_composite_segment(job, job->pixels + (size_t)u * 4, seg))
                job->next[u] = (uint16_t)(u + 1);
        }
    }
}

void vfi_row_order0(const row_job_t *job, run_merge_t *m, bool preclass)
{
    const bool one_ray = VF_MAX_RAYS == 1 || job->step == 65536; /* constant in one-ray builds */
    if (job->plain && !preclass)
        row_point_plain(job, m);
    else if (one_ray)
        preclass ? row_general(job, m, true, true) : row_general(job, m, false, true);
    else
        preclass ? row_general(job, m, true, false) : row_general(job, m, false, false);
}
