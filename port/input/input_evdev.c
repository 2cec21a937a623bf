/* SPDX-License-Identifier: MIT */
/* input_evdev.c: knobs and buttons that the kernel already decodes: the rotary-encoder overlay (EV_REL, REL_X or
 * REL_DIAL, each event whole detents) and gpio-keys (EV_KEY press and release). Every device the board names is
 * opened non-blocking and must answer EVIOCGVERSION (a path to something else is refused at open); several
 * controls may share one (knobs are told apart by axis, buttons by key code).
 *
 * read() follows LVGL's evdev driver: drain every device into state, then report. Turns are summed per knob into
 * one event per read (a fast spin is one event of many detents, not a queue the viewer lags behind); presses and
 * releases are kept in order. A device that goes away (ENODEV, or end of file) makes read() return -1 with
 * "DEVICE: removed". Event times are the kernel's, on CLOCK_MONOTONIC (EVIOCSCLOCKID at open); where the clock
 * cannot be set (a pipe or an emulated device in a test) the time of the read is used instead. */
#include "input.h"
#include "input_backends.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/epoll.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

#include <linux/input.h>

#define MAX_DEVICES (VFP_MAX_KNOBS + VFP_MAX_BUTTONS)
#define CHUNK 64  /* input_events per read() */
#define QUEUE 256 /* events waiting to be reported; draining pauses when fewer than CHUNK slots are free */
#define BITS_PER_LONG (8 * sizeof(unsigned long))
#define TEST_BIT(bits, n) (((bits)[(n) / BITS_PER_LONG] >> ((n) % BITS_PER_LONG)) & 1u)

typedef struct device {
    int fd;
    char path[VFP_PATH_LEN];
    int kernel_time; /* EVIOCSCLOCKID took: event times are CLOCK_MONOTONIC */
    int dropped;     /* SYN_DROPPED seen: skip to the next SYN_REPORT, then read the key state afresh */
} device_t;

typedef struct evdev {
    device_t devices[MAX_DEVICES];
    int device_count;
    int epoll_fd;                       /* with several devices, the one fd the viewer polls; -1 otherwise */
    int knob_count, button_count;
    int knob_device[VFP_MAX_KNOBS], knob_axis[VFP_MAX_KNOBS];
    int button_device[VFP_MAX_BUTTONS], button_code[VFP_MAX_BUTTONS];
    int pressed[VFP_MAX_BUTTONS];       /* the last state reported */
    vfp_event_t queue[QUEUE];           /* drained, not yet reported, in arrival order */
    int queued;
    int turn_slot[VFP_MAX_KNOBS];       /* where knob k's turn of this read sits in the queue, or -1 */
    int removed;                        /* a device went away: every read fails from then on */
    char removed_msg[VFP_PATH_LEN + 64];
} evdev_t;

static vfp_status_t evdev_open(vfp_input_t *in, const vfp_board_t *board, const char *script, char *err, size_t errlen);
static int evdev_fd(vfp_input_t *in);
static uint64_t evdev_deadline(vfp_input_t *in);
static int evdev_read(vfp_input_t *in, vfp_event_t *events, int max, uint64_t now_ns, char *err, size_t errlen);
static void evdev_close(vfp_input_t *in);
static int list_devices(const vfp_board_t *board, const char **paths);
static int device_index(const char *const *paths, int count, const char *path);
static vfp_status_t check_device(evdev_t *e, int d, char *err, size_t errlen);
static void drain(evdev_t *e, int d, uint64_t now_ns);
static void handle(evdev_t *e, int d, const struct input_event *ev, uint64_t now_ns);
static void resync_keys(evdev_t *e, int d, uint64_t now_ns);
static int push(evdev_t *e, vfp_event_type_t type, int control, int steps, uint64_t time_ns);

const vfp_input_ops_t vfp_input_evdev_ops = {
    .name = "evdev",
    .open = evdev_open,
    .fd = evdev_fd,
    .deadline_ns = evdev_deadline,
    .read = evdev_read,
    .close = evdev_close,
};

/* ---------------------------------------------------------------------------------------------------------- */
/* Public functions */

/* The seam for tests (input_backends.h): one fd per distinct device of the board, in the order the board first
 * names them (knob 0's device, knob 1's..., then the buttons'). The input owns the fds from here on, also when
 * this fails. */
