/* SPDX-License-Identifier: MIT */
/*
 * composite_partial.c: partial slabs at the volume's side faces (docs/algorithm.md, section 4c).
 *
 * Where a ray enters or leaves the box through a side face between two slices, preint1 composites the part of the
 * slab it spends inside the box, its entry corrected for that length, instead of the whole slab or nothing; and an
 * order-0 sample stands for the ray's part in the box from halfway to the slice before to halfway to the slice
 * after. Such pixels lie along the slices' edges (a few per row, and the rows that one slice of a slab covers and
 * the other does not), so this file favours exactness over speed and skips no cells: a segment whose cells are
 * invisible is exactly zero anyway.
 *
 * Everything is rounded where the spec rounds it: the inside part [lo, hi] of a slab on the 2^-16 grid, face
 * positions in Q16.16, face scalars in Q8.32. The length correction is the one step with a fixed-point error.
 */
#include "composite.h"
#include "fixmath.h"

#if VF_PARTIAL_SLABS

#define ONE_Q16 65536
#define MIN(a, b) ((a) < (b) ? (a) : (b))
#define MAX(a, b) ((a) > (b) ? (a) : (b))

/* round(2^16 a / b), half up, for b != 0: the quotient of two multiples of 2^-16 on the 2^-16 grid, where only
 * whether it lies in [0, 1] matters (the caller clamps it there). So |a| >= |b| is settled without dividing, and
 * otherwise |a| < |b| <= 2^16 (|shear| <= 1: consecutive offsets differ by at most a voxel), a 32-bit division. */
static int32_t quotient_q16(int64_t a, int64_t b)
{
    if (b < 0)
        a = -a, b = -b;
    if (a >= b)
        return a == b ? ONE_Q16 : 2 * ONE_Q16;
    if (a <= -b)
        return -2 * ONE_Q16;
    const uint32_t scaled = (uint32_t)(a < 0 ? -a : a) << 16, den = (uint32_t)b;
    const uint32_t q = scaled / den, twice_r = 2 * (scaled % den);
    /* t = +-(q + r / den); floor(t + 1/2) rounds up at exactly a half either way */
    return a >= 0 ? (int32_t)(q + (twice_r >= den)) : -(int32_t)(q + (twice_r > den));
}

/* Along one axis: the ray is at x0 + phi dx (Q16.16); narrow [l, h] to the fractions phi where it is in [0, last].
 * False when it never is. */
static bool narrow_axis(int64_t x0, int64_t dx, int64_t last, int32_t *l, int32_t *h)
{
    if (dx == 0)
        return x0 >= 0 && x0 <= last;
    const int32_t t0 = quotient_q16(-x0, dx), t1 = quotient_q16(last - x0, dx);
    *l = MAX(*l, MIN(t0, t1));
    *h = MIN(*h, MAX(t0, t1));
    return true;
}

/* The slab between slices fr (phi = 0) and bk (phi = 1) at pixel (u, v): the ray's slice position at phi = 0 and
 * its change over the slab, Q16.16. */
typedef struct slab_ray {
    int64_t x0, y0, dx, dy;
} slab_ray_t;

static slab_ray_t slab_ray(const row_job_t *job, const slice_place_t *fr, const slice_place_t *bk, uint32_t u,
                           int32_t v)
{
    slab_ray_t ray;
    ray.x0 = (int64_t)u * job->step - fr->ou;
    ray.y0 = (int64_t)v * job->step - fr->ov;
    ray.dx = (int64_t)fr->ou - bk->ou;
    ray.dy = (int64_t)fr->ov - bk->ov;
    return ray;
}

/* The part [lo, hi] of the slab (Q0.16) the ray spends inside the box; false when it is empty (lo > hi). */
static bool slab_inside(const row_job_t *job, const slab_ray_t *ray, int32_t *lo, int32_t *hi)
{
    int32_t l = 0, h = ONE_Q16;
    if (!narrow_axis(ray->x0, ray->dx, (int64_t)(job->ni - 1) << 16, &l, &h) ||
        !narrow_axis(ray->y0, ray->dy, (int64_t)(job->nj - 1) << 16, &l, &h))
        return false;
    *lo = l;
    *hi = h;
    return l <= h;
}

