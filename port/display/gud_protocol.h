/* SPDX-License-Identifier: MIT */
/*
 * gud_protocol.h: the GUD (Generic USB Display) protocol, as the Linux kernel's host driver speaks it, and the
 * pure helpers display_gud.c builds on (display_gud_protocol.c: packing requests, parsing replies, splitting a
 * rectangle to the device's buffer, choosing compression), which the tests check without a device.
 *
 * The constants and wire layouts are written from the kernel's include/drm/gud.h (MIT licence, Copyright 2020
 * Noralf Trønnes), read alongside drivers/gpu/drm/gud/gud_drv.c, gud_connector.c and gud_pipe.c for how the host
 * uses them. All multi-byte fields are little-endian and the structures are packed; sizes are given here as
 * byte counts instead of C structs, and the helpers pack and unpack byte by byte.
 *
 * Control requests are vendor requests to the interface: bmRequestType 0xC1 (in) or 0x41 (out), wIndex the
 * interface number, wValue 0 or the connector index for the connector requests. When a request fails the device
 * stalls it; GET_STATUS then tells why.
 */
#ifndef VFP_GUD_PROTOCOL_H
#define VFP_GUD_PROTOCOL_H

#include <stddef.h>
#include <stdint.h>

#include "status.h"

/* USB IDs the kernel's gud driver matches (gud_drv.c, gud_id_table), with the vendor-specific interface class. */
#define GUD_VID_OPENMOKO 0x1d50
#define GUD_PID_OPENMOKO 0x614d
#define GUD_VID_MCS 0x16d0
#define GUD_PID_MCS 0x10a9
#define GUD_INTERFACE_CLASS 0xff

#define GUD_REQTYPE_IN 0xc1  /* device to host, vendor, interface */
#define GUD_REQTYPE_OUT 0x41 /* host to device, vendor, interface */

/* struct gud_display_descriptor_req (30 bytes): magic u32, version u8, flags u32, compression u8,
 * max_buffer_size u32, min_width u32, max_width u32, min_height u32, max_height u32. */
#define GUD_DISPLAY_DESCRIPTOR_SIZE 30
#define GUD_DISPLAY_MAGIC 0x1d50614du
#define GUD_DISPLAY_FLAG_STATUS_ON_SET (1u << 0) /* read GET_STATUS after every SET request */
#define GUD_DISPLAY_FLAG_FULL_UPDATE (1u << 1)   /* always send the whole frame; SET_BUFFER only after a failure */
#define GUD_COMPRESSION_LZ4 (1u << 0)

/* struct gud_property_req (10 bytes): prop u16, val u64. */
#define GUD_PROPERTY_SIZE 10
#define GUD_PROPERTY_BACKLIGHT_BRIGHTNESS 12 /* properties 1..12 are connector properties */
#define GUD_PROPERTY_ROTATION 50
#define GUD_ROTATION_0 (1u << 0)

/* struct gud_display_mode_req (24 bytes): clock u32 (kHz), hdisplay, hsync_start, hsync_end, htotal, vdisplay,
 * vsync_start, vsync_end, vtotal u16, flags u32. */
#define GUD_DISPLAY_MODE_SIZE 24
#define GUD_DISPLAY_MODE_FLAG_PREFERRED (1u << 10)

/* struct gud_connector_descriptor_req (5 bytes): connector_type u8, flags u32. */
#define GUD_CONNECTOR_DESCRIPTOR_SIZE 5

/* struct gud_set_buffer_req (25 bytes): x, y, width, height, length u32, compression u8, compressed_length u32. */
#define GUD_SET_BUFFER_SIZE 25

/* struct gud_state_req: mode (24 bytes), format u8, connector u8, then properties (10 bytes each). */
#define GUD_STATE_HEADER_SIZE 26

