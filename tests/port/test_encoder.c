/* SPDX-License-Identifier: MIT */
/* test_encoder.c: the quadrature decoder and the button debouncer (port/input/encoder.c), edge by edge. */
#include "check.h"
#include "input/input.h"

#define MS 1000000ull /* ns */

/* Feed a sequence of (A, B) states; returns the sum of the detents reported, and counts the reports. */
static int feed(vfp_encoder_t *enc, const int (*ab)[2], int n, int *reports)
{
    int sum = 0;
    for (int i = 0; i < n; i++) {
        int d = vfp_encoder_update(enc, ab[i][0], ab[i][1]);
        sum += d;
        if (reports && d)
            (*reports)++;
    }
    return sum;
}

/* One clockwise detent from rest with pull-ups (both high): A leads, 11 -> 01 -> 00 -> 10 -> 11. */
static const int CW[4][2] = {{0, 1}, {0, 0}, {1, 0}, {1, 1}};
/* One counter-clockwise detent: B leads, 11 -> 10 -> 00 -> 01 -> 11. */
static const int CCW[4][2] = {{1, 0}, {0, 0}, {0, 1}, {1, 1}};

/* ---------------------------------------------------------------------------------------------------------- */
/* Quadrature */

static void clockwise_detents(void)
{
    vfp_encoder_t enc;
    vfp_encoder_init(&enc, 1, 1);
    /* the detent is reported on the fourth step, not before */
    CHECK_EQ(vfp_encoder_update(&enc, CW[0][0], CW[0][1]), 0);
    CHECK_EQ(vfp_encoder_update(&enc, CW[1][0], CW[1][1]), 0);
    CHECK_EQ(vfp_encoder_update(&enc, CW[2][0], CW[2][1]), 0);
    CHECK_EQ(vfp_encoder_update(&enc, CW[3][0], CW[3][1]), 1);
    CHECK_EQ(enc.steps, 0);
    int reports = 0;
    for (int i = 0; i < 10; i++)
        CHECK_EQ(feed(&enc, CW, 4, &reports), 1);
    CHECK_EQ(reports, 10);
}

static void counter_clockwise_detents(void)
{
    vfp_encoder_t enc;
    vfp_encoder_init(&enc, 1, 1);
    CHECK_EQ(vfp_encoder_update(&enc, CCW[0][0], CCW[0][1]), 0);
    CHECK_EQ(vfp_encoder_update(&enc, CCW[1][0], CCW[1][1]), 0);
    CHECK_EQ(vfp_encoder_update(&enc, CCW[2][0], CCW[2][1]), 0);
    CHECK_EQ(vfp_encoder_update(&enc, CCW[3][0], CCW[3][1]), -1);
    int reports = 0;
    for (int i = 0; i < 7; i++)
        CHECK_EQ(feed(&enc, CCW, 4, &reports), -1);
    CHECK_EQ(reports, 7);
}

static void from_low_rest(void)
{
    /* Pull-downs: rest at 00. The same table, the same direction: 00 -> 10 -> 11 -> 01 -> 00 is clockwise. */
    static const int cw_low[4][2] = {{1, 0}, {1, 1}, {0, 1}, {0, 0}};
    vfp_encoder_t enc;
    vfp_encoder_init(&enc, 0, 0);
    CHECK_EQ(feed(&enc, cw_low, 4, NULL), 1);
    CHECK_EQ(enc.steps, 0);
}

static void partial_steps_and_reversal(void)
{
    vfp_encoder_t enc;
    vfp_encoder_init(&enc, 1, 1);
    /* half a detent forward, then back: nothing */
    static const int half_and_back[4][2] = {{0, 1}, {0, 0}, {0, 1}, {1, 1}};
    CHECK_EQ(feed(&enc, half_and_back, 4, NULL), 0);
    CHECK_EQ(enc.steps, 0);
    /* three steps forward, one back, two forward: the count reaches +4 on the last edge */
    static const int wobble[6][2] = {{0, 1}, {0, 0}, {1, 0}, {0, 0}, {1, 0}, {1, 1}};
    int reports = 0;
    CHECK_EQ(feed(&enc, wobble, 5, &reports), 0);
    CHECK_EQ(enc.steps, 3);
    CHECK_EQ(vfp_encoder_update(&enc, wobble[5][0], wobble[5][1]), 1);
    CHECK_EQ(enc.steps, 0);
    /* a whole detent clockwise then a whole one back */
    CHECK_EQ(feed(&enc, CW, 4, NULL), 1);
    CHECK_EQ(feed(&enc, CCW, 4, NULL), -1);
    CHECK_EQ(enc.steps, 0);
}

