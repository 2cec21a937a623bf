/* SPDX-License-Identifier: MIT */
/* arena.h: internal allocation from the caller's arena (vf_arena_t in volfix.h). */
#ifndef VF_ARENA_H
#define VF_ARENA_H

#include "volfix.h"

#define VFI_ALIGN 16 /* every block starts on 16 bytes: enough for any type here, and for cache-friendly rows */

/* A block of `bytes` aligned to VFI_ALIGN, or NULL when the arena is short (or fault injection says so). */
void *vfi_arena_alloc(vf_arena_t *arena, size_t bytes);

/* Bytes an allocation of `bytes` takes, padding included, so that size queries match what allocation uses. */
size_t vfi_arena_block(size_t bytes);

/* Set bytes to zero. (A struct assignment from {0} would let the compiler call memset, which a freestanding
 * core does not have.) */
void vfi_zero(void *p, size_t bytes);

/* The free space at the arena's end, without taking it: for output whose size is known only once written (the
 * run lists). A vfi_arena_alloc that follows returns this same pointer. *bytes: how much is free. */
void *vfi_arena_top(vf_arena_t *arena, size_t *bytes);

/* Give back everything allocated after `mark` (a value of arena->used taken earlier). */
void vfi_arena_rewind(vf_arena_t *arena, size_t mark);

#endif