/* The exact bilinear sample of slice sl at slice position (x, y), Q16.16, inside the slice: Q8.32. */
static uint64_t sample_slice(const row_job_t *job, const slice_place_t *sl, int64_t x, int64_t y)
{
    const uint8_t *p = sl->data + (size_t)(y >> 16) * job->row + (size_t)(x >> 16);
    return vfi_sample_at(p, job->row, (uint32_t)x & 0xFFFFu, (uint32_t)y & 0xFFFFu);
}

/* floor(x / 2^16) for any sign (>> of a negative value is implementation-defined in C99). */
static int64_t floor_q16(int64_t x)
{
    return x >= 0 ? x >> 16 : -((-x + 0xFFFF) >> 16);
}

static int64_t clamp64(int64_t x, int64_t lo, int64_t hi)
{
    return x < lo ? lo : x > hi ? hi : x;
}

/* The face scalar at fraction phi (Q0.16) of the slab: the ray's position there rounded to the 2^-16 grid and
 * clamped to the slice, and (1 - phi) s_front + phi s_back of the two slices' samples there, rounded to Q8.32. */
static uint64_t face_scalar(const row_job_t *job, const slice_place_t *fr, const slice_place_t *bk,
                            const slab_ray_t *ray, int32_t phi)
{
    const int64_t x = clamp64(floor_q16(ray->x0 * ONE_Q16 + phi * ray->dx + 0x8000), 0, (int64_t)(job->ni - 1) << 16);
    const int64_t y = clamp64(floor_q16(ray->y0 * ONE_Q16 + phi * ray->dy + 0x8000), 0, (int64_t)(job->nj - 1) << 16);
    const uint64_t s_f = sample_slice(job, fr, x, y), s_b = sample_slice(job, bk, x, y); /* below 2^40 */
    return ((uint64_t)(ONE_Q16 - phi) * s_f + (uint64_t)phi * s_b + 0x8000u) >> 16;
}

static bool inside(const slice_place_t *sl, uint32_t u, int32_t v)
{
    return (int32_t)u >= sl->u_lo && (int32_t)u <= sl->u_hi && v >= sl->v_lo && v <= sl->v_hi;
}

/* (1 - a)^rho of a segment whose opacity is sum_k w_k a_k over table entries with optical depths D_k (a_k = 1 -
 * exp(-D_k); weights Q0.16 summing to 2^16): 1 - a = sum_k w_k exp(-D_k), taken in logs about the least depth of a
 * weighted entry, so that a transmittance far below 2^-16 keeps its bits (the entry's Q1.15 opacity does not: near
 * 1, 1 - a is a few LSB or 0, and a short part of a nearly opaque slab would come out opaque). Q.30. */
static uint32_t transmittance_q30(const uint64_t depth_q28[], const uint32_t weight_q16[], int count, uint32_t rho_q16)
{
    uint64_t least = UINT64_MAX, sum_q32 = 0;
    for (int k = 0; k < count; k++)
        if (weight_q16[k] && depth_q28[k] < least)
            least = depth_q28[k];
    for (int k = 0; k < count; k++) /* Q0.16 times Q.30: Q.46, to Q.32; at least 2^-16 (the least depth's term) */
        if (weight_q16[k])
            sum_q32 += ((uint64_t)weight_q16[k] * vfi_exp_neg_q28(depth_q28[k] - least)) >> 14;
    const uint64_t neg_ln_q28 = least + vfi_neg_ln_q32(sum_q32);
    return vfi_exp_neg_q28((neg_ln_q28 * rho_q16 + 0x8000u) >> 16); /* below 2^40 times 2^17: no overflow */
}

/* (1 - a)^rho from the entry's own opacity: for tables on a coarser grid (table bits below 16), where both
 * implementations shorten the value on the grid. */
static uint32_t transmittance_of_opacity_q30(uint32_t a, uint32_t rho_q16)
{
    if (a >= VFI_ONE_Q15)
        return 0;
    const uint64_t neg_ln_q28 = vfi_neg_ln_q32((uint64_t)(VFI_ONE_Q15 - a) << 17);
    return vfi_exp_neg_q28((neg_ln_q28 * rho_q16 + 0x8000u) >> 16);
}

