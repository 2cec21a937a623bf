/* SPDX-License-Identifier: MIT */
/*
 * test_display_gud_usb.c: the GUD backend against a scripted USB display, through the real libusb, with
 * umockdev standing in for the kernel: the test adds a USB device to a umockdev testbed (sysfs attributes and
 * descriptors, as libusb reads them) and answers the usbfs ioctls on /dev/bus/usb/001/011 itself (a
 * UMockdevIoctlBase "handle-ioctl" handler), playing a GUD device: it replies to the probe, records every control
 * request (request type, request, value, index, length, payload) and bulk transfer, stalls a request when told,
 * and answers ENODEV once unplugged. The cases compare the recorded conversation with the expected one byte for
 * byte.
 *
 * umockdev works by preloading libumockdev-preload.so, so the test re-executes itself under umockdev-wrapper when
 * the preload is missing (with ASan, its link-order check is turned off: the preload comes first by design).
 * Needs libumockdev-dev (VFP_HAVE_UMOCKDEV, set by the Makefile's rule for this test) and the GUD backend.
 */
#if defined(VFP_HAVE_UMOCKDEV) && defined(VFP_HAVE_GUD)

#include <errno.h>
#include <sys/ioctl.h> /* before usbdevice_fs.h, for _IOR and friends */
#include <linux/usbdevice_fs.h>
#include <pthread.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <umockdev.h>
#include <unistd.h>
#ifdef VFP_HAVE_LZ4
#include <lz4.h>
#endif

#include "check.h"
#include "display/display.h"
#include "display/gud_protocol.h"

#define DEVNODE "/dev/bus/usb/001/011"
#define SYSPATH "/sys/devices/pci0000:00/0000:00:14.0/usb1/1-3"
#define MAX_LOG 64
#define IFACE 1        /* the GUD interface; interface 0 is vendor-class too, but has no bulk OUT endpoint */
#define BULK_EP 0x03

/* One transfer the backend made: a control request (setup and, for OUT, its payload) or a bulk OUT. */
typedef struct transfer {
    int bulk;
    uint8_t type, request;
    uint16_t value, index, length;
    uint8_t data[4096];
    size_t data_len;
} transfer_t;

/* A URB submitted and not yet reaped, with the result the device gives it. */
typedef struct pending {
    UMockdevIoctlData *urb;
    int status, actual;
} pending_t;

/* The scripted device: what it answers (set by a case before open) and what it saw. Both the handler (in
 * umockdev's worker thread) and the case touch it, under the lock. */
typedef struct fake {
    pthread_mutex_t lock;
    uint8_t descriptor[GUD_DISPLAY_DESCRIPTOR_SIZE];
    uint8_t formats[4];
    int format_count;
    uint8_t modes[3 * GUD_DISPLAY_MODE_SIZE];
    int mode_bytes;
    int stall_request;    /* a SET request to stall (-1: none) */
    uint8_t stall_status; /* what GET_STATUS says after it */
    int refuse_request;   /* a SET request taken without a stall, but with a bad status (-1: none) */
    uint8_t refuse_status;
    int fail_bulk;        /* bulk transfers to stall */
    int none_connected;   /* connector 1 reports disconnected too */
    uint8_t status;       /* GUD status of the last request */
    int unplugged;        /* every ioctl fails with ENODEV */
    transfer_t log[MAX_LOG];
    int count;
    pending_t pending[8];
    int pending_count;
} fake_t;

static fake_t fake;
static UMockdevTestbed *bed;
static UMockdevIoctlBase *handler;

/* ---------------------------------------------------------------------------------------------------------- */
/* The device */

/* Device descriptor (1d50:614d or 16d0:10a9, USB 2.0, one configuration) and configuration 1: interface 0 (vendor
 * class, a bulk IN endpoint only) and interface 1 (vendor class, bulk OUT endpoint 3), as sysfs's descriptors file
 * holds them. */
static const char *device_text(int second_id)
{
    static char text[2048];
    snprintf(text, sizeof text,
             "P: /devices/pci0000:00/0000:00:14.0/usb1/1-3\n"
             "N: bus/usb/001/011\n"
             "E: SUBSYSTEM=usb\n"
             "E: DEVTYPE=usb_device\n"
             "E: DRIVER=usb\n"
             "E: BUSNUM=001\n"
             "E: DEVNUM=011\n"
             "E: DEVNAME=/dev/bus/usb/001/011\n"
             "E: PRODUCT=%s/100\n"
             "A: busnum=1\\n\n"
             "A: devnum=11\\n\n"
             "A: bConfigurationValue=1\\n\n"
             "A: speed=480\\n\n"
             "H: descriptors=1201000200000040%s000101020001"
             "09022900020100803209040000" "01ff000000" "07058102000200"
             "0904010001ff000000" "07050302000200\n",
             second_id ? "16d0/10a9" : "1d50/614d", second_id ? "d016a910" : "501d4d61");
    return text;
}

static void put32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

/* A GUD display: RGB565 and XRGB8888, rotation, connector 0 disconnected and connector 1 connected with a
 * backlight, modes 8x8 and 4x2 (preferred). */
