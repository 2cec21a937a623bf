/* SPDX-License-Identifier: MIT */
/* test_input_gpiod.c: the GPIO backend's decoding path (port/input/gpio_decoder.c) with synthetic edges: two lines of an
 * encoder delivered out of order as libgpiod 1.x delivers them (one line's fd after the other), bouncing contacts,
 * and buttons that settle between reads. Compiled with or without libgpiod: the decoder needs none. With libgpiod,
 * also the message for a chip label that is not there (real lines are tested in tests/hw on gpio-sim). */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "input/input.h"
#include "input/input_backends.h" /* the decoder's interface */

#define MS 1000000ull
#define A0 17 /* knob 0 */
#define B0 27
#define A1 5 /* knob 1 */
#define B1 6
#define SW0 22 /* button 0, active low */
#define SW1 13 /* button 1, active high with a pull-down */

static vfp_board_t test_board(void)
{
    vfp_board_t b;
    memset(&b, 0, sizeof b);
    snprintf(b.path, sizeof b.path, "test.board");
    snprintf(b.input, sizeof b.input, "gpiod");
    snprintf(b.gpio_chip, sizeof b.gpio_chip, "no-such-chip-label");
    b.knob_count = 2;
    b.knobs[0] = (vfp_knob_t){.line_a = A0, .line_b = B0, .pull = VFP_PULL_UP, .action = VFP_ACT_AZIMUTH, .step = 5};
    b.knobs[1] = (vfp_knob_t){.line_a = A1, .line_b = B1, .pull = VFP_PULL_UP, .action = VFP_ACT_ZOOM, .step = 5};
    b.button_count = 2;
    b.buttons[0] = (vfp_button_t){.line = SW0, .pull = VFP_PULL_UP, .active_low = 1, .debounce_ms = 10,
                                  .action = VFP_ACT_NEXT_PRESET};
    b.buttons[1] = (vfp_button_t){.line = SW1, .pull = VFP_PULL_DOWN, .active_low = 0, .debounce_ms = 5,
                                  .action = VFP_ACT_QUIT};
    return b;
}

/* One clockwise detent of (a, b) from rest (both high) starting at t ms, a step every ms: A falls, B falls, A
 * rises, B rises; written line A's edges first, then line B's, as two fds read one after the other. */
static int cw_detent_by_line(vfp_gpio_edge_t *e, unsigned a, unsigned b, uint64_t t)
{
    e[0] = (vfp_gpio_edge_t){a, 0, (t + 0) * MS};
    e[1] = (vfp_gpio_edge_t){a, 1, (t + 2) * MS};
    e[2] = (vfp_gpio_edge_t){b, 0, (t + 1) * MS};
    e[3] = (vfp_gpio_edge_t){b, 1, (t + 3) * MS};
    return 4;
}

/* Counter-clockwise: B leads. */
static int ccw_detent_by_line(vfp_gpio_edge_t *e, unsigned a, unsigned b, uint64_t t)
{
    return cw_detent_by_line(e, b, a, t);
}

/* ---------------------------------------------------------------------------------------------------------- */

static void out_of_order_lines_make_one_detent(void)
{
    vfp_board_t b = test_board();
    vfp_gpio_decoder_t *dec = vfp_gpio_decoder_new(&b);
    CHECK(dec);
    vfp_gpio_edge_t e[8];
    int n = cw_detent_by_line(e, A0, B0, 100);
    vfp_gpio_decoder_edges(dec, e, n, 0);
    vfp_event_t ev[8];
    int got = vfp_gpio_decoder_read(dec, ev, 8, 200 * MS);
    vfp_gpio_decoder_free(dec);
    /* in arrival order the edges would read A:0, A:1, B:0, B:1 = +1 -1 -1 +1: nothing. Merged by time: a detent. */
    CHECK_EQ(got, 1);
    CHECK_EQ(ev[0].type, VFP_EV_TURN);
    CHECK_EQ(ev[0].control, 0);
    CHECK_EQ(ev[0].steps, 1);
    CHECK_EQ(ev[0].time_ns, 103 * MS); /* the edge that completed it */
}