static void remainder_is_kept(void)
{
    vfp_encoder_t enc;
    vfp_encoder_init(&enc, 1, 1);
    /* six steps: one detent and two left over, which the next two steps complete */
    CHECK_EQ(feed(&enc, CW, 4, NULL), 1);
    CHECK_EQ(feed(&enc, CW, 2, NULL), 0);
    CHECK_EQ(enc.steps, 2);
    CHECK_EQ(feed(&enc, CW + 2, 2, NULL), 1);
    CHECK_EQ(enc.steps, 0);
    /* counter-clockwise from a partial clockwise position: -1, -2, ..., -4 reports at the fourth step back */
    CHECK_EQ(feed(&enc, CW, 1, NULL), 0); /* +1 (at 01) */
    static const int back[5][2] = {{1, 1}, {1, 0}, {0, 0}, {0, 1}, {1, 1}};
    int reports = 0;
    CHECK_EQ(feed(&enc, back, 5, &reports), -1); /* 0, -1, -2, -3, -4 */
    CHECK_EQ(reports, 1);
    CHECK_EQ(enc.steps, 0);
}

static void bouncing_a_line(void)
{
    vfp_encoder_t enc;
    vfp_encoder_init(&enc, 1, 1);
    /* A chatters while B stays high: each bounce is a step and its undoing */
    static const int chatter[6][2] = {{0, 1}, {1, 1}, {0, 1}, {1, 1}, {0, 1}, {1, 1}};
    CHECK_EQ(feed(&enc, chatter, 6, NULL), 0);
    CHECK_EQ(enc.steps, 0);
    /* a real detent whose first edge bounces three times: still exactly one detent */
    static const int bouncy_detent[7][2] = {{0, 1}, {1, 1}, {0, 1}, {1, 1}, {0, 1}, {0, 0}, {1, 0}};
    int reports = 0;
    CHECK_EQ(feed(&enc, bouncy_detent, 7, &reports), 0);
    CHECK_EQ(vfp_encoder_update(&enc, 1, 1), 1);
    CHECK_EQ(reports, 0);
    CHECK_EQ(enc.steps, 0);
}

static void repeated_edges(void)
{
    vfp_encoder_t enc;
    vfp_encoder_init(&enc, 1, 1);
    /* the same state reported again (a line read twice, or an edge whose level did not change) moves nothing */
    static const int repeats[8][2] = {{0, 1}, {0, 1}, {0, 0}, {0, 0}, {0, 0}, {1, 0}, {1, 0}, {1, 1}};
    int reports = 0;
    CHECK_EQ(feed(&enc, repeats, 8, &reports), 1);
    CHECK_EQ(reports, 1);
    CHECK_EQ(vfp_encoder_update(&enc, 1, 1), 0);
    CHECK_EQ(enc.steps, 0);
}

static void invalid_double_transition(void)
{
    vfp_encoder_t enc;
    vfp_encoder_init(&enc, 1, 1);
    /* 11 -> 00 directly (both lines changed between two looks: a lost edge) counts nothing... */
    CHECK_EQ(vfp_encoder_update(&enc, 0, 0), 0);
    CHECK_EQ(enc.steps, 0);
    CHECK_EQ(enc.state, 0);
    /* ...but the state follows, so the next valid edges count from there: 00 -> 10 -> 11 is +2 */
    CHECK_EQ(vfp_encoder_update(&enc, 1, 0), 0);
    CHECK_EQ(vfp_encoder_update(&enc, 1, 1), 0);
    CHECK_EQ(enc.steps, 2);
    /* two more valid steps complete the detent: 11 -> 01 -> 00 is +3, +4 */
    CHECK_EQ(vfp_encoder_update(&enc, 0, 1), 0);
    CHECK_EQ(vfp_encoder_update(&enc, 0, 0), 1);
    CHECK_EQ(enc.steps, 0);
}

