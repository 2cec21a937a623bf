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

static int32_t voxel(const vf_volume_t *v, size_t i);
static void axis_factors(const uint32_t sp[3], uint32_t q[3][2]);
static void gradient_at(const vf_volume_t *v, uint32_t q[3][2], uint32_t x, uint32_t y, uint32_t z, int64_t g[3]);

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
    const uint64_t qx = vfi_udiv64((uint64_t)(x + (int64_t)s) * (levels - 1) + s, 2 * s);
    const uint64_t qy = vfi_udiv64((uint64_t)(y + (int64_t)s) * (levels - 1) + s, 2 * s);
    return (uint32_t)qy * levels + (uint32_t)qx;
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
    uint32_t q[3][2];
    axis_factors(v->spacing_q16, q);
    const uint32_t nx = v->dims[0], ny = v->dims[1], nz = v->dims[2];
    vfi_layout_t lz;
    vfi_layout(v->dims, 2, &lz); /* i = x, j = y: the file's own order */
    /* the largest magnitude first, which the 8-bit magnitudes are relative to */
    uint64_t most = 0;
    for (uint32_t z = 0; z < nz; z++)
        for (uint32_t y = 0; y < ny; y++)
            for (uint32_t x = 0; x < nx; x++) {
                int64_t g[3];
                gradient_at(v, q, x, y, z, g);
                const uint64_t m = vfi_isqrt64((uint64_t)(g[0] * g[0]) + (uint64_t)(g[1] * g[1]) +
                                               (uint64_t)(g[2] * g[2]));
                most = m > most ? m : most;
            }
    uint16_t *code_z = codes[2];
    uint8_t *mag_z = magnitudes[2];
    for (uint32_t z = 0; z < nz; z++)
        for (uint32_t y = 0; y < ny; y++) {
            const size_t row = (size_t)z * lz.slice + (size_t)y * lz.row;
            for (uint32_t x = 0; x < nx; x++) {
                int64_t g[3];
                gradient_at(v, q, x, y, z, g);
                code_z[row + x] = (uint16_t)vfi_normal_code(g[0], g[1], g[2], levels);
                const uint64_t m = vfi_isqrt64((uint64_t)(g[0] * g[0]) + (uint64_t)(g[1] * g[1]) +
                                               (uint64_t)(g[2] * g[2]));
                mag_z[row + x] = most ? (uint8_t)vfi_udiv64(510 * m + most, 2 * most) : 0; /* round(255 m / M) */
            }
        }
    vfi_pad_copy(code_z, &lz, sizeof *code_z);
    vfi_pad_copy(mag_z, &lz, 1);
    for (int a = 0; a < 2; a++) {
        vfi_transpose_copy(code_z, v->dims, a, codes[a], sizeof *code_z);
        vfi_transpose_copy(mag_z, v->dims, a, magnitudes[a], 1);
    }
}

/* Raw voxel i as stored, signed where the type is. */
static int32_t voxel(const vf_volume_t *v, size_t i)
{
    switch (v->type) {
    case VF_VOXEL_U8: return ((const uint8_t *)v->voxels)[i];
    case VF_VOXEL_I8: return ((const int8_t *)v->voxels)[i];
    case VF_VOXEL_U16: return ((const uint16_t *)v->voxels)[i];
    default: return ((const int16_t *)v->voxels)[i];
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

/* G at voxel (x, y, z): central differences, one-sided at the faces, in world units times 2^14. */
static void gradient_at(const vf_volume_t *v, uint32_t q[3][2], uint32_t x, uint32_t y, uint32_t z, int64_t g[3])
{
    const uint32_t p[3] = {x, y, z};
    const size_t stride[3] = {1, v->dims[0], (size_t)v->dims[0] * v->dims[1]};
    const size_t at = x + stride[1] * y + stride[2] * z;
    for (int a = 0; a < 3; a++) {
        const bool down = p[a] > 0, up = p[a] + 1 < v->dims[a];
        const size_t lo = down ? at - stride[a] : at, hi = up ? at + stride[a] : at;
        g[a] = (int64_t)(voxel(v, hi) - voxel(v, lo)) * q[a][(uint32_t)down + (uint32_t)up - 1];
    }
}