/* The length correction for rho slabs (Q16.16, up to 1.5; section 4c): a' = 1 - (1 - a)^rho, given (1 - a)^rho,
 * and C' = C a' / a (rho C when a = 0). */
static void shorten(uint32_t seg[4], uint32_t rho_q16, uint32_t transmit_q30)
{
    const uint32_t a = MIN(seg[3], VFI_ONE_Q15);
    if (a == 0) {
        for (int c = 0; c < 3; c++)
            seg[c] = (uint32_t)(((uint64_t)seg[c] * rho_q16 + 0x8000u) >> 16);
        return;
    }
    const uint32_t alpha_q30 = (uint32_t)(VFI_ONE_Q30 - transmit_q30);
    const uint32_t gain_q16 = (uint32_t)(((uint64_t)alpha_q30 * 2 + a / 2) / a); /* a' / a: alpha_q30 / a is Q.15 */
    for (int c = 0; c < 3; c++)
        seg[c] = (uint32_t)(((uint64_t)seg[c] * gain_q16 + 0x8000u) >> 16);
    seg[3] = (alpha_q30 + (1u << 14)) >> 15;
}

/* The optical depth of pre-integrated entry (f, b) for the view's slab length d, Q.28: d / r times the sum of the r
 * intervals' mean extinctions (section 2), the D with opacity 1 - exp(-D); the point entry's tau_f d when f = b. */
static uint64_t depth_of_entries(const row_job_t *job, uint32_t f, uint32_t b)
{
    const vfi_classify_t *cls = job->cls;
    const uint64_t d = job->slab_q16;
    if (f == b)
        return ((uint64_t)cls->tau_q28[f] * d + 0x8000u) >> 16;
    const uint32_t lo = MIN(f, b), hi = MAX(f, b), r = hi - lo;
    /* twice the sum of means: the end entries once, those between twice; below 2^43, so shifted to keep the
     * product with d (below 2^23) in 64 bits */
    const uint64_t twice = 2 * (cls->tau_sum_q28[hi] - cls->tau_sum_q28[lo + 1]) + cls->tau_q28[lo] + cls->tau_q28[hi];
    return vfi_udiv64(((twice >> 8) * d + 0x80u) >> 8, 2 * (uint64_t)r);
}

/* (1 - a)^rho of a preint1 segment with table positions pos_f, pos_b (section 4b's lookups). */
static uint32_t preint1_transmittance(const row_job_t *job, uint32_t pos_f, uint32_t pos_b, const uint32_t seg[4],
                                      uint32_t rho_q16)
{
    if (!job->depth_from_tau)
        return transmittance_of_opacity_q30(MIN(seg[3], VFI_ONE_Q15), rho_q16);
    uint64_t depth[4];
    uint32_t weight[4];
    if (!job->bilinear) {
        depth[0] = depth_of_entries(job, pos_f, pos_b);
        weight[0] = ONE_Q16;
        return transmittance_q30(depth, weight, 1, rho_q16);
    }
    uint32_t i, fi, j, fj;
    vfi_split_position(job->lookup.n, pos_f, &i, &fi);
    vfi_split_position(job->lookup.n, pos_b, &j, &fj);
    vfi_weights(fi, fj, weight); /* entries (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1), as the lookup */
    for (int k = 0; k < 4; k++)
        depth[k] = depth_of_entries(job, i + (k & 1), j + (k >> 1));
    return transmittance_q30(depth, weight, 4, rho_q16);
}

/* The same for an order-0 segment: the sample's entry (nearest), the two entries about it (bilinear) or, for
 * preclass, the four voxels' entries with the sample's bilinear weights. */
