/* SPDX-License-Identifier: MIT */
/*
 * test_lighting.c: lighting's parts in the core (docs/algorithm.md, section 7; core/normals.c, shade.c), each
 * against the section written out here in double: normal codes and their unit normals, gradients and magnitudes of
 * a volume, the shade table, the gradient ramp; and lit frames through the public API: a lit sphere is brightest
 * where it faces the light, unlit frames of a lighting renderer equal a plain renderer's to the bit, and every
 * argument error of vf_renderer_set_lighting.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "frame.h"
#include "normals.h"
#include "shade.h"
#include "volfix.h"

#define PI 3.14159265358979323846

static uint64_t seed = 0x5EEDF00Du;

/* ---- section 7 in double ------------------------------------------------------------------------------ */

static double sg(double t)
{
    return t >= 0 ? 1.0 : -1.0;
}

/* the unit normal of a code, as section 7 defines it */
static void decode_double(uint32_t code, uint32_t levels, double n[3])
{
    const double span = levels - 1.0;
    double px = 2.0 * (code % levels) / span - 1.0, py = 2.0 * (code / levels) / span - 1.0;
    double pz = 1.0 - fabs(px) - fabs(py);
    if (pz < 0) {
        const double ox = px, oy = py;
        px = sg(ox) * (1.0 - fabs(oy));
        py = sg(oy) * (1.0 - fabs(ox));
    }
    const double len = sqrt(px * px + py * py + pz * pz);
    n[0] = px / len, n[1] = py / len, n[2] = pz / len;
}

static double angle_between(const double a[3], const double b[3])
{
    const double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    double c = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb);
    return acos(c > 1 ? 1 : c < -1 ? -1 : c);
}

/* ---- normal codes -------------------------------------------------------------------------------------- */

/* Every code decodes to a unit vector within 2^-24 of section 7's, and a direction's code is the nearest code to
 * within the octahedron's cell: the decoded normal is at most about one cell (2 / (L - 1) of the map) from it. */
static void codes_and_units(void)
{
    for (uint32_t bits = 8; bits <= 16; bits += 2) {
        const uint32_t levels = vfi_normal_levels(bits), count = vfi_normal_code_count(levels);
        int32_t *unit = malloc(sizeof(int32_t) * 3 * count);
        CHECK(unit);
        vfi_normals_decode(levels, unit);
        double worst = 0;
        for (uint32_t code = 0; code + 1 < count; code++) {
            double n[3];
            decode_double(code, levels, n);
            for (int a = 0; a < 3; a++)
                worst = fmax(worst, fabs(unit[code * 3 + a] / 1073741824.0 - n[a]));
        }
        CHECK_MSG(worst <= 1.0 / 16777216.0, "%u bits: unit normals %g off", bits, worst);
        CHECK(unit[(count - 1) * 3] == 0 && unit[(count - 1) * 3 + 1] == 0 && unit[(count - 1) * 3 + 2] == 0);
        /* random directions, and their codes' normals */
        double worst_angle = 0;
        for (int t = 0; t < 20000; t++) {
            int64_t g[3];
            for (int a = 0; a < 3; a++)
                g[a] = (int64_t)check_below(&seed, 1u << 30) - (1 << 29);
            const uint32_t code = vfi_normal_code(g[0], g[1], g[2], levels);
            CHECK(code + 1 < count);
            double n[3], gd[3] = {(double)g[0], (double)g[1], (double)g[2]};
            decode_double(code, levels, n);
            worst_angle = fmax(worst_angle, angle_between(n, gd));
        }
        /* a cell of the map is 2 / (L - 1) a side; its half diagonal, stretched by up to 3 where the octahedron
         * folds (measured: 2.9 at 8 bits, in angle over the map's distance) */
        const double bound = 3.2 * 2.0 / (levels - 1) * sqrt(2.0) / 2;
        printf("# %u bits: worst angle %.3f degrees\n", bits, worst_angle * 180 / PI);
        CHECK_MSG(worst_angle <= bound, "%u bits: a code's normal %.3f degrees from its gradient (bound %.3f)", bits,
                  worst_angle * 180 / PI, bound * 180 / PI);
        free(unit);
    }
}