static void fake_reset(void)
{
    for (int i = 0; i < fake.pending_count; i++)
        g_object_unref(fake.pending[i].urb);
    memset(&fake, 0, sizeof fake);
    pthread_mutex_init(&fake.lock, NULL);
    uint8_t *d = fake.descriptor;
    put32(d, GUD_DISPLAY_MAGIC);
    d[4] = 1;                  /* version */
    put32(d + 5, 0);           /* flags */
    d[9] = 0;                  /* compression */
    put32(d + 10, 0);          /* max_buffer_size: not given */
    put32(d + 14, 1);
    put32(d + 18, 64);
    put32(d + 22, 1);
    put32(d + 26, 64);
    fake.formats[0] = GUD_PIXEL_FORMAT_XRGB8888;
    fake.formats[1] = GUD_PIXEL_FORMAT_RGB565;
    fake.format_count = 2;
    vfp_gud_mode_t big = {2000, 8, 9, 10, 11, 8, 9, 10, 11, 0};
    vfp_gud_mode_t small = {1000, 4, 5, 6, 7, 2, 3, 4, 5, GUD_DISPLAY_MODE_FLAG_PREFERRED};
    vfp_gud_pack_mode(fake.modes, &big);
    vfp_gud_pack_mode(fake.modes + GUD_DISPLAY_MODE_SIZE, &small);
    fake.mode_bytes = 2 * GUD_DISPLAY_MODE_SIZE;
    fake.stall_request = -1;
    fake.refuse_request = -1;
}

/* The reply to a GET request, into out (at most cap bytes); returns its length, or -1 to stall. */
static int fake_reply(uint8_t request, uint16_t value, uint8_t *out, int cap)
{
    static const uint8_t properties[] = {0x32, 0x00, 0x0f, 0, 0, 0, 0, 0, 0, 0};          /* rotation: 0..270 */
    static const uint8_t connectors[] = {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x01, 0, 0, 0}; /* panel, panel */
    static const uint8_t connector_props[] = {0x0c, 0x00, 0x4b, 0, 0, 0, 0, 0, 0, 0};     /* backlight 75 */
    const uint8_t *src = NULL;
    int len = 0;
    uint8_t byte;
    switch (request) {
    case GUD_REQ_GET_STATUS:
        byte = fake.status, src = &byte, len = 1;
        break;
    case GUD_REQ_GET_DESCRIPTOR:
        src = fake.descriptor, len = sizeof fake.descriptor;
        break;
    case GUD_REQ_GET_FORMATS:
        src = fake.formats, len = fake.format_count;
        break;
    case GUD_REQ_GET_PROPERTIES:
        src = properties, len = sizeof properties;
        break;
    case GUD_REQ_GET_CONNECTORS:
        src = connectors, len = sizeof connectors;
        break;
    case GUD_REQ_GET_CONNECTOR_STATUS:
        byte = value == 1 && !fake.none_connected ? 0x01 : 0x00, src = &byte, len = 1;
        break;
    case GUD_REQ_GET_CONNECTOR_PROPERTIES:
        if (value != 1)
            return -1;
        src = connector_props, len = sizeof connector_props;
        break;
    case GUD_REQ_GET_CONNECTOR_MODES:
        if (value != 1)
            return -1;
        src = fake.modes, len = fake.mode_bytes;
        break;
    default:
        return -1;
    }
    if (len > cap)
        len = cap;
    memcpy(out, src, (size_t)len);
    return len;
}

static void log_transfer(int bulk, const uint8_t *setup, const uint8_t *data, size_t len)
{
    if (fake.count >= MAX_LOG)
        return;
    transfer_t *t = &fake.log[fake.count++];
    memset(t, 0, sizeof *t);
    t->bulk = bulk;
    if (setup) {
        t->type = setup[0];
        t->request = setup[1];
        t->value = (uint16_t)(setup[2] | setup[3] << 8);
        t->index = (uint16_t)(setup[4] | setup[5] << 8);
        t->length = (uint16_t)(setup[6] | setup[7] << 8);
    }
    t->data_len = len < sizeof t->data ? len : sizeof t->data;
    if (data)
        memcpy(t->data, data, t->data_len);
}

/* A submitted URB: control transfers are answered at once (the reply written into its buffer), bulk ones
 * recorded; the result is given when libusb reaps it. */
static void submit(UMockdevIoctlData *arg)
{
    UMockdevIoctlData *urb_data = umockdev_ioctl_data_resolve(arg, 0, sizeof(struct usbdevfs_urb), NULL);
    struct usbdevfs_urb *urb = (struct usbdevfs_urb *)urb_data->data;
    UMockdevIoctlData *buf = umockdev_ioctl_data_resolve(urb_data, offsetof(struct usbdevfs_urb, buffer),
                                                         (size_t)urb->buffer_length, NULL);
    uint8_t *bytes = buf->data; /* urb->buffer now points here too */
    int status = 0, actual = 0;
    if (urb->type == USBDEVFS_URB_TYPE_CONTROL && urb->buffer_length >= 8) {
        uint8_t type = bytes[0], request = bytes[1];
        uint16_t value = (uint16_t)(bytes[2] | bytes[3] << 8), length = (uint16_t)(bytes[6] | bytes[7] << 8);
        if (type & 0x80) {
            log_transfer(0, bytes, NULL, 0);
            actual = fake_reply(request, value, bytes + 8, length);
            if (actual < 0)
                status = -EPIPE, actual = 0, fake.status = GUD_STATUS_REQUEST_NOT_SUPPORTED;
        } else {
            log_transfer(0, bytes, bytes + 8, length);
            if (request == fake.stall_request)
                status = -EPIPE, fake.status = fake.stall_status;
            else
                actual = length, fake.status = request == fake.refuse_request ? fake.refuse_status : GUD_STATUS_OK;
        }
    } else {
        log_transfer(1, NULL, bytes, (size_t)urb->buffer_length);
        if (fake.fail_bulk > 0)
            fake.fail_bulk--, status = -EPIPE;
        else
            actual = urb->buffer_length;
    }
    fake.pending[fake.pending_count++] = (pending_t){urb_data, status, actual};
    g_object_unref(buf);
}