static void detents_sum_per_knob_per_read(void)
{
    vfp_board_t b = test_board();
    vfp_gpio_decoder_t *dec = vfp_gpio_decoder_new(&b);
    CHECK(dec);
    vfp_gpio_edge_t e[32];
    int n = 0;
    n += cw_detent_by_line(e + n, A0, B0, 10);
    n += cw_detent_by_line(e + n, A0, B0, 20);
    n += cw_detent_by_line(e + n, A0, B0, 30);
    n += ccw_detent_by_line(e + n, A1, B1, 12);
    n += ccw_detent_by_line(e + n, A1, B1, 40);
    vfp_gpio_decoder_edges(dec, e, n, 0);
    vfp_event_t ev[8];
    int got = vfp_gpio_decoder_read(dec, ev, 8, 50 * MS);
    CHECK_EQ(got, 2);
    CHECK_EQ(ev[0].control, 0); /* knob 0's first detent completed first */
    CHECK_EQ(ev[0].steps, 3);
    CHECK_EQ(ev[0].time_ns, 33 * MS);
    CHECK_EQ(ev[1].control, 1);
    CHECK_EQ(ev[1].steps, -2);
    CHECK_EQ(ev[1].time_ns, 43 * MS);
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 8, 60 * MS), 0);
    CHECK_EQ(vfp_gpio_decoder_deadline(dec), 0);
    /* back and forth in one read: no event at all */
    n = cw_detent_by_line(e, A0, B0, 70);
    n += ccw_detent_by_line(e + n, A0, B0, 80);
    vfp_gpio_decoder_edges(dec, e, n, 0);
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 8, 90 * MS), 0);
    vfp_gpio_decoder_free(dec);
}

static void bouncing_encoder_contacts(void)
{
    vfp_board_t b = test_board();
    vfp_gpio_decoder_t *dec = vfp_gpio_decoder_new(&b);
    CHECK(dec);
    /* A chatters five times on its falling edge (us apart), and B once on its rising edge; a repeated edge of the
     * same level (a lost opposite edge) on A; all still one detent clockwise. */
    vfp_gpio_edge_t e[] = {
        {A0, 0, 1000}, {A0, 1, 1200}, {A0, 0, 1300}, {A0, 1, 1350}, {A0, 0, 1400}, /* A falls, bouncing */
        {B0, 0, 2000000},                                                          /* B falls */
        {A0, 1, 3000000}, {A0, 1, 3000100},                                        /* A rises, twice */
        {B0, 1, 4000000}, {B0, 0, 4000050}, {B0, 1, 4000090},                      /* B rises, bouncing */
    };
    vfp_gpio_decoder_edges(dec, e, (int)(sizeof e / sizeof e[0]), 0);
    vfp_event_t ev[4];
    int got = vfp_gpio_decoder_read(dec, ev, 4, 10 * MS);
    CHECK_EQ(got, 1);
    CHECK_EQ(ev[0].steps, 1);
    /* the detent completed at the first B rise; the bounce after it undid and redid the last step, no more */
    CHECK_EQ(ev[0].time_ns, 4000000);
    vfp_gpio_edge_t more[] = {{B0, 0, 5 * MS}, {B0, 1, 6 * MS}}; /* a last bounce of B, read later */
    vfp_gpio_decoder_edges(dec, more, 2, 0);
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 4, 10 * MS), 0);
    vfp_gpio_decoder_free(dec);
}

static void initial_levels(void)
{
    vfp_board_t b = test_board();
    vfp_gpio_decoder_t *dec = vfp_gpio_decoder_new(&b);
    CHECK(dec);
    /* the encoder rests at A=0 B=0 (a detent at 00): a clockwise detent is 00 -> 10 -> 11 -> 01 -> 00. Had the
     * decoder assumed the idle level of a pull-up (11), the first two edges would be no steps and the detent lost. */
    vfp_gpio_decoder_set_level(dec, A0, 0);
    vfp_gpio_decoder_set_level(dec, B0, 0);
    vfp_gpio_edge_t f[] = {{A0, 1, 11 * MS}, {B0, 1, 12 * MS}, {A0, 0, 13 * MS}, {B0, 0, 14 * MS}};
    vfp_gpio_decoder_edges(dec, f, 4, 0);
    vfp_event_t ev[4];
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 4, 20 * MS), 1);
    CHECK_EQ(ev[0].steps, 1);
    CHECK_EQ(ev[0].time_ns, 14 * MS);
    /* sorted: A up (00 -> 10, +1), A down (-1), B up (00 -> 01, -1), B down (+1): a wobble, net 0 */
    vfp_gpio_edge_t e[] = {{B0, 1, 24 * MS}, {A0, 1, 21 * MS}, {A0, 0, 23 * MS}, {B0, 0, 26 * MS}};
    vfp_gpio_decoder_edges(dec, e, 4, 0);
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 4, 30 * MS), 0);
    /* a button that starts pressed (active low, reading 0) reports its release */
    vfp_gpio_decoder_set_level(dec, SW0, 0);
    vfp_gpio_edge_t r[] = {{SW0, 1, 40 * MS}};
    vfp_gpio_decoder_edges(dec, r, 1, 0);
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 4, 50 * MS), 1);
    CHECK_EQ(ev[0].type, VFP_EV_RELEASE);
    vfp_gpio_decoder_free(dec);
}

