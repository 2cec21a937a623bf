/* SPDX-License-Identifier: MIT */
/* test_display_gud.c: the GUD protocol's pure parts (gud_protocol.h), byte for byte, without a device. The
 * conversation with a device is in test_display_gud_usb.c. */
#include <string.h>

#include "check.h"
#include "display/gud_protocol.h"

/* A valid descriptor: version 1, flags STATUS_ON_SET, LZ4, 64 KiB buffer, 1x1 to 480x320. */
static const uint8_t good_descriptor[GUD_DISPLAY_DESCRIPTOR_SIZE] = {
    0x4d, 0x61, 0x50, 0x1d,    /* magic 0x1d50614d, little-endian */
    0x01,                      /* version */
    0x01, 0x00, 0x00, 0x00,    /* flags */
    0x01,                      /* compression: LZ4 */
    0x00, 0x00, 0x01, 0x00,    /* max_buffer_size 65536 */
    0x01, 0x00, 0x00, 0x00,    /* min_width */
    0xe0, 0x01, 0x00, 0x00,    /* max_width 480 */
    0x01, 0x00, 0x00, 0x00,    /* min_height */
    0x40, 0x01, 0x00, 0x00,    /* max_height 320 */
};

static void descriptor_good(void)
{
    vfp_gud_descriptor_t d;
    char err[200];
    CHECK_EQ(vfp_gud_parse_descriptor(good_descriptor, sizeof good_descriptor, &d, err, sizeof err), 0);
    CHECK_EQ(d.version, 1);
    CHECK_EQ(d.flags, GUD_DISPLAY_FLAG_STATUS_ON_SET);
    CHECK_EQ(d.compression, GUD_COMPRESSION_LZ4);
    CHECK_EQ(d.max_buffer_size, 65536);
    CHECK_EQ(d.min_width, 1);
    CHECK_EQ(d.max_width, 480);
    CHECK_EQ(d.min_height, 1);
    CHECK_EQ(d.max_height, 320);
}

static void descriptor_bad_magic(void)
{
    uint8_t buf[GUD_DISPLAY_DESCRIPTOR_SIZE];
    memcpy(buf, good_descriptor, sizeof buf);
    buf[0] = 0x78, buf[1] = 0x56, buf[2] = 0x34, buf[3] = 0x12;
    vfp_gud_descriptor_t d;
    char err[200] = "";
    CHECK_EQ(vfp_gud_parse_descriptor(buf, sizeof buf, &d, err, sizeof err), 2);
    CHECK_MSG(strcmp(err, "not a GUD display: descriptor magic 0x12345678 (expected 0x1d50614d)") == 0, "%s", err);
}

static void descriptor_bad_version_size_limits(void)
{
    uint8_t buf[GUD_DISPLAY_DESCRIPTOR_SIZE];
    vfp_gud_descriptor_t d;
    char err[200] = "";
    CHECK_EQ(vfp_gud_parse_descriptor(good_descriptor, 29, &d, err, sizeof err), 2);
    CHECK_MSG(strcmp(err, "display descriptor of 29 bytes (expected 30)") == 0, "%s", err);

    memcpy(buf, good_descriptor, sizeof buf);
    buf[4] = 2;
    CHECK_EQ(vfp_gud_parse_descriptor(buf, sizeof buf, &d, err, sizeof err), 2);
    CHECK_MSG(strcmp(err, "GUD protocol version 2 is not supported (expected 1)") == 0, "%s", err);
    buf[4] = 0;
    CHECK_EQ(vfp_gud_parse_descriptor(buf, sizeof buf, &d, err, sizeof err), 2);

    memcpy(buf, good_descriptor, sizeof buf);
    buf[14] = 0xf0, buf[15] = 0x01; /* min_width 496 > max_width 480 */
    CHECK_EQ(vfp_gud_parse_descriptor(buf, sizeof buf, &d, err, sizeof err), 2);
    CHECK_MSG(strstr(err, "bad size limits") && strstr(err, "496x1 to 480x320"), "%s", err);
}

