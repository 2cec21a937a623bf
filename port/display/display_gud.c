/* SPDX-License-Identifier: MIT */
/*
 * display_gud.c: a GUD (Generic USB Display) driven from user space with libusb, for boards whose kernel lacks
 * the gud driver or where the viewer should own the display outright. The protocol is the kernel's
 * (gud_protocol.h); this file follows what its host driver does:
 *
 * - open: find the device (VID:PID 1d50:614d or 16d0:10a9, or the board's display.device "VVVV:PPPP") with a
 *   vendor-class interface and a bulk OUT endpoint; claim the interface (detaching the kernel's driver); probe
 *   (GET_DESCRIPTOR, GET_FORMATS, GET_PROPERTIES, GET_CONNECTORS, GET_CONNECTOR_STATUS until one is connected,
 *   GET_CONNECTOR_PROPERTIES and GET_CONNECTOR_MODES of that one); then STATE_CHECK with the preferred mode (else
 *   the first) and the format (RGB565 little-endian, or XRGB8888 when the board asks and the device has it),
 *   SET_CONTROLLER_ENABLE 1, STATE_COMMIT, SET_DISPLAY_ENABLE 1, in the kernel's order.
 * - present: per band of rows that fits the device's buffer, SET_BUFFER then a bulk OUT transfer of the pixels
 *   (LZ4-compressed when the device takes LZ4, liblz4 is compiled in and it comes out smaller).
 * - a stalled request is explained by GET_STATUS in the message; a device that went away (no device, I/O error)
 *   makes present return VFP_DISPLAY_LOST, and a later open() finds it again, each open starting a fresh libusb
 *   context that scans the bus.
 *
 * The pure parts (packing, parsing, splitting, the compression decision) are in display_gud_protocol.c, compiled
 * in every build and tested on their own; this file needs libusb (VFP_HAVE_GUD).
 */

#ifdef VFP_HAVE_GUD

/*********************
 *      INCLUDES
 *********************/
#include "display.h"
#include "display_backends.h"
#include "gud_protocol.h"

#include <libusb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef VFP_HAVE_LZ4
#include <lz4.h>
#endif

/*********************
 *      DEFINES
 *********************/
#define CONTROL_TIMEOUT_MS 5000 /* the kernel's USB_CTRL_GET_TIMEOUT */
#define BULK_TIMEOUT_MS 3000    /* the kernel's gud_usb_bulk */
#define MAX_STATE_PROPS (GUD_CONNECTOR_PROPERTIES_MAX_NUM + 1)

/**********************
 *      TYPES
 **********************/
typedef struct gud {
    char name[16];                /* "1d50:614d", for messages */
    libusb_context *ctx;
    libusb_device_handle *handle;
    int claimed;
    uint8_t interface, endpoint;  /* the vendor interface and its bulk OUT endpoint */
    vfp_gud_descriptor_t desc;
    uint8_t format;               /* GUD_PIXEL_FORMAT_* */
    uint32_t bytes;               /* per pixel */
    uint32_t max_buffer;          /* bytes one transfer may carry */
    uint8_t *buf;                 /* one transfer's pixels */
    uint8_t *packed;              /* the same compressed (NULL: no compression) */
    uint8_t *frame;               /* FULL_UPDATE devices: the whole frame, sent each time */
    int enabled;                  /* controller and display on: turn them off at close */
    int lost;                     /* the device went away: send nothing more */
    int failed;                   /* FULL_UPDATE: the last transfer failed, so send SET_BUFFER again */
} gud_t;

/**********************
 *  STATIC PROTOTYPES
 **********************/
static vfp_status_t gud_open(vfp_display_t *d, const vfp_board_t *board, char *err, size_t errlen);
static vfp_status_t gud_present(vfp_display_t *d, uint32_t x, uint32_t y, uint32_t w, uint32_t h, const void *pixels,
                                uint32_t stride, char *err, size_t errlen);
