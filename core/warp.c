/* SPDX-License-Identifier: MIT */
/*
 * warp.c: resample the intermediate image onto the final image, one band of output rows at a time
 * (docs/algorithm.md, section 5).
 *
 * Each final pixel's intermediate point is u0 + x du/dx + y du/dy in Q32.32, exact (no accumulated rounding);
 * the bilinear weights are Q0.16, the colour Q1.15 until it is packed into the output format. Per row, the
 * pixels whose footprint misses the box of non-empty intermediate pixels get the background without being
 * sampled, and those whose four neighbours are all inside the image take a path without bounds checks, a loop for
 * each output format. The loops over a row's pixels are in warp_rows.c.
 */
#include "fixmath.h"
#include "warp_rows.h"

static void span(int64_t start, int64_t step, int64_t lo, int64_t hi, int64_t width, int64_t *x0, int64_t *x1);

vf_status_t vfi_warp_band(const vf_renderer_t *r, const vf_image_t *image, uint32_t y0, uint32_t y1)
{
    const vf_factor_t *f = &r->factor;
    const uint32_t bpp = vf_format_bytes(image->format);
    if (!image->pixels)
        return VF_ERR_NULL;
    if (bpp == 0 || image->width != f->out_w || image->height != f->out_h ||
        image->stride < (uint64_t)image->width * bpp)
        return VF_ERR_IMAGE;
    if (y0 >= y1 || y1 > image->height)
        return VF_ERR_ARG;

    /* The background shows through what the volume leaves: out = C + (1 - A) bg. */
    vfi_warp_row_t w;
    w.r = r;
    w.fraction_mask = (0xFFFFu >> (16 - r->params.warp_bits)) << (16 - r->params.warp_bits);
    w.format = image->format;
    w.have_bg = false;
    /* every table entry grey, lit or not (lights are white): so is every composited pixel; read by the inner loop */
    w.grey = VF_SPECIAL_LOOPS && r->tf_grey;
    for (int c = 0; c < 3; c++) {
        w.bg[c] = ((uint32_t)r->params.background[c] * VFI_ONE_Q15 + 65535u / 2) / 65535u;
        w.have_bg |= w.bg[c] != 0;
    }
    unsigned char background[4];
    vfi_warp_background(&w, background);

    const int64_t iw = f->int_w, ih = f->int_h;
    const uint16_t *img = r->intermediate;
    /* The box of intermediate pixels with anything in them, from the bands' row extents (VF_SPECIAL_LOOPS; else
     * the whole image): a final pixel whose footprint misses it is the background, however far inside the image it
     * lies. */
    int64_t box_u0 = 0, box_u1 = iw, box_v0 = 0, box_v1 = ih;
    if (VF_SPECIAL_LOOPS) {
        box_u0 = iw, box_u1 = 0, box_v0 = ih, box_v1 = 0;
        for (int64_t v = 0; v < ih; v++) {
            const int64_t lo = r->row_extent[2 * v], hi = r->row_extent[2 * v + 1];
            if (lo >= hi)
                continue;
            box_u0 = lo < box_u0 ? lo : box_u0, box_u1 = hi > box_u1 ? hi : box_u1;
            box_v0 = v < box_v0 ? v : box_v0, box_v1 = v + 1;
        }
    }
    for (uint32_t y = y0; y < y1; y++) {
        unsigned char *row = (unsigned char *)image->pixels + (size_t)y * image->stride;
        const int64_t u_row = f->u0_q32 + (int64_t)y * f->du_dy_q32, v_row = f->v0_q32 + (int64_t)y * f->dv_dy_q32;
        /* Pixels [touch0, touch1) see some of the box (u in (u0 - 1, u1), v in (v0 - 1, v1): none when it is
         * empty); within them, [inner0, inner1) have all four neighbours inside the image (u in [0, w - 1), v in
         * [0, h - 1)). */
        int64_t a0, a1, b0, b1, touch0, touch1, inner0, inner1;
        span(u_row, f->du_dx_q32, (box_u0 - 1) * VFI_ONE_Q32, box_u1 * VFI_ONE_Q32, image->width, &a0, &a1);
        span(v_row, f->dv_dx_q32, (box_v0 - 1) * VFI_ONE_Q32, box_v1 * VFI_ONE_Q32, image->width, &b0, &b1);
        touch0 = a0 > b0 ? a0 : b0;
        touch1 = a1 < b1 ? a1 : b1;
        span(u_row, f->du_dx_q32, 0, (iw - 1) * VFI_ONE_Q32, image->width, &a0, &a1);
        span(v_row, f->dv_dx_q32, 0, (ih - 1) * VFI_ONE_Q32, image->width, &b0, &b1);
        inner0 = a0 > b0 ? a0 : b0;
        inner1 = a1 < b1 ? a1 : b1;
        if (touch1 < touch0)
            touch0 = touch1 = 0;
        inner0 = inner0 > touch0 ? inner0 : touch0; /* inside the box's footprint too */
        inner1 = inner1 < touch1 ? inner1 : touch1;
        if (inner1 <= inner0 || !VF_SPECIAL_LOOPS) /* the small build: the edge's bilinear for every pixel */
            inner0 = inner1 = touch0;

        vfi_warp_fill(row, (uint32_t)touch0, background, w.format);
        for (int64_t x = touch0; x < inner0; x++)
            vfi_warp_edge(&w, u_row + x * f->du_dx_q32, v_row + x * f->dv_dx_q32, row + x * bpp);
        if (VF_SPECIAL_LOOPS)
            vfi_warp_inner(&w, img, iw, u_row + inner0 * f->du_dx_q32, v_row + inner0 * f->dv_dx_q32, f->du_dx_q32,
                           f->dv_dx_q32, row + inner0 * bpp, (uint32_t)(inner1 - inner0), background);
        for (int64_t x = inner1 > touch0 ? inner1 : touch0; x < touch1; x++)
            vfi_warp_edge(&w, u_row + x * f->du_dx_q32, v_row + x * f->dv_dx_q32, row + x * bpp);
        vfi_warp_fill(row + touch1 * bpp, image->width - (uint32_t)touch1, background, w.format);
    }
    return VF_OK;
}

/* The smallest x in [0, width] with start + x step > c (or >= c when or_equal), for step > 0: an estimate by
 * division, made exact by testing the inequality itself, so rounding can never admit a pixel outside. */
static int64_t first_past(int64_t start, int64_t step, int64_t c, bool or_equal, int64_t width)
{
    int64_t x = 0;
    if (c > start) {
        uint64_t q = vfi_udiv64((uint64_t)(c - start), (uint64_t)step);
        x = q > (uint64_t)width ? width : (int64_t)q;
    }
    while (x > 0 && (or_equal ? start + (x - 1) * step >= c : start + (x - 1) * step > c))
        x--;
    while (x < width && !(or_equal ? start + x * step >= c : start + x * step > c))
        x++;
    return x;
}

/* The pixels x in [0, width) with lo < start + x step < hi, as [x0, x1) (x1 <= x0 when there are none). */
static void span(int64_t start, int64_t step, int64_t lo, int64_t hi, int64_t width, int64_t *x0, int64_t *x1)
{
    if (step == 0) {
        *x0 = 0;
        *x1 = start > lo && start < hi ? width : 0;
    } else if (step > 0) {
        *x0 = first_past(start, step, lo, false, width);
        *x1 = first_past(start, step, hi, true, width);
    } else { /* mirrored: start + x step < hi  <=>  -start + x (-step) > -hi */
        *x0 = first_past(-start, -step, -hi, false, width);
        *x1 = first_past(-start, -step, -lo, true, width);
    }
}
