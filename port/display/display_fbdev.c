/* SPDX-License-Identifier: MIT */
/*
 * display_fbdev.c: a Linux framebuffer device (/dev/fbN; the board's display.device, default /dev/fb0), as
 * older SPI panel overlays (fbtft) provide. The visible resolution is the display's size; the framebuffer must
 * be 16 bpp RGB565 or 32 bpp XRGB8888 (checked bit field by bit field), and it is written through mmap, row by
 * row, since a row of the framebuffer (line_length) may be longer than the visible width.
 *
 * Seams for tests (the kernel's fb ioctls cannot be made on a regular file; declared in display_backends.h):
 * vfp_fbdev_open_fd() opens from a descriptor, vfp_fbdev_check() is the pure format check, and vfp_fbdev_attach()
 * builds the display over screen information and memory the caller supplies.
 */

/*********************
 *      INCLUDES
 *********************/
#include "display.h"
#include "display_backends.h"

#include <errno.h>
#include <fcntl.h>
#include <linux/fb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

/*********************
 *      DEFINES
 *********************/
#define DEFAULT_DEVICE "/dev/fb0"

/**********************
 *      TYPES
 **********************/
typedef struct fbdev {
    char name[VFP_PATH_LEN]; /* for messages */
    int fd;                  /* -1 when attached to the caller's memory */
    uint8_t *map;            /* the framebuffer memory */
    size_t map_len;
    int mapped;              /* map came from mmap (unmap it on close) */
    uint8_t *origin;         /* the visible area's first pixel (the pan offsets applied) */
    uint32_t line_length;    /* bytes from one framebuffer row to the next */
    uint32_t bytes;          /* per pixel */
} fbdev_t;

/**********************
 *  STATIC PROTOTYPES
 **********************/
static vfp_status_t fbdev_open(vfp_display_t *d, const vfp_board_t *board, char *err, size_t errlen);
static vfp_status_t fbdev_present(vfp_display_t *d, uint32_t x, uint32_t y, uint32_t w, uint32_t h, const void *pixels,
                                  uint32_t stride, char *err, size_t errlen);
static void fbdev_close(vfp_display_t *d);
static int field_is(const struct fb_bitfield *f, uint32_t offset, uint32_t length);

/**********************
 *  GLOBAL VARIABLES
 **********************/
const vfp_display_ops_t vfp_display_fbdev_ops = {"fbdev", fbdev_open, fbdev_present, fbdev_close};

/**********************
 *   GLOBAL FUNCTIONS
 **********************/