/* The axes and the zero gradient, exactly; and the code of a gradient does not depend on its length. */
static void codes_exact(void)
{
    const uint32_t levels = vfi_normal_levels(14), half = (levels - 1) / 2;
    CHECK_EQ(vfi_normal_code(0, 0, 0, levels), levels * levels);
    CHECK_EQ(vfi_normal_code(0, 0, 5, levels), half * levels + half);             /* +z: the centre */
    CHECK_EQ(vfi_normal_code(7, 0, 0, levels), half * levels + (levels - 1));     /* +x */
    CHECK_EQ(vfi_normal_code(-7, 0, 0, levels), half * levels);                   /* -x */
    CHECK_EQ(vfi_normal_code(0, 3, 0, levels), (levels - 1) * levels + half);     /* +y */
    CHECK_EQ(vfi_normal_code(0, 0, -1, levels), vfi_normal_code(0, 0, -9, levels)); /* -z: a corner */
    for (int t = 0; t < 2000; t++) {
        const int64_t g[3] = {(int64_t)check_below(&seed, 2001) - 1000, (int64_t)check_below(&seed, 2001) - 1000,
                              (int64_t)check_below(&seed, 2001) - 1000};
        const uint32_t k = 1 + check_below(&seed, 1000);
        CHECK_EQ(vfi_normal_code(g[0], g[1], g[2], levels), vfi_normal_code(g[0] * k, g[1] * k, g[2] * k, levels));
    }
}

/* ---- a volume's normals --------------------------------------------------------------------------------- */

#define N 9
static uint16_t vox16[N * N * N];

/* Codes and magnitudes of a volume against section 7's central differences in double, on every copy: the copy
 * of axis k holds voxel (i, j, k) of its standard order at k * slice + j * row + i. */
static void volume_normals(void)
{
    for (uint32_t n = 0; n < N * N * N; n++)
        vox16[n] = (uint16_t)check_below(&seed, 60000);
    const uint32_t dims[3] = {N, N - 2, N - 1};
    const vf_volume_t vol = {{dims[0], dims[1], dims[2]}, {65536, 3 * 65536, 2 * 65536}, VF_VOXEL_U16, vox16};
    const uint32_t levels = vfi_normal_levels(12);
    uint16_t *codes[3];
    uint8_t *mags[3];
    for (int a = 0; a < 3; a++) {
        codes[a] = malloc(sizeof(uint16_t) * vfi_slices_bytes(dims, a));
        mags[a] = malloc(vfi_slices_bytes(dims, a));
        CHECK(codes[a] && mags[a]);
    }
    vfi_normals_build(&vol, levels, codes, mags);
    /* G and m in double from section 7 */
    static double m[N * N * N];
    static uint32_t code_of[N * N * N];
    double most = 0;
    const double sp[3] = {1, 3, 2};
    for (uint32_t z = 0; z < dims[2]; z++)
        for (uint32_t y = 0; y < dims[1]; y++)
            for (uint32_t x = 0; x < dims[0]; x++) {
                const uint32_t p[3] = {x, y, z};
                const size_t stride[3] = {1, dims[0], (size_t)dims[0] * dims[1]}, at = x + stride[1] * y + stride[2] * z;
                int64_t g[3];
                for (int a = 0; a < 3; a++) {
                    const int down = p[a] > 0, up = p[a] + 1 < dims[a];
                    const int64_t d = (int64_t)vox16[up ? at + stride[a] : at] - vox16[down ? at - stride[a] : at];
                    const int64_t q = (int64_t)floor(16384.0 / ((down + up) * sp[a]) + 0.5);
                    g[a] = d * q;
                }
                m[at] = floor(sqrt((double)g[0] * g[0] + (double)g[1] * g[1] + (double)g[2] * g[2]));
                most = fmax(most, m[at]);
                code_of[at] = vfi_normal_code(g[0], g[1], g[2], levels);
            }
    for (int k = 0; k < 3; k++) {
        vfi_layout_t l;
        vfi_layout(dims, k, &l);
        for (uint32_t kk = 0; kk < l.nk; kk++)
            for (uint32_t j = 0; j < l.nj; j++)
                for (uint32_t i = 0; i < l.ni; i++) {
                    uint32_t p[3];
                    p[l.i_axis] = i, p[l.j_axis] = j, p[k] = kk;
                    const size_t at = p[0] + (size_t)dims[0] * (p[1] + (size_t)dims[1] * p[2]);
                    const size_t in_copy = (size_t)kk * l.slice + (size_t)j * l.row + i;
                    CHECK_EQ(codes[k][in_copy], code_of[at]);
                    CHECK_EQ(mags[k][in_copy], (uint32_t)floor(255 * m[at] / most + 0.5));
                }
    }
    for (int a = 0; a < 3; a++)
        free(codes[a]), free(mags[a]);
}

/* ---- the shade table ------------------------------------------------------------------------------------ */

