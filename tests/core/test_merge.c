/* SPDX-License-Identifier: MIT */
/*
 * test_merge.c: the union of a slab row's runs (core/composite.h: vfi_merge_runs), which decides the pixels a slab
 * walks and, in the runs it records, where the next slab finds its fronts buffered: a pixel too many there would
 * read a stale front. Against brute force: the pixels each slice's runs cover set in a bitmap, clipped, read back
 * as maximal intervals (runs that overlap or touch are one interval there, as the merge joins them).
 */
#include <stdint.h>
#include <string.h>

#include "check.h"
#include "composite.h"

#define CELLS 300     /* cells in a row */
#define PIXELS 400    /* pixels of the intermediate row: cells + column offsets below 80 */
#define MAX_PAIRS 400 /* (skip, length) pairs, at most a run every other cell */

static uint64_t rng = 0x3C6EF372FE94F82Bu;

/* A random run list of a cell row as runs.c writes it: (skip, length) pairs, the first skip 0 or more, the others 1
 * or more (a run ends at an invisible cell), every length 1 or more; dense, sparse, or with single gaps (which the
 * other slice's runs, a pixel off, fill). Returns the number of uint16 values. */
static uint32_t random_runs(uint16_t *pairs)
{
    const uint32_t style = check_below(&rng, 4);
    uint32_t n = 0, cell = 0;
    for (;;) {
        uint32_t skip = style == 0 ? 1 : style == 1 ? 1 + check_below(&rng, 3) : 1 + check_below(&rng, 40);
        if (n == 0)
            skip = check_below(&rng, 3) == 0 ? 0 : skip;
        const uint32_t length = 1 + check_below(&rng, style == 3 ? 60 : 8);
        if (cell + skip + length > CELLS)
            return n;
        pairs[n++] = (uint16_t)skip;
        pairs[n++] = (uint16_t)length;
        cell += skip + length;
    }
}

/* The pixels of a row's runs at column offset cu, set in covered */
static void cover(const uint16_t *pairs, uint32_t n, int32_t cu, uint8_t *covered)
{
    int32_t cell = 0;
    for (uint32_t k = 0; k < n; k += 2) {
        cell += pairs[k];
        for (int32_t c = cell; c < cell + pairs[k + 1]; c++)
            covered[c + cu] = 1;
        cell += pairs[k + 1];
    }
}

/* The maximal intervals of covered pixels in [lo, hi] */
static uint32_t intervals(const uint8_t *covered, int32_t lo, int32_t hi, vfi_span_t *out)
{
    uint32_t count = 0;
    for (int32_t u = lo < 0 ? 0 : lo; u <= hi && u < PIXELS; u++) {
        if (!covered[u])
            continue;
        int32_t end = u;
        while (end + 1 <= hi && end + 1 < PIXELS && covered[end + 1])
            end++;
        out[count].a = (uint32_t)u;
        out[count].b = (uint32_t)end + 1;
        count++;
        u = end;
    }
    return count;
}

static int same(const vfi_span_t *a, uint32_t na, const vfi_span_t *b, uint32_t nb)
{
    return na == nb && memcmp(a, b, sizeof *a * na) == 0;
}

/* Slices whose first pixels are 1..60 and a pixel or none apart, either way round, and a clip anywhere */
static void random_placement(slice_place_t *front, slice_place_t *back, int32_t *lo, int32_t *hi)
{
    memset(front, 0, sizeof *front);
    memset(back, 0, sizeof *back);
    front->cu = 1 + (int32_t)check_below(&rng, 60);
    back->cu = front->cu + (int32_t)check_below(&rng, 3) - 1;
    *lo = (int32_t)check_below(&rng, 80);
    *hi = *lo + (int32_t)check_below(&rng, PIXELS - 80);
}

/* The merge of a front and a back row's runs equals brute force; the number of runs it gave in *got_count, brute
 * force's in *want_count. */
