/* SPDX-License-Identifier: MIT */
/*
 * runs_parts.c: a transfer function's run lists encoded in parts that threads run side by side, joined into the
 * lists vf_renderer_set_tf makes, to the byte (volfix.h, vf_renderer_set_tf_begin).
 *
 * The arena after the mark is laid out as the whole encoding leaves it: the three indices, then each axis's pairs
 * in a block. Begin allocates the indices and cuts the free space above them into one region a part, in part
 * order, and keeps each part's count of values at the free space's end. Part q (axis q / ranges, its
 * (q % ranges)-th range of slabs) writes its rows' index entries in place, counted from its own first value, and
 * its pairs into its region. The join then walks the parts in order, adds
 * to each part's entries the values before it on its axis and moves its pairs down to follow them. Moving down is
 * safe: the values before a part take no more room than the regions before it (each region is a multiple of the
 * arena's alignment and at least as long as its part's pairs), so a part's destination never passes its source,
 * nor its end the next part's region.
 *
 * A part whose pairs did not fit its region leaves the join to the whole encoding on the calling thread, which is
 * then what vf_renderer_set_tf would have done from the start (VF_ERR_NOMEM and the size it needs included).
 */
#include "arena.h"
#include "renderer.h"

#if VF_MAX_ENCODE_PARTS >= 6

/* A part's values before it has run: more than any region holds. */
#define NOT_RUN SIZE_MAX

/* Slabs [*k0, *k1) of part q's axis: the axis's slabs in `ranges` ranges, the first ones one shorter. */
static int part_slabs(const vf_renderer_t *r, uint32_t q, uint32_t *k0, uint32_t *k1)
{
    const int a = (int)(q / r->encode_ranges);
    const uint32_t s = q % r->encode_ranges, slabs = r->layout[a].nk - 1;
    *k0 = (uint32_t)((uint64_t)slabs * s / r->encode_ranges);
    *k1 = (uint32_t)((uint64_t)slabs * (s + 1) / r->encode_ranges);
    return a;
}

static uint16_t *region(const vf_renderer_t *r, uint32_t q)
{
    return r->part_pairs + (size_t)q * r->part_capacity;
}

vf_status_t vfi_encode_parts_begin(vf_renderer_t *r, uint32_t ranges)
{
    vf_arena_t *arena = r->arena;
    r->have_runs = false;
    r->encode_parts = 0;
    vfi_arena_rewind(arena, r->runs_mark);
    size_t index_bytes, free_bytes;
    if (!vfi_runs_indices(arena, r->layout, r->part_index, &index_bytes))
        return vfi_encode_runs(r); /* short of memory: the whole encoding counts what would do */
    const uint32_t parts = 3 * ranges;
    unsigned char *top = vfi_arena_top(arena, &free_bytes);
    /* each part's count at the free space's end, where the join moves nothing; the regions below it */
    const size_t count_bytes = vfi_arena_block(sizeof(size_t) * parts);
    const size_t below = free_bytes > count_bytes ? (free_bytes - count_bytes) / VFI_ALIGN * VFI_ALIGN : 0;
    const size_t region_bytes = below / parts / VFI_ALIGN * VFI_ALIGN;
    if (!top || !region_bytes)
        return vfi_encode_runs(r);
    r->part_pairs = (uint16_t *)top;
    r->part_capacity = region_bytes / sizeof(uint16_t);
    r->part_values = (size_t *)(top + below);
    for (uint32_t q = 0; q < parts; q++)
        r->part_values[q] = NOT_RUN;
    r->encode_ranges = ranges;
    r->encode_parts = parts;
    return VF_OK;
}

#endif

uint32_t vf_renderer_encode_parts(const vf_renderer_t *r)
{
#if VF_MAX_ENCODE_PARTS >= 6
    return r ? r->encode_parts : 0;
#else
    (void)r;
    return 0;
#endif
}

vf_status_t vf_renderer_encode_part(vf_renderer_t *r, uint32_t part)
{
    if (!r)
        return VF_ERR_NULL;
#if VF_MAX_ENCODE_PARTS >= 6
    if (part >= r->encode_parts)
        return VF_ERR_ARG;
    if (r->part_values[part] != NOT_RUN)
        return VF_OK; /* this part has run */
    uint32_t k0, k1;
    const int a = part_slabs(r, part, &k0, &k1);
    r->part_values[part] = vfi_runs_encode_slabs(r->slices[a], &r->layout[a], &r->cls, &r->bricks, k0, k1,
                                                 r->part_index[a], region(r, part), r->part_capacity);
    return VF_OK;
#else
    (void)part;
    return VF_ERR_ARG;
#endif
}

vf_status_t vf_renderer_set_tf_end(vf_renderer_t *r)
{
    if (!r)
        return VF_ERR_NULL;
#if VF_MAX_ENCODE_PARTS >= 6
    const uint32_t parts = r->encode_parts;
    if (!parts)
        return VF_OK; /* begin encoded the whole, or had nothing to encode */
    for (uint32_t q = 0; q < parts; q++) {
        vf_renderer_encode_part(r, q); /* a part the caller left out runs here */
        if (r->part_values[q] > r->part_capacity)
            return vfi_encode_runs(r); /* it did not fit its region: the whole encoding, as set_tf's */
    }
    r->encode_parts = 0;
    vf_arena_t *arena = r->arena;
    size_t total = 0;
    for (int a = 0; a < 3; a++)
        total += vfi_runs_index_bytes(&r->layout[a]);
    for (int a = 0; a < 3; a++) {
        const vfi_layout_t *l = &r->layout[a];
        uint32_t *index = r->part_index[a];
        size_t free_bytes, at = 0; /* values of the axis so far */
        uint16_t *pairs = vfi_arena_top(arena, &free_bytes);
        for (uint32_t q = (uint32_t)a * r->encode_ranges; q < (uint32_t)(a + 1) * r->encode_ranges; q++) {
            uint32_t k0, k1;
            part_slabs(r, q, &k0, &k1);
            for (uint32_t row = k0 * l->nj; row < k1 * l->nj; row++)
                index[row] += (uint32_t)at;
            const uint16_t *from = region(r, q);
            uint16_t *to = pairs + at;
            if (to != from)
                for (size_t v = 0; v < r->part_values[q]; v++) /* upwards: to is below from */
                    to[v] = from[v];
            at += r->part_values[q];
        }
        index[(l->nk - 1) * l->nj] = (uint32_t)at;
        const size_t pair_bytes = vfi_arena_block(sizeof(uint16_t) * (at ? at : 1));
        if (!vfi_arena_alloc(arena, pair_bytes))
            return vfi_encode_runs(r); /* an injected fault: the whole encoding reports it as set_tf's would */
        r->runs[a].row_start = index;
        r->runs[a].pairs = pairs;
        r->runs[a].nj = l->nj;
        total += pair_bytes;
    }
    r->needed = r->runs_mark + total + VFI_ALIGN;
    r->memory.runs = total;
    r->have_runs = true;
    return VF_OK;
#else
    return VF_OK;
#endif
}
