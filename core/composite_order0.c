/* SPDX-License-Identifier: MIT */
/*
 * composite_order0.c: the rows of one slice in the order-0 modes (docs/algorithm.md, sections 4 and 4b): each open
 * pixel of the visible runs takes its sample's point-table entry (point) or the interpolation of its four voxels'
 * entries (preclass).
 */
#include "composite.h"


/* The point-table entry of the sample at p (its two slice rows p and p + row). n256: a 256-entry table. */
static VF_ALWAYS_INLINE const uint16_t *point_entry(const uint16_t *table, const uint8_t *p, uint32_t row, uint32_t fx,
                                                    uint32_t fy, uint32_t n, bool n256)
{
    return table + (size_t)vfi_entry_rows(p, p + row, fx, fy, n, n256) * 4;
}

/* point with a 16-bit table and one ray per voxel column: the loop on its own, everything it reads in locals (the
 * table's size too: the stores to the pixels might change cls->n as far as the compiler knows). The samples by
 * columns (vfi_row_sampler_t), a run's next pixel reusing the last one's right column.
 * With VF_LOOK_AHEAD each pixel's entry is looked up one open pixel ahead of its blend, as preint1's loop does
 * (composite_order1.c), so that the branches on the entry do not wait for its load. The span's end is tested once
 * a pixel, before the look-up ahead (the last pixel's blend has a copy of its own). What each of these saves is in
 * docs/performance.md. grey: the table is grey (vfi_blend_entry). */
static VF_ALWAYS_INLINE void row_point_plain(const row_job_t *job, run_merge_t *m, bool n256, bool grey)
{
    const slice_place_t *sl = job->front;
    const uint32_t n = job->lookup.n;
    const uint16_t *table = job->lookup.q15;
    vfi_row_sampler_t smp; /* by pixel: the slice rows from column -cu */
    vfi_sampler_init(&smp, job->row_data - sl->cu, job->row, sl->fx, job->front_fy, n256);
    uint16_t *next = job->next, *pixels = job->pixels;
    int32_t a, b;
    while (vfi_merge_next(m, &a, &b)) {
        a = a > job->clip_lo ? a : job->clip_lo;
        b = b < job->clip_hi + 1 ? b : job->clip_hi + 1;
        uint32_t u = a < b ? vfi_next_open(next, (uint32_t)a) : (uint32_t)b;
        if (!VF_LOOK_AHEAD) {
            for (; u < (uint32_t)b; u = vfi_next_open(next, u + 1))
                vfi_blend_entry(pixels + (size_t)u * 4, next, u,
                                table + (size_t)vfi_sampler_entry(&smp, u, n, n256) * 4, grey);
            continue;
        }
        if (u >= (uint32_t)b)
            continue;
        const uint16_t *e = table + (size_t)vfi_sampler_entry(&smp, u, n, n256) * 4;
        for (;;) {
            const uint32_t u_next = vfi_next_open(next, u + 1); /* a blend closes only the pixel it blends */
            if (u_next >= (uint32_t)b) {
                vfi_blend_entry(pixels + (size_t)u * 4, next, u, e, grey);
                break;
            }
            const uint16_t *e_next = table + (size_t)vfi_sampler_entry(&smp, u_next, n, n256) * 4;
            vfi_blend_entry(pixels + (size_t)u * 4, next, u, e, grey);
            u = u_next, e = e_next;
        }
    }
}

static VF_NOINLINE void row_point_256(const row_job_t *job, run_merge_t *m)
{
    row_point_plain(job, m, true, false);
}

#if VF_SPECIAL_LOOPS
/* A grey transfer function's table (r = g = b in every entry): one colour product a pixel for three */
static VF_NOINLINE void row_point_256_grey(const row_job_t *job, run_merge_t *m)
{
    row_point_plain(job, m, true, true);
}

static VF_NOINLINE void row_point_n(const row_job_t *job, run_merge_t *m)
{
    row_point_plain(job, m, false, false);
}
#endif

#if VF_LIGHTING
/* A lit point frame's plain loop (docs/algorithm.md, section 7): each visible entry lit with its sample's shade;
 * nearest: the nearest voxel's, read through a code row with the slice's rounding folded in. grey: the table is
 * grey, one colour lit and blended for three (vfi_light_point's and vfi_blend's sums, the plain lit path having no
 * gradient factor). */
