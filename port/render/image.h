/* SPDX-License-Identifier: MIT */
/*
 * image.h: images of the core's pixel formats in malloc'd memory, and the hash that says two frames are the
 * same (across architectures, threads, and on a microcontroller that can only print a number).
 */
#ifndef VFP_IMAGE_H
#define VFP_IMAGE_H

#include <stdint.h>

#include "status.h"
#include "volfix.h"

/* An image of this size and format in calloc'd memory, rows packed: VFP_OK, or VFP_ERR when out of memory (pixels
 * NULL; the caller words the message). vfp_image_free gives it back and leaves pixels NULL (safe to call again). */
vfp_status_t vfp_image_alloc(vf_image_t *image, uint32_t width, uint32_t height, vf_format_t format);
void vfp_image_free(vf_image_t *image);

/* FNV-1a, 64 bits, over the pixel bytes row by row (width * bytes per pixel of each row, never the stride's
 * padding), starting from the offset basis 0xcbf29ce484222325 with the prime 0x100000001b3. The firmware of
 * boards/mps2-an386 computes the same over its frame. */
uint64_t vfp_image_hash(const vf_image_t *image);

#endif