static uint32_t order0_transmittance(const row_job_t *job, const uint8_t *p, uint32_t fx, uint32_t fy, bool preclass,
                                     const uint32_t seg[4], uint32_t rho_q16)
{
    if (!job->depth_from_tau)
        return transmittance_of_opacity_q30(MIN(seg[3], VFI_ONE_Q15), rho_q16);
    uint64_t depth[4];
    uint32_t weight[4], entry[4];
    int count;
    if (preclass) {
        vfi_weights(fx, fy, weight);
        const uint16_t *of = job->cls->entry_of_scalar;
        entry[0] = of[p[0]], entry[1] = of[p[1]], entry[2] = of[p[job->row]], entry[3] = of[p[job->row + 1]];
        count = 4;
    } else if (job->bilinear) {
        uint32_t i, f;
        vfi_split_position(job->lookup.n, vfi_table_position(job, p, fx, fy), &i, &f);
        entry[0] = i, entry[1] = i + 1, weight[0] = ONE_Q16 - f, weight[1] = f;
        count = 2;
    } else {
        entry[0] = vfi_table_position(job, p, fx, fy), weight[0] = ONE_Q16;
        count = 1;
    }
    for (int k = 0; k < count; k++)
        depth[k] = depth_of_entries(job, entry[k], entry[k]);
    return transmittance_q30(depth, weight, count, rho_q16);
}

void vfi_faces_preint1(const row_job_t *job, int32_t v, uint32_t x, uint32_t y)
{
    const slice_place_t *fr = job->front, *bk = job->back;
    for (uint32_t u = vfi_next_open(job->next, x); u < y; u = vfi_next_open(job->next, u + 1)) {
        const bool in_f = inside(fr, u, v), in_b = inside(bk, u, v);
        const slab_ray_t ray = slab_ray(job, fr, bk, u, v);
        int32_t lo, hi;
        if ((in_f && in_b) || !slab_inside(job, &ray, &lo, &hi) || lo >= hi)
            continue;
        const uint64_t s_f = in_f ? sample_slice(job, fr, ray.x0, ray.y0) : face_scalar(job, fr, bk, &ray, lo);
        const uint64_t s_b = in_b ? sample_slice(job, bk, ray.x0 + ray.dx, ray.y0 + ray.dy)
                                  : face_scalar(job, fr, bk, &ray, hi);
        const uint32_t pos_f = vfi_position_of(job, s_f), pos_b = vfi_position_of(job, s_b);
        uint32_t seg[4];
        vfi_segment_preint1(job, pos_f, pos_b, seg);
        const uint32_t rho = (uint32_t)(hi - lo);
        shorten(seg, rho, preint1_transmittance(job, pos_f, pos_b, seg, rho));
        if (vfi_composite_segment(job, job->pixels + (size_t)u * 4, seg))
            job->next[u] = (uint16_t)(u + 1);
    }
}

/* rho_- (or rho_+) of an order-0 sample of slice sl at (u, v): nothing beyond the first (last) slice, half a slab
 * when the neighbour's sample is inside, else the part inside the box of the slab between them. */
static uint32_t neighbour_part(const row_job_t *job, const slice_place_t *front, const slice_place_t *back,
                               const slice_place_t *neighbour, uint32_t u, int32_t v)
{
    if (!neighbour)
        return 0;
    if (inside(neighbour, u, v))
        return ONE_Q16 / 2;
    const slab_ray_t ray = slab_ray(job, front, back, u, v);
    int32_t lo, hi;
    return slab_inside(job, &ray, &lo, &hi) ? (uint32_t)(hi - lo) : 0;
}

void vfi_faces_order0(const row_job_t *job, int32_t v, uint32_t x, uint32_t y, bool preclass)
{
    const slice_place_t *sl = job->front;
    for (uint32_t u = vfi_next_open(job->next, x); u < y; u = vfi_next_open(job->next, u + 1)) {
        const uint32_t rho = neighbour_part(job, job->before, sl, job->before, u, v) +
                             neighbour_part(job, sl, job->after, job->after, u, v);
        if (rho == 0)
            continue;
        uint32_t fx, seg[4];
        const uint32_t i = vfi_column(sl, job->step, u, &fx);
        vfi_segment_order0(job, job->row_data + i, fx, job->front_fy, preclass, seg);
        if (rho != ONE_Q16)
            shorten(seg, rho, order0_transmittance(job, job->row_data + i, fx, job->front_fy, preclass, seg, rho));
        if (vfi_composite_segment(job, job->pixels + (size_t)u * 4, seg))
            job->next[u] = (uint16_t)(u + 1);
    }
}

#else

typedef int vfi_no_partial_slabs; /* an ISO C translation unit declares something */

#endif
