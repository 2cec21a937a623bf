/* SPDX-License-Identifier: MIT */
/* pngio.h: images to and from PNG files (libpng), for the simulator, tests and the headless board. */
#ifndef VFP_PNG_H
#define VFP_PNG_H

#include <stddef.h>
#include <stdint.h>

#include "status.h"
#include "volfix.h"

/* Where a PNG goes (every PNG volfix and volfix-sim write):
 * - "-": standard output;
 * - an existing device, FIFO or socket: written in place, never replaced or removed;
 * - a regular file, or a name not there yet: written to a temporary file beside it (".NAME.XXXXXX"), then renamed
 *   over it, so that a failed write leaves the old file whole; the temporary file is the only thing volfix ever
 *   removes, and SIGINT, SIGTERM and SIGHUP wait until it is gone or renamed;
 * - a symbolic link: the file it names, by the same rules (the link stays).
 *
 * Write an image in any core format as an 8-bit RGB PNG. Returns VFP_OK, or VFP_ERR with a one-line message in err. */
vfp_status_t vfp_png_write(const char *path, const vf_image_t *image, char *err, size_t errlen);

/* Write 8-bit RGB pixels (width * height * 3, rows packed). */
vfp_status_t vfp_png_write_rgb(const char *path, const uint8_t *rgb, uint32_t width, uint32_t height, char *err,
                               size_t errlen);

/* Before any work: can a PNG be written to path by the rules above (its directory there and writable, or a
 * writable device or FIFO, or "-")? Returns VFP_OK, or VFP_ERR with a line naming the path in err. */
vfp_status_t vfp_png_check_output(const char *path, char *err, size_t errlen);

/* Read a PNG as 8-bit RGB (malloc'd, rows packed; free() it). Returns VFP_OK, or VFP_ERR with err. */
vfp_status_t vfp_png_read_rgb(const char *path, uint8_t **rgb, uint32_t *width, uint32_t *height, char *err,
                              size_t errlen);

/* Expand any core format to 8-bit RGB (RGB565 channels scaled to 0..255 with rounding). */
void vfp_image_to_rgb(const vf_image_t *image, uint8_t *rgb);

#endif
