/* SPDX-License-Identifier: MIT */
/*
 * test_arena.c: the caller-owned arena (core/arena.c): alignment, exact fit, running out without moving the
 * cursor, rewind, the high-water mark, fault injection, misaligned and NULL buffers, and the block size query.
 */
#include <stdint.h>
#include <string.h>

#include "arena.h"
#include "check.h"
#include "volfix_internal.h"

/* 16-byte aligned backing store with room to misalign it on purpose */
static _Alignas(64) unsigned char store[4096 + 64];

static void alignment(void)
{
    vf_arena_t a;
    vf_arena_init(&a, store, 1024);
    CHECK(a.base == store);
    CHECK_EQ(a.size, 1024);
    CHECK_EQ(a.used, 0);
    CHECK_EQ(a.peak, 0);
    CHECK_EQ(a.allocs, 0);
    CHECK_EQ(a.reserved, 0); /* no fault injected */
    const size_t sizes[] = {1, 3, 16, 17, 31, 32, 33, 5, 100};
    size_t expect_used = 0;
    for (size_t n = 0; n < sizeof sizes / sizeof sizes[0]; n++) {
        unsigned char *p = vfi_arena_alloc(&a, sizes[n]);
        CHECK(p != NULL);
        CHECK_EQ((uintptr_t)p % VFI_ALIGN, 0);
        CHECK(p == store + expect_used); /* blocks are consecutive: only padding between them */
        memset(p, 0xA5, sizes[n]);       /* writable (ASan would catch an overrun) */
        expect_used += (sizes[n] + 15) / 16 * 16;
        CHECK_EQ(a.used, expect_used);
        CHECK_EQ(a.allocs, n + 1);
    }
    CHECK_EQ(a.peak, a.used);
}

static void block_size(void)
{
    CHECK_EQ(vfi_arena_block(0), 0);
    CHECK_EQ(vfi_arena_block(1), 16);
    CHECK_EQ(vfi_arena_block(15), 16);
    CHECK_EQ(vfi_arena_block(16), 16);
    CHECK_EQ(vfi_arena_block(17), 32);
    CHECK_EQ(vfi_arena_block(1000), 1008);
    /* the query matches what an allocation takes */
    for (size_t bytes = 0; bytes < 200; bytes++) {
        vf_arena_t a;
        vf_arena_init(&a, store, 1024);
        CHECK(vfi_arena_alloc(&a, bytes) != NULL);
        CHECK_EQ(a.used, vfi_arena_block(bytes));
    }
}

static void exact_fit(void)
{
    vf_arena_t a;
    vf_arena_init(&a, store, 64);
    CHECK(vfi_arena_alloc(&a, 48) != NULL);
    CHECK(vfi_arena_alloc(&a, 16) != NULL); /* exactly the rest */
    CHECK_EQ(a.used, 64);
    CHECK(vfi_arena_alloc(&a, 1) == NULL);
    CHECK_EQ(a.used, 64);
    /* a zero-byte block at the very end does not move the cursor past the buffer */
    unsigned char *z = vfi_arena_alloc(&a, 0);
    CHECK(a.used <= a.size);
    (void)z;
    /* a size that is not a multiple of 16 fits when its padded block fits */
    vf_arena_init(&a, store, 48);
    CHECK(vfi_arena_alloc(&a, 33) != NULL);
    CHECK_EQ(a.used, 48);
    vf_arena_init(&a, store, 47);
    CHECK(vfi_arena_alloc(&a, 33) == NULL); /* the padded block (48) does not fit in 47 */
    CHECK_EQ(a.used, 0);
}

static void out_of_space_keeps_cursor(void)
{
    vf_arena_t a;
    vf_arena_init(&a, store, 100);
    CHECK(vfi_arena_alloc(&a, 40) != NULL);
    size_t used = a.used, peak = a.peak;
    uint32_t allocs = a.allocs;
    CHECK(vfi_arena_alloc(&a, 100) == NULL);
    CHECK(vfi_arena_alloc(&a, SIZE_MAX) == NULL);
    CHECK(vfi_arena_alloc(&a, SIZE_MAX - 15) == NULL);
    CHECK(vfi_arena_alloc(&a, SIZE_MAX - 16) == NULL);
    CHECK(vfi_arena_alloc(&a, (size_t)1 << (sizeof(size_t) * 8 - 1)) == NULL);
    CHECK_EQ(a.used, used);
    CHECK_EQ(a.peak, peak);
    CHECK_EQ(a.allocs, allocs);
    /* what still fits is still handed out */
    CHECK(vfi_arena_alloc(&a, 48) != NULL);
    CHECK_EQ(a.used, 96);
}

