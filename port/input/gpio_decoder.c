/* SPDX-License-Identifier: MIT */
/* gpio_decoder.c: the GPIO backend's decoder (declared in input_backends.h), compiled in every build, with or
 * without libgpiod, so that tests drive it with synthetic edges. It takes (line, level, time) edges: it merges the
 * lines' edges in time order, tracks each line's level, feeds encoders to the quadrature table and buttons to the
 * debouncer, and queues whole detents and settled presses for input_gpiod.c's read(). */
#include "gpiod_internal.h"

#include <stdlib.h>
#include <string.h>

#define QUEUE 128                  /* decoded events waiting for read() */
#define HELD 64                    /* edges kept back for the next read (see vfp_gpio_decoder_edges) */
#define OTHER_CLOCK_NS 1000000000u /* an edge this far ahead of the reading is on another clock: never held */

/* ---------------------------------------------------------------------------------------------------------- */
/* Types */

typedef struct gpio_knob {
    int line_a, line_b;
    int a, b; /* the lines' levels as last seen */
    vfp_encoder_t enc;
} gpio_knob_t;

typedef struct gpio_button {
    int line;
    int pressed; /* the level that means pressed: 0 for active-low */
    vfp_debounce_t db;
} gpio_button_t;

struct vfp_gpio_decoder {
    gpio_knob_t knobs[VFP_MAX_KNOBS];
    gpio_button_t buttons[VFP_MAX_BUTTONS];
    int knob_count, button_count;
    vfp_event_t queue[QUEUE];
    int queued;
    int turn_slot[VFP_MAX_KNOBS]; /* where knob k's turn sits in the queue, or -1 */
    vfp_gpio_edge_t held[HELD];   /* read but too recent to decode, in time order */
    int held_count;
};

/* ---------------------------------------------------------------------------------------------------------- */
/* Prototypes */

static void sort_edges(vfp_gpio_edge_t *edges, int count);
static void edge(vfp_gpio_decoder_t *dec, const vfp_gpio_edge_t *e);
static void settle(vfp_gpio_decoder_t *dec, int b, uint64_t now_ns);
static void push(vfp_gpio_decoder_t *dec, vfp_event_type_t type, int control, int steps, uint64_t time_ns);

/* ---------------------------------------------------------------------------------------------------------- */
/* Public functions */

/* A decoder for the board's knobs and buttons, every line at its idle level (high with a pull-up or no pull,
 * low with a pull-down) until vfp_gpio_decoder_set_level says otherwise. NULL when out of memory. */
vfp_gpio_decoder_t *vfp_gpio_decoder_new(const vfp_board_t *board)
{
    vfp_gpio_decoder_t *dec = calloc(1, sizeof *dec);
    if (!dec)
        return NULL;
    dec->knob_count = board->knob_count;
    dec->button_count = board->button_count;
    for (int k = 0; k < dec->knob_count; k++) {
        gpio_knob_t *kn = &dec->knobs[k];
        kn->line_a = board->knobs[k].line_a;
        kn->line_b = board->knobs[k].line_b;
        kn->a = kn->b = board->knobs[k].pull != VFP_PULL_DOWN;
        vfp_encoder_init(&kn->enc, kn->a, kn->b);
        dec->turn_slot[k] = -1;
    }
    for (int b = 0; b < dec->button_count; b++) {
        gpio_button_t *bt = &dec->buttons[b];
        bt->line = board->buttons[b].line;
        bt->pressed = !board->buttons[b].active_low;
        vfp_debounce_init(&bt->db, board->buttons[b].pull != VFP_PULL_DOWN, board->buttons[b].debounce_ms);
    }
    return dec;
}

/* The level a line has now (read once the lines are requested): the start for its encoder or debouncer. */
void vfp_gpio_decoder_set_level(vfp_gpio_decoder_t *dec, unsigned line, int level)
{
    level = level != 0;
    for (int k = 0; k < dec->knob_count; k++) {
        gpio_knob_t *kn = &dec->knobs[k];
        if (kn->line_a == (int)line)
            kn->a = level;
        if (kn->line_b == (int)line)
            kn->b = level;
        if (kn->line_a == (int)line || kn->line_b == (int)line)
            vfp_encoder_init(&kn->enc, kn->a, kn->b);
    }
    for (int b = 0; b < dec->button_count; b++)
        if (dec->buttons[b].line == (int)line) {
            vfp_debounce_t *db = &dec->buttons[b].db;
            vfp_debounce_init(db, level, (int)(db->window_ns / 1000000u));
        }
}

/* Edges from any lines, in any order: sorted by time here (ties keep their order), then decoded. `edges` is
 * reordered.
 *
 * libgpiod 1.x gives each line its own fd, read one after the other: while line B is read, line A (already found
 * empty) may get an edge older than some of B's. So read_ns is when the first line was found empty, and edges
 * less than VFPI_GPIO_HOLD_NS older than that are kept back and merged with the next call's (the hold also covers
 * the kernel's time from stamping an edge to queueing it); vfp_gpio_decoder_deadline says when to call again.
 * read_ns = 0 decodes everything at once (2.x: one request, one queue in time order; and tests). */
