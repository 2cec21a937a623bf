/* SPDX-License-Identifier: MIT */
/*
 * display.h: a display is a small table of operations (as LVGL's display drivers): open it, present a rectangle
 * of pixels, close it. Each backend lives in its own file (display_drm.c, display_fbdev.c, display_gud.c,
 * display_sdl.c, display_png.c) and is compiled in when its library is present (the Makefile defines
 * VFP_HAVE_DRM, VFP_HAVE_GUD, VFP_HAVE_SDL; fbdev and png need nothing extra).
 *
 * Contract for a backend:
 * - open() fills width, height and format (the mode it got) and priv, or returns VFP_ERR with a one-line message
 *   naming the device ("/dev/dri/card1: no connected connector") and leaves nothing open.
 * - present() shows the rectangle (x, y, w, h) of `pixels` (rows `stride` bytes apart, in `format`) at (x, y),
 *   and is done with the pointer when it returns. It returns VFP_OK, VFP_ERR with err for a failure, or
 *   VFP_DISPLAY_LOST when the device went away (an unplugged USB display): the caller closes it and tries open()
 *   again later.
 * - close() gives everything back (a DRM backend restores the CRTC it found); it is safe after a failed or
 *   lost present, and on a display that never opened.
 */
#ifndef VFP_DISPLAY_H
#define VFP_DISPLAY_H

#include <stddef.h>
#include <stdint.h>

#include "board/board.h"
#include "status.h"
#include "volfix.h"

typedef struct vfp_display vfp_display_t;

typedef struct vfp_display_ops {
    const char *name; /* the board's display = NAME */
    vfp_status_t (*open)(vfp_display_t *d, const vfp_board_t *board, char *err, size_t errlen);
    vfp_status_t (*present)(vfp_display_t *d, uint32_t x, uint32_t y, uint32_t w, uint32_t h, const void *pixels,
                            uint32_t stride, char *err, size_t errlen);
    void (*close)(vfp_display_t *d);
} vfp_display_ops_t;

struct vfp_display {
    const vfp_display_ops_t *ops;
    uint32_t width, height; /* set by open */
    vf_format_t format;     /* set by open */
    void *priv;             /* the backend's own state */
};

/* The backend a board names, or NULL with err ("boards/x.board: display 'drm' is not compiled in: install
 * libdrm-dev and rebuild"). */
const vfp_display_ops_t *vfp_display_find(const char *name, const vfp_board_t *board, char *err, size_t errlen);

/* For backends: VFP_OK when the rectangle (x, y, w, h) lies inside the display and rows `stride` bytes apart hold
 * x + w pixels of its format; else VFP_ERR with "NAME: rectangle WxH at (X,Y) with stride S does not fit the WxH
 * display" in err. */
vfp_status_t vfp_display_check_rect(const vfp_display_t *d, const char *name, uint32_t x, uint32_t y, uint32_t w,
                                    uint32_t h, uint32_t stride, char *err, size_t errlen);

/* For backends, what present() checks first: that the display is open (d->priv set; else VFP_ERR with "OPS
 * display: present on a display that is not open", OPS the backend's name) and vfp_display_check_rect. name is
 * the backend's name for the device, NULL when d->priv is. */
vfp_status_t vfp_display_check_present(const vfp_display_t *d, const char *name, uint32_t x, uint32_t y, uint32_t w,
                                       uint32_t h, uint32_t stride, char *err, size_t errlen);

/* The backends compiled in, NULL-terminated. */
extern const vfp_display_ops_t *const vfp_displays[];

#endif
