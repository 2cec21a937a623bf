/*
 * fixmath.c: integer trigonometry, exponential, logarithm, square root and division for the core.
 *
 * No floating point anywhere: the tables below were generated once by
 *   python3 -c "import math; print([round(math.sin(n*math.pi/128)*2**30) for n in range(65)])"
 *   python3 -c "print([round(2**(-n/64)*2**30) for n in range(65)])"
 * and are const, so two renderers in one process share nothing mutable.
 */
#include "fixmath.h"

/* sin(n * pi / 128) in Q2.30 for n = 0..64: a quarter wave in steps of 1/256 turn (256 BAU). */
static const int32_t sin_quarter[65] = {
    0, 26350943, 52686014, 78989349, 105245103, 131437462, 157550647, 183568930, 209476638, 235258165,
    260897982, 286380643, 311690799, 336813204, 361732726, 386434353, 410903207, 435124548, 459083786,
    482766489, 506158392, 529245404, 552013618, 574449320, 596538995, 618269338, 639627258, 660599890,
    681174602, 701339000, 721080937, 740388522, 759250125, 777654384, 795590213, 813046808, 830013654,
    846480531, 862437520, 877875009, 892783698, 907154608, 920979082, 934248793, 946955747, 959092290,
    970651112, 981625251, 992008094, 1001793390, 1010975242, 1019548121, 1027506862, 1034846671, 1041563127,
    1047652185, 1053110176, 1057933813, 1062120190, 1065666786, 1068571464, 1070832474, 1072448455, 1073418433,
    1073741824,
};

/* 2^(-n/64) in Q.30 for n = 0..64. */
static const uint32_t exp2_neg_64th[65] = {
    1073741824, 1062175491, 1050733751, 1039415261, 1028218693, 1017142735, 1006186087, 995347464, 984625594,
    974019220, 963527098, 953147997, 942880699, 932724001, 922676710, 912737649, 902905651, 893179563,
    883558244, 874040567, 864625413, 855311680, 846098274, 836984114, 827968132, 819049271, 810226483,
    801498734, 792865000, 784324269, 775875538, 767517817, 759250125, 751071493, 742980960, 734977579,
    727060411, 719228525, 711481005, 703816941, 696235434, 688735596, 681316545, 673977412, 666717336,
    659535466, 652430958, 645402981, 638450708, 631573326, 624770026, 618040012, 611382493, 604796689,
    598281827, 591837143, 585461881, 579155293, 572916640, 566745190, 560640218, 554601009, 548626854,
    542717053, 536870912,
};

#define RAD_PER_BAU_Q46 INT64_C(6746518852) /* 2 pi / 65536 in Q.46 */
#define LOG2_E_Q30 UINT64_C(1549082005)     /* log2(e) */
#define LN2_Q32 UINT64_C(2977044472)        /* ln(2) */

static int64_t mul_q30(int64_t a, int64_t b)
{
    return (a * b + (INT64_C(1) << 29)) >> 30;
}

void vfi_sincos(int32_t angle_bau, int32_t *sin_q30, int32_t *cos_q30)
{
    uint32_t a = (uint32_t)angle_bau & 0xFFFFu;
    uint32_t quadrant = a >> 14, within = a & 0x3FFFu;
    uint32_t n = within >> 8, delta = within & 0xFFu;
    int64_t s0 = sin_quarter[n], c0 = sin_quarter[64 - n];

    /* The remainder delta (< 1/256 turn, < 0.0246 rad) by Taylor series: sin(a + d) = sin a cos d + cos a sin d. */
    int64_t x = ((int64_t)delta * RAD_PER_BAU_Q46 + (INT64_C(1) << 15)) >> 16; /* radians, Q.30 */
    /* the powers are below 2^30: divide them as 32-bit values (a 64-bit division would need a libgcc helper) */
    int32_t x2 = (int32_t)mul_q30(x, x), x3 = (int32_t)mul_q30(x2, x), x4 = (int32_t)mul_q30(x3, x);
    int64_t cos_d = VFI_ONE_Q30 - x2 / 2 + x4 / 24;
    int64_t sin_d = x - x3 / 6;
    int64_t s = mul_q30(s0, cos_d) + mul_q30(c0, sin_d);
    int64_t c = mul_q30(c0, cos_d) - mul_q30(s0, sin_d);

    switch (quadrant) {
    case 0: *sin_q30 = (int32_t)s; *cos_q30 = (int32_t)c; break;
    case 1: *sin_q30 = (int32_t)c; *cos_q30 = (int32_t)-s; break;
    case 2: *sin_q30 = (int32_t)-s; *cos_q30 = (int32_t)-c; break;
    default: *sin_q30 = (int32_t)-c; *cos_q30 = (int32_t)s; break;
    }
}

uint32_t vfi_exp_neg_q28(uint64_t x_q28)
{
    /* exp(-x) = 2^-(x log2 e) = 2^-n * 2^-(f_hi / 64) * 2^-f_lo, the last by its Taylor series. */
    if (x_q28 >= (UINT64_C(23) << 28))
        return 0; /* exp(-23) < 2^-31: below half an LSB of Q.30 */
    uint64_t z = (x_q28 * LOG2_E_Q30 + (UINT64_C(1) << 29)) >> 30; /* Q.28 */
    uint32_t n = (uint32_t)(z >> 28);
    uint32_t f = (uint32_t)(z & ((UINT32_C(1) << 28) - 1));
    uint32_t f_hi = f >> 22, f_lo = f & ((UINT32_C(1) << 22) - 1);
    int64_t y = (int64_t)(((uint64_t)f_lo * LN2_Q32) >> 30); /* f_lo * ln 2, Q.30, < 0.0109 */
    int32_t y2 = (int32_t)mul_q30(y, y), y3 = (int32_t)mul_q30(y2, y), y4 = (int32_t)mul_q30(y3, y);
    int64_t poly = VFI_ONE_Q30 - y + y2 / 2 - y3 / 6 + y4 / 24;
    uint64_t r = ((uint64_t)exp2_neg_64th[f_hi] * (uint64_t)poly + (UINT64_C(1) << 29)) >> 30;
    if (n == 0)
        return (uint32_t)r;
    if (n >= 32)
        return 0;
    return (uint32_t)((r + (UINT64_C(1) << (n - 1))) >> n);
}

