/* SPDX-License-Identifier: MIT */
/*
 * normals.c: normal codes and gradient magnitudes from central differences of the voxels as stored
 * (docs/algorithm.md, section 7), and the unit normal of each code.
 *
 * The gradient is taken before the window on purpose: a window that clips (CT bone at the top of a 12-bit range)
 * would flatten the gradients of everything beyond it, and the normals would change with the window. Everything is
 * integer and exact up to the rounding section 7 defines, so the double reference can take the same codes.
 */
#include "fixmath.h"
#include "normals.h"

static void axis_factors(const uint32_t sp[3], uint32_t q[3][2]);
static uint64_t gradients(const vf_volume_t *v, uint32_t levels, uint16_t *code, uint8_t *mag,
                          const uint64_t *at_least, const vfi_layout_t *lz);

/* Raw voxel i as stored, signed where the type is (type a constant where this is inlined). */
static inline int32_t voxel_of(const void *voxels, vf_voxel_t type, size_t i)
{
    switch (type) {
    case VF_VOXEL_U8: return ((const uint8_t *)voxels)[i];
    case VF_VOXEL_I8: return ((const int8_t *)voxels)[i];
    case VF_VOXEL_U16: return ((const uint16_t *)voxels)[i];
    default: return ((const int16_t *)voxels)[i];
    }
}

uint32_t vfi_normal_code(int64_t gx, int64_t gy, int64_t gz, uint32_t levels)
{
    const uint64_t ax = (uint64_t)(gx < 0 ? -gx : gx), ay = (uint64_t)(gy < 0 ? -gy : gy);
    const uint64_t s = ax + ay + (uint64_t)(gz < 0 ? -gz : gz);
    if (s == 0)
        return levels * levels;
    int64_t x = gx, y = gy;
    if (gz < 0) { /* the lower half folded over the diagonals */
        x = gx >= 0 ? (int64_t)(s - ay) : -(int64_t)(s - ay);
        y = gy >= 0 ? (int64_t)(s - ax) : -(int64_t)(s - ax);
    }
    /* round((x / s + 1) / 2 (L - 1)) = floor(((x + s)(L - 1) + s) / 2s), x + s in [0, 2s] */
    const uint64_t nx = (uint64_t)(x + (int64_t)s) * (levels - 1) + s, ny = (uint64_t)(y + (int64_t)s) * (levels - 1) + s;
    if ((nx | ny | 2 * s) <= UINT32_MAX) /* 8-bit data: 32-bit divisions, several times faster on most cores */
        return (uint32_t)ny / (uint32_t)(2 * s) * levels + (uint32_t)nx / (uint32_t)(2 * s);
    return (uint32_t)vfi_udiv64(ny, 2 * s) * levels + (uint32_t)vfi_udiv64(nx, 2 * s);
}

void vfi_normals_decode(uint32_t levels, int32_t *unit)
{
    const int32_t span = (int32_t)levels - 1;
    for (uint32_t code = 0; code < levels * levels; code++) {
        int32_t p[3];
        p[0] = 2 * (int32_t)(code % levels) - span;
        p[1] = 2 * (int32_t)(code / levels) - span;
        const int32_t ax = p[0] < 0 ? -p[0] : p[0], ay = p[1] < 0 ? -p[1] : p[1];
        p[2] = span - ax - ay;
        if (p[2] < 0) {
            p[0] = p[0] >= 0 ? span - ay : ay - span;
            p[1] = p[1] >= 0 ? span - ax : ax - span;
        }
        /* n = p / |p| in Q1.30: |p| 2^22 from the integer square root of |p|^2 2^44 (|p|^2 < 2^18), and
         * p 2^52 / that (|p| < 2^9: the product fits) */
        const uint64_t len2 = (uint64_t)((int64_t)p[0] * p[0] + (int64_t)p[1] * p[1] + (int64_t)p[2] * p[2]);
        const int64_t root = vfi_isqrt64(len2 << 44);
        for (int a = 0; a < 3; a++)
            unit[code * 3 + a] = (int32_t)vfi_sdiv64_round((int64_t)p[a] * (INT64_C(1) << 52), root);
    }
    unit[levels * levels * 3] = unit[levels * levels * 3 + 1] = unit[levels * levels * 3 + 2] = 0;
}

void vfi_normals_build(const vf_volume_t *v, uint32_t levels, uint16_t *const codes[3], uint8_t *const magnitudes[3])
{
    vfi_layout_t lz;
    vfi_layout(v->dims, 2, &lz); /* i = x, j = y: the file's own order */
    /* the largest squared magnitude first: floor(sqrt) is monotonic, so M is its root */
    const uint64_t most2 = gradients(v, levels, NULL, NULL, NULL, &lz);
    const uint32_t most = vfi_isqrt64(most2);
    /* gm >= k exactly when m >= c_k = ceil((2k - 1) M / 510), that is when m^2 >= c_k^2 (section 7's rounding
     * without a square root a voxel) */
    uint64_t at_least[256];
    at_least[0] = 0;
    for (uint32_t k = 1; k < 256; k++) {
        const uint64_t c = vfi_udiv64((uint64_t)(2 * k - 1) * most + 509, 510);
        at_least[k] = c * c;
    }
    gradients(v, levels, codes[2], magnitudes[2], most ? at_least : NULL, &lz);
    vfi_pad_copy(codes[2], &lz, sizeof *codes[2]);
    vfi_pad_copy(magnitudes[2], &lz, 1);
    for (int a = 0; a < 2; a++) {
        vfi_transpose_copy(codes[2], v->dims, a, codes[a], sizeof *codes[2]);
        vfi_transpose_copy(magnitudes[2], v->dims, a, magnitudes[a], 1);
    }
}