vfp_status_t vfp_evdev_open_fds(vfp_input_t *in, const vfp_board_t *board, const int *fds, int count, char *err,
                                size_t errlen)
{
    const char *paths[MAX_DEVICES];
    int want = list_devices(board, paths);
    in->ops = &vfp_input_evdev_ops;
    in->priv = NULL;
    evdev_t *e = calloc(1, sizeof *e);
    if (!e) {
        snprintf(err, errlen, "%s: out of memory", board->path);
        goto fail;
    }
    e->epoll_fd = -1;
    if (count != want) {
        snprintf(err, errlen, "%s: %d devices given for %d named in the board", board->path, count, want);
        goto fail;
    }
    for (int d = 0; d < count; d++) {
        e->devices[d].fd = fds[d];
        snprintf(e->devices[d].path, sizeof e->devices[d].path, "%s", paths[d]);
    }
    e->device_count = count;
    e->knob_count = board->knob_count;
    e->button_count = board->button_count;
    for (int k = 0; k < board->knob_count; k++) {
        e->knob_device[k] = device_index(paths, count, board->knobs[k].device);
        e->knob_axis[k] = board->knobs[k].axis;
        e->turn_slot[k] = -1;
    }
    for (int b = 0; b < board->button_count; b++) {
        e->button_device[b] = device_index(paths, count, board->buttons[b].device);
        e->button_code[b] = board->buttons[b].code;
    }
    for (int d = 0; d < count; d++)
        if (check_device(e, d, err, errlen))
            goto fail;
    if (count > 1) {
        e->epoll_fd = epoll_create1(EPOLL_CLOEXEC);
        if (e->epoll_fd < 0) {
            snprintf(err, errlen, "epoll_create1: %s", strerror(errno));
            goto fail;
        }
        for (int d = 0; d < count; d++) {
            struct epoll_event ev = {.events = EPOLLIN, .data.u32 = (uint32_t)d};
            if (epoll_ctl(e->epoll_fd, EPOLL_CTL_ADD, e->devices[d].fd, &ev) != 0) {
                snprintf(err, errlen, "%s: epoll_ctl: %s", e->devices[d].path, strerror(errno));
                goto fail;
            }
        }
    }
    in->priv = e;
    return VFP_OK;

fail:
    if (e && e->epoll_fd >= 0)
        close(e->epoll_fd);
    for (int d = count - 1; d >= 0; d--)
        close(fds[d]);
    free(e);
    return VFP_ERR;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Static functions: the operations */

static vfp_status_t evdev_open(vfp_input_t *in, const vfp_board_t *board, const char *script, char *err, size_t errlen)
{
    (void)script;
    const char *paths[MAX_DEVICES];
    int fds[MAX_DEVICES];
    int count = list_devices(board, paths);
    for (int d = 0; d < count; d++) {
        fds[d] = open(paths[d], O_RDONLY | O_NONBLOCK | O_CLOEXEC);
        if (fds[d] < 0) {
            int e = errno;
            snprintf(err, errlen, "%s: cannot open: %s%s", paths[d], strerror(e),
                     e == EACCES  ? " (is the user in the input group?)"
                     : e == ENOENT ? " (is the overlay in config.txt, and the path right? see ls /dev/input/by-path)"
                                   : "");
            while (d-- > 0)
                close(fds[d]);
            in->ops = &vfp_input_evdev_ops;
            in->priv = NULL;
            return VFP_ERR;
        }
        /* An event device answers EVIOCGVERSION; a file that does not know the request (ENOTTY: /dev/zero,
         * /dev/null, a regular file, a FIFO, a tty) is not one, and read from as one it would give endless or no
         * events. Other failures pass: umockdev's emulated devices answer every request it has no recording of
         * with ENOENT, and the axis and key checks below are skipped for them the same way. */
        int version;
        if (ioctl(fds[d], EVIOCGVERSION, &version) != 0 && (errno == ENOTTY || errno == EINVAL)) {
            snprintf(err, errlen, "%s: not an input event device (it does not answer EVIOCGVERSION; expected "
                     "a /dev/input/event* device, e.g. /dev/input/by-path/platform-rotary@11-event)", paths[d]);
            for (; d >= 0; d--)
                close(fds[d]);
            in->ops = &vfp_input_evdev_ops;
            in->priv = NULL;
            return VFP_ERR;
        }
    }
    return vfp_evdev_open_fds(in, board, fds, count, err, errlen);
}

static int evdev_fd(vfp_input_t *in)
{
    const evdev_t *e = in->priv;
    if (!e || e->device_count == 0)
        return -1;
    return e->device_count == 1 ? e->devices[0].fd : e->epoll_fd;
}

static uint64_t evdev_deadline(vfp_input_t *in)
{
    /* Events left over from a read() with a small `max` are due at once: their fd may not be readable again. */
    const evdev_t *e = in->priv;
    return e && e->queued > 0 ? 1 : 0;
}

static int evdev_read(vfp_input_t *in, vfp_event_t *events, int max, uint64_t now_ns, char *err, size_t errlen)
{
    evdev_t *e = in->priv;
    if (!e)
        return 0;
    for (int d = 0; d < e->device_count && !e->removed; d++)
        drain(e, d, now_ns);
    if (e->removed) {
        snprintf(err, errlen, "%s", e->removed_msg);
        return -1;
    }

    return vfpi_events_report(e->queue, &e->queued, e->turn_slot, e->knob_count, events, max);
}

static void evdev_close(vfp_input_t *in)
{
    evdev_t *e = in->priv;
    if (!e)
        return;
    if (e->epoll_fd >= 0)
        close(e->epoll_fd);
    for (int d = e->device_count - 1; d >= 0; d--)
        close(e->devices[d].fd);
    free(e);
    in->priv = NULL;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Static functions: devices */

/* The distinct devices of the board, knobs first, in the order named. */
static int list_devices(const vfp_board_t *board, const char **paths)
{
    int count = 0;
    for (int k = 0; k < board->knob_count; k++)
        if (device_index(paths, count, board->knobs[k].device) < 0)
            paths[count++] = board->knobs[k].device;
    for (int b = 0; b < board->button_count; b++)
        if (device_index(paths, count, board->buttons[b].device) < 0)
            paths[count++] = board->buttons[b].device;
    return count;
}

static int device_index(const char *const *paths, int count, const char *path)
{
    for (int d = 0; d < count; d++)
        if (strcmp(paths[d], path) == 0)
            return d;
    return -1;
}

/* Non-blocking, kernel times on CLOCK_MONOTONIC, and (where the device answers) the axes and keys the board
 * expects of it, so that a wrong path is told at open rather than by a knob that does nothing. */
static vfp_status_t check_device(evdev_t *e, int d, char *err, size_t errlen)
{
    device_t *dev = &e->devices[d];
    int flags = fcntl(dev->fd, F_GETFL);
    if (flags < 0 || fcntl(dev->fd, F_SETFL, flags | O_NONBLOCK) < 0) {
        snprintf(err, errlen, "%s: %s", dev->path, strerror(errno));
        return VFP_ERR;
    }
    int clock = CLOCK_MONOTONIC;
    dev->kernel_time = ioctl(dev->fd, EVIOCSCLOCKID, &clock) == 0;

    unsigned long rel[REL_CNT / BITS_PER_LONG + 1] = {0}, keys[KEY_CNT / BITS_PER_LONG + 1] = {0};
    int have_rel = ioctl(dev->fd, EVIOCGBIT(EV_REL, sizeof rel), rel) >= 0;
    int have_keys = ioctl(dev->fd, EVIOCGBIT(EV_KEY, sizeof keys), keys) >= 0;
    for (int k = 0; k < e->knob_count; k++)
        if (e->knob_device[k] == d && have_rel &&
            (e->knob_axis[k] < 0 || e->knob_axis[k] > REL_MAX || !TEST_BIT(rel, (unsigned)e->knob_axis[k]))) {
            snprintf(err, errlen, "%s: no relative axis %d for knob.%d (a rotary-encoder reports REL_X (0) by "
                     "default, or the axis of its linux,axis)", dev->path, e->knob_axis[k], k);
            return VFP_ERR;
        }
    for (int b = 0; b < e->button_count; b++)
        if (e->button_device[b] == d && have_keys &&
            (e->button_code[b] <= 0 || e->button_code[b] > KEY_MAX || !TEST_BIT(keys, (unsigned)e->button_code[b]))) {
            snprintf(err, errlen, "%s: no key %d for button.%d (the gpio-keys node's linux,code)", dev->path,
                     e->button_code[b], b);
            return VFP_ERR;
        }
    return VFP_OK;
}

/* Read everything pending on device d (as long as the queue has room) into the queue; a device that is gone sets
 * e->removed. */
static void drain(evdev_t *e, int d, uint64_t now_ns)
{
    device_t *dev = &e->devices[d];
    struct input_event buf[CHUNK];
    while (e->queued <= QUEUE - CHUNK) {
        ssize_t got = read(dev->fd, buf, sizeof buf);
        if (got < 0 && errno == EINTR)
            continue;
        if (got < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
            return;
        if (got <= 0) {
            /* ENODEV is the kernel's word for an unplugged device; end of file is a pipe's or socket's */
            e->removed = 1;
            if (got == 0 || errno == ENODEV)
                snprintf(e->removed_msg, sizeof e->removed_msg, "%s: removed", dev->path);
            else
                snprintf(e->removed_msg, sizeof e->removed_msg, "%s: %s", dev->path, strerror(errno));
            return;
        }
        size_t count = (size_t)got / sizeof buf[0];
        for (size_t i = 0; i < count; i++)
            handle(e, d, &buf[i], now_ns);
    }
}

static void handle(evdev_t *e, int d, const struct input_event *ev, uint64_t now_ns)
{
    device_t *dev = &e->devices[d];
    uint64_t t = now_ns;
    if (dev->kernel_time)
        t = (uint64_t)ev->input_event_sec * 1000000000u + (uint64_t)ev->input_event_usec * 1000u;

    if (ev->type == EV_SYN && ev->code == SYN_DROPPED) {
        dev->dropped = 1;
        return;
    }
    if (dev->dropped) {
        /* The kernel's buffer overflowed: what follows up to the next report is partial. Detents in it are lost
         * (a knob turned while nobody read); the buttons' state is read afresh so none stays stuck down. */
        if (ev->type == EV_SYN && ev->code == SYN_REPORT) {
            dev->dropped = 0;
            resync_keys(e, d, t);
        }
        return;
    }
    if (ev->type == EV_REL) {
        for (int k = 0; k < e->knob_count; k++) {
            if (e->knob_device[k] != d || e->knob_axis[k] != ev->code)
                continue;
            if (e->turn_slot[k] >= 0) {
                e->queue[e->turn_slot[k]].steps += ev->value;
                e->queue[e->turn_slot[k]].time_ns = t;
            } else if (push(e, VFP_EV_TURN, k, ev->value, t)) {
                e->turn_slot[k] = e->queued - 1;
            }
        }
    } else if (ev->type == EV_KEY && (ev->value == 0 || ev->value == 1)) { /* 2 is autorepeat */
        for (int b = 0; b < e->button_count; b++)
            if (e->button_device[b] == d && e->button_code[b] == ev->code && e->pressed[b] != ev->value) {
                e->pressed[b] = ev->value;
                push(e, ev->value ? VFP_EV_PRESS : VFP_EV_RELEASE, b, 0, t);
            }
    }
}

static void resync_keys(evdev_t *e, int d, uint64_t now_ns)
{
    unsigned long keys[KEY_CNT / BITS_PER_LONG + 1] = {0};
    if (ioctl(e->devices[d].fd, EVIOCGKEY(sizeof keys), keys) < 0)
        return;
    for (int b = 0; b < e->button_count; b++) {
        if (e->button_device[b] != d || e->button_code[b] <= 0 || e->button_code[b] > KEY_MAX)
            continue;
        int down = (int)TEST_BIT(keys, (unsigned)e->button_code[b]);
        if (down != e->pressed[b]) {
            e->pressed[b] = down;
            push(e, down ? VFP_EV_PRESS : VFP_EV_RELEASE, b, 0, now_ns);
        }
    }
}

/* 1 when queued; 0 when the queue is full (drain() stops while CHUNK slots remain, so only a flood of SYN_DROPPED
 * resyncs could get here; the event is then lost). */
static int push(evdev_t *e, vfp_event_type_t type, int control, int steps, uint64_t time_ns)
{
    if (e->queued >= QUEUE)
        return 0;
    e->queue[e->queued++] = (vfp_event_t){.type = type, .control = control, .steps = steps, .time_ns = time_ns};
    return 1;
}
