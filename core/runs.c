/* SPDX-License-Identifier: MIT */
/* runs.c: run-length encode the visible cells of one standard-order copy (see runs.h). */
#include "arena.h"
#include "runs.h"

/* Cells a row is read in at a time: the column ranges of a chunk are found first, in a loop the compiler can
 * vectorise, then the cells are classified and counted into runs. */
#define CHUNK 64

static inline uint8_t min2(uint8_t a, uint8_t b)
{
    return a < b ? a : b;
}

static inline uint8_t max2(uint8_t a, uint8_t b)
{
    return a > b ? a : b;
}

/* Each column's range over four rows. Inlined with a constant n the loop has a fixed count, which compilers
 * vectorise even at -O2 (GCC's cheap cost model); the rows are read once each. */
static inline void column_ranges(const uint8_t *a, const uint8_t *b, const uint8_t *c, const uint8_t *d, uint32_t n,
                                 uint8_t *lo, uint8_t *hi)
{
    for (uint32_t i = 0; i < n; i++) {
        lo[i] = min2(min2(a[i], b[i]), min2(c[i], d[i]));
        hi[i] = max2(max2(a[i], b[i]), max2(c[i], d[i]));
    }
}

size_t vfi_runs_index_bytes(const vfi_layout_t *l)
{
    return vfi_arena_block(sizeof(uint32_t) * ((size_t)(l->nk - 1) * l->nj + 1));
}

/* Emit a (skip, length) pair if there is room; count it either way. */
static inline void emit(uint16_t *pairs, size_t capacity, size_t *used, uint32_t skip, uint32_t length)
{
    if (*used + 2 <= capacity) {
        pairs[*used] = (uint16_t)skip;
        pairs[*used + 1] = (uint16_t)length;
    }
    *used += 2;
}

size_t vfi_runs_encode(const uint8_t *copy, const vfi_layout_t *l, const vfi_classify_t *cls, uint32_t *row_start,
                       uint16_t *pairs, size_t capacity)
{
    const bool index = row_start != NULL;
    const uint16_t *visible_from = cls->visible_from;
    if (!pairs)
        capacity = 0;
    size_t used = 0;
    for (uint32_t k = 0; k + 1 < l->nk; k++)
        for (uint32_t j = 0; j < l->nj; j++) {
            if (index)
                row_start[k * l->nj + j] = (uint32_t)used;
            /* the four rows (j, j+1) x (k, k+1) of the cell row */
            const uint8_t *r00 = copy + (size_t)k * l->slice + (size_t)j * l->row;
            const uint8_t *r01 = r00 + l->row, *r10 = r00 + l->slice, *r11 = r10 + l->row;
            uint32_t skip = 0, length = 0;
            for (uint32_t i0 = 0; i0 < l->ni; i0 += CHUNK) {
                const uint32_t n = l->ni - i0 < CHUNK ? l->ni - i0 : CHUNK;
                /* Column c's range over the four rows; cell c spans columns c and c + 1 (column n_i is the
                 * copy's padding, so it exists). */
                uint8_t lo[CHUNK + 1], hi[CHUNK + 1];
                if (n == CHUNK)
                    column_ranges(r00 + i0, r01 + i0, r10 + i0, r11 + i0, CHUNK, lo, hi); /* a fixed count */
                else
                    column_ranges(r00 + i0, r01 + i0, r10 + i0, r11 + i0, n, lo, hi);
                lo[n] = min2(min2(r00[i0 + n], r01[i0 + n]), min2(r10[i0 + n], r11[i0 + n]));
                hi[n] = max2(max2(r00[i0 + n], r01[i0 + n]), max2(r10[i0 + n], r11[i0 + n]));
                for (uint32_t c = 0; c < n; c++) {
                    if (max2(hi[c], hi[c + 1]) >= visible_from[min2(lo[c], lo[c + 1])]) {
                        length++;
                    } else if (length) { /* a run ends: emit it, start counting invisible cells again */
                        emit(pairs, capacity, &used, skip, length);
                        skip = 1;
                        length = 0;
                    } else {
                        skip++;
                    }
                }
            }
            if (length)
                emit(pairs, capacity, &used, skip, length);
        }
    if (index)
        row_start[(l->nk - 1) * l->nj] = (uint32_t)used;
    return used;
}

bool vfi_runs_valid(const uint32_t *row_start, size_t row_count, const uint16_t *pairs, size_t pair_count,
                    const vfi_layout_t *l)
{
    if (row_count != (size_t)(l->nk - 1) * l->nj + 1 || row_start[0] != 0 || row_start[row_count - 1] != pair_count)
        return false;
    for (size_t r = 0; r + 1 < row_count; r++) {
        const uint32_t begin = row_start[r], end = row_start[r + 1];
        if (end < begin || (end - begin) % 2)
            return false;
        uint32_t cells = 0;
        for (uint32_t at = begin; at < end; at += 2) {
            cells += (uint32_t)pairs[at] + pairs[at + 1];
            if (cells > l->ni)
                return false;
        }
    }
    return true;
}