static void set_buffer_bytes(void)
{
    vfp_gud_set_buffer_t req = {0x01020304, 5, 320, 0x0100, 0x00a00000, GUD_COMPRESSION_LZ4, 0x12345};
    uint8_t buf[GUD_SET_BUFFER_SIZE + 1];
    memset(buf, 0xee, sizeof buf);
    vfp_gud_pack_set_buffer(buf, &req);
    static const uint8_t expected[GUD_SET_BUFFER_SIZE] = {
        0x04, 0x03, 0x02, 0x01, /* x */
        0x05, 0x00, 0x00, 0x00, /* y */
        0x40, 0x01, 0x00, 0x00, /* width 320 */
        0x00, 0x01, 0x00, 0x00, /* height 256 */
        0x00, 0x00, 0xa0, 0x00, /* length */
        0x01,                   /* compression */
        0x45, 0x23, 0x01, 0x00, /* compressed_length */
    };
    CHECK(memcmp(buf, expected, sizeof expected) == 0);
    CHECK_EQ(buf[GUD_SET_BUFFER_SIZE], 0xee); /* nothing beyond 25 bytes */
}

static const vfp_gud_mode_t mode_320x240 = {6400, 320, 330, 340, 350, 240, 245, 250, 255,
                                            GUD_DISPLAY_MODE_FLAG_PREFERRED};

static void state_bytes(void)
{
    vfp_gud_property_t props[2] = {{GUD_PROPERTY_BACKLIGHT_BRIGHTNESS, 75},
                                   {GUD_PROPERTY_ROTATION, 0x0102030405060708}};
    uint8_t buf[64];
    memset(buf, 0xee, sizeof buf);
    size_t len = vfp_gud_pack_state(buf, sizeof buf, &mode_320x240, GUD_PIXEL_FORMAT_RGB565, 1, props, 2);
    static const uint8_t expected[46] = {
        0x00, 0x19, 0x00, 0x00, /* clock 6400 kHz */
        0x40, 0x01, 0x4a, 0x01, 0x54, 0x01, 0x5e, 0x01, /* 320, 330, 340, 350 */
        0xf0, 0x00, 0xf5, 0x00, 0xfa, 0x00, 0xff, 0x00, /* 240, 245, 250, 255 */
        0x00, 0x04, 0x00, 0x00, /* flags: preferred */
        0x40,                   /* format RGB565 */
        0x01,                   /* connector */
        0x0c, 0x00, 0x4b, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
        0x32, 0x00, 0x08, 0x07, 0x06, 0x05, 0x04, 0x03, 0x02, 0x01,
    };
    CHECK_EQ(len, sizeof expected);
    CHECK(memcmp(buf, expected, sizeof expected) == 0);
    CHECK_EQ(buf[len], 0xee);
    CHECK_EQ(vfp_gud_pack_state(buf, 45, &mode_320x240, GUD_PIXEL_FORMAT_RGB565, 1, props, 2), 0); /* too small */
    CHECK_EQ(vfp_gud_pack_state(buf, sizeof buf, &mode_320x240, GUD_PIXEL_FORMAT_XRGB8888, 0, NULL, 0), 26);
    CHECK_EQ(buf[24], GUD_PIXEL_FORMAT_XRGB8888);
}

static void mode_round_trip_and_pick(void)
{
    uint8_t modes[3 * GUD_DISPLAY_MODE_SIZE];
    vfp_gud_mode_t a = mode_320x240, b = mode_320x240, c = mode_320x240, got;
    a.hdisplay = 160, a.flags = 0;
    b.hdisplay = 320; /* preferred */
    c.hdisplay = 640, c.flags = 0;
    vfp_gud_pack_mode(modes, &a);
    vfp_gud_pack_mode(modes + 24, &b);
    vfp_gud_pack_mode(modes + 48, &c);
    vfp_gud_parse_mode(modes + 24, &got);
    CHECK(memcmp(&got, &b, sizeof got) == 0);

    CHECK_EQ(vfp_gud_pick_mode(modes, sizeof modes, &got), 3);
    CHECK_EQ(got.hdisplay, 320); /* the preferred one */
    b.flags = 0;
    vfp_gud_pack_mode(modes + 24, &b);
    CHECK_EQ(vfp_gud_pick_mode(modes, sizeof modes, &got), 3);
    CHECK_EQ(got.hdisplay, 160); /* none preferred: the first */
    CHECK_EQ(vfp_gud_pick_mode(modes, 0, &got), 0);
    CHECK_EQ(vfp_gud_pick_mode(modes, 30, &got), 0); /* not whole modes */
}

