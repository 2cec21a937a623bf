/* SPDX-License-Identifier: MIT */
/*
 * test_gpio.c: the "gpiod" input backend (port/input/input_gpiod.c, gpio_decoder.c) against the kernel's GPIO
 * character device, with the lines simulated by gpio-sim inside the test VM (tests/hw/README.md). Built twice,
 * against libgpiod 1.6 and 2.x; the test names carry the version loaded at run time.
 *
 * It makes two gpio-sim chips through configfs (a decoy first, so the chip under test is not gpiochip0 and the
 * backend has to find it by its label), opens the backend with a board it fills itself (knob 0 on lines 0/1,
 * knob 1 on lines 2/3, a button on line 4, all pulled up, the button active low), and drives the lines from a
 * second thread through gpio-sim's sysfs "pull" files while the main thread polls the backend's fd and reads its
 * events, as the viewer does.
 *
 * "At full speed" means the driver thread writes the edges back to back, with no sleep. It waits for the reader
 * between bursts of at most 12 edges per line: the kernel keeps at most 16 edge events per line (libgpiod 1.6:
 * one 16-event queue per line; 2.x: 16 per requested line), and a burst longer than that could overflow the
 * kernel's queue before any reader had a chance, which no backend can recover from.
 *
 * Usage: test_gpio   (as root, in the VM: gpio-sim loaded, configfs mounted at /sys/kernel/config)
 */
#define _GNU_SOURCE
#include <gpiod.h>
#include <limits.h>
#include <poll.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hwtest.h"
#include "input/input.h"

#define SIM "/sys/kernel/config/gpio-sim"
#define LABEL "volfix-knobs"
#define DECOY "volfix-decoy"
#define NLINES 8
#define BUTTON_LINE 4
#define DEBOUNCE_MS 10
#define MAX_BURST_EDGES_PER_LINE 12

static char prefix[64];     /* "hw/gpio-sim libgpiod 1.6" */
static int pull_fd[NLINES]; /* sim_gpioN/pull of the chip under test */
static int level[NLINES];   /* what the test last wrote */
static char chip_name[64];

/* ---------------------------------------------------------------------------------------------------------- */
/* gpio-sim */

static int sim_make(const char *name, const char *label, int lines, char *dev, size_t devcap, char *chip,
                    size_t chipcap, char *err, size_t errlen)
{
    char path[PATH_MAX], text[32];
    snprintf(path, sizeof path, SIM "/%s", name);
    if (mkdir(path, 0755) != 0) {
        snprintf(err, errlen, "mkdir %s: %s (is gpio-sim loaded and configfs mounted?)", path, strerror(errno));
        return -1;
    }
    snprintf(path, sizeof path, SIM "/%s/bank0", name);
    if (mkdir(path, 0755) != 0) {
        snprintf(err, errlen, "mkdir %s: %s", path, strerror(errno));
        return -1;
    }
    snprintf(text, sizeof text, "%d", lines);
    snprintf(path, sizeof path, SIM "/%s/bank0/num_lines", name);
    if (hw_write_file(path, text, err, errlen))
        return -1;
    snprintf(path, sizeof path, SIM "/%s/bank0/label", name);
    if (hw_write_file(path, label, err, errlen))
        return -1;
    snprintf(path, sizeof path, SIM "/%s/live", name);
    if (hw_write_file(path, "1", err, errlen))
        return -1;
    snprintf(path, sizeof path, SIM "/%s/dev_name", name);
    if (hw_read_file(path, dev, devcap, err, errlen))
        return -1;
    snprintf(path, sizeof path, SIM "/%s/bank0/chip_name", name);
    return hw_read_file(path, chip, chipcap, err, errlen);
}

static void sim_remove(const char *name)
{
    char path[PATH_MAX], err[256];
    snprintf(path, sizeof path, SIM "/%s/live", name);
    hw_write_file(path, "0", err, sizeof err);
    snprintf(path, sizeof path, SIM "/%s/bank0", name);
    rmdir(path);
    snprintf(path, sizeof path, SIM "/%s", name);
    rmdir(path);
}

