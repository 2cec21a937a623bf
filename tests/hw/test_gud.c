/* SPDX-License-Identifier: MIT */
/*
 * test_gud.c: the "gud" display backend (port/display/display_gud.c, libusb) against a GUD device made in the same Linux
 * VM by gud_gadget.c over dummy_hcd and FunctionFS (tests/hw/README.md). For each gadget configuration it
 * starts the gadget, opens the backend through vfp_display_find("gud"), presents known frames and checks that
 * the frame the gadget holds equals them pixel for pixel, and reads the gadget's log of control requests to
 * check the protocol. Prints "ok - hw/gud ..." / "not ok - hw/gud ...: why" lines.
 *
 * Usage: test_gud --gadget PATH/gud_gadget [--work DIR]   (as root, in the VM: it writes to configfs)
 */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "display/display.h"
#include "hwtest.h"
#include "render/render_mt.h"
#include "io/tf.h"
#include "io/volume.h"

#define W 64
#define H 48
#define GADGET_NAME "volfix-gud"

typedef struct config {
    const char *label;   /* in the test names */
    unsigned vid, pid;
    const char *args[6]; /* extra gadget arguments */
    unsigned max_buffer; /* what --max-buffer says (0: none) */
    int lz4, status_on_set, full_update;
    int unplug;          /* also unplug and plug back in */
} config_t;

static const config_t configs[] = {
    {"1d50:614d", 0x1d50, 0x614d, {NULL}, 0, 0, 0, 0, 1},
    {"16d0:10a9 lz4 max_buffer_size=1024 status-on-set", 0x16d0, 0x10a9,
     {"--lz4", "--max-buffer", "1024", "--status-on-set", NULL}, 1024, 1, 1, 0, 0},
    {"1d50:614d full-update", 0x1d50, 0x614d, {"--full-update", NULL}, 0, 0, 0, 1, 0},
};

static const char *gadget_path, *work = "/tmp/gud";

/* ---------------------------------------------------------------------------------------------------------- */
/* Frames */

static uint16_t rgb565(unsigned r, unsigned g, unsigned b)
{
    return (uint16_t)((r & 31) << 11 | (g & 63) << 5 | (b & 31));
}

static void put_px(uint8_t *buf, uint32_t stride, uint32_t x, uint32_t y, uint16_t v)
{
    buf[(size_t)y * stride + x * 2] = (uint8_t)v;
    buf[(size_t)y * stride + x * 2 + 1] = (uint8_t)(v >> 8);
}

static uint16_t get_px(const uint8_t *buf, uint32_t stride, uint32_t x, uint32_t y)
{
    return (uint16_t)(buf[(size_t)y * stride + x * 2] | buf[(size_t)y * stride + x * 2 + 1] << 8);
}

/* A gradient whose every pixel differs from its neighbours, seeded so that two frames differ everywhere. */
static void gradient(uint8_t *buf, uint32_t stride, unsigned seed)
{
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++)
            put_px(buf, stride, x, y, rgb565(x * 31 / (W - 1) + seed, y * 63 / (H - 1) + seed, (x + y + seed) & 31));
}

/* The gadget's framebuffer (DIR/frame) equals `want` (W x H, tightly packed), within timeout_ms. Returns 1, or 0
 * with the first difference in why. */
static int wait_frame(const char *dir, const uint8_t *want, unsigned timeout_ms, char *why, size_t whylen)
{
    char path[PATH_MAX];
    snprintf(path, sizeof path, "%s/frame", dir);
    static uint8_t got[W * H * 2];
    uint64_t until = hw_now_ns() + (uint64_t)timeout_ms * 1000000u;
    snprintf(why, whylen, "the gadget wrote no frame (%s)", path);
    do {
        FILE *f = fopen(path, "rb");
        if (f) {
            size_t n = fread(got, 1, sizeof got, f);
            fclose(f);
            if (n != sizeof got) {
                snprintf(why, whylen, "%s has %zu bytes, not %d", path, n, W * H * 2);
            } else if (memcmp(got, want, sizeof got) == 0) {
                return 1;
            } else {
                int diff = 0, fx = -1, fy = -1;
                for (uint32_t y = 0; y < H; y++)
                    for (uint32_t x = 0; x < W; x++)
                        if (get_px(got, W * 2, x, y) != get_px(want, W * 2, x, y)) {
                            if (!diff++)
                                fx = (int)x, fy = (int)y;
                        }
                snprintf(why, whylen, "%d of %d pixels differ; first at (%d,%d): got 0x%04x, want 0x%04x", diff,
                         W * H, fx, fy, get_px(got, W * 2, (uint32_t)fx, (uint32_t)fy),
                         get_px(want, W * 2, (uint32_t)fx, (uint32_t)fy));
            }
        }
        hw_sleep_ms(20);
    } while (hw_now_ns() < until);
    return 0;
}

