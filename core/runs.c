/* runs.c: run-length encode the visible cells of one standard-order copy (see runs.h). */
#include "arena.h"
#include "runs.h"

static uint8_t min4(uint8_t a, uint8_t b, uint8_t c, uint8_t d);
static uint8_t max4(uint8_t a, uint8_t b, uint8_t c, uint8_t d);

size_t vfi_runs_index_bytes(const vfi_layout_t *l)
{
    return vfi_arena_block(sizeof(uint32_t) * ((size_t)(l->nk - 1) * l->nj + 1));
}

size_t vfi_runs_encode(const uint8_t *copy, const vfi_layout_t *l, const vfi_classify_t *cls, vfi_runs_t *runs)
{
    const bool fill = runs->pairs != NULL;
    size_t used = 0;
    runs->nj = l->nj;
    for (uint32_t k = 0; k + 1 < l->nk; k++)
        for (uint32_t j = 0; j < l->nj; j++) {
            if (fill)
                runs->row_start[k * l->nj + j] = (uint32_t)used;
            /* the four rows (j, j+1) x (k, k+1) of the cell row; column ranges are combined pairwise */
            const uint8_t *r00 = copy + (size_t)k * l->slice + (size_t)j * l->row;
            const uint8_t *r01 = r00 + l->row, *r10 = r00 + l->slice, *r11 = r10 + l->row;
            uint8_t lo_prev = min4(r00[0], r01[0], r10[0], r11[0]);
            uint8_t hi_prev = max4(r00[0], r01[0], r10[0], r11[0]);
            uint32_t skip = 0, length = 0;
            for (uint32_t i = 0; i < l->ni; i++) {
                uint8_t lo = min4(r00[i + 1], r01[i + 1], r10[i + 1], r11[i + 1]);
                uint8_t hi = max4(r00[i + 1], r01[i + 1], r10[i + 1], r11[i + 1]);
                bool visible = vfi_range_visible(cls, lo < lo_prev ? lo : lo_prev, hi > hi_prev ? hi : hi_prev);
                lo_prev = lo;
                hi_prev = hi;
                if (visible) {
                    length++;
                } else if (length) { /* a run ends: emit it, start counting invisible cells again */
                    if (fill) {
                        runs->pairs[used] = (uint16_t)skip;
                        runs->pairs[used + 1] = (uint16_t)length;
                    }
                    used += 2;
                    skip = 1;
                    length = 0;
                } else {
                    skip++;
                }
            }
            if (length) {
                if (fill) {
                    runs->pairs[used] = (uint16_t)skip;
                    runs->pairs[used + 1] = (uint16_t)length;
                }
                used += 2;
            }
        }
    if (fill)
        runs->row_start[(l->nk - 1) * l->nj] = (uint32_t)used;
    return used;
}

static uint8_t min4(uint8_t a, uint8_t b, uint8_t c, uint8_t d)
{
    uint8_t x = a < b ? a : b, y = c < d ? c : d;
    return x < y ? x : y;
}

static uint8_t max4(uint8_t a, uint8_t b, uint8_t c, uint8_t d)
{
    uint8_t x = a > b ? a : b, y = c > d ? c : d;
    return x > y ? x : y;
}
