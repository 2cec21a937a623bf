/* SPDX-License-Identifier: MIT */
/*
 * shade.c: a frame's shade table (docs/algorithm.md, section 7): Blinn-Phong for every normal code, in integers.
 *
 * The normals are in world axes and the lights in eye axes; rather than turn every normal into eye space, the
 * lights and the viewing axis are turned into world space once a frame (R^T, R orthonormal), so that a code costs
 * the dot products alone. Vectors and dot products are Q1.30.
 */
#include "fixmath.h"
#include "shade.h"

#define ONE_Q30 (INT64_C(1) << 30)

static int64_t dot_q30(const int32_t n[3], const int64_t w[3]);
static VF_ALWAYS_INLINE void shade_codes(const int32_t *unit, uint32_t count, uint64_t *shade, const int64_t view_z[3],
                                         int64_t (*light_w)[3], int64_t (*half_w)[3], uint32_t lights,
                                         const vf_lighting_t *lighting);
static uint64_t power_q30(uint64_t x, uint32_t e);
static uint32_t unorm16_q30(uint16_t v);
static uint32_t q30_to_q14(uint64_t v);

void vfi_shade_table(int32_t r[3][3], const vf_lighting_t *lighting, const int32_t *unit, uint32_t count,
                     uint64_t *shade)
{
    /* towards light l and its half vector with V = (0, 0, -1), in eye axes, then in world axes (R^T) */
    int64_t light_w[VF_MAX_LIGHTS][3], half_w[VF_MAX_LIGHTS][3];
    const uint32_t lights = lighting->light_count;
    for (uint32_t l = 0; l < lights; l++) {
        int32_t sa, ca, se, ce;
        vfi_sincos(lighting->lights[l].azimuth, &sa, &ca);
        vfi_sincos(lighting->lights[l].elevation, &se, &ce);
        const int64_t eye[3] = {((int64_t)sa * ce + (ONE_Q30 >> 1)) >> 30, -(int64_t)se,
                                -(((int64_t)ca * ce + (ONE_Q30 >> 1)) >> 30)};
        int64_t half[3] = {eye[0], eye[1], eye[2] - ONE_Q30};
        const uint64_t len2 = (uint64_t)(half[0] * half[0] + half[1] * half[1] + half[2] * half[2]); /* Q.60 */
        const int64_t len = vfi_isqrt64(len2);                                                        /* Q.30 */
        for (int a = 0; a < 3; a++)
            half[a] = len ? vfi_sdiv64_round(half[a] * ONE_Q30, len) : 0; /* |half| < 2^31: the product fits */
        for (int a = 0; a < 3; a++) {
            light_w[l][a] = 0, half_w[l][a] = 0;
            for (int b = 0; b < 3; b++) {
                light_w[l][a] += (int64_t)r[b][a] * eye[b];
                half_w[l][a] += (int64_t)r[b][a] * half[b];
            }
            light_w[l][a] = (light_w[l][a] + (ONE_Q30 >> 1)) >> 30;
            half_w[l][a] = (half_w[l][a] + (ONE_Q30 >> 1)) >> 30;
        }
    }
    const int64_t view_z[3] = {r[2][0], r[2][1], r[2][2]}; /* the eye's z axis (into the screen), in world axes */
    if (lights == 1) /* the default: the lights' loop gone */
        shade_codes(unit, count, shade, view_z, light_w, half_w, 1, lighting);
    else
        shade_codes(unit, count, shade, view_z, light_w, half_w, lights, lighting);
}

void vfi_gradient_ramp(uint8_t lo, uint8_t hi, uint16_t factor[256])
{
    for (uint32_t m = 0; m < 256; m++) {
        if (lo >= hi || m >= hi)
            factor[m] = 32768u;
        else if (m <= lo)
            factor[m] = 0;
        else /* round(2^15 (m - lo) / (hi - lo)) */
            factor[m] = (uint16_t)(((m - lo) * 65536u + (hi - lo)) / (2u * (hi - lo)));
    }
}

/* Every code's entry, and the last code's (no normal): ambient light alone. Inline, so that a single light is a
 * constant count. */
static VF_ALWAYS_INLINE void shade_codes(const int32_t *unit, uint32_t count, uint64_t *shade, const int64_t view_z[3],
                                         int64_t (*light_w)[3], int64_t (*half_w)[3], uint32_t lights,
                                         const vf_lighting_t *lighting)
{
    const uint64_t ka = unorm16_q30(lighting->ka), kd = unorm16_q30(lighting->kd), ks = unorm16_q30(lighting->ks);
    const uint32_t ambient = q30_to_q14(ka), shininess = lighting->shininess;
    for (uint32_t code = 0; code + 1 < count; code++) {
        const int32_t *n = unit + (size_t)code * 3;
        /* two-sided: a normal facing away from the viewer (m_z > 0) is turned round */
        const int64_t side = dot_q30(n, view_z) > 0 ? -1 : 1;
        uint64_t diffuse = 0, specular = 0; /* Q.30 sums over the lights */
        for (uint32_t l = 0; l < lights; l++) {
            const int64_t d = side * dot_q30(n, light_w[l]), h = side * dot_q30(n, half_w[l]);
            diffuse += d > 0 ? (uint64_t)d : 0;
            specular += h > 0 ? power_q30((uint64_t)(h < ONE_Q30 ? h : ONE_Q30), shininess) : 0;
        }
        const uint32_t ld = q30_to_q14(ka + ((kd * diffuse + (UINT64_C(1) << 29)) >> 30));
        const uint32_t ls = q30_to_q14((ks * specular + (UINT64_C(1) << 29)) >> 30);
        shade[code] = ld | (uint64_t)ls << 32;
    }
    shade[count - 1] = ambient;
}

/* n . w, both Q1.30 (|n|, |w| at most about 1), rounded to Q1.30 */
static int64_t dot_q30(const int32_t n[3], const int64_t w[3])
{
    const int64_t sum = n[0] * w[0] + n[1] * w[1] + n[2] * w[2]; /* Q.60, |sum| < 2^62 */
    return (sum + (INT64_C(1) << 29)) >> 30;
}

/* x^e for x in [0, 1], Q.30, by squaring: x^(2^j) for each bit j of e, rounded, multiplied into the result from
 * the lowest bit up, each product rounded. The result starts as the lowest bit's power itself, which is 1.0 times it
 * rounded (exact: x 2^30 + 2^29 >> 30 = x), and nothing is squared past the highest bit. */
static uint64_t power_q30(uint64_t x, uint32_t e)
{
    if (e == 0)
        return (uint64_t)ONE_Q30;
    for (; !(e & 1u); e >>= 1)
        x = (x * x + (UINT64_C(1) << 29)) >> 30;
    uint64_t result = x;
    for (e >>= 1; e; e >>= 1) {
        x = (x * x + (UINT64_C(1) << 29)) >> 30;
        if (e & 1u)
            result = (result * x + (UINT64_C(1) << 29)) >> 30;
    }
    return result;
}

/* round(v 2^30 / 65535) */
static uint32_t unorm16_q30(uint16_t v)
{
    return (uint32_t)vfi_udiv64(((uint64_t)v << 31) + 65535, 2 * 65535);
}

static uint32_t q30_to_q14(uint64_t v)
{
    const uint64_t q = (v + (UINT64_C(1) << 15)) >> 16;
    return q > 0xFFFFu ? 0xFFFFu : (uint32_t)q;
}
