/* SPDX-License-Identifier: MIT */
/* ref_normals.c: gradients, normal codes and 8-bit gradient magnitudes of the voxels as stored (section 7).
 *
 * Section 7 defines the codes and magnitudes in integers, exactly, so that both implementations light with the
 * same quantised normals ("the same inputs"): this file computes them from that definition, on its own, with
 * 64-bit integers where the definition rounds (q, the code's divisions, the magnitude's square root), and in
 * double everywhere else. Nothing here comes from the core. */
#include "ref/ref.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* floor(sqrt(v)), exactly: the double root corrected by a step or two either way */
static uint64_t isqrt64(uint64_t v)
{
    uint64_t r = (uint64_t)sqrt((double)v);
    while (r > 0 && (r > UINT32_MAX || r * r > v))
        r--;
    while (r + 1 <= UINT32_MAX && (r + 1) * (r + 1) <= v)
        r++;
    return r;
}

int ref_normal_levels(int normal_bits)
{
    return (1 << (normal_bits / 2)) - 1;
}

/* What a gradient needs of the volume: its strides, and for each axis and step count c (1 or 2) the integer
 * q_a(c) = round(2^14 sp_min / (c sp_a)) = floor((2^15 sp_min + c sp_a) / (2 c sp_a)) and the double
 * sp_min / (c sp_a), from the spacings as the core has them, Q16.16 integers (the reference's are q / 65536:
 * exact). */
typedef struct grad_ctx {
    const ref_volume_t *vol;
    const void *raw;
    int type;
    size_t stride[3];
    int64_t q[3][2];
    double w[3][2];
} grad_ctx_t;

static void grad_init(grad_ctx_t *g, const ref_volume_t *vol, const void *raw, int type)
{
    g->vol = vol, g->raw = raw, g->type = type;
    g->stride[0] = 1, g->stride[1] = (size_t)vol->dims[0], g->stride[2] = g->stride[1] * (size_t)vol->dims[1];
    int64_t sp[3], sp_min;
    for (int a = 0; a < 3; a++)
        sp[a] = (int64_t)llround(vol->spacing[a] * 65536.0);
    sp_min = sp[0] < sp[1] ? sp[0] : sp[1];
    sp_min = sp[2] < sp_min ? sp[2] : sp_min;
    for (int a = 0; a < 3; a++)
        for (int64_t c = 1; c <= 2; c++) {
            g->q[a][c - 1] = ((sp_min << 15) + c * sp[a]) / (2 * c * sp[a]);
            g->w[a][c - 1] = (double)sp_min / ((double)c * (double)sp[a]);
        }
}

static void grad_at(const grad_ctx_t *g, int x, int y, int z, int64_t G[3], double gd[3])
{
    const int p[3] = {x, y, z};
    const size_t at = (size_t)x * g->stride[0] + (size_t)y * g->stride[1] + (size_t)z * g->stride[2];
    for (int a = 0; a < 3; a++) {
        const int lo = p[a] > 0 ? p[a] - 1 : 0, hi = p[a] + 1 < g->vol->dims[a] ? p[a] + 1 : p[a];
        const int c = hi - lo; /* 2 inside, 1 at a face */
        const int64_t D = (int64_t)ref_raw_voxel(g->raw, g->type, at + (size_t)(hi - p[a]) * g->stride[a]) -
                          (int64_t)ref_raw_voxel(g->raw, g->type, at - (size_t)(p[a] - lo) * g->stride[a]);
        G[a] = D * g->q[a][c - 1];
        if (gd)
            gd[a] = (double)D * g->w[a][c - 1];
    }
}

void ref_gradient(const ref_volume_t *vol, const void *raw, int raw_type, int x, int y, int z, int64_t G[3],
                  double gd[3])
{
    grad_ctx_t g;
    grad_init(&g, vol, raw, raw_type);
    grad_at(&g, x, y, z, G, gd);
}