/* Control requests. */
#define GUD_REQ_GET_STATUS 0x00
#define GUD_STATUS_OK 0x00
#define GUD_STATUS_BUSY 0x01
#define GUD_STATUS_REQUEST_NOT_SUPPORTED 0x02
#define GUD_STATUS_PROTOCOL_ERROR 0x03
#define GUD_STATUS_INVALID_PARAMETER 0x04
#define GUD_STATUS_ERROR 0x05
#define GUD_REQ_GET_DESCRIPTOR 0x01
#define GUD_REQ_GET_FORMATS 0x40
#define GUD_FORMATS_MAX_NUM 32
#define GUD_PIXEL_FORMAT_RGB565 0x40
#define GUD_PIXEL_FORMAT_XRGB8888 0x80
#define GUD_REQ_GET_PROPERTIES 0x41
#define GUD_PROPERTIES_MAX_NUM 32
#define GUD_REQ_GET_CONNECTORS 0x50
#define GUD_CONNECTORS_MAX_NUM 32
#define GUD_REQ_GET_CONNECTOR_PROPERTIES 0x51
#define GUD_CONNECTOR_PROPERTIES_MAX_NUM 32
#define GUD_REQ_GET_CONNECTOR_STATUS 0x54
#define GUD_CONNECTOR_STATUS_CONNECTED_MASK 0x03
#define GUD_CONNECTOR_STATUS_CONNECTED 0x01
#define GUD_REQ_GET_CONNECTOR_MODES 0x55
#define GUD_CONNECTOR_MAX_NUM_MODES 128
#define GUD_REQ_SET_BUFFER 0x60
#define GUD_REQ_SET_STATE_CHECK 0x61
#define GUD_REQ_SET_STATE_COMMIT 0x62
#define GUD_REQ_SET_CONTROLLER_ENABLE 0x63
#define GUD_REQ_SET_DISPLAY_ENABLE 0x64

/* The host caps the device's buffer, as the kernel does (gud_probe: 4096x4096 XRGB8888). */
#define GUD_MAX_BUFFER_SIZE (64u << 20)

/* ---------------------------------------------------------------------------------------------------------- */
/* Pure helpers (display_gud_protocol.c), compiled in every build. */

typedef struct vfp_gud_descriptor {
    uint8_t version;
    uint32_t flags;
    uint8_t compression;
    uint32_t max_buffer_size; /* 0: the device did not say */
    uint32_t min_width, max_width, min_height, max_height;
} vfp_gud_descriptor_t;

typedef struct vfp_gud_mode {
    uint32_t clock; /* kHz */
    uint16_t hdisplay, hsync_start, hsync_end, htotal;
    uint16_t vdisplay, vsync_start, vsync_end, vtotal;
    uint32_t flags;
} vfp_gud_mode_t;

typedef struct vfp_gud_property {
    uint16_t prop;
    uint64_t val;
} vfp_gud_property_t;

typedef struct vfp_gud_set_buffer {
    uint32_t x, y, width, height;
    uint32_t length;            /* bytes of pixels before compression */
    uint8_t compression;        /* 0 or GUD_COMPRESSION_LZ4 */
    uint32_t compressed_length; /* bytes on the wire when compressed */
} vfp_gud_set_buffer_t;

/* Checks the size, magic, version (1) and limits as the kernel does. Returns VFP_OK, or VFP_ERR with a message. */
vfp_status_t vfp_gud_parse_descriptor(const uint8_t *buf, size_t len, vfp_gud_descriptor_t *desc, char *err,
                                      size_t errlen);

/* The display mode at buf (24 bytes), and back. */
void vfp_gud_parse_mode(const uint8_t *buf, vfp_gud_mode_t *mode);
void vfp_gud_pack_mode(uint8_t *buf, const vfp_gud_mode_t *mode);

/* From a GET_CONNECTOR_MODES reply: the preferred mode, else the first. Returns the number of modes (0 if none
 * or len is not a multiple of 24). */
int vfp_gud_pick_mode(const uint8_t *buf, size_t len, vfp_gud_mode_t *mode);

/* The 10-byte property at buf. */
void vfp_gud_parse_property(const uint8_t *buf, vfp_gud_property_t *prop);

/* SET_BUFFER's 25 bytes. */
void vfp_gud_pack_set_buffer(uint8_t *buf, const vfp_gud_set_buffer_t *req);

/* A STATE_CHECK payload; returns its length (26 + 10 per property), or 0 if cap is too small. */
size_t vfp_gud_pack_state(uint8_t *buf, size_t cap, const vfp_gud_mode_t *mode, uint8_t format, uint8_t connector,
                          const vfp_gud_property_t *props, int count);

/* Rows of `row_bytes` each that fit one transfer of at most max_buffer bytes (0: a row does not fit). */
uint32_t vfp_gud_rows_per_transfer(uint32_t row_bytes, uint32_t height, uint32_t max_buffer);

/* Whether to send LZ4: the device takes it (its compression flags), and the compressed size (from
 * LZ4_compress_default: 0 when it did not fit) is smaller than the raw one. */
int vfp_gud_use_lz4(uint8_t device_compression, uint32_t raw_length, int compressed_length);

/* "invalid parameter" for GUD_STATUS_INVALID_PARAMETER, and so on. */
const char *vfp_gud_status_text(uint8_t status);

/* "SET_BUFFER" for GUD_REQ_SET_BUFFER, and so on. */
const char *vfp_gud_request_name(uint8_t request);

#endif
