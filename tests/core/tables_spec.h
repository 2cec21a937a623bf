/* SPDX-License-Identifier: MIT */
/*
 * tables_spec.h: what the table suites (test_classify_tables.c, test_lit_tables.c) share: a classification and
 * table scratch over one arena, docs/algorithm.md section 1's classification written again in double (the spec
 * each suite builds its own section 2 or section 7 on), and random transfer functions. Header-only and static
 * inline, as frame.h is, so that each suite stays one file. Random draws come from the suite's own generator and
 * seed.
 */
#ifndef TESTS_CORE_TABLES_SPEC_H
#define TESTS_CORE_TABLES_SPEC_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>

#include "arena.h"
#include "classify.h"
#include "scene_fixture.h"
#include "tables.h"

#define SPEC_MAX_N 1024

/* Room for classification and scratch (lit included) of up to SPEC_MAX_N entries; tables are the suites' own. */
static _Alignas(16) unsigned char arena_buf[1 << 19];

typedef struct fixture {
    vf_arena_t arena;
    vfi_classify_t cls;
    vfi_table_scratch_t scratch;
} fixture_t;

/* A classification of n entries and table scratch, with the lit builders' part when lit: 1, or 0 when short. */
static inline int fixture_init(fixture_t *fx, uint32_t n, bool lit)
{
    vf_arena_init(&fx->arena, arena_buf, sizeof arena_buf);
    if (vfi_classify_alloc(&fx->cls, n, VF_LOOKUP_NEAREST, &fx->arena) != VF_OK)
        return 0;
    if (lit)
        return vfi_table_scratch_alloc_lit(&fx->scratch, n, &fx->arena) == VF_OK;
    return vfi_table_scratch_alloc(&fx->scratch, n, &fx->arena) == VF_OK;
}

/* ---- section 1 in double -------------------------------------------------------------------------------- */

static inline double channel(const vf_tf_point_t *p, int c)
{
    return (c == 0 ? p->r : c == 1 ? p->g : c == 2 ? p->b : p->a) / 65535.0;
}

/* Channel c of the transfer function at entry i's scalar s_i = i 255 / (N - 1). Which segment s_i falls in is
 * decided exactly (Q8.8 scalars times N - 1 against i 65280); the interpolation is double. */
static inline double tf_at_entry(const vf_tf_t *tf, uint32_t i, uint32_t n, int c)
{
    const vf_tf_point_t *pts = tf->points;
    uint64_t num = (uint64_t)i * 65280, den = n - 1;
    int64_t p = -1;
    while (p + 1 < (int64_t)tf->count && (uint64_t)pts[p + 1].scalar_q8 * den <= num)
        p++;
    if (p < 0)
        return channel(&pts[0], c);
    if (p + 1 == (int64_t)tf->count)
        return channel(&pts[p], c);
    double s = (double)num / (double)den; /* Q8.8 units */
    double w = (s - pts[p].scalar_q8) / (pts[p + 1].scalar_q8 - pts[p].scalar_q8);
    return channel(&pts[p], c) + w * (channel(&pts[p + 1], c) - channel(&pts[p], c));
}

/* Entry i's opacity per unit length a0 as the transfer function gives it, its extinction tau (a0 clamped below 1
 * as the core clamps it) and its colour. */
typedef struct spec {
    uint32_t n;
    double a0[SPEC_MAX_N], tau[SPEC_MAX_N], col[SPEC_MAX_N][3];
} spec_t;

static spec_t spec;

static inline void spec_classify(const vf_tf_t *tf, uint32_t n)
{
    spec.n = n;
    for (uint32_t i = 0; i < n; i++) {
        double a0 = tf_at_entry(tf, i, n, 3);
        spec.a0[i] = a0;
        a0 = fmin(a0, 1 - 1.0 / 65536);
        spec.tau[i] = -log1p(-a0);
        for (int c = 0; c < 3; c++)
            spec.col[i][c] = tf_at_entry(tf, i, n, c);
    }
}

/* ---- transfer functions ----------------------------------------------------------------------------------- */

/* 1..8 points into pts, coloured or grey (r = g = b), sometimes sharing a scalar (a step), opacity often exactly
 * zero (invisible ranges), sometimes 65535 (the clamp, opaque runs), sometimes tiny, and sometimes points outside
 * the used range. */
static inline vf_tf_t spec_random_tf(vf_tf_point_t *pts, bool grey, scene_draw_t draw, uint64_t *state)
{
    uint32_t count = 1 + draw(state, 8);
    uint32_t s = draw(state, 40000);
    for (uint32_t p = 0; p < count; p++) {
        if (p > 0 && draw(state, 4) != 0)
            s += draw(state, 30000);
        if (s > 65280)
            s = 65280;
        pts[p].scalar_q8 = (uint16_t)s;
        pts[p].r = (uint16_t)draw(state, 65536);
        pts[p].g = grey ? pts[p].r : (uint16_t)draw(state, 65536);
        pts[p].b = grey ? pts[p].r : (uint16_t)draw(state, 65536);
        uint32_t k = draw(state, 6);
        pts[p].a = (uint16_t)(k < 2 ? 0 : k == 2 ? 65535 : k == 3 ? draw(state, 64) : draw(state, 65536));
    }
    return (vf_tf_t){pts, count};
}

#endif
