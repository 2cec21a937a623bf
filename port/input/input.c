/* SPDX-License-Identifier: MIT */
/* input.c: the input backends compiled into this build, and finding one by the name a board file gives. */
#include "input.h"
#include "input_backends.h" /* each backend's table, defined in its own file when its library is there */

#include <stdio.h>
#include <string.h>

/* Every backend volfix knows, and what it takes to build it in. */
static const struct known_input {
    const char *name;
    const char *needs;
} known[] = {
    {"gpiod", "install libgpiod-dev and rebuild"},
    {"evdev", "it needs only Linux"},
    {"sdl", "install libsdl2-dev and rebuild"},
    {"script", "it needs nothing"},
};

const vfp_input_ops_t *const vfp_inputs[] = {
#ifdef VFP_HAVE_GPIOD
    &vfp_input_gpiod_ops,
#endif
    &vfp_input_evdev_ops,
#ifdef VFP_HAVE_SDL
    &vfp_input_sdl_ops,
#endif
    &vfp_input_script_ops,
    NULL,
};

/* ---------------------------------------------------------------------------------------------------------- */
/* Public functions */

const vfp_input_ops_t *vfp_input_find(const char *name, const vfp_board_t *board, char *err, size_t errlen)
{
    const char *where = board && board->path[0] ? board->path : "volfix";
    if (!name || !*name)
        name = board ? board->input : "";
    for (int i = 0; vfp_inputs[i]; i++)
        if (strcmp(vfp_inputs[i]->name, name) == 0)
            return vfp_inputs[i];
    for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
        if (strcmp(known[i].name, name) == 0) {
            snprintf(err, errlen, "%s: input '%s' is not compiled in: %s", where, name, known[i].needs);
            return NULL;
        }
    snprintf(err, errlen, "%s: unknown input '%s' (expected gpiod, evdev, sdl or script)", where, name);
    return NULL;
}

int vfpi_events_report(vfp_event_t *queue, int *queued, int *turn_slot, int knob_count, vfp_event_t *events,
                       int max)
{
    int n = 0, i = 0;
    for (; i < *queued && n < max; i++)
        if (queue[i].type != VFP_EV_TURN || queue[i].steps != 0)
            events[n++] = queue[i];
    memmove(queue, queue + i, sizeof queue[0] * (size_t)(*queued - i));
    *queued -= i;
    for (int k = 0; k < knob_count; k++)
        turn_slot[k] = -1;
    for (int j = 0; j < *queued; j++)
        if (queue[j].type == VFP_EV_TURN)
            turn_slot[queue[j].control] = j;
    return n;
}
