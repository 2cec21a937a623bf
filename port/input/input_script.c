/* SPDX-License-Identifier: MIT */
/* input_script.c: scripted input for the simulator and tests. A text file of timestamped events, one a line
 * (boards/README.md, "Input scripts"):
 *
 *     # TIME_MS is milliseconds after open(), never decreasing
 *     0     turn 0 3         # knob 0 turns 3 detents clockwise (negative: counter-clockwise)
 *     500   press 1          # button 1 goes down...
 *     600   release 1        # ...and up
 *     2000  quit
 *
 * There is no file descriptor to poll: deadline_ns() is the next event's time, and read() returns the events
 * due at now_ns, each stamped with its scheduled time (not the time it was read), so a run is reproducible. */
#include "input.h"
#include "input_backends.h"
#include "io/printable.h"
#include "io/readfile.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define MAX_TIME_MS 1000000000LL /* about 11 days */
#define MAX_STEPS 1000

typedef struct script {
    vfp_event_t *events; /* in time order, time_ns absolute (CLOCK_MONOTONIC) */
    int count, cap;
    int next;            /* the first event not read yet */
} script_t;

static vfp_status_t script_open(vfp_input_t *in, const vfp_board_t *board, const char *script, char *err,
                                size_t errlen);
static int script_fd(vfp_input_t *in);
static uint64_t script_deadline(vfp_input_t *in);
static int script_read(vfp_input_t *in, vfp_event_t *events, int max, uint64_t now_ns, char *err, size_t errlen);
static void script_close(vfp_input_t *in);
static vfp_status_t parse(script_t *s, const vfp_board_t *board, char *text, const char *name, uint64_t start_ns,
                          char *err, size_t errlen);
static int parse_int(const char *s, long long min, long long max, long long *out);
static char *read_file(const char *path, char *err, size_t errlen);
static vfp_status_t printable(char *err, size_t errlen);

const vfp_input_ops_t vfp_input_script_ops = {
    .name = "script",
    .open = script_open,
    .fd = script_fd,
    .deadline_ns = script_deadline,
    .read = script_read,
    .close = script_close,
};

/* ---------------------------------------------------------------------------------------------------------- */
/* Public functions */

/* The seam for tests: a script from a string, its times counted from start_ns. `name` stands for the file in
 * messages. On success in->ops and in->priv are set; on failure nothing is left allocated. */
