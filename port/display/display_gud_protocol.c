/* SPDX-License-Identifier: MIT */
/*
 * display_gud_protocol.c: the pure parts of the GUD backend (gud_protocol.h): packing requests, parsing replies,
 * splitting a rectangle to the device's buffer and choosing compression. Byte by byte, little-endian, with no
 * library: compiled in every build so the tests can check them without libusb or a device.
 */

/*********************
 *      INCLUDES
 *********************/
#include "gud_protocol.h"

#include <stdio.h>

/**********************
 *  STATIC PROTOTYPES
 **********************/
static uint16_t get16(const uint8_t *p);
static uint32_t get32(const uint8_t *p);
static uint64_t get64(const uint8_t *p);
static void put16(uint8_t *p, uint16_t v);
static void put32(uint8_t *p, uint32_t v);
static void put64(uint8_t *p, uint64_t v);

/**********************
 *   GLOBAL FUNCTIONS
 **********************/
vfp_status_t vfp_gud_parse_descriptor(const uint8_t *buf, size_t len, vfp_gud_descriptor_t *desc, char *err,
                                      size_t errlen)
{
    if (len != GUD_DISPLAY_DESCRIPTOR_SIZE) {
        snprintf(err, errlen, "display descriptor of %zu bytes (expected %d)", len, GUD_DISPLAY_DESCRIPTOR_SIZE);
        return VFP_ERR;
    }
    uint32_t magic = get32(buf);
    if (magic != GUD_DISPLAY_MAGIC) {
        snprintf(err, errlen, "not a GUD display: descriptor magic 0x%08x (expected 0x%08x)", magic,
                 GUD_DISPLAY_MAGIC);
        return VFP_ERR;
    }
    desc->version = buf[4];
    desc->flags = get32(buf + 5);
    desc->compression = buf[9];
    desc->max_buffer_size = get32(buf + 10);
    desc->min_width = get32(buf + 14);
    desc->max_width = get32(buf + 18);
    desc->min_height = get32(buf + 22);
    desc->max_height = get32(buf + 26);
    if (desc->version != 1) {
        snprintf(err, errlen, "GUD protocol version %u is not supported (expected 1)", desc->version);
        return VFP_ERR;
    }
    if (!desc->max_width || !desc->max_height || desc->min_width > desc->max_width ||
        desc->min_height > desc->max_height) {
        snprintf(err, errlen, "bad size limits in the display descriptor: %ux%u to %ux%u", desc->min_width,
                 desc->min_height, desc->max_width, desc->max_height);
        return VFP_ERR;
    }
    return VFP_OK;
}

void vfp_gud_parse_mode(const uint8_t *buf, vfp_gud_mode_t *mode)
{
    mode->clock = get32(buf);
    mode->hdisplay = get16(buf + 4);
    mode->hsync_start = get16(buf + 6);
    mode->hsync_end = get16(buf + 8);
    mode->htotal = get16(buf + 10);
    mode->vdisplay = get16(buf + 12);
    mode->vsync_start = get16(buf + 14);
    mode->vsync_end = get16(buf + 16);
    mode->vtotal = get16(buf + 18);
    mode->flags = get32(buf + 20);
}

void vfp_gud_pack_mode(uint8_t *buf, const vfp_gud_mode_t *mode)
{
    put32(buf, mode->clock);
    put16(buf + 4, mode->hdisplay);
    put16(buf + 6, mode->hsync_start);
    put16(buf + 8, mode->hsync_end);
    put16(buf + 10, mode->htotal);
    put16(buf + 12, mode->vdisplay);
    put16(buf + 14, mode->vsync_start);
    put16(buf + 16, mode->vsync_end);
    put16(buf + 18, mode->vtotal);
    put32(buf + 20, mode->flags);
}

int vfp_gud_pick_mode(const uint8_t *buf, size_t len, vfp_gud_mode_t *mode)
{
    if (len == 0 || len % GUD_DISPLAY_MODE_SIZE)
        return 0;
    int count = (int)(len / GUD_DISPLAY_MODE_SIZE);
    vfp_gud_parse_mode(buf, mode);
    for (int i = 0; i < count; i++) {
        vfp_gud_mode_t m;
        vfp_gud_parse_mode(buf + (size_t)i * GUD_DISPLAY_MODE_SIZE, &m);
        if (m.flags & GUD_DISPLAY_MODE_FLAG_PREFERRED) {
            *mode = m;
            break;
        }
    }
    return count;
}

