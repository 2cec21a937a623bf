/* SPDX-License-Identifier: MIT */
/*
 * input_backends.h: the input backends' ops tables and the seams their tests drive, for the registry (input.c)
 * and tests, not for applications: a program finds its backend with vfp_input_find() (input.h), and nothing here
 * is a promise to it.
 *
 * Each table lives in its backend's file; an optional backend's file defines it only when its library is there
 * (the Makefile's VFP_HAVE_GPIOD, VFP_HAVE_SDL), so its declaration is conditional too.
 */
#ifndef VFP_INPUT_BACKENDS_H
#define VFP_INPUT_BACKENDS_H

#include <stddef.h>
#include <stdint.h>

#include "board/board.h"
#include "input.h"

#ifdef VFP_HAVE_GPIOD
extern const vfp_input_ops_t vfp_input_gpiod_ops; /* input_gpiod.c */
#endif
extern const vfp_input_ops_t vfp_input_evdev_ops; /* input_evdev.c */
#ifdef VFP_HAVE_SDL
extern const vfp_input_ops_t vfp_input_sdl_ops; /* input_sdl.c */
#endif
extern const vfp_input_ops_t vfp_input_script_ops; /* input_script.c */

/* ---------------------------------------------------------------------------------------------------------- */
/* input.c: the report step of "drain, accumulate, report" that the GPIO decoder and evdev share. Their events
 * wait in a queue in arrival order, and a knob's turns since the last read add up in one event, the one
 * turn_slot[knob] points at (-1: none). */

/* Moves the queue's first events (at most max) to events, leaving out turns that added up to nothing, and points
 * turn_slot at the turns that stay queued. Returns how many went out. */
int vfpi_events_report(vfp_event_t *queue, int *queued, int *turn_slot, int knob_count, vfp_event_t *events,
                       int max);

/* ---------------------------------------------------------------------------------------------------------- */
/* input_evdev.c: open from descriptors the caller opened (pipes in tests), one per distinct device of the board,
 * in the order the board first names them. The input owns the fds from here on, also when this fails. */

vfp_status_t vfp_evdev_open_fds(vfp_input_t *in, const vfp_board_t *board, const int *fds, int count, char *err,
                                size_t errlen);

/* ---------------------------------------------------------------------------------------------------------- */
/* input_script.c: a script from a string, its times counted from start_ns; `name` stands for the file in
 * messages. */

vfp_status_t vfp_script_load_string(vfp_input_t *in, const vfp_board_t *board, const char *text, const char *name,
                                    uint64_t start_ns, char *err, size_t errlen);

/* ---------------------------------------------------------------------------------------------------------- */
/* gpio_decoder.c: the GPIO backend's decoder, which needs no libgpiod (compiled in every build): (line, level,
 * time) edges in, whole detents and debounced presses out. input_gpiod.c feeds it the kernel's edges; tests feed
 * it synthetic ones. */

/* One edge: the line's offset on the chip, its level after the edge, and when (CLOCK_MONOTONIC, ns). */
typedef struct vfp_gpio_edge {
    unsigned line;
    int level;
    uint64_t time_ns;
} vfp_gpio_edge_t;

typedef struct vfp_gpio_decoder vfp_gpio_decoder_t;

/* NULL when out of memory. Every line starts at its idle level (high unless pulled down). */
vfp_gpio_decoder_t *vfp_gpio_decoder_new(const vfp_board_t *board);
/* A line's level as read once the lines are requested. */
void vfp_gpio_decoder_set_level(vfp_gpio_decoder_t *dec, unsigned line, int level);
/* Edges of any lines in any order (`edges` is sorted in place); read_ns = 0 decodes them all now, otherwise the
 * most recent are held back to merge with the next call's (see the definition). */
void vfp_gpio_decoder_edges(vfp_gpio_decoder_t *dec, vfp_gpio_edge_t *edges, int count, uint64_t read_ns);
/* At most `max` events decoded by now_ns; returns how many. */
int vfp_gpio_decoder_read(vfp_gpio_decoder_t *dec, vfp_event_t *events, int max, uint64_t now_ns);
/* When read() will have something without a new edge: 1 (at once), a time, or 0 for never. */
uint64_t vfp_gpio_decoder_deadline(const vfp_gpio_decoder_t *dec);
void vfp_gpio_decoder_free(vfp_gpio_decoder_t *dec);

#endif /* VFP_INPUT_BACKENDS_H */
