/* SPDX-License-Identifier: MIT */
/*
 * overlay.h: a line of text drawn into an image (the viewer's frame-time overlay): a built-in 5x7 font of
 * digits, capital letters and a little punctuation (lower case is drawn as capitals), white on a dark box,
 * scaled up for bigger displays, and turned with the panel's mounting so that it reads upright.
 */
#ifndef VFP_OVERLAY_H
#define VFP_OVERLAY_H

#include "volfix.h"

/* Draw `text` with its top-left corner at (x, y) of the upright picture, `scale` pixels per font pixel. The
 * image is the panel's own buffer, mounted `rotation` degrees clockwise (0, 90, 180, 270). Whatever falls
 * outside the image is clipped. */
void vfp_overlay_text(const vf_image_t *image, int rotation, int x, int y, int scale, const char *text);

/* The upright picture's size in pixels of the text, for placing it. */
int vfp_overlay_width(const char *text, int scale);
int vfp_overlay_height(int scale);

/* The patient directions of the upright picture's edges (vfp_view_edges' letters, "L", "LA"), each at the middle
 * of its edge; an empty or NULL text draws nothing there. */
void vfp_overlay_directions(const vf_image_t *image, int rotation, int scale, const char *right, const char *left,
                            const char *top, const char *bottom);

#endif