/* Takes fd (closed on failure too): reads the screen information, checks the format, maps the memory. */
vfp_status_t vfp_fbdev_open_fd(vfp_display_t *d, int fd, const char *name, char *err, size_t errlen)
{
    struct fb_var_screeninfo var;
    struct fb_fix_screeninfo fix;
    void *map = MAP_FAILED;
    d->priv = NULL;
    if (ioctl(fd, FBIOGET_VSCREENINFO, &var) != 0 || ioctl(fd, FBIOGET_FSCREENINFO, &fix) != 0) {
        snprintf(err, errlen, "%s: not a framebuffer device (FBIOGET_VSCREENINFO: %s)", name, strerror(errno));
        goto fail;
    }
    vf_format_t format;
    if (vfp_fbdev_check(&var, &fix, name, &format, err, errlen))
        goto fail;
    map = mmap(NULL, fix.smem_len, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    if (map == MAP_FAILED) {
        snprintf(err, errlen, "%s: cannot map %u bytes of framebuffer memory: %s", name, fix.smem_len,
                 strerror(errno));
        goto fail;
    }
    if (vfp_fbdev_attach(d, &var, &fix, map, fix.smem_len, name, err, errlen))
        goto fail;
    fbdev_t *fb = d->priv;
    fb->fd = fd;
    fb->mapped = 1;
    return VFP_OK;

fail:
    if (map != MAP_FAILED)
        munmap(map, fix.smem_len);
    close(fd);
    return VFP_ERR;
}

/* RGB565 or XRGB8888 in packed pixels, or VFP_ERR with a message naming the device and what it found. */
vfp_status_t vfp_fbdev_check(const struct fb_var_screeninfo *var, const struct fb_fix_screeninfo *fix, const char *name,
                             vf_format_t *format, char *err, size_t errlen)
{
    if (fix->type != FB_TYPE_PACKED_PIXELS || (fix->visual != FB_VISUAL_TRUECOLOR &&
                                               fix->visual != FB_VISUAL_DIRECTCOLOR)) {
        snprintf(err, errlen, "%s: unsupported framebuffer: type %u, visual %u (expected packed pixels in true "
                 "colour)", name, fix->type, fix->visual);
        return VFP_ERR;
    }
    if (var->bits_per_pixel == 16 && var->grayscale == 0 && field_is(&var->red, 11, 5) &&
        field_is(&var->green, 5, 6) && field_is(&var->blue, 0, 5)) {
        *format = VF_FORMAT_RGB565;
        return VFP_OK;
    }
    if (var->bits_per_pixel == 32 && var->grayscale == 0 && field_is(&var->red, 16, 8) &&
        field_is(&var->green, 8, 8) && field_is(&var->blue, 0, 8)) {
        *format = VF_FORMAT_XRGB8888;
        return VFP_OK;
    }
    snprintf(err, errlen, "%s: unsupported pixel format: %u bpp, red %u/%u, green %u/%u, blue %u/%u%s (expected 16 "
             "bpp RGB565 or 32 bpp XRGB8888)", name, var->bits_per_pixel, var->red.offset, var->red.length,
             var->green.offset, var->green.length, var->blue.offset, var->blue.length,
             var->grayscale ? ", greyscale" : "");
    return VFP_ERR;
}

/* The display over memory the caller maps (and keeps): checks the format and that the visible area fits. */
vfp_status_t vfp_fbdev_attach(vfp_display_t *d, const struct fb_var_screeninfo *var,
                              const struct fb_fix_screeninfo *fix, void *mem, size_t mem_len, const char *name,
                              char *err, size_t errlen)
{
    vf_format_t format;
    d->priv = NULL;
    if (vfp_fbdev_check(var, fix, name, &format, err, errlen))
        return VFP_ERR;
    uint32_t bytes = var->bits_per_pixel / 8;
    if (var->xres == 0 || var->yres == 0 || fix->line_length < (uint64_t)(var->xoffset + var->xres) * bytes ||
        (uint64_t)fix->line_length * (var->yoffset + var->yres) > mem_len) {
        snprintf(err, errlen, "%s: inconsistent framebuffer: %ux%u visible at (%u,%u), %u bytes a line, %zu bytes "
                 "of memory", name, var->xres, var->yres, var->xoffset, var->yoffset, fix->line_length, mem_len);
        return VFP_ERR;
    }
    fbdev_t *fb = calloc(1, sizeof *fb);
    if (!fb) {
        snprintf(err, errlen, "%s: out of memory", name);
        return VFP_ERR;
    }
    snprintf(fb->name, sizeof fb->name, "%s", name);
    fb->fd = -1;
    fb->map = mem;
    fb->map_len = mem_len;
    fb->line_length = fix->line_length;
    fb->bytes = bytes;
    fb->origin = fb->map + (size_t)var->yoffset * fix->line_length + (size_t)var->xoffset * bytes;
    d->priv = fb;
    d->width = var->xres;
    d->height = var->yres;
    d->format = format;
    return VFP_OK;
}

/**********************
 *   STATIC FUNCTIONS
 **********************/
static vfp_status_t fbdev_open(vfp_display_t *d, const vfp_board_t *board, char *err, size_t errlen)
{
    const char *path = board->display_device[0] ? board->display_device : DEFAULT_DEVICE;
    d->priv = NULL;
    int fd = open(path, O_RDWR | O_CLOEXEC);
    if (fd < 0) {
        snprintf(err, errlen, "%s: cannot open: %s%s", path, strerror(errno),
                 errno == EACCES ? " (is the user in the video group?)" : "");
        return VFP_ERR;
    }
    return vfp_fbdev_open_fd(d, fd, path, err, errlen);
}

static vfp_status_t fbdev_present(vfp_display_t *d, uint32_t x, uint32_t y, uint32_t w, uint32_t h, const void *pixels,
                                  uint32_t stride, char *err, size_t errlen)
{
    fbdev_t *fb = d->priv;
    if (vfp_display_check_present(d, fb ? fb->name : NULL, x, y, w, h, stride, err, errlen))
        return VFP_ERR;
    size_t offset = (size_t)x * fb->bytes, row_bytes = (size_t)w * fb->bytes;
    for (uint32_t row = y; row < y + h; row++)
        memcpy(fb->origin + (size_t)row * fb->line_length + offset,
               (const uint8_t *)pixels + (size_t)row * stride + offset, row_bytes);
    return VFP_OK;
}

static void fbdev_close(vfp_display_t *d)
{
    fbdev_t *fb = d->priv;
    if (fb) {
        if (fb->mapped)
            munmap(fb->map, fb->map_len);
        if (fb->fd >= 0)
            close(fb->fd);
        free(fb);
    }
    d->priv = NULL;
}

static int field_is(const struct fb_bitfield *f, uint32_t offset, uint32_t length)
{
    return f->offset == offset && f->length == length && f->msb_right == 0;
}