vfp_status_t vfp_script_load_string(vfp_input_t *in, const vfp_board_t *board, const char *text, const char *name,
                                    uint64_t start_ns, char *err, size_t errlen)
{
    in->ops = &vfp_input_script_ops;
    in->priv = NULL;
    script_t *s = calloc(1, sizeof *s);
    char *copy = strdup(text);
    if (!s || !copy) {
        snprintf(err, errlen, "%s: out of memory", name);
        goto fail;
    }
    if (parse(s, board, copy, name, start_ns, err, errlen))
        goto fail;
    free(copy);
    in->priv = s;
    return VFP_OK;
fail:
    free(copy);
    if (s)
        free(s->events);
    free(s);
    return printable(err, errlen);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Static functions: the operations */

static vfp_status_t script_open(vfp_input_t *in, const vfp_board_t *board, const char *script, char *err, size_t errlen)
{
    const char *path = script && *script ? script : board ? board->script : "";
    if (!*path) {
        snprintf(err, errlen, "%s: input = script needs a script (input.script in the board file, or --script "
                 "FILE)", board && board->path[0] ? board->path : "volfix");
        return VFP_ERR;
    }
    char *text = read_file(path, err, errlen);
    if (!text)
        return printable(err, errlen);
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    uint64_t now = (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
    vfp_status_t status = vfp_script_load_string(in, board, text, path, now, err, errlen);
    free(text);
    return status;
}

static int script_fd(vfp_input_t *in)
{
    (void)in;
    return -1;
}

static uint64_t script_deadline(vfp_input_t *in)
{
    const script_t *s = in->priv;
    if (!s || s->next >= s->count)
        return 0;
    uint64_t t = s->events[s->next].time_ns;
    return t ? t : 1; /* 0 would mean "nothing pending" */
}

static int script_read(vfp_input_t *in, vfp_event_t *events, int max, uint64_t now_ns, char *err, size_t errlen)
{
    (void)err;
    (void)errlen;
    script_t *s = in->priv;
    int n = 0;
    while (s && n < max && s->next < s->count && s->events[s->next].time_ns <= now_ns)
        events[n++] = s->events[s->next++];
    return n;
}

static void script_close(vfp_input_t *in)
{
    script_t *s = in->priv;
    if (s)
        free(s->events);
    free(s);
    in->priv = NULL;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Static functions: parsing */

/* 1 when added, 0 when out of memory. */
static int add(script_t *s, vfp_event_t ev)
{
    if (s->count == s->cap) {
        int cap = s->cap ? s->cap * 2 : 64;
        vfp_event_t *grown = realloc(s->events, sizeof *grown * (size_t)cap);
        if (!grown)
            return 0;
        s->events = grown;
        s->cap = cap;
    }
    s->events[s->count++] = ev;
    return 1;
}

static vfp_status_t parse(script_t *s, const vfp_board_t *board, char *text, const char *name, uint64_t start_ns,
                          char *err, size_t errlen)
{
    int knobs = board ? board->knob_count : VFP_MAX_KNOBS, buttons = board ? board->button_count : VFP_MAX_BUTTONS;
    long long last_ms = 0;
    int line = 0;
    for (char *cur = text, *eol; cur; cur = eol) {
        line++;
        eol = strchr(cur, '\n');
        if (eol)
            *eol++ = '\0';
        char *hash = strchr(cur, '#');
        if (hash)
            *hash = '\0';
        char *save = NULL, *tok[6];
        int ntok = 0;
        for (char *t = strtok_r(cur, " \t\r\f\v", &save); t; t = strtok_r(NULL, " \t\r\f\v", &save))
            if (ntok < 6)
                tok[ntok++] = t;
            else
                ntok = 6;
        if (ntok == 0)
            continue;

        long long ms, index = 0, steps = 0;
        if (!parse_int(tok[0], 0, MAX_TIME_MS, &ms)) {
            snprintf(err, errlen, "%s:%d: expected a time in milliseconds (0 to %lld) first, found '%.40s'", name,
                     line, MAX_TIME_MS, tok[0]);
            return VFP_ERR;
        }
        if (ms < last_ms) {
            snprintf(err, errlen, "%s:%d: time %lld is before the previous event's %lld (times must not decrease)",
                     name, line, ms, last_ms);
            return VFP_ERR;
        }
        last_ms = ms;
        vfp_event_t ev = {.time_ns = start_ns + (uint64_t)ms * 1000000u};
        const char *verb = ntok > 1 ? tok[1] : "";
        if (strcmp(verb, "turn") == 0) {
            if (ntok != 4) {
                snprintf(err, errlen, "%s:%d: expected 'TIME_MS turn KNOB STEPS'", name, line);
                return VFP_ERR;
            }
            if (!parse_int(tok[2], 0, LLONG_MAX, &index) || index >= knobs) {
                if (knobs == 0)
                    snprintf(err, errlen, "%s:%d: turn: the board has no knobs", name, line);
                else
                    snprintf(err, errlen, "%s:%d: turn: expected a knob from 0 to %d, found '%.40s'", name, line,
                             knobs - 1, tok[2]);
                return VFP_ERR;
            }
            if (!parse_int(tok[3], -MAX_STEPS, MAX_STEPS, &steps) || steps == 0) {
                snprintf(err, errlen, "%s:%d: turn: expected detents, a non-zero number from %d to %d, found "
                         "'%.40s'", name, line, -MAX_STEPS, MAX_STEPS, tok[3]);
                return VFP_ERR;
            }
            ev.type = VFP_EV_TURN;
        } else if (strcmp(verb, "press") == 0 || strcmp(verb, "release") == 0) {
            if (ntok != 3) {
                snprintf(err, errlen, "%s:%d: expected 'TIME_MS %s BUTTON'", name, line, verb);
                return VFP_ERR;
            }
            if (!parse_int(tok[2], 0, LLONG_MAX, &index) || index >= buttons) {
                if (buttons == 0)
                    snprintf(err, errlen, "%s:%d: %s: the board has no buttons", name, line, verb);
                else
                    snprintf(err, errlen, "%s:%d: %s: expected a button from 0 to %d, found '%.40s'", name, line,
                             verb, buttons - 1, tok[2]);
                return VFP_ERR;
            }
            ev.type = verb[0] == 'p' ? VFP_EV_PRESS : VFP_EV_RELEASE;
        } else if (strcmp(verb, "quit") == 0) {
            if (ntok != 2) {
                snprintf(err, errlen, "%s:%d: expected 'TIME_MS quit'", name, line);
                return VFP_ERR;
            }
            ev.type = VFP_EV_QUIT;
        } else {
            snprintf(err, errlen, "%s:%d: unknown event '%.40s' (expected turn, press, release or quit)", name, line,
                     verb);
            return VFP_ERR;
        }
        ev.control = (int)index;
        ev.steps = (int)steps;
        if (!add(s, ev)) {
            snprintf(err, errlen, "%s:%d: out of memory", name, line);
            return VFP_ERR;
        }
    }
    return VFP_OK;
}

/* A quoted word may carry a control byte from the file (a terminal escape, a form feed; tests/fuzz sends them).
 * Returns VFP_ERR, for `return printable()`. */
static vfp_status_t printable(char *err, size_t errlen)
{
    if (errlen)
        vfp_printable(err);
    return VFP_ERR;
}

static int parse_int(const char *s, long long min, long long max, long long *out)
{
    char *end;
    errno = 0;
    long long v = strtoll(s, &end, 10);
    if (end == s || *end || errno || v < min || v > max)
        return 0;
    *out = v;
    return 1;
}

static char *read_file(const char *path, char *err, size_t errlen)
{
    char *text;
    size_t len;
    if (vfp_read_text(path, VFP_CAP_SCRIPT, "knob script", &text, &len, err, errlen))
        return NULL;
    unsigned nul = vfp_text_nul_line(text, len);
    if (nul) {
        snprintf(err, errlen, "%s:%u: expected text, found a NUL byte", path, nul);
        free(text);
        return NULL;
    }
    return text;
}
