/* SPDX-License-Identifier: MIT */
/* board.c: read a board file (board.h; every key is described in boards/README.md) into a vfp_board_t, with one
 * "FILE:LINE: what was expected" line for anything wrong. This file reads the lines and sets each key on its own;
 * board_check.c takes over once the last line is read (defaults, and checks across keys), and board_names.c holds
 * the long name tables (board_internal.h). */
#include "board_internal.h"
#include "io/printable.h"
#include "io/readfile.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <linux/input-event-codes.h>

#define MAX_LINE_OFFSET 65535
#define DEFAULT_CYCLE_STEP 5.0 /* a cycled action's step when knob.N.cycle gives none, as knob.N.step's default */

/* ---------------------------------------------------------------------------------------------------------- */
/* Tables */

/* The keys, in the order of board_internal.h's enums. */
static const char *const top_keys[T_COUNT] = {
    "name", "display", "display.device", "display.width", "display.height", "display.format", "display.rotation",
    "input", "input.script", "gpio.chip", "threads", "idle_ms", "overlay",
};
static const char *const knob_keys[KN_COUNT] = {"a", "b", "pull", "action", "step", "device", "axis", "key_up",
                                                "key_down", "cycle"};
static const char *const button_keys[BT_COUNT] = {"line", "pull", "active_low", "debounce_ms", "action", "device",
                                                  "code"};

static const char *const displays[] = {"drm", "fbdev", "gud", "sdl", "png", "none"};
static const char *const inputs[] = {"gpiod", "evdev", "sdl", "script"};

/* ---------------------------------------------------------------------------------------------------------- */
/* Prototypes */

static char *trim(char *s);
static vfp_status_t parse_line(vfpi_board_parser_t *p, char *text);
static vfp_status_t set_top(vfpi_board_parser_t *p, int key, const char *keyname, const char *value);
static vfp_status_t set_knob(vfpi_board_parser_t *p, int n, int key, const char *keyname, const char *value);
static vfp_status_t set_button(vfpi_board_parser_t *p, int n, int key, const char *keyname, const char *value);
static int index_of(const char *const *names, int count, const char *name);
static vfp_status_t copy_string(vfpi_board_parser_t *p, char *dst, size_t size, const char *keyname, const char *value);
static void join_names(char *out, size_t size, const char *const *names, int count, const char *last);

