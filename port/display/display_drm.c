/* SPDX-License-Identifier: MIT */
/*
 * display_drm.c: Linux DRM/KMS with a dumb buffer: the default on current Raspberry Pi OS (vc4), and also SPI
 * panels through panel-mipi-dbi and USB displays through the kernel's gud driver. Those last two only send what
 * DirtyFB names, so every present ends with DirtyFB over its rectangle (drivers without it say ENOSYS).
 *
 * Open: the board's display.device (default: the first /dev/dri/cardN with a connected connector), master if
 * not already, the first connected connector with its preferred mode, a CRTC its encoders can drive, a dumb
 * buffer in RGB565 (board format rgb565) or XRGB8888 (otherwise), then SetCrtc. The CRTC found at open is
 * restored at close, so the console (or whatever was there) comes back.
 */
#ifdef VFP_HAVE_DRM

/*********************
 *      INCLUDES
 *********************/
#include "display.h"
#include "display_backends.h"

#include <drm_fourcc.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

/*********************
 *      DEFINES
 *********************/
#define MAX_CARDS 16

/**********************
 *      TYPES
 **********************/
typedef struct drm_display {
    char path[VFP_PATH_LEN];
    int fd;
    int became_master;      /* drmSetMaster was ours to undo */
    uint32_t connector_id, crtc_id;
    drmModeModeInfo mode;
    uint32_t handle;        /* the dumb buffer (0: none) */
    uint32_t pitch, bytes;  /* bytes a row, and a pixel */
    uint64_t size;
    uint8_t *map;           /* NULL: not mapped */
    uint32_t fb_id;         /* 0: none */
    drmModeCrtc *saved;     /* the CRTC as found, restored on close */
    int crtc_set;
} drm_display_t;

/**********************
 *  STATIC PROTOTYPES
 **********************/
static vfp_status_t drm_open(vfp_display_t *d, const vfp_board_t *board, char *err, size_t errlen);
static vfp_status_t drm_present(vfp_display_t *d, uint32_t x, uint32_t y, uint32_t w, uint32_t h, const void *pixels,
                                uint32_t stride, char *err, size_t errlen);
static void drm_close(vfp_display_t *d);
static vfp_status_t open_card(vfp_display_t *d, const char *path, vf_format_t format, char *err, size_t errlen);
static vfp_status_t find_output(drm_display_t *m, drmModeRes *res, char *err, size_t errlen);
static uint32_t find_crtc(int fd, drmModeRes *res, drmModeConnector *conn);
static vfp_status_t create_buffer(drm_display_t *m, vf_format_t format, char *err, size_t errlen);
static void destroy(drm_display_t *m);

/**********************
 *  GLOBAL VARIABLES
 **********************/
const vfp_display_ops_t vfp_display_drm_ops = {"drm", drm_open, drm_present, drm_close};

/**********************
 *   STATIC FUNCTIONS
 **********************/
static vfp_status_t drm_open(vfp_display_t *d, const vfp_board_t *board, char *err, size_t errlen)
{
    d->priv = NULL;
    vf_format_t format = board->format == VF_FORMAT_RGB565 ? VF_FORMAT_RGB565 : VF_FORMAT_XRGB8888;
    if (board->display_device[0])
        return open_card(d, board->display_device, format, err, errlen);

    /* The first card that can show something: on a Raspberry Pi 4 card0 may be the render-only v3d. */
    char first_reason[256] = "";
    for (int i = 0; i < MAX_CARDS; i++) {
        char path[32];
        snprintf(path, sizeof path, "/dev/dri/card%d", i);
        if (access(path, F_OK) != 0)
            continue;
        if (open_card(d, path, format, err, errlen) == 0)
            return VFP_OK;
        if (!first_reason[0])
            snprintf(first_reason, sizeof first_reason, "%s", err);
    }
    if (first_reason[0])
        snprintf(err, errlen, "no DRM card with a connected display (%s)", first_reason);
    else
        snprintf(err, errlen, "no DRM card found (/dev/dri/card0 to card%d): is the KMS driver loaded?",
                 MAX_CARDS - 1);
    return VFP_ERR;
}

