/* SPDX-License-Identifier: MIT */
/* test_input_evdev.c: the evdev backend (port/input/input_evdev.c).
 *
 * Run as it is, it feeds struct input_event records through pipes (the backend's open-from-fds seam): draining,
 * one turn event per knob per read, presses in order, autorepeat ignored, several devices behind one epoll fd, a
 * device that goes away. Run under umockdev (tests/port/evdev_umockdev.sh starts it with umockdev-run, which sets
 * UMOCKDEV_DIR), it opens the devices of tests/data/evdev/evdev.board by path as the viewer does and checks what
 * the recorded event streams in tests/data/evdev/ add up to. */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/epoll.h>
#include <time.h>
#include <unistd.h>

#include <linux/input.h>

#include "check.h"
#include "input/input.h"
#include "input/input_backends.h" /* the seam in port/input/input_evdev.c */

#define NOW 777000000000ull /* what the tests pass as now_ns */

static uint64_t monotonic_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

/* Knob 0 on device A (REL_X), knob 1 on device A (REL_DIAL), buttons 0 and 1 on device B (KEY_ENTER, KEY_M). */
static vfp_board_t two_devices(void)
{
    vfp_board_t b;
    memset(&b, 0, sizeof b);
    snprintf(b.path, sizeof b.path, "test.board");
    snprintf(b.input, sizeof b.input, "evdev");
    b.knob_count = 2;
    snprintf(b.knobs[0].device, sizeof b.knobs[0].device, "/dev/input/A");
    b.knobs[0].axis = REL_X;
    b.knobs[0].action = VFP_ACT_AZIMUTH;
    snprintf(b.knobs[1].device, sizeof b.knobs[1].device, "/dev/input/A");
    b.knobs[1].axis = REL_DIAL;
    b.knobs[1].action = VFP_ACT_ZOOM;
    b.button_count = 2;
    snprintf(b.buttons[0].device, sizeof b.buttons[0].device, "/dev/input/B");
    b.buttons[0].code = KEY_ENTER;
    b.buttons[0].action = VFP_ACT_RESET;
    snprintf(b.buttons[1].device, sizeof b.buttons[1].device, "/dev/input/B");
    b.buttons[1].code = KEY_M;
    b.buttons[1].action = VFP_ACT_QUIT;
    return b;
}

/* Pipes standing in for the devices: fds[i] for the backend, writers[i] for the test. */
typedef struct rig {
    vfp_input_t in;
    int writers[2];
} rig_t;

static int rig_open(rig_t *r, const vfp_board_t *b, char *err, size_t errlen)
{
    int fds[2];
    for (int i = 0; i < 2; i++) {
        int p[2];
        if (pipe(p) != 0)
            return -1;
        fds[i] = p[0];
        r->writers[i] = p[1];
    }
    return vfp_evdev_open_fds(&r->in, b, fds, 2, err, errlen);
}

static void rig_close(rig_t *r)
{
    r->in.ops->close(&r->in);
    for (int i = 0; i < 2; i++)
        if (r->writers[i] >= 0)
            close(r->writers[i]);
}

static void send_ev(rig_t *r, int dev, int type, int code, int value, int usec)
{
    struct input_event ev;
    memset(&ev, 0, sizeof ev);
    ev.input_event_sec = 12;
    ev.input_event_usec = usec;
    ev.type = (unsigned short)type;
    ev.code = (unsigned short)code;
    ev.value = value;
    if (write(r->writers[dev], &ev, sizeof ev) != (ssize_t)sizeof ev)
        abort();
}