static void gud_close(vfp_display_t *d);
static vfp_status_t parse_ids(const char *text, uint16_t ids[2][2], int *count);
static vfp_status_t find_device(gud_t *g, uint16_t ids[2][2], int count, libusb_device **found);
static vfp_status_t find_interface(libusb_device *dev, uint8_t *interface, uint8_t *endpoint);
static vfp_status_t probe(gud_t *g, vf_format_t wanted, vfp_gud_mode_t *mode, char *err, size_t errlen);
static vfp_status_t get(gud_t *g, uint8_t request, uint16_t value, uint8_t *buf, uint16_t len, int *got, char *err,
                        size_t errlen);
static vfp_status_t set(gud_t *g, uint8_t request, uint16_t value, const uint8_t *buf, uint16_t len, char *err,
                        size_t errlen);
static vfp_status_t set_u8(gud_t *g, uint8_t request, uint8_t value, char *err, size_t errlen);
static vfp_status_t failure(gud_t *g, const char *what, int r, int ask_status, char *err, size_t errlen);
static vfp_status_t send_band(gud_t *g, const vfp_gud_set_buffer_t *band, char *err, size_t errlen);
static void destroy(gud_t *g);

/**********************
 *  GLOBAL VARIABLES
 **********************/
const vfp_display_ops_t vfp_display_gud_ops = {"gud", gud_open, gud_present, gud_close};

/**********************
 *   STATIC FUNCTIONS
 **********************/
static vfp_status_t gud_open(vfp_display_t *d, const vfp_board_t *board, char *err, size_t errlen)
{
    uint16_t ids[2][2];
    int count;
    libusb_device *dev = NULL;
    d->priv = NULL;
    if (parse_ids(board->display_device, ids, &count)) {
        snprintf(err, errlen, "display.device '%s': expected VID:PID in hex, like 1d50:614d",
                 board->display_device);
        return VFP_ERR;
    }
    gud_t *g = calloc(1, sizeof *g);
    if (!g) {
        snprintf(err, errlen, "gud display: out of memory");
        return VFP_ERR;
    }
    int r = libusb_init(&g->ctx);
    if (r != 0) {
        g->ctx = NULL;
        snprintf(err, errlen, "gud display: libusb_init failed: %s", libusb_strerror(r));
        goto fail;
    }
    if (find_device(g, ids, count, &dev) != VFP_OK) {
        if (count == 1)
            snprintf(err, errlen, "no GUD display found (VID:PID %04x:%04x): is it plugged in?", ids[0][0],
                     ids[0][1]);
        else
            snprintf(err, errlen, "no GUD display found (VID:PID %04x:%04x or %04x:%04x): is it plugged in?",
                     ids[0][0], ids[0][1], ids[1][0], ids[1][1]);
        goto fail;
    }
    r = libusb_open(dev, &g->handle);
    if (r != 0) {
        g->handle = NULL;
        snprintf(err, errlen, "%s: cannot open (bus %u, device %u): %s%s", g->name, libusb_get_bus_number(dev),
                 libusb_get_device_address(dev), libusb_strerror(r),
                 r == LIBUSB_ERROR_ACCESS ? " (a udev rule can give the user access)" : "");
        goto fail;
    }
    libusb_unref_device(dev);
    dev = NULL;
    libusb_set_auto_detach_kernel_driver(g->handle, 1);
    r = libusb_claim_interface(g->handle, g->interface);
    if (r != 0) {
        snprintf(err, errlen, "%s: cannot claim interface %u: %s", g->name, g->interface, libusb_strerror(r));
        goto fail;
    }
    g->claimed = 1;

    vfp_gud_mode_t mode;
    if (probe(g, board->format, &mode, err, errlen))
        goto fail;

    /* Buffers: one transfer, its compressed copy, and for FULL_UPDATE devices the whole frame. */
    uint64_t frame_bytes = (uint64_t)mode.hdisplay * mode.vdisplay * g->bytes;
    g->max_buffer = g->desc.max_buffer_size ? g->desc.max_buffer_size : (uint32_t)frame_bytes;
    if (g->max_buffer > GUD_MAX_BUFFER_SIZE)
        g->max_buffer = GUD_MAX_BUFFER_SIZE;
    size_t buf_bytes = g->max_buffer < frame_bytes ? g->max_buffer : (size_t)frame_bytes;
    g->buf = malloc(buf_bytes);
#ifdef VFP_HAVE_LZ4
    if ((g->desc.compression & GUD_COMPRESSION_LZ4) && !(g->desc.flags & GUD_DISPLAY_FLAG_FULL_UPDATE))
        g->packed = malloc(buf_bytes);
#endif
    if (g->desc.flags & GUD_DISPLAY_FLAG_FULL_UPDATE)
        g->frame = calloc(1, (size_t)frame_bytes);
    if (!g->buf || ((g->desc.flags & GUD_DISPLAY_FLAG_FULL_UPDATE) && !g->frame)) {
        snprintf(err, errlen, "%s: out of memory for a %ux%u display", g->name, mode.hdisplay, mode.vdisplay);
        goto fail;
    }
    d->priv = g;
    d->width = mode.hdisplay;
    d->height = mode.vdisplay;
    d->format = g->format == GUD_PIXEL_FORMAT_XRGB8888 ? VF_FORMAT_XRGB8888 : VF_FORMAT_RGB565;
    return VFP_OK;

fail:
    if (dev)
        libusb_unref_device(dev);
    destroy(g);
    return VFP_ERR;
}