static vfp_status_t drm_present(vfp_display_t *d, uint32_t x, uint32_t y, uint32_t w, uint32_t h, const void *pixels,
                                uint32_t stride, char *err, size_t errlen)
{
    drm_display_t *m = d->priv;
    if (vfp_display_check_present(d, m ? m->path : NULL, x, y, w, h, stride, err, errlen))
        return VFP_ERR;
    if (w == 0 || h == 0)
        return VFP_OK;
    size_t offset = (size_t)x * m->bytes, row_bytes = (size_t)w * m->bytes;
    for (uint32_t row = y; row < y + h; row++)
        memcpy(m->map + (size_t)row * m->pitch + offset, (const uint8_t *)pixels + (size_t)row * stride + offset,
               row_bytes);
    drmModeClip clip = {(unsigned short)x, (unsigned short)y, (unsigned short)(x + w), (unsigned short)(y + h)};
    int ret = drmModeDirtyFB(m->fd, m->fb_id, &clip, 1);
    if (ret == 0 || ret == -ENOSYS)
        return VFP_OK;
    snprintf(err, errlen, "%s: DirtyFB failed: %s", m->path, strerror(-ret));
    /* A USB display (the gud driver) that was unplugged answers ENODEV from now on. */
    return ret == -ENODEV ? VFP_DISPLAY_LOST : VFP_ERR;
}

static void drm_close(vfp_display_t *d)
{
    if (d->priv)
        destroy(d->priv);
    d->priv = NULL;
}

/* Everything from the open to SetCrtc on one card; on failure nothing stays open. */
static vfp_status_t open_card(vfp_display_t *d, const char *path, vf_format_t format, char *err, size_t errlen)
{
    drmModeRes *res = NULL;
    drm_display_t *m = calloc(1, sizeof *m);
    if (!m) {
        snprintf(err, errlen, "%s: out of memory", path);
        return VFP_ERR;
    }
    snprintf(m->path, sizeof m->path, "%s", path);
    m->fd = open(path, O_RDWR | O_CLOEXEC);
    if (m->fd < 0) {
        snprintf(err, errlen, "%s: cannot open: %s%s", path, strerror(errno),
                 errno == EACCES ? " (is the user in the video group?)" : "");
        goto fail;
    }
    res = drmModeGetResources(m->fd);
    if (!res) {
        snprintf(err, errlen, "%s: not a mode-setting device (%s)", path, strerror(errno));
        goto fail;
    }
    if (find_output(m, res, err, errlen))
        goto fail;
    if (!drmIsMaster(m->fd)) {
        if (drmSetMaster(m->fd) != 0) {
            snprintf(err, errlen, "%s: cannot become DRM master: %s (is a desktop or another program using the "
                     "display?)", path, strerror(errno));
            goto fail;
        }
        m->became_master = 1;
    }
    if (create_buffer(m, format, err, errlen))
        goto fail;
    m->saved = drmModeGetCrtc(m->fd, m->crtc_id);
    if (drmModeSetCrtc(m->fd, m->crtc_id, m->fb_id, 0, 0, &m->connector_id, 1, &m->mode) != 0) {
        snprintf(err, errlen, "%s: cannot set mode %s: %s", path, m->mode.name, strerror(errno));
        goto fail;
    }
    m->crtc_set = 1;
    drmModeFreeResources(res);
    d->priv = m;
    d->width = m->mode.hdisplay;
    d->height = m->mode.vdisplay;
    d->format = format;
    return VFP_OK;

fail:
    if (res)
        drmModeFreeResources(res);
    destroy(m);
    return VFP_ERR;
}

/* The first connected connector with modes, its preferred mode (else the first) and a CRTC for it. */
static vfp_status_t find_output(drm_display_t *m, drmModeRes *res, char *err, size_t errlen)
{
    int connected = 0;
    for (int i = 0; i < res->count_connectors; i++) {
        drmModeConnector *conn = drmModeGetConnector(m->fd, res->connectors[i]);
        if (!conn)
            continue;
        if (conn->connection != DRM_MODE_CONNECTED || conn->count_modes == 0) {
            drmModeFreeConnector(conn);
            continue;
        }
        connected++;
        uint32_t crtc = find_crtc(m->fd, res, conn);
        if (crtc) {
            m->connector_id = conn->connector_id;
            m->crtc_id = crtc;
            m->mode = conn->modes[0];
            for (int k = 0; k < conn->count_modes; k++)
                if (conn->modes[k].type & DRM_MODE_TYPE_PREFERRED) {
                    m->mode = conn->modes[k];
                    break;
                }
            drmModeFreeConnector(conn);
            return VFP_OK;
        }
        drmModeFreeConnector(conn);
    }
    if (connected)
        snprintf(err, errlen, "%s: no CRTC can drive the connected connector", m->path);
    else
        snprintf(err, errlen, "%s: no connected connector", m->path);
    return VFP_ERR;
}