static void syn(rig_t *r, int dev)
{
    send_ev(r, dev, EV_SYN, SYN_REPORT, 0, 0);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Through pipes */

static void turns_sum_per_knob(void)
{
    vfp_board_t b = two_devices();
    rig_t r;
    char err[256] = "";
    CHECK_MSG(rig_open(&r, &b, err, sizeof err) == 0, "%s", err);
    vfp_event_t ev[8];
    CHECK_EQ(r.in.ops->read(&r.in, ev, 8, NOW, err, sizeof err), 0); /* nothing yet */
    for (int i = 0; i < 5; i++) {
        send_ev(&r, 0, EV_REL, REL_X, 1, i);
        syn(&r, 0);
    }
    send_ev(&r, 0, EV_REL, REL_DIAL, -2, 10);
    send_ev(&r, 0, EV_REL, REL_WHEEL, 3, 10); /* an axis no knob uses */
    syn(&r, 0);
    send_ev(&r, 0, EV_REL, REL_X, -1, 11);
    syn(&r, 0);
    int n = r.in.ops->read(&r.in, ev, 8, NOW, err, sizeof err);
    CHECK_EQ(n, 2);
    CHECK_EQ(ev[0].type, VFP_EV_TURN);
    CHECK_EQ(ev[0].control, 0);
    CHECK_EQ(ev[0].steps, 4);
    CHECK_EQ(ev[0].time_ns, NOW); /* a pipe takes no EVIOCSCLOCKID: the time of the read */
    CHECK_EQ(ev[1].control, 1);
    CHECK_EQ(ev[1].steps, -2);
    CHECK_EQ(r.in.ops->deadline_ns(&r.in), 0);
    CHECK_EQ(r.in.ops->read(&r.in, ev, 8, NOW, err, sizeof err), 0);
    /* forth and back in one read: no event */
    send_ev(&r, 0, EV_REL, REL_X, 2, 20);
    send_ev(&r, 0, EV_REL, REL_X, -2, 21);
    CHECK_EQ(r.in.ops->read(&r.in, ev, 8, NOW, err, sizeof err), 0);
    rig_close(&r);
}

static void presses_in_order(void)
{
    vfp_board_t b = two_devices();
    rig_t r;
    char err[256] = "";
    CHECK_MSG(rig_open(&r, &b, err, sizeof err) == 0, "%s", err);
    send_ev(&r, 1, EV_KEY, KEY_ENTER, 1, 0);
    syn(&r, 1);
    send_ev(&r, 1, EV_KEY, KEY_ENTER, 2, 0); /* autorepeat */
    send_ev(&r, 1, EV_KEY, KEY_ENTER, 2, 0);
    send_ev(&r, 1, EV_KEY, KEY_A, 1, 0);     /* not a button of the board */
    send_ev(&r, 1, EV_KEY, KEY_M, 1, 0);
    send_ev(&r, 1, EV_KEY, KEY_ENTER, 0, 0);
    send_ev(&r, 1, EV_KEY, KEY_M, 0, 0);
    send_ev(&r, 1, EV_KEY, KEY_ENTER, 1, 0);
    syn(&r, 1);
    vfp_event_t ev[8];
    int n = r.in.ops->read(&r.in, ev, 8, NOW, err, sizeof err);
    CHECK_EQ(n, 5);
    static const vfp_event_type_t types[5] = {VFP_EV_PRESS, VFP_EV_PRESS, VFP_EV_RELEASE, VFP_EV_RELEASE,
                                              VFP_EV_PRESS};
    static const int controls[5] = {0, 1, 0, 1, 0};
    for (int i = 0; i < 5; i++) {
        CHECK_EQ(ev[i].type, types[i]);
        CHECK_EQ(ev[i].control, controls[i]);
    }
    rig_close(&r);
}

static void small_max_keeps_the_rest(void)
{
    vfp_board_t b = two_devices();
    rig_t r;
    char err[256] = "";
    CHECK_MSG(rig_open(&r, &b, err, sizeof err) == 0, "%s", err);
    send_ev(&r, 0, EV_REL, REL_X, 1, 0);
    send_ev(&r, 1, EV_KEY, KEY_ENTER, 1, 0);
    send_ev(&r, 1, EV_KEY, KEY_ENTER, 0, 0);
    vfp_event_t ev[2];
    CHECK_EQ(r.in.ops->read(&r.in, ev, 2, NOW, err, sizeof err), 2);
    CHECK_EQ(ev[0].type, VFP_EV_TURN);
    CHECK_EQ(ev[1].type, VFP_EV_PRESS);
    CHECK_EQ(r.in.ops->deadline_ns(&r.in), 1); /* the release is waiting, though no fd is readable */
    /* a turn arriving meanwhile joins the next read */
    send_ev(&r, 0, EV_REL, REL_X, 1, 0);
    CHECK_EQ(r.in.ops->read(&r.in, ev, 2, NOW, err, sizeof err), 2);
    CHECK_EQ(ev[0].type, VFP_EV_RELEASE);
    CHECK_EQ(ev[1].type, VFP_EV_TURN);
    CHECK_EQ(ev[1].steps, 1);
    CHECK_EQ(r.in.ops->deadline_ns(&r.in), 0);
    rig_close(&r);
}

static void many_events_drain(void)
{
    /* more than one read() worth (64 records) and more than the queue (256): nothing lost, turns summed */
    vfp_board_t b = two_devices();
    rig_t r;
    char err[256] = "";
    CHECK_MSG(rig_open(&r, &b, err, sizeof err) == 0, "%s", err);
    for (int i = 0; i < 300; i++) {
        send_ev(&r, 0, EV_REL, REL_X, 1, i);
        syn(&r, 0);
        send_ev(&r, 1, EV_KEY, KEY_M, (i & 1) == 0, i);
    }
    int steps = 0, presses = 0, releases = 0, reads = 0;
    vfp_event_t ev[16];
    for (;;) {
        int n = r.in.ops->read(&r.in, ev, 16, NOW, err, sizeof err);
        CHECK(n >= 0);
        if (n == 0)
            break;
        reads++;
        for (int i = 0; i < n; i++) {
            if (ev[i].type == VFP_EV_TURN)
                steps += ev[i].steps;
            presses += ev[i].type == VFP_EV_PRESS;
            releases += ev[i].type == VFP_EV_RELEASE;
        }
        CHECK(reads < 1000);
    }
    CHECK_EQ(steps, 300);
    CHECK_EQ(presses, 150);
    CHECK_EQ(releases, 150);
    rig_close(&r);
}

static void dropped_events_are_skipped(void)
{
    vfp_board_t b = two_devices();
    rig_t r;
    char err[256] = "";
    CHECK_MSG(rig_open(&r, &b, err, sizeof err) == 0, "%s", err);
    send_ev(&r, 0, EV_REL, REL_X, 1, 0);
    syn(&r, 0);
    send_ev(&r, 0, EV_SYN, SYN_DROPPED, 0, 0);
    send_ev(&r, 0, EV_REL, REL_X, 5, 0); /* partial: up to the next report it does not count */
    syn(&r, 0);
    send_ev(&r, 0, EV_REL, REL_X, 2, 0);
    vfp_event_t ev[4];
    CHECK_EQ(r.in.ops->read(&r.in, ev, 4, NOW, err, sizeof err), 1);
    CHECK_EQ(ev[0].steps, 3);
    rig_close(&r);
}

static void one_fd_for_several_devices(void)
{
    vfp_board_t b = two_devices();
    rig_t r;
    char err[256] = "";
    CHECK_MSG(rig_open(&r, &b, err, sizeof err) == 0, "%s", err);
    int fd = r.in.ops->fd(&r.in);
    CHECK(fd >= 0);
    struct pollfd p = {.fd = fd, .events = POLLIN};
    CHECK_EQ(poll(&p, 1, 0), 0);
    send_ev(&r, 1, EV_KEY, KEY_M, 1, 0); /* the second device */
    CHECK_EQ(poll(&p, 1, 1000), 1);
    CHECK(p.revents & POLLIN);
    vfp_event_t ev[2];
    CHECK_EQ(r.in.ops->read(&r.in, ev, 2, NOW, err, sizeof err), 1);
    CHECK_EQ(poll(&p, 1, 0), 0); /* drained */
    rig_close(&r);

    /* one device: its own fd */
    vfp_board_t one = two_devices();
    one.button_count = 0;
    int pfd[2];
    CHECK(pipe(pfd) == 0);
    vfp_input_t in;
    CHECK_MSG(vfp_evdev_open_fds(&in, &one, pfd, 1, err, sizeof err) == 0, "%s", err);
    CHECK_EQ(in.ops->fd(&in), pfd[0]);
    CHECK(fcntl(pfd[0], F_GETFL) & O_NONBLOCK);
    in.ops->close(&in);
    close(pfd[1]);
}

static void removed_device(void)
{
    vfp_board_t b = two_devices();
    rig_t r;
    char err[256] = "";
    CHECK_MSG(rig_open(&r, &b, err, sizeof err) == 0, "%s", err);
    send_ev(&r, 1, EV_KEY, KEY_M, 1, 0);
    close(r.writers[1]); /* the device goes away */
    r.writers[1] = -1;
    vfp_event_t ev[2];
    CHECK_EQ(r.in.ops->read(&r.in, ev, 2, NOW, err, sizeof err), -1);
    CHECK_MSG(strcmp(err, "/dev/input/B: removed") == 0, "%s", err);
    err[0] = '\0';
    CHECK_EQ(r.in.ops->read(&r.in, ev, 2, NOW, err, sizeof err), -1); /* and stays gone */
    CHECK_MSG(strcmp(err, "/dev/input/B: removed") == 0, "%s", err);
    rig_close(&r);
}

static void open_errors(void)
{
    vfp_board_t b = two_devices();
    char err[256] = "";
    const vfp_input_ops_t *ops = vfp_input_find("evdev", &b, err, sizeof err);
    CHECK_MSG(ops, "%s", err);
    vfp_input_t in;
    CHECK_EQ(ops->open(&in, &b, NULL, err, sizeof err), 2);
    CHECK_MSG(strncmp(err, "/dev/input/A: cannot open: No such file or directory (is the overlay", 68) == 0, "%s",
              err);
    ops->close(&in); /* safe after a failed open */
    int p[2];
    CHECK(pipe(p) == 0);
    close(p[1]);
    CHECK_EQ(vfp_evdev_open_fds(&in, &b, p, 1, err, sizeof err), 2);
    CHECK_MSG(strcmp(err, "test.board: 1 devices given for 2 named in the board") == 0, "%s", err);
    CHECK(fcntl(p[0], F_GETFD) < 0 && errno == EBADF); /* the fds were taken, and closed */
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Under umockdev: tests/data/evdev/ replayed on /dev/input/event0..2 */

static void umockdev_replay(void)
{
    vfp_board_t b;
    char err[512] = "";
    CHECK_MSG(vfp_board_load(&b, "tests/data/evdev/evdev.board", err, sizeof err) == 0, "%s", err);
    const vfp_input_ops_t *ops = vfp_input_find(NULL, &b, err, sizeof err);
    CHECK_MSG(ops && strcmp(ops->name, "evdev") == 0, "%s", err);
    vfp_input_t in;
    uint64_t opened = monotonic_ns();
    CHECK_MSG(ops->open(&in, &b, NULL, err, sizeof err) == 0, "%s", err);
    int fd = ops->fd(&in);
    CHECK(fd >= 0);

    int steps[3] = {0, 0, 0}, turn_events = 0;
    vfp_event_t seen[16];
    int nseen = 0;
    uint64_t last = 0;
    int status = 0;
    /* the recordings last 0.6 s; the loop ends as soon as all of it has come, and gives up after 30 s (a cap,
     * not a time the test expects: a stalled machine only makes it wait longer) */
    while (monotonic_ns() - opened < 30000000000ull) {
        struct pollfd p = {.fd = fd, .events = POLLIN};
        poll(&p, 1, 100);
        vfp_event_t ev[8];
        uint64_t now = monotonic_ns();
        int n = ops->read(&in, ev, 8, now, err, sizeof err);
        if (n < 0) {
            status = -1;
            break;
        }
        for (int i = 0; i < n; i++) {
            if (ev[i].time_ns < last || ev[i].time_ns < opened || ev[i].time_ns > now)
                status = -2;
            last = ev[i].time_ns;
            if (ev[i].type == VFP_EV_TURN) {
                steps[ev[i].control] += ev[i].steps;
                turn_events++;
            } else if (nseen < 16) {
                seen[nseen++] = ev[i];
            }
        }
        if (steps[0] == 2 && steps[1] == -2 && steps[2] == 2 && nseen >= 4)
            break;
    }
    ops->close(&in);
    CHECK_MSG(status != -1, "read failed: %s", err);
    CHECK_MSG(status != -2, "event times out of order or outside the run");
    CHECK_EQ(steps[0], 2);
    CHECK_EQ(steps[1], -2);
    CHECK_EQ(steps[2], 2);
    CHECK(turn_events >= 3);
    CHECK_EQ(nseen, 4);
    CHECK_EQ(seen[0].type, VFP_EV_PRESS);
    CHECK_EQ(seen[0].control, 0);
    CHECK_EQ(seen[1].type, VFP_EV_RELEASE);
    CHECK_EQ(seen[1].control, 0);
    CHECK_EQ(seen[2].type, VFP_EV_PRESS);
    CHECK_EQ(seen[2].control, 1);
    CHECK_EQ(seen[3].type, VFP_EV_RELEASE);
    CHECK_EQ(seen[3].control, 1);
}

static void umockdev_wrong_axis(void)
{
    /* a knob on an axis the recording never sends just stays still: no error, no events */
    vfp_board_t b;
    char err[512] = "";
    CHECK_MSG(vfp_board_load(&b, "tests/data/evdev/evdev.board", err, sizeof err) == 0, "%s", err);
    b.knobs[0].axis = REL_HWHEEL;
    b.button_count = 0;
    const vfp_input_ops_t *ops = vfp_input_find(NULL, &b, err, sizeof err);
    vfp_input_t in;
    CHECK_MSG(ops->open(&in, &b, NULL, err, sizeof err) == 0, "%s", err);
    uint64_t start = monotonic_ns();
    int knob0 = 0;
    while (monotonic_ns() - start < 800000000ull) {
        struct pollfd p = {.fd = ops->fd(&in), .events = POLLIN};
        poll(&p, 1, 50);
        vfp_event_t ev[8];
        int n = ops->read(&in, ev, 8, monotonic_ns(), err, sizeof err);
        for (int i = 0; i < n; i++)
            knob0 += ev[i].type == VFP_EV_TURN && ev[i].control == 0;
    }
    ops->close(&in);
    CHECK_EQ(knob0, 0);
}

static const check_case_t pipe_cases[] = {
    {"turns_sum_per_knob", turns_sum_per_knob},
    {"presses_in_order", presses_in_order},
    {"small_max_keeps_the_rest", small_max_keeps_the_rest},
    {"many_events_drain", many_events_drain},
    {"dropped_events_are_skipped", dropped_events_are_skipped},
    {"one_fd_for_several_devices", one_fd_for_several_devices},
    {"removed_device", removed_device},
    {"open_errors", open_errors},
};
static const check_case_t umockdev_cases[] = {
    {"replay", umockdev_replay},
    {"wrong_axis", umockdev_wrong_axis},
};

int main(int argc, char **argv)
{
    if (getenv("UMOCKDEV_DIR"))
        return check_main("evdev-umockdev", umockdev_cases, (int)(sizeof umockdev_cases / sizeof umockdev_cases[0]),
                          argc, argv);
    return check_main("input_evdev", pipe_cases, (int)(sizeof pipe_cases / sizeof pipe_cases[0]), argc, argv);
}