void vfp_gud_parse_property(const uint8_t *buf, vfp_gud_property_t *prop)
{
    prop->prop = get16(buf);
    prop->val = get64(buf + 2);
}

void vfp_gud_pack_set_buffer(uint8_t *buf, const vfp_gud_set_buffer_t *req)
{
    put32(buf, req->x);
    put32(buf + 4, req->y);
    put32(buf + 8, req->width);
    put32(buf + 12, req->height);
    put32(buf + 16, req->length);
    buf[20] = req->compression;
    put32(buf + 21, req->compressed_length);
}

size_t vfp_gud_pack_state(uint8_t *buf, size_t cap, const vfp_gud_mode_t *mode, uint8_t format, uint8_t connector,
                          const vfp_gud_property_t *props, int count)
{
    size_t len = GUD_STATE_HEADER_SIZE + (size_t)count * GUD_PROPERTY_SIZE;
    if (count < 0 || len > cap)
        return 0;
    vfp_gud_pack_mode(buf, mode);
    buf[24] = format;
    buf[25] = connector;
    for (int i = 0; i < count; i++) {
        uint8_t *p = buf + GUD_STATE_HEADER_SIZE + (size_t)i * GUD_PROPERTY_SIZE;
        put16(p, props[i].prop);
        put64(p + 2, props[i].val);
    }
    return len;
}

uint32_t vfp_gud_rows_per_transfer(uint32_t row_bytes, uint32_t height, uint32_t max_buffer)
{
    if (row_bytes == 0 || max_buffer == 0)
        return height;
    uint32_t rows = max_buffer / row_bytes;
    return rows < height ? rows : height;
}

int vfp_gud_use_lz4(uint8_t device_compression, uint32_t raw_length, int compressed_length)
{
    return (device_compression & GUD_COMPRESSION_LZ4) && compressed_length > 0 &&
           (uint32_t)compressed_length < raw_length;
}

const char *vfp_gud_status_text(uint8_t status)
{
    switch (status) {
    case GUD_STATUS_OK:
        return "ok";
    case GUD_STATUS_BUSY:
        return "busy";
    case GUD_STATUS_REQUEST_NOT_SUPPORTED:
        return "request not supported";
    case GUD_STATUS_PROTOCOL_ERROR:
        return "protocol error";
    case GUD_STATUS_INVALID_PARAMETER:
        return "invalid parameter";
    case GUD_STATUS_ERROR:
        return "error";
    default:
        return "unknown status";
    }
}

const char *vfp_gud_request_name(uint8_t request)
{
    switch (request) {
    case GUD_REQ_GET_STATUS:
        return "GET_STATUS";
    case GUD_REQ_GET_DESCRIPTOR:
        return "GET_DESCRIPTOR";
    case GUD_REQ_GET_FORMATS:
        return "GET_FORMATS";
    case GUD_REQ_GET_PROPERTIES:
        return "GET_PROPERTIES";
    case GUD_REQ_GET_CONNECTORS:
        return "GET_CONNECTORS";
    case GUD_REQ_GET_CONNECTOR_PROPERTIES:
        return "GET_CONNECTOR_PROPERTIES";
    case GUD_REQ_GET_CONNECTOR_STATUS:
        return "GET_CONNECTOR_STATUS";
    case GUD_REQ_GET_CONNECTOR_MODES:
        return "GET_CONNECTOR_MODES";
    case GUD_REQ_SET_BUFFER:
        return "SET_BUFFER";
    case GUD_REQ_SET_STATE_CHECK:
        return "STATE_CHECK";
    case GUD_REQ_SET_STATE_COMMIT:
        return "STATE_COMMIT";
    case GUD_REQ_SET_CONTROLLER_ENABLE:
        return "SET_CONTROLLER_ENABLE";
    case GUD_REQ_SET_DISPLAY_ENABLE:
        return "SET_DISPLAY_ENABLE";
    default:
        return "request";
    }
}

/**********************
 *   STATIC FUNCTIONS
 **********************/
static uint16_t get16(const uint8_t *p)
{
    return (uint16_t)(p[0] | p[1] << 8);
}

static uint32_t get32(const uint8_t *p)
{
    return p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static uint64_t get64(const uint8_t *p)
{
    return get32(p) | (uint64_t)get32(p + 4) << 32;
}

static void put16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}

static void put32(uint8_t *p, uint32_t v)
{
    put16(p, (uint16_t)v);
    put16(p + 2, (uint16_t)(v >> 16));
}

static void put64(uint8_t *p, uint64_t v)
{
    put32(p, (uint32_t)v);
    put32(p + 4, (uint32_t)(v >> 32));
}
