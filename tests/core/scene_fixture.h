/* SPDX-License-Identifier: MIT */
/*
 * scene_fixture.h: what the core suites build their frames from: a ball in noise, a random transfer function,
 * and a renderer over a caller's arena buffer with the identity window and a transfer function set. Header-only
 * and static inline, as frame.h is, so that each suite stays one file; it needs only the core's header, so that
 * small_config.c, built outside the test framework, can use it too. Every random draw comes from the suite's own
 * generator and seed (check_mod or check_below, check.h), so that each suite keeps its own cases.
 */
#ifndef TESTS_CORE_SCENE_FIXTURE_H
#define TESTS_CORE_SCENE_FIXTURE_H

#include <stddef.h>
#include <stdint.h>

#include "volfix.h"

/* One value in [0, n) from *state: check_mod or check_below. */
typedef uint32_t (*scene_draw_t)(uint64_t *state, uint32_t n);

/* A ball of radius rad_min + draw(rad_span) around a random voxel: inside + draw(noise) in it, outside +
 * draw(noise) around it, and a voxel where draw(salt) is 0 replaced by draw(256). */
typedef struct scene_blob {
    uint32_t rad_min, rad_span;
    uint32_t inside, outside, noise;
    uint32_t salt;
} scene_blob_t;

/* Fills the dims[0] x dims[1] x dims[2] u8 voxels at vox, x fastest. */
static inline void scene_fill_blob(uint8_t *vox, const uint32_t dims[3], const scene_blob_t *b, scene_draw_t draw,
                                   uint64_t *state)
{
    const uint32_t nx = dims[0], ny = dims[1], nz = dims[2];
    const int cx = (int)draw(state, nx), cy = (int)draw(state, ny), cz = (int)draw(state, nz);
    const int rad = (int)b->rad_min + (int)draw(state, b->rad_span);
    for (uint32_t z = 0; z < nz; z++)
        for (uint32_t y = 0; y < ny; y++)
            for (uint32_t x = 0; x < nx; x++) {
                int d2 = ((int)x - cx) * ((int)x - cx) + ((int)y - cy) * ((int)y - cy) + ((int)z - cz) * ((int)z - cz);
                uint32_t val = (d2 < rad * rad ? b->inside : b->outside) + draw(state, b->noise);
                if (draw(state, b->salt) == 0)
                    val = draw(state, 256);
                vox[((size_t)z * ny + y) * nx + x] = (uint8_t)val;
            }
}

/* Fills the dims[0] x dims[1] x dims[2] u8 voxels at vox, x fastest, with shape(x, y, z) plus noise_bits of a
 * linear congruential sequence from seed: a fixed volume, the same on every machine. */
static inline void scene_fill_shape(uint8_t *vox, const uint32_t dims[3], int (*shape)(int x, int y, int z),
                                    uint32_t seed, unsigned noise_bits)
{
    for (uint32_t z = 0; z < dims[2]; z++)
        for (uint32_t y = 0; y < dims[1]; y++)
            for (uint32_t x = 0; x < dims[0]; x++) {
                seed = seed * 1103515245u + 12345u;
                vox[((size_t)z * dims[1] + y) * dims[0] + x] =
                    (uint8_t)(shape((int)x, (int)y, (int)z) + (int)(seed >> (32 - noise_bits)));
            }
}

/* A random transfer function's shape: 1 to 6 points from scalar draw(50000) on, draw(step) apart, random colours;
 * each point's opacity by k = draw(5): zero for k < zeros, then opaque, then faint (draw(faint)), else any. */
typedef struct scene_tf_style {
    uint32_t step, zeros, faint;
} scene_tf_style_t;

/* Writes up to 6 points into pts. */
static inline vf_tf_t scene_random_tf(vf_tf_point_t *pts, const scene_tf_style_t *st, scene_draw_t draw,
                                      uint64_t *state)
{
    uint32_t count = 1 + draw(state, 6), s = draw(state, 50000);
    for (uint32_t p = 0; p < count; p++) {
        if (p)
            s += draw(state, st->step);
        uint32_t k = draw(state, 5);
        pts[p] = (vf_tf_point_t){(uint16_t)(s > 65280 ? 65280 : s), (uint16_t)draw(state, 65536),
                                 (uint16_t)draw(state, 65536), (uint16_t)draw(state, 65536),
                                 (uint16_t)(k < st->zeros        ? 0
                                            : k == st->zeros     ? 65535
                                            : k == st->zeros + 1 ? draw(state, st->faint)
                                                                 : draw(state, 65536))};
    }
    return (vf_tf_t){pts, count};
}

/* A renderer for vol over an arena on buf, with the window (0, 255) and, when tf is not NULL, tf set: VF_OK or
 * the first failure's status. */
static inline vf_status_t scene_renderer(vf_renderer_t **r, vf_arena_t *arena, void *buf, size_t bytes,
                                         const vf_params_t *p, const vf_volume_t *vol, const vf_tf_t *tf)
{
    vf_arena_init(arena, buf, bytes);
    *r = NULL;
    vf_status_t s = vf_renderer_create(r, p, vol, arena);
    if (s == VF_OK)
        s = vf_renderer_set_window(*r, (vf_window_t){0, 255});
    if (s == VF_OK && tf)
        s = vf_renderer_set_tf(*r, tf);
    return s;
}

#endif