static vfp_status_t gud_present(vfp_display_t *d, uint32_t x, uint32_t y, uint32_t w, uint32_t h, const void *pixels,
                                uint32_t stride, char *err, size_t errlen)
{
    gud_t *g = d->priv;
    if (g && g->lost) {
        snprintf(err, errlen, "%s: display gone", g->name);
        return VFP_DISPLAY_LOST;
    }
    if (vfp_display_check_present(d, g ? g->name : NULL, x, y, w, h, stride, err, errlen))
        return VFP_ERR;
    if (w == 0 || h == 0)
        return VFP_OK;
    const uint8_t *src = pixels;
    if (g->frame) {
        /* FULL_UPDATE: the device only takes whole frames, so keep one and send all of it. */
        uint32_t frame_stride = d->width * g->bytes;
        for (uint32_t row = y; row < y + h; row++)
            memcpy(g->frame + (size_t)row * frame_stride + (size_t)x * g->bytes,
                   src + (size_t)row * stride + (size_t)x * g->bytes, (size_t)w * g->bytes);
        src = g->frame;
        stride = frame_stride;
        x = y = 0;
        w = d->width;
        h = d->height;
    }
    uint32_t row_bytes = w * g->bytes;
    uint32_t rows = vfp_gud_rows_per_transfer(row_bytes, h, g->max_buffer);
    if (rows == 0) {
        snprintf(err, errlen, "%s: a row of %u pixels (%u bytes) is larger than the device's %u-byte buffer",
                 g->name, w, row_bytes, g->max_buffer);
        return VFP_ERR;
    }
    for (uint32_t done = 0; done < h; done += rows) {
        uint32_t n = h - done < rows ? h - done : rows;
        for (uint32_t i = 0; i < n; i++)
            memcpy(g->buf + (size_t)i * row_bytes, src + (size_t)(y + done + i) * stride + (size_t)x * g->bytes,
                   row_bytes);
        vfp_gud_set_buffer_t band = {x, y + done, w, n, n * row_bytes, 0, 0};
        vfp_status_t status = send_band(g, &band, err, errlen);
        if (status)
            return status;
    }
    return VFP_OK;
}

static void gud_close(vfp_display_t *d)
{
    if (d->priv)
        destroy(d->priv);
    d->priv = NULL;
}

