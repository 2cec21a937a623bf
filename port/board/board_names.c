/* SPDX-License-Identifier: MIT */
/* board_names.c: the names a board file's values may take, and what each stands for: formats, pulls, booleans,
 * actions, evdev axes and key codes (linux/input-event-codes.h) and SDL 2's key names. Each table is looked up
 * by name (board_internal.h); vfp_action_name() (board.h) goes the other way. */
#include "board_internal.h"

#include <string.h>
#include <strings.h>

#include <linux/input-event-codes.h>

/* SDL 2 key codes (SDL_keycode.h): a printable key is its character, lower case for letters; the others are
 * their scancode (SDL_scancode.h) with SDLK_SCANCODE_MASK set. Copied here so that board files parse without SDL's
 * headers; tests/port/test_board.c compares them with SDL's own values when SDL is there. */
#define SDLK_SCANCODE_MASK (1 << 30)
#define SDLK_RETURN '\r'
#define SDLK_ESCAPE '\033'
#define SDLK_BACKSPACE '\b'
#define SDLK_TAB '\t'
#define SDLK_SPACE ' '
#define SDLK_HOME (74 | SDLK_SCANCODE_MASK)     /* SDL_SCANCODE_HOME */
#define SDLK_PAGEUP (75 | SDLK_SCANCODE_MASK)   /* SDL_SCANCODE_PAGEUP */
#define SDLK_END (77 | SDLK_SCANCODE_MASK)      /* SDL_SCANCODE_END */
#define SDLK_PAGEDOWN (78 | SDLK_SCANCODE_MASK) /* SDL_SCANCODE_PAGEDOWN */
#define SDLK_RIGHT (79 | SDLK_SCANCODE_MASK)    /* SDL_SCANCODE_RIGHT */
#define SDLK_LEFT (80 | SDLK_SCANCODE_MASK)     /* SDL_SCANCODE_LEFT */
#define SDLK_DOWN (81 | SDLK_SCANCODE_MASK)     /* SDL_SCANCODE_DOWN */
#define SDLK_UP (82 | SDLK_SCANCODE_MASK)       /* SDL_SCANCODE_UP */

#define CODE(n) {#n, n}

/* ---------------------------------------------------------------------------------------------------------- */
/* Types */

typedef struct name_value {
    const char *name;
    int value;
} name_value_t;

/* ---------------------------------------------------------------------------------------------------------- */
/* Prototypes */

static int lookup(const name_value_t *table, const char *name, int *value);

/* ---------------------------------------------------------------------------------------------------------- */
/* Tables */

static const name_value_t formats[] = {
    {"rgb565", VF_FORMAT_RGB565}, {"xrgb8888", VF_FORMAT_XRGB8888}, {"rgb888", VF_FORMAT_RGB888}, {NULL, 0}};
static const name_value_t pulls[] = {{"up", VFP_PULL_UP}, {"down", VFP_PULL_DOWN}, {"none", VFP_PULL_NONE},
                                     {NULL, 0}};
static const name_value_t booleans[] = {{"1", 1}, {"0", 0}, {"yes", 1}, {"no", 0}, {"true", 1}, {"false", 0},
                                        {"on", 1}, {"off", 0}, {NULL, 0}};

static const char *const action_names[VFP_ACT_COUNT] = {
    "none", "azimuth", "elevation", "roll", "zoom", "level", "width",
    "light-azimuth", "light-elevation", "shade", "preset",
    "next-preset", "next-mode", "reset", "overlay", "quit", "toggle-shade", "cycle-knobs",
};

static const name_value_t rel_axes[] = {CODE(REL_X), CODE(REL_Y), CODE(REL_Z), CODE(REL_HWHEEL), CODE(REL_DIAL),
                                        CODE(REL_WHEEL), CODE(REL_MISC), {NULL, 0}};
/* The key codes a gpio-keys overlay is likely to be given (its linux,code), by their names in
 * linux/input-event-codes.h; any other code can be written as a number. */
