/* SPDX-License-Identifier: MIT */
/*
 * fixmath.h: integer arithmetic the core needs (trigonometry, exp, log, square root, 64-bit division).
 * Formats are in the names: _q30 is Q.30 (1.0 = 2^30), _q28 Q.28, and so on.
 */
#ifndef VF_FIXMATH_H
#define VF_FIXMATH_H

#include <stdint.h>

#define VFI_ONE_Q30 (INT32_C(1) << 30)

/* sin and cos of an angle in binary angle units (65536 per turn), Q2.30; exact at multiples of 1/256 turn
 * (table values), otherwise within 3e-9 (measured 2.3e-9 over all 65536 angles). */
void vfi_sincos(int32_t angle_bau, int32_t *sin_q30, int32_t *cos_q30);

/* exp(-x) for x >= 0 in Q.28; result Q.30, within 1.25 LSB (1.17e-9) absolute (measured 1.14 LSB), and on average
 * within 0.1 LSB of exact over each stretch tests/core/test_fixmath.c walks (measured 0.071): what a table builder
 * compositing hundreds of intervals in a row accumulates.
 * exp(-x) = exp(-n) exp(-h / 256) exp(-m / 65536) exp(-l) for x = n + h / 256 + m / 65536 + l: the first three
 * from tables, exp(-l) = 1 - l for the last 12 bits (l < 2^-16: 1 - l is low by l^2 / 2 < 2^-33, an eighth of an
 * LSB). One product and rounding a factor; the intermediate values keep two bits more than the result (Q.32), so
 * that the roundings and the tables' own add up to about one LSB of Q.30. */
uint32_t vfi_exp_neg_q28(uint64_t x_q28);

/* The same, inline, for loops over many arguments (the incremental table builder: 65025 of them for a
 * 256-entry table): with the tables from vfi_exp_neg_tables(), fetched once before the loop. A function rather
 * than a global array, so that position-independent builds of the core need no global offset table. */
#define VFI_EXP_WHOLE 23 /* exp(-23) < 2^-33: below half an LSB of Q.30 from there on */
const uint32_t *vfi_exp_neg_tables(void);

static inline uint32_t vfi_exp_neg_q28_with(const uint32_t *tables, uint64_t x_q28)
{
    if (x_q28 >= ((uint64_t)VFI_EXP_WHOLE << 28))
        return 0;
    const uint32_t x = (uint32_t)x_q28, n = (uint32_t)(x_q28 >> 28); /* n: the whole part; the fraction: x's low 28 bits */
    const uint32_t h = (x >> 20) & 0xFFu, m = (x >> 12) & 0xFFu, l = x & 0xFFFu;
    /* exp(-n) at tables[n], exp(-h / 256) at tables[23 + h], exp(-m / 65536) at tables[23 + 256 + m], Q.31 */
    uint64_t p = ((uint64_t)tables[n] * tables[VFI_EXP_WHOLE + h] + (UINT64_C(1) << 29)) >> 30; /* to Q.32 */
    p = (p * tables[VFI_EXP_WHOLE + 256 + m] + (UINT64_C(1) << 30)) >> 31;                      /* Q.32 */
    return (uint32_t)((p * ((UINT32_C(1) << 28) - l) + (UINT64_C(1) << 29)) >> 30);            /* Q.30 */
}

/* -ln(y) for y in Q.32, 2^-16 <= y <= 1 (smaller y is taken as 2^-16); result Q.28, within 1e-8. */
uint32_t vfi_neg_ln_q32(uint64_t y_q32);

/* floor(sqrt(x)) and round(sqrt(x)). */
uint32_t vfi_isqrt64(uint64_t x);
uint32_t vfi_sqrt64_round(uint64_t x);

/* Division without the compiler's 64-bit helpers (so the core links with nothing on 32-bit targets; 64-bit
 * targets use their divide instruction). den must not be 0. The _round form rounds half away from zero. */
uint64_t vfi_udiv64(uint64_t num, uint64_t den);
int64_t vfi_sdiv64_round(int64_t num, int64_t den);

/* round(num * 2^32 / den) for den != 0 and |num / den| < 2^31: a ratio in Q32.32 without a 128-bit type. */
int64_t vfi_ratio_q32(int64_t num, int64_t den);

/* (a * b) >> shift with a 128-bit intermediate, rounded to nearest: for Q32.32 products whose intermediate
 * would overflow 64 bits. shift is 1..63. */
int64_t vfi_mul_shift_round(int64_t a, int64_t b, unsigned shift);

#endif
