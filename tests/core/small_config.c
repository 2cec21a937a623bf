/* SPDX-License-Identifier: MIT */
/*
 * small_config.c: one program built twice by small_config.sh, against the whole core and against the smallest
 * configuration of core/vf_config.h (the microcontroller's: no partial slabs, rays, table parts, view tables,
 * tables built as read, brute-force table builder or order 2). It prints, a line each, the status of creating a
 * renderer with more than one ray, with partial slabs and in preint2 and of building a table by brute force, and a
 * hash of every frame
 * of a few scenes and turns with one ray and whole slabs; the script requires the small build to refuse the options
 * left out (VF_ERR_UNSUPPORTED) and to render every frame exactly as the whole core does.
 */
#include <stdint.h>
#include <stdio.h>

#include "frame.h"
#include "scene_fixture.h"
#include "volfix.h"

#define NX 21
#define NY 17
#define NZ 13
static uint8_t vox[NX * NY * NZ];
static _Alignas(16) unsigned char arena_buf[4 << 20];
static _Alignas(16) unsigned char scratch[1 << 18];
static unsigned char pixels[48 * 40 * 4];

static const vf_volume_t volume = {{NX, NY, NZ}, {65536, 65536, 65536}, VF_VOXEL_U8, vox};

/* Two nested balls, visible up to the box at one corner (where partial slabs would differ). */
static int nested_balls(int x, int y, int z)
{
    int d2 = (x - 10) * (x - 10) + (y - 8) * (y - 8) + (z - 6) * (z - 6);
    return d2 <= 9 ? 220 : d2 <= 30 ? 140 : x + y < 6 ? 180 : 30;
}

static void fill_volume(void)
{
    scene_fill_shape(vox, volume.dims, nested_balls, 777, 4);
}

static const vf_tf_point_t tf_pts[4] = {
    {0, 65535, 0, 0, 0}, {100 * 256, 65535, 40000, 0, 2500}, {160 * 256, 0, 65535, 20000, 200}, {230 * 256, 0, 0, 65535, 12000}};
static const vf_tf_t tf = {tf_pts, 4};

static uint64_t fnv1a(const unsigned char *p, size_t n)
{
    uint64_t h = 14695981039346656037u;
    for (size_t i = 0; i < n; i++)
        h = (h ^ p[i]) * 1099511628211u;
    return h;
}

static vf_status_t create(const vf_params_t *p, vf_arena_t *arena, vf_renderer_t **r)
{
    return scene_renderer(r, arena, arena_buf, sizeof arena_buf, p, &volume, &tf);
}

/* A frame of renderer r and its hash, else 0. */
static vf_status_t frame(vf_renderer_t *r, const vf_view_t *view, uint64_t *hash)
{
    vf_image_t im = {pixels, 48, 40, 48 * 3, VF_FORMAT_RGB888};
    vf_status_t s = VF_OK;
    *hash = 0;
#if VF_MAX_TABLE_PARTS > 1
    /* the whole core builds its table in 3 parts (the last first), the small core in begin */
    if (s == VF_OK)
        s = begin_frame(r, view, im.width, im.height, 3, false);
    for (uint32_t part = vf_renderer_table_parts(r); s == VF_OK && part-- > 0;)
        s = vf_renderer_build_table_part(r, part, scratch, sizeof scratch);
#else
    if (s == VF_OK)
        s = begin_frame(r, view, im.width, im.height, 0, false);
#endif
    if (s == VF_OK)
        s = vf_renderer_composite_band(r, 0, vf_renderer_factor(r)->int_h, scratch, sizeof scratch);
    if (s == VF_OK)
        s = vf_renderer_warp_band(r, &im, 0, im.height);
    if (s == VF_OK)
        *hash = fnv1a(pixels, sizeof pixels);
    return s;
}

/* A renderer's status with these parameters, and (when it renders) its frame's hash, else 0. */
static vf_status_t render(const vf_params_t *p, const vf_view_t *view, uint64_t *hash)
{
    vf_arena_t arena;
    vf_renderer_t *r = NULL;
    vf_status_t s = create(p, &arena, &r);
    *hash = 0;
    return s == VF_OK ? frame(r, view, hash) : s;
}