static void invalid_double_transition_counts(void)
{
    vfp_encoder_t enc;
    vfp_encoder_init(&enc, 1, 1);
    CHECK_EQ(vfp_encoder_update(&enc, 0, 1), 0); /* +1 */
    CHECK_EQ(vfp_encoder_update(&enc, 1, 0), 0); /* 01 -> 10: invalid, 0 */
    CHECK_EQ(enc.steps, 1);
    CHECK_EQ(vfp_encoder_update(&enc, 1, 1), 0); /* 10 -> 11: +1 */
    CHECK_EQ(enc.steps, 2);
    CHECK_EQ(vfp_encoder_update(&enc, 0, 0), 0); /* 11 -> 00: invalid */
    CHECK_EQ(enc.steps, 2);
}

static void every_transition(void)
{
    /* The whole table: +1 for A leading, -1 for B leading, 0 for none and for both. */
    for (int from = 0; from < 4; from++)
        for (int to = 0; to < 4; to++) {
            vfp_encoder_t enc;
            vfp_encoder_init(&enc, from >> 1, from & 1);
            vfp_encoder_update(&enc, to >> 1, to & 1);
            int expect;
            if (from == to || (from ^ to) == 3)
                expect = 0;
            else {
                /* clockwise order of states: 00, 10, 11, 01 */
                static const int pos[4] = {0, 3, 1, 2}; /* position of state 00, 01, 10, 11 in that order */
                expect = (pos[to] - pos[from] + 4) % 4 == 1 ? 1 : -1;
            }
            CHECK_MSG(enc.steps == expect, "from %d to %d: %d steps, expected %d", from, to, enc.steps, expect);
        }
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Debouncing: an active-low button (pressed reads 0) with a 10 ms window */

static void press_with_bounces(void)
{
    vfp_debounce_t db;
    vfp_debounce_init(&db, 1, 10);
    CHECK_EQ(vfp_debounce_deadline(&db), 0);
    CHECK_EQ(vfp_debounce_update(&db, 0, 0, 100 * MS), 0); /* first contact */
    CHECK_EQ(vfp_debounce_deadline(&db), 110 * MS);
    CHECK_EQ(vfp_debounce_update(&db, 1, 0, 101 * MS), 0); /* bounce */
    CHECK_EQ(vfp_debounce_update(&db, 0, 0, 102 * MS), 0);
    CHECK_EQ(vfp_debounce_update(&db, 1, 0, 103 * MS), 0);
    CHECK_EQ(vfp_debounce_update(&db, 0, 0, 104 * MS), 0); /* settles here */
    CHECK_EQ(vfp_debounce_deadline(&db), 114 * MS);
    /* polls before the window is over give nothing; the one at the deadline gives the press, once */
    CHECK_EQ(vfp_debounce_update(&db, 0, 0, 110 * MS), 0);
    CHECK_EQ(vfp_debounce_update(&db, 0, 0, 114 * MS - 1), 0);
    CHECK_EQ(vfp_debounce_update(&db, 0, 0, 114 * MS), 1);
    CHECK_EQ(db.changed_ns, 104 * MS); /* when the level settled */
    CHECK_EQ(vfp_debounce_deadline(&db), 0);
    CHECK_EQ(vfp_debounce_update(&db, 0, 0, 200 * MS), 0);
    CHECK_EQ(db.stable, 0);
}

static void glitch_counts_nothing(void)
{
    vfp_debounce_t db;
    vfp_debounce_init(&db, 1, 10);
    CHECK_EQ(vfp_debounce_update(&db, 0, 0, 50 * MS), 0);
    CHECK_EQ(vfp_debounce_update(&db, 1, 0, 53 * MS), 0); /* back after 3 ms */
    CHECK_EQ(vfp_debounce_deadline(&db), 0);
    CHECK_EQ(vfp_debounce_update(&db, 1, 0, 100 * MS), 0);
    CHECK_EQ(db.stable, 1);
    /* a glitch of 9.999 ms is still a glitch */
    CHECK_EQ(vfp_debounce_update(&db, 0, 0, 200 * MS), 0);
    CHECK_EQ(vfp_debounce_update(&db, 1, 0, 210 * MS - 1), 0);
    CHECK_EQ(vfp_debounce_update(&db, 1, 0, 300 * MS), 0);
}

static void release_with_bounces(void)
{
    vfp_debounce_t db;
    vfp_debounce_init(&db, 0, 10); /* starts pressed */
    CHECK_EQ(vfp_debounce_update(&db, 1, 0, 10 * MS), 0);
    CHECK_EQ(vfp_debounce_update(&db, 0, 0, 11 * MS), 0);
    CHECK_EQ(vfp_debounce_update(&db, 1, 0, 13 * MS), 0);
    CHECK_EQ(vfp_debounce_deadline(&db), 23 * MS);
    CHECK_EQ(vfp_debounce_update(&db, 1, 0, 22 * MS), 0);
    CHECK_EQ(vfp_debounce_update(&db, 1, 0, 30 * MS), -1); /* a late poll still gives it */
    CHECK_EQ(db.changed_ns, 13 * MS);
    /* and a release glitch while pressed... */
    vfp_debounce_init(&db, 0, 10);
    CHECK_EQ(vfp_debounce_update(&db, 1, 0, 10 * MS), 0);
    CHECK_EQ(vfp_debounce_update(&db, 0, 0, 12 * MS), 0);
    CHECK_EQ(vfp_debounce_update(&db, 0, 0, 40 * MS), 0);
}

static void settled_change_then_edge(void)
{
    /* Nobody polled at the deadline; the next edge comes later. The settled press must not be lost. */
    vfp_debounce_t db;
    vfp_debounce_init(&db, 1, 10);
    CHECK_EQ(vfp_debounce_update(&db, 0, 0, 0), 0);
    CHECK_EQ(vfp_debounce_update(&db, 1, 0, 30 * MS), 1); /* the press, accepted before the release edge */
    CHECK_EQ(vfp_debounce_deadline(&db), 40 * MS);        /* the release is pending now */
    CHECK_EQ(vfp_debounce_update(&db, 1, 0, 40 * MS), -1);
}

static void active_high_and_no_window(void)
{
    vfp_debounce_t db;
    vfp_debounce_init(&db, 0, 10); /* pressed reads 1 */
    CHECK_EQ(vfp_debounce_update(&db, 1, 1, 5 * MS), 0);
    CHECK_EQ(vfp_debounce_update(&db, 1, 1, 15 * MS), 1);
    CHECK_EQ(vfp_debounce_update(&db, 0, 1, 20 * MS), 0);
    CHECK_EQ(vfp_debounce_update(&db, 0, 1, 30 * MS), -1);
    /* debounce_ms = 0: every change counts at once */
    vfp_debounce_init(&db, 1, 0);
    CHECK_EQ(vfp_debounce_update(&db, 0, 0, 7), 1);
    CHECK_EQ(vfp_debounce_deadline(&db), 0);
    CHECK_EQ(vfp_debounce_update(&db, 1, 0, 8), -1);
    CHECK_EQ(vfp_debounce_update(&db, 1, 0, 9), 0);
}

CHECK_CASES({"clockwise_detents", clockwise_detents}, {"counter_clockwise_detents", counter_clockwise_detents},
            {"from_low_rest", from_low_rest}, {"partial_steps_and_reversal", partial_steps_and_reversal},
            {"remainder_is_kept", remainder_is_kept}, {"bouncing_a_line", bouncing_a_line},
            {"repeated_edges", repeated_edges}, {"invalid_double_transition", invalid_double_transition},
            {"invalid_double_transition_counts", invalid_double_transition_counts},
            {"every_transition", every_transition}, {"press_with_bounces", press_with_bounces},
            {"glitch_counts_nothing", glitch_counts_nothing}, {"release_with_bounces", release_with_bounces},
            {"settled_change_then_edge", settled_change_then_edge},
            {"active_high_and_no_window", active_high_and_no_window});
CHECK_RUN("encoder")
