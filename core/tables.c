/*
 * tables.c: point and pre-integrated tables (docs/algorithm.md, section 2), integer only.
 *
 * Accumulation is Q.30 (1.0 = 2^30) so that compositing hundreds of intervals loses nothing visible; the
 * entries are rounded to Q1.15 once, at the end.
 */
#include "arena.h"
#include "fixmath.h"
#include "tables.h"

#define ONE_Q30 (UINT64_C(1) << 30)

typedef struct accum {
    uint64_t a, r, g, b; /* Q.30 */
} accum_t;

static void point_entry(const vfi_classify_t *cls, uint32_t i, uint32_t slab_q16, uint16_t *out);
static void intervals_for_length(const vfi_classify_t *cls, uint64_t length_q28, uint32_t *out);
static void composite_interval(accum_t *acc, const uint32_t *interval);
static void store_entry(const accum_t *acc, uint16_t *out);
static uint32_t opacity_q30(uint64_t tau_length_q28);

size_t vfi_table_scratch_bytes(uint32_t n)
{
    return vfi_arena_block(sizeof(uint32_t) * (n - 1) * 4);
}

vf_status_t vfi_table_scratch_alloc(vfi_table_scratch_t *scratch, uint32_t n, vf_arena_t *arena)
{
    scratch->interval_q30 = vfi_arena_alloc(arena, sizeof(uint32_t) * (n - 1) * 4);
    return scratch->interval_q30 ? VF_OK : VF_ERR_NOMEM;
}

void vfi_point_table(const vfi_classify_t *cls, uint32_t slab_q16, uint16_t *out)
{
    for (uint32_t i = 0; i < cls->n; i++)
        point_entry(cls, i, slab_q16, out + i * 4);
}

void vfi_preint_table_bruteforce(const vfi_classify_t *cls, uint32_t slab_q16, vfi_table_scratch_t *scratch,
                                 uint16_t *out)
{
    const uint32_t n = cls->n;
    uint32_t *iv = scratch->interval_q30;

    /* The diagonal (constant scalar across the slab) is the point table. */
    for (uint32_t i = 0; i < n; i++)
        point_entry(cls, i, slab_q16, out + ((size_t)i * n + i) * 4);

    /* Entries r = |b - f| apart cross r intervals of length d / r each. */
    for (uint32_t r = 1; r < n; r++) {
        uint64_t length_q28 = vfi_udiv64(((uint64_t)slab_q16 << 12) + r / 2, r);
        intervals_for_length(cls, length_q28, iv);
        for (uint32_t f = 0; f + r < n; f++) {
            uint32_t b = f + r;
            accum_t up, down; /* field by field: an aggregate initialiser may become a memset call */
            up.a = up.r = up.g = up.b = 0;
            down.a = down.r = down.g = down.b = 0;
            for (uint32_t m = f; m < b; m++) /* front f < back b: intervals f .. b-1 in order */
                composite_interval(&up, iv + m * 4);
            for (uint32_t m = b; m-- > f;) /* front b > back f: intervals b-1 .. f */
                composite_interval(&down, iv + m * 4);
            store_entry(&up, out + ((size_t)f * n + b) * 4);
            store_entry(&down, out + ((size_t)b * n + f) * 4);
        }
    }
}

/* Entry i of the point table: a = 1 - exp(-tau_i d), C = c_i a. */
static void point_entry(const vfi_classify_t *cls, uint32_t i, uint32_t slab_q16, uint16_t *out)
{
    uint32_t a = opacity_q30(((uint64_t)cls->tau_q28[i] * slab_q16 + (1u << 15)) >> 16);
    accum_t acc;
    acc.a = a;
    acc.r = ((uint64_t)cls->colour_q30[i * 3 + 0] * a + (ONE_Q30 >> 1)) >> 30;
    acc.g = ((uint64_t)cls->colour_q30[i * 3 + 1] * a + (ONE_Q30 >> 1)) >> 30;
    acc.b = ((uint64_t)cls->colour_q30[i * 3 + 2] * a + (ONE_Q30 >> 1)) >> 30;
    store_entry(&acc, out);
}

/* Opacity and premultiplied colour of every interval for pieces of the given length (Q.28 in d_ref). */
static void intervals_for_length(const vfi_classify_t *cls, uint64_t length_q28, uint32_t *out)
{
    for (uint32_t m = 0; m + 1 < cls->n; m++) {
        /* mean extinction (t0 + t1) / 2 in Q.24 times the length in Q.28: Q.52, back to Q.28 */
        uint64_t mean_q24 = ((uint64_t)cls->tau_q28[m] + cls->tau_q28[m + 1] + 16) >> 5;
        uint32_t a = opacity_q30((mean_q24 * length_q28 + (UINT64_C(1) << 23)) >> 24);
        out[m * 4 + 0] = a;
        for (int c = 0; c < 3; c++)
            out[m * 4 + 1 + c] = (uint32_t)(((uint64_t)cls->weight_q30[m * 3 + c] * a + (ONE_Q30 >> 1)) >> 30);
    }
}

/* Front to back: C += (1 - A) C_m, A += (1 - A) a_m. */
static void composite_interval(accum_t *acc, const uint32_t *iv)
{
    uint64_t t = ONE_Q30 - acc->a;
    acc->r += (t * iv[1] + (ONE_Q30 >> 1)) >> 30;
    acc->g += (t * iv[2] + (ONE_Q30 >> 1)) >> 30;
    acc->b += (t * iv[3] + (ONE_Q30 >> 1)) >> 30;
    acc->a += (t * iv[0] + (ONE_Q30 >> 1)) >> 30;
}

static uint16_t q30_to_q15(uint64_t v)
{
    uint64_t q = (v + (1u << 14)) >> 15;
    return (uint16_t)(q > VFI_ONE_Q15 ? VFI_ONE_Q15 : q);
}

static void store_entry(const accum_t *acc, uint16_t *out)
{
    out[0] = q30_to_q15(acc->r);
    out[1] = q30_to_q15(acc->g);
    out[2] = q30_to_q15(acc->b);
    out[3] = q30_to_q15(acc->a);
}

/* 1 - exp(-x), x in Q.28; Q.30. */
static uint32_t opacity_q30(uint64_t tau_length_q28)
{
    return (uint32_t)(ONE_Q30 - vfi_exp_neg_q28(tau_length_q28));
}
