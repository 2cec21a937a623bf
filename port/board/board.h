/* SPDX-License-Identifier: MIT */
/*
 * board.h: a board is a text file (boards/NAME.board), not code: which display backend and device, the size,
 * pixel format and rotation, which input backend, the GPIO chip (by label) and lines, and what each knob and
 * button does. The format, one setting a line:
 *
 *     # comments start with '#'
 *     name = rpi4-spi-st7789
 *     display = drm                  # drm, fbdev, gud, sdl, png or none
 *     display.device = /dev/dri/card1
 *     display.format = rgb565        # rgb565, xrgb8888 or rgb888 (what the panel takes)
 *     display.rotation = 0           # 0, 90, 180 or 270: how the panel is mounted
 *     input = gpiod                  # gpiod, evdev, sdl or script
 *     gpio.chip = pinctrl-bcm2711    # the chip's label, not its number
 *     knob.0.a = 17                  # line offsets on that chip
 *     knob.0.b = 27
 *     knob.0.pull = up               # up, down or none
 *     knob.0.action = azimuth        # azimuth, elevation, roll, zoom, level, width, light-azimuth,
 *                                    # light-elevation, shade, preset
 *     knob.0.step = 5                # per detent: degrees, percent of zoom, or percent of the window
 *     knob.0.cycle = light-azimuth:10, level:2   # more actions (and their steps) a cycle-knobs button moves
 *                                    # the knob on to, in turn, and back to its action
 *     button.0.line = 22
 *     button.0.action = next-preset  # next-preset, next-mode, reset, overlay, quit, toggle-shade, cycle-knobs
 *
 * All keys are listed in boards/README.md. An error names the file and line and says what was expected:
 * "boards/x.board:7: unknown action 'spin' (expected azimuth, elevation, roll, zoom, level or width)".
 */
#ifndef VFP_BOARD_H
#define VFP_BOARD_H

#include <stddef.h>
#include <stdint.h>

#include "status.h"
#include "volfix.h"

#define VFP_MAX_KNOBS 8
#define VFP_MAX_CYCLE 6 /* a knob's actions: its action and up to five more in knob.N.cycle */
#define VFP_MAX_BUTTONS 8
#define VFP_PATH_LEN 256

typedef enum vfp_action {
    VFP_ACT_NONE,
    VFP_ACT_AZIMUTH,     /* knob: turn the volume about the screen's vertical axis */
    VFP_ACT_ELEVATION,   /* knob: tilt it about the horizontal axis */
    VFP_ACT_ROLL,        /* knob: about the viewing axis */
    VFP_ACT_ZOOM,        /* knob: zoom in and out */
    VFP_ACT_LEVEL,       /* knob: move the window's centre (CT level), moving the transfer function */
    VFP_ACT_WIDTH,       /* knob: widen and narrow the window (CT width) */
    VFP_ACT_LIGHT_AZIMUTH,   /* knob: move the (first) light about the viewer's vertical axis */
    VFP_ACT_LIGHT_ELEVATION, /* knob: move it up and down */
    VFP_ACT_SHADE,       /* knob: shading on (turned clockwise) or off (counter-clockwise) */
    VFP_ACT_PRESET,      /* knob: the next transfer-function preset (clockwise) or the one before */
    VFP_ACT_NEXT_PRESET, /* button: cycle the transfer-function presets */
    VFP_ACT_NEXT_MODE,   /* button: cycle the rendering modes */
    VFP_ACT_RESET,       /* button: back to the first view and window */
    VFP_ACT_OVERLAY,     /* button: show or hide the frame-time overlay */
    VFP_ACT_QUIT,        /* button: leave */
    VFP_ACT_TOGGLE_SHADE, /* button: shading on or off */
    VFP_ACT_CYCLE_KNOBS, /* button: every knob with a knob.N.cycle list takes its next action */
    VFP_ACT_COUNT
} vfp_action_t;

typedef enum vfp_pull { VFP_PULL_NONE, VFP_PULL_UP, VFP_PULL_DOWN } vfp_pull_t;

typedef struct vfp_knob {
    int line_a, line_b;       /* gpiod: line offsets on the board's chip */
    vfp_pull_t pull;
    vfp_action_t action;
    double step;              /* per detent, in the action's unit (default: 5) */
    /* What a cycle-knobs button moves the knob through: cycle[0] is action and step, then knob.N.cycle's;
     * cycle_count 1 when the knob has no cycle */
    int cycle_count;
    vfp_action_t cycle[VFP_MAX_CYCLE];
    double cycle_step[VFP_MAX_CYCLE];
    char device[VFP_PATH_LEN]; /* evdev: the rotary-encoder device */
    int axis;                 /* evdev: REL_X (0) by default, or REL_DIAL (7), REL_WHEEL (8) */
    int key_up, key_down;     /* sdl: SDL key codes that turn it one detent each way */
} vfp_knob_t;

typedef struct vfp_button {
    int line;                 /* gpiod: line offset */
    vfp_pull_t pull;
    int active_low;           /* pressed reads 0 (the usual wiring to ground with a pull-up): default 1 */
    int debounce_ms;          /* default 10 */
    vfp_action_t action;
    char device[VFP_PATH_LEN]; /* evdev: the gpio-keys device */
    int code;                 /* evdev: the key code (KEY_*); sdl: the SDL key code */
} vfp_button_t;

typedef struct vfp_board {
    char name[64];
    char path[VFP_PATH_LEN];      /* the file it came from, for messages */
    /* display */
    char display[16];             /* drm, fbdev, gud, sdl, png */
    char display_device[VFP_PATH_LEN]; /* drm, fbdev: the device; gud: "VID:PID" (default any GUD); png: a directory */
    uint32_t width, height;       /* sdl, png: the size; others take the display's mode (0) */
    vf_format_t format;           /* what the display takes */
    int rotation;                 /* 0, 90, 180, 270 */
    /* input */
    char input[16];               /* gpiod, evdev, sdl, script */
    char gpio_chip[64];           /* gpiod: the chip's label */
    char script[VFP_PATH_LEN];    /* script: the default script file (--script overrides) */
    vfp_knob_t knobs[VFP_MAX_KNOBS];
    int knob_count;
    vfp_button_t buttons[VFP_MAX_BUTTONS];
    int button_count;
    /* rendering */
    int threads;                  /* compositing threads (default: the processors online) */
    int idle_ms;                  /* full quality once the knobs rest this long (default 300) */
    int overlay;                  /* frame-time overlay on at start (default 0) */
} vfp_board_t;

/* Read a board file. Returns VFP_OK, or VFP_ERR with a one-line "FILE:LINE: ..." message in err. */
vfp_status_t vfp_board_load(vfp_board_t *board, const char *path, char *err, size_t errlen);

/* Names, for messages and the parser. */
const char *vfp_action_name(vfp_action_t action);

#endif
