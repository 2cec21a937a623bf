/*
 * composite_order1.c: the rows of one slab in preint1 (docs/algorithm.md, sections 4 and 4b): each open pixel of
 * the visible runs takes the pre-integrated entry of its front and back sample.
 *
 * A slab's back sample is the next slab's front sample, so its table position is buffered. Whether a pixel's
 * buffered position is this slab's front is known per run rather than per pixel: it is exactly when the last slab
 * walked the pixel, that is when the pixel lies in one of the runs the last slab walked in this row (an open pixel
 * now was open then, and every open pixel of a walked run was given its back sample). So each run is cut where the
 * last slab's runs begin and end, into spans whose fronts are all in the buffer or all sampled here, and the loops
 * over pixels test nothing per pixel. (A slice tag in every buffered word, tested per pixel, measured 1.4% more
 * instructions per frame for engine and 7% more for brainsmall, whose runs are long: callgrind, `volfix-sim bench
 * VOLUME --preset ramp --frames 1`.)
 */
#include "composite.h"

#define MIN(a, b) ((a) < (b) ? (a) : (b))
#define MAX(a, b) ((a) > (b) ? (a) : (b))


/* The arrays of one row of the plain path addressed by c = u - cu, the back slice's column of pixel u (the slice
 * buffer's rows have one element before column 0, for a front slice one column to the right of the back one). */
typedef struct row_arrays {
    uint32_t cu;
    const uint8_t *top, *bottom;   /* the back sample's two slice rows */
    const uint32_t *front_buf;
    uint32_t *back_buf;
    uint16_t *pixels;
} row_arrays_t;

/* The default path (nearest lookup, 16-bit table, no lut, full precision), where preint1 frames spend their time:
 * the open pixels of [x, y), their front entries from the buffer (buffered) or sampled here. The loop keeps all it
 * reads in locals, so that the stores to the buffer and the pixels cannot make the compiler read it again; as
 * first written it kept eleven values on the stack and read them every segment.
 * Returns y, or, in a table built as read, the pixel whose entry was unbuilt, its back sample stored, with the
 * entry's front and back in *f, *b: the caller builds that diagonal and composites the pixel (plain_unbuilt).
 * The call in the loop would make it keep more on the stack: 3 instructions more a segment. */
static VF_ALWAYS_INLINE uint32_t span_plain(const row_job_t *job, const row_arrays_t *ra, uint32_t x, uint32_t y,
                                            bool buffered, bool n256, uint32_t *f, uint32_t *b)
{
    const uint32_t n = n256 ? 256 : job->lookup.n, cu = ra->cu, fx = job->back->fx, fy = job->back_fy;
    const uint8_t *top = ra->top, *bottom = ra->bottom;
    const uint32_t *front_buf = ra->front_buf;
    uint32_t *back_buf = ra->back_buf;
    const uint16_t *table = job->lookup.q15;
    uint16_t *next = job->next, *pixels = ra->pixels;
    for (uint32_t u = vfi_next_open(next, x); u < y; u = vfi_next_open(next, u + 1)) {
        const uint32_t c = u - cu;
        uint32_t row_f; /* front entry times N */
        if (buffered) {
            row_f = front_buf[c];
        } else {
            const slice_place_t *fr = job->front;
            uint64_t s = vfi_sample_at(job->row_data + (u - (uint32_t)fr->cu), job->row, fr->fx, job->front_fy);
            row_f = n * vfi_entry_of_sample_n(n, s);
        }
        const uint32_t pos_b = vfi_entry_of_sample_n(n, vfi_sample_rows(top + c, bottom + c, fx, fy));
        back_buf[c] = pos_b * n;
        const uint16_t *e = table + ((size_t)row_f + pos_b) * 4;
        if (e[3]) {
            if (vfi_blend_q15(pixels + (size_t)c * 4, e))
                next[u] = (uint16_t)(u + 1);
        } else if (VF_TABLE_ON_DEMAND && e[0] == VFI_UNBUILT_Q15) { /* only ever in a table built as read */
            *f = row_f / n, *b = pos_b;
            return u;
        }
    }
    return y;
}

/* Pixel u's segment, entry (f, b), which span_plain found unbuilt: the diagonal built, then what the loop would do
 * with it. Returns the pixel to go on from. */
static uint32_t plain_unbuilt(const row_job_t *job, const row_arrays_t *ra, uint32_t u, uint32_t f, uint32_t b)
{
    vfi_preint_demand_diagonal(job->demand, f, b);
    const uint16_t *e = job->lookup.q15 + ((size_t)f * job->lookup.n + b) * 4;
    if (e[3] && vfi_blend_q15(ra->pixels + (size_t)(u - ra->cu) * 4, e))
        job->next[u] = (uint16_t)(u + 1);
    return u + 1;
}