static gboolean on_ioctl(UMockdevIoctlBase *base, UMockdevIoctlClient *client, gpointer user)
{
    (void)base, (void)user;
    gulong request = umockdev_ioctl_client_get_request(client);
    UMockdevIoctlData *arg = umockdev_ioctl_client_get_arg(client);
    pthread_mutex_lock(&fake.lock);
    if (fake.unplugged) {
        pthread_mutex_unlock(&fake.lock);
        umockdev_ioctl_client_complete(client, -1, ENODEV);
        return TRUE;
    }
    long result = 0;
    int error = 0;
    switch (request) {
    case USBDEVFS_GET_CAPABILITIES: {
        UMockdevIoctlData *d = umockdev_ioctl_data_resolve(arg, 0, sizeof(uint32_t), NULL);
        *(uint32_t *)d->data = USBDEVFS_CAP_BULK_CONTINUATION | USBDEVFS_CAP_NO_PACKET_SIZE_LIM;
        g_object_unref(d);
        break;
    }
    case USBDEVFS_CLAIMINTERFACE:
    case USBDEVFS_RELEASEINTERFACE:
    case USBDEVFS_DISCONNECT_CLAIM:
    case USBDEVFS_CLEAR_HALT:
        break;
    case USBDEVFS_GETDRIVER:
    case USBDEVFS_IOCTL: /* no kernel driver to detach or attach */
        result = -1, error = ENODATA;
        break;
    case USBDEVFS_SUBMITURB:
        if (fake.pending_count < 8)
            submit(arg);
        else
            result = -1, error = ENOMEM;
        break;
    case USBDEVFS_REAPURB:
    case USBDEVFS_REAPURBNDELAY:
        if (fake.pending_count == 0) {
            result = -1, error = EAGAIN;
            break;
        }
        pending_t p = fake.pending[0];
        memmove(fake.pending, fake.pending + 1, (size_t)--fake.pending_count * sizeof p);
        struct usbdevfs_urb *urb = (struct usbdevfs_urb *)p.urb->data;
        urb->status = p.status;
        urb->actual_length = p.actual;
        UMockdevIoctlData *ptr = umockdev_ioctl_data_resolve(arg, 0, sizeof(void *), NULL);
        umockdev_ioctl_data_set_ptr(ptr, 0, p.urb);
        g_object_unref(ptr);
        g_object_unref(p.urb);
        break;
    case USBDEVFS_DISCARDURB:
        result = -1, error = EINVAL;
        break;
    default:
        fprintf(stderr, "fake GUD: unexpected ioctl 0x%lx\n", (unsigned long)request);
        result = -1, error = ENOTTY;
        break;
    }
    pthread_mutex_unlock(&fake.lock);
    umockdev_ioctl_client_complete(client, result, error);
    return TRUE;
}

static void plug_in(int second_id)
{
    GError *error = NULL;
    if (!umockdev_testbed_attach_ioctl(bed, DEVNODE, handler, &error) ||
        !umockdev_testbed_add_from_string(bed, device_text(second_id), &error)) {
        fprintf(stderr, "umockdev: %s\n", error ? error->message : "attach failed");
        exit(2);
    }
}

static void unplug(void)
{
    pthread_mutex_lock(&fake.lock);
    fake.unplugged = 1;
    pthread_mutex_unlock(&fake.lock);
    umockdev_testbed_remove_device(bed, SYSPATH);
    umockdev_testbed_detach_ioctl(bed, DEVNODE, NULL);
}

/* A fresh testbed with the device plugged in (or not). */
static void setup(int plugged)
{
    fake_reset();
    bed = umockdev_testbed_new();
    handler = umockdev_ioctl_base_new();
    g_signal_connect(handler, "handle-ioctl", G_CALLBACK(on_ioctl), NULL);
    if (plugged)
        plug_in(0);
}

