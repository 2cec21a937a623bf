/* SPDX-License-Identifier: MIT */
/*
 * display_none.c: a display that shows nothing: every frame is rendered and dropped. For the long-run test
 * (10,000 frames without 10,000 files) and for timing the viewer without a display's cost. The board gives the
 * size and format as for png (display.width, display.height, display.format).
 */
#include "display.h"

static vfp_status_t none_open(vfp_display_t *d, const vfp_board_t *board, char *err, size_t errlen)
{
    (void)err;
    (void)errlen;
    d->width = board->width;
    d->height = board->height;
    d->format = board->format;
    d->priv = NULL;
    return VFP_OK;
}

static vfp_status_t none_present(vfp_display_t *d, uint32_t x, uint32_t y, uint32_t w, uint32_t h, const void *pixels,
                                 uint32_t stride, char *err, size_t errlen)
{
    (void)pixels;
    return vfp_display_check_rect(d, "none display", x, y, w, h, stride, err, errlen);
}

static void none_close(vfp_display_t *d)
{
    (void)d;
}

const vfp_display_ops_t vfp_display_none_ops = {"none", none_open, none_present, none_close};
