/* SPDX-License-Identifier: MIT */
/*
 * arena.c: the core's only memory source. The caller owns the buffer; the core moves a cursor through it and
 * can rewind to a mark (the renderer rebuilds its transfer-function-dependent part that way). Nothing is ever
 * freed singly, so there is nothing to leak.
 */
#include "arena.h"
#include "volfix_internal.h"

void vf_arena_init(vf_arena_t *arena, void *buffer, size_t size)
{
    if (!arena)
        return;
    arena->base = buffer;
    arena->size = buffer ? size : 0;
    arena->used = 0;
    arena->peak = 0;
    arena->allocs = 0;
    arena->reserved = 0; /* no fault injected */
    /* Align the start so that block sizes, not the buffer's address, decide how much fits. */
    size_t misalign = (size_t)((uintptr_t)buffer % VFI_ALIGN);
    if (misalign)
        arena->used = arena->size < VFI_ALIGN - misalign ? arena->size : VFI_ALIGN - misalign;
}

size_t vfi_arena_block(size_t bytes)
{
    return (bytes + VFI_ALIGN - 1) / VFI_ALIGN * VFI_ALIGN;
}

void *vfi_arena_alloc(vf_arena_t *arena, size_t bytes)
{
    if (bytes > SIZE_MAX - VFI_ALIGN)
        return NULL;
    size_t block = vfi_arena_block(bytes);
    if (arena->reserved && arena->allocs >= arena->reserved)
        return NULL; /* vfi_arena_fail_after */
    if (!arena->base || block > arena->size - arena->used)
        return NULL;
    void *p = arena->base + arena->used;
    arena->used += block;
    arena->allocs++;
    if (arena->used > arena->peak)
        arena->peak = arena->used;
    return p;
}

void *vfi_arena_top(vf_arena_t *arena, size_t *bytes)
{
    /* used is always a multiple of VFI_ALIGN from an aligned start, so the top is where the next block goes */
    *bytes = arena->base ? arena->size - arena->used : 0;
    return arena->base ? arena->base + arena->used : NULL;
}

void vfi_arena_rewind(vf_arena_t *arena, size_t mark)
{
    if (mark < arena->used)
        arena->used = mark;
}

void vfi_zero(void *p, size_t bytes)
{
    unsigned char *b = p;
    for (size_t i = 0; i < bytes; i++)
        b[i] = 0;
}

void vfi_arena_fail_after(vf_arena_t *arena, uint32_t count)
{
    if (arena)
        arena->reserved = count;
}
