/* SPDX-License-Identifier: MIT */
/*
 * composite_preclass.c: preclass's plain loop (docs/algorithm.md, section 4; docs/performance.md, 0.7.0): the rows
 * of one slice of an unlit preclass frame on the plain path, to the bit what the general loop computes.
 *
 * The general loop classifies each of a sample's four voxels (scalar to entry to four Q1.15 values), lerps the two
 * slice rows across at fx, then the two results down at fy: 4 look-ups and 24 multiplications a sample. Here:
 *   - a band's classes: each 8-bit scalar's entry as two 64-bit words of two 32-bit lanes, r | b << 32 and
 *     g | a << 32 (vfi_preclass_classes), so that one multiplication scales two channels; every lane stays below
 *     2^32 in what follows (values at most 1.0 = 2^15, fractions below 2^16), so the lanes never carry into each
 *     other and each lane holds exactly what the general loop's 32-bit channel holds;
 *   - a slice's terms: fx is the same for the whole slice (one ray per voxel column), so the lerp across,
 *     (x (2^16 - fx) + y fx + 2^15) >> 16, is a sum of two terms of a 256-entry table each: x's side with the
 *     rounding in it and y's side (vfi_preclass_terms);
 *   - a sample: across the two rows by those sums, down by two multiplications a word, blended by one a word.
 */
#include "composite.h"

#if VF_SPECIAL_LOOPS
#define LANES UINT64_C(0x0000FFFF0000FFFF)    /* the low 16 bits of each 32-bit lane */
#define ROUND16 UINT64_C(0x0000800000008000) /* 2^15 in each lane: rounds a lerp's >> 16 */
#define ROUND15 UINT64_C(0x0000400000004000) /* 2^14 in each lane: rounds a blend's >> 15 */

void vfi_preclass_classes(const row_job_t *job, uint64_t *classes)
{
    const uint16_t *table = job->lookup.q15, *entry = job->cls->entry_of_scalar;
    for (uint32_t s = 0; s < 256; s++) {
        const uint16_t *e = table + (size_t)entry[s] * 4;
        classes[2 * s] = e[0] | (uint64_t)(job->grey ? e[3] : e[2]) << 32;
        classes[2 * s + 1] = e[1] | (uint64_t)e[3] << 32;
    }
}

void vfi_preclass_terms(const uint64_t *classes, uint32_t fx, bool grey, uint64_t *terms)
{
    const uint32_t fx1 = 65536u - fx;
    for (uint32_t s = 0; s < 256; s++) {
        const uint64_t w0 = classes[2 * s], w1 = classes[2 * s + 1];
        terms[s] = w0 * fx1 + ROUND16;
        terms[512 + s] = w0 * fx;
        if (grey)
            continue;
        terms[256 + s] = w1 * fx1 + ROUND16;
        terms[768 + s] = w1 * fx;
    }
}

/* Pixel px's r, g, b, a as one word of four 16-bit lanes, r lowest, and back (any byte order; on a little-endian
 * core the compiler makes each a single load or store). */
static VF_ALWAYS_INLINE uint64_t load_pixel(const uint16_t *px)
{
    return px[0] | (uint64_t)px[1] << 16 | (uint64_t)px[2] << 32 | (uint64_t)px[3] << 48;
}

static VF_ALWAYS_INLINE void store_pixel(uint16_t *px, uint64_t v)
{
    px[0] = (uint16_t)v;
    px[1] = (uint16_t)(v >> 16);
    px[2] = (uint16_t)(v >> 32);
    px[3] = (uint16_t)(v >> 48);
}

/* The lerp across a slice row at its slice's fx, of voxels p[0] and p[1]: word 0 or 1 of their classes. */
static VF_ALWAYS_INLINE uint64_t across(const uint64_t *terms, const uint8_t *p, int word)
{
    return ((terms[word * 256 + p[0]] + terms[512 + word * 256 + p[1]]) >> 16) & LANES;
}

/* The lerp down from x (the upper row's) to y at fy, fy1 = 2^16 - fy. */
static VF_ALWAYS_INLINE uint64_t down(uint64_t x, uint64_t y, uint32_t fy, uint32_t fy1)
{
    return ((x * fy1 + y * fy + ROUND16) >> 16) & LANES;
}

/* One row. grey: r = g = b in every entry, and the classes' word 0 is r | a << 32: one channel for three. */
static VF_ALWAYS_INLINE void row_body(const row_job_t *job, run_merge_t *m, bool grey)
{
    const slice_place_t *sl = job->front;
    const uint32_t row = job->row, cu = (uint32_t)sl->cu, fy = job->front_fy, fy1 = 65536u - fy;
    const uint64_t *terms = job->preclass_terms;
    const uint8_t *data = job->row_data;
    uint16_t *next = job->next, *pixels = job->pixels;
    const int alpha_word = grey ? 0 : 1;
    int32_t a, b;
    while (vfi_merge_next(m, &a, &b)) {
        a = a > job->clip_lo ? a : job->clip_lo;
        b = b < job->clip_hi + 1 ? b : job->clip_hi + 1;
        for (uint32_t u = a < b ? vfi_next_open(next, (uint32_t)a) : (uint32_t)b; u < (uint32_t)b;
             u = vfi_next_open(next, u + 1)) {
            const uint8_t *p = data + (u - cu);
            const uint64_t wa = down(across(terms, p, alpha_word), across(terms, p + row, alpha_word), fy, fy1);
            if (!(wa >> 32))
                continue; /* alpha 0, and so colour 0 (an entry's colour is at most its alpha): nothing to add */
            uint16_t *px = pixels + (size_t)u * 4;
            const uint64_t before = load_pixel(px);
            const uint32_t t = VFI_ONE_Q15 - (uint32_t)(before >> 48);
            /* a lane's sum is below 2^31, so >> 15 leaves it in the low 16 bits of its lane; a channel's sum stays
             * below 2^16 (at most 1.0 and a rounding), so the four adds do not carry into each other */
            const uint64_t add_a = (wa * t + ROUND15) >> 15;
            uint64_t add;
            if (grey) {
                add = (add_a & 0xFFFFu) * UINT64_C(0x100010001) + ((add_a >> 32) << 48);
            } else {
                const uint64_t rb = down(across(terms, p, 0), across(terms, p + row, 0), fy, fy1);
                add = (((rb * t + ROUND15) >> 15) & LANES) | (add_a & LANES) << 16;
            }
            store_pixel(px, before + add);
            if (px[3] >= VFI_OPAQUE_Q15)
                next[u] = (uint16_t)(u + 1);
        }
    }
}

static VF_NOINLINE void row_grey(const row_job_t *job, run_merge_t *m)
{
    row_body(job, m, true);
}

static VF_NOINLINE void row_colour(const row_job_t *job, run_merge_t *m)
{
    row_body(job, m, false);
}

void vfi_row_preclass(const row_job_t *job, run_merge_t *m)
{
    if (job->grey)
        row_grey(job, m);
    else
        row_colour(job, m);
}
#endif
