/* SPDX-License-Identifier: MIT */
/* fuzz_shade.c: the core's lighting from arbitrary bytes, through its public API as the programs use it: normal
 * codes and gradient magnitudes of a small volume of any voxel type and spacing (vfi_normals_build, at renderer
 * creation), the per-frame shade table of any lights and material (vfi_shade_table, at each frame), and the lit
 * loops of point, preint1 and preclass with either shade lookup, at any view.
 *
 * The input: 16 bytes of settings (below), then the voxels, repeated to fill the volume. What must hold:
 * - vf_renderer_set_lighting gives VF_ERR_ARG exactly when the lighting breaks its documented ranges (volfix.h:
 *   1..VF_MAX_LIGHTS lights, shininess 1..255, a gradient ramp lo < hi unless both are 0), VF_OK otherwise;
 * - a frame of an accepted lighting renders (VF_OK), twice with the same pixels (the shade table is rebuilt per
 *   frame from the lighting alone);
 * - with shading off and no gradient ramp, the frame is the unlit renderer's to the bit (volfix.h's promise);
 * - and no sanitizer report, as everywhere. */
#include "fuzz.h"
#include "volfix.h"

#define SIZE 16 /* the frame, SIZE x SIZE */
#define SETTINGS 16

/* A renderer for the volume, transfer function and params, with its arena in *buffer (malloc'd; the caller frees
 * it). NULL when the core refuses the volume or params (never expected: the settings stay in range). */
static vf_renderer_t *open_renderer(const vf_params_t *params, const vf_volume_t *vol, const vf_tf_t *tf,
                                    void **buffer)
{
    size_t bytes = 0;
    if (vf_renderer_bytes(params, vol, &bytes) != VF_OK)
        abort();
    /* the run lists: at most two values per cell and a row index per axis */
    bytes += 3 * (size_t)(vol->dims[0] + 1) * (vol->dims[1] + 1) * (vol->dims[2] + 1) * 4 + 4096;
    *buffer = malloc(bytes);
    vf_arena_t arena;
    vf_renderer_t *r = NULL;
    vf_arena_init(&arena, *buffer, bytes);
    if (!*buffer || vf_renderer_create(&r, params, vol, &arena) != VF_OK ||
        vf_renderer_set_window(r, (vf_window_t){0, vol->type == VF_VOXEL_U8 ? 255 : 4000}) != VF_OK ||
        vf_renderer_set_tf(r, tf) != VF_OK)
        abort();
    return r;
}

/* One frame into pixels (SIZE x SIZE RGB888), composited in one band. */
static void frame(vf_renderer_t *r, const vf_view_t *view, unsigned char *pixels)
{
    const vf_frame_t f = {.view = *view, .width = SIZE, .height = SIZE};
    if (vf_renderer_begin(r, &f) != VF_OK)
        abort();
    const uint32_t rows = vf_renderer_factor(r)->int_h;
    const size_t scratch_bytes = vf_renderer_band_scratch_bytes(r, rows);
    void *scratch = malloc(scratch_bytes ? scratch_bytes : 1);
    const vf_image_t image = {pixels, SIZE, SIZE, SIZE * 3, VF_FORMAT_RGB888};
    if (!scratch || vf_renderer_composite_band(r, 0, rows, scratch, scratch_bytes) != VF_OK ||
        vf_renderer_warp_band(r, &image, 0, SIZE) != VF_OK)
        abort();
    free(scratch);
}

