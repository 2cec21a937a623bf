/* SPDX-License-Identifier: MIT */
/* ref_window.c: raw voxels to the 8-bit scalar domain (docs/algorithm.md, section 1). */
#include "ref/ref.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

/* The quotient (v - lo) * 255 / (hi - lo) is a ratio of integers below 2^42 in magnitude, so one rounding of
 * the double division cannot move it across a half-integer (it is at least 1 / (2 |hi - lo|) away from one
 * unless it is exactly on one, and then the division is exact): round half up below is the exact rule. */
int ref_window(const void *raw, int type, const int dims[3], int32_t lo, int32_t hi, uint8_t *out)
{
    if (!raw || !dims || !out || lo == hi || type < REF_VOXEL_U8 || type > REF_VOXEL_I16)
        return -1;
    for (int a = 0; a < 3; a++)
        if (dims[a] < 2 || dims[a] > REF_MAX_DIM)
            return -1;
    size_t count = (size_t)dims[0] * (size_t)dims[1] * (size_t)dims[2];
    double den = (double)((int64_t)hi - lo);
    for (size_t n = 0; n < count; n++) {
        double x = (double)(((int64_t)ref_raw_voxel(raw, type, n) - lo) * 255) / den;
        double s = floor(x + 0.5);
        out[n] = (uint8_t)(s < 0 ? 0 : s > 255 ? 255 : s);
    }
    return 0;
}
