/* SPDX-License-Identifier: MIT */
/*
 * board_internal.h: what the board file's reader shares between its files and no one else: board.c reads the
 * file line by line and sets each key, board_check.c fills the defaults and checks the file as a whole once it is
 * read, board_names.c holds the names a value may be given by (formats, pulls, booleans, actions, evdev axes and
 * key codes, SDL keys).
 *
 * Names: vfpi_ marks what these files share (as volume_internal.h does for the volume readers). A check returns
 * VFP_OK, or VFP_ERR with one "FILE:LINE: what was expected" line in the parser's err; a lookup or a number parser
 * returns 1 when it understood its text, else 0 (its caller writes the message).
 */
#ifndef VFP_BOARD_INTERNAL_H
#define VFP_BOARD_INTERNAL_H

#include <stddef.h>

#include "board.h"

#define MAX_THREADS 256

/* Actions by kind, and how messages list them (board_names.c holds the names in vfp_action_t's order). */
#define FIRST_KNOB_ACTION VFP_ACT_AZIMUTH
#define LAST_KNOB_ACTION VFP_ACT_PRESET
#define KNOB_ACTIONS "azimuth, elevation, roll, zoom, level, width, light-azimuth, light-elevation, shade or preset"
#define BUTTON_ACTIONS "next-preset, next-mode, reset, overlay, quit, toggle-shade or cycle-knobs"

/* What vfpi_board_sdl_key() takes, for messages. */
#define SDL_KEY_NAMES \
    "a letter, a digit, Left, Right, Up, Down, PageUp, PageDown, Home, End, Space, Return, Escape, Tab, " \
    "Backspace, + - = , . [ ] / (or plus, minus, equals, comma, period, leftbracket, rightbracket, slash)"

/* The keys, one enum per scope; a key's line is remembered for duplicates and for later checks. */
enum top_key { T_NAME, T_DISPLAY, T_DEVICE, T_WIDTH, T_HEIGHT, T_FORMAT, T_ROTATION, T_INPUT, T_SCRIPT, T_CHIP,
               T_THREADS, T_IDLE, T_OVERLAY, T_COUNT };
enum knob_key { KN_A, KN_B, KN_PULL, KN_ACTION, KN_STEP, KN_DEVICE, KN_AXIS, KN_KEY_UP, KN_KEY_DOWN, KN_CYCLE,
                KN_COUNT };
enum button_key { BT_LINE, BT_PULL, BT_ACTIVE_LOW, BT_DEBOUNCE, BT_ACTION, BT_DEVICE, BT_CODE, BT_COUNT };

typedef struct vfpi_board_parser {
    vfp_board_t *board;
    const char *path;
    char *err;
    size_t errlen;
    int line;                                      /* the line being read, from 1 */
    int top_line[T_COUNT];                         /* where each key was given (0: not given) */
    int knob_line[VFP_MAX_KNOBS][KN_COUNT];
    int knob_first[VFP_MAX_KNOBS];                 /* the first line naming knob N */
    int button_line[VFP_MAX_BUTTONS][BT_COUNT];
    int button_first[VFP_MAX_BUTTONS];
    char button_code[VFP_MAX_BUTTONS][64];         /* resolved once the input backend is known */
} vfpi_board_parser_t;

/* board.c: "FILE:LINE: message" (line 0: "FILE: message") into p->err; returns VFP_ERR, so that a check can
 * `return vfpi_board_fail(...)`. */
vfp_status_t vfpi_board_fail(vfpi_board_parser_t *p, int line, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* board.c: a whole number with nothing after it, in [min, max] (base as strtol's); 1 if it is one, else 0. */
int vfpi_board_parse_long(const char *s, int base, long min, long max, long *out);

/* board_check.c: after the last line, the defaults of what was not given, then the checks of the whole file. */
vfp_status_t vfpi_board_finish(vfpi_board_parser_t *p);

/* board_names.c: a name to what it stands for. Each returns 1 and sets the value when it knows the name, else 0;
 * names match exactly, except SDL's. */
int vfpi_board_format(const char *name, int *format); /* a vf_format_t: rgb565, xrgb8888, rgb888 */
int vfpi_board_pull(const char *name, int *pull);     /* a vfp_pull_t: up, down, none */
int vfpi_board_boolean(const char *name, int *flag);  /* 1 or 0: 1/0, yes/no, true/false, on/off */
/* REL_X, REL_DIAL... (linux/input-event-codes.h). */
int vfpi_board_evdev_axis(const char *name, int *axis);
/* KEY_* and BTN_* names a gpio-keys overlay is likely to be given. */
int vfpi_board_evdev_key(const char *name, int *code);
/* An SDL key name (SDL_KEY_NAMES), without case, as SDL 2's key code. */
int vfpi_board_sdl_key(const char *name, int *code);
/* An action's name: its vfp_action_t (VFP_ACT_NONE for "none"), or -1. */
int vfpi_board_action(const char *name);

#endif /* VFP_BOARD_INTERNAL_H */
