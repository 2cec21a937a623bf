/* SPDX-License-Identifier: MIT */
/*
 * gud_gadget.c: a GUD (Generic USB Display) device in user space, for make test-hw (tests/hw/README.md).
 *
 * Inside the test VM the kernel's dummy_hcd connects a USB device controller (dummy_udc) to a USB host
 * controller in the same machine. This program makes a USB device on the device side through configfs
 * (libcomposite) and FunctionFS: one vendor-specific interface with one bulk OUT endpoint, and control requests
 * on endpoint 0 answered here, as a GUD display would. The host side (test_gud.c, through the "gud" display
 * backend and libusb) then sees a GUD display of a given size that takes RGB565.
 *
 * It writes what it saw into a directory the test reads:
 *   DIR/ready    once the gadget is bound to the UDC (the host will enumerate it)
 *   DIR/log      one line per control request and bulk transfer: "SET_BUFFER x=0 y=0 w=64 h=48 length=6144
 *                compression=0 compressed_length=0 status=0", "BULK bytes=6144 frame=1 status=0", ...
 *                status is the GUD status the request got (0 ok; anything else is a refusal, with why=...)
 *   DIR/frame    the device's framebuffer (width * height RGB565 little-endian pixels), rewritten after every
 *                bulk transfer, and DIR/frames the number of transfers applied so far (written after frame)
 *
 * Usage: gud_gadget --dir DIR [--vid 0x1d50] [--pid 0x614d] [--size 64x48] [--lz4] [--max-buffer BYTES]
 *                   [--status-on-set] [--full-update] [--udc NAME] [--name GADGET]
 * --full-update sets GUD_DISPLAY_FLAG_FULL_UPDATE: every bulk transfer is then a whole uncompressed frame, with no
 * SET_BUFFER before it (one comes only after a failed transfer, and must then cover the whole display).
 * It runs until SIGTERM or SIGINT, then unbinds and removes the gadget.
 *
 * The protocol constants come from port/display/gud_protocol.h (written from the kernel's include/drm/gud.h); the
 * replies are packed here byte by byte, independently of display_gud.c's helpers, so that a wrong layout on one
 * side is not hidden by the same mistake on the other.
 */
#define _GNU_SOURCE
#include <endian.h>
#include <errno.h>
#include <fcntl.h>
#include <linux/usb/ch9.h>
#include <linux/usb/functionfs.h>
#include <pthread.h>
#include <signal.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#ifdef VFP_HAVE_LZ4
#include <lz4.h>
#endif

#include "display/gud_protocol.h"
#include "hwtest.h"

/* Requests gud_protocol.h has no name for (the host may send them; the gadget answers or refuses them). */
#ifndef GUD_REQ_GET_CONNECTOR_TV_MODE_VALUES
#define GUD_REQ_GET_CONNECTOR_TV_MODE_VALUES 0x52
#endif
#ifndef GUD_REQ_SET_CONNECTOR_FORCE_DETECT
#define GUD_REQ_SET_CONNECTOR_FORCE_DETECT 0x53
#endif
#ifndef GUD_REQ_GET_CONNECTOR_EDID
#define GUD_REQ_GET_CONNECTOR_EDID 0x56
#endif
#define GUD_CONNECTOR_TYPE_PANEL 0

#define QUEUE_LEN 64

typedef struct set_buffer {
    uint32_t x, y, w, h, length, compressed_length;
    uint8_t compression;
} set_buffer_t;

static struct {
    /* configuration */
    const char *dir, *udc, *name;
    unsigned vid, pid, width, height, max_buffer;
    int lz4, status_on_set, full_update;
    char gadget[256], ffs_mount[256];
    /* files */
    int ep0, ep1;
    FILE *log;
    /* state, under lock */
    pthread_mutex_t lock;
    pthread_cond_t cond;
    set_buffer_t queue[QUEUE_LEN];
    unsigned q_head, q_count;
    uint8_t last_status;
    int checked, committed, controller_enabled, display_enabled;
    unsigned frames;
    uint16_t *fb; /* width * height, little-endian on the wire and in the file */
    volatile sig_atomic_t quit;
    pthread_t bulk_thread;
} g = {
    .vid = GUD_VID_OPENMOKO,
    .pid = GUD_PID_OPENMOKO,
    .width = 64,
    .height = 48,
    .name = "volfix-gud",
    .ep0 = -1,
    .ep1 = -1,
    .lock = PTHREAD_MUTEX_INITIALIZER,
    .cond = PTHREAD_COND_INITIALIZER,
};

