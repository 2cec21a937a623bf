/* SPDX-License-Identifier: MIT */
/* runs.c: run-length encode the visible cells of one standard-order copy, brick by brick (see runs.h). */
#include "arena.h"
#include "runs.h"

/* Cells a row is read in at a time: the column ranges of a chunk are found first, in a loop the compiler can
 * vectorise, then the cells are classified and counted into runs. */
#define CHUNK 64

/* What a transfer function makes of a brick. */
enum { BRICK_EMPTY, BRICK_SOLID, BRICK_MIXED };

/* The encoder's state along a row, and its output. */
typedef struct encoder {
    uint16_t *pairs;
    size_t capacity, used;
    uint32_t skip, length; /* invisible cells before the open run, and its visible ones */
} encoder_t;

static inline uint8_t min2(uint8_t a, uint8_t b)
{
    return a < b ? a : b;
}

static inline uint8_t max2(uint8_t a, uint8_t b)
{
    return a > b ? a : b;
}

static inline uint32_t min_u32(uint32_t a, uint32_t b)
{
    return a < b ? a : b;
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

size_t vfi_bricks_bytes(const uint32_t dims[3])
{
    if (!VF_RUN_BRICKS)
        return 0;
    size_t n = 1;
    for (int a = 0; a < 3; a++)
        n *= (dims[a] + VFI_BRICK - 1) / VFI_BRICK;
    return vfi_arena_block(2 * n);
}

void vfi_bricks_init(vfi_bricks_t *b, const uint32_t dims[3], uint8_t *range)
{
    b->range = range;
    for (int a = 0; a < 3; a++)
        b->n[a] = (dims[a] + VFI_BRICK - 1) / VFI_BRICK;
}

/* Fold a row into each column's running range (n a constant where it matters, as in column_ranges). */
static inline void fold_row(const uint8_t *row, uint32_t n, uint8_t *lo, uint8_t *hi)
{
    for (uint32_t i = 0; i < n; i++) {
        lo[i] = min2(lo[i], row[i]);
        hi[i] = max2(hi[i], row[i]);
    }
}

void vfi_bricks_build(vfi_bricks_t *b, const uint8_t *z, const uint32_t dims[3])
{
    if (!VF_RUN_BRICKS || !b->range)
        return;
    vfi_layout_t l;
    vfi_layout(dims, 2, &l); /* i = x, j = y, k = z */
    uint8_t *out = b->range;
    for (uint32_t bz = 0; bz < b->n[2]; bz++)
        for (uint32_t by = 0; by < b->n[1]; by++, out += 2 * b->n[0]) {
            /* The voxels the brick's cells read: one past its last cell, where the copy's padding row and column
             * (repeating the last ones) stand in at the end; the copy has no padding slice. */
            const uint32_t z0 = bz * VFI_BRICK, z1 = min_u32(z0 + VFI_BRICK, l.nk - 1);
            const uint32_t y0 = by * VFI_BRICK, y1 = min_u32(y0 + VFI_BRICK, l.nj);
            for (uint32_t x0 = 0; x0 < l.ni; x0 += CHUNK) {
                /* columns x0 .. x0 + n, over every row of the brick row, then each brick's share of them */
                const uint32_t n = l.ni - x0 < CHUNK ? l.ni - x0 : CHUNK;
                uint8_t lo[CHUNK + 1], hi[CHUNK + 1];
                for (uint32_t c = 0; c <= n; c++) {
                    lo[c] = 255;
                    hi[c] = 0;
                }
                for (uint32_t zz = z0; zz <= z1; zz++)
                    for (uint32_t yy = y0; yy <= y1; yy++) {
                        const uint8_t *row = z + (size_t)zz * l.slice + (size_t)yy * l.row + x0;
                        if (n == CHUNK)
                            fold_row(row, CHUNK, lo, hi); /* a fixed count */
                        else
                            fold_row(row, n, lo, hi);
                        lo[n] = min2(lo[n], row[n]);
                        hi[n] = max2(hi[n], row[n]);
                    }
                for (uint32_t c0 = 0; c0 < n; c0 += VFI_BRICK) {
                    const uint32_t c1 = min_u32(c0 + VFI_BRICK, n);
                    uint8_t blo = lo[c0], bhi = hi[c0];
                    for (uint32_t c = c0 + 1; c <= c1; c++) {
                        blo = min2(blo, lo[c]);
                        bhi = max2(bhi, hi[c]);
                    }
                    const uint32_t bx = (x0 + c0) / VFI_BRICK;
                    out[2 * bx] = blo;
                    out[2 * bx + 1] = bhi;
                }
            }
        }
}

/* Emit a (skip, length) pair if there is room; count it either way. */
static inline void emit(encoder_t *e, uint32_t skip, uint32_t length)
{
    if (e->used + 2 <= e->capacity) {
        e->pairs[e->used] = (uint16_t)skip;
        e->pairs[e->used + 1] = (uint16_t)length;
    }
    e->used += 2;
}

/* n invisible cells: a run that was open ends. */
static inline void invisible(encoder_t *e, uint32_t n)
{
    if (e->length) {
        emit(e, e->skip, e->length);
        e->skip = n;
        e->length = 0;
    } else {
        e->skip += n;
    }
}

/* Each cell's range: the ranges of its two columns joined (n a constant where it matters, as in column_ranges). */
static inline void cell_ranges(const uint8_t *lo, const uint8_t *hi, uint32_t n, uint8_t *cell_lo, uint8_t *cell_hi)
{
    for (uint32_t c = 0; c < n; c++) {
        cell_lo[c] = min2(lo[c], lo[c + 1]);
        cell_hi[c] = max2(hi[c], hi[c + 1]);
    }
}

/* Cells [c0, c1) of the row whose four voxel rows (j, j+1) x (k, k+1) are r00, r01, r10, r11 (of n_i cells), read
 * one by one, a chunk at a time. A chunk's ranges are found in loops of constant count whenever its columns lie
 * in the row, also for the cells past c1 (a mixed brick's 8 cells cost what 64 do in vector loops, and far less
 * than a loop of variable count); only the cells up to c1 are then classified. */
static void read_cells(encoder_t *e, const uint8_t *r00, const uint8_t *r01, const uint8_t *r10, const uint8_t *r11,
                       uint32_t c0, uint32_t c1, uint32_t ni, const uint16_t *visible_from)
{
    uint32_t skip = e->skip, length = e->length;
    for (uint32_t i0 = c0; i0 < c1; i0 += CHUNK) {
        const uint32_t n = c1 - i0 < CHUNK ? c1 - i0 : CHUNK;
        /* Column c's range over the four rows; cell c spans columns c and c + 1 (column n_i is the copy's
         * padding, so it exists). */
        uint8_t lo[CHUNK + 1], hi[CHUNK + 1], cell_lo[CHUNK], cell_hi[CHUNK];
        if (VF_RUN_BRICKS && i0 + CHUNK <= ni) {
            column_ranges(r00 + i0, r01 + i0, r10 + i0, r11 + i0, CHUNK, lo, hi); /* a fixed count */
            lo[CHUNK] = min2(min2(r00[i0 + CHUNK], r01[i0 + CHUNK]), min2(r10[i0 + CHUNK], r11[i0 + CHUNK]));
            hi[CHUNK] = max2(max2(r00[i0 + CHUNK], r01[i0 + CHUNK]), max2(r10[i0 + CHUNK], r11[i0 + CHUNK]));
            cell_ranges(lo, hi, CHUNK, cell_lo, cell_hi);
        } else {
            column_ranges(r00 + i0, r01 + i0, r10 + i0, r11 + i0, n, lo, hi);
            lo[n] = min2(min2(r00[i0 + n], r01[i0 + n]), min2(r10[i0 + n], r11[i0 + n]));
            hi[n] = max2(max2(r00[i0 + n], r01[i0 + n]), max2(r10[i0 + n], r11[i0 + n]));
            cell_ranges(lo, hi, n, cell_lo, cell_hi);
        }
        for (uint32_t c = 0; c < n; c++) {
            if (cell_hi[c] >= visible_from[cell_lo[c]]) {
                length++;
            } else if (length) { /* a run ends: emit it, start counting invisible cells again */
                emit(e, skip, length);
                skip = 1;
                length = 0;
            } else {
                skip++;
            }
        }
    }
    e->skip = skip;
    e->length = length;
}

static inline int brick_class(const vfi_classify_t *cls, const uint8_t *range)
{
    return !vfi_range_visible(cls, range[0], range[1])  ? BRICK_EMPTY
           : vfi_range_solid(cls, range[0], range[1]) ? BRICK_SOLID
                                                       : BRICK_MIXED;
}

/* Slabs [k0, k1) (vfi_runs_encode_slabs); static, so that a build without encodings in parts has it inlined in
 * its one caller. */
static size_t encode_slabs(const uint8_t *copy, const vfi_layout_t *l, const vfi_classify_t *cls,
                           const vfi_bricks_t *bricks, uint32_t k0, uint32_t k1, uint32_t *row_start, uint16_t *pairs,
                           size_t capacity)
{
    const bool index = row_start != NULL;
    encoder_t e = {pairs, pairs ? capacity : 0, 0, 0, 0};
    /* a brick's step in the range array along each object axis */
    size_t step[3] = {0, 0, 0};
    if (!VF_RUN_BRICKS || (bricks && !bricks->range))
        bricks = NULL; /* a build without them, or none made */
    if (bricks) {
        step[0] = 2;
        step[1] = 2 * (size_t)bricks->n[0];
        step[2] = 2 * (size_t)bricks->n[0] * bricks->n[1];
    }
    const size_t step_i = step[l->i_axis];
    const int k_axis = 3 - l->i_axis - l->j_axis;
    const uint32_t bricks_i = (l->ni + VFI_BRICK - 1) / VFI_BRICK;
    for (uint32_t k = k0; k < k1; k++)
        for (uint32_t j = 0; j < l->nj; j++) {
            if (index)
                row_start[k * l->nj + j] = (uint32_t)e.used;
            /* the four rows (j, j+1) x (k, k+1) of the cell row */
            const uint8_t *r00 = copy + (size_t)k * l->slice + (size_t)j * l->row;
            const uint8_t *r01 = r00 + l->row, *r10 = r00 + l->slice, *r11 = r10 + l->row;
            e.skip = e.length = 0;
            if (!bricks) {
                read_cells(&e, r00, r01, r10, r11, 0, l->ni, l->ni, cls->visible_from);
            } else {
                const uint8_t *row_bricks =
                    bricks->range + (k / VFI_BRICK) * step[k_axis] + (j / VFI_BRICK) * step[l->j_axis];
                int kind = brick_class(cls, row_bricks);
                for (uint32_t b = 0; b < bricks_i;) {
                    if (kind == BRICK_MIXED) { /* the cells of this and the mixed bricks after it, in one read */
                        uint32_t b1 = b + 1;
                        int next = BRICK_EMPTY;
                        while (b1 < bricks_i && (next = brick_class(cls, row_bricks + b1 * step_i)) == BRICK_MIXED)
                            b1++;
                        read_cells(&e, r00, r01, r10, r11, b * VFI_BRICK, min_u32(b1 * VFI_BRICK, l->ni), l->ni,
                                   cls->visible_from);
                        b = b1;
                        kind = next;
                        continue;
                    }
                    const uint32_t n = min_u32(b * VFI_BRICK + VFI_BRICK, l->ni) - b * VFI_BRICK;
                    if (kind == BRICK_EMPTY)
                        invisible(&e, n);
                    else
                        e.length += n;
                    if (++b < bricks_i)
                        kind = brick_class(cls, row_bricks + b * step_i);
                }
            }
            if (e.length)
                emit(&e, e.skip, e.length);
        }
    return e.used;
}

#if VF_MAX_ENCODE_PARTS >= 6
size_t vfi_runs_encode_slabs(const uint8_t *copy, const vfi_layout_t *l, const vfi_classify_t *cls,
                             const vfi_bricks_t *bricks, uint32_t k0, uint32_t k1, uint32_t *row_start,
                             uint16_t *pairs, size_t capacity)
{
    return encode_slabs(copy, l, cls, bricks, k0, k1, row_start, pairs, capacity);
}
#endif

size_t vfi_runs_encode(const uint8_t *copy, const vfi_layout_t *l, const vfi_classify_t *cls,
                       const vfi_bricks_t *bricks, uint32_t *row_start, uint16_t *pairs, size_t capacity)
{
    const size_t used = encode_slabs(copy, l, cls, bricks, 0, l->nk - 1, row_start, pairs, capacity);
    if (row_start)
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
