/* SPDX-License-Identifier: MIT */
/* image.c: images in malloc'd memory, and their hash (see image.h). */
#include "image.h"

#include <stdlib.h>

vfp_status_t vfp_image_alloc(vf_image_t *img, uint32_t width, uint32_t height, vf_format_t format)
{
    img->width = width;
    img->height = height;
    img->format = format;
    img->stride = width * vf_format_bytes(format);
    img->pixels = calloc(height, img->stride);
    return img->pixels ? VFP_OK : VFP_ERR;
}

void vfp_image_free(vf_image_t *img)
{
    free(img->pixels);
    img->pixels = NULL;
}

uint64_t vfp_image_hash(const vf_image_t *img)
{
    uint64_t h = UINT64_C(0xcbf29ce484222325);
    const size_t row_bytes = (size_t)img->width * vf_format_bytes(img->format);
    for (uint32_t y = 0; y < img->height; y++) {
        const uint8_t *row = (const uint8_t *)img->pixels + (size_t)y * img->stride;
        for (size_t i = 0; i < row_bytes; i++) {
            h ^= row[i];
            h *= UINT64_C(0x100000001b3);
        }
    }
    return h;
}