/* "" gives both IDs the kernel's driver knows; "VVVV:PPPP" gives one. */
static vfp_status_t parse_ids(const char *text, uint16_t ids[2][2], int *count)
{
    if (!text || !text[0]) {
        ids[0][0] = GUD_VID_OPENMOKO;
        ids[0][1] = GUD_PID_OPENMOKO;
        ids[1][0] = GUD_VID_MCS;
        ids[1][1] = GUD_PID_MCS;
        *count = 2;
        return VFP_OK;
    }
    unsigned vid, pid;
    int used = 0;
    if (strlen(text) != 9 || sscanf(text, "%4x:%4x%n", &vid, &pid, &used) != 2 || used != 9)
        return VFP_ERR;
    ids[0][0] = (uint16_t)vid;
    ids[0][1] = (uint16_t)pid;
    *count = 1;
    return VFP_OK;
}

/* The first device with one of the IDs and a vendor interface with a bulk OUT endpoint (referenced), or VFP_ERR
 * (the caller words the message). */
static vfp_status_t find_device(gud_t *g, uint16_t ids[2][2], int count, libusb_device **found)
{
    libusb_device **list;
    ssize_t n = libusb_get_device_list(g->ctx, &list);
    *found = NULL;
    for (ssize_t i = 0; i < n && !*found; i++) {
        struct libusb_device_descriptor dd;
        if (libusb_get_device_descriptor(list[i], &dd) != 0)
            continue;
        for (int k = 0; k < count; k++)
            if (dd.idVendor == ids[k][0] && dd.idProduct == ids[k][1] &&
                find_interface(list[i], &g->interface, &g->endpoint) == VFP_OK) {
                *found = libusb_ref_device(list[i]);
                snprintf(g->name, sizeof g->name, "%04x:%04x", dd.idVendor, dd.idProduct);
                break;
            }
    }
    if (n >= 0)
        libusb_free_device_list(list, 1);
    return *found ? VFP_OK : VFP_ERR;
}

static vfp_status_t find_interface(libusb_device *dev, uint8_t *interface, uint8_t *endpoint)
{
    struct libusb_config_descriptor *config;
    if (libusb_get_active_config_descriptor(dev, &config) != 0 &&
        libusb_get_config_descriptor(dev, 0, &config) != 0)
        return VFP_ERR;
    int found = 0;
    for (int i = 0; i < config->bNumInterfaces && !found; i++) {
        if (config->interface[i].num_altsetting < 1)
            continue;
        const struct libusb_interface_descriptor *alt = &config->interface[i].altsetting[0];
        if (alt->bInterfaceClass != GUD_INTERFACE_CLASS)
            continue;
        for (int e = 0; e < alt->bNumEndpoints; e++) {
            const struct libusb_endpoint_descriptor *ep = &alt->endpoint[e];
            if ((ep->bmAttributes & 3) == LIBUSB_TRANSFER_TYPE_BULK &&
                (ep->bEndpointAddress & LIBUSB_ENDPOINT_DIR_MASK) == LIBUSB_ENDPOINT_OUT) {
                *interface = alt->bInterfaceNumber;
                *endpoint = ep->bEndpointAddress;
                found = 1;
                break;
            }
        }
    }
    libusb_free_config_descriptor(config);
    return found ? VFP_OK : VFP_ERR;
}

/* The kernel's probe and first commit: descriptor, formats, properties, a connected connector and its mode,
 * then the state, and the display on. Errors during open are all VFP_ERR. */