/* Any lookup, table format, correction, precision study or number of rays: the open pixels of [x, y). Nearest
 * positions are kept times N in the buffer (the front entry's row in the 2D table), bilinear ones as they are.
 * With one ray per voxel a pixel's column is u - cu at the slice's one fraction; with more each pixel has its own. */
static VF_ALWAYS_INLINE void span_general_body(const row_job_t *job, uint32_t x, uint32_t y, bool buffered,
                                               bool one_ray)
{
    const slice_place_t *fr = job->front, *bk = job->back;
    const uint32_t n = job->lookup.n, scale = job->bilinear ? 1 : n;
    for (uint32_t u = vfi_next_open(job->next, x); u < y; u = vfi_next_open(job->next, u + 1)) {
        uint32_t fx, i, pos_f;
        if (buffered) {
            pos_f = job->front_buf[u - (uint32_t)job->front_shift];
        } else {
            i = one_ray ? u - (uint32_t)fr->cu : vfi_column(fr, job->step, u, &fx);
            pos_f = scale * vfi_table_position(job, job->row_data + i, one_ray ? fr->fx : fx, job->front_fy);
        }
        i = one_ray ? u - (uint32_t)bk->cu : vfi_column(bk, job->step, u, &fx);
        uint32_t pos_b = vfi_table_position(job, job->back_row_data + i, one_ray ? bk->fx : fx, job->back_fy);
        job->back_buf[u - (uint32_t)job->back_shift] = pos_b * scale;
        uint32_t seg[4];
        vfi_segment_preint1(job, job->bilinear ? pos_f : pos_f / n, pos_b, seg);
        if (vfi_composite_segment(job, job->pixels + (size_t)u * 4, seg))
            job->next[u] = (uint16_t)(u + 1);
    }
}

static void span_general(const row_job_t *job, uint32_t x, uint32_t y, bool buffered)
{
    if (VF_MAX_RAYS == 1 || job->step == 65536) /* constant in one-ray builds */
        buffered ? span_general_body(job, x, y, true, true) : span_general_body(job, x, y, false, true);
    else
        buffered ? span_general_body(job, x, y, true, false) : span_general_body(job, x, y, false, false);
}

/* A row: its visible runs, each cut into spans whose fronts are all buffered or all sampled here. Specialised below
 * for the plain path with 256 entries (the default), the plain path and the general one. */
static VF_ALWAYS_INLINE void row(const row_job_t *job, run_merge_t *m, bool plain, bool n256)
{
    const slice_place_t *fr = job->front, *bk = job->back;
    const int32_t lo = MAX(fr->u_lo, bk->u_lo), hi = MIN(fr->u_hi, bk->u_hi); /* both samples inside */
    const vfi_span_t *last = job->last ? job->last->span : NULL;
    const uint32_t last_count = job->last ? job->last->count : 0;
    vfi_span_t *walked = job->visits->span;
    uint32_t k = 0, count = 0; /* k: the first of the last slab's runs that may reach the current pixel */
    row_arrays_t ra;
    ra.cu = (uint32_t)bk->cu;
    ra.top = job->back_row_data;
    ra.bottom = ra.top + job->row;
    ra.front_buf = job->front_buf + (bk->cu - job->front_shift); /* slice buffer: -1, 0 or 1 */
    ra.back_buf = job->back_buf + (bk->cu - job->back_shift);
    ra.pixels = job->pixels + (size_t)ra.cu * 4;
    int32_t a, b;
    while (vfi_merge_next(m, &a, &b)) {
        a = MAX(a, lo);
        b = MIN(b, hi + 1);
        if (a >= b)
            continue;
        walked[count].a = (uint32_t)a;
        walked[count].b = (uint32_t)b;
        count++;
        for (uint32_t x = (uint32_t)a; x < (uint32_t)b;) {
            while (k < last_count && last[k].b <= x)
                k++;
            const bool buffered = k < last_count && last[k].a <= x;
            const uint32_t end = buffered ? last[k].b : k < last_count ? last[k].a : (uint32_t)b;
            const uint32_t y = MIN(end, (uint32_t)b);
            if (!plain) {
                span_general(job, x, y, buffered);
                x = y;
                continue;
            }
            uint32_t ef, eb; /* the entry span_plain found unbuilt */
            x = buffered ? span_plain(job, &ra, x, y, true, n256, &ef, &eb)
                         : span_plain(job, &ra, x, y, false, n256, &ef, &eb);
            if (VF_TABLE_ON_DEMAND && x < y)
                x = plain_unbuilt(job, &ra, x, ef, eb);
            else
                x = y;
        }
    }
    job->visits->count = count;
}

void vfi_row_preint1(const row_job_t *job, run_merge_t *m)
{
    if (!job->plain)
        row(job, m, false, false);
    else if (job->lookup.n == 256)
        row(job, m, true, true);
    else
        row(job, m, true, false);
}