/* The CRTC the connector's encoder already drives, else the first one any of its encoders can. */
static uint32_t find_crtc(int fd, drmModeRes *res, drmModeConnector *conn)
{
    if (conn->encoder_id) {
        drmModeEncoder *enc = drmModeGetEncoder(fd, conn->encoder_id);
        uint32_t crtc = enc ? enc->crtc_id : 0;
        drmModeFreeEncoder(enc);
        if (crtc)
            return crtc;
    }
    for (int e = 0; e < conn->count_encoders; e++) {
        drmModeEncoder *enc = drmModeGetEncoder(fd, conn->encoders[e]);
        if (!enc)
            continue;
        for (int c = 0; c < res->count_crtcs && c < 32; c++)
            if (enc->possible_crtcs & (1u << c)) {
                drmModeFreeEncoder(enc);
                return res->crtcs[c];
            }
        drmModeFreeEncoder(enc);
    }
    return 0;
}

/* A dumb buffer of the mode's size, a framebuffer over it, and its memory mapped and cleared to black. */
static vfp_status_t create_buffer(drm_display_t *m, vf_format_t format, char *err, size_t errlen)
{
    uint32_t w = m->mode.hdisplay, h = m->mode.vdisplay;
    struct drm_mode_create_dumb create = {.width = w, .height = h, .bpp = format == VF_FORMAT_RGB565 ? 16 : 32};
    if (drmIoctl(m->fd, DRM_IOCTL_MODE_CREATE_DUMB, &create) != 0) {
        snprintf(err, errlen, "%s: cannot create a %ux%u dumb buffer: %s", m->path, w, h, strerror(errno));
        return VFP_ERR;
    }
    m->handle = create.handle;
    m->pitch = create.pitch;
    m->size = create.size;
    m->bytes = create.bpp / 8;
    uint32_t handles[4] = {m->handle}, pitches[4] = {m->pitch}, offsets[4] = {0};
    uint32_t fourcc = format == VF_FORMAT_RGB565 ? DRM_FORMAT_RGB565 : DRM_FORMAT_XRGB8888;
    if (drmModeAddFB2(m->fd, w, h, fourcc, handles, pitches, offsets, &m->fb_id, 0) != 0) {
        m->fb_id = 0;
        snprintf(err, errlen, "%s: cannot add a %s framebuffer: %s", m->path,
                 format == VF_FORMAT_RGB565 ? "RGB565" : "XRGB8888", strerror(errno));
        return VFP_ERR;
    }
    struct drm_mode_map_dumb map = {.handle = m->handle};
    if (drmIoctl(m->fd, DRM_IOCTL_MODE_MAP_DUMB, &map) != 0) {
        snprintf(err, errlen, "%s: cannot map the dumb buffer: %s", m->path, strerror(errno));
        return VFP_ERR;
    }
    void *p = mmap(NULL, m->size, PROT_READ | PROT_WRITE, MAP_SHARED, m->fd, (off_t)map.offset);
    if (p == MAP_FAILED) {
        snprintf(err, errlen, "%s: cannot map the dumb buffer: %s", m->path, strerror(errno));
        return VFP_ERR;
    }
    m->map = p;
    memset(m->map, 0, m->size);
    return VFP_OK;
}

/* Gives back whatever m holds, in the reverse order of open_card. */
static void destroy(drm_display_t *m)
{
    if (m->crtc_set) {
        drmModeCrtc *s = m->saved;
        if (s && s->mode_valid)
            drmModeSetCrtc(m->fd, s->crtc_id, s->buffer_id, s->x, s->y, &m->connector_id, 1, &s->mode);
        else
            drmModeSetCrtc(m->fd, m->crtc_id, 0, 0, 0, NULL, 0, NULL);
    }
    if (m->saved)
        drmModeFreeCrtc(m->saved);
    if (m->map)
        munmap(m->map, m->size);
    if (m->fb_id)
        drmModeRmFB(m->fd, m->fb_id);
    if (m->handle) {
        struct drm_mode_destroy_dumb destroy_req = {.handle = m->handle};
        drmIoctl(m->fd, DRM_IOCTL_MODE_DESTROY_DUMB, &destroy_req);
    }
    if (m->became_master)
        drmDropMaster(m->fd);
    if (m->fd >= 0)
        close(m->fd);
    free(m);
}

#else
/* Without libdrm (VFP_HAVE_DRM) this backend is not compiled in; display.c says how to get it. */
typedef int vfp_display_drm_unused_t;
#endif