static void property_parse(void)
{
    static const uint8_t buf[10] = {0x32, 0x00, 0x0f, 0, 0, 0, 0, 0, 0, 0x80};
    vfp_gud_property_t p;
    vfp_gud_parse_property(buf, &p);
    CHECK_EQ(p.prop, GUD_PROPERTY_ROTATION);
    CHECK(p.val == 0x800000000000000full);
}

static void splitting(void)
{
    /* 320 pixels of RGB565 a row: 640 bytes. */
    CHECK_EQ(vfp_gud_rows_per_transfer(640, 240, 0), 240);          /* no limit given */
    CHECK_EQ(vfp_gud_rows_per_transfer(640, 240, 640 * 240), 240);  /* exactly one frame */
    CHECK_EQ(vfp_gud_rows_per_transfer(640, 240, 65536), 102);      /* 65536 / 640 */
    CHECK_EQ(vfp_gud_rows_per_transfer(640, 240, 640), 1);
    CHECK_EQ(vfp_gud_rows_per_transfer(640, 240, 639), 0);          /* a row does not fit */
    CHECK_EQ(vfp_gud_rows_per_transfer(640, 5, 1u << 20), 5);
}

static void compression_decision(void)
{
    CHECK(vfp_gud_use_lz4(GUD_COMPRESSION_LZ4, 1000, 200));
    CHECK(!vfp_gud_use_lz4(0, 1000, 200));                    /* the device does not take LZ4 */
    CHECK(!vfp_gud_use_lz4(GUD_COMPRESSION_LZ4, 1000, 1000)); /* no smaller */
    CHECK(!vfp_gud_use_lz4(GUD_COMPRESSION_LZ4, 1000, 1001));
    CHECK(!vfp_gud_use_lz4(GUD_COMPRESSION_LZ4, 1000, 0));    /* LZ4_compress_default: did not fit */
    CHECK(!vfp_gud_use_lz4(GUD_COMPRESSION_LZ4, 1000, -1));
    CHECK(vfp_gud_use_lz4(0xff, 1000, 999));
}

static void status_and_request_names(void)
{
    CHECK(strcmp(vfp_gud_status_text(GUD_STATUS_PROTOCOL_ERROR), "protocol error") == 0);
    CHECK(strcmp(vfp_gud_status_text(GUD_STATUS_INVALID_PARAMETER), "invalid parameter") == 0);
    CHECK(strcmp(vfp_gud_status_text(GUD_STATUS_BUSY), "busy") == 0);
    CHECK(strcmp(vfp_gud_status_text(0x77), "unknown status") == 0);
    CHECK(strcmp(vfp_gud_request_name(GUD_REQ_SET_BUFFER), "SET_BUFFER") == 0);
    CHECK(strcmp(vfp_gud_request_name(GUD_REQ_SET_STATE_CHECK), "STATE_CHECK") == 0);
    CHECK(strcmp(vfp_gud_request_name(GUD_REQ_GET_CONNECTOR_MODES), "GET_CONNECTOR_MODES") == 0);
}

CHECK_CASES({"descriptor_good", descriptor_good}, {"descriptor_bad_magic", descriptor_bad_magic},
            {"descriptor_bad_version_size_limits", descriptor_bad_version_size_limits},
            {"set_buffer_bytes", set_buffer_bytes}, {"state_bytes", state_bytes},
            {"mode_round_trip_and_pick", mode_round_trip_and_pick}, {"property_parse", property_parse},
            {"splitting", splitting}, {"compression_decision", compression_decision},
            {"status_and_request_names", status_and_request_names});
CHECK_RUN("display_gud")
