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
    if (grey) { /* word 0 alone, two scalars a step: the loop's own count and test weigh as much as a term */
        for (uint32_t s = 0; s < 256; s += 2) {
            const uint64_t w0 = classes[2 * s], v0 = classes[2 * s + 2];
            terms[s] = w0 * fx1 + ROUND16, terms[s + 1] = v0 * fx1 + ROUND16;
            terms[512 + s] = w0 * fx, terms[512 + s + 1] = v0 * fx;
        }
        return;
    }
    for (uint32_t s = 0; s < 256; s++) {
        const uint64_t w0 = classes[2 * s], w1 = classes[2 * s + 1];
        terms[s] = w0 * fx1 + ROUND16;
        terms[512 + s] = w0 * fx;
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

/* Composite a sample (its alpha word wa, g | a << 32, and its colour word rb, r | b << 32, unused when grey)
 * behind pixel u, front to back, and mark the pixel finished once it is opaque. */
static VF_ALWAYS_INLINE void over(uint16_t *pixels, uint16_t *next, uint32_t u, uint64_t wa, uint64_t rb, bool grey)
{
    uint16_t *px = pixels + (size_t)u * 4;
    const uint64_t before = load_pixel(px);
    const uint32_t t = VFI_ONE_Q15 - (uint32_t)(before >> 48);
    /* a lane's sum is below 2^31, so >> 15 leaves it in the low 16 bits of its lane; a channel's sum stays below
     * 2^16 (at most 1.0 and a rounding), so the four adds do not carry into each other */
    uint64_t add;
    if (grey) { /* vfi_blend_grey's sums: two 32-bit products, the colour's added to r, g and b in one word */
        const uint32_t add_c = (t * (uint32_t)wa + 0x4000u) >> 15, add_a = (t * (uint32_t)(wa >> 32) + 0x4000u) >> 15;
        add = add_c * 0x10001u | (uint64_t)(add_c | add_a << 16) << 32;
    } else {
        add = (((rb * t + ROUND15) >> 15) & LANES) | (((wa * t + ROUND15) >> 15) & LANES) << 16;
    }
    store_pixel(px, before + add);
    if (px[3] >= VFI_OPAQUE_Q15)
        next[u] = (uint16_t)(u + 1);
}

/* One row. grey: r = g = b in every entry, and the classes' word 0 is r | a << 32: one channel for three. */
static VF_ALWAYS_INLINE void row_body(const row_job_t *job, run_merge_t *m, bool grey)
{
    const uint32_t row = job->row, cu = (uint32_t)job->front->cu, fy = job->front_fy, fy1 = 65536u - fy;
    const uint64_t *terms = job->preclass_terms;
    /* grey: the slice rows by pixel, from column -cu (a register and a subtraction fewer); the colour loop, short of
     * registers already, does better with the pixel's column and the row length */
    const uint8_t *data = job->row_data, *top = data - cu, *bottom = top + row;
    uint16_t *next = job->next, *pixels = job->pixels;
    const int alpha_word = grey ? 0 : 1;
    int32_t a, b;
    while (vfi_merge_next(m, &a, &b)) {
        a = a > job->clip_lo ? a : job->clip_lo;
        b = b < job->clip_hi + 1 ? b : job->clip_hi + 1;
        for (uint32_t u = a < b ? vfi_next_open(next, (uint32_t)a) : (uint32_t)b; u < (uint32_t)b;
             u = vfi_next_open(next, u + 1)) {
            const uint8_t *p = grey ? top + u : data + (u - cu), *q = grey ? bottom + u : p + row;
            const uint64_t wa = down(across(terms, p, alpha_word), across(terms, q, alpha_word), fy, fy1);
            if (!(wa >> 32))
                continue; /* alpha 0, and so colour 0 (an entry's colour is at most its alpha): nothing to add */
            over(pixels, next, u, wa, grey ? 0 : down(across(terms, p, 0), across(terms, q, 0), fy, fy1), grey);
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

#if VF_LIGHTING
/* A voxel of scalar v and normal code c lit as the general loop lights it, C' = min((L_d C + L_s a + 2^13) >> 14, a)
 * per colour channel (vfi_light_point without a gradient factor: the plain path has none), into its words. */
static VF_ALWAYS_INLINE void lit_voxel(const uint64_t *classes, const uint64_t *shade, uint8_t v, uint16_t c, bool grey,
                                       uint64_t *out)
{
    const uint64_t e = shade[c], w0 = classes[2 * (size_t)v];
    const uint32_t d = vfi_shade_diffuse(e), a = (uint32_t)(classes[2 * (size_t)v + !grey] >> 32),
                   sa = vfi_shade_specular(e) * a + 0x2000u;
    uint32_t x = (d * (uint32_t)w0 + sa) >> 14;
    const uint64_t first = x < a ? x : a;
    if (grey) {
        out[0] = first | (uint64_t)a << 32;
        return;
    }
    const uint64_t w1 = classes[2 * (size_t)v + 1];
    x = (d * (uint32_t)(w0 >> 32) + sa) >> 14;
    out[0] = first | (uint64_t)(x < a ? x : a) << 32;
    x = (d * (uint32_t)w1 + sa) >> 14;
    out[1] = (x < a ? x : a) | (uint64_t)a << 32;
}

/* The lerp of two words at f (vfi_lerp on two lanes): x (2^16 - f) + y f is x 2^16 + (y - x) f, one product; y - x
 * borrows across the lanes, and the product and the sum carry back what it borrowed, as every lane of the sum is
 * in [0, 2^32). */
static VF_ALWAYS_INLINE uint64_t lerp_words(uint64_t x, uint64_t y, uint32_t f)
{
    return (((x << 16) + (y - x) * f + ROUND16) >> 16) & LANES;
}

/* A row of a lit frame. A pixel's sample is the lerp down of two lerps across (x), of the lit voxels at columns i and
 * i + 1 of slice rows j and j + 1. Row j + 1's x is this row's to work out; row j's the row above worked out (as its
 * row j + 1) if it walked this pixel, and left in the cache stamped with its slice row: else it is worked out here.
 * Along a run, column i's voxel of row j + 1 is the one the pixel before lit as its column i + 1: one voxel lit a
 * pixel, where the general loop lights four. */
static VF_ALWAYS_INLINE void row_lit_body(const row_job_t *job, run_merge_t *m, bool grey)
{
    const slice_place_t *sl = job->front;
    const uint32_t row = job->row, cu = (uint32_t)sl->cu, fx = sl->fx, fy = job->front_fy;
    const uint8_t *data = job->row_data;
    const vfi_shading_t *sh = job->shading;
    const uint64_t *classes = job->preclass_classes, *shade = sh->shade;
    const uint16_t *codes = sh->codes + (data - sh->slices);
    /* x of slice row j is stamped t (nj + 1) + j, in the cache row of j's parity. Row j + 1 can be row nj, past the
     * slice (the last row's samples have fy = 0 and weigh it 0), which is no other slice's row 0 that way */
    const uint32_t j = (uint32_t)((size_t)(data - sl->data) / row), key = job->t * (job->nj + 1) + j;
    const size_t cols = job->preclass_cols;
    const uint64_t *x_top = job->preclass_lit + (j & 1) * 2 * cols;
    uint64_t *x_bottom = job->preclass_lit + (~j & 1) * 2 * cols;
    const uint32_t *stamp_top = job->preclass_stamp + (j & 1) * cols;
    uint32_t *stamp_bottom = job->preclass_stamp + (~j & 1) * cols;
    uint16_t *next = job->next, *pixels = job->pixels;
    const int w = grey ? 0 : 1; /* the word with alpha */
    uint32_t last = UINT32_MAX - 1; /* the pixel before, whose column i + 1 voxel of row j + 1 is in carry */
    uint64_t carry[2] = {0, 0};
    int32_t a, b;
    while (vfi_merge_next(m, &a, &b)) {
        a = a > job->clip_lo ? a : job->clip_lo;
        b = b < job->clip_hi + 1 ? b : job->clip_hi + 1;
        for (uint32_t u = a < b ? vfi_next_open(next, (uint32_t)a) : (uint32_t)b; u < (uint32_t)b;
             u = vfi_next_open(next, u + 1)) {
            const uint32_t i = u - cu;
            uint64_t v0[2] = {carry[0], carry[1]}, top[2];
            if (u != last + 1)
                lit_voxel(classes, shade, data[row + i], codes[row + i], grey, v0);
            lit_voxel(classes, shade, data[row + i + 1], codes[row + i + 1], grey, carry);
            last = u;
            uint64_t *bottom = x_bottom + 2 * (size_t)i;
            bottom[0] = lerp_words(v0[0], carry[0], fx);
            if (!grey)
                bottom[1] = lerp_words(v0[1], carry[1], fx);
            stamp_bottom[i] = key + 1;
            if (stamp_top[i] == key) {
                top[0] = x_top[2 * (size_t)i];
                top[1] = grey ? 0 : x_top[2 * (size_t)i + 1];
            } else {
                uint64_t t0[2] = {0, 0}, t1[2] = {0, 0};
                lit_voxel(classes, shade, data[i], codes[i], grey, t0);
                lit_voxel(classes, shade, data[i + 1], codes[i + 1], grey, t1);
                top[0] = lerp_words(t0[0], t1[0], fx);
                top[1] = grey ? 0 : lerp_words(t0[1], t1[1], fx);
            }
            const uint64_t wa = lerp_words(top[w], bottom[w], fy);
            if (!(wa >> 32))
                continue;
            over(pixels, next, u, wa, grey ? 0 : lerp_words(top[0], bottom[0], fy), grey);
        }
    }
}

static VF_NOINLINE void row_lit_grey(const row_job_t *job, run_merge_t *m)
{
    row_lit_body(job, m, true);
}

static VF_NOINLINE void row_lit_colour(const row_job_t *job, run_merge_t *m)
{
    row_lit_body(job, m, false);
}

void vfi_row_preclass_lit(const row_job_t *job, run_merge_t *m)
{
    if (job->grey)
        row_lit_grey(job, m);
    else
        row_lit_colour(job, m);
}
#endif
#endif
