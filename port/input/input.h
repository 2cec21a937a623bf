/* SPDX-License-Identifier: MIT */
/*
 * input.h: an input is a small table of operations (as LVGL's input drivers): open it, give a file descriptor to
 * poll (or -1 with a deadline), read the events that arrived, close it. Backends: input_gpiod.c (rotary encoders
 * and buttons on GPIO lines, libgpiod 1.6 or 2.x, VFP_HAVE_GPIOD), input_evdev.c (the kernel's rotary-encoder
 * and gpio-keys devices), input_sdl.c (keys of the SDL window, VFP_HAVE_SDL), input_script.c (a file of
 * timestamped events, for the simulator and tests).
 *
 * Contract for a backend (LVGL's "drain, accumulate, report"): read() empties what is pending into at most
 * `max` events and returns how many (0 when nothing happened), or -1 with err when the device is gone. Knob
 * events carry whole detents (quadrature already decoded, four steps a detent); button events are debounced.
 */
#ifndef VFP_INPUT_H
#define VFP_INPUT_H

#include <stddef.h>
#include <stdint.h>

#include "board/board.h"
#include "status.h"

typedef enum vfp_event_type {
    VFP_EV_TURN,    /* knob `control` turned `steps` detents (signed; positive clockwise) */
    VFP_EV_PRESS,   /* button `control` pressed */
    VFP_EV_RELEASE, /* button `control` released */
    VFP_EV_QUIT,    /* the window was closed, or the script ended with "quit" */
} vfp_event_type_t;

typedef struct vfp_event {
    vfp_event_type_t type;
    int control;      /* index into the board's knobs or buttons */
    int steps;        /* VFP_EV_TURN */
    uint64_t time_ns; /* CLOCK_MONOTONIC when it happened (the kernel's timestamp where there is one) */
} vfp_event_t;

typedef struct vfp_input vfp_input_t;

typedef struct vfp_input_ops {
    const char *name; /* the board's input = NAME */
    vfp_status_t (*open)(vfp_input_t *in, const vfp_board_t *board, const char *script, char *err, size_t errlen);
    int (*fd)(vfp_input_t *in);                      /* to poll for reading, or -1 */
    uint64_t (*deadline_ns)(vfp_input_t *in);        /* the next time read() has something without an fd (0: none) */
    int (*read)(vfp_input_t *in, vfp_event_t *events, int max, uint64_t now_ns, char *err, size_t errlen);
    void (*close)(vfp_input_t *in);
} vfp_input_ops_t;

struct vfp_input {
    const vfp_input_ops_t *ops;
    void *priv;
};

const vfp_input_ops_t *vfp_input_find(const char *name, const vfp_board_t *board, char *err, size_t errlen);
extern const vfp_input_ops_t *const vfp_inputs[];

/* ------------------------------------------------------------------------------------------------------- */
/* Pure helpers the backends share, tested on their own (encoder.c). */

/* A quadrature rotary encoder decoded with the 16-entry transition table: each valid edge of A or B moves
 * one step, an invalid transition (a bounce seen as a double edge) moves none, and a detent is four steps. */
typedef struct vfp_encoder {
    uint8_t state; /* (A << 1) | B, the last level seen */
    int steps;     /* steps since the last whole detent */
} vfp_encoder_t;

void vfp_encoder_init(vfp_encoder_t *enc, int a, int b);
/* The new levels of A and B after an edge; returns the whole detents completed (-1, 0 or +1). */
int vfp_encoder_update(vfp_encoder_t *enc, int a, int b);

/* A push button debounced in software: a change counts once the level has been stable for debounce_ms. */
typedef struct vfp_debounce {
    int stable, last;    /* accepted level, and the last level seen */
    uint64_t changed_ns; /* when `last` was first seen */
    uint64_t window_ns;
} vfp_debounce_t;

void vfp_debounce_init(vfp_debounce_t *db, int level, int debounce_ms);
/* Feed a level seen at time now_ns (an edge, or a poll). Returns +1 when an accepted press (level going to
 * `pressed`), -1 for an accepted release, 0 otherwise. */
int vfp_debounce_update(vfp_debounce_t *db, int level, int pressed, uint64_t now_ns);
/* When the pending change will be accepted if nothing else arrives (0: none pending). */
uint64_t vfp_debounce_deadline(const vfp_debounce_t *db);

#endif
