/* SPDX-License-Identifier: MIT */
/*
 * gpiod_internal.h: what the GPIO input backend's files share and no one else: input_gpiod.c (the ops table and
 * everything that does not depend on libgpiod's version), gpio_decoder.c (edges to events; its interface is in
 * input_backends.h, since tests drive it), and gpiod_v1.c or gpiod_v2.c (the lines through libgpiod 1.6 or 2.x;
 * the Makefile's VFP_GPIOD_MAJOR picks one, the other compiles to nothing).
 *
 * Names: vfpi_ marks what these files share (as volume_internal.h does for the volume readers).
 */
#ifndef VFP_GPIOD_INTERNAL_H
#define VFP_GPIOD_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "input_backends.h"

#define VFPI_GPIO_MAX_LINES (VFP_MAX_KNOBS * 2 + VFP_MAX_BUTTONS)
#define VFPI_GPIO_EDGE_BATCH 256     /* edges read from the kernel per read() */
#define VFPI_GPIO_HOLD_NS 1000000u   /* how far behind the reading an edge must be to be decoded: 1 ms */
#define VFPI_GPIOD_CONSUMER "volfix" /* the lines' consumer, as gpioinfo shows it */

#ifdef VFP_HAVE_GPIOD

#if !defined(VFP_GPIOD_MAJOR) || (VFP_GPIOD_MAJOR != 1 && VFP_GPIOD_MAJOR != 2)
#error "VFP_GPIOD_MAJOR must be 1 or 2 (the Makefile sets it from pkg-config's libgpiod version)"
#endif

/* libgpiod's handles are opaque: named here so that this header (and the decoder) need no <gpiod.h>. */
struct gpiod_chip;
struct gpiod_line;
struct gpiod_line_request;
struct gpiod_edge_event_buffer;

/* A line the board uses, and the pull it asks for. */
typedef struct vfpi_gpio_line {
    unsigned offset;
    vfp_pull_t pull;
} vfpi_gpio_line_t;

/* The backend's state (vfp_input_t's priv). */
typedef struct vfpi_gpiod {
    vfp_gpio_decoder_t *dec;
    char label[64];
    vfpi_gpio_line_t lines[VFPI_GPIO_MAX_LINES];
    int line_count;
#if VFP_GPIOD_MAJOR == 1
    struct gpiod_chip *chip;
    struct gpiod_line *handles[VFPI_GPIO_MAX_LINES];
    int fds[VFPI_GPIO_MAX_LINES];
    int epoll_fd; /* -1 with one line */
#else
    struct gpiod_line_request *request;
    struct gpiod_edge_event_buffer *buffer;
#endif
} vfpi_gpiod_t;

/* gpiod_v1.c or gpiod_v2.c. hw_open requests g->lines on the chip labelled g->label and gives the decoder their
 * levels; it returns VFP_OK, or VFP_ERR with err, and hw_close (safe on a g that hw_open failed on) gives
 * everything back. hw_fd is the fd to poll. hw_collect reads what the kernel has queued, at most max edges; *read_ns is the horizon
 * for vfp_gpio_decoder_edges (0: decode everything). It returns how many, or -1 with err when the chip is gone. */
vfp_status_t vfpi_gpiod_hw_open(vfpi_gpiod_t *g, char *err, size_t errlen);
int vfpi_gpiod_hw_fd(const vfpi_gpiod_t *g);
int vfpi_gpiod_hw_collect(vfpi_gpiod_t *g, vfp_gpio_edge_t *edges, int max, uint64_t *read_ns, char *err,
                          size_t errlen);
void vfpi_gpiod_hw_close(vfpi_gpiod_t *g);

/* input_gpiod.c: what to add to a message for errno e, "" when there is nothing to add. */
const char *vfpi_gpiod_hint(int e);

#endif /* VFP_HAVE_GPIOD */
#endif /* VFP_GPIOD_INTERNAL_H */
