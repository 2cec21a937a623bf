/* SPDX-License-Identifier: MIT */
/* board_check.c: a board file once every line is read (board.c): the defaults of what it does not give, then the
 * checks that need more than one key: every knob and button has what its input backend needs, indices are dense,
 * a button's code is read in the backend's terms, and no line, axis or key serves two controls. */
#include "board_internal.h"

#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include <linux/input-event-codes.h>

#define DEFAULT_STEP 5.0
#define DEFAULT_DEBOUNCE_MS 10
#define DEFAULT_IDLE_MS 300
#define DEFAULT_SIZE_W 320 /* sdl and png, when the file gives no size */
#define DEFAULT_SIZE_H 240

/* ---------------------------------------------------------------------------------------------------------- */
/* Prototypes */

static vfp_status_t check_dense(vfpi_board_parser_t *p, const char *what, const int *first, int count, int *count_out);
static vfp_status_t check_input(vfpi_board_parser_t *p);
static vfp_status_t check_lines(vfpi_board_parser_t *p);
static vfp_status_t check_shared(vfpi_board_parser_t *p, int evdev, int sdl);

/* ---------------------------------------------------------------------------------------------------------- */
/* Shared functions */

vfp_status_t vfpi_board_finish(vfpi_board_parser_t *p)
{
    vfp_board_t *b = p->board;
    if (!b->display[0])
        return vfpi_board_fail(p, 0, "no display given (expected display = drm, fbdev, gud, sdl, png or none)");
    if (!b->input[0])
        return vfpi_board_fail(p, 0, "no input given (expected input = gpiod, evdev, sdl or script)");

    /* defaults of what was not given */
    if (!p->top_line[T_NAME]) {
        const char *base = strrchr(p->path, '/');
        base = base ? base + 1 : p->path;
        size_t len = strlen(base);
        if (len > 6 && strcmp(base + len - 6, ".board") == 0)
            len -= 6;
        snprintf(b->name, sizeof b->name, "%.*s", (int)(len < sizeof b->name ? len : sizeof b->name - 1), base);
    }
    int is_sdl = strcmp(b->display, "sdl") == 0;
    int is_png = strcmp(b->display, "png") == 0 || strcmp(b->display, "none") == 0; /* sized and formatted alike */
    if (!p->top_line[T_FORMAT])
        b->format = strcmp(b->display, "gud") == 0 ? VF_FORMAT_RGB565 : is_png ? VF_FORMAT_RGB888
                                                                               : VF_FORMAT_XRGB8888;
    if (is_sdl || is_png) {
        if (!b->width)
            b->width = DEFAULT_SIZE_W;
        if (!b->height)
            b->height = DEFAULT_SIZE_H;
    }
    if (!b->display_device[0]) {
        const char *dev = strcmp(b->display, "drm") == 0 ? "/dev/dri/card0"
                          : strcmp(b->display, "fbdev") == 0 ? "/dev/fb0"
                          : strcmp(b->display, "png") == 0 ? "out/frames" : "";
        snprintf(b->display_device, sizeof b->display_device, "%s", dev);
    }
    if (!b->threads) {
        long cpus = sysconf(_SC_NPROCESSORS_ONLN);
        b->threads = cpus < 1 ? 1 : cpus > MAX_THREADS ? MAX_THREADS : (int)cpus;
    }
    if (!p->top_line[T_IDLE])
        b->idle_ms = DEFAULT_IDLE_MS;

    if (check_dense(p, "knob", p->knob_first, VFP_MAX_KNOBS, &b->knob_count) ||
        check_dense(p, "button", p->button_first, VFP_MAX_BUTTONS, &b->button_count))
        return VFP_ERR;
    for (int i = 0; i < b->knob_count; i++) {
        vfp_knob_t *k = &b->knobs[i];
        if (!p->knob_line[i][KN_A])
            k->line_a = -1;
        if (!p->knob_line[i][KN_B])
            k->line_b = -1;
        if (!p->knob_line[i][KN_PULL])
            k->pull = VFP_PULL_UP;
        if (!p->knob_line[i][KN_STEP])
            k->step = DEFAULT_STEP;
        if (!p->knob_line[i][KN_AXIS])
            k->axis = REL_X;
        if (!p->knob_line[i][KN_ACTION])
            return vfpi_board_fail(p, p->knob_first[i],
                                   "knob.%d has no action (expected knob.%d.action = " KNOB_ACTIONS ")", i, i);
        if (!p->knob_line[i][KN_CYCLE])
            k->cycle_count = 1;
        k->cycle[0] = k->action;
        k->cycle_step[0] = k->step;
    }
    for (int i = 0; i < b->button_count; i++) {
        vfp_button_t *btn = &b->buttons[i];
        if (!p->button_line[i][BT_LINE])
            btn->line = -1;
        if (!p->button_line[i][BT_PULL])
            btn->pull = VFP_PULL_UP;
        if (!p->button_line[i][BT_ACTIVE_LOW])
            btn->active_low = 1;
        if (!p->button_line[i][BT_DEBOUNCE])
            btn->debounce_ms = DEFAULT_DEBOUNCE_MS;
        if (!p->button_line[i][BT_ACTION])
            return vfpi_board_fail(p, p->button_first[i],
                                   "button.%d has no action (expected button.%d.action = " BUTTON_ACTIONS ")", i, i);
    }
    return check_input(p);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Static functions */

/* Knobs (buttons) are numbered 0, 1, 2... with no gap: the count is one more than the highest index. */
static vfp_status_t check_dense(vfpi_board_parser_t *p, const char *what, const int *first, int max, int *count_out)
{
    int count = 0;
    for (int i = 0; i < max; i++)
        if (first[i])
            count = i + 1;
    for (int i = 0; i < count; i++) {
        if (first[i])
            continue;
        int j = i + 1;
        while (!first[j])
            j++;
        return vfpi_board_fail(p, first[j], "%s.%d given but %s.%d is missing (indices must be dense from 0)", what, j,
                               what, i);
    }
    *count_out = count;
    return VFP_OK;
}

/* What the input backend needs of every knob and button, and each button's code in the backend's terms. */
static vfp_status_t check_input(vfpi_board_parser_t *p)
{
    vfp_board_t *b = p->board;
    int input_line = p->top_line[T_INPUT];
    int gpiod = strcmp(b->input, "gpiod") == 0, evdev = strcmp(b->input, "evdev") == 0,
        sdl = strcmp(b->input, "sdl") == 0;

    if (gpiod && !b->gpio_chip[0])
        return vfpi_board_fail(p, input_line,
                               "input = gpiod needs gpio.chip (the GPIO chip's label, e.g. pinctrl-bcm2711)");
    for (int i = 0; i < b->knob_count; i++) {
        const vfp_knob_t *k = &b->knobs[i];
        int line = p->knob_first[i];
        if (gpiod && (k->line_a < 0 || k->line_b < 0))
            return vfpi_board_fail(p, line, "knob.%d: input = gpiod needs knob.%d.a and knob.%d.b (line offsets on %s)",
                                   i, i, i, b->gpio_chip);
        if (evdev && !k->device[0])
            return vfpi_board_fail(p, line,
                                   "knob.%d: input = evdev needs knob.%d.device (the rotary-encoder's event device, "
                                   "e.g. /dev/input/by-path/platform-rotary@11-event)", i, i);
        if (sdl && (!k->key_up || !k->key_down))
            return vfpi_board_fail(p, line,
                                   "knob.%d: input = sdl needs knob.%d.key_up and knob.%d.key_down (SDL key names "
                                   "such as Left and Right)", i, i, i);
    }
    for (int i = 0; i < b->button_count; i++) {
        vfp_button_t *btn = &b->buttons[i];
        int line = p->button_first[i], code_line = p->button_line[i][BT_CODE];
        const char *code = p->button_code[i];
        if (gpiod && btn->line < 0)
            return vfpi_board_fail(p, line, "button.%d: input = gpiod needs button.%d.line (a line offset on %s)", i, i,
                                   b->gpio_chip);
        if (evdev && !btn->device[0])
            return vfpi_board_fail(p, line,
                                   "button.%d: input = evdev needs button.%d.device (the gpio-keys event device, e.g. "
                                   "/dev/input/by-path/platform-gpio-keys-event)", i, i);
        if ((evdev || sdl) && !code_line)
            return vfpi_board_fail(p, line, "button.%d: input = %s needs button.%d.code (%s)", i, b->input, i,
                                   evdev ? "a KEY_* name such as KEY_ENTER" : "an SDL key name such as Space");
        if (!code_line)
            continue;
        long v;
        int value;
        int as_evdev = vfpi_board_evdev_key(code, &value), as_sdl = !as_evdev && vfpi_board_sdl_key(code, &value);
        if (evdev && !as_evdev && !vfpi_board_parse_long(code, 0, 1, KEY_MAX, &v))
            return vfpi_board_fail(p, code_line,
                                   "button.%d.code: unknown key '%.60s' (expected a KEY_* or BTN_* name from "
                                   "linux/input-event-codes.h, or a number from 1 to %d)", i, code, KEY_MAX);
        if (sdl && !as_sdl && !vfpi_board_parse_long(code, 0, 1, INT_MAX, &v))
            return vfpi_board_fail(p, code_line, "button.%d.code: unknown SDL key '%.60s' (expected %s)", i, code,
                                   SDL_KEY_NAMES);
        if (!as_evdev && !as_sdl && !vfpi_board_parse_long(code, 0, 1, INT_MAX, &v))
            return vfpi_board_fail(p, code_line,
                                   "button.%d.code: unknown key '%.60s' (expected a KEY_* name for evdev, an "
                                   "SDL key name for sdl, or a number)", i, code);
        btn->code = as_evdev || as_sdl ? value : (int)v;
    }
    if (gpiod)
        return check_lines(p);
    return check_shared(p, evdev, sdl);
}

/* evdev: two knobs on one device need different axes, two buttons different codes; sdl: every key does one thing. */
static vfp_status_t check_shared(vfpi_board_parser_t *p, int evdev, int sdl)
{
    const vfp_board_t *b = p->board;
    for (int i = 0; i < b->knob_count; i++)
        for (int j = 0; j < i; j++) {
            const vfp_knob_t *ki = &b->knobs[i], *kj = &b->knobs[j];
            if (evdev && ki->axis == kj->axis && strcmp(ki->device, kj->device) == 0)
                return vfpi_board_fail(p, p->knob_first[i],
                                       "knob.%d: knob.%d already reads axis %d of %s (give each knob on "
                                       "a device its own knob.N.axis)", i, j, ki->axis, ki->device);
            int ki_keys[2] = {ki->key_up, ki->key_down}, kj_keys[2] = {kj->key_up, kj->key_down};
            for (int a = 0; sdl && a < 2; a++)
                for (int c = 0; c < 2; c++)
                    if (ki_keys[a] == kj_keys[c])
                        return vfpi_board_fail(p, p->knob_first[i], "knob.%d: its %s key is knob.%d's %s key already",
                                               i, a ? "key_down" : "key_up", j, c ? "key_down" : "key_up");
        }
    for (int i = 0; i < b->button_count; i++) {
        const vfp_button_t *bi = &b->buttons[i];
        int line = p->button_line[i][BT_CODE] ? p->button_line[i][BT_CODE] : p->button_first[i];
        for (int j = 0; j < i; j++)
            if ((evdev || sdl) && bi->code == b->buttons[j].code &&
                (!evdev || strcmp(bi->device, b->buttons[j].device) == 0))
                return vfpi_board_fail(p, line, "button.%d.code: button.%d has that key already", i, j);
        for (int k = 0; sdl && k < b->knob_count; k++)
            if (bi->code == b->knobs[k].key_up || bi->code == b->knobs[k].key_down)
                return vfpi_board_fail(p, line, "button.%d.code: that key turns knob.%d already", i, k);
    }
    return VFP_OK;
}

/* Each GPIO line serves one purpose. */
static vfp_status_t check_lines(vfpi_board_parser_t *p)
{
    const vfp_board_t *b = p->board;
    struct use {
        int offset, line;
        char key[32];
    } uses[VFP_MAX_KNOBS * 2 + VFP_MAX_BUTTONS];
    int n = 0;
    for (int i = 0; i < b->knob_count; i++) {
        uses[n] = (struct use){b->knobs[i].line_a, p->knob_line[i][KN_A], ""};
        snprintf(uses[n++].key, sizeof uses[0].key, "knob.%d.a", i);
        uses[n] = (struct use){b->knobs[i].line_b, p->knob_line[i][KN_B], ""};
        snprintf(uses[n++].key, sizeof uses[0].key, "knob.%d.b", i);
    }
    for (int i = 0; i < b->button_count; i++) {
        uses[n] = (struct use){b->buttons[i].line, p->button_line[i][BT_LINE], ""};
        snprintf(uses[n++].key, sizeof uses[0].key, "button.%d.line", i);
    }
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            if (j != i && uses[j].offset == uses[i].offset && uses[j].line < uses[i].line)
                return vfpi_board_fail(p, uses[i].line, "%s: line %d is already used by %s (line %d)", uses[i].key,
                                       uses[i].offset, uses[j].key, uses[j].line);
    return VFP_OK;
}