static vfp_status_t probe(gud_t *g, vf_format_t wanted, vfp_gud_mode_t *mode, char *err, size_t errlen)
{
    uint8_t buf[GUD_CONNECTOR_MAX_NUM_MODES * GUD_DISPLAY_MODE_SIZE]; /* the largest reply: 3072 bytes */
    int got;
    if (get(g, GUD_REQ_GET_DESCRIPTOR, 0, buf, GUD_DISPLAY_DESCRIPTOR_SIZE, &got, err, errlen))
        return VFP_ERR;
    char why[160];
    if (vfp_gud_parse_descriptor(buf, (size_t)got, &g->desc, why, sizeof why)) {
        snprintf(err, errlen, "%s: %s", g->name, why);
        return VFP_ERR;
    }

    if (get(g, GUD_REQ_GET_FORMATS, 0, buf, GUD_FORMATS_MAX_NUM, &got, err, errlen))
        return VFP_ERR;
    int has565 = 0, has8888 = 0;
    for (int i = 0; i < got; i++) {
        has565 |= buf[i] == GUD_PIXEL_FORMAT_RGB565;
        has8888 |= buf[i] == GUD_PIXEL_FORMAT_XRGB8888;
    }
    if (wanted == VF_FORMAT_XRGB8888 && has8888)
        g->format = GUD_PIXEL_FORMAT_XRGB8888;
    else if (has565)
        g->format = GUD_PIXEL_FORMAT_RGB565;
    else if (has8888)
        g->format = GUD_PIXEL_FORMAT_XRGB8888;
    else {
        snprintf(err, errlen, "%s: the display takes neither RGB565 nor XRGB8888 (it lists %d other formats)",
                 g->name, got);
        return VFP_ERR;
    }
    g->bytes = g->format == GUD_PIXEL_FORMAT_XRGB8888 ? 4 : 2;

    /* State properties: the connector's (echoing the values it gave) then the plane's rotation, unrotated. */
    vfp_gud_property_t props[MAX_STATE_PROPS];
    int nprops = 0, has_rotation = 0;
    if (get(g, GUD_REQ_GET_PROPERTIES, 0, buf, GUD_PROPERTIES_MAX_NUM * GUD_PROPERTY_SIZE, &got, err, errlen))
        return VFP_ERR;
    if (got % GUD_PROPERTY_SIZE) {
        snprintf(err, errlen, "%s: GET_PROPERTIES gave %d bytes, not a multiple of %d", g->name, got,
                 GUD_PROPERTY_SIZE);
        return VFP_ERR;
    }
    for (int i = 0; i < got / GUD_PROPERTY_SIZE; i++) {
        vfp_gud_property_t p;
        vfp_gud_parse_property(buf + i * GUD_PROPERTY_SIZE, &p);
        has_rotation |= p.prop == GUD_PROPERTY_ROTATION;
    }

    if (get(g, GUD_REQ_GET_CONNECTORS, 0, buf, GUD_CONNECTORS_MAX_NUM * GUD_CONNECTOR_DESCRIPTOR_SIZE, &got, err,
            errlen))
        return VFP_ERR;
    if (got == 0 || got % GUD_CONNECTOR_DESCRIPTOR_SIZE) {
        snprintf(err, errlen, "%s: GET_CONNECTORS gave %d bytes (expected connectors of %d bytes)", g->name, got,
                 GUD_CONNECTOR_DESCRIPTOR_SIZE);
        return VFP_ERR;
    }
    int connectors = got / GUD_CONNECTOR_DESCRIPTOR_SIZE, connector = -1;
    for (int i = 0; i < connectors && connector < 0; i++) {
        if (get(g, GUD_REQ_GET_CONNECTOR_STATUS, (uint16_t)i, buf, 1, &got, err, errlen))
            return VFP_ERR;
        if (got == 1 && (buf[0] & GUD_CONNECTOR_STATUS_CONNECTED_MASK) == GUD_CONNECTOR_STATUS_CONNECTED)
            connector = i;
    }
    if (connector < 0) {
        snprintf(err, errlen, "%s: none of its %d connectors has a display connected", g->name, connectors);
        return VFP_ERR;
    }

    if (get(g, GUD_REQ_GET_CONNECTOR_PROPERTIES, (uint16_t)connector, buf,
            GUD_CONNECTOR_PROPERTIES_MAX_NUM * GUD_PROPERTY_SIZE, &got, err, errlen))
        return VFP_ERR;
    for (int i = 0; i + GUD_PROPERTY_SIZE <= got; i += GUD_PROPERTY_SIZE) {
        vfp_gud_property_t p;
        vfp_gud_parse_property(buf + i, &p);
        if (p.prop >= 1 && p.prop <= GUD_PROPERTY_BACKLIGHT_BRIGHTNESS) /* those the kernel knows */
            props[nprops++] = p;
    }
    if (has_rotation)
        props[nprops++] = (vfp_gud_property_t){GUD_PROPERTY_ROTATION, GUD_ROTATION_0};

    if (get(g, GUD_REQ_GET_CONNECTOR_MODES, (uint16_t)connector, buf, sizeof buf, &got, err, errlen))
        return VFP_ERR;
    if (vfp_gud_pick_mode(buf, (size_t)got, mode) == 0 || mode->hdisplay == 0 || mode->vdisplay == 0) {
        snprintf(err, errlen, "%s: connector %d offers no display mode (GET_CONNECTOR_MODES gave %d bytes)",
                 g->name, connector, got);
        return VFP_ERR;
    }

    size_t len = vfp_gud_pack_state(buf, sizeof buf, mode, g->format, (uint8_t)connector, props, nprops);
    if (set(g, GUD_REQ_SET_STATE_CHECK, 0, buf, (uint16_t)len, err, errlen) ||
        set_u8(g, GUD_REQ_SET_CONTROLLER_ENABLE, 1, err, errlen))
        return VFP_ERR;
    g->enabled = 1;
    if (set(g, GUD_REQ_SET_STATE_COMMIT, 0, NULL, 0, err, errlen) ||
        set_u8(g, GUD_REQ_SET_DISPLAY_ENABLE, 1, err, errlen))
        return VFP_ERR;
    return VFP_OK;
}