int ref_normal_code(const int64_t G[3], int levels)
{
    const int64_t ax = G[0] < 0 ? -G[0] : G[0], ay = G[1] < 0 ? -G[1] : G[1], az = G[2] < 0 ? -G[2] : G[2];
    const int64_t s = ax + ay + az;
    if (s == 0)
        return levels * levels;
    int64_t X = G[0], Y = G[1];
    if (G[2] < 0) { /* the lower half folded over the diagonals */
        X = G[0] >= 0 ? s - ay : -(s - ay);
        Y = G[1] >= 0 ? s - ax : -(s - ax);
    }
    /* q = floor(((X + s)(L - 1) + s) / (2 s)): X + s in [0, 2 s], s below 2^35, L - 1 below 2^8: it fits */
    const int64_t qx = ((X + s) * (levels - 1) + s) / (2 * s), qy = ((Y + s) * (levels - 1) + s) / (2 * s);
    return (int)(qy * levels + qx);
}

static double sg(double t)
{
    return t >= 0 ? 1.0 : -1.0;
}

void ref_normal_decode(int code, int levels, double n[3])
{
    if (code >= levels * levels) {
        n[0] = n[1] = n[2] = 0;
        return;
    }
    const double span = levels - 1.0;
    double px = 2.0 * (code % levels) / span - 1.0, py = 2.0 * (code / levels) / span - 1.0;
    const double pz = 1.0 - fabs(px) - fabs(py);
    if (pz < 0) {
        const double ox = px, oy = py;
        px = sg(ox) * (1.0 - fabs(oy));
        py = sg(oy) * (1.0 - fabs(ox));
    }
    const double len = sqrt(px * px + py * py + pz * pz);
    n[0] = px / len;
    n[1] = py / len;
    n[2] = pz / len;
}

int ref_normals(const ref_volume_t *vol, const void *raw, int raw_type, int normal_bits, int32_t *codes,
                uint8_t *magnitudes)
{
    if (!vol || !raw || !magnitudes || raw_type < REF_VOXEL_U8 || raw_type > REF_VOXEL_I16 || normal_bits < 8 ||
        normal_bits > 16 || normal_bits % 2)
        return -1;
    double spmin;
    if (ref_volume_check(vol, &spmin))
        return -1;
    const int levels = ref_normal_levels(normal_bits);
    const size_t count = (size_t)vol->dims[0] * (size_t)vol->dims[1] * (size_t)vol->dims[2];
    uint32_t *m = malloc(sizeof *m * count); /* m = floor(|G|) < 2^32: |G_a| <= 65535 2^14 */
    if (!m)
        return -1;
    uint64_t most = 0;
    size_t n = 0;
    grad_ctx_t g;
    grad_init(&g, vol, raw, raw_type);
    for (int z = 0; z < vol->dims[2]; z++)
        for (int y = 0; y < vol->dims[1]; y++)
            for (int x = 0; x < vol->dims[0]; x++, n++) {
                int64_t G[3];
                grad_at(&g, x, y, z, G, NULL);
                const uint64_t len2 = (uint64_t)(G[0] * G[0]) + (uint64_t)(G[1] * G[1]) + (uint64_t)(G[2] * G[2]);
                m[n] = (uint32_t)isqrt64(len2);
                most = m[n] > most ? m[n] : most;
                if (codes)
                    codes[n] = ref_normal_code(G, levels);
            }
    /* gm = floor((510 m + M) / (2 M)) = round(255 m / M); 0 everywhere when M = 0 */
    for (n = 0; n < count; n++)
        magnitudes[n] = most ? (uint8_t)((510 * (uint64_t)m[n] + most) / (2 * most)) : 0;
    free(m);
    return 0;
}

int64_t ref_gradient_most(const ref_volume_t *vol, const void *raw, int raw_type)
{
    double spmin;
    if (!vol || !raw || raw_type < REF_VOXEL_U8 || raw_type > REF_VOXEL_I16 || ref_volume_check(vol, &spmin))
        return -1;
    uint64_t most2 = 0; /* floor(sqrt) is monotonic: M is the root of the largest square */
    grad_ctx_t g;
    grad_init(&g, vol, raw, raw_type);
    for (int z = 0; z < vol->dims[2]; z++)
        for (int y = 0; y < vol->dims[1]; y++)
            for (int x = 0; x < vol->dims[0]; x++) {
                int64_t G[3];
                grad_at(&g, x, y, z, G, NULL);
                const uint64_t len2 = (uint64_t)(G[0] * G[0]) + (uint64_t)(G[1] * G[1]) + (uint64_t)(G[2] * G[2]);
                most2 = len2 > most2 ? len2 : most2;
            }
    return (int64_t)isqrt64(most2);
}