void vfp_gpio_decoder_edges(vfp_gpio_decoder_t *dec, vfp_gpio_edge_t *edges, int count, uint64_t read_ns)
{
    sort_edges(edges, count);
    int e = 0, h = 0, kept = 0;
    vfp_gpio_edge_t keep[HELD];
    /* merge the held edges (sorted) with the new ones (sorted) */
    while (e < count || h < dec->held_count) {
        const vfp_gpio_edge_t *next = h < dec->held_count && (e >= count || dec->held[h].time_ns <= edges[e].time_ns)
                                          ? &dec->held[h++]
                                          : &edges[e++];
        int hold = read_ns && next->time_ns + VFPI_GPIO_HOLD_NS > read_ns && next->time_ns < read_ns + OTHER_CLOCK_NS;
        if (hold && kept < HELD)
            keep[kept++] = *next;
        else
            edge(dec, next); /* a full hold buffer lets the oldest through rather than losing it */
    }
    memcpy(dec->held, keep, sizeof keep[0] * (size_t)kept);
    dec->held_count = kept;
}

/* Report: buttons whose level has been stable for their window by now_ns are accepted (stamped with the time
 * the level settled), then the queue's first `max` events go out; a knob's detents of this read are one event. */
int vfp_gpio_decoder_read(vfp_gpio_decoder_t *dec, vfp_event_t *events, int max, uint64_t now_ns)
{
    for (int b = 0; b < dec->button_count; b++)
        settle(dec, b, now_ns);
    return vfpi_events_report(dec->queue, &dec->queued, dec->turn_slot, dec->knob_count, events, max);
}

/* The earliest time read() will have something without a new edge: 1 (at once) when events are queued, else the
 * first debounce deadline or the time the first held edge can be decoded; 0 for none. */
uint64_t vfp_gpio_decoder_deadline(const vfp_gpio_decoder_t *dec)
{
    if (dec->queued > 0)
        return 1;
    uint64_t first = dec->held_count ? dec->held[0].time_ns + VFPI_GPIO_HOLD_NS + 1 : 0;
    for (int b = 0; b < dec->button_count; b++) {
        uint64_t t = vfp_debounce_deadline(&dec->buttons[b].db);
        if (t && (!first || t < first))
            first = t;
    }
    return first;
}

void vfp_gpio_decoder_free(vfp_gpio_decoder_t *dec)
{
    free(dec);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Static functions */

/* Insertion sort: stable, and the batches are short and nearly sorted already. */
static void sort_edges(vfp_gpio_edge_t *edges, int count)
{
    for (int i = 1; i < count; i++) {
        vfp_gpio_edge_t e = edges[i];
        int j = i;
        while (j > 0 && edges[j - 1].time_ns > e.time_ns) {
            edges[j] = edges[j - 1];
            j--;
        }
        edges[j] = e;
    }
}

static void edge(vfp_gpio_decoder_t *dec, const vfp_gpio_edge_t *e)
{
    int level = e->level != 0;
    for (int k = 0; k < dec->knob_count; k++) {
        gpio_knob_t *kn = &dec->knobs[k];
        if (kn->line_a != (int)e->line && kn->line_b != (int)e->line)
            continue;
        if (kn->line_a == (int)e->line)
            kn->a = level;
        else
            kn->b = level;
        int detent = vfp_encoder_update(&kn->enc, kn->a, kn->b);
        if (!detent)
            continue;
        if (dec->turn_slot[k] >= 0) {
            dec->queue[dec->turn_slot[k]].steps += detent;
            dec->queue[dec->turn_slot[k]].time_ns = e->time_ns;
        } else if (dec->queued < QUEUE) {
            dec->turn_slot[k] = dec->queued;
            push(dec, VFP_EV_TURN, k, detent, e->time_ns);
        }
    }
    for (int b = 0; b < dec->button_count; b++) {
        gpio_button_t *bt = &dec->buttons[b];
        if (bt->line != (int)e->line)
            continue;
        /* A change that had settled before this edge is accepted first, with its own time. */
        settle(dec, b, e->time_ns);
        int r = vfp_debounce_update(&bt->db, level, bt->pressed, e->time_ns);
        if (r) /* only with no window: the edge counts at once */
            push(dec, r > 0 ? VFP_EV_PRESS : VFP_EV_RELEASE, b, 0, e->time_ns);
    }
}

static void settle(vfp_gpio_decoder_t *dec, int b, uint64_t now_ns)
{
    gpio_button_t *bt = &dec->buttons[b];
    int r = vfp_debounce_update(&bt->db, bt->db.last, bt->pressed, now_ns);
    if (r)
        push(dec, r > 0 ? VFP_EV_PRESS : VFP_EV_RELEASE, b, 0, bt->db.changed_ns);
}

static void push(vfp_gpio_decoder_t *dec, vfp_event_type_t type, int control, int steps, uint64_t time_ns)
{
    if (dec->queued >= QUEUE) /* nobody has read for a long while: the newest events are dropped */
        return;
    dec->queue[dec->queued++] = (vfp_event_t){.type = type, .control = control, .steps = steps, .time_ns = time_ns};
}