static int32_t s16(const uint8_t *p)
{
    return (int16_t)(uint16_t)(p[0] | p[1] << 8);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < SETTINGS + 1)
        return 0;
    /* settings: 0-2 dims (2..9), 3 voxel type and mode, 4 normal bits, shade lookup and table size, 5-7 spacing,
     * 8 shade, light count, gradient ramp, 9-10 light 0's azimuth and elevation (and light 1's, negated), 11
     * shininess (0 and above 255 out of range), 12-14 ka, kd, ks, 15 the view */
    const uint8_t *s = data;
    static const vf_mode_t modes[3] = {VF_MODE_POINT, VF_MODE_PREINT1, VF_MODE_PRECLASS};
    static const uint32_t bits[5] = {8, 10, 12, 14, 16};
    vf_volume_t vol = {{2 + s[0] % 8u, 2 + s[1] % 8u, 2 + s[2] % 8u}, {0, 0, 0}, (vf_voxel_t)(s[3] & 3), NULL};
    for (int a = 0; a < 3; a++)
        vol.spacing_q16[a] = 16384u + (uint32_t)s[5 + a] * 1024u; /* 0.25 to 4.2: anisotropic volumes too */
    const size_t bytes_per = vol.type < VF_VOXEL_U16 ? 1 : 2;
    const size_t count = (size_t)vol.dims[0] * vol.dims[1] * vol.dims[2];
    unsigned char *voxels = malloc(count * bytes_per);
    if (!voxels)
        abort();
    for (size_t i = 0; i < count * bytes_per; i++)
        voxels[i] = data[SETTINGS + i % (size - SETTINGS)];
    vol.voxels = voxels;

    vf_params_t params;
    vf_params_default(&params);
    params.mode = modes[(s[3] >> 2) % 3u];
    params.table_size = 16u << (s[4] >> 6 & 1); /* 16 or 32 entries: each input renders in a moment */
    params.normal_bits = bits[(s[4] & 7) % 5u];
    params.shade_lookup = s[4] & 8 ? VF_LOOKUP_BILINEAR : VF_LOOKUP_NEAREST;
    params.lighting = true;

    /* a transfer function with some colour, opaque enough to show surfaces */
    static const vf_tf_point_t points[3] = {{0, 0, 0, 0, 0}, {128 << 8, 65535, 40000, 20000, 30000},
                                            {255 << 8, 30000, 50000, 65535, 65535}};
    const vf_tf_t tf = {points, 3};

    vf_lighting_t l;
    vf_lighting_default(&l);
    l.shade = s[8] & 1;
    l.light_count = s[8] >> 1 & 3; /* 0..3: 0 and 3 out of range */
    l.lights[0].azimuth = s16(s + 9) * 4;
    l.lights[0].elevation = s16(s + 9) * -3 + (int32_t)s[10] * 64;
    l.lights[1].azimuth = -l.lights[0].azimuth;
    l.lights[1].elevation = -l.lights[0].elevation;
    l.shininess = (uint16_t)(s[11] == 255 ? 256 : s[11]);
    l.ka = (uint16_t)(s[12] * 257);
    l.kd = (uint16_t)(s[13] * 257);
    l.ks = (uint16_t)(s[14] * 257);
    l.gradient_lo = s[8] & 8 ? (uint8_t)(s[12] ^ s[13]) : 0;
    l.gradient_hi = s[8] & 8 ? (uint8_t)(s[13] ^ s[14]) : 0;
    const bool ramp_ok = (l.gradient_lo == 0 && l.gradient_hi == 0) || l.gradient_lo < l.gradient_hi;
    const bool valid = l.light_count >= 1 && l.light_count <= VF_MAX_LIGHTS && l.shininess >= 1 &&
                       l.shininess <= 255 && ramp_ok;
    const vf_view_t view = {(int32_t)s[15] * 257, (int32_t)(s[15] ^ s[0]) * 129 - 16384, (int32_t)s[1] * 97,
                            65536u + (uint32_t)(s[2] & 31) * 2048u};

    void *buffer = NULL;
    vf_renderer_t *r = open_renderer(&params, &vol, &tf, &buffer);
    const vf_status_t st = vf_renderer_set_lighting(r, &l);
    if (st != (valid ? VF_OK : VF_ERR_ARG))
        abort();
    static unsigned char first[SIZE * SIZE * 3], again[SIZE * SIZE * 3], unlit[SIZE * SIZE * 3];
    frame(r, &view, first);
    frame(r, &view, again);
    if (memcmp(first, again, sizeof first) != 0)
        abort();
    if (getenv("VOLFIX_SHOW_ERRORS")) { /* as the other harnesses show their outcome */
        unsigned long sum = 0;
        for (size_t i = 0; i < sizeof first; i++)
            sum += first[i];
        fprintf(stderr, "# %s %ux%ux%u, lighting %s, frame's byte sum %lu\n", vf_mode_name(params.mode), vol.dims[0],
                vol.dims[1], vol.dims[2], vf_status_text(st), sum);
    }
    if (valid && !l.shade && l.gradient_lo == 0 && l.gradient_hi == 0) {
        /* lighting that changes nothing: the unlit renderer's pixels */
        void *plain_buffer = NULL;
        params.lighting = false;
        vf_renderer_t *plain = open_renderer(&params, &vol, &tf, &plain_buffer);
        frame(plain, &view, unlit);
        if (memcmp(first, unlit, sizeof first) != 0)
            abort();
        free(plain_buffer);
    }
    free(buffer);
    free(voxels);
    return 0;
}