static void die(const char *fmt, ...) __attribute__((format(printf, 1, 2), noreturn));
static void die(const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "gud_gadget: ");
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\n");
    exit(1);
}

static void logline(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static void logline(const char *fmt, ...)
{
    va_list ap;
    pthread_mutex_lock(&g.lock);
    va_start(ap, fmt);
    vfprintf(g.log, fmt, ap);
    va_end(ap);
    fputc('\n', g.log);
    fflush(g.log);
    pthread_mutex_unlock(&g.lock);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* configfs and FunctionFS */

static void gpath(char *buf, size_t cap, const char *rel)
{
    snprintf(buf, cap, "%s/%s", g.gadget, rel);
}

static void gwrite(const char *rel, const char *text)
{
    char path[512], err[600];
    gpath(path, sizeof path, rel);
    if (hw_write_file(path, text, err, sizeof err) != 0)
        die("%s", err);
}

static void gmkdir(const char *rel)
{
    char path[512];
    gpath(path, sizeof path, rel);
    if (mkdir(path, 0755) != 0 && errno != EEXIST)
        die("mkdir %s: %s", path, strerror(errno));
}

static void teardown_configfs(void)
{
    char path[512], err[600];
    gpath(path, sizeof path, "UDC");
    if (access(path, F_OK) == 0)
        hw_write_file(path, "\n", err, sizeof err); /* unbind: fails harmlessly when not bound */
    gpath(path, sizeof path, "configs/c.1/ffs.gud");
    unlink(path);
    static const char *const dirs[] = {"configs/c.1/strings/0x409", "configs/c.1", "functions/ffs.gud",
                                       "strings/0x409", ""};
    for (size_t i = 0; i < sizeof dirs / sizeof dirs[0]; i++) {
        gpath(path, sizeof path, dirs[i]);
        rmdir(path);
    }
}

static void setup_configfs(void)
{
    char text[64];
    snprintf(g.gadget, sizeof g.gadget, "/sys/kernel/config/usb_gadget/%s", g.name);
    if (access("/sys/kernel/config/usb_gadget", F_OK) != 0)
        die("/sys/kernel/config/usb_gadget: %s (configfs mounted? libcomposite loaded?)", strerror(errno));
    teardown_configfs(); /* a gadget left by an earlier run */
    if (mkdir(g.gadget, 0755) != 0)
        die("mkdir %s: %s", g.gadget, strerror(errno));
    snprintf(text, sizeof text, "0x%04x", g.vid);
    gwrite("idVendor", text);
    snprintf(text, sizeof text, "0x%04x", g.pid);
    gwrite("idProduct", text);
    gwrite("bcdDevice", "0x0100");
    gwrite("bcdUSB", "0x0200");
    gmkdir("strings/0x409");
    gwrite("strings/0x409/manufacturer", "volfix");
    gwrite("strings/0x409/product", "volfix GUD test gadget");
    gwrite("strings/0x409/serialnumber", "0001");
    gmkdir("configs/c.1");
    gmkdir("configs/c.1/strings/0x409");
    gwrite("configs/c.1/strings/0x409/configuration", "GUD");
    gwrite("configs/c.1/MaxPower", "100");
    gmkdir("functions/ffs.gud");
    char from[512], to[512];
    gpath(from, sizeof from, "functions/ffs.gud");
    gpath(to, sizeof to, "configs/c.1/ffs.gud");
    if (symlink(from, to) != 0)
        die("symlink %s: %s", to, strerror(errno));
}

static void write_descriptors(void)
{
    struct {
        struct usb_functionfs_descs_head_v2 header;
        __le32 fs_count, hs_count;
        struct {
            struct usb_interface_descriptor intf;
            struct usb_endpoint_descriptor_no_audio out;
        } __attribute__((packed)) fs, hs;
    } __attribute__((packed)) d;
    memset(&d, 0, sizeof d);
    d.header.magic = htole32(FUNCTIONFS_DESCRIPTORS_MAGIC_V2);
    d.header.flags = htole32(FUNCTIONFS_HAS_FS_DESC | FUNCTIONFS_HAS_HS_DESC);
    d.header.length = htole32(sizeof d);
    d.fs_count = htole32(2);
    d.hs_count = htole32(2);
    d.fs.intf.bLength = USB_DT_INTERFACE_SIZE;
    d.fs.intf.bDescriptorType = USB_DT_INTERFACE;
    d.fs.intf.bNumEndpoints = 1;
    d.fs.intf.bInterfaceClass = USB_CLASS_VENDOR_SPEC;
    d.fs.intf.iInterface = 1;
    d.fs.out.bLength = USB_DT_ENDPOINT_SIZE;
    d.fs.out.bDescriptorType = USB_DT_ENDPOINT;
    d.fs.out.bEndpointAddress = 1 | USB_DIR_OUT;
    d.fs.out.bmAttributes = USB_ENDPOINT_XFER_BULK;
    d.fs.out.wMaxPacketSize = htole16(64);
    d.hs = d.fs;
    d.hs.out.wMaxPacketSize = htole16(512);

    static const char str[] = "volfix GUD";
    struct {
        struct usb_functionfs_strings_head header;
        __le16 code;
        char str[sizeof str];
    } __attribute__((packed)) s;
    s.header.magic = htole32(FUNCTIONFS_STRINGS_MAGIC);
    s.header.length = htole32(sizeof s);
    s.header.str_count = htole32(1);
    s.header.lang_count = htole32(1);
    s.code = htole16(0x0409);
    memcpy(s.str, str, sizeof str);

    if (write(g.ep0, &d, sizeof d) != (ssize_t)sizeof d)
        die("writing the FunctionFS descriptors to ep0: %s", strerror(errno));
    if (write(g.ep0, &s, sizeof s) != (ssize_t)sizeof s)
        die("writing the FunctionFS strings to ep0: %s", strerror(errno));
}

static void setup_functionfs(void)
{
    snprintf(g.ffs_mount, sizeof g.ffs_mount, "/dev/ffs-%s", g.name);
    if (mkdir(g.ffs_mount, 0755) != 0 && errno != EEXIST)
        die("mkdir %s: %s", g.ffs_mount, strerror(errno));
    umount(g.ffs_mount);
    if (mount("gud", g.ffs_mount, "functionfs", 0, NULL) != 0)
        die("mount -t functionfs gud %s: %s", g.ffs_mount, strerror(errno));
    char path[512];
    snprintf(path, sizeof path, "%s/ep0", g.ffs_mount);
    g.ep0 = open(path, O_RDWR);
    if (g.ep0 < 0)
        die("%s: %s", path, strerror(errno));
    write_descriptors();
    snprintf(path, sizeof path, "%s/ep1", g.ffs_mount);
    g.ep1 = open(path, O_RDWR);
    if (g.ep1 < 0)
        die("%s: %s", path, strerror(errno));
}

static void bind_udc(void)
{
    char name[128], err[600];
    if (g.udc) {
        snprintf(name, sizeof name, "%s", g.udc);
    } else {
        /* the first (only) UDC: dummy_udc.0 */
        FILE *p = popen("ls /sys/class/udc", "r");
        if (!p || !fgets(name, sizeof name, p))
            die("no USB device controller in /sys/class/udc (dummy_hcd loaded?)");
        pclose(p);
        name[strcspn(name, "\n")] = 0;
    }
    char path[512];
    gpath(path, sizeof path, "UDC");
    if (hw_write_file(path, name, err, sizeof err) != 0)
        die("binding to the UDC: %s", err);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Little-endian packing */

static void put16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}

static void put32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

static uint16_t get16(const uint8_t *p)
{
    return (uint16_t)(p[0] | p[1] << 8);
}

static uint32_t get32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static void pack_mode(uint8_t *p)
{
    uint16_t w = (uint16_t)g.width, h = (uint16_t)g.height;
    put32(p, (uint32_t)((uint64_t)g.width * g.height * 60 / 1000)); /* kHz for 60 Hz, no blanking */
    put16(p + 4, w);
    put16(p + 6, w);
    put16(p + 8, w);
    put16(p + 10, w);
    put16(p + 12, h);
    put16(p + 14, h);
    put16(p + 16, h);
    put16(p + 18, h);
    put32(p + 20, GUD_DISPLAY_MODE_FLAG_PREFERRED);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Control requests */

static const char *req_name(uint8_t req)
{
    switch (req) {
    case GUD_REQ_GET_STATUS: return "GET_STATUS";
    case GUD_REQ_GET_DESCRIPTOR: return "GET_DESCRIPTOR";
    case GUD_REQ_GET_FORMATS: return "GET_FORMATS";
    case GUD_REQ_GET_PROPERTIES: return "GET_PROPERTIES";
    case GUD_REQ_GET_CONNECTORS: return "GET_CONNECTORS";
    case GUD_REQ_GET_CONNECTOR_PROPERTIES: return "GET_CONNECTOR_PROPERTIES";
    case GUD_REQ_GET_CONNECTOR_TV_MODE_VALUES: return "GET_CONNECTOR_TV_MODE_VALUES";
    case GUD_REQ_SET_CONNECTOR_FORCE_DETECT: return "SET_CONNECTOR_FORCE_DETECT";
    case GUD_REQ_GET_CONNECTOR_STATUS: return "GET_CONNECTOR_STATUS";
    case GUD_REQ_GET_CONNECTOR_MODES: return "GET_CONNECTOR_MODES";
    case GUD_REQ_GET_CONNECTOR_EDID: return "GET_CONNECTOR_EDID";
    case GUD_REQ_SET_BUFFER: return "SET_BUFFER";
    case GUD_REQ_SET_STATE_CHECK: return "SET_STATE_CHECK";
    case GUD_REQ_SET_STATE_COMMIT: return "SET_STATE_COMMIT";
    case GUD_REQ_SET_CONTROLLER_ENABLE: return "SET_CONTROLLER_ENABLE";
    case GUD_REQ_SET_DISPLAY_ENABLE: return "SET_DISPLAY_ENABLE";
    default: return "UNKNOWN";
    }
}

/* Stall the pending control request (FunctionFS: a read for an IN request, a write for an OUT one). */
static void stall(int in)
{
    char dummy = 0;
    ssize_t r = in ? read(g.ep0, &dummy, 0) : write(g.ep0, &dummy, 0);
    (void)r; /* returns -1 with EL2HLT once the stall is done */
}

/* An IN request: the reply in buf and its length, or a GUD status other than OK to stall it. */
static uint8_t reply_in(uint8_t req, uint16_t value, uint8_t *buf, size_t *len, char *why, size_t whylen)
{
    *len = 0;
    switch (req) {
    case GUD_REQ_GET_STATUS:
        buf[0] = g.last_status;
        *len = 1;
        return GUD_STATUS_OK;
    case GUD_REQ_GET_DESCRIPTOR:
        put32(buf, GUD_DISPLAY_MAGIC);
        buf[4] = 1; /* version */
        put32(buf + 5, (g.status_on_set ? GUD_DISPLAY_FLAG_STATUS_ON_SET : 0) |
                           (g.full_update ? GUD_DISPLAY_FLAG_FULL_UPDATE : 0));
        buf[9] = g.lz4 ? GUD_COMPRESSION_LZ4 : 0;
        put32(buf + 10, g.max_buffer);
        put32(buf + 14, g.width);
        put32(buf + 18, g.width);
        put32(buf + 22, g.height);
        put32(buf + 26, g.height);
        *len = GUD_DISPLAY_DESCRIPTOR_SIZE;
        return GUD_STATUS_OK;
    case GUD_REQ_GET_FORMATS:
        buf[0] = GUD_PIXEL_FORMAT_RGB565;
        *len = 1;
        return GUD_STATUS_OK;
    case GUD_REQ_GET_PROPERTIES:
        return GUD_STATUS_OK; /* none */
    case GUD_REQ_GET_CONNECTORS:
        buf[0] = GUD_CONNECTOR_TYPE_PANEL;
        put32(buf + 1, 0);
        *len = GUD_CONNECTOR_DESCRIPTOR_SIZE;
        return GUD_STATUS_OK;
    case GUD_REQ_GET_CONNECTOR_PROPERTIES:
    case GUD_REQ_GET_CONNECTOR_STATUS:
    case GUD_REQ_GET_CONNECTOR_MODES:
    case GUD_REQ_GET_CONNECTOR_EDID:
        if (value != 0) {
            snprintf(why, whylen, "connector %u does not exist", value);
            return GUD_STATUS_INVALID_PARAMETER;
        }
        if (req == GUD_REQ_GET_CONNECTOR_STATUS) {
            buf[0] = GUD_CONNECTOR_STATUS_CONNECTED;
            *len = 1;
        } else if (req == GUD_REQ_GET_CONNECTOR_MODES) {
            pack_mode(buf);
            *len = GUD_DISPLAY_MODE_SIZE;
        }
        return GUD_STATUS_OK; /* no properties, no EDID */
    default:
        snprintf(why, whylen, "request 0x%02x not supported", req);
        return GUD_STATUS_REQUEST_NOT_SUPPORTED;
    }
}

/* The wLength an OUT request must have (-1: any of 26 + 10 n; -2: unknown request). */
static int out_length(uint8_t req)
{
    switch (req) {
    case GUD_REQ_SET_CONNECTOR_FORCE_DETECT: return 0;
    case GUD_REQ_SET_BUFFER: return GUD_SET_BUFFER_SIZE;
    case GUD_REQ_SET_STATE_CHECK: return -1;
    case GUD_REQ_SET_STATE_COMMIT: return 0;
    case GUD_REQ_SET_CONTROLLER_ENABLE: return 1;
    case GUD_REQ_SET_DISPLAY_ENABLE: return 1;
    default: return -2;
    }
}

/* An OUT request whose data has arrived (the status stage is done by then: FunctionFS acknowledges it, so a
 * refusal can only be told through GET_STATUS, which is what STATUS_ON_SET is for). Returns the GUD status,
 * with a line for the log in text. */
static uint8_t handle_out(uint8_t req, uint16_t value, const uint8_t *buf, size_t len, char *text, size_t cap)
{
    switch (req) {
    case GUD_REQ_SET_CONNECTOR_FORCE_DETECT:
        snprintf(text, cap, "connector=%u", value);
        return value == 0 ? GUD_STATUS_OK : GUD_STATUS_INVALID_PARAMETER;
    case GUD_REQ_SET_STATE_CHECK: {
        unsigned hd = get16(buf + 4), vd = get16(buf + 12), fmt = buf[24], conn = buf[25];
        unsigned props = (unsigned)(len - GUD_STATE_HEADER_SIZE) / GUD_PROPERTY_SIZE;
        int ok = hd == g.width && vd == g.height && fmt == GUD_PIXEL_FORMAT_RGB565 && conn == 0 && props == 0;
        snprintf(text, cap, "mode=%ux%u format=0x%02x connector=%u properties=%u%s", hd, vd, fmt, conn, props,
                 ok ? "" : " why=not-the-mode-format-connector-offered");
        pthread_mutex_lock(&g.lock);
        g.checked = ok;
        pthread_mutex_unlock(&g.lock);
        return ok ? GUD_STATUS_OK : GUD_STATUS_INVALID_PARAMETER;
    }
    case GUD_REQ_SET_STATE_COMMIT: {
        pthread_mutex_lock(&g.lock);
        int ok = g.checked;
        if (ok)
            g.committed = 1;
        pthread_mutex_unlock(&g.lock);
        snprintf(text, cap, "%s", ok ? "" : "why=commit-without-a-good-check");
        return ok ? GUD_STATUS_OK : GUD_STATUS_PROTOCOL_ERROR;
    }
    case GUD_REQ_SET_CONTROLLER_ENABLE:
    case GUD_REQ_SET_DISPLAY_ENABLE: {
        int on = buf[0];
        snprintf(text, cap, "value=%d%s", on, on > 1 ? " why=not-0-or-1" : "");
        if (on > 1)
            return GUD_STATUS_INVALID_PARAMETER;
        pthread_mutex_lock(&g.lock);
        if (req == GUD_REQ_SET_CONTROLLER_ENABLE)
            g.controller_enabled = on;
        else
            g.display_enabled = on;
        pthread_mutex_unlock(&g.lock);
        return GUD_STATUS_OK;
    }
    case GUD_REQ_SET_BUFFER: {
        set_buffer_t b = {get32(buf), get32(buf + 4), get32(buf + 8), get32(buf + 12), get32(buf + 16),
                          get32(buf + 21), buf[20]};
        const char *why = NULL;
        pthread_mutex_lock(&g.lock);
        if (!g.committed)
            why = "no-committed-state";
        else if (!b.w || !b.h || b.x >= g.width || b.y >= g.height || b.w > g.width - b.x || b.h > g.height - b.y)
            why = "rectangle-outside-the-display";
        else if (b.length != b.w * b.h * 2)
            why = "length-is-not-width*height*2";
        else if (g.max_buffer && b.length > g.max_buffer)
            why = "length-over-max_buffer_size";
        else if (b.compression & ~(g.lz4 ? GUD_COMPRESSION_LZ4 : 0))
            why = "compression-not-offered";
        else if (b.compression && (!b.compressed_length || b.compressed_length > b.length + b.length / 255 + 16))
            why = "bad-compressed_length";
        else if (g.full_update && (b.x || b.y || b.w != g.width || b.h != g.height || b.compression))
            why = "full-update-device-needs-whole-uncompressed-frames";
        else if (g.q_count == QUEUE_LEN)
            why = "queue-full";
        if (!why && !g.full_update) {
            g.queue[(g.q_head + g.q_count) % QUEUE_LEN] = b;
            g.q_count++;
            pthread_cond_signal(&g.cond);
        }
        pthread_mutex_unlock(&g.lock);
        snprintf(text, cap, "x=%u y=%u w=%u h=%u length=%u compression=%u compressed_length=%u%s%s", b.x, b.y, b.w,
                 b.h, b.length, b.compression, b.compressed_length, why ? " why=" : "", why ? why : "");
        return why ? GUD_STATUS_INVALID_PARAMETER : GUD_STATUS_OK;
    }
    }
    snprintf(text, cap, "why=unknown");
    return GUD_STATUS_REQUEST_NOT_SUPPORTED;
}

static void handle_setup(const struct usb_ctrlrequest *s)
{
    uint8_t type = s->bRequestType, req = s->bRequest;
    uint16_t value = le16toh(s->wValue), index = le16toh(s->wIndex), length = le16toh(s->wLength);
    int in = (type & USB_DIR_IN) != 0;
    char why[256] = "";
    static uint8_t buf[65536];

    if ((type & USB_TYPE_MASK) != USB_TYPE_VENDOR || (type & USB_RECIP_MASK) != USB_RECIP_INTERFACE) {
        logline("UNEXPECTED bRequestType=0x%02x bRequest=0x%02x wValue=%u wIndex=%u wLength=%u status=%u", type,
                req, value, index, length, GUD_STATUS_PROTOCOL_ERROR);
        stall(in);
        return;
    }
    if (in) {
        size_t len;
        uint8_t st = reply_in(req, value, buf, &len, why, sizeof why);
        if (st != GUD_STATUS_OK) {
            stall(1);
            g.last_status = st;
            logline("%s wValue=%u wLength=%u status=%u why=%s (stalled)", req_name(req), value, length, st, why);
            return;
        }
        if (len > length)
            len = length;
        ssize_t n = write(g.ep0, buf, len);
        if (req != GUD_REQ_GET_STATUS)
            g.last_status = GUD_STATUS_OK;
        logline("%s wValue=%u wLength=%u replied=%zd status=%u%s%s", req_name(req), value, length, n,
                req == GUD_REQ_GET_STATUS ? buf[0] : GUD_STATUS_OK, n < 0 ? " write-error=" : "",
                n < 0 ? strerror(errno) : "");
        return;
    }
    int want = out_length(req);
    int len_ok = want == -1 ? length >= GUD_STATE_HEADER_SIZE && (length - GUD_STATE_HEADER_SIZE) % GUD_PROPERTY_SIZE == 0
                            : want == length;
    if (want == -2 || !len_ok) {
        stall(0);
        g.last_status = want == -2 ? GUD_STATUS_REQUEST_NOT_SUPPORTED : GUD_STATUS_PROTOCOL_ERROR;
        logline("%s bRequest=0x%02x wValue=%u wLength=%u status=%u why=%s (stalled)", req_name(req), req, value,
                length, g.last_status, want == -2 ? "unknown-request" : "wrong-wLength");
        return;
    }
    ssize_t n = read(g.ep0, buf, length); /* the data stage, and FunctionFS acknowledges the status stage */
    if (n != length) {
        g.last_status = GUD_STATUS_ERROR;
        logline("%s wLength=%u status=%u why=data-stage-read-%zd:%s", req_name(req), length, g.last_status, n,
                n < 0 ? strerror(errno) : "short");
        return;
    }
    char text[512];
    uint8_t st = handle_out(req, value, buf, (size_t)n, text, sizeof text);
    g.last_status = st;
    logline("%s %s status=%u", req_name(req), text, st);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Bulk OUT: the pixels of each SET_BUFFER */

static void save_frame(unsigned frames)
{
    char path[512], tmp[520], err[600], num[32];
    snprintf(path, sizeof path, "%s/frame", g.dir);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "wb");
    if (!f)
        die("%s: %s", tmp, strerror(errno));
    for (unsigned i = 0; i < g.width * g.height; i++) {
        uint8_t le[2] = {(uint8_t)g.fb[i], (uint8_t)(g.fb[i] >> 8)};
        fwrite(le, 1, 2, f);
    }
    if (fclose(f) != 0 || rename(tmp, path) != 0)
        die("%s: %s", path, strerror(errno));
    snprintf(path, sizeof path, "%s/frames", g.dir);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    snprintf(num, sizeof num, "%u\n", frames);
    int fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0)
        die("%s: %s", tmp, strerror(errno));
    close(fd);
    if (hw_write_file(tmp, num, err, sizeof err) != 0 || rename(tmp, path) != 0)
        die("%s: %s", path, err);
}

static void *bulk_main(void *arg)
{
    (void)arg;
    size_t cap = (size_t)g.width * g.height * 2 * 2 + 64;
    uint8_t *wire = malloc(cap), *raw = malloc(cap);
    if (!wire || !raw)
        die("out of memory");
    for (;;) {
        set_buffer_t b = {0, 0, g.width, g.height, g.width * g.height * 2, 0, 0};
        pthread_mutex_lock(&g.lock);
        while (!g.full_update && !g.q_count && !g.quit)
            pthread_cond_wait(&g.cond, &g.lock);
        if (g.quit) {
            pthread_mutex_unlock(&g.lock);
            break;
        }
        if (!g.full_update) {
            b = g.queue[g.q_head];
            g.q_head = (g.q_head + 1) % QUEUE_LEN;
            g.q_count--;
        }
        pthread_mutex_unlock(&g.lock);

        size_t want = b.compression ? b.compressed_length : b.length, got = 0;
        ssize_t n = 0;
        while (got < want) {
            n = read(g.ep1, wire + got, want - got);
            if (n == 0 && got == 0) { /* a zero-length packet the host ended the previous transfer with */
                logline("ZLP");
                continue;
            }
            if (n <= 0)
                break;
            got += (size_t)n;
        }
        if (got < want) {
            if (g.quit)
                break;
            logline("BULK bytes=%zu expected=%zu status=%u why=%s", got, want, GUD_STATUS_ERROR,
                    n < 0 ? strerror(errno) : "short-transfer");
            continue;
        }
        const uint8_t *pix = wire;
        if (b.compression) {
#ifdef VFP_HAVE_LZ4
            int out = LZ4_decompress_safe((const char *)wire, (char *)raw, (int)want, (int)b.length);
            if (out != (int)b.length) {
                logline("BULK bytes=%zu lz4 status=%u why=lz4-decompressed-to-%d-not-%u", got, GUD_STATUS_ERROR,
                        out, b.length);
                continue;
            }
            pix = raw;
#else
            logline("BULK bytes=%zu status=%u why=lz4-not-built-in", got, GUD_STATUS_ERROR);
            continue;
#endif
        }
        pthread_mutex_lock(&g.lock);
        for (uint32_t row = 0; row < b.h; row++)
            for (uint32_t col = 0; col < b.w; col++) {
                const uint8_t *p = pix + ((size_t)row * b.w + col) * 2;
                g.fb[(size_t)(b.y + row) * g.width + b.x + col] = (uint16_t)(p[0] | p[1] << 8);
            }
        unsigned frames = ++g.frames;
        pthread_mutex_unlock(&g.lock);
        save_frame(frames);
        logline("BULK bytes=%zu%s frame=%u status=0", got, b.compression ? " lz4" : "", frames);
    }
    free(wire);
    free(raw);
    return NULL;
}

/* ---------------------------------------------------------------------------------------------------------- */

static void on_signal(int sig)
{
    (void)sig;
    g.quit = 1;
}

static const char *event_name(int type)
{
    switch (type) {
    case FUNCTIONFS_BIND: return "BIND";
    case FUNCTIONFS_UNBIND: return "UNBIND";
    case FUNCTIONFS_ENABLE: return "ENABLE";
    case FUNCTIONFS_DISABLE: return "DISABLE";
    case FUNCTIONFS_SUSPEND: return "SUSPEND";
    case FUNCTIONFS_RESUME: return "RESUME";
    default: return "EVENT?";
    }
}

int main(int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--lz4")) {
#ifndef VFP_HAVE_LZ4
            die("--lz4: built without liblz4");
#endif
            g.lz4 = 1;
        } else if (!strcmp(a, "--full-update")) {
            g.full_update = 1;
        } else if (!strcmp(a, "--status-on-set")) {
            g.status_on_set = 1;
        } else if (v && !strcmp(a, "--dir")) {
            g.dir = v, i++;
        } else if (v && !strcmp(a, "--udc")) {
            g.udc = v, i++;
        } else if (v && !strcmp(a, "--name")) {
            g.name = v, i++;
        } else if (v && !strcmp(a, "--vid")) {
            g.vid = (unsigned)strtoul(v, NULL, 16), i++;
        } else if (v && !strcmp(a, "--pid")) {
            g.pid = (unsigned)strtoul(v, NULL, 16), i++;
        } else if (v && !strcmp(a, "--max-buffer")) {
            g.max_buffer = (unsigned)strtoul(v, NULL, 0), i++;
        } else if (v && !strcmp(a, "--size")) {
            if (sscanf(v, "%ux%u", &g.width, &g.height) != 2 || !g.width || !g.height || g.width > 4096 ||
                g.height > 4096)
                die("--size %s: expected WxH", v);
            i++;
        } else {
            die("unknown argument '%s' (see the comment at the top of tests/hw/gud_gadget.c)", a);
        }
    }
    if (!g.dir)
        die("--dir DIR is required");
    if (g.full_update && g.lz4)
        die("--full-update cannot be combined with --lz4 (gud.h: FULL_UPDATE excludes compression)");
    char path[512];
    snprintf(path, sizeof path, "%s/log", g.dir);
    g.log = fopen(path, "w");
    if (!g.log)
        die("%s: %s", path, strerror(errno));
    g.fb = calloc((size_t)g.width * g.height, sizeof *g.fb);
    if (!g.fb)
        die("out of memory");

    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal; /* no SA_RESTART: a blocking read on ep0 or ep1 returns EINTR */
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGUSR1, &sa, NULL);

    setup_configfs();
    setup_functionfs();
    if (pthread_create(&g.bulk_thread, NULL, bulk_main, NULL) != 0)
        die("pthread_create failed");
    bind_udc();
    logline("READY vid=0x%04x pid=0x%04x size=%ux%u lz4=%d max_buffer=%u status_on_set=%d full_update=%d", g.vid,
            g.pid, g.width, g.height, g.lz4, g.max_buffer, g.status_on_set, g.full_update);
    snprintf(path, sizeof path, "%s/ready", g.dir);
    int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0)
        close(fd);

    while (!g.quit) {
        struct usb_functionfs_event ev[4];
        ssize_t n = read(g.ep0, ev, sizeof ev);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            logline("EP0 read-error=%s", strerror(errno));
            hw_sleep_ms(10);
            continue;
        }
        for (size_t i = 0; i < (size_t)n / sizeof ev[0]; i++) {
            if (ev[i].type == FUNCTIONFS_SETUP) {
                handle_setup(&ev[i].u.setup);
            } else {
                logline("%s", event_name(ev[i].type));
                if (ev[i].type == FUNCTIONFS_DISABLE || ev[i].type == FUNCTIONFS_UNBIND) {
                    /* an unplug: what the host had announced will not come */
                    pthread_mutex_lock(&g.lock);
                    g.q_count = 0;
                    g.checked = g.committed = 0;
                    pthread_mutex_unlock(&g.lock);
                }
            }
        }
    }

    /* SIGTERM: unbind, stop the bulk thread, remove everything. */
    char err[600];
    snprintf(path, sizeof path, "%s/UDC", g.gadget);
    hw_write_file(path, "\n", err, sizeof err);
    pthread_mutex_lock(&g.lock);
    pthread_cond_signal(&g.cond);
    pthread_mutex_unlock(&g.lock);
    /* the bulk thread may be in read() on ep1 (waiting for an enable that will not come): interrupt it until it
     * has seen g.quit */
    for (int i = 0; i < 100; i++) {
        struct timespec until;
        pthread_kill(g.bulk_thread, SIGUSR1);
        clock_gettime(CLOCK_REALTIME, &until);
        until.tv_nsec += 20000000;
        if (until.tv_nsec >= 1000000000) {
            until.tv_sec++;
            until.tv_nsec -= 1000000000;
        }
        if (pthread_timedjoin_np(g.bulk_thread, NULL, &until) == 0)
            break;
    }
    close(g.ep1);
    close(g.ep0);
    umount(g.ffs_mount);
    rmdir(g.ffs_mount);
    teardown_configfs();
    logline("EXIT");
    return 0;
}