/* q[a][c - 1] = round(2^14 min(sp) / (c sp_a)) for a difference over c = 1 or 2 voxel steps along axis a: the
 * factor that turns it into world units (section 7). At most 2^14, so that a gradient's squared length fits 64
 * bits for any 16-bit data. */
static void axis_factors(const uint32_t sp[3], uint32_t q[3][2])
{
    uint32_t sp_min = sp[0] < sp[1] ? sp[0] : sp[1];
    sp_min = sp[2] < sp_min ? sp[2] : sp_min;
    for (int a = 0; a < 3; a++)
        for (uint32_t c = 1; c <= 2; c++) {
            const uint64_t den = (uint64_t)c * sp[a];
            q[a][c - 1] = (uint32_t)vfi_udiv64(((uint64_t)sp_min << 15) + den, 2 * den);
        }
}

/* One pass of central differences over the volume in file order, with the voxel type a constant so that the
 * compiler makes a loop for each: with code NULL, the largest squared magnitude; else every voxel's code and
 * 8-bit magnitude (at_least: the thresholds of vfi_normals_build; NULL when every magnitude is 0) into the z copy. */
static VF_ALWAYS_INLINE uint64_t gradients_of(const vf_volume_t *v, vf_voxel_t type, uint32_t levels, uint16_t *code,
                                              uint8_t *mag, const uint64_t *at_least, const vfi_layout_t *lz)
{
    uint32_t q[3][2];
    axis_factors(v->spacing_q16, q);
    const uint32_t n[3] = {v->dims[0], v->dims[1], v->dims[2]};
    const size_t stride[3] = {1, n[0], (size_t)n[0] * n[1]};
    uint64_t most2 = 0;
    for (uint32_t z = 0; z < n[2]; z++)
        for (uint32_t y = 0; y < n[1]; y++) {
            const size_t row = (size_t)z * lz->slice + (size_t)y * lz->row, first = stride[1] * y + stride[2] * z;
            /* along y and z the neighbours are the same for the whole row */
            const bool y_down = y > 0, y_up = y + 1 < n[1], z_down = z > 0, z_up = z + 1 < n[2];
            const size_t y_lo = y_down ? stride[1] : 0, y_hi = y_up ? stride[1] : 0;
            const size_t z_lo = z_down ? stride[2] : 0, z_hi = z_up ? stride[2] : 0;
            const int64_t qy = q[1][(uint32_t)y_down + (uint32_t)y_up - 1], qz = q[2][(uint32_t)z_down + (uint32_t)z_up - 1];
            for (uint32_t x = 0; x < n[0]; x++) {
                const size_t at = first + x;
                const bool x_down = x > 0, x_up = x + 1 < n[0];
                const int64_t g[3] = {
                    (int64_t)(voxel_of(v->voxels, type, at + x_up) - voxel_of(v->voxels, type, at - x_down)) *
                        q[0][(uint32_t)x_down + (uint32_t)x_up - 1],
                    (int64_t)(voxel_of(v->voxels, type, at + y_hi) - voxel_of(v->voxels, type, at - y_lo)) * qy,
                    (int64_t)(voxel_of(v->voxels, type, at + z_hi) - voxel_of(v->voxels, type, at - z_lo)) * qz};
                const uint64_t m2 = (uint64_t)(g[0] * g[0]) + (uint64_t)(g[1] * g[1]) + (uint64_t)(g[2] * g[2]);
                if (!code) {
                    most2 = m2 > most2 ? m2 : most2;
                    continue;
                }
                code[row + x] = (uint16_t)vfi_normal_code(g[0], g[1], g[2], levels);
                uint32_t gm = 0; /* the largest k with at_least[k] <= m2, by halves */
                if (at_least && m2)
                    for (uint32_t half = 128; half; half >>= 1)
                        gm = at_least[gm + half] <= m2 ? gm + half : gm;
                mag[row + x] = (uint8_t)gm;
            }
        }
    return most2;
}

static uint64_t gradients(const vf_volume_t *v, uint32_t levels, uint16_t *code, uint8_t *mag,
                          const uint64_t *at_least, const vfi_layout_t *lz)
{
    switch (v->type) {
    case VF_VOXEL_U8: return gradients_of(v, VF_VOXEL_U8, levels, code, mag, at_least, lz);
    case VF_VOXEL_I8: return gradients_of(v, VF_VOXEL_I8, levels, code, mag, at_least, lz);
    case VF_VOXEL_U16: return gradients_of(v, VF_VOXEL_U16, levels, code, mag, at_least, lz);
    default: return gradients_of(v, VF_VOXEL_I16, levels, code, mag, at_least, lz);
    }
}
