/* SPDX-License-Identifier: MIT */
/*
 * warp_rows.h: the warp's loops over a row (warp_rows.c), for warp.c, which works out each row's spans.
 */
#ifndef VF_WARP_ROWS_H
#define VF_WARP_ROWS_H

#include "renderer.h"

#define VFI_ONE_Q32 (INT64_C(1) << 32)

/* What a band's rows share: the renderer, the format and the background. */
typedef struct vfi_warp_row {
    const vf_renderer_t *r;
    uint32_t fraction_mask; /* the warp's fraction bits kept (precision studies: fewer than 16) */
    uint32_t bg[3];         /* background, Q1.15 */
    bool have_bg;
    bool grey;              /* every intermediate pixel's r = g = b (a grey transfer function: renderer.h's tf_grey) */
    vf_format_t format;
} vfi_warp_row_t;

/* count pixels from dst whose four neighbours are all inside the intermediate image img (iw pixels a row), the
 * first at (u, v) in Q32.32, then a step of (du, dv) a pixel. */
void vfi_warp_inner(const vfi_warp_row_t *w, const uint16_t *img, int64_t iw, int64_t u, int64_t v, int64_t du,
                    int64_t dv, unsigned char *dst, uint32_t count, const unsigned char *background);

/* One pixel at (u, v) in Q32.32 whose neighbours may lie outside the intermediate image (transparent there). */
void vfi_warp_edge(const vfi_warp_row_t *w, int64_t u_q32, int64_t v_q32, unsigned char *dst);

/* count pixels of background (the format's bytes) from dst. */
void vfi_warp_fill(unsigned char *dst, uint32_t count, const unsigned char *background, vf_format_t format);

/* The background alone (a transparent pixel over it) as the format's bytes. */
void vfi_warp_background(const vfi_warp_row_t *w, unsigned char *dst);

#endif