/* A frame rendered by the core: phantom:sphere:16 at W x H in RGB565. Returns 0, or 2 with err. */
static int render_sphere(uint8_t *pixels, char *err, size_t errlen)
{
    vfp_volume_t vol;
    if (vfp_volume_load(&vol, "phantom:sphere:16", NULL, err, errlen))
        return 2;
    vf_params_t params;
    vf_params_default(&params);
    vfp_tf_t tf;
    vf_tf_point_t points[VF_MAX_TF_POINTS];
    vf_window_t window = vfp_default_window(&vol);
    int status = vfp_tf_preset(&tf, "ramp", err, errlen);
    uint32_t count = status ? 0 : vfp_tf_to_core(&tf, &vol, window, points);
    vfp_render_t r;
    if (status == 0)
        status = vfp_render_open(&r, &params, &vol.core, 1, err, errlen);
    if (status == 0) {
        vf_view_t view = {VF_BAU_PER_TURN / 12, VF_BAU_PER_TURN / 16, 0, 65536};
        vf_image_t img = {pixels, W, H, W * 2, VF_FORMAT_RGB565};
        status = vfp_render_set_window(&r, window, err, errlen);
        if (status == 0)
            status = vfp_render_set_tf(&r, points, count, err, errlen);
        if (status == 0)
            status = vfp_render_frame(&r, &view, &img, err, errlen);
        vfp_render_close(&r);
    }
    vfp_volume_free(&vol);
    return status;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* The USB device as the host's sysfs shows it */

/* The device's sysfs name ("1-1") for vid:pid, or 0. */
static int find_usb(unsigned vid, unsigned pid, char *name, size_t cap)
{
    DIR *d = opendir("/sys/bus/usb/devices");
    if (!d)
        return 0;
    struct dirent *e;
    int found = 0;
    while (!found && (e = readdir(d))) {
        char path[PATH_MAX], v[16], p[16], err[64];
        if (e->d_name[0] == '.' || strchr(e->d_name, ':'))
            continue;
        snprintf(path, sizeof path, "/sys/bus/usb/devices/%s/idVendor", e->d_name);
        if (hw_read_file(path, v, sizeof v, err, sizeof err))
            continue;
        snprintf(path, sizeof path, "/sys/bus/usb/devices/%s/idProduct", e->d_name);
        if (hw_read_file(path, p, sizeof p, err, sizeof err))
            continue;
        if (strtoul(v, NULL, 16) == vid && strtoul(p, NULL, 16) == pid) {
            snprintf(name, cap, "%s", e->d_name);
            found = 1;
        }
    }
    closedir(d);
    return found;
}

/* The driver bound to interface 0 of device `name` ("" when none). */
static void interface_driver(const char *name, char *driver, size_t cap)
{
    char path[PATH_MAX], link[PATH_MAX];
    snprintf(path, sizeof path, "/sys/bus/usb/devices/%s:1.0/driver", name);
    ssize_t n = readlink(path, link, sizeof link - 1);
    driver[0] = 0;
    if (n > 0) {
        link[n] = 0;
        const char *base = strrchr(link, '/');
        snprintf(driver, cap, "%s", base ? base + 1 : link);
    }
}

static int wait_usb(unsigned vid, unsigned pid, int present, char *name, size_t cap, unsigned timeout_ms)
{
    uint64_t until = hw_now_ns() + (uint64_t)timeout_ms * 1000000u;
    do {
        if (find_usb(vid, pid, name, cap) == present)
            return 1;
        hw_sleep_ms(20);
    } while (hw_now_ns() < until);
    return 0;
}

static int wait_driver(const char *name, const char *want, unsigned timeout_ms, char *got, size_t cap)
{
    uint64_t until = hw_now_ns() + (uint64_t)timeout_ms * 1000000u;
    do {
        interface_driver(name, got, cap);
        if (strcmp(got, want) == 0)
            return 1;
        hw_sleep_ms(20);
    } while (hw_now_ns() < until);
    return 0;
}

static int usbtest_loaded(void)
{
    return access("/sys/bus/usb/drivers/usbtest", F_OK) == 0;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* The gadget's log */

typedef struct log {
    char **lines;
    int count;
} log_t;

static void log_read(const char *dir, log_t *log)
{
    char path[PATH_MAX], line[1024];
    snprintf(path, sizeof path, "%s/log", dir);
    log->lines = NULL;
    log->count = 0;
    FILE *f = fopen(path, "r");
    if (!f)
        return;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = 0;
        log->lines = realloc(log->lines, sizeof(char *) * (size_t)(log->count + 1));
        log->lines[log->count++] = strdup(line);
    }
    fclose(f);
}

static void log_free(log_t *log)
{
    for (int i = 0; i < log->count; i++)
        free(log->lines[i]);
    free(log->lines);
    log->lines = NULL;
    log->count = 0;
}

static int starts(const char *line, const char *word);
static int log_find(const log_t *log, int from, const char *word);

/* Read the log once it has a line starting with `word` at or after line `from` and then nothing new for 150 ms
 * (the gadget logs a control request after the host has seen it complete), or after timeout_ms. */
static void log_settle(const char *dir, log_t *log, int from, const char *word, unsigned timeout_ms)
{
    uint64_t until = hw_now_ns() + (uint64_t)timeout_ms * 1000000u, stable_since = 0;
    int last = -1;
    for (;;) {
        log_read(dir, log);
        uint64_t now = hw_now_ns();
        if (log->count != last) {
            last = log->count;
            stable_since = now;
        }
        if (now >= until || (log_find(log, from, word) >= 0 && now - stable_since >= 150000000u))
            return;
        log_free(log);
        hw_sleep_ms(20);
    }
}

static int starts(const char *line, const char *word)
{
    size_t n = strlen(word);
    return strncmp(line, word, n) == 0 && (line[n] == ' ' || line[n] == 0);
}

/* The first line at or after `from` that starts with `word`, or -1. */
static int log_find(const log_t *log, int from, const char *word)
{
    for (int i = from; i < log->count; i++)
        if (starts(log->lines[i], word))
            return i;
    return -1;
}

static unsigned field(const char *line, const char *key)
{
    char k[64];
    snprintf(k, sizeof k, " %s=", key);
    const char *p = strstr(line, k);
    return p ? (unsigned)strtoul(p + strlen(k), NULL, 0) : UINT_MAX;
}

/* Lines from `from` with a refusal (status other than 0; GET_STATUS lines report a status, they are not one). */
static int log_refusal(const log_t *log, int from, int to)
{
    for (int i = from; i < to && i < log->count; i++) {
        const char *l = log->lines[i];
        if (starts(l, "GET_STATUS"))
            continue;
        unsigned st = field(l, "status");
        if ((st != UINT_MAX && st != 0) || starts(l, "UNEXPECTED") || starts(l, "EP0"))
            return i;
    }
    return -1;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* The gadget process */

static pid_t start_gadget(const config_t *c, const char *dir, char *why, size_t whylen)
{
    char vid[16], pid_s[16], size[16], out[PATH_MAX];
    snprintf(vid, sizeof vid, "0x%04x", c->vid);
    snprintf(pid_s, sizeof pid_s, "0x%04x", c->pid);
    snprintf(size, sizeof size, "%dx%d", W, H);
    snprintf(out, sizeof out, "%s/stderr", dir);
    const char *argv[24] = {gadget_path, "--dir", dir, "--vid", vid, "--pid", pid_s, "--size", size, "--name",
                            GADGET_NAME};
    int n = 11;
    for (int i = 0; c->args[i]; i++)
        argv[n++] = c->args[i];
    argv[n] = NULL;
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        if (!freopen(out, "w", stdout) || !freopen(out, "a", stderr))
            _exit(127);
        execv(gadget_path, (char *const *)argv);
        fprintf(stderr, "exec %s: %s\n", gadget_path, strerror(errno));
        _exit(127);
    }
    if (pid < 0) {
        snprintf(why, whylen, "fork: %s", strerror(errno));
        return -1;
    }
    char ready[PATH_MAX];
    snprintf(ready, sizeof ready, "%s/ready", dir);
    uint64_t until = hw_now_ns() + 10000000000ull;
    while (hw_now_ns() < until) {
        if (access(ready, F_OK) == 0)
            return pid;
        int st;
        if (waitpid(pid, &st, WNOHANG) == pid) {
            char text[512] = "", err[64];
            hw_read_file(out, text, sizeof text, err, sizeof err);
            snprintf(why, whylen, "gud_gadget exited (%s)", text[0] ? text : "no message");
            return -1;
        }
        hw_sleep_ms(20);
    }
    kill(pid, SIGKILL);
    waitpid(pid, NULL, 0);
    snprintf(why, whylen, "gud_gadget was not ready within 10 s");
    return -1;
}

static void stop_gadget(pid_t pid)
{
    kill(pid, SIGTERM);
    for (int i = 0; i < 150; i++) {
        if (waitpid(pid, NULL, WNOHANG) == pid)
            return;
        hw_sleep_ms(20);
    }
    printf("# gud_gadget did not stop within 3 s of SIGTERM; killed\n");
    kill(pid, SIGKILL);
    waitpid(pid, NULL, 0);
}

static int set_udc(int bind, char *why, size_t whylen)
{
    char udc[128] = "\n";
    if (bind) {
        DIR *d = opendir("/sys/class/udc");
        struct dirent *e;
        udc[0] = 0;
        while (d && (e = readdir(d)))
            if (e->d_name[0] != '.')
                snprintf(udc, sizeof udc, "%s", e->d_name);
        if (d)
            closedir(d);
    }
    return hw_write_file("/sys/kernel/config/usb_gadget/" GADGET_NAME "/UDC", udc, why, whylen);
}

/* ---------------------------------------------------------------------------------------------------------- */

static int open_display(vfp_display_t *d, const config_t *c, unsigned timeout_ms, char *err, size_t errlen)
{
    vfp_board_t board;
    memset(&board, 0, sizeof board);
    snprintf(board.name, sizeof board.name, "hw-test");
    snprintf(board.path, sizeof board.path, "tests/hw/test_gud.c");
    snprintf(board.display, sizeof board.display, "gud");
    snprintf(board.display_device, sizeof board.display_device, "%04x:%04x", c->vid, c->pid);
    board.format = VF_FORMAT_RGB565;
    const vfp_display_ops_t *ops = vfp_display_find("gud", &board, err, errlen);
    if (!ops)
        return 2;
    uint64_t until = hw_now_ns() + (uint64_t)timeout_ms * 1000000u;
    int status;
    do {
        memset(d, 0, sizeof *d);
        d->ops = ops;
        status = ops->open(d, &board, err, errlen);
        if (status == 0)
            return 0;
        hw_sleep_ms(100);
    } while (hw_now_ns() < until);
    d->ops = NULL;
    return status;
}

/* Presents a w x h rectangle at (x, y) of pixels (rows stride bytes apart) and reports the case name: the frame
 * the gadget then shows must be want. */
static void present_arrives(vfp_display_t *d, const char *dir, const char *name, uint32_t x, uint32_t y, uint32_t w,
                            uint32_t h, const uint8_t *pixels, uint32_t stride, const uint8_t *want)
{
    char err[512], why[1024];
    int st = d->ops->present(d, x, y, w, h, pixels, stride, err, sizeof err);
    if (st != 0)
        hw_result(0, name, "present() returned %d: %s", st, err);
    else
        hw_result(wait_frame(dir, want, 3000, why, sizeof why), name, "%s", why);
}

static void run_config(const config_t *c, int index)
{
    char dir[PATH_MAX], name[512], why[1024], err[512], usb[64] = "", driver[64];
    char base[256];
    snprintf(base, sizeof base, "hw/gud %s", c->label);
    snprintf(dir, sizeof dir, "%s/%d", work, index);
    mkdir(work, 0755);
    mkdir(dir, 0755);

    pid_t gadget = start_gadget(c, dir, why, sizeof why);
    snprintf(name, sizeof name, "%s: the gadget binds to dummy_udc and the host enumerates it", base);
    if (gadget < 0) {
        hw_result(0, name, "%s", why);
        return;
    }
    if (!wait_usb(c->vid, c->pid, 1, usb, sizeof usb, 10000)) {
        hw_result(0, name, "no USB device %04x:%04x in /sys/bus/usb/devices within 10 s", c->vid, c->pid);
        stop_gadget(gadget);
        return;
    }
    hw_result(1, name, " ");

    /* A kernel driver on the interface, for the backend to detach: usbtest, loaded by the init script with
     * vendor=0x1d50 product=0x614d (Debian's kernel has no gud driver to bind). */
    int with_usbtest = c->vid == 0x1d50 && c->pid == 0x614d && usbtest_loaded();
    if (with_usbtest) {
        snprintf(name, sizeof name, "%s: usbtest binds to the interface (the driver open() must detach)", base);
        int bound = wait_driver(usb, "usbtest", 5000, driver, sizeof driver);
        hw_result(bound, name, "%s:1.0 has driver '%s' after 5 s", usb, driver);
    }
    interface_driver(usb, driver, sizeof driver);
    int had_usbtest = strcmp(driver, "usbtest") == 0;

    vfp_display_t d;
    snprintf(name, sizeof name, "%s: open() gives the gadget's %dx%d RGB565 mode", base, W, H);
    if (open_display(&d, c, 5000, err, sizeof err) != 0) {
        hw_result(0, name, "%s", err);
        stop_gadget(gadget);
        return;
    }
    hw_result(d.width == W && d.height == H && d.format == VF_FORMAT_RGB565, name, "got %ux%u format %d",
              d.width, d.height, (int)d.format);

    if (had_usbtest) {
        interface_driver(usb, driver, sizeof driver);
        snprintf(name, sizeof name, "%s: open() detached the kernel driver (usbtest) and claimed the interface",
                 base);
        hw_result(strcmp(driver, "usbfs") == 0, name, "interface %s:1.0 has driver '%s', expected usbfs", usb,
                  driver);
    }

    /* The probe, as the gadget saw it. */
    log_t log;
    log_settle(dir, &log, 0, "SET_DISPLAY_ENABLE", 3000);
    {
        static const char *const need[] = {"GET_DESCRIPTOR", "GET_FORMATS", "GET_CONNECTORS", "GET_CONNECTOR_STATUS",
                                           "GET_CONNECTOR_MODES", "SET_STATE_CHECK", "SET_STATE_COMMIT"};
        char missing[512] = "";
        for (size_t i = 0; i < sizeof need / sizeof need[0]; i++)
            if (log_find(&log, 0, need[i]) < 0)
                snprintf(missing + strlen(missing), sizeof missing - strlen(missing), " %s", need[i]);
        int desc = log_find(&log, 0, "GET_DESCRIPTOR"), modes = log_find(&log, 0, "GET_CONNECTOR_MODES");
        int check = log_find(&log, 0, "SET_STATE_CHECK"), commit = log_find(&log, 0, "SET_STATE_COMMIT");
        int ctrl = log_find(&log, 0, "SET_CONTROLLER_ENABLE"), disp = log_find(&log, 0, "SET_DISPLAY_ENABLE");
        int refused = log_refusal(&log, 0, log.count);
        snprintf(name, sizeof name,
                 "%s: open() probes (descriptor, formats, connectors, status, modes), checks and commits the "
                 "state, enables controller and display, and the gadget refuses nothing",
                 base);
        if (missing[0])
            hw_result(0, name, "the gadget never saw:%s", missing);
        else if (!(desc < modes && modes < check && check < commit))
            hw_result(0, name, "out of order: GET_DESCRIPTOR line %d, GET_CONNECTOR_MODES %d, STATE_CHECK %d, "
                               "STATE_COMMIT %d", desc, modes, check, commit);
        else if (ctrl < 0 || field(log.lines[ctrl], "value") != 1 || disp < 0 ||
                 field(log.lines[disp], "value") != 1 || disp < commit)
            hw_result(0, name, "controller enable: %s; display enable: %s", ctrl < 0 ? "never" : log.lines[ctrl],
                      disp < 0 ? "never" : log.lines[disp]);
        else if (refused >= 0)
            hw_result(0, name, "the gadget refused: %s", log.lines[refused]);
        else
            hw_result(1, name, " ");
        if (c->status_on_set) {
            int bad = -1;
            for (int i = 0; i < log.count && bad < 0; i++)
                if (strncmp(log.lines[i], "SET_", 4) == 0 && (i + 1 >= log.count || !starts(log.lines[i + 1], "GET_STATUS")))
                    bad = i;
            snprintf(name, sizeof name, "%s: GET_STATUS follows every SET request (STATUS_ON_SET)", base);
            hw_result(bad < 0, name, "no GET_STATUS after line %d: %s", bad, bad >= 0 ? log.lines[bad] : "");
        }
    }
    int log_mark = log.count;
    log_free(&log);

    /* 1. a whole frame */
    static uint8_t frame[W * H * 2], expect[W * H * 2];
    gradient(frame, W * 2, 0);
    snprintf(name, sizeof name, "%s: a %dx%d gradient arrives pixel for pixel", base, W, H);
    present_arrives(&d, dir, name, 0, 0, W, H, frame, W * 2, frame);

    /* 2. a rectangle out of a buffer whose rows are padded */
    {
        enum { RX = 10, RY = 5, RW = 20, RH = 7, STRIDE = W * 2 + 36 };
        static uint8_t padded[H * STRIDE];
        memset(padded, 0xEE, sizeof padded);
        for (uint32_t y = 0; y < H; y++)
            for (uint32_t x = 0; x < W; x++)
                put_px(padded, STRIDE, x, y, (uint16_t)(0xF81F ^ (x * 37 + y * 11)));
        memcpy(expect, frame, sizeof expect);
        for (uint32_t y = RY; y < RY + RH; y++)
            for (uint32_t x = RX; x < RX + RW; x++)
                put_px(expect, W * 2, x, y, get_px(padded, STRIDE, x, y));
        snprintf(name, sizeof name, "%s: a %dx%d rectangle at (%d,%d) from rows %d bytes apart changes exactly "
                 "those pixels", base, RW, RH, RX, RY, STRIDE);
        present_arrives(&d, dir, name, RX, RY, RW, RH, padded, STRIDE, expect);
    }

    /* 3. a frame rendered by the core */
    snprintf(name, sizeof name, "%s: a frame rendered by the core (phantom:sphere:16) arrives pixel for pixel", base);
    if (render_sphere(expect, err, sizeof err) != 0) {
        hw_result(0, name, "rendering: %s", err);
    } else {
        present_arrives(&d, dir, name, 0, 0, W, H, expect, W * 2, expect);
    }

    /* The transfers the presents made, as the gadget saw them (each frame was waited for above). */
    log_settle(dir, &log, log_mark, "BULK", 1000);
    {
        int sets = 0, lz4 = 0, bulks = 0, too_big = -1;
        for (int i = log_mark; i < log.count; i++) {
            if (starts(log.lines[i], "SET_BUFFER")) {
                sets++;
                lz4 += field(log.lines[i], "compression") != 0;
                if (c->max_buffer && field(log.lines[i], "length") > c->max_buffer && too_big < 0)
                    too_big = i;
            }
            bulks += starts(log.lines[i], "BULK");
        }
        int refused = log_refusal(&log, log_mark, log.count);
        snprintf(name, sizeof name, "%s: the gadget accepted every transfer", base);
        hw_result(refused < 0, name, "%s", refused >= 0 ? log.lines[refused] : "");
        if (c->full_update) {
            snprintf(name, sizeof name, "%s: whole frames without SET_BUFFER (FULL_UPDATE)", base);
            hw_result(sets == 0 && bulks == 3, name, "%d SET_BUFFER, %d bulk transfers for 3 presents", sets, bulks);
        }
        if (c->max_buffer) {
            unsigned per = c->max_buffer / (W * 2);
            unsigned want = 2 * ((H + per - 1) / per) + 1; /* two whole frames, and the 7-row rectangle */
            snprintf(name, sizeof name, "%s: frames are split into transfers of at most %u bytes", base,
                     c->max_buffer);
            hw_result(too_big < 0 && sets == (int)want, name, "%d SET_BUFFERs (want %u)%s%s", sets, want,
                      too_big >= 0 ? "; too big: " : "", too_big >= 0 ? log.lines[too_big] : "");
        }
        if (c->lz4) {
            printf("# %s: %d of %d transfers were LZ4-compressed\n", base, lz4, sets);
#ifdef VFP_HAVE_LZ4
            snprintf(name, sizeof name, "%s: LZ4 is used where it pays (the rendered frame's empty bands)", base);
            hw_result(lz4 > 0, name, "no transfer was compressed, though the device offers LZ4 and liblz4 is in");
#endif
        }
        log_mark = log.count;
        log_free(&log);
    }

    /* 4. unplug and plug back in */
    if (c->unplug) {
        snprintf(name, sizeof name, "%s: present() returns VFP_DISPLAY_LOST once the device is unplugged", base);
        if (set_udc(0, why, sizeof why) != 0 || !wait_usb(c->vid, c->pid, 0, usb, sizeof usb, 5000)) {
            hw_result(0, name, "could not unplug the gadget: %s", why);
        } else {
            gradient(frame, W * 2, 5);
            int st = d.ops->present(&d, 0, 0, W, H, frame, W * 2, err, sizeof err);
            if (st != VFP_DISPLAY_LOST) /* a second try, in case the first only failed */
                st = d.ops->present(&d, 0, 0, W, H, frame, W * 2, err, sizeof err);
            hw_result(st == VFP_DISPLAY_LOST, name, "present() returned %d (%s)", st, st ? err : "ok");
        }
        d.ops->close(&d);
        snprintf(name, sizeof name, "%s: after it is plugged back in, open() finds it again and frames arrive", base);
        if (set_udc(1, why, sizeof why) != 0) {
            hw_result(0, name, "could not plug the gadget back in: %s", why);
        } else if (!wait_usb(c->vid, c->pid, 1, usb, sizeof usb, 10000)) {
            hw_result(0, name, "the device did not come back within 10 s");
        } else if (open_display(&d, c, 5000, err, sizeof err) != 0) {
            hw_result(0, name, "open(): %s", err);
            d.ops = NULL;
        } else {
            present_arrives(&d, dir, name, 0, 0, W, H, frame, W * 2, frame);
        }
        log_read(dir, &log);
        log_mark = log.count;
        log_free(&log);
    }

    /* 5. close */
    if (d.ops) {
        d.ops->close(&d);
        log_settle(dir, &log, log_mark, "SET_CONTROLLER_ENABLE", 3000);
        int doff = -1, coff = -1;
        for (int i = log_mark; i < log.count; i++) {
            if (starts(log.lines[i], "SET_DISPLAY_ENABLE") && field(log.lines[i], "value") == 0)
                doff = i;
            if (starts(log.lines[i], "SET_CONTROLLER_ENABLE") && field(log.lines[i], "value") == 0)
                coff = i;
        }
        snprintf(name, sizeof name, "%s: close() turns the display and then the controller off", base);
        hw_result(doff >= 0 && coff > doff, name, "SET_DISPLAY_ENABLE 0 at line %d, SET_CONTROLLER_ENABLE 0 at %d",
                  doff, coff);
        log_free(&log);
        if (had_usbtest) {
            snprintf(name, sizeof name, "%s: close() gives the interface back to the kernel driver (usbtest)", base);
            hw_result(wait_driver(usb, "usbtest", 3000, driver, sizeof driver), name,
                      "interface %s:1.0 has driver '%s'", usb, driver);
        }
    }
    stop_gadget(gadget);
}

int main(int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--gadget") && i + 1 < argc)
            gadget_path = argv[++i];
        else if (!strcmp(argv[i], "--work") && i + 1 < argc)
            work = argv[++i];
        else {
            fprintf(stderr, "usage: test_gud --gadget PATH/gud_gadget [--work DIR]\n");
            return 2;
        }
    }
    if (!gadget_path) {
        fprintf(stderr, "usage: test_gud --gadget PATH/gud_gadget [--work DIR]\n");
        return 2;
    }
    setvbuf(stdout, NULL, _IOLBF, 0);
    printf("# the kernel's gud driver: %s\n", access("/sys/bus/usb/drivers/gud", F_OK) == 0
                                                   ? "loaded (the backend must detach it)"
                                                   : "not in this kernel (Debian's 6.1 has CONFIG_DRM_GUD unset); "
                                                     "usbtest stands in for a bound driver");
    for (size_t i = 0; i < sizeof configs / sizeof configs[0]; i++)
        run_config(&configs[i], (int)i);
    return hw_failed ? 1 : 0;
}
