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

/* exp(-x) for x >= 0 in Q.28; result Q.30, within 4e-9 absolute (measured 3.6e-9). */
uint32_t vfi_exp_neg_q28(uint64_t x_q28);

/* -ln(y) for y in Q.32, 2^-16 <= y <= 1 (smaller y is taken as 2^-16); result Q.28, within 1e-8. */
uint32_t vfi_neg_ln_q32(uint64_t y_q32);

/* floor(sqrt(x)) and round(sqrt(x)). */
uint32_t vfi_isqrt64(uint64_t x);
uint32_t vfi_sqrt64_round(uint64_t x);

/* Division without the compiler's 64-bit helpers (so the core links with nothing on 32-bit targets).
 * den must not be 0. The _round form rounds half away from zero. */
uint64_t vfi_udiv64(uint64_t num, uint64_t den);
int64_t vfi_sdiv64_round(int64_t num, int64_t den);

/* round(num * 2^32 / den) for den != 0 and |num / den| < 2^31: a ratio in Q32.32 without a 128-bit type. */
int64_t vfi_ratio_q32(int64_t num, int64_t den);

/* (a * b) >> shift with a 128-bit intermediate, rounded to nearest: for Q32.32 products whose intermediate
 * would overflow 64 bits. shift is 1..63. */
int64_t vfi_mul_shift_round(int64_t a, int64_t b, unsigned shift);

#endif