static void rotation_double(double az, double el, double roll, double r[3][3])
{
    const double ry[3][3] = {{cos(az), 0, sin(az)}, {0, 1, 0}, {-sin(az), 0, cos(az)}};
    const double rx[3][3] = {{1, 0, 0}, {0, cos(el), -sin(el)}, {0, sin(el), cos(el)}};
    const double rz[3][3] = {{cos(roll), -sin(roll), 0}, {sin(roll), cos(roll), 0}, {0, 0, 1}};
    double rxy[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            rxy[i][j] = 0;
            for (int k = 0; k < 3; k++)
                rxy[i][j] += rx[i][k] * ry[k][j];
        }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            r[i][j] = 0;
            for (int k = 0; k < 3; k++)
                r[i][j] += rz[i][k] * rxy[k][j];
        }
}

static double bau_rad(int32_t bau)
{
    return bau * 2 * PI / 65536;
}

/* Section 7's L_d and L_s of one code in double. */
static void shade_double(uint32_t code, uint32_t levels, const double r[3][3], const vf_lighting_t *l, double *ld,
                         double *ls)
{
    const double ka = l->ka / 65535.0, kd = l->kd / 65535.0, ks = l->ks / 65535.0;
    if (code == levels * levels) {
        *ld = ka, *ls = 0;
        return;
    }
    double n[3], m[3];
    decode_double(code, levels, n);
    for (int i = 0; i < 3; i++)
        m[i] = r[i][0] * n[0] + r[i][1] * n[1] + r[i][2] * n[2];
    if (m[2] > 0)
        for (int i = 0; i < 3; i++)
            m[i] = -m[i];
    double diffuse = 0, specular = 0;
    for (uint32_t k = 0; k < l->light_count; k++) {
        const double az = bau_rad(l->lights[k].azimuth), el = bau_rad(l->lights[k].elevation);
        const double lv[3] = {sin(az) * cos(el), -sin(el), -cos(az) * cos(el)};
        double h[3] = {lv[0], lv[1], lv[2] - 1};
        const double hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        for (int i = 0; i < 3; i++)
            h[i] = hl > 0 ? h[i] / hl : 0;
        diffuse += fmax(0, m[0] * lv[0] + m[1] * lv[1] + m[2] * lv[2]);
        specular += pow(fmax(0, m[0] * h[0] + m[1] * h[1] + m[2] * h[2]), l->shininess);
    }
    *ld = ka + kd * diffuse;
    *ls = ks * specular;
}

/* Every code's L_d and L_s within 2 LSB of Q2.14 of section 7, for views, lights and materials at random. */
static void shade_table(void)
{
    const uint32_t levels = vfi_normal_levels(12), count = vfi_normal_code_count(levels);
    int32_t *unit = malloc(sizeof(int32_t) * 3 * count);
    uint64_t *shade = malloc(sizeof(uint64_t) * count);
    CHECK(unit && shade);
    vfi_normals_decode(levels, unit);
    for (int t = 0; t < 12; t++) {
        vf_view_t view = {(int32_t)check_below(&seed, 65536), (int32_t)check_below(&seed, 65536) - 32768,
                          (int32_t)check_below(&seed, 65536), 65536};
        vf_lighting_t l;
        vf_lighting_default(&l);
        l.light_count = 1 + (uint32_t)(t % 2);
        for (uint32_t k = 0; k < l.light_count; k++)
            l.lights[k] = (vf_light_t){(int32_t)check_below(&seed, 65536), (int32_t)check_below(&seed, 32768) - 16384};
        l.ka = (uint16_t)check_below(&seed, 65536), l.kd = (uint16_t)check_below(&seed, 65536);
        l.ks = (uint16_t)check_below(&seed, 65536), l.shininess = (uint16_t)(1 + check_below(&seed, 255));
        if (t == 0) /* a headlight */
            l.lights[0] = (vf_light_t){0, 0}, l.light_count = 1;
        int32_t rq[3][3];
        vfi_view_rotation(&view, rq);
        vfi_shade_table(rq, &l, unit, count, shade);
        double r[3][3];
        rotation_double(bau_rad(view.azimuth), bau_rad(view.elevation), bau_rad(view.roll), r);
        double worst = 0;
        for (uint32_t code = 0; code < count; code++) {
            double ld, ls;
            shade_double(code, levels, r, &l, &ld, &ls);
            worst = fmax(worst, fabs(vfi_shade_diffuse(shade[code]) - ld * 16384));
            worst = fmax(worst, fabs(vfi_shade_specular(shade[code]) - ls * 16384));
        }
        CHECK_MSG(worst <= 2.0, "case %d: the shade table is %.2f LSB of Q2.14 off (shininess %u)", t, worst,
                  l.shininess);
    }
    free(unit);
    free(shade);
}