static void button_press_with_bounces(void)
{
    vfp_board_t b = test_board();
    vfp_gpio_decoder_t *dec = vfp_gpio_decoder_new(&b);
    CHECK(dec);
    vfp_event_t ev[4];
    /* press: contact at 100 ms, bounces until 102 ms */
    vfp_gpio_edge_t e[] = {{SW0, 0, 100 * MS}, {SW0, 1, 101 * MS}, {SW0, 0, 102 * MS}};
    vfp_gpio_decoder_edges(dec, e, 3, 0);
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 4, 105 * MS), 0);
    CHECK_EQ(vfp_gpio_decoder_deadline(dec), 112 * MS); /* when the viewer must look again */
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 4, 112 * MS - 1), 0);
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 4, 112 * MS), 1);
    CHECK_EQ(ev[0].type, VFP_EV_PRESS);
    CHECK_EQ(ev[0].control, 0);
    CHECK_EQ(ev[0].time_ns, 102 * MS);
    CHECK_EQ(vfp_gpio_decoder_deadline(dec), 0);
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 4, 150 * MS), 0);
    /* release: the same, read late */
    vfp_gpio_edge_t r[] = {{SW0, 1, 200 * MS}, {SW0, 0, 201 * MS}, {SW0, 1, 203 * MS}};
    vfp_gpio_decoder_edges(dec, r, 3, 0);
    CHECK_EQ(vfp_gpio_decoder_deadline(dec), 213 * MS);
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 4, 500 * MS), 1);
    CHECK_EQ(ev[0].type, VFP_EV_RELEASE);
    CHECK_EQ(ev[0].time_ns, 203 * MS);
    vfp_gpio_decoder_free(dec);
}

static void button_glitch_and_late_edges(void)
{
    vfp_board_t b = test_board();
    vfp_gpio_decoder_t *dec = vfp_gpio_decoder_new(&b);
    CHECK(dec);
    vfp_event_t ev[4];
    /* a 4 ms glitch on an active-high button with a 5 ms window: nothing */
    vfp_gpio_edge_t g[] = {{SW1, 1, 10 * MS}, {SW1, 0, 14 * MS}};
    vfp_gpio_decoder_edges(dec, g, 2, 0);
    CHECK_EQ(vfp_gpio_decoder_deadline(dec), 0);
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 4, 100 * MS), 0);
    /* a whole press and release in one batch, nobody reading between: both come, in order, with their times */
    vfp_gpio_edge_t p[] = {{SW1, 0, 250 * MS}, {SW1, 1, 200 * MS}, {SW1, 0, 240 * MS}};
    vfp_gpio_decoder_edges(dec, p, 3, 0); /* out of order: sorted to 200 (up), 240 (down), 250 (down again) */
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 4, 300 * MS), 2);
    CHECK_EQ(ev[0].type, VFP_EV_PRESS);
    CHECK_EQ(ev[0].control, 1);
    CHECK_EQ(ev[0].time_ns, 200 * MS);
    CHECK_EQ(ev[1].type, VFP_EV_RELEASE);
    CHECK_EQ(ev[1].time_ns, 240 * MS);
    vfp_gpio_decoder_free(dec);
}

static void buttons_and_knobs_together(void)
{
    vfp_board_t b = test_board();
    vfp_gpio_decoder_t *dec = vfp_gpio_decoder_new(&b);
    CHECK(dec);
    vfp_gpio_edge_t e[16];
    int n = cw_detent_by_line(e, A1, B1, 0);
    e[n++] = (vfp_gpio_edge_t){SW0, 0, 1 * MS};
    e[n++] = (vfp_gpio_edge_t){99, 0, 2 * MS}; /* a line nobody uses: ignored */
    vfp_gpio_decoder_edges(dec, e, n, 0);
    vfp_event_t ev[4];
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 4, 5 * MS), 1);
    CHECK_EQ(ev[0].type, VFP_EV_TURN);
    CHECK_EQ(ev[0].control, 1);
    CHECK_EQ(vfp_gpio_decoder_deadline(dec), 11 * MS);
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 4, 11 * MS), 1);
    CHECK_EQ(ev[0].type, VFP_EV_PRESS);
    vfp_gpio_decoder_free(dec);
}