uint32_t vfi_neg_ln_q32(uint64_t y_q32)
{
    /* log2 by normalisation and repeated squaring (one result bit per squaring), then times ln 2. */
    if (y_q32 < (UINT64_C(1) << 16))
        y_q32 = UINT64_C(1) << 16; /* the result must fit Q4.28: -ln(2^-16) = 11.09 */
    uint32_t p = 0; /* position of the top bit */
    while ((y_q32 >> p) > 1)
        p++;
    /* m = y / 2^p in Q.30, in [1, 2) */
    uint64_t m = p >= 30 ? y_q32 >> (p - 30) : y_q32 << (30 - p);
    uint64_t frac = 0; /* log2(m), Q.28 */
    for (int bit = 27; bit >= 0; bit--) {
        m = (m * m) >> 30;
        if (m >= (UINT64_C(2) << 30)) {
            m >>= 1;
            frac |= UINT64_C(1) << bit;
        }
    }
    /* -log2(y) = (32 - p) - frac, in Q.28 */
    uint64_t neg_log2 = ((uint64_t)(32 - p) << 28) - frac;
    return (uint32_t)((neg_log2 * LN2_Q32 + (UINT64_C(1) << 31)) >> 32);
}

uint32_t vfi_isqrt64(uint64_t x)
{
    uint64_t root = 0, bit = UINT64_C(1) << 62;
    while (bit > x)
        bit >>= 2;
    while (bit) {
        if (x >= root + bit) {
            x -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return (uint32_t)root;
}

uint32_t vfi_sqrt64_round(uint64_t x)
{
    uint32_t r = vfi_isqrt64(x);
    /* (r + 1/2)^2 = r^2 + r + 1/4: round up when x - r^2 > r */
    return x - (uint64_t)r * r > r && r != UINT32_MAX ? r + 1 : r;
}

uint64_t vfi_udiv64(uint64_t num, uint64_t den)
{
    uint64_t q = 0, r = 0;
    for (int i = 63; i >= 0; i--) {
        r = (r << 1) | ((num >> i) & 1u);
        if (r >= den) {
            r -= den;
            q |= UINT64_C(1) << i;
        }
    }
    return q;
}

int64_t vfi_sdiv64_round(int64_t num, int64_t den)
{
    int negative = (num < 0) != (den < 0);
    uint64_t n = num < 0 ? (uint64_t)0 - (uint64_t)num : (uint64_t)num;
    uint64_t d = den < 0 ? (uint64_t)0 - (uint64_t)den : (uint64_t)den;
    uint64_t q = vfi_udiv64(n + d / 2, d);
    return negative ? -(int64_t)q : (int64_t)q;
}

int64_t vfi_ratio_q32(int64_t num, int64_t den)
{
    int negative = (num < 0) != (den < 0);
    uint64_t n = num < 0 ? (uint64_t)0 - (uint64_t)num : (uint64_t)num;
    uint64_t d = den < 0 ? (uint64_t)0 - (uint64_t)den : (uint64_t)den;
    uint64_t whole = vfi_udiv64(n, d);
    uint64_t r = n - whole * d, frac = 0;
    /* 33 fraction bits by long division (the last one rounds); r < d, so 2r cannot overflow while d < 2^63 */
    for (int i = 0; i < 33; i++) {
        r <<= 1;
        frac <<= 1;
        if (r >= d) {
            r -= d;
            frac |= 1u;
        }
    }
    uint64_t q = (whole << 32) + ((frac + 1) >> 1);
    return negative ? -(int64_t)q : (int64_t)q;
}

int64_t vfi_mul_shift_round(int64_t a, int64_t b, unsigned shift)
{
    /* 64 x 64 -> 128 bits from 32-bit halves, on magnitudes. */
    int negative = (a < 0) != (b < 0);
    uint64_t x = a < 0 ? (uint64_t)0 - (uint64_t)a : (uint64_t)a;
    uint64_t y = b < 0 ? (uint64_t)0 - (uint64_t)b : (uint64_t)b;
    uint64_t x0 = x & 0xFFFFFFFFu, x1 = x >> 32, y0 = y & 0xFFFFFFFFu, y1 = y >> 32;
    uint64_t p00 = x0 * y0, p01 = x0 * y1, p10 = x1 * y0, p11 = x1 * y1;
    uint64_t mid = (p00 >> 32) + (p01 & 0xFFFFFFFFu) + (p10 & 0xFFFFFFFFu);
    uint64_t lo = (p00 & 0xFFFFFFFFu) | (mid << 32);
    uint64_t hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
    /* add half an LSB of the result, then shift the 128-bit value right */
    uint64_t half = UINT64_C(1) << (shift - 1);
    uint64_t lo2 = lo + half;
    hi += lo2 < lo;
    uint64_t q = (lo2 >> shift) | (hi << (64 - shift));
    return negative ? -(int64_t)q : (int64_t)q;
}