static void gradient_ramp(void)
{
    uint16_t f[256];
    vfi_gradient_ramp(0, 0, f);
    for (int m = 0; m < 256; m++)
        CHECK_EQ(f[m], 32768);
    vfi_gradient_ramp(10, 30, f);
    for (int m = 0; m < 256; m++) {
        const double want = m <= 10 ? 0 : m >= 30 ? 1 : (m - 10) / 20.0;
        CHECK_MSG(fabs(f[m] - want * 32768) <= 0.5, "magnitude %d: %u", m, f[m]);
    }
}

/* ---- lit frames ----------------------------------------------------------------------------------------- */

#define S 24
static uint8_t sphere[S * S * S];
static _Alignas(16) unsigned char arena_buf[1 << 23];
static _Alignas(16) unsigned char scratch[1 << 20];
static unsigned char pixels[2][96 * 96 * 3];

static void make_sphere(void)
{
    for (int z = 0; z < S; z++)
        for (int y = 0; y < S; y++)
            for (int x = 0; x < S; x++) {
                const double d = sqrt((x - 11.5) * (x - 11.5) + (y - 11.5) * (y - 11.5) + (z - 11.5) * (z - 11.5));
                sphere[(z * S + y) * S + x] = (uint8_t)(d < 9 ? 200 : d < 10 ? 200 - 200 * (d - 9) : 0);
            }
}

static const vf_tf_point_t opaque_white[] = {{0, 65535, 65535, 65535, 0}, {100 << 8, 65535, 65535, 65535, 65535}};

/* One frame of the sphere; lighting NULL: a renderer without lighting. */
static vf_status_t draw_sphere(vf_mode_t mode, const vf_lighting_t *lighting, int unlit_frame, const vf_view_t *view,
                               unsigned char *out)
{
    const vf_volume_t vol = {{S, S, S}, {65536, 65536, 65536}, VF_VOXEL_U8, sphere};
    vf_params_t p;
    vf_params_default(&p);
    p.mode = mode;
    p.lighting = lighting != NULL;
    vf_arena_t arena;
    vf_arena_init(&arena, arena_buf, sizeof arena_buf);
    vf_renderer_t *r;
    const vf_tf_t tf = {opaque_white, 2};
    vf_status_t s = vf_renderer_create(&r, &p, &vol, &arena);
    if (s == VF_OK)
        s = vf_renderer_set_window(r, (vf_window_t){0, 255});
    if (s == VF_OK)
        s = vf_renderer_set_tf(r, &tf);
    if (s == VF_OK && lighting)
        s = vf_renderer_set_lighting(r, unlit_frame ? NULL : lighting);
    const vf_image_t im = {out, 96, 96, 96 * 3, VF_FORMAT_RGB888};
    if (s == VF_OK)
        s = vf_renderer_draw(r, view, &im, scratch, sizeof scratch);
    return s;
}

/* Lit by a headlight, an opaque white sphere is brightest in the middle and darker towards its rim, in every
 * order-0 mode; unlit it is flat. */
static void lit_sphere(void)
{
    make_sphere();
    const vf_view_t view = {0, 0, 0, 65536};
    vf_lighting_t l;
    vf_lighting_default(&l);
    const vf_mode_t modes[] = {VF_MODE_POINT, VF_MODE_PRECLASS};
    for (int m = 0; m < 2; m++) {
        CHECK_EQ(draw_sphere(modes[m], &l, 0, &view, pixels[0]), VF_OK);
        const unsigned char *centre = pixels[0] + (48 * 96 + 48) * 3, *rim = pixels[0] + (48 * 96 + 48 + 28) * 3;
        CHECK_MSG(centre[0] > 200 && rim[0] < centre[0] - 40, "mode %d: centre %u, near the rim %u", m, centre[0],
                  rim[0]);
        /* the brightness falls from the middle outwards along a row */
        for (int x = 52; x < 48 + 28; x += 4)
            CHECK_MSG(pixels[0][(48 * 96 + x) * 3] <= pixels[0][(48 * 96 + x - 4) * 3] + 2, "mode %d at x %d", m, x);
    }
}