/* A GET request; the reply's length in *got. Returns VFP_OK, VFP_ERR or VFP_DISPLAY_LOST with err. */
static vfp_status_t get(gud_t *g, uint8_t request, uint16_t value, uint8_t *buf, uint16_t len, int *got, char *err,
                        size_t errlen)
{
    int r = libusb_control_transfer(g->handle, GUD_REQTYPE_IN, request, value, g->interface, buf, len,
                                    CONTROL_TIMEOUT_MS);
    *got = r < 0 ? 0 : r;
    return r < 0 ? failure(g, vfp_gud_request_name(request), r, 1, err, errlen) : VFP_OK;
}

/* A SET request with its payload (len may be 0); then GET_STATUS if the device wants it after every SET. */
static vfp_status_t set(gud_t *g, uint8_t request, uint16_t value, const uint8_t *buf, uint16_t len, char *err,
                        size_t errlen)
{
    const char *what = vfp_gud_request_name(request);
    int r = libusb_control_transfer(g->handle, GUD_REQTYPE_OUT, request, value, g->interface, (uint8_t *)buf, len,
                                    CONTROL_TIMEOUT_MS);
    if (r < 0)
        return failure(g, what, r, 1, err, errlen);
    if (r != len) {
        snprintf(err, errlen, "%s: %s sent %d of %u bytes", g->name, what, r, len);
        return VFP_ERR;
    }
    if (g->desc.flags & GUD_DISPLAY_FLAG_STATUS_ON_SET) {
        uint8_t status;
        r = libusb_control_transfer(g->handle, GUD_REQTYPE_IN, GUD_REQ_GET_STATUS, 0, g->interface, &status, 1,
                                    CONTROL_TIMEOUT_MS);
        if (r < 0)
            return failure(g, "GET_STATUS", r, 0, err, errlen);
        if (r == 1 && status != GUD_STATUS_OK) {
            snprintf(err, errlen, "%s: %s failed: device status %u (%s)", g->name, what, status,
                     vfp_gud_status_text(status));
            return VFP_ERR;
        }
    }
    return VFP_OK;
}

static vfp_status_t set_u8(gud_t *g, uint8_t request, uint8_t value, char *err, size_t errlen)
{
    return set(g, request, 0, &value, 1, err, errlen);
}

/* The message for a failed transfer, and whether the display is lost (gone from the bus) or just failed. A
 * stalled control request is explained by GET_STATUS (ask_status). */