static int merge_is_union(const uint16_t *pairs_f, uint32_t nf, const uint16_t *pairs_b, uint32_t nb,
                          const slice_place_t *front, const slice_place_t *back, int32_t lo, int32_t hi,
                          uint32_t *got_count, uint32_t *want_count)
{
    vfi_span_t want[PIXELS], got[PIXELS];
    uint8_t covered[PIXELS] = {0};
    cover(pairs_f, nf, front->cu, covered);
    cover(pairs_b, nb, back->cu, covered);
    *want_count = intervals(covered, lo, hi, want);
    run_merge_t m;
    vfi_merge_init(&m, 16, pairs_f, pairs_f + nf, front, pairs_b, pairs_b + nb, back);
    *got_count = vfi_merge_runs(&m, lo, hi, got);
    return same(got, *got_count, want, *want_count);
}

/* 20,000 random rows: the front slice's and the back slice's, or (same_row) one row for both */
static void random_unions(int same_row)
{
    uint16_t pairs_f[MAX_PAIRS], pairs_b[MAX_PAIRS];
    for (int trial = 0; trial < 20000; trial++) {
        const uint32_t nf = random_runs(pairs_f), nb = same_row ? nf : random_runs(pairs_b);
        slice_place_t front, back;
        int32_t lo, hi;
        uint32_t got, want;
        random_placement(&front, &back, &lo, &hi);
        CHECK_MSG(merge_is_union(pairs_f, nf, same_row ? pairs_f : pairs_b, nb, &front, &back, lo, hi, &got, &want),
                  "trial %d: %u runs, brute force %u (cu %d and %d, clip %d..%d)", trial, got, want, front.cu,
                  back.cu, lo, hi);
    }
}

/* Both slices on one cell row (the common case: a small vertical shear): the merge of the row with itself at the
 * two columns is the union. */
static void one_row_is_the_union(void)
{
    random_unions(1);
}

/* Two different cell rows (the general case): the merge is the union. */
static void two_rows_are_the_union(void)
{
    random_unions(0);
}

/* The joins by hand: a row's runs a cell apart, at columns a pixel apart, join; at the same columns they do not; an
 * empty row; a clip that leaves nothing, and one that cuts a run. */
static void by_hand(void)
{
    const uint16_t gap1[] = {0, 2, 1, 3}; /* cells 0-1 and 3-5 */
    slice_place_t a, b;
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    a.cu = 10, b.cu = 11;
    vfi_span_t s[4];
    run_merge_t m;
    vfi_merge_init(&m, 16, gap1, gap1 + 4, &a, gap1, gap1 + 4, &b); /* 10-11 | 13-15 and 11-12 | 14-16 */
    CHECK_EQ(vfi_merge_runs(&m, 0, 100, s), 1u);
    CHECK(s[0].a == 10 && s[0].b == 17);
    vfi_merge_init(&m, 16, gap1, gap1 + 4, &a, gap1, gap1 + 4, &a);
    CHECK_EQ(vfi_merge_runs(&m, 0, 100, s), 2u);
    CHECK(s[0].a == 10 && s[0].b == 12 && s[1].a == 13 && s[1].b == 16);
    vfi_merge_init(&m, 16, gap1, gap1, &a, gap1, gap1, &b);
    CHECK_EQ(vfi_merge_runs(&m, 0, 100, s), 0u);
    vfi_merge_init(&m, 16, gap1, gap1 + 4, &a, gap1, gap1 + 4, &b);
    CHECK_EQ(vfi_merge_runs(&m, 20, 100, s), 0u);
    vfi_merge_init(&m, 16, gap1, gap1 + 4, &a, gap1, gap1 + 4, &b);
    CHECK_EQ(vfi_merge_runs(&m, 12, 14, s), 1u);
    CHECK(s[0].a == 12 && s[0].b == 15);
}

CHECK_CASES(CHECK_CASE(one_row_is_the_union), CHECK_CASE(two_rows_are_the_union), CHECK_CASE(by_hand));
CHECK_RUN("core/merge")
