/* SPDX-License-Identifier: MIT */
/* input_sdl.c: the keys of the SDL window (VFP_HAVE_SDL) as knobs and buttons, for a desktop. The window belongs to
 * the SDL display (display_sdl.c); SDL itself is shared through sdl_video.h. A key press of a knob's key_up or
 * key_down turns it one detent (held down, the key's auto-repeat keeps turning it); a button's key gives press and
 * release; closing the window is VFP_EV_QUIT.
 *
 * SDL has no file descriptor to poll: fd() is -1 and deadline_ns() is 10 ms after the last read(). Event
 * times are the time of the read (SDL's own timestamps count milliseconds from SDL_Init, another clock). */
#include "input.h"
#include "input_backends.h"

#ifdef VFP_HAVE_SDL

#include <SDL.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "display/sdl_video.h"

#define POLL_NS 10000000u /* how often the viewer should look at SDL's queue */

typedef struct sdl_input {
    int knob_count, button_count;
    int key_up[VFP_MAX_KNOBS], key_down[VFP_MAX_KNOBS];
    int code[VFP_MAX_BUTTONS];
    int pressed[VFP_MAX_BUTTONS];
    uint64_t next_look_ns; /* 10 ms after the last read: when SDL's queue is due a look again */
} sdl_input_t;

static vfp_status_t sdl_open(vfp_input_t *in, const vfp_board_t *board, const char *script, char *err, size_t errlen);
static int sdl_fd(vfp_input_t *in);
static uint64_t sdl_deadline(vfp_input_t *in);
static int sdl_read(vfp_input_t *in, vfp_event_t *events, int max, uint64_t now_ns, char *err, size_t errlen);
static void sdl_close(vfp_input_t *in);
static uint64_t monotonic_ns(void);
static int add_turn(vfp_event_t *events, int n, int max, int knob, int steps, uint64_t now_ns);

const vfp_input_ops_t vfp_input_sdl_ops = {
    .name = "sdl",
    .open = sdl_open,
    .fd = sdl_fd,
    .deadline_ns = sdl_deadline,
    .read = sdl_read,
    .close = sdl_close,
};

/* ---------------------------------------------------------------------------------------------------------- */
/* Static functions: the operations */

static vfp_status_t sdl_open(vfp_input_t *in, const vfp_board_t *board, const char *script, char *err, size_t errlen)
{
    (void)script;
    in->ops = &vfp_input_sdl_ops;
    in->priv = NULL;
    sdl_input_t *s = calloc(1, sizeof *s);
    if (!s) {
        snprintf(err, errlen, "%s: out of memory", board->path);
        return VFP_ERR;
    }
    if (vfp_sdl_init(err, errlen)) {
        free(s);
        return VFP_ERR;
    }
    s->knob_count = board->knob_count;
    s->button_count = board->button_count;
    for (int k = 0; k < s->knob_count; k++) {
        s->key_up[k] = board->knobs[k].key_up;
        s->key_down[k] = board->knobs[k].key_down;
    }
    for (int b = 0; b < s->button_count; b++)
        s->code[b] = board->buttons[b].code;
    s->next_look_ns = 1; /* at once */
    in->priv = s;
    return VFP_OK;
}

static int sdl_fd(vfp_input_t *in)
{
    (void)in;
    return -1;
}

static uint64_t sdl_deadline(vfp_input_t *in)
{
    /* A fixed point in time, not "now + 10 ms" recomputed on every call: a caller that compares the deadline with
     * the time it took before asking must see it come due. */
    const sdl_input_t *s = in->priv;
    return s ? s->next_look_ns : 0;
}

static int sdl_read(vfp_input_t *in, vfp_event_t *events, int max, uint64_t now_ns, char *err, size_t errlen)
{
    (void)err;
    (void)errlen;
    sdl_input_t *s = in->priv;
    if (!s)
        return 0;
    s->next_look_ns = monotonic_ns() + POLL_NS;
    int n = 0;
    SDL_Event ev;
    /* Stop while there is room for one more event: what is left stays in SDL's queue for the next read. */
    while (n < max && SDL_PollEvent(&ev)) {
        if (ev.type == SDL_QUIT) {
            events[n++] = (vfp_event_t){.type = VFP_EV_QUIT, .time_ns = now_ns};
            continue;
        }
        if (ev.type != SDL_KEYDOWN && ev.type != SDL_KEYUP)
            continue;
        int sym = (int)ev.key.keysym.sym, down = ev.type == SDL_KEYDOWN;
        for (int k = 0; k < s->knob_count && down; k++) {
            if (sym == s->key_up[k])
                n = add_turn(events, n, max, k, +1, now_ns);
            else if (sym == s->key_down[k])
                n = add_turn(events, n, max, k, -1, now_ns);
        }
        for (int b = 0; b < s->button_count && n < max; b++)
            if (sym == s->code[b] && !ev.key.repeat && s->pressed[b] != down) {
                s->pressed[b] = down;
                events[n++] = (vfp_event_t){.type = down ? VFP_EV_PRESS : VFP_EV_RELEASE, .control = b,
                                            .time_ns = now_ns};
            }
    }
    /* turns that came back to nothing (up and down in one read) are left out */
    int kept = 0;
    for (int i = 0; i < n; i++)
        if (events[i].type != VFP_EV_TURN || events[i].steps != 0)
            events[kept++] = events[i];
    return kept;
}

static void sdl_close(vfp_input_t *in)
{
    if (!in->priv)
        return;
    free(in->priv);
    in->priv = NULL;
    vfp_sdl_quit();
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Static functions: helpers */

static uint64_t monotonic_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

/* One turn event per knob per read: add to the knob's event of this read, or start one. */
static int add_turn(vfp_event_t *events, int n, int max, int knob, int steps, uint64_t now_ns)
{
    for (int i = 0; i < n; i++)
        if (events[i].type == VFP_EV_TURN && events[i].control == knob) {
            events[i].steps += steps;
            events[i].time_ns = now_ns;
            return n;
        }
    if (n < max)
        events[n++] = (vfp_event_t){.type = VFP_EV_TURN, .control = knob, .steps = steps, .time_ns = now_ns};
    return n;
}

#else

/* Without SDL the file compiles to nothing (input.h's declarations only): input.c does not list the backend. */

#endif /* VFP_HAVE_SDL */
