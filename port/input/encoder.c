/* SPDX-License-Identifier: MIT */
/* encoder.c: the pure helpers the input backends share (input.h): quadrature decoding of a rotary encoder, and
 * software debouncing of a push button. No I/O and no clock: the caller passes levels and times. */
#include "input.h"

#include <string.h>

/* Steps per detent of the usual mechanical encoder (a full quadrature cycle between two clicks). */
#define STEPS_PER_DETENT 4

/* Indexed by (old state << 2) | new state, a state being (A << 1) | B. A valid single-bit change moves one step;
 * no change and an impossible double change (both lines flipped: a missed edge or a bounce) move none.
 * Positive is A leading B, the states in the order 00, 10, 11, 01, 00, which is clockwise on the common encoders
 * (EC11 and the like, A and B as printed on the part); swap a and b in the board file when a knob turns the wrong
 * way. */
static const signed char transition[16] = {
    0,  -1, +1, 0,  /* from 00 to 00, 01, 10, 11 */
    +1, 0,  0,  -1, /* from 01 */
    -1, 0,  0,  +1, /* from 10 */
    0,  +1, -1, 0,  /* from 11 */
};

/* ---------------------------------------------------------------------------------------------------------- */
/* Quadrature */

void vfp_encoder_init(vfp_encoder_t *enc, int a, int b)
{
    enc->state = (uint8_t)(((a != 0) << 1) | (b != 0));
    enc->steps = 0;
}

int vfp_encoder_update(vfp_encoder_t *enc, int a, int b)
{
    uint8_t next = (uint8_t)(((a != 0) << 1) | (b != 0));
    enc->steps += transition[(enc->state << 2) | next];
    enc->state = next;
    /* A detent is reported when the count reaches +-4 and the remainder is kept, so that steps turned back and
     * forth inside a detent (a hand resting on the knob) cancel instead of adding up. */
    if (enc->steps >= STEPS_PER_DETENT) {
        enc->steps -= STEPS_PER_DETENT;
        return 1;
    }
    if (enc->steps <= -STEPS_PER_DETENT) {
        enc->steps += STEPS_PER_DETENT;
        return -1;
    }
    return 0;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Debouncing */

void vfp_debounce_init(vfp_debounce_t *db, int level, int debounce_ms)
{
    memset(db, 0, sizeof *db);
    db->stable = db->last = level != 0;
    db->changed_ns = 0;
    db->window_ns = debounce_ms > 0 ? (uint64_t)debounce_ms * 1000000u : 0;
}

/* The pending change (last != stable) settles once `last` has been seen for the whole window. */
static int settle(vfp_debounce_t *db, int pressed, uint64_t now_ns)
{
    if (db->last == db->stable || now_ns < db->changed_ns || now_ns - db->changed_ns < db->window_ns)
        return 0;
    db->stable = db->last;
    return db->stable == pressed ? 1 : -1;
}

int vfp_debounce_update(vfp_debounce_t *db, int level, int pressed, uint64_t now_ns)
{
    level = level != 0;
    pressed = pressed != 0;
    /* First a change that had already settled before this sample, so that a late edge cannot hide it. */
    int result = settle(db, pressed, now_ns);
    if (level != db->last) {
        db->last = level;
        db->changed_ns = now_ns;
    }
    /* With no window (debounce_ms = 0) the new level counts at once. */
    if (result == 0)
        result = settle(db, pressed, now_ns);
    return result;
}

uint64_t vfp_debounce_deadline(const vfp_debounce_t *db)
{
    if (db->last == db->stable)
        return 0;
    uint64_t t = db->changed_ns + db->window_ns;
    return t ? t : 1; /* 0 means "nothing pending": a change at time 0 with no window is due at once */
}
