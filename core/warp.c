/*
 * warp.c: resample the intermediate image onto the final image, one band of output rows at a time
 * (docs/algorithm.md, section 5).
 *
 * Each final pixel's intermediate point is u0 + x du/dx + y du/dy in Q32.32, exact (no accumulated rounding);
 * the bilinear weights are Q0.16, the colour Q1.15 until it is packed into the output format.
 */
#include "render.h"

#define ONE_Q32 (INT64_C(1) << 32)

static void sample_intermediate(const vf_renderer_t *r, int64_t u_q32, int64_t v_q32, uint32_t rgba[4]);
static void store_pixel(unsigned char *dst, vf_format_t format, const uint32_t rgb[3]);

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
    uint32_t bg[3];
    bool have_bg = false;
    for (int c = 0; c < 3; c++) {
        bg[c] = ((uint32_t)r->params.background[c] * VFI_ONE_Q15 + 65535u / 2) / 65535u;
        have_bg |= bg[c] != 0;
    }

    for (uint32_t y = y0; y < y1; y++) {
        unsigned char *dst = (unsigned char *)image->pixels + (size_t)y * image->stride;
        int64_t u = f->u0_q32 + (int64_t)y * f->du_dy_q32;
        int64_t v = f->v0_q32 + (int64_t)y * f->dv_dy_q32;
        for (uint32_t x = 0; x < image->width; x++, dst += bpp, u += f->du_dx_q32, v += f->dv_dx_q32) {
            uint32_t px[4];
            sample_intermediate(r, u, v, px);
            if (have_bg)
                for (int c = 0; c < 3; c++)
                    px[c] += ((VFI_ONE_Q15 - (px[3] > VFI_ONE_Q15 ? VFI_ONE_Q15 : px[3])) * bg[c] + 0x4000u) >> 15;
            store_pixel(dst, image->format, px);
        }
    }
    return VF_OK;
}

/* Bilinear, with pixels outside the intermediate image transparent; Q1.15 r, g, b, a. */
static void sample_intermediate(const vf_renderer_t *r, int64_t u_q32, int64_t v_q32, uint32_t out[4])
{
    const int64_t w = r->factor.int_w, h = r->factor.int_h;
    out[0] = out[1] = out[2] = out[3] = 0;
    /* Shifted by one pixel, the support (-1, w) x (-1, h) is positive, and shifts act as floor. */
    int64_t us = u_q32 + ONE_Q32, vs = v_q32 + ONE_Q32;
    if (us <= 0 || vs <= 0 || us >= (w + 1) * ONE_Q32 || vs >= (h + 1) * ONE_Q32)
        return;
    int32_t iu = (int32_t)(us >> 32) - 1, iv = (int32_t)(vs >> 32) - 1;
    uint32_t fx = (uint32_t)(us >> 16) & 0xFFFFu, fy = (uint32_t)(vs >> 16) & 0xFFFFu;
    uint32_t w11 = (fx * fy + 0x8000u) >> 16;
    const uint32_t weight[4] = {65536u - fx - fy + w11, fx - w11, fy - w11, w11};
    const int32_t du[4] = {0, 1, 0, 1}, dv[4] = {0, 0, 1, 1};
    uint32_t acc[4] = {0x8000u, 0x8000u, 0x8000u, 0x8000u};
    for (int n = 0; n < 4; n++) {
        int32_t pu = iu + du[n], pv = iv + dv[n];
        if (weight[n] == 0 || pu < 0 || pv < 0 || pu >= w || pv >= h)
            continue;
        const uint16_t *p = r->intermediate + ((size_t)pv * (size_t)w + (size_t)pu) * 4;
        for (int c = 0; c < 4; c++)
            acc[c] += p[c] * weight[n]; /* at most 32768 * 65536 in all */
    }
    for (int c = 0; c < 4; c++)
        out[c] = acc[c] >> 16;
}

static void store_pixel(unsigned char *dst, vf_format_t format, const uint32_t rgb[3])
{
    uint32_t c[3];
    for (int n = 0; n < 3; n++)
        c[n] = rgb[n] > VFI_ONE_Q15 ? VFI_ONE_Q15 : rgb[n];
    switch (format) {
    case VF_FORMAT_RGB888:
        for (int n = 0; n < 3; n++)
            dst[n] = (unsigned char)((c[n] * 255u + 0x4000u) >> 15);
        break;
    case VF_FORMAT_RGB565: {
        uint32_t word = ((c[0] * 31u + 0x4000u) >> 15) << 11 | ((c[1] * 63u + 0x4000u) >> 15) << 5 |
                        ((c[2] * 31u + 0x4000u) >> 15);
        dst[0] = (unsigned char)(word & 0xFFu);
        dst[1] = (unsigned char)(word >> 8);
        break;
    }
    default: /* VF_FORMAT_XRGB8888: bytes B, G, R, X */
        dst[0] = (unsigned char)((c[2] * 255u + 0x4000u) >> 15);
        dst[1] = (unsigned char)((c[1] * 255u + 0x4000u) >> 15);
        dst[2] = (unsigned char)((c[0] * 255u + 0x4000u) >> 15);
        dst[3] = 0xFFu;
        break;
    }
}