/* A message that quotes a path, made one printable line; returns VFP_ERR. */
static vfp_status_t printable_err(char *err, size_t errlen)
{
    if (errlen)
        vfp_printable(err);
    return VFP_ERR;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Public functions */

vfp_status_t vfp_board_load(vfp_board_t *board, const char *path, char *err, size_t errlen)
{
    vfpi_board_parser_t *p = calloc(1, sizeof *p);
    if (!p) {
        snprintf(err, errlen, "%s: out of memory", path);
        return VFP_ERR;
    }
    p->board = board;
    p->path = path;
    p->err = err;
    p->errlen = errlen;
    memset(board, 0, sizeof *board);
    snprintf(board->path, sizeof board->path, "%s", path);

    vfp_status_t status = VFP_OK;
    char *text = NULL;
    size_t size;
    if (vfp_read_text(path, VFP_CAP_BOARD, "board file", &text, &size, err, errlen)) {
        free(p);
        return printable_err(err, errlen);
    }
    unsigned nul = vfp_text_nul_line(text, size);
    char *cursor = text, *line;
    while ((line = vfp_text_next_line(&cursor)) != NULL) {
        p->line++;
        if ((unsigned)p->line == nul) {
            status = vfpi_board_fail(p, p->line, "expected text, found a NUL byte");
            break;
        }
        if ((status = parse_line(p, line)) != VFP_OK)
            break;
    }
    if (status == VFP_OK)
        status = vfpi_board_finish(p);
    free(text);
    free(p);
    return status;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Shared functions */

vfp_status_t vfpi_board_fail(vfpi_board_parser_t *p, int line, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (line > 0)
        snprintf(p->err, p->errlen, "%s:%d: %s", p->path, line, msg);
    else
        snprintf(p->err, p->errlen, "%s: %s", p->path, msg);
    /* a quoted key or value may carry a vertical tab or a terminal escape from the file (tests/fuzz sends them) */
    if (p->errlen)
        vfp_printable(p->err);
    return VFP_ERR;
}

/* A whole number with nothing after it, in [min, max]. */
int vfpi_board_parse_long(const char *s, int base, long min, long max, long *out)
{
    char *end;
    if (!*s || *s == '+' || *s == ' ')
        return 0;
    errno = 0;
    long v = strtol(s, &end, base);
    if (*end || errno || v < min || v > max)
        return 0;
    *out = v;
    return 1;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Static functions: reading lines */

static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n' || *s == '\f' || *s == '\v')
        s++;
    size_t n = strlen(s);
    while (n > 0 && strchr(" \t\r\n\f\v", s[n - 1]))
        s[--n] = '\0';
    return s;
}

/* One line: blank, a comment, or KEY = VALUE with an optional comment after it. */
static vfp_status_t parse_line(vfpi_board_parser_t *p, char *text)
{
    char *hash = strchr(text, '#');
    if (hash)
        *hash = '\0';
    char *line = trim(text);
    if (!*line)
        return VFP_OK;
    char *eq = strchr(line, '=');
    if (!eq)
        return vfpi_board_fail(p, p->line, "expected KEY = VALUE, found '%.60s'", line);
    *eq = '\0';
    char *key = trim(line), *value = trim(eq + 1);
    if (!*key)
        return vfpi_board_fail(p, p->line, "expected a key before '='");
    if (!*value)
        return vfpi_board_fail(p, p->line, "%s: expected a value after '='", key);

    int is_knob = strncmp(key, "knob.", 5) == 0, is_button = strncmp(key, "button.", 7) == 0;
    if (!is_knob && !is_button) {
        int k = index_of(top_keys, T_COUNT, key);
        if (k < 0) {
            char names[512];
            join_names(names, sizeof names, top_keys, T_COUNT, ", ");
            return vfpi_board_fail(p, p->line, "unknown key '%.60s' (expected %s, knob.N.* or button.N.*)", key, names);
        }
        return set_top(p, k, key, value);
    }

    /* knob.N.KEY or button.N.KEY, N from 0 */
    const char *what = is_knob ? "knob" : "button";
    int max = is_knob ? VFP_MAX_KNOBS : VFP_MAX_BUTTONS;
    char *num = key + (is_knob ? 5 : 7), *dot = strchr(num, '.');
    long n;
    if (!dot || dot == num) {
        return vfpi_board_fail(p, p->line, "unknown key '%.60s' (expected %s.N.KEY with N from 0 to %d)", key, what,
                               max - 1);
    }
    *dot = '\0';
    int ok = vfpi_board_parse_long(num, 10, 0, LONG_MAX, &n);
    *dot = '.';
    if (!ok)
        return vfpi_board_fail(p, p->line, "unknown key '%.60s' (expected %s.N.KEY with N from 0 to %d)", key, what,
                               max - 1);
    if (n >= max)
        return vfpi_board_fail(p, p->line, "%s.%ld: index out of range (expected 0 to %d)", what, n, max - 1);
    const char *sub = dot + 1;
    const char *const *names = is_knob ? knob_keys : button_keys;
    int count = is_knob ? KN_COUNT : BT_COUNT;
    int k = index_of(names, count, sub);
    if (k < 0) {
        char list[256];
        join_names(list, sizeof list, names, count, " or ");
        return vfpi_board_fail(p, p->line, "unknown %s key '%.60s' (expected %s.%ld. followed by %s)", what, key, what,
                               n, list);
    }
    return is_knob ? set_knob(p, (int)n, k, key, value) : set_button(p, (int)n, k, key, value);
}

static vfp_status_t duplicate(vfpi_board_parser_t *p, int *seen, const char *keyname)
{
    if (*seen)
        return vfpi_board_fail(p, p->line, "%s given twice (first on line %d)", keyname, *seen);
    *seen = p->line;
    return VFP_OK;
}

static vfp_status_t set_top(vfpi_board_parser_t *p, int key, const char *keyname, const char *value)
{
    vfp_board_t *b = p->board;
    long n;
    int v;
    if (duplicate(p, &p->top_line[key], keyname))
        return VFP_ERR;
    switch (key) {
    case T_NAME:
        return copy_string(p, b->name, sizeof b->name, keyname, value);
    case T_DISPLAY:
        if (index_of(displays, (int)(sizeof displays / sizeof *displays), value) < 0)
            return vfpi_board_fail(p, p->line, "unknown display '%.60s' (expected drm, fbdev, gud, sdl, png or none)",
                                   value);
        return copy_string(p, b->display, sizeof b->display, keyname, value);
    case T_DEVICE:
        return copy_string(p, b->display_device, sizeof b->display_device, keyname, value);
    case T_WIDTH:
    case T_HEIGHT:
        /* the renderer draws images of at most VF_MAX_IMAGE a side: a larger board is refused here, naming the key,
         * rather than at the first frame */
        if (!vfpi_board_parse_long(value, 10, 1, VF_MAX_IMAGE, &n))
            return vfpi_board_fail(p, p->line, "%s: expected a size in pixels from 1 to %d, found '%.60s'", keyname,
                                   VF_MAX_IMAGE, value);
        *(key == T_WIDTH ? &b->width : &b->height) = (uint32_t)n;
        return VFP_OK;
    case T_FORMAT:
        if (!vfpi_board_format(value, &v))
            return vfpi_board_fail(p, p->line, "unknown format '%.60s' (expected rgb565, xrgb8888 or rgb888)", value);
        b->format = (vf_format_t)v;
        return VFP_OK;
    case T_ROTATION:
        if (!vfpi_board_parse_long(value, 10, 0, 270, &n) || n % 90 != 0)
            return vfpi_board_fail(p, p->line, "%s: expected 0, 90, 180 or 270, found '%.60s'", keyname, value);
        b->rotation = (int)n;
        return VFP_OK;
    case T_INPUT:
        if (index_of(inputs, (int)(sizeof inputs / sizeof *inputs), value) < 0)
            return vfpi_board_fail(p, p->line, "unknown input '%.60s' (expected gpiod, evdev, sdl or script)", value);
        return copy_string(p, b->input, sizeof b->input, keyname, value);
    case T_SCRIPT: {
        /* relative to the board file's directory, as a NRRD header's data file is to the header */
        const char *slash = strrchr(p->path, '/');
        int dir = value[0] != '/' && slash ? (int)(slash - p->path) + 1 : 0;
        if ((size_t)dir + strlen(value) >= sizeof b->script)
            return vfpi_board_fail(p, p->line, "%s: expected at most %zu characters with the board's directory",
                                   keyname, sizeof b->script - 1);
        snprintf(b->script, sizeof b->script, "%.*s%s", dir, p->path, value);
        return VFP_OK;
    }
    case T_CHIP:
        return copy_string(p, b->gpio_chip, sizeof b->gpio_chip, keyname, value);
    case T_THREADS:
        if (strcmp(value, "auto") == 0)
            return VFP_OK; /* b->threads stays 0: the processors online, set in vfpi_board_finish() */
        if (!vfpi_board_parse_long(value, 10, 1, MAX_THREADS, &n))
            return vfpi_board_fail(p, p->line, "threads: expected auto or a number from 1 to %d, found '%.60s'",
                                   MAX_THREADS, value);
        b->threads = (int)n;
        return VFP_OK;
    case T_IDLE:
        if (!vfpi_board_parse_long(value, 10, 0, 60000, &n))
            return vfpi_board_fail(p, p->line, "idle_ms: expected milliseconds from 0 to 60000, found '%.60s'", value);
        b->idle_ms = (int)n;
        return VFP_OK;
    case T_OVERLAY:
        if (!vfpi_board_boolean(value, &v))
            return vfpi_board_fail(p, p->line,
                                   "overlay: expected 0 or 1 (or yes/no, on/off, true/false), found '%.60s'", value);
        b->overlay = v;
        return VFP_OK;
    }
    return vfpi_board_fail(p, p->line, "%s: internal error (unhandled key)", keyname);
}

static vfp_status_t parse_action(vfpi_board_parser_t *p, const char *value, int knob, vfp_action_t *out)
{
    int a = vfpi_board_action(value);
    int is_knob_action = a >= FIRST_KNOB_ACTION && a <= LAST_KNOB_ACTION;
    if (a <= VFP_ACT_NONE)
        return vfpi_board_fail(p, p->line, "unknown action '%.60s' (expected %s)", value,
                               knob ? KNOB_ACTIONS : BUTTON_ACTIONS);
    if (knob && !is_knob_action)
        return vfpi_board_fail(p, p->line, "'%s' is a button action, not for a knob (expected %s)", value,
                               KNOB_ACTIONS);
    if (!knob && is_knob_action)
        return vfpi_board_fail(p, p->line, "'%s' is a knob action, not for a button (expected %s)", value,
                               BUTTON_ACTIONS);
    *out = (vfp_action_t)a;
    return VFP_OK;
}

/* knob.N.cycle = ACTION[:STEP], ...: up to VFP_MAX_CYCLE - 1 more knob actions, each with its step (default 5),
 * into cycle[1..]; board_check.c puts the knob's own action and step in cycle[0]. */
static vfp_status_t parse_cycle(vfpi_board_parser_t *p, const char *keyname, const char *value, vfp_knob_t *k)
{
    char list[256];
    if (strlen(value) >= sizeof list)
        return vfpi_board_fail(p, p->line, "%s: too long (expected at most %d actions)", keyname, VFP_MAX_CYCLE - 1);
    strcpy(list, value);
    k->cycle_count = 1;
    char *save = NULL;
    for (char *item = strtok_r(list, ",", &save); item; item = strtok_r(NULL, ",", &save)) {
        item = trim(item);
        if (k->cycle_count == VFP_MAX_CYCLE)
            return vfpi_board_fail(p, p->line, "%s: expected at most %d actions (ACTION[:STEP], ...), found more",
                                   keyname, VFP_MAX_CYCLE - 1);
        char *colon = strchr(item, ':');
        double step = DEFAULT_CYCLE_STEP;
        if (colon) {
            *colon = '\0';
            char *end;
            errno = 0;
            step = strtod(trim(colon + 1), &end);
            if (*end || errno || !isfinite(step) || step == 0 || fabs(step) > 1e6 || end == trim(colon + 1))
                return vfpi_board_fail(p, p->line, "%s: expected ACTION[:STEP] with a non-zero STEP, found '%.60s:%.60s'",
                                       keyname, trim(item), colon + 1);
        }
        vfp_action_t a;
        if (parse_action(p, trim(item), 1, &a))
            return VFP_ERR;
        k->cycle[k->cycle_count] = a;
        k->cycle_step[k->cycle_count++] = step;
    }
    if (k->cycle_count == 1)
        return vfpi_board_fail(p, p->line, "%s: expected ACTION[:STEP], ... (knob actions: %s), found nothing", keyname,
                               KNOB_ACTIONS);
    return VFP_OK;
}

static vfp_status_t parse_line_offset(vfpi_board_parser_t *p, const char *keyname, const char *value, int *out)
{
    long n;
    if (!vfpi_board_parse_long(value, 10, 0, MAX_LINE_OFFSET, &n))
        return vfpi_board_fail(p, p->line, "%s: expected a line offset (a number from 0 to %d), found '%.60s'", keyname,
                               MAX_LINE_OFFSET, value);
    *out = (int)n;
    return VFP_OK;
}

static vfp_status_t parse_pull(vfpi_board_parser_t *p, const char *keyname, const char *value, vfp_pull_t *out)
{
    int v;
    if (!vfpi_board_pull(value, &v))
        return vfpi_board_fail(p, p->line, "%s: expected up, down or none, found '%.60s'", keyname, value);
    *out = (vfp_pull_t)v;
    return VFP_OK;
}

static vfp_status_t set_knob(vfpi_board_parser_t *p, int n, int key, const char *keyname, const char *value)
{
    vfp_knob_t *k = &p->board->knobs[n];
    long v;
    if (duplicate(p, &p->knob_line[n][key], keyname))
        return VFP_ERR;
    if (!p->knob_first[n])
        p->knob_first[n] = p->line;
    switch (key) {
    case KN_A:
        return parse_line_offset(p, keyname, value, &k->line_a);
    case KN_B:
        return parse_line_offset(p, keyname, value, &k->line_b);
    case KN_PULL:
        return parse_pull(p, keyname, value, &k->pull);
    case KN_ACTION:
        return parse_action(p, value, 1, &k->action);
    case KN_CYCLE:
        return parse_cycle(p, keyname, value, k);
    case KN_STEP: {
        char *end;
        errno = 0;
        double d = strtod(value, &end);
        if (*end || errno || !isfinite(d) || d == 0 || fabs(d) > 1e6)
            return vfpi_board_fail(p, p->line,
                                   "%s: expected a non-zero number (per detent, in the action's unit), found "
                                   "'%.60s'", keyname, value);
        k->step = d;
        return VFP_OK;
    }
    case KN_DEVICE:
        return copy_string(p, k->device, sizeof k->device, keyname, value);
    case KN_AXIS: {
        int a;
        if (vfpi_board_evdev_axis(value, &a)) {
            k->axis = a;
            return VFP_OK;
        }
        if (!vfpi_board_parse_long(value, 0, 0, REL_MAX, &v))
            return vfpi_board_fail(p, p->line,
                                   "%s: expected REL_X, REL_DIAL, REL_WHEEL (or another REL_ name) or a number "
                                   "from 0 to %d, found '%.60s'", keyname, REL_MAX, value);
        k->axis = (int)v;
        return VFP_OK;
    }
    case KN_KEY_UP:
    case KN_KEY_DOWN: {
        int code;
        if (!vfpi_board_sdl_key(value, &code))
            return vfpi_board_fail(p, p->line, "%s: unknown SDL key '%.60s' (expected %s)", keyname, value,
                                   SDL_KEY_NAMES);
        *(key == KN_KEY_UP ? &k->key_up : &k->key_down) = code;
        return VFP_OK;
    }
    }
    return vfpi_board_fail(p, p->line, "%s: internal error (unhandled key)", keyname);
}

static vfp_status_t set_button(vfpi_board_parser_t *p, int n, int key, const char *keyname, const char *value)
{
    vfp_button_t *b = &p->board->buttons[n];
    long v;
    int flag;
    if (duplicate(p, &p->button_line[n][key], keyname))
        return VFP_ERR;
    if (!p->button_first[n])
        p->button_first[n] = p->line;
    switch (key) {
    case BT_LINE:
        return parse_line_offset(p, keyname, value, &b->line);
    case BT_PULL:
        return parse_pull(p, keyname, value, &b->pull);
    case BT_ACTIVE_LOW:
        if (!vfpi_board_boolean(value, &flag))
            return vfpi_board_fail(p, p->line, "%s: expected 1 (pressed reads 0) or 0 (pressed reads 1), found '%.60s'",
                                   keyname, value);
        b->active_low = flag;
        return VFP_OK;
    case BT_DEBOUNCE:
        if (!vfpi_board_parse_long(value, 10, 0, 1000, &v))
            return vfpi_board_fail(p, p->line, "%s: expected milliseconds from 0 to 1000, found '%.60s'", keyname,
                                   value);
        b->debounce_ms = (int)v;
        return VFP_OK;
    case BT_ACTION:
        return parse_action(p, value, 0, &b->action);
    case BT_DEVICE:
        return copy_string(p, b->device, sizeof b->device, keyname, value);
    case BT_CODE:
        /* KEY_* for evdev, an SDL key name for sdl: which one is known only once the whole file is read */
        return copy_string(p, p->button_code[n], sizeof p->button_code[n], keyname, value);
    }
    return vfpi_board_fail(p, p->line, "%s: internal error (unhandled key)", keyname);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Static functions: small parsers */

static int index_of(const char *const *names, int count, const char *name)
{
    for (int i = 0; i < count; i++)
        if (strcmp(names[i], name) == 0)
            return i;
    return -1;
}

static vfp_status_t copy_string(vfpi_board_parser_t *p, char *dst, size_t size, const char *keyname, const char *value)
{
    if (strlen(value) >= size)
        return vfpi_board_fail(p, p->line, "%s: expected at most %zu characters, found %zu", keyname, size - 1,
                               strlen(value));
    memcpy(dst, value, strlen(value) + 1);
    return VFP_OK;
}

/* "a, b, c or d" (last = " or "), or "a, b, c, d" (last = ", ") */
static void join_names(char *out, size_t size, const char *const *names, int count, const char *last)
{
    size_t used = 0;
    out[0] = '\0';
    for (int i = 0; i < count && used < size; i++) {
        const char *sep = i == 0 ? "" : i == count - 1 ? last : ", ";
        int n = snprintf(out + used, size - used, "%s%s", sep, names[i]);
        if (n < 0)
            break;
        used += (size_t)n;
    }
}
