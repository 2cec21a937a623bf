/* SPDX-License-Identifier: MIT */
/*
 * ref_fixtures.h: what the tests of the reference (host-sim/ref) build their cases from: tiny volumes from a
 * function of the voxel, a repeatable random sequence, a smooth transfer function, angles in binary angle units.
 * Header-only and static inline, as check.h is, so that each test program stays one file.
 */
#ifndef REF_FIXTURES_H
#define REF_FIXTURES_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "ref/ref.h"

#define PI 3.14159265358979323846
#define BAU(deg) ((int32_t)((deg) * 65536.0 / 360.0 + ((deg) < 0 ? -0.5 : 0.5))) /* nearest, a constant */

/* The next number of a test's own sequence (a linear congruential generator in *seed), uniform in [0, 1): the
 * same cases on every machine. */
static inline double rf_uniform(uint32_t *seed)
{
    *seed = *seed * 1664525u + 1013904223u;
    return (*seed >> 8) / 16777216.0;
}

/* A volume of exactly dims voxels (so that AddressSanitizer sees any read past the last one), x fastest; NULL when
 * out of memory. */
static inline uint8_t *rf_volume_of(const int dims[3], int (*value)(int x, int y, int z))
{
    uint8_t *s = malloc((size_t)dims[0] * dims[1] * dims[2]);
    for (int z = 0; s && z < dims[2]; z++)
        for (int y = 0; y < dims[1]; y++)
            for (int x = 0; x < dims[0]; x++)
                s[((size_t)z * dims[1] + y) * dims[0] + x] = (uint8_t)value(x, y, z);
    return s;
}

static inline int rf_const_200(int x, int y, int z)
{
    (void)x, (void)y, (void)z;
    return 200;
}

/* A smooth opacity bump (peak at scalar 140) and smooth colours through 33 control points; returns 33. */
static inline int rf_smooth_tf(ref_tf_point_t *tf, double peak)
{
    for (int p = 0; p < 33; p++) {
        double s = p * 255.0 / 32;
        tf[p] = (ref_tf_point_t){s, 0.5 + 0.5 * sin(s / 40), s / 255, 1 - s / 255,
                                 peak * exp(-((s - 140) / 45) * ((s - 140) / 45))};
    }
    return 33;
}

#endif