static const name_value_t evdev_keys[] = {
    CODE(KEY_ESC), CODE(KEY_1), CODE(KEY_2), CODE(KEY_3), CODE(KEY_4), CODE(KEY_5), CODE(KEY_6), CODE(KEY_7),
    CODE(KEY_8), CODE(KEY_9), CODE(KEY_0), CODE(KEY_MINUS), CODE(KEY_EQUAL), CODE(KEY_BACKSPACE), CODE(KEY_TAB),
    CODE(KEY_Q), CODE(KEY_W), CODE(KEY_E), CODE(KEY_R), CODE(KEY_T), CODE(KEY_Y), CODE(KEY_U), CODE(KEY_I),
    CODE(KEY_O), CODE(KEY_P), CODE(KEY_ENTER), CODE(KEY_A), CODE(KEY_S), CODE(KEY_D), CODE(KEY_F), CODE(KEY_G),
    CODE(KEY_H), CODE(KEY_J), CODE(KEY_K), CODE(KEY_L), CODE(KEY_Z), CODE(KEY_X), CODE(KEY_C), CODE(KEY_V),
    CODE(KEY_B), CODE(KEY_N), CODE(KEY_M), CODE(KEY_SPACE), CODE(KEY_F1), CODE(KEY_F2), CODE(KEY_F3),
    CODE(KEY_F4), CODE(KEY_F5), CODE(KEY_F6), CODE(KEY_F7), CODE(KEY_F8), CODE(KEY_F9), CODE(KEY_F10),
    CODE(KEY_HOME), CODE(KEY_UP), CODE(KEY_PAGEUP), CODE(KEY_LEFT), CODE(KEY_RIGHT), CODE(KEY_END),
    CODE(KEY_DOWN), CODE(KEY_PAGEDOWN), CODE(KEY_MUTE), CODE(KEY_VOLUMEDOWN), CODE(KEY_VOLUMEUP),
    CODE(KEY_POWER), CODE(KEY_MENU), CODE(KEY_BACK), CODE(KEY_NEXTSONG), CODE(KEY_PLAYPAUSE),
    CODE(KEY_PREVIOUSSONG), CODE(KEY_OK), CODE(KEY_SELECT), CODE(KEY_MODE), CODE(KEY_NEXT), CODE(KEY_PREVIOUS),
    CODE(KEY_ZOOMIN), CODE(KEY_ZOOMOUT), CODE(KEY_ZOOMRESET), CODE(BTN_0), CODE(BTN_1), CODE(BTN_2),
    CODE(BTN_3), CODE(BTN_4), CODE(BTN_5), CODE(BTN_6), CODE(BTN_7), CODE(BTN_8), CODE(BTN_9), CODE(BTN_LEFT),
    CODE(BTN_RIGHT), CODE(BTN_MIDDLE), CODE(BTN_SELECT), CODE(BTN_START), CODE(BTN_MODE), {NULL, 0}};
/* SDL key names as SDL_GetKeyName spells them (matched without case, as SDL_GetKeyFromName does), plus words
 * for the punctuation; letters and digits are handled apart. */
static const name_value_t sdl_keys[] = {
    {"Left", SDLK_LEFT}, {"Right", SDLK_RIGHT}, {"Up", SDLK_UP}, {"Down", SDLK_DOWN}, {"PageUp", SDLK_PAGEUP},
    {"PageDown", SDLK_PAGEDOWN}, {"Home", SDLK_HOME}, {"End", SDLK_END}, {"Space", SDLK_SPACE},
    {"Return", SDLK_RETURN}, {"Escape", SDLK_ESCAPE}, {"Tab", SDLK_TAB}, {"Backspace", SDLK_BACKSPACE},
    {"+", '+'}, {"plus", '+'}, {"-", '-'}, {"minus", '-'}, {"=", '='}, {"equals", '='}, {",", ','},
    {"comma", ','}, {".", '.'}, {"period", '.'}, {"[", '['}, {"leftbracket", '['}, {"]", ']'},
    {"rightbracket", ']'}, {"/", '/'}, {"slash", '/'}, {NULL, 0}};

/* ---------------------------------------------------------------------------------------------------------- */
/* Public functions */

const char *vfp_action_name(vfp_action_t action)
{
    return (unsigned)action < VFP_ACT_COUNT ? action_names[action] : "?";
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Shared functions */

int vfpi_board_format(const char *name, int *format)
{
    return lookup(formats, name, format);
}

int vfpi_board_pull(const char *name, int *pull)
{
    return lookup(pulls, name, pull);
}

int vfpi_board_boolean(const char *name, int *flag)
{
    return lookup(booleans, name, flag);
}

int vfpi_board_action(const char *name)
{
    for (int i = 0; i < VFP_ACT_COUNT; i++)
        if (strcmp(action_names[i], name) == 0)
            return i;
    return -1;
}

int vfpi_board_evdev_axis(const char *name, int *axis)
{
    return lookup(rel_axes, name, axis);
}

int vfpi_board_evdev_key(const char *name, int *code)
{
    return lookup(evdev_keys, name, code);
}

int vfpi_board_sdl_key(const char *name, int *code)
{
    if (name[0] && !name[1]) {
        char c = name[0];
        if (c >= 'A' && c <= 'Z')
            c = (char)(c - 'A' + 'a');
        if ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9')) {
            *code = c;
            return 1;
        }
    }
    for (const name_value_t *k = sdl_keys; k->name; k++)
        if (strcasecmp(k->name, name) == 0) {
            *code = k->value;
            return 1;
        }
    return 0;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Static functions */

/* In a table ending with {NULL, 0}; names match exactly. */
static int lookup(const name_value_t *table, const char *name, int *value)
{
    for (; table->name; table++)
        if (strcmp(table->name, name) == 0) {
            *value = table->value;
            return 1;
        }
    return 0;
}