static void teardown(void)
{
    g_clear_object(&handler);
    g_clear_object(&bed);
    pthread_mutex_lock(&fake.lock);
    for (int i = 0; i < fake.pending_count; i++)
        g_object_unref(fake.pending[i].urb);
    fake.pending_count = 0;
    pthread_mutex_unlock(&fake.lock);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Checking the conversation */

typedef struct expect {
    int bulk;
    uint8_t type, request;
    uint16_t value, length;
    const uint8_t *data; /* the OUT payload (control) or the bulk bytes; NULL: not checked */
    size_t data_len;
} expect_t;

#define IN(req, value, len) {0, GUD_REQTYPE_IN, req, value, len, NULL, 0}
#define OUT(req, bytes) {0, GUD_REQTYPE_OUT, req, 0, sizeof bytes, bytes, sizeof bytes}
#define OUT0(req) {0, GUD_REQTYPE_OUT, req, 0, 0, NULL, 0}
#define BULK(bytes) {1, 0, 0, 0, 0, bytes, sizeof bytes}

/* The recorded transfers from `first` on equal `expected`; a message in why otherwise. */
static int conversation_is(int first, const expect_t *expected, int count, char *why, size_t whylen)
{
    pthread_mutex_lock(&fake.lock);
    int status = 0;
    if (fake.count - first != count) {
        snprintf(why, whylen, "%d transfers, expected %d", fake.count - first, count);
        status = 1;
    }
    for (int i = 0; i < count && !status; i++) {
        const transfer_t *t = &fake.log[first + i];
        const expect_t *e = &expected[i];
        if (t->bulk != e->bulk || (!e->bulk && (t->type != e->type || t->request != e->request ||
                                                t->value != e->value || t->index != IFACE ||
                                                t->length != e->length))) {
            snprintf(why, whylen, "transfer %d: %s type %02x request %02x value %u index %u length %u", i,
                     t->bulk ? "bulk" : "control", t->type, t->request, t->value, t->index, t->length);
            status = 1;
        } else if (e->data && (t->data_len != e->data_len || memcmp(t->data, e->data, e->data_len) != 0)) {
            size_t at = 0;
            while (at < t->data_len && at < e->data_len && t->data[at] == e->data[at])
                at++;
            snprintf(why, whylen, "transfer %d (%s %02x): %zu bytes, expected %zu; byte %zu is %02x, expected %02x",
                     i, t->bulk ? "bulk" : "request", t->request, t->data_len, e->data_len, at,
                     at < t->data_len ? t->data[at] : 0, at < e->data_len ? e->data[at] : 0);
            status = 1;
        }
    }
    pthread_mutex_unlock(&fake.lock);
    return status;
}

static int transfers(void)
{
    pthread_mutex_lock(&fake.lock);
    int n = fake.count;
    pthread_mutex_unlock(&fake.lock);
    return n;
}

static vfp_board_t gud_board(vf_format_t format, const char *device)
{
    vfp_board_t b;
    memset(&b, 0, sizeof b);
    snprintf(b.display, sizeof b.display, "gud");
    snprintf(b.display_device, sizeof b.display_device, "%s", device);
    b.format = format;
    return b;
}

static const vfp_display_ops_t *gud_ops(void)
{
    return vfp_display_find("gud", NULL, NULL, 0);
}

/* The 4x2 test frame in RGB565 (little-endian words), rows 12 bytes apart (4 of them padding). */
static const uint8_t frame565[24] = {
    0x00, 0xf8, 0xe0, 0x07, 0x1f, 0x00, 0xff, 0xff, 0xee, 0xee, 0xee, 0xee,
    0x00, 0x00, 0x34, 0x12, 0x10, 0x84, 0xcd, 0xab, 0xee, 0xee, 0xee, 0xee,
};

/* The probe for connector 1 of the fake, and the state for its 4x2 mode in `format`. */
#define PROBE \
    IN(GUD_REQ_GET_DESCRIPTOR, 0, 30), IN(GUD_REQ_GET_FORMATS, 0, 32), IN(GUD_REQ_GET_PROPERTIES, 0, 320), \
    IN(GUD_REQ_GET_CONNECTORS, 0, 160), IN(GUD_REQ_GET_CONNECTOR_STATUS, 0, 1), \
    IN(GUD_REQ_GET_CONNECTOR_STATUS, 1, 1), IN(GUD_REQ_GET_CONNECTOR_PROPERTIES, 1, 320), \
    IN(GUD_REQ_GET_CONNECTOR_MODES, 1, 3072)
#define STATE(format) \
    {0xe8, 0x03, 0x00, 0x00, 0x04, 0x00, 0x05, 0x00, 0x06, 0x00, 0x07, 0x00, 0x02, 0x00, 0x03, 0x00, 0x04, 0x00, \
     0x05, 0x00, 0x00, 0x04, 0x00, 0x00, format, 0x01, 0x0c, 0x00, 0x4b, 0, 0, 0, 0, 0, 0, 0, 0x32, 0x00, 0x01, 0, \
     0, 0, 0, 0, 0, 0}

static const uint8_t one[1] = {1}, zero[1] = {0};

/* ---------------------------------------------------------------------------------------------------------- */
/* Cases */

static void probe_and_frame(void)
{
    setup(1);
    vfp_display_t d = {gud_ops(), 0, 0, 0, NULL};
    vfp_board_t b = gud_board(VF_FORMAT_RGB565, "");
    char err[256] = "", why[256] = "";
    int opened = d.ops->open(&d, &b, err, sizeof err);
    int presented = opened ? -1 : (int)d.ops->present(&d, 0, 0, 4, 2, frame565, 12, err, sizeof err);
    int partial = opened ? -1 : (int)d.ops->present(&d, 1, 1, 2, 1, frame565, 12, err, sizeof err);
    vfp_display_t opened_as = d;
    d.ops->close(&d);
    static const uint8_t state[] = STATE(GUD_PIXEL_FORMAT_RGB565);
    static const uint8_t set_buffer[] = {0, 0, 0, 0, 0, 0, 0, 0, 4, 0, 0, 0, 2, 0, 0, 0, 16, 0, 0, 0, 0, 0, 0, 0, 0};
    static const uint8_t pixels[] = {0x00, 0xf8, 0xe0, 0x07, 0x1f, 0x00, 0xff, 0xff,
                                     0x00, 0x00, 0x34, 0x12, 0x10, 0x84, 0xcd, 0xab};
    static const uint8_t set_buffer_part[] = {1, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0, 1, 0, 0, 0,
                                              4, 0, 0, 0, 0, 0, 0, 0, 0};
    static const uint8_t pixels_part[] = {0x34, 0x12, 0x10, 0x84};
    static const expect_t expected[] = {
        PROBE,
        OUT(GUD_REQ_SET_STATE_CHECK, state),
        OUT(GUD_REQ_SET_CONTROLLER_ENABLE, one),
        OUT0(GUD_REQ_SET_STATE_COMMIT),
        OUT(GUD_REQ_SET_DISPLAY_ENABLE, one),
        OUT(GUD_REQ_SET_BUFFER, set_buffer),
        BULK(pixels),
        OUT(GUD_REQ_SET_BUFFER, set_buffer_part),
        BULK(pixels_part),
        OUT(GUD_REQ_SET_DISPLAY_ENABLE, zero),
        OUT(GUD_REQ_SET_CONTROLLER_ENABLE, zero),
    };
    int differs = conversation_is(0, expected, sizeof expected / sizeof expected[0], why, sizeof why);
    teardown();
    CHECK_MSG(opened == 0, "open: %s", err);
    CHECK_MSG(presented == 0 && partial == 0, "present: %s", err);
    CHECK_EQ(opened_as.width, 4);
    CHECK_EQ(opened_as.height, 2);
    CHECK_EQ(opened_as.format, VF_FORMAT_RGB565);
    CHECK(d.priv == NULL);
    CHECK_MSG(!differs, "%s", why);
}

static void xrgb8888_when_asked(void)
{
    setup(1);
    vfp_display_t d = {gud_ops(), 0, 0, 0, NULL};
    vfp_board_t b = gud_board(VF_FORMAT_XRGB8888, "1d50:614d");
    char err[256] = "", why[256] = "";
    static const uint32_t frame[8] = {0xff102030, 0xff405060, 0xff708090, 0xffa0b0c0,
                                      0xff000000, 0xffffffff, 0xff123456, 0xff654321};
    int opened = d.ops->open(&d, &b, err, sizeof err);
    vf_format_t format = d.format;
    int presented = opened ? -1 : (int)d.ops->present(&d, 0, 0, 4, 2, frame, 16, err, sizeof err);
    d.ops->close(&d);
    static const uint8_t state[] = STATE(GUD_PIXEL_FORMAT_XRGB8888);
    static const uint8_t set_buffer[] = {0, 0, 0, 0, 0, 0, 0, 0, 4, 0, 0, 0, 2, 0, 0, 0, 32, 0, 0, 0, 0, 0, 0, 0, 0};
    static const uint8_t pixels[] = {0x30, 0x20, 0x10, 0xff, 0x60, 0x50, 0x40, 0xff, 0x90, 0x80, 0x70, 0xff,
                                     0xc0, 0xb0, 0xa0, 0xff, 0x00, 0x00, 0x00, 0xff, 0xff, 0xff, 0xff, 0xff,
                                     0x56, 0x34, 0x12, 0xff, 0x21, 0x43, 0x65, 0xff};
    static const expect_t expected[] = {
        PROBE,
        OUT(GUD_REQ_SET_STATE_CHECK, state),
        OUT(GUD_REQ_SET_CONTROLLER_ENABLE, one),
        OUT0(GUD_REQ_SET_STATE_COMMIT),
        OUT(GUD_REQ_SET_DISPLAY_ENABLE, one),
        OUT(GUD_REQ_SET_BUFFER, set_buffer),
        BULK(pixels),
        OUT(GUD_REQ_SET_DISPLAY_ENABLE, zero),
        OUT(GUD_REQ_SET_CONTROLLER_ENABLE, zero),
    };
    int differs = conversation_is(0, expected, sizeof expected / sizeof expected[0], why, sizeof why);
    teardown();
    CHECK_MSG(opened == 0 && presented == 0, "%s", err);
    CHECK_EQ(format, VF_FORMAT_XRGB8888);
    CHECK_MSG(!differs, "%s", why);
}

/* A device whose buffer holds one row: the frame goes as two bands. */
static void split_to_buffer(void)
{
    setup(1);
    put32(fake.descriptor + 10, 8); /* max_buffer_size */
    vfp_display_t d = {gud_ops(), 0, 0, 0, NULL};
    vfp_board_t b = gud_board(VF_FORMAT_RGB565, "");
    char err[256] = "", why[256] = "";
    int opened = d.ops->open(&d, &b, err, sizeof err);
    int first = transfers();
    int presented = opened ? -1 : (int)d.ops->present(&d, 0, 0, 4, 2, frame565, 12, err, sizeof err);
    int too_wide = -1;
    d.ops->close(&d);
    static const uint8_t band0[] = {0, 0, 0, 0, 0, 0, 0, 0, 4, 0, 0, 0, 1, 0, 0, 0, 8, 0, 0, 0, 0, 0, 0, 0, 0};
    static const uint8_t band1[] = {0, 0, 0, 0, 1, 0, 0, 0, 4, 0, 0, 0, 1, 0, 0, 0, 8, 0, 0, 0, 0, 0, 0, 0, 0};
    static const uint8_t row0[] = {0x00, 0xf8, 0xe0, 0x07, 0x1f, 0x00, 0xff, 0xff};
    static const uint8_t row1[] = {0x00, 0x00, 0x34, 0x12, 0x10, 0x84, 0xcd, 0xab};
    static const expect_t expected[] = {
        OUT(GUD_REQ_SET_BUFFER, band0), BULK(row0), OUT(GUD_REQ_SET_BUFFER, band1), BULK(row1),
        OUT(GUD_REQ_SET_DISPLAY_ENABLE, zero), OUT(GUD_REQ_SET_CONTROLLER_ENABLE, zero),
    };
    int differs = conversation_is(first, expected, sizeof expected / sizeof expected[0], why, sizeof why);

    /* a buffer smaller than a row cannot take anything */
    fake_reset();
    put32(fake.descriptor + 10, 6);
    if (d.ops->open(&d, &b, err, sizeof err) == 0)
        too_wide = d.ops->present(&d, 0, 0, 4, 2, frame565, 12, err, sizeof err);
    d.ops->close(&d);
    teardown();
    CHECK_MSG(opened == 0 && presented == 0, "%s", err);
    CHECK_MSG(!differs, "%s", why);
    CHECK_EQ(too_wide, VFP_ERR);
    CHECK_MSG(strcmp(err, "1d50:614d: a row of 4 pixels (8 bytes) is larger than the device's 6-byte buffer") == 0,
              "%s", err);
}

static void lz4_when_smaller(void)
{
#ifdef VFP_HAVE_LZ4
    setup(1);
    fake.descriptor[9] = GUD_COMPRESSION_LZ4;
    vfp_gud_mode_t mode = {9000, 64, 65, 66, 67, 16, 17, 18, 19, GUD_DISPLAY_MODE_FLAG_PREFERRED};
    vfp_gud_pack_mode(fake.modes, &mode);
    fake.mode_bytes = GUD_DISPLAY_MODE_SIZE;
    vfp_display_t d = {gud_ops(), 0, 0, 0, NULL};
    vfp_board_t b = gud_board(VF_FORMAT_RGB565, "");
    char err[256] = "";
    static uint8_t frame[64 * 16 * 2];
    for (size_t i = 0; i < sizeof frame; i++)
        frame[i] = (uint8_t)(i / 64); /* compresses well */
    int opened = d.ops->open(&d, &b, err, sizeof err);
    int first = transfers();
    int presented = opened ? -1 : (int)d.ops->present(&d, 0, 0, 64, 16, frame, 128, err, sizeof err);
    int small = opened ? -1 : (int)d.ops->present(&d, 0, 0, 1, 1, frame, 128, err, sizeof err); /* 2 bytes: raw */
    d.ops->close(&d);
    pthread_mutex_lock(&fake.lock);
    transfer_t set = fake.log[first], bulk = fake.log[first + 1], set_small = fake.log[first + 2],
               bulk_small = fake.log[first + 3];
    pthread_mutex_unlock(&fake.lock);
    teardown();
    CHECK_MSG(opened == 0 && presented == 0 && small == 0, "%s", err);
    CHECK_EQ(set.request, GUD_REQ_SET_BUFFER);
    CHECK_EQ(set.data[16] | set.data[17] << 8, 2048); /* length */
    CHECK_EQ(set.data[20], GUD_COMPRESSION_LZ4);
    uint32_t packed = set.data[21] | set.data[22] << 8 | (uint32_t)set.data[23] << 16;
    CHECK(bulk.bulk && bulk.data_len == packed && packed < 2048);
    static char unpacked[2048];
    CHECK_EQ(LZ4_decompress_safe((const char *)bulk.data, unpacked, (int)packed, sizeof unpacked), 2048);
    CHECK(memcmp(unpacked, frame, sizeof frame) == 0);
    CHECK_EQ(set_small.data[20], 0); /* LZ4 would not make 2 bytes smaller */
    CHECK(bulk_small.bulk && bulk_small.data_len == 2);
#endif
}

/* STATUS_ON_SET: GET_STATUS after every SET, and a bad status fails the request without a stall. */
static void status_after_set(void)
{
    setup(1);
    put32(fake.descriptor + 5, GUD_DISPLAY_FLAG_STATUS_ON_SET);
    vfp_display_t d = {gud_ops(), 0, 0, 0, NULL};
    vfp_board_t b = gud_board(VF_FORMAT_RGB565, "");
    char err[256] = "", refused[256] = "", why[256] = "";
    int opened = d.ops->open(&d, &b, err, sizeof err);
    int presented = opened ? -1 : (int)d.ops->present(&d, 0, 0, 4, 2, frame565, 12, err, sizeof err);
    d.ops->close(&d);
    static const uint8_t state[] = STATE(GUD_PIXEL_FORMAT_RGB565);
    static const uint8_t set_buffer[] = {0, 0, 0, 0, 0, 0, 0, 0, 4, 0, 0, 0, 2, 0, 0, 0, 16, 0, 0, 0, 0, 0, 0, 0, 0};
    static const expect_t expected[] = {
        PROBE,
        OUT(GUD_REQ_SET_STATE_CHECK, state), IN(GUD_REQ_GET_STATUS, 0, 1),
        OUT(GUD_REQ_SET_CONTROLLER_ENABLE, one), IN(GUD_REQ_GET_STATUS, 0, 1),
        OUT0(GUD_REQ_SET_STATE_COMMIT), IN(GUD_REQ_GET_STATUS, 0, 1),
        OUT(GUD_REQ_SET_DISPLAY_ENABLE, one), IN(GUD_REQ_GET_STATUS, 0, 1),
        OUT(GUD_REQ_SET_BUFFER, set_buffer), IN(GUD_REQ_GET_STATUS, 0, 1),
        {1, 0, 0, 0, 0, NULL, 0},
        OUT(GUD_REQ_SET_DISPLAY_ENABLE, zero), IN(GUD_REQ_GET_STATUS, 0, 1),
        OUT(GUD_REQ_SET_CONTROLLER_ENABLE, zero), IN(GUD_REQ_GET_STATUS, 0, 1),
    };
    int differs = conversation_is(0, expected, sizeof expected / sizeof expected[0], why, sizeof why);

    fake_reset();
    put32(fake.descriptor + 5, GUD_DISPLAY_FLAG_STATUS_ON_SET);
    fake.refuse_request = GUD_REQ_SET_STATE_CHECK;
    fake.refuse_status = GUD_STATUS_INVALID_PARAMETER;
    int check = d.ops->open(&d, &b, refused, sizeof refused);
    d.ops->close(&d);
    teardown();
    CHECK_MSG(opened == 0 && presented == 0, "%s", err);
    CHECK_MSG(!differs, "%s", why);
    CHECK_EQ(check, VFP_ERR);
    CHECK_MSG(strcmp(refused, "1d50:614d: STATE_CHECK failed: device status 4 (invalid parameter)") == 0, "%s",
              refused);
}

/* FULL_UPDATE: whole frames from a kept copy, SET_BUFFER only after a failed transfer. */
static void full_update(void)
{
    setup(1);
    put32(fake.descriptor + 5, GUD_DISPLAY_FLAG_FULL_UPDATE);
    vfp_display_t d = {gud_ops(), 0, 0, 0, NULL};
    vfp_board_t b = gud_board(VF_FORMAT_RGB565, "");
    char err[256] = "", failed[256] = "", why[256] = "";
    static const uint8_t other[24] = {[12 + 4] = 0x99, [12 + 5] = 0x88, [12 + 6] = 0x77, [12 + 7] = 0x66};
    int opened = d.ops->open(&d, &b, err, sizeof err);
    int first = transfers();
    int full = opened ? -1 : (int)d.ops->present(&d, 0, 0, 4, 2, frame565, 12, err, sizeof err);
    int part = opened ? -1 : (int)d.ops->present(&d, 2, 1, 2, 1, other, 12, err, sizeof err);
    pthread_mutex_lock(&fake.lock);
    fake.fail_bulk = 1;
    pthread_mutex_unlock(&fake.lock);
    int broken = opened ? -1 : (int)d.ops->present(&d, 0, 0, 1, 1, frame565, 12, failed, sizeof failed);
    int after = opened ? -1 : (int)d.ops->present(&d, 0, 0, 1, 1, frame565, 12, err, sizeof err);
    d.ops->close(&d);
    static const uint8_t pixels[] = {0x00, 0xf8, 0xe0, 0x07, 0x1f, 0x00, 0xff, 0xff,
                                     0x00, 0x00, 0x34, 0x12, 0x10, 0x84, 0xcd, 0xab};
    static const uint8_t updated[] = {0x00, 0xf8, 0xe0, 0x07, 0x1f, 0x00, 0xff, 0xff,
                                      0x00, 0x00, 0x34, 0x12, 0x99, 0x88, 0x77, 0x66};
    static const uint8_t set_buffer[] = {0, 0, 0, 0, 0, 0, 0, 0, 4, 0, 0, 0, 2, 0, 0, 0, 16, 0, 0, 0, 0, 0, 0, 0, 0};
    static const expect_t expected[] = {
        BULK(pixels), BULK(updated), BULK(updated), OUT(GUD_REQ_SET_BUFFER, set_buffer), BULK(updated),
        OUT(GUD_REQ_SET_DISPLAY_ENABLE, zero), OUT(GUD_REQ_SET_CONTROLLER_ENABLE, zero),
    };
    int differs = conversation_is(first, expected, sizeof expected / sizeof expected[0], why, sizeof why);
    teardown();
    CHECK_MSG(opened == 0 && full == 0 && part == 0 && after == 0, "%s", err);
    CHECK_EQ(broken, VFP_ERR);
    CHECK_MSG(strstr(failed, "1d50:614d: bulk transfer failed: ") != NULL, "%s", failed);
    CHECK_MSG(!differs, "%s", why);
}

static void stall_gives_status(void)
{
    setup(1);
    fake.stall_request = GUD_REQ_SET_BUFFER;
    fake.stall_status = GUD_STATUS_INVALID_PARAMETER;
    vfp_display_t d = {gud_ops(), 0, 0, 0, NULL};
    vfp_board_t b = gud_board(VF_FORMAT_RGB565, "");
    char err[256] = "", why[256] = "";
    int opened = d.ops->open(&d, &b, err, sizeof err);
    int first = transfers();
    int presented = opened ? -1 : (int)d.ops->present(&d, 0, 0, 4, 2, frame565, 12, err, sizeof err);
    static const uint8_t set_buffer[] = {0, 0, 0, 0, 0, 0, 0, 0, 4, 0, 0, 0, 2, 0, 0, 0, 16, 0, 0, 0, 0, 0, 0, 0, 0};
    static const expect_t expected[] = {OUT(GUD_REQ_SET_BUFFER, set_buffer), IN(GUD_REQ_GET_STATUS, 0, 1)};
    int differs = conversation_is(first, expected, 2, why, sizeof why);
    d.ops->close(&d);
    teardown();
    CHECK_MSG(opened == 0, "%s", err);
    CHECK_EQ(presented, VFP_ERR);
    CHECK_MSG(strcmp(err, "1d50:614d: SET_BUFFER stalled: device status 4 (invalid parameter)") == 0, "%s", err);
    CHECK_MSG(!differs, "%s", why);
}

/* Unplugged: present says VFP_DISPLAY_LOST, close sends nothing, open finds nothing; plugged in again, open
 * finds it and frames flow. */
static void unplug_and_replug(void)
{
    setup(1);
    vfp_display_t d = {gud_ops(), 0, 0, 0, NULL};
    vfp_board_t b = gud_board(VF_FORMAT_RGB565, "");
    char err[256] = "", lost_err[256] = "", missing_err[256] = "";
    int opened = d.ops->open(&d, &b, err, sizeof err);
    int before = opened ? -1 : (int)d.ops->present(&d, 0, 0, 4, 2, frame565, 12, err, sizeof err);
    unplug();
    int after = opened ? -1 : (int)d.ops->present(&d, 0, 0, 4, 2, frame565, 12, lost_err, sizeof lost_err);
    int again = opened ? -1 : (int)d.ops->present(&d, 0, 0, 4, 2, frame565, 12, err, sizeof err);
    int sent = transfers();
    d.ops->close(&d);
    int sent_by_close = transfers() - sent;
    int missing = d.ops->open(&d, &b, missing_err, sizeof missing_err);
    d.ops->close(&d);

    fake_reset();
    plug_in(0);
    int reopened = d.ops->open(&d, &b, err, sizeof err);
    int first = transfers();
    int presented = reopened ? -1 : (int)d.ops->present(&d, 0, 0, 4, 2, frame565, 12, err, sizeof err);
    int frames = transfers() - first;
    d.ops->close(&d);
    teardown();
    CHECK_MSG(opened == 0 && before == 0, "%s", err);
    CHECK_EQ(after, VFP_DISPLAY_LOST);
    CHECK_MSG(strstr(lost_err, "1d50:614d: display gone (SET_BUFFER: ") != NULL, "%s", lost_err);
    CHECK_EQ(again, VFP_DISPLAY_LOST);
    CHECK_EQ(sent_by_close, 0);
    CHECK_EQ(missing, VFP_ERR);
    CHECK_MSG(strcmp(missing_err, "no GUD display found (VID:PID 1d50:614d or 16d0:10a9): is it plugged in?") == 0,
              "%s", missing_err);
    CHECK_MSG(reopened == 0 && presented == 0, "%s", err);
    CHECK_EQ(frames, 2); /* SET_BUFFER and the bulk transfer */
}

static void missing_or_other_id(void)
{
    setup(0);
    vfp_display_t d = {gud_ops(), 0, 0, 0, NULL};
    char err[256] = "", err_id[256] = "", err_syntax[256] = "", err_second[256] = "";
    vfp_board_t b = gud_board(VF_FORMAT_RGB565, "");
    int missing = d.ops->open(&d, &b, err, sizeof err);
    plug_in(1); /* 16d0:10a9 */
    b = gud_board(VF_FORMAT_RGB565, "1d50:614d");
    int other = d.ops->open(&d, &b, err_id, sizeof err_id);
    b = gud_board(VF_FORMAT_RGB565, "1d50-614d");
    int syntax = d.ops->open(&d, &b, err_syntax, sizeof err_syntax);
    b = gud_board(VF_FORMAT_RGB565, "");
    int second = d.ops->open(&d, &b, err_second, sizeof err_second);
    d.ops->close(&d);
    teardown();
    CHECK_EQ(missing, VFP_ERR);
    CHECK_MSG(strcmp(err, "no GUD display found (VID:PID 1d50:614d or 16d0:10a9): is it plugged in?") == 0, "%s",
              err);
    CHECK_EQ(other, VFP_ERR);
    CHECK_MSG(strcmp(err_id, "no GUD display found (VID:PID 1d50:614d): is it plugged in?") == 0, "%s", err_id);
    CHECK_EQ(syntax, VFP_ERR);
    CHECK_MSG(strcmp(err_syntax, "display.device '1d50-614d': expected VID:PID in hex, like 1d50:614d") == 0, "%s",
              err_syntax);
    CHECK_MSG(second == 0, "the second ID: %s", err_second);
}

static void bad_magic(void)
{
    setup(1);
    put32(fake.descriptor, 0xdeadbeef);
    vfp_display_t d = {gud_ops(), 0, 0, 0, NULL};
    vfp_board_t b = gud_board(VF_FORMAT_RGB565, "");
    char err[256] = "", why[256] = "";
    int opened = d.ops->open(&d, &b, err, sizeof err);
    static const expect_t expected[] = {IN(GUD_REQ_GET_DESCRIPTOR, 0, 30)};
    int differs = conversation_is(0, expected, 1, why, sizeof why);
    d.ops->close(&d);
    teardown();
    CHECK_EQ(opened, VFP_ERR);
    CHECK(d.priv == NULL);
    CHECK_MSG(strcmp(err, "1d50:614d: not a GUD display: descriptor magic 0xdeadbeef (expected 0x1d50614d)") == 0,
              "%s", err);
    CHECK_MSG(!differs, "%s", why);
}

static void no_format_or_connector(void)
{
    setup(1);
    fake.formats[0] = 0x08, fake.formats[1] = 0x01; /* R8 and R1 only */
    vfp_display_t d = {gud_ops(), 0, 0, 0, NULL};
    vfp_board_t b = gud_board(VF_FORMAT_RGB565, "");
    char err[256] = "", err_connector[256] = "";
    int no_format = d.ops->open(&d, &b, err, sizeof err);
    fake_reset();
    fake.none_connected = 1;
    int no_connector = d.ops->open(&d, &b, err_connector, sizeof err_connector);
    teardown();
    CHECK_EQ(no_format, VFP_ERR);
    CHECK_MSG(strcmp(err, "1d50:614d: the display takes neither RGB565 nor XRGB8888 (it lists 2 other formats)") ==
              0, "%s", err);
    CHECK_EQ(no_connector, VFP_ERR);
    CHECK_MSG(strcmp(err_connector, "1d50:614d: none of its 2 connectors has a display connected") == 0, "%s",
              err_connector);
}

CHECK_CASES({"probe_and_frame", probe_and_frame}, {"xrgb8888_when_asked", xrgb8888_when_asked},
            {"split_to_buffer", split_to_buffer}, {"lz4_when_smaller", lz4_when_smaller},
            {"stall_gives_status", stall_gives_status}, {"status_after_set", status_after_set},
            {"full_update", full_update}, {"unplug_and_replug", unplug_and_replug},
            {"missing_or_other_id", missing_or_other_id}, {"bad_magic", bad_magic},
            {"no_format_or_connector", no_format_or_connector});

int main(int argc, char **argv)
{
    const char *preload = getenv("LD_PRELOAD");
    if (!preload || !strstr(preload, "libumockdev-preload")) {
        if (getenv("VOLFIX_UMOCKDEV_REEXEC")) {
            printf("not ok - display_gud_usb/umockdev: umockdev-wrapper did not preload libumockdev-preload\n");
            return 1;
        }
        setenv("VOLFIX_UMOCKDEV_REEXEC", "1", 1);
        /* umockdev redirects /sys and /dev through a preloaded library: run again with it. */
        const char *asan = getenv("ASAN_OPTIONS");
        char options[512];
        snprintf(options, sizeof options, "%s%sverify_asan_link_order=0", asan ? asan : "", asan ? ":" : "");
        setenv("ASAN_OPTIONS", options, 1);
        char self[4096];
        ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
        self[n > 0 ? n : 0] = 0;
        char **args = calloc((size_t)argc + 2, sizeof *args);
        args[0] = "umockdev-wrapper";
        args[1] = n > 0 ? self : argv[0];
        for (int i = 1; i < argc; i++)
            args[i + 1] = argv[i];
        execvp(args[0], args);
        printf("not ok - display_gud_usb/umockdev: cannot run umockdev-wrapper: %s\n", strerror(errno));
        return 1;
    }
    return check_main("display_gud_usb", check_cases_, (int)(sizeof check_cases_ / sizeof check_cases_[0]), argc,
                      argv);
}

#else
#include <stdio.h>

/* Built without libusb or umockdev: make test installs both (tools/deps.sh test), so this is a broken set-up, not
 * a reason to skip. Cross builds without umockdev leave this suite out altogether (Makefile). */
int main(void)
{
    printf("not ok - display_gud_usb: built without the GUD backend or umockdev (install libusb-1.0-0-dev and "
           "libumockdev-dev: sh tools/deps.sh test)\n");
    return 1;
}
#endif