static vfp_status_t failure(gud_t *g, const char *what, int r, int ask_status, char *err, size_t errlen)
{
    if (r == LIBUSB_ERROR_NO_DEVICE || r == LIBUSB_ERROR_IO) {
        g->lost = 1;
        snprintf(err, errlen, "%s: display gone (%s: %s)", g->name, what, libusb_strerror(r));
        return VFP_DISPLAY_LOST;
    }
    if (r == LIBUSB_ERROR_PIPE && ask_status) {
        uint8_t status;
        int s = libusb_control_transfer(g->handle, GUD_REQTYPE_IN, GUD_REQ_GET_STATUS, 0, g->interface, &status, 1,
                                        CONTROL_TIMEOUT_MS);
        if (s == 1) {
            snprintf(err, errlen, "%s: %s stalled: device status %u (%s)", g->name, what, status,
                     vfp_gud_status_text(status));
            return VFP_ERR;
        }
        if (s == LIBUSB_ERROR_NO_DEVICE || s == LIBUSB_ERROR_IO)
            return failure(g, what, s, 0, err, errlen);
        snprintf(err, errlen, "%s: %s stalled (and GET_STATUS: %s)", g->name, what,
                 s < 0 ? libusb_strerror(s) : "no status byte");
        return VFP_ERR;
    }
    snprintf(err, errlen, "%s: %s failed: %s", g->name, what, libusb_strerror(r));
    return VFP_ERR;
}

/* One band of rows, already packed in g->buf: SET_BUFFER (compressed if that pays) and the bulk transfer. */
static vfp_status_t send_band(gud_t *g, const vfp_gud_set_buffer_t *band, char *err, size_t errlen)
{
    vfp_gud_set_buffer_t req = *band;
    uint8_t *data = g->buf;
    uint32_t length = req.length;
#ifdef VFP_HAVE_LZ4
    if (g->packed) {
        int packed = LZ4_compress_default((const char *)g->buf, (char *)g->packed, (int)req.length,
                                          (int)req.length);
        if (vfp_gud_use_lz4(g->desc.compression, req.length, packed)) {
            req.compression = GUD_COMPRESSION_LZ4;
            req.compressed_length = (uint32_t)packed;
            data = g->packed;
            length = (uint32_t)packed;
        }
    }
#endif
    if (!(g->desc.flags & GUD_DISPLAY_FLAG_FULL_UPDATE) || g->failed) {
        uint8_t wire[GUD_SET_BUFFER_SIZE];
        vfp_gud_pack_set_buffer(wire, &req);
        vfp_status_t status = set(g, GUD_REQ_SET_BUFFER, 0, wire, sizeof wire, err, errlen);
        if (status)
            return status;
    }
    int sent = 0;
    int r = libusb_bulk_transfer(g->handle, g->endpoint, data, (int)length, &sent, BULK_TIMEOUT_MS);
    g->failed = r != 0 || (uint32_t)sent != length;
    if (r == LIBUSB_ERROR_PIPE)
        libusb_clear_halt(g->handle, g->endpoint); /* so that the next frame can go */
    if (r != 0)
        return failure(g, "bulk transfer", r, 0, err, errlen);
    if ((uint32_t)sent != length) {
        snprintf(err, errlen, "%s: bulk transfer sent %d of %u bytes", g->name, sent, length);
        return VFP_ERR;
    }
    return VFP_OK;
}

/* Gives back what g holds, in the reverse order of gud_open; after a loss, nothing more is sent. */
static void destroy(gud_t *g)
{
    if (g->enabled && !g->lost) {
        char ignored[8];
        set_u8(g, GUD_REQ_SET_DISPLAY_ENABLE, 0, ignored, sizeof ignored);
        set_u8(g, GUD_REQ_SET_CONTROLLER_ENABLE, 0, ignored, sizeof ignored);
    }
    free(g->frame);
    free(g->packed);
    free(g->buf);
    if (g->claimed)
        libusb_release_interface(g->handle, g->interface); /* gives the interface back to the kernel's driver */
    if (g->handle)
        libusb_close(g->handle);
    if (g->ctx)
        libusb_exit(g->ctx);
    free(g);
}

#else
/* Without libusb (VFP_HAVE_GUD) this backend is not compiled in; display.c says how to get it. */
typedef int vfp_display_gud_unused_t;
#endif