static void small_max_keeps_the_rest(void)
{
    vfp_board_t b = test_board();
    vfp_gpio_decoder_t *dec = vfp_gpio_decoder_new(&b);
    CHECK(dec);
    vfp_gpio_edge_t e[16];
    int n = cw_detent_by_line(e, A0, B0, 0);
    n += cw_detent_by_line(e + n, A1, B1, 1);
    e[n++] = (vfp_gpio_edge_t){SW1, 1, 2 * MS};
    e[n++] = (vfp_gpio_edge_t){SW1, 0, 20 * MS}; /* settles the press (5 ms window), starts a release */
    vfp_gpio_decoder_edges(dec, e, n, 0);
    vfp_event_t ev[4];
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 1, 21 * MS), 1);
    CHECK_EQ(ev[0].control, 0);
    CHECK_EQ(vfp_gpio_decoder_deadline(dec), 1); /* more is due at once */
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 1, 21 * MS), 1);
    CHECK_EQ(ev[0].type, VFP_EV_TURN);
    CHECK_EQ(ev[0].control, 1);
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 4, 21 * MS), 1);
    CHECK_EQ(ev[0].type, VFP_EV_PRESS);
    CHECK_EQ(vfp_gpio_decoder_deadline(dec), 25 * MS); /* the release */
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 4, 25 * MS), 1);
    CHECK_EQ(ev[0].type, VFP_EV_RELEASE);
    vfp_gpio_decoder_free(dec);
}

static void lines_read_apart_are_merged(void)
{
    /* libgpiod 1.x: line A's fd is found empty at 2.5 ms, line B's is read later and already holds B's edges of
     * 2 and 4 ms, while A's edge of 3 ms is still to be read. Decoded at once, B's edge of 4 ms would come before
     * A's of 3 ms and the detent would be lost; held back until A has been read again, it is not. */
    vfp_board_t b = test_board();
    vfp_gpio_decoder_t *dec = vfp_gpio_decoder_new(&b);
    CHECK(dec);
    vfp_gpio_edge_t first[] = {{A0, 0, 1 * MS}, {B0, 0, 2 * MS}, {B0, 1, 4 * MS}};
    vfp_gpio_decoder_edges(dec, first, 3, 2500000);
    vfp_event_t ev[4];
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 4, 5 * MS), 0);
    /* the edges newer than 1.5 ms wait; the viewer is asked back once the oldest of them is 1 ms old */
    CHECK_EQ(vfp_gpio_decoder_deadline(dec), 3 * MS + 1);
    vfp_gpio_edge_t second[] = {{A0, 1, 3 * MS}};
    vfp_gpio_decoder_edges(dec, second, 1, 6 * MS);
    CHECK_EQ(vfp_gpio_decoder_read(dec, ev, 4, 6 * MS), 1);
    CHECK_EQ(ev[0].steps, 1);
    CHECK_EQ(ev[0].time_ns, 4 * MS);
    CHECK_EQ(vfp_gpio_decoder_deadline(dec), 0);
    /* nothing new: the held edges go once they are old enough */
    vfp_gpio_edge_t late[] = {{A0, 0, 10 * MS}};
    vfp_gpio_decoder_edges(dec, late, 1, 10500000);
    CHECK_EQ(vfp_gpio_decoder_deadline(dec), 11 * MS + 1);
    vfp_gpio_decoder_edges(dec, NULL, 0, 11 * MS + 1);
    CHECK_EQ(vfp_gpio_decoder_deadline(dec), 0);
    /* an edge stamped by another clock (kernels before 5.7 used CLOCK_REALTIME for 1.x) is never held */
    vfp_gpio_edge_t realtime[] = {{A0, 1, 1700000000000000000ull}};
    vfp_gpio_decoder_edges(dec, realtime, 1, 12 * MS);
    CHECK_EQ(vfp_gpio_decoder_deadline(dec), 0);
    vfp_gpio_decoder_free(dec);
}

static void missing_chip_label(void)
{
#ifdef VFP_HAVE_GPIOD
    vfp_board_t b = test_board();
    char err[512] = "";
    const vfp_input_ops_t *ops = vfp_input_find("gpiod", &b, err, sizeof err);
    CHECK_MSG(ops, "%s", err);
    vfp_input_t in;
    CHECK_EQ(ops->open(&in, &b, NULL, err, sizeof err), VFP_ERR);
    CHECK_MSG(strncmp(err, "gpio chip 'no-such-chip-label' not found (", 42) == 0, "%s", err);
    CHECK(in.priv == NULL);
    ops->close(&in); /* safe on an input that never opened */
#endif
}

CHECK_CASES({"out_of_order_lines_make_one_detent", out_of_order_lines_make_one_detent},
            {"detents_sum_per_knob_per_read", detents_sum_per_knob_per_read},
            {"bouncing_encoder_contacts", bouncing_encoder_contacts}, {"initial_levels", initial_levels},
            {"button_press_with_bounces", button_press_with_bounces},
            {"button_glitch_and_late_edges", button_glitch_and_late_edges},
            {"buttons_and_knobs_together", buttons_and_knobs_together},
            {"small_max_keeps_the_rest", small_max_keeps_the_rest},
            {"lines_read_apart_are_merged", lines_read_apart_are_merged}, {"missing_chip_label", missing_chip_label});
CHECK_RUN("input_gpiod")
