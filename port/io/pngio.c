/* pngio.c: PNG files through libpng (see pngio.h). */
#include "pngio.h"

#include <errno.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void vfp_image_to_rgb(const vf_image_t *img, uint8_t *rgb)
{
    for (uint32_t y = 0; y < img->height; y++) {
        const uint8_t *src = (const uint8_t *)img->pixels + (size_t)y * img->stride;
        uint8_t *dst = rgb + (size_t)y * img->width * 3;
        for (uint32_t x = 0; x < img->width; x++, dst += 3) {
            switch (img->format) {
            case VF_FORMAT_RGB888:
                memcpy(dst, src + x * 3, 3);
                break;
            case VF_FORMAT_RGB565: {
                unsigned word = src[x * 2] | (unsigned)src[x * 2 + 1] << 8;
                dst[0] = (uint8_t)(((word >> 11) * 255 + 15) / 31);
                dst[1] = (uint8_t)((((word >> 5) & 63) * 255 + 31) / 63);
                dst[2] = (uint8_t)(((word & 31) * 255 + 15) / 31);
                break;
            }
            default: /* XRGB8888: B, G, R, X */
                dst[0] = src[x * 4 + 2];
                dst[1] = src[x * 4 + 1];
                dst[2] = src[x * 4 + 0];
                break;
            }
        }
    }
}

vfp_status_t vfp_png_write(const char *path, const vf_image_t *img, char *err, size_t errlen)
{
    uint8_t *rgb = malloc((size_t)img->width * img->height * 3);
    if (!rgb) {
        snprintf(err, errlen, "%s: out of memory for a %ux%u image", path, img->width, img->height);
        return VFP_ERR;
    }
    vfp_image_to_rgb(img, rgb);
    vfp_status_t status = vfp_png_write_rgb(path, rgb, img->width, img->height, err, errlen);
    free(rgb);
    return status;
}

vfp_status_t vfp_png_write_rgb(const char *path, const uint8_t *rgb, uint32_t width, uint32_t height, char *err,
                               size_t errlen)
{
    png_image image;
    memset(&image, 0, sizeof image);
    image.version = PNG_IMAGE_VERSION;
    image.width = width;
    image.height = height;
    image.format = PNG_FORMAT_RGB;
    if (!png_image_write_to_file(&image, path, 0, rgb, (png_int_32)(width * 3), NULL)) {
        snprintf(err, errlen, "%s: cannot write PNG: %s", path, image.message[0] ? image.message : strerror(errno));
        return VFP_ERR;
    }
    return VFP_OK;
}

vfp_status_t vfp_png_read_rgb(const char *path, uint8_t **rgb, uint32_t *width, uint32_t *height, char *err,
                              size_t errlen)
{
    png_image image;
    memset(&image, 0, sizeof image);
    image.version = PNG_IMAGE_VERSION;
    *rgb = NULL;
    if (!png_image_begin_read_from_file(&image, path)) {
        snprintf(err, errlen, "%s: cannot read PNG: %s", path, image.message);
        return VFP_ERR;
    }
    image.format = PNG_FORMAT_RGB;
    uint8_t *buf = malloc(PNG_IMAGE_SIZE(image));
    if (!buf || !png_image_finish_read(&image, NULL, buf, 0, NULL)) {
        snprintf(err, errlen, "%s: cannot read PNG: %s", path, buf ? image.message : "out of memory");
        free(buf);
        png_image_free(&image);
        return VFP_ERR;
    }
    *rgb = buf;
    *width = image.width;
    *height = image.height;
    return VFP_OK;
}
