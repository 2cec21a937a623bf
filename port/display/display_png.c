/* SPDX-License-Identifier: MIT */
/*
 * display_png.c: a display that writes every presented frame to DIR/frame-NNNNN.png (numbered from 0), for the
 * headless board and the viewer's end-to-end test, which compares the frames with volfix-sim render.
 *
 * The board gives the directory (display.device, default out/frames, created if missing), the size and the
 * format (any core format; the PNG is 8-bit RGB). A presented rectangle updates a kept copy of the whole frame,
 * and the whole frame is written.
 */

/*********************
 *      INCLUDES
 *********************/
#include "display.h"
#include "display_backends.h"
#include "io/pngio.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/*********************
 *      DEFINES
 *********************/
#define DEFAULT_DIR "out/frames"

/**********************
 *      TYPES
 **********************/
typedef struct png_display {
    char dir[VFP_PATH_LEN];
    uint8_t *frame;  /* the whole frame in the display's format, rows width * bytes apart */
    uint8_t *rgb;    /* the frame expanded for libpng */
    uint32_t stride;
    unsigned next;   /* the number of the next frame file */
} png_display_t;

/**********************
 *  STATIC PROTOTYPES
 **********************/
static vfp_status_t png_open(vfp_display_t *d, const vfp_board_t *board, char *err, size_t errlen);
static vfp_status_t png_present(vfp_display_t *d, uint32_t x, uint32_t y, uint32_t w, uint32_t h, const void *pixels,
                                uint32_t stride, char *err, size_t errlen);
static void png_close(vfp_display_t *d);
static vfp_status_t make_dirs(const char *dir, char *err, size_t errlen);

/**********************
 *  GLOBAL VARIABLES
 **********************/
const vfp_display_ops_t vfp_display_png_ops = {"png", png_open, png_present, png_close};

/**********************
 *   STATIC FUNCTIONS
 **********************/
static vfp_status_t png_open(vfp_display_t *d, const vfp_board_t *board, char *err, size_t errlen)
{
    d->priv = NULL;
    const char *dir = board->display_device[0] ? board->display_device : DEFAULT_DIR;
    uint32_t bytes = vf_format_bytes(board->format);
    if (board->width == 0 || board->height == 0 || board->width > VF_MAX_IMAGE || board->height > VF_MAX_IMAGE) {
        snprintf(err, errlen, "%s: display 'png' needs a size from 1x1 to %dx%d (the board gives %ux%u)", dir,
                 VF_MAX_IMAGE, VF_MAX_IMAGE, board->width, board->height);
        return VFP_ERR;
    }
    if (bytes == 0) {
        snprintf(err, errlen, "%s: unknown pixel format %d", dir, (int)board->format);
        return VFP_ERR;
    }
    if (strlen(dir) >= VFP_PATH_LEN - 16) {
        snprintf(err, errlen, "%s: directory name too long", dir);
        return VFP_ERR;
    }
    if (make_dirs(dir, err, errlen))
        return VFP_ERR;

    png_display_t *p = calloc(1, sizeof *p);
    if (!p)
        goto nomem;
    snprintf(p->dir, sizeof p->dir, "%s", dir);
    p->stride = board->width * bytes;
    p->frame = calloc((size_t)p->stride, board->height);
    if (!p->frame)
        goto nomem;
    p->rgb = malloc((size_t)board->width * board->height * 3);
    if (!p->rgb)
        goto nomem;
    d->priv = p;
    d->width = board->width;
    d->height = board->height;
    d->format = board->format;
    return VFP_OK;

nomem:
    if (p)
        free(p->frame);
    free(p);
    snprintf(err, errlen, "%s: out of memory for a %ux%u frame", dir, board->width, board->height);
    return VFP_ERR;
}

static vfp_status_t png_present(vfp_display_t *d, uint32_t x, uint32_t y, uint32_t w, uint32_t h, const void *pixels,
                                uint32_t stride, char *err, size_t errlen)
{
    png_display_t *p = d->priv;
    uint32_t bytes = vf_format_bytes(d->format);
    if (vfp_display_check_present(d, p ? p->dir : NULL, x, y, w, h, stride, err, errlen))
        return VFP_ERR;
    for (uint32_t row = y; row < y + h; row++)
        memcpy(p->frame + (size_t)row * p->stride + (size_t)x * bytes,
               (const uint8_t *)pixels + (size_t)row * stride + (size_t)x * bytes, (size_t)w * bytes);

    vf_image_t image = {p->frame, d->width, d->height, p->stride, d->format};
    vfp_image_to_rgb(&image, p->rgb);
    char path[VFP_PATH_LEN + 32];
    snprintf(path, sizeof path, "%s/frame-%05u.png", p->dir, p->next);
    if (vfp_png_write_rgb(path, p->rgb, d->width, d->height, err, errlen))
        return VFP_ERR;
    p->next++;
    return VFP_OK;
}

static void png_close(vfp_display_t *d)
{
    png_display_t *p = d->priv;
    if (p) {
        free(p->rgb);
        free(p->frame);
        free(p);
    }
    d->priv = NULL;
}

/* mkdir -p: each missing component in turn. */
static vfp_status_t make_dirs(const char *dir, char *err, size_t errlen)
{
    char path[VFP_PATH_LEN];
    snprintf(path, sizeof path, "%s", dir);
    for (char *slash = path + 1;; slash++) {
        if (*slash != '/' && *slash != 0)
            continue;
        char saved = *slash;
        *slash = 0;
        if (mkdir(path, 0777) != 0 && errno != EEXIST) {
            snprintf(err, errlen, "%s: cannot create directory: %s", path, strerror(errno));
            return VFP_ERR;
        }
        *slash = saved;
        if (!saved)
            break;
    }
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        snprintf(err, errlen, "%s: not a directory", dir);
        return VFP_ERR;
    }
    if (access(dir, W_OK) != 0) {
        snprintf(err, errlen, "%s: cannot write frames there: %s", dir, strerror(errno));
        return VFP_ERR;
    }
    return VFP_OK;
}