static void rewind_and_peak(void)
{
    vf_arena_t a;
    vf_arena_init(&a, store, 1024);
    void *first = vfi_arena_alloc(&a, 100);
    size_t mark = a.used;
    void *second = vfi_arena_alloc(&a, 300);
    CHECK(first && second);
    size_t high = a.used;
    vfi_arena_rewind(&a, mark);
    CHECK_EQ(a.used, mark);
    CHECK_EQ(a.peak, high); /* the high-water mark survives a rewind */
    void *again = vfi_arena_alloc(&a, 10);
    CHECK(again == second); /* the space is handed out again */
    CHECK_EQ(a.peak, high);
    /* a mark beyond the cursor does not move it forward */
    vfi_arena_rewind(&a, 1000);
    CHECK_EQ(a.used, mark + 16);
    vfi_arena_rewind(&a, 0);
    CHECK_EQ(a.used, 0);
    CHECK(vfi_arena_alloc(&a, 1024) == store);
    CHECK_EQ(a.peak, 1024);
}

static void fault_injection(void)
{
    /* allocation number fail_after + 1 (and every later one) fails; 0 never fails */
    for (uint32_t fail = 1; fail <= 5; fail++) {
        vf_arena_t a;
        vf_arena_init(&a, store, 1024);
        vfi_arena_fail_after(&a, fail);
        for (uint32_t n = 1; n <= 8; n++) {
            void *p = vfi_arena_alloc(&a, 8);
            if (n <= fail)
                CHECK_MSG(p != NULL, "fail_after %u: allocation %u failed", fail, n);
            else
                CHECK_MSG(p == NULL, "fail_after %u: allocation %u succeeded", fail, n);
        }
        CHECK_EQ(a.allocs, fail);
        CHECK_EQ(a.used, 16 * fail);
    }
    vf_arena_t a;
    vf_arena_init(&a, store, 1024); /* a fresh arena injects no fault */
    for (int n = 0; n < 64; n++)
        CHECK(vfi_arena_alloc(&a, 16) != NULL);
    /* setting fail_after on a used arena counts the allocations already made */
    vf_arena_init(&a, store, 1024);
    CHECK(vfi_arena_alloc(&a, 1) && vfi_arena_alloc(&a, 1));
    vfi_arena_fail_after(&a, 2);
    CHECK(vfi_arena_alloc(&a, 1) == NULL);
}

static void misaligned_buffer(void)
{
    for (size_t off = 0; off < 16; off++) {
        vf_arena_t a;
        vf_arena_init(&a, store + off, 256);
        unsigned char *p = vfi_arena_alloc(&a, 1);
        CHECK(p != NULL);
        CHECK_EQ((uintptr_t)p % VFI_ALIGN, 0);
        CHECK(p >= store + off && p < store + off + 16);
        /* what fits depends on block sizes, not on the address: 256 - padding bytes are left */
        size_t pad = (16 - off % 16) % 16;
        CHECK_EQ(a.used, pad + 16);
        size_t rest = 256 - a.used;
        CHECK(vfi_arena_alloc(&a, rest / 16 * 16) != NULL);
        CHECK(vfi_arena_alloc(&a, 1) == NULL || rest % 16 >= 1);
        CHECK(a.used <= a.size);
        CHECK((unsigned char *)a.base + a.used <= store + off + 256);
    }
    /* a misaligned buffer smaller than the padding: nothing fits, nothing breaks */
    vf_arena_t a;
    vf_arena_init(&a, store + 1, 5);
    CHECK(a.used <= a.size);
    CHECK(vfi_arena_alloc(&a, 1) == NULL);
    CHECK(vfi_arena_alloc(&a, 0) == NULL || a.used <= a.size);
    vf_arena_init(&a, store + 1, 15); /* exactly the padding */
    CHECK_EQ(a.used, 15);
    CHECK(vfi_arena_alloc(&a, 1) == NULL);
    vf_arena_init(&a, store + 1, 31); /* padding + one block */
    CHECK(vfi_arena_alloc(&a, 16) == store + 16);
    CHECK(vfi_arena_alloc(&a, 1) == NULL);
}

static void null_buffer(void)
{
    vf_arena_t a;
    vf_arena_init(&a, NULL, 1000);
    CHECK_EQ(a.size, 0); /* a NULL buffer has no room, whatever size is claimed */
    CHECK(vfi_arena_alloc(&a, 1) == NULL);
    CHECK(vfi_arena_alloc(&a, 0) == NULL);
    CHECK_EQ(a.used, 0);
    CHECK_EQ(a.allocs, 0);
    vf_arena_init(NULL, store, 10); /* does nothing, does not crash */
    vf_arena_init(&a, store, 0);
    CHECK(vfi_arena_alloc(&a, 1) == NULL);
}

CHECK_CASES(CHECK_CASE(alignment), CHECK_CASE(block_size), CHECK_CASE(exact_fit), CHECK_CASE(out_of_space_keeps_cursor),
            CHECK_CASE(rewind_and_peak), CHECK_CASE(fault_injection), CHECK_CASE(misaligned_buffer),
            CHECK_CASE(null_buffer));
CHECK_RUN("core/arena")
