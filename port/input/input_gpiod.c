/* SPDX-License-Identifier: MIT */
/* input_gpiod.c: rotary encoders and push buttons on GPIO lines, through libgpiod 1.6 (Debian 12, Raspberry Pi OS
 * bookworm) or 2.x, chosen at build time (VFP_HAVE_GPIOD, VFP_GPIOD_MAJOR). The chip is found by its label
 * (pinctrl-bcm2711, pinctrl-rp1...), never by number, which changes between kernels.
 *
 * This file is the backend's ops table and what does not depend on libgpiod's version: the lines the board uses,
 * the decoder's life, and the hints added to errors. The rest is in three files (gpiod_internal.h): gpiod_v1.c or
 * gpiod_v2.c requests every line for both edges with the board's pulls and turns the kernel's edge events into
 * (line, level, time) edges, and gpio_decoder.c turns those into whole detents and settled presses.
 *
 * fd(): with 2.x the one request's fd; with 1.x (one fd per line) an epoll fd over all of them. deadline_ns():
 * when a bouncing button will have settled, so the viewer wakes up to report the press although no edge
 * follows (and, with 1.x, when edges held back to merge the lines' fds in time order can be decoded). Edge
 * times are the kernel's CLOCK_MONOTONIC (2.x asks for it; 1.6 gets it from kernels >= 5.7). */
#include "gpiod_internal.h"

#ifdef VFP_HAVE_GPIOD

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

/* ---------------------------------------------------------------------------------------------------------- */
/* Prototypes */

static vfp_status_t gpiod_open(vfp_input_t *in, const vfp_board_t *board, const char *script, char *err, size_t errlen);
static int gpiod_fd(vfp_input_t *in);
static uint64_t gpiod_deadline(vfp_input_t *in);
static int gpiod_read(vfp_input_t *in, vfp_event_t *events, int max, uint64_t now_ns, char *err, size_t errlen);
static void gpiod_close(vfp_input_t *in);
static int list_lines(const vfp_board_t *board, vfpi_gpio_line_t *lines);

const vfp_input_ops_t vfp_input_gpiod_ops = {
    .name = "gpiod",
    .open = gpiod_open,
    .fd = gpiod_fd,
    .deadline_ns = gpiod_deadline,
    .read = gpiod_read,
    .close = gpiod_close,
};

/* ---------------------------------------------------------------------------------------------------------- */
/* Shared functions */

const char *vfpi_gpiod_hint(int e)
{
    return e == EACCES ? " (is the user in the gpio group?)"
           : e == EBUSY ? " (is another program, or an overlay in config.txt, using the line?)"
           : e == EINVAL ? " (is the offset on this chip? gpioinfo lists its lines)"
                         : "";
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Static functions */

static vfp_status_t gpiod_open(vfp_input_t *in, const vfp_board_t *board, const char *script, char *err, size_t errlen)
{
    (void)script;
    in->ops = &vfp_input_gpiod_ops;
    in->priv = NULL;
    vfpi_gpiod_t *g = calloc(1, sizeof *g);
    if (!g || !(g->dec = vfp_gpio_decoder_new(board))) {
        snprintf(err, errlen, "%s: out of memory", board->path);
        free(g);
        return VFP_ERR;
    }
    snprintf(g->label, sizeof g->label, "%s", board->gpio_chip);
    g->line_count = list_lines(board, g->lines);
    if (vfpi_gpiod_hw_open(g, err, errlen)) {
        vfpi_gpiod_hw_close(g);
        vfp_gpio_decoder_free(g->dec);
        free(g);
        return VFP_ERR;
    }
    in->priv = g;
    return VFP_OK;
}

static int gpiod_fd(vfp_input_t *in)
{
    const vfpi_gpiod_t *g = in->priv;
    return g ? vfpi_gpiod_hw_fd(g) : -1;
}

static uint64_t gpiod_deadline(vfp_input_t *in)
{
    const vfpi_gpiod_t *g = in->priv;
    return g ? vfp_gpio_decoder_deadline(g->dec) : 0;
}

static int gpiod_read(vfp_input_t *in, vfp_event_t *events, int max, uint64_t now_ns, char *err, size_t errlen)
{
    vfpi_gpiod_t *g = in->priv;
    if (!g)
        return 0;
    vfp_gpio_edge_t edges[VFPI_GPIO_EDGE_BATCH];
    uint64_t read_ns = 0;
    int n = vfpi_gpiod_hw_collect(g, edges, VFPI_GPIO_EDGE_BATCH, &read_ns, err, errlen);
    if (n < 0)
        return -1;
    vfp_gpio_decoder_edges(g->dec, edges, n, read_ns);
    return vfp_gpio_decoder_read(g->dec, events, max, now_ns);
}

static void gpiod_close(vfp_input_t *in)
{
    vfpi_gpiod_t *g = in->priv;
    if (!g)
        return;
    vfpi_gpiod_hw_close(g);
    vfp_gpio_decoder_free(g->dec);
    free(g);
    in->priv = NULL;
}

/* Every line the board uses, once (the board file's check makes them distinct). */
static int list_lines(const vfp_board_t *board, vfpi_gpio_line_t *lines)
{
    int n = 0;
    for (int k = 0; k < board->knob_count; k++) {
        lines[n++] = (vfpi_gpio_line_t){(unsigned)board->knobs[k].line_a, board->knobs[k].pull};
        lines[n++] = (vfpi_gpio_line_t){(unsigned)board->knobs[k].line_b, board->knobs[k].pull};
    }
    for (int b = 0; b < board->button_count; b++)
        lines[n++] = (vfpi_gpio_line_t){(unsigned)board->buttons[b].line, board->buttons[b].pull};
    return n;
}

#endif /* VFP_HAVE_GPIOD */