/* One renderer through a turn of 6 views (each a slab length of its own) with a new transfer function after the
 * third: the tables must follow (with the lut, the whole core's view table is corrected again each view and
 * rebuilt with the function, the small core corrects each segment). */
static void turn(vf_mode_t mode, vf_correction_t correction, uint32_t table_bits)
{
    vf_params_t p;
    vf_params_default(&p);
    p.mode = mode;
    p.correction = correction;
    p.table_bits = table_bits;
    p.table_size = 96;
    vf_arena_t arena;
    vf_renderer_t *r = NULL;
    vf_status_t s = create(&p, &arena, &r);
    static const vf_tf_point_t other_pts[3] = {{0, 0, 0, 0, 0}, {120 * 256, 65535, 30000, 10000, 9000}, {255 * 256, 0, 65535, 65535, 30000}};
    const vf_tf_t other = {other_pts, 3};
    for (int k = 0; k < 6; k++) {
        const vf_view_t view = {(int32_t)(k * 2900), 1500 + k * 700, 0, 65536};
        uint64_t h = 0;
        if (s == VF_OK && k == 3)
            s = vf_renderer_set_tf(r, &other);
        if (s == VF_OK)
            s = frame(r, &view, &h);
        printf("%s %s %u-bit turn view %d: %s %016llx\n", vf_mode_name(mode), vf_correction_name(correction),
               table_bits, k, vf_status_text(s), (unsigned long long)h);
    }
}

static const char *status_name(vf_status_t s)
{
    return s == VF_OK ? "VF_OK" : s == VF_ERR_UNSUPPORTED ? "VF_ERR_UNSUPPORTED" : vf_status_text(s);
}

/* A 16-entry table built by the brute-force oracle */
static vf_status_t oracle_table(void)
{
    static unsigned char scratch[1 << 16];
    static uint16_t table[16 * 16 * 4];
    const vf_tf_point_t points[2] = {{0, 0, 0, 0, 0}, {255 << 8, 65535, 65535, 65535, 32768}};
    vf_tf_t tf = {points, 2};
    vf_arena_t arena;
    vf_arena_init(&arena, scratch, sizeof scratch);
    return vf_table_preint(&tf, 16, 65536, VF_BUILDER_BRUTEFORCE, &arena, table);
}

int main(void)
{
    fill_volume();
    const vf_view_t views[3] = {{1000, 2000, 300, 65536}, {16384, 500, 0, 65536}, {5000, 14000, 2000, 80000}};
    vf_params_t p;
    uint64_t h;

    vf_params_default(&p);
    p.rays = 2;
    printf("rays 2: %s\n", status_name(render(&p, &views[0], &h)));
    vf_params_default(&p);
    p.partial_slabs = 1;
    printf("partial slabs: %s\n", status_name(render(&p, &views[0], &h)));
    printf("brute-force table: %s\n", status_name(oracle_table()));
    vf_params_default(&p);
    p.mode = VF_MODE_PREINT2;
    p.table2_size = 32;
    printf("preint2: %s\n", status_name(render(&p, &views[0], &h)));

    /* the modes and lookups both builds have (preint2 and its trilinear lookup: above) */
    for (int mode = 0; mode <= VF_MODE_PRECLASS; mode++)
        for (int lookup = 0; lookup <= VF_LOOKUP_BILINEAR; lookup++)
            for (int correction = 0; correction < 2; correction++)
                for (int v = 0; v < 3; v++) {
                    vf_params_default(&p);
                    p.mode = (vf_mode_t)mode;
                    p.lookup = (vf_lookup_t)lookup;
                    p.correction = correction ? VF_CORRECTION_LUT : VF_CORRECTION_REBUILD;
                    p.table_size = 128;
                    vf_status_t s = render(&p, &views[v], &h);
                    printf("%s %s %s view %d: %s %016llx\n", vf_mode_name(p.mode), vf_lookup_name(p.lookup),
                           vf_correction_name(p.correction), v, vf_status_text(s), (unsigned long long)h);
                }
    for (int mode = 0; mode <= VF_MODE_PRECLASS; mode++)
        for (int correction = 0; correction < 2; correction++)
            for (uint32_t bits = 8; bits <= 16; bits += 8)
                turn((vf_mode_t)mode, correction ? VF_CORRECTION_LUT : VF_CORRECTION_REBUILD, bits);
    return 0;
}