static VF_ALWAYS_INLINE void row_point_lit_body(const row_job_t *job, run_merge_t *m, bool n256, bool nearest,
                                                bool grey)
{
    const slice_place_t *sl = job->front;
    const uint32_t row = job->row, cu = (uint32_t)sl->cu, fx = sl->fx, fy = job->front_fy, n = job->lookup.n;
    const uint16_t *table = job->lookup.q15;
    const uint8_t *data = job->row_data;
    const vfi_shading_t *sh = job->shading;
    const uint16_t *codes = sh->codes + (data - sh->slices) + (fy >= 32768u ? row : 0) + (fx >= 32768u ? 1 : 0) - cu;
    uint16_t *next = job->next, *pixels = job->pixels;
    int32_t a, b;
    while (vfi_merge_next(m, &a, &b)) {
        a = a > job->clip_lo ? a : job->clip_lo;
        b = b < job->clip_hi + 1 ? b : job->clip_hi + 1;
        for (uint32_t u = a < b ? vfi_next_open(next, (uint32_t)a) : (uint32_t)b; u < (uint32_t)b;
             u = vfi_next_open(next, u + 1)) {
            const uint8_t *p = data + (u - cu);
            const uint16_t *e = point_entry(table, p, row, fx, fy, n, n256);
            if (!e[3])
                continue;
            uint32_t seg[4] = {e[0], e[1], e[2], e[3]};
            vfi_shade_t shade;
            if (nearest) {
                const uint64_t lit = sh->shade[codes[u]];
                shade.d = vfi_shade_diffuse(lit), shade.s = vfi_shade_specular(lit), shade.g = 32768u;
            } else {
                shade = vfi_sample_shade(sh, p, row, fx, fy);
            }
            if (grey) {
                const uint32_t alpha = e[3], c = (shade.d * e[0] + shade.s * alpha + 0x2000u) >> 14;
                const uint32_t colour = c < alpha ? c : alpha, over = alpha > VFI_ONE_Q15 ? VFI_ONE_Q15 : alpha;
                if (vfi_blend_grey(pixels + (size_t)u * 4, colour, over))
                    next[u] = (uint16_t)(u + 1);
                continue;
            }
            vfi_light_point(seg, shade);
            if (vfi_blend(pixels + (size_t)u * 4, seg))
                next[u] = (uint16_t)(u + 1);
        }
    }
}

#if VF_SPECIAL_LOOPS
static VF_NOINLINE void row_point_lit_grey(const row_job_t *job, run_merge_t *m)
{
    row_point_lit_body(job, m, true, true, true);
}
#endif

static VF_NOINLINE void row_point_lit(const row_job_t *job, run_merge_t *m)
{
    const bool n256 = job->lookup.n == 256;
#if VF_SPECIAL_LOOPS
    if (n256 && !job->shading->bilinear && job->grey) { /* the default lit frame of a grey transfer function */
        row_point_lit_grey(job, m);
        return;
    }
#endif
    if (!job->shading->bilinear)
        n256 ? row_point_lit_body(job, m, true, true, false) : row_point_lit_body(job, m, false, true, false);
    else
        n256 ? row_point_lit_body(job, m, true, false, false) : row_point_lit_body(job, m, false, false, false);
}
#endif

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

/* The general loops out of vfi_row_order0, so that a row of the plain path does not pay for their registers (inlined,
 * the dispatch would save six registers a row for them: 24 instructions). */
static VF_NOINLINE void row_general_any(const row_job_t *job, run_merge_t *m, bool preclass)
{
    const bool one_ray = VF_MAX_RAYS == 1 || job->step == 65536; /* constant in one-ray builds */
    if (one_ray)
        preclass ? row_general(job, m, true, true) : row_general(job, m, false, true);
    else
        preclass ? row_general(job, m, true, false) : row_general(job, m, false, false);
}

void vfi_row_order0(const row_job_t *job, run_merge_t *m, bool preclass)
{
#if VF_LIGHTING
    if (job->plain_lit && !preclass) {
        row_point_lit(job, m);
        return;
    }
#if VF_SPECIAL_LOOPS
    if (job->plain_lit) {
        vfi_row_preclass_lit(job, m);
        return;
    }
#endif
#endif
#if VF_SPECIAL_LOOPS
    if (job->plain && !preclass && job->lookup.n == 256 && job->grey)
        row_point_256_grey(job, m);
    else
#endif
    if (job->plain && !preclass && job->lookup.n == 256)
        row_point_256(job, m);
#if VF_SPECIAL_LOOPS
    else if (job->preclass_terms)
        vfi_row_preclass(job, m);
    else if (job->plain && !preclass)
        row_point_n(job, m);
#endif
    else
        row_general_any(job, m, preclass);
}
