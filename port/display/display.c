/* SPDX-License-Identifier: MIT */
/* display.c: the display backends compiled into this build, and finding the one a board names (see display.h). */

/*********************
 *      INCLUDES
 *********************/
#include "display.h"
#include "display_backends.h" /* each backend's table, defined in its own file when its library is there */

#include <stdio.h>
#include <string.h>

/*********************
 *      DEFINES
 *********************/
#define KNOWN_DISPLAYS "drm, fbdev, gud, sdl, png or none"

/**********************
 *      TYPES
 **********************/
/* Every backend the source knows, and the package that brings its library when it is not compiled in. */
typedef struct known_display {
    const char *name;
    const char *package; /* NULL: always compiled in */
} known_display_t;

/**********************
 *  STATIC PROTOTYPES
 **********************/
static vfp_status_t message(char *err, size_t errlen, const vfp_board_t *board, const char *fmt, const char *name,
                            const char *extra);

/**********************
 *  STATIC VARIABLES
 **********************/
static const known_display_t known[] = {
    {"drm", "libdrm-dev"},
    {"fbdev", NULL},
    {"gud", "libusb-1.0-0-dev"},
    {"sdl", "libsdl2-dev"},
    {"png", NULL},
    {"none", NULL},
};

/**********************
 *   GLOBAL FUNCTIONS
 **********************/
const vfp_display_ops_t *const vfp_displays[] = {
#ifdef VFP_HAVE_DRM
    &vfp_display_drm_ops,
#endif
    &vfp_display_fbdev_ops,
#ifdef VFP_HAVE_GUD
    &vfp_display_gud_ops,
#endif
#ifdef VFP_HAVE_SDL
    &vfp_display_sdl_ops,
#endif
    &vfp_display_png_ops,
    &vfp_display_none_ops,
    NULL,
};

const vfp_display_ops_t *vfp_display_find(const char *name, const vfp_board_t *board, char *err, size_t errlen)
{
    if (!name || !name[0]) {
        message(err, errlen, board, "no display given (expected %s)", KNOWN_DISPLAYS, NULL);
        return NULL;
    }
    for (int i = 0; vfp_displays[i]; i++)
        if (strcmp(vfp_displays[i]->name, name) == 0)
            return vfp_displays[i];
    for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
        if (strcmp(known[i].name, name) == 0) {
            message(err, errlen, board, "display '%s' is not compiled in: install %s and rebuild", name,
                    known[i].package);
            return NULL;
        }
    message(err, errlen, board, "unknown display '%s' (expected %s)", name, KNOWN_DISPLAYS);
    return NULL;
}

/**********************
 *   STATIC FUNCTIONS
 **********************/
/* "FILE: " + fmt, where fmt takes one or two strings. */
static vfp_status_t message(char *err, size_t errlen, const vfp_board_t *board, const char *fmt, const char *name,
                            const char *extra)
{
    if (!err || !errlen)
        return VFP_ERR;
    size_t n = 0;
    if (board && board->path[0]) {
        int k = snprintf(err, errlen, "%s: ", board->path);
        n = k < 0 ? 0 : (size_t)k < errlen ? (size_t)k : errlen - 1;
    }
    snprintf(err + n, errlen - n, fmt, name, extra);
    return VFP_ERR;
}

vfp_status_t vfp_display_check_rect(const vfp_display_t *d, const char *name, uint32_t x, uint32_t y, uint32_t w,
                                    uint32_t h, uint32_t stride, char *err, size_t errlen)
{
    uint64_t row_bytes = ((uint64_t)x + w) * vf_format_bytes(d->format);
    if (x > d->width || y > d->height || w > d->width - x || h > d->height - y || stride < row_bytes) {
        snprintf(err, errlen, "%s: rectangle %ux%u at (%u,%u) with stride %u does not fit the %ux%u display", name, w,
                 h, x, y, stride, d->width, d->height);
        return VFP_ERR;
    }
    return VFP_OK;
}

vfp_status_t vfp_display_check_present(const vfp_display_t *d, const char *name, uint32_t x, uint32_t y, uint32_t w,
                                       uint32_t h, uint32_t stride, char *err, size_t errlen)
{
    if (!d->priv) {
        snprintf(err, errlen, "%s display: present on a display that is not open", d->ops->name);
        return VFP_ERR;
    }
    return vfp_display_check_rect(d, name, x, y, w, h, stride, err, errlen);
}