/* A lighting renderer's unlit frames are a plain renderer's, to the bit. */
static void unlit_frames_unchanged(void)
{
    make_sphere();
    const vf_view_t view = {30 * 65536 / 360, 20 * 65536 / 360, 0, 65536};
    vf_lighting_t l;
    vf_lighting_default(&l);
    const vf_mode_t modes[] = {VF_MODE_POINT, VF_MODE_PRECLASS, VF_MODE_PREINT1};
    for (int m = 0; m < 3; m++) {
        CHECK_EQ(draw_sphere(modes[m], NULL, 0, &view, pixels[0]), VF_OK);
        CHECK_EQ(draw_sphere(modes[m], &l, 1, &view, pixels[1]), VF_OK);
        CHECK_MSG(memcmp(pixels[0], pixels[1], sizeof pixels[0]) == 0, "mode %d", m);
    }
}

/* Shading off but gradient opacity on: the sphere's flat inside (magnitude 0) goes, its shell stays. */
static void gradient_opacity(void)
{
    make_sphere();
    const vf_view_t view = {0, 0, 0, 65536};
    vf_lighting_t l;
    vf_lighting_default(&l);
    l.shade = false;
    CHECK_EQ(draw_sphere(VF_MODE_POINT, &l, 0, &view, pixels[0]), VF_OK);
    l.gradient_lo = 0, l.gradient_hi = 255;
    CHECK_EQ(draw_sphere(VF_MODE_POINT, &l, 0, &view, pixels[1]), VF_OK);
    const size_t centre = (48 * 96 + 48) * 3;
    CHECK_MSG(pixels[1][centre] < pixels[0][centre], "centre %u with gradient opacity, %u without", pixels[1][centre],
              pixels[0][centre]);
}

static void lighting_errors(void)
{
    make_sphere();
    const vf_volume_t vol = {{S, S, S}, {65536, 65536, 65536}, VF_VOXEL_U8, sphere};
    vf_params_t p;
    vf_params_default(&p);
    vf_arena_t arena;
    vf_arena_init(&arena, arena_buf, sizeof arena_buf);
    vf_renderer_t *r;
    CHECK_EQ(vf_renderer_create(&r, &p, &vol, &arena), VF_OK);
    vf_lighting_t l;
    vf_lighting_default(&l);
    CHECK_EQ(vf_renderer_set_lighting(r, &l), VF_ERR_UNSUPPORTED); /* created without lighting */
    CHECK_EQ(vf_renderer_set_lighting(NULL, &l), VF_ERR_NULL);
    vf_arena_init(&arena, arena_buf, sizeof arena_buf);
    p.lighting = true;
    CHECK_EQ(vf_renderer_create(&r, &p, &vol, &arena), VF_OK);
    CHECK_EQ(vf_renderer_set_lighting(r, &l), VF_OK);
    CHECK_EQ(vf_renderer_set_lighting(r, NULL), VF_OK);
    vf_lighting_t bad = l;
    bad.light_count = 0;
    CHECK_EQ(vf_renderer_set_lighting(r, &bad), VF_ERR_ARG);
    bad.light_count = VF_MAX_LIGHTS + 1;
    CHECK_EQ(vf_renderer_set_lighting(r, &bad), VF_ERR_ARG);
    bad = l, bad.shininess = 0;
    CHECK_EQ(vf_renderer_set_lighting(r, &bad), VF_ERR_ARG);
    bad = l, bad.shininess = 256;
    CHECK_EQ(vf_renderer_set_lighting(r, &bad), VF_ERR_ARG);
    bad = l, bad.gradient_lo = 9, bad.gradient_hi = 9;
    CHECK_EQ(vf_renderer_set_lighting(r, &bad), VF_ERR_ARG);
    /* normal bits and partial slabs */
    vf_params_t q = p;
    q.normal_bits = 13;
    size_t bytes;
    CHECK_EQ(vf_renderer_bytes(&q, &vol, &bytes), VF_ERR_ARG);
    q.normal_bits = 18;
    CHECK_EQ(vf_renderer_bytes(&q, &vol, &bytes), VF_ERR_ARG);
    q = p, q.partial_slabs = true;
    CHECK_EQ(vf_renderer_bytes(&q, &vol, &bytes), VF_ERR_UNSUPPORTED);
    /* memory: what lighting adds is reported */
    vf_memory_t mem;
    vf_renderer_memory(r, &mem);
    CHECK(mem.normals >= (size_t)S * S * S * 3 * 3);
}

CHECK_CASES({"codes and unit normals", codes_and_units}, {"codes exact", codes_exact},
            {"volume normals", volume_normals}, {"shade table", shade_table}, {"gradient ramp", gradient_ramp},
            {"lit sphere", lit_sphere}, {"unlit frames unchanged", unlit_frames_unchanged},
            {"gradient opacity", gradient_opacity}, {"lighting errors", lighting_errors});
CHECK_RUN("lighting")