/* Set a simulated line's level (gpio-sim's pull, which the consumer then reads as the line's value). */
static void set_line(int line, int value)
{
    static const char up[] = "pull-up", down[] = "pull-down";
    const char *s = value ? up : down;
    if (pwrite(pull_fd[line], s, strlen(s), 0) != (ssize_t)strlen(s)) {
        fprintf(stderr, "test_gpio: writing %s to line %d: %s\n", s, line, strerror(errno));
        exit(1);
    }
    level[line] = value;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* The driver thread: a script of edges, in bursts */

#define MAX_SCRIPT 4096
typedef struct step {
    signed char line;  /* -1: end of burst, wait for the reader to catch up */
    signed char value;
    short sleep_ms;    /* after the edge (0: none, full speed) */
} step_t;

static step_t script[MAX_SCRIPT];
static int script_len;
static atomic_int progress;      /* whole detents and button changes the reader has seen, in absolute value */
static int progress_at[MAX_SCRIPT]; /* what progress should be at each end of burst */
static atomic_int driver_done;

static void add(int line, int value, int sleep_ms)
{
    if (script_len < MAX_SCRIPT)
        script[script_len++] = (step_t){(signed char)line, (signed char)value, (short)sleep_ms};
}

static void end_burst(int expected_progress)
{
    progress_at[script_len] = expected_progress;
    add(-1, 0, 0);
}

/* An edge on `line` to `value`, bouncing: `bounces` extra toggles (to the old level and back) at full speed. */
static void add_edge(int line, int value, int bounces)
{
    add(line, value, 0);
    for (int i = 0; i < bounces; i++) {
        add(line, !value, 0);
        add(line, value, 0);
    }
}

/* One detent of knob (lines a, b) from rest (both high): clockwise is A leading B (port/input/encoder.c). */
static void add_detent(int a, int b, int dir, int bounces)
{
    int first = dir > 0 ? a : b, second = dir > 0 ? b : a;
    add_edge(first, 0, bounces);
    add_edge(second, 0, bounces);
    add_edge(first, 1, bounces);
    add_edge(second, 1, bounces);
}

static void *driver_main(void *arg)
{
    (void)arg;
    for (int i = 0; i < script_len; i++) {
        if (script[i].line < 0) {
            uint64_t until = hw_now_ns() + 2000000000ull;
            while (atomic_load(&progress) < progress_at[i] && hw_now_ns() < until)
                hw_sleep_ms(1);
            continue;
        }
        set_line(script[i].line, script[i].value);
        if (script[i].sleep_ms)
            hw_sleep_ms((unsigned)script[i].sleep_ms);
    }
    atomic_store(&driver_done, 1);
    return NULL;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* The reader: what the viewer's loop does */

typedef struct tally {
    int steps[VFP_MAX_KNOBS];
    int turn_events;
    int moved; /* detents in either direction, added up */
    int presses[VFP_MAX_BUTTONS], releases[VFP_MAX_BUTTONS];
    char buttons[64]; /* "PR..." in order */
    int other;
    int time_backwards, time_future, time_zero;
    int read_error;
    int stale_deadline; /* deadline_ns() stayed more than 1 s before the time read() was last given */
    char err[256];
} tally_t;

/* The last event time per control (knobs, then buttons): one control's events come in time order. (Across
 * controls they need not: a read() reports each knob's detents as one event, stamped with its last detent.) */
static uint64_t last_time_ns[VFP_MAX_KNOBS + VFP_MAX_BUTTONS];

static void tally_events(tally_t *t, const vfp_event_t *ev, int n)
{
    for (int i = 0; i < n; i++) {
        const vfp_event_t *e = &ev[i];
        int slot = e->type == VFP_EV_TURN ? e->control : VFP_MAX_KNOBS + e->control;
        uint64_t *last = slot >= 0 && slot < VFP_MAX_KNOBS + VFP_MAX_BUTTONS ? &last_time_ns[slot] : NULL;
        if (e->time_ns == 0)
            t->time_zero++;
        else if (last && e->time_ns < *last)
            t->time_backwards++;
        else if (e->time_ns > hw_now_ns())
            t->time_future++;
        if (e->time_ns && last)
            *last = e->time_ns;
        size_t len = strlen(t->buttons);
        if (e->type == VFP_EV_TURN && e->control >= 0 && e->control < VFP_MAX_KNOBS) {
            t->steps[e->control] += e->steps;
            t->moved += abs(e->steps);
            t->turn_events++;
        } else if (e->type == VFP_EV_PRESS && e->control >= 0 && e->control < VFP_MAX_BUTTONS) {
            t->presses[e->control]++;
            if (len + 1 < sizeof t->buttons)
                t->buttons[len] = 'P';
        } else if (e->type == VFP_EV_RELEASE && e->control >= 0 && e->control < VFP_MAX_BUTTONS) {
            t->releases[e->control]++;
            if (len + 1 < sizeof t->buttons)
                t->buttons[len] = 'R';
        } else {
            t->other++;
        }
    }
}

static int tally_progress(const tally_t *t)
{
    int p = t->moved;
    for (int b = 0; b < VFP_MAX_BUTTONS; b++)
        p += t->presses[b] + t->releases[b];
    return p;
}

/* Poll and read until the driver is done and nothing more has come for quiet_ms (with no pending deadline),
 * or max_ms. */
static void pump(vfp_input_t *in, tally_t *t, unsigned quiet_ms, unsigned max_ms)
{
    uint64_t start = hw_now_ns(), last_event = start, last_read = 0; /* last_read: the now given to read() */
    for (;;) {
        uint64_t now = hw_now_ns();
        if (now - start > (uint64_t)max_ms * 1000000u)
            break;
        uint64_t deadline = in->ops->deadline_ns ? in->ops->deadline_ns(in) : 0;
        if (atomic_load(&driver_done) && now - last_event > (uint64_t)quiet_ms * 1000000u) {
            if (deadline == 0)
                break;
            /* read() was told a time a second past it, and it is still there: judged by the time read() was
             * given, not by the clock now, so a stalled machine cannot make a deadline look stale */
            if (last_read && deadline + 1000000000u < last_read) {
                t->stale_deadline = 1;
                break;
            }
        }
        int timeout = 5;
        if (deadline && deadline > now && (deadline - now) / 1000000u < (uint64_t)timeout)
            timeout = (int)((deadline - now) / 1000000u) + 1;
        int fd = in->ops->fd(in);
        if (fd >= 0) {
            struct pollfd p = {fd, POLLIN, 0};
            poll(&p, 1, timeout);
        } else {
            hw_sleep_ms((unsigned)timeout);
        }
        vfp_event_t ev[64];
        char err[256];
        last_read = hw_now_ns();
        int n = in->ops->read(in, ev, 64, last_read, err, sizeof err);
        if (n < 0) {
            t->read_error++;
            snprintf(t->err, sizeof t->err, "%s", err);
            break;
        }
        if (n > 0) {
            tally_events(t, ev, n);
            atomic_store(&progress, tally_progress(t));
            last_event = hw_now_ns();
        }
    }
}

/* Run the script on the driver thread while reading; the tally of what the backend reported. */
static void run(vfp_input_t *in, tally_t *t, unsigned quiet_ms)
{
    memset(t, 0, sizeof *t);
    atomic_store(&progress, 0);
    atomic_store(&driver_done, 0);
    pthread_t th;
    pthread_create(&th, NULL, driver_main, NULL);
    pump(in, t, quiet_ms, 20000);
    pthread_join(th, NULL);
    script_len = 0;
}

/* The whole tally against what was expected: knob steps, and the button's events in order. */
static void expect(const char *what, const tally_t *t, int k0, int k1, const char *buttons)
{
    char name[256];
    snprintf(name, sizeof name, "%s: %s", prefix, what);
    if (t->read_error)
        hw_result(0, name, "read() failed: %s", t->err);
    else if (t->steps[0] != k0 || t->steps[1] != k1 || strcmp(t->buttons, buttons) != 0 || t->other)
        hw_result(0, name, "knob 0 turned %+d (want %+d), knob 1 %+d (want %+d), button events \"%s\" (want \"%s\")%s",
                  t->steps[0], k0, t->steps[1], k1, t->buttons, buttons, t->other ? ", and unexpected events" : "");
    else if (t->stale_deadline)
        hw_result(0, name, "deadline_ns() stayed in the past for over a second although read() was called");
    else if (t->time_backwards || t->time_future || t->time_zero)
        hw_result(0, name, "event times: %d earlier than the same control's last, %d in the future, %d zero",
                  t->time_backwards, t->time_future, t->time_zero);
    else
        hw_result(1, name, " ");
}

/* Detents on one knob, at full speed, in bursts the kernel's queues hold; `base` is the reader's progress
 * (detents and button changes) before them. */
static void script_turns(int knob, int dir, int detents, int bounces, int base)
{
    int a = knob * 2, b = knob * 2 + 1;
    int edges_per_line = 2 * (1 + 2 * bounces);
    int per_burst = MAX_BURST_EDGES_PER_LINE / edges_per_line;
    if (per_burst < 1)
        per_burst = 1;
    for (int d = 0; d < detents; d++) {
        add_detent(a, b, dir, bounces);
        if ((d + 1) % per_burst == 0 || d + 1 == detents)
            end_burst(base + d + 1);
    }
}

/* Detents on one knob from rest (script_turns), read and checked: knob 0 must turn k0 and knob 1 k1, no button. */
static void turns_read_as(vfp_input_t *in, int knob, int dir, int detents, int bounces, int k0, int k1,
                          const char *what)
{
    tally_t t;
    script_turns(knob, dir, detents, bounces, 0);
    run(in, &t, 100);
    expect(what, &t, k0, k1, "");
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
#if VFP_GPIOD_MAJOR >= 2
    const char *version = gpiod_api_version();
#else
    const char *version = gpiod_version_string();
#endif
    int major = 0, minor = 0;
    sscanf(version, "%d.%d", &major, &minor);
    snprintf(prefix, sizeof prefix, "hw/gpio-sim libgpiod %d.%d", major, minor);
    char name[256], err[512], dev[64], decoy_dev[64], decoy_chip[64];

    snprintf(name, sizeof name, "%s: the libgpiod loaded at run time (%s) is the one built for (%d.x)", prefix,
             version, VFP_GPIOD_MAJOR);
    hw_result(major == VFP_GPIOD_MAJOR, name, "built with VFP_GPIOD_MAJOR=%d", VFP_GPIOD_MAJOR);

    sim_remove(LABEL);
    sim_remove(DECOY);
    snprintf(name, sizeof name, "%s: gpio-sim makes a decoy chip and the chip '%s' through configfs", prefix, LABEL);
    if (sim_make(DECOY, DECOY, 4, decoy_dev, sizeof decoy_dev, decoy_chip, sizeof decoy_chip, err, sizeof err) ||
        sim_make(LABEL, LABEL, NLINES, dev, sizeof dev, chip_name, sizeof chip_name, err, sizeof err)) {
        hw_result(0, name, "%s", err);
        sim_remove(LABEL);
        sim_remove(DECOY);
        return 1;
    }
    hw_result(1, name, " ");
    printf("# %s: decoy %s, '%s' is %s (%s)\n", prefix, decoy_chip, LABEL, chip_name, dev);

    for (int i = 0; i < NLINES; i++) {
        char path[PATH_MAX];
        snprintf(path, sizeof path, "/sys/devices/platform/%s/%s/sim_gpio%d/pull", dev, chip_name, i);
        pull_fd[i] = open(path, O_WRONLY);
        if (pull_fd[i] < 0) {
            fprintf(stderr, "test_gpio: %s: %s\n", path, strerror(errno));
            return 1;
        }
        set_line(i, 1); /* at rest: knobs on a detent with both contacts open, the button up */
    }

    vfp_board_t board;
    memset(&board, 0, sizeof board);
    snprintf(board.name, sizeof board.name, "hw-test");
    snprintf(board.path, sizeof board.path, "tests/hw/test_gpio.c");
    snprintf(board.input, sizeof board.input, "gpiod");
    snprintf(board.gpio_chip, sizeof board.gpio_chip, "%s", LABEL);
    board.knob_count = 2;
    for (int k = 0; k < 2; k++) {
        board.knobs[k].line_a = 2 * k;
        board.knobs[k].line_b = 2 * k + 1;
        board.knobs[k].pull = VFP_PULL_UP;
        board.knobs[k].action = k == 0 ? VFP_ACT_AZIMUTH : VFP_ACT_ZOOM;
        board.knobs[k].step = 5;
    }
    board.button_count = 1;
    board.buttons[0].line = BUTTON_LINE;
    board.buttons[0].pull = VFP_PULL_UP;
    board.buttons[0].active_low = 1;
    board.buttons[0].debounce_ms = DEBOUNCE_MS;
    board.buttons[0].action = VFP_ACT_NEXT_PRESET;

    vfp_input_t in = {0};
    snprintf(name, sizeof name, "%s: open() finds the chip by its label '%s' (%s, not gpiochip0)", prefix, LABEL,
             chip_name);
    const vfp_input_ops_t *ops = vfp_input_find("gpiod", &board, err, sizeof err);
    if (!ops) {
        hw_result(0, name, "%s", err);
        return 1;
    }
    in.ops = ops;
    if (ops->open(&in, &board, NULL, err, sizeof err) != 0) {
        hw_result(0, name, "%s", err);
        sim_remove(LABEL);
        sim_remove(DECOY);
        return 1;
    }
    hw_result(ops->fd(&in) >= 0, name, "fd() is %d", ops->fd(&in));

    tally_t t;
    run(&in, &t, 150);
    expect("nothing moves, nothing is reported", &t, 0, 0, "");

    turns_read_as(&in, 0, +1, 12, 0, 12, 0, "12 clockwise detents at full speed (knob 0, lines 0/1)");
    turns_read_as(&in, 0, -1, 12, 0, -12, 0, "12 counter-clockwise detents at full speed (knob 0)");

    script_turns(1, +1, 8, 0, 0);
    script_turns(1, -1, 3, 0, 8);
    run(&in, &t, 100);
    expect("8 clockwise then 3 counter-clockwise detents at full speed (knob 1, lines 2/3)", &t, 0, 5, "");

    /* both knobs at once: their edges interleaved, one from each in turn */
    for (int d = 0; d < 6; d++) {
        static const int seq_cw[4][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};  /* (line of knob 0, value) */
        static const int seq_ccw[4][2] = {{3, 0}, {2, 0}, {3, 1}, {2, 1}}; /* knob 1 counter-clockwise */
        for (int e = 0; e < 4; e++) {
            add(seq_cw[e][0], seq_cw[e][1], 0);
            add(seq_ccw[e][0], seq_ccw[e][1], 0);
        }
        if (d % 3 == 2)
            end_burst(2 * (d + 1));
    }
    run(&in, &t, 100);
    expect("both knobs turned at once, edges interleaved: +6 and -6", &t, 6, -6, "");

    turns_read_as(&in, 0, +1, 8, 1, 8, 0, "8 clockwise detents with every edge bouncing once (3 edges for 1)");
    turns_read_as(&in, 0, -1, 6, 2, -6, 0,
                  "6 counter-clockwise detents with every edge bouncing twice (5 edges for 1)");

    /* half a detent forward and back, twice: a hand resting on the knob */
    for (int i = 0; i < 2; i++) {
        add(0, 0, 0);
        add(1, 0, 0);
        add(1, 1, 0);
        add(0, 1, 0);
    }
    end_burst(0);
    run(&in, &t, 150);
    expect("half a detent forward and back again is no detent", &t, 0, 0, "");

    /* the button: bounces at full speed, then held well past the debounce time */
    for (int i = 0; i < 3; i++) {
        add_edge(BUTTON_LINE, 0, 4);
        script[script_len - 1].sleep_ms = 5 * DEBOUNCE_MS;
        end_burst(2 * i + 1);
        add_edge(BUTTON_LINE, 1, 4);
        script[script_len - 1].sleep_ms = 5 * DEBOUNCE_MS;
        end_burst(2 * i + 2);
    }
    run(&in, &t, 150);
    expect("3 presses, each bouncing 4 times on the way down and up, give 3 presses and 3 releases", &t, 0, 0,
           "PRPRPR");

    /* a glitch: down and up again at once, far shorter than the debounce time */
    for (int i = 0; i < 5; i++) {
        add(BUTTON_LINE, 0, 0);
        add(BUTTON_LINE, 1, 2 * DEBOUNCE_MS);
    }
    end_burst(0);
    run(&in, &t, 150);
    expect("5 glitches shorter than the 10 ms debounce give no press", &t, 0, 0, "");

    /* turning while the button is held */
    add_edge(BUTTON_LINE, 0, 2);
    script[script_len - 1].sleep_ms = 4 * DEBOUNCE_MS;
    end_burst(1);
    script_turns(1, +1, 4, 0, 1);
    add_edge(BUTTON_LINE, 1, 2);
    script[script_len - 1].sleep_ms = 4 * DEBOUNCE_MS;
    end_burst(6);
    run(&in, &t, 150);
    expect("4 clockwise detents on knob 1 while the button is held", &t, 0, 4, "PR");

    ops->close(&in);
    for (int i = 0; i < NLINES; i++)
        close(pull_fd[i]);
    sim_remove(LABEL);
    sim_remove(DECOY);
    return hw_failed ? 1 : 0;
}
