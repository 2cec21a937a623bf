/* SPDX-License-Identifier: MIT */
/*
 * gen_scene.c: a host program that writes the firmware's scene as a C header.
 *
 *   gen_scene VOLUME [volfix-sim render options] [--band-rows N] [--prebuilt] -o scene.h
 *
 * It takes exactly the scene options of `volfix-sim render` and loads the scene with the same code
 * (sim_parse, sim_scene_load: the port's volume reader, default window, preset or transfer-function file,
 * degrees to binary angle units), so the firmware starts from the very inputs the host renders: the voxels,
 * dimensions, spacing, window, transfer-function points, parameters, view, size and format. Everything after
 * that, the window, classification, tables, factorisation, compositing and warp, is the core's work on the
 * target. The header also carries the memory sizes the firmware's static buffers need, measured here with the
 * core's own size queries (a 64-bit host's figures are upper bounds for a 32-bit target: only the renderer
 * struct differs, by its pointers); the firmware checks them again with the target's figures.
 *
 * With --prebuilt it also does on the host what the core would do on the target for this window and transfer
 * function (the slices of the three axes, with lighting their normals, the run lists: vf_renderer_export) and
 * writes them beside the header as SCENE_data.bin, with SCENE_data.S placing them in the firmware's read-only
 * memory (.incbin, one symbol an array), for vf_renderer_create_prebuilt; the arena is then measured for a
 * renderer over that storage, with an intermediate image for this view only. Without it SCENE_data.S is empty.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "options.h"
#include "scene.h"

static const char usage_head[] =
    "usage: gen_scene VOLUME [options] [--band-rows N] -o SCENE.h\n"
    "Write the scene of `volfix-sim render VOLUME [options]` as a C header for the mps2-an386 firmware.\n\n"
    "  -o FILE              the header to write\n"
    "  --band-rows N        intermediate rows the firmware composites per band (default 8): its scratch\n"
    "                       buffer is sized for that many\n"
    "  --arena-bytes N      give the firmware an arena of N bytes instead of the measured size (to test\n"
    "                       that a short arena ends in VF_ERR_NOMEM)\n"
    "  --prebuilt           build the slices, normals and run lists here, into the firmware's read-only memory\n"
    "                       (SCENE_data.bin, SCENE_data.S), for vf_renderer_create_prebuilt\n";

/* The prebuilt arrays as the firmware names them: symbol, C element type, element size. */
typedef struct blob {
    char name[32];
    const char *ctype;
    size_t elem, count;
    const void *data;
} blob_t;
#define MAX_BLOBS 20

static void add_blob(blob_t *b, size_t *n, const char *name, int axis, const char *ctype, size_t elem, size_t count,
                     const void *data)
{
    if (axis >= 0)
        snprintf(b[*n].name, sizeof b[*n].name, "%s%d", name, axis);
    else
        snprintf(b[*n].name, sizeof b[*n].name, "%s", name);
    b[*n].ctype = ctype;
    b[*n].elem = elem;
    b[*n].count = count;
    b[*n].data = data;
    (*n)++;
}

static size_t prebuilt_blobs(const vf_prebuilt_t *p, blob_t *b)
{
    size_t n = 0;
    for (int a = 0; a < 3; a++) {
        add_blob(b, &n, "scene_slices", a, "uint8_t", 1, p->slice_count[a], p->slices[a]);
        add_blob(b, &n, "scene_row_start", a, "uint32_t", 4, p->row_count[a], p->row_start[a]);
        add_blob(b, &n, "scene_pairs", a, "uint16_t", 2, p->pair_count[a], p->pairs[a]);
        if (p->codes[a]) {
            add_blob(b, &n, "scene_codes", a, "uint16_t", 2, p->slice_count[a], p->codes[a]);
            add_blob(b, &n, "scene_magnitudes", a, "uint8_t", 1, p->slice_count[a], p->magnitudes[a]);
        }
    }
    if (p->unit)
        add_blob(b, &n, "scene_unit", -1, "int32_t", 4, p->unit_count, p->unit);
    add_blob(b, &n, "scene_visible_from", -1, "uint16_t", 2, 256, p->visible_from);
    return n;
}

static void emit_voxels(FILE *f, const vf_volume_t *v)
{
    static const char *const ctype[] = {"uint8_t", "int8_t", "uint16_t", "int16_t"};
    const size_t n = (size_t)v->dims[0] * v->dims[1] * v->dims[2];
    fprintf(f, "static const %s scene_voxels[%zu] = {", ctype[v->type], n);
    for (size_t i = 0; i < n; i++) {
        long value = v->type == VF_VOXEL_U8    ? ((const uint8_t *)v->voxels)[i]
                     : v->type == VF_VOXEL_I8  ? ((const int8_t *)v->voxels)[i]
                     : v->type == VF_VOXEL_U16 ? ((const uint16_t *)v->voxels)[i]
                                               : ((const int16_t *)v->voxels)[i];
        fprintf(f, "%s%ld,", i % 24 ? "" : "\n    ", value);
    }
    fprintf(f, "\n};\n\n");
}

/* Host sizes: the arena the renderer needs with its run lists for this transfer function, and a band's
 * scratch. Returns 0, or 2 with err. */
/* Set the scene's window, transfer function and lighting on r. */
static vf_status_t set_scene(vf_renderer_t *r, const sim_scene_t *s)
{
    vf_status_t st = vf_renderer_set_window(r, s->window);
    if (st == VF_OK) {
        vf_tf_t tf = {s->points, s->npoints};
        st = vf_renderer_set_tf(r, &tf);
    }
    if (st == VF_OK && s->params.lighting)
        st = vf_renderer_set_lighting(r, &s->lighting);
    return st;
}

/* --prebuilt: a renderer on the host with the scene's window, transfer function and lighting (*host, in *buffer,
 * both the caller's to free), what it built (*pre) and the intermediate image of the scene's view; then the arena
 * and band scratch of a renderer over that storage, its arena's high-water mark included, and the arena the run
 * lists of this transfer function take when encoded there (what changing it needs more). Returns 0, or 2 with err. */
static int measure_prebuilt(const sim_scene_t *s, uint32_t band_rows, vf_prebuilt_t *pre, void **buffer,
                            size_t *arena_bytes, size_t *scratch_bytes, size_t *runs_bytes, char *err, size_t errlen)
{
    size_t bytes = 0;
    vf_status_t st = vf_renderer_bytes(&s->params, &s->vol.core, &bytes);
    size_t guess = bytes + 3 * (size_t)(s->vol.core.dims[0] + 1) * (s->vol.core.dims[1] + 1) *
                               (s->vol.core.dims[2] + 1) * 4;
    *buffer = st == VF_OK ? malloc(guess) : NULL;
    vf_arena_t arena, arena2;
    vf_renderer_t *r = NULL, *r2 = NULL;
    void *buffer2 = NULL;
    if (st == VF_OK && !*buffer)
        st = VF_ERR_NOMEM;
    if (st == VF_OK) {
        vf_arena_init(&arena, *buffer, guess);
        st = vf_renderer_create(&r, &s->params, &s->vol.core, &arena);
    }
    if (st == VF_OK)
        st = set_scene(r, s);
    const vf_frame_t frame = {.view = s->view, .width = s->width, .height = s->height};
    if (st == VF_OK)
        st = vf_renderer_begin(r, &frame);
    if (st == VF_OK)
        st = vf_renderer_export(r, pre);
    if (st == VF_OK) {
        const vf_factor_t *f = vf_renderer_factor(r);
        pre->intermediate_pixels = f->int_w * f->int_h;
        vf_memory_t m;
        vf_renderer_memory(r, &m);
        *runs_bytes = m.runs;
        st = vf_renderer_prebuilt_bytes(&s->params, &s->vol.core, pre, &bytes);
    }
    buffer2 = st == VF_OK ? malloc(bytes + 4096) : NULL;
    if (st == VF_OK && !buffer2)
        st = VF_ERR_NOMEM;
    if (st == VF_OK) {
        vf_arena_init(&arena2, buffer2, bytes + 4096);
        st = vf_renderer_create_prebuilt(&r2, &s->params, &s->vol.core, pre, &arena2);
    }
    if (st == VF_OK)
        st = set_scene(r2, s);
    if (st == VF_OK)
        st = vf_renderer_begin(r2, &frame);
    if (st == VF_OK) {
        *arena_bytes = vf_renderer_needed_bytes(r2) > arena2.peak ? vf_renderer_needed_bytes(r2) : arena2.peak;
        *scratch_bytes = vf_renderer_band_scratch_bytes(r2, band_rows);
    }
    free(buffer2);
    if (st != VF_OK) {
        snprintf(err, errlen, "measuring the prebuilt scene: %s", vf_status_text(st));
        return 2;
    }
    return 0;
}

/* SCENE_data.bin with the blobs one after another, each 4-byte aligned, and SCENE_data.S, which places each in
 * .rodata under its name (path: the header's; NULL blobs: an empty .S). Returns 0, or 2 with err. */
static int write_blobs(const char *header, const blob_t *b, size_t n, char *err, size_t errlen)
{
    char bin[4096], as[4096];
    size_t base = strlen(header) > 2 && strcmp(header + strlen(header) - 2, ".h") == 0 ? strlen(header) - 2
                                                                                        : strlen(header);
    snprintf(bin, sizeof bin, "%.*s_data.bin", (int)base, header);
    snprintf(as, sizeof as, "%.*s_data.S", (int)base, header);
    FILE *fb = n ? fopen(bin, "wb") : NULL, *fs = fopen(as, "w");
    int status = (n && !fb) || !fs;
    if (fs)
        fprintf(fs, "/* %s: written by boards/mps2-an386/gen_scene; do not edit. */\n", as);
    size_t at = 0;
    for (size_t i = 0; i < n && !status; i++) {
        static const unsigned char zero[4] = {0};
        const size_t bytes = b[i].elem * b[i].count, pad = (4 - bytes % 4) % 4;
        status = fwrite(b[i].data, 1, bytes, fb) != bytes || fwrite(zero, 1, pad, fb) != pad;
        fprintf(fs, "    .section .rodata.%s, \"a\"\n    .balign 4\n    .global %s\n%s:\n    .incbin \"%s\", %zu, %zu\n",
                b[i].name, b[i].name, b[i].name, bin, at, bytes);
        at += bytes + pad;
    }
    if (fb && fclose(fb) != 0)
        status = 1;
    if (fs && fclose(fs) != 0)
        status = 1;
    if (status) {
        snprintf(err, errlen, "%.200s, %.200s: cannot write", bin, as);
        return 2;
    }
    return 0;
}

static int measure(const sim_scene_t *s, uint32_t band_rows, size_t *arena_bytes, size_t *scratch_bytes,
                   char *err, size_t errlen)
{
    size_t bytes = 0;
    vf_status_t st = vf_renderer_bytes(&s->params, &s->vol.core, &bytes);
    /* the run lists are at most two values per cell and a row index per axis: a first guess that
     * vf_renderer_needed_bytes then corrects */
    size_t guess = bytes + 3 * (size_t)(s->vol.core.dims[0] + 1) * (s->vol.core.dims[1] + 1) *
                               (s->vol.core.dims[2] + 1) * 4;
    void *buffer = st == VF_OK ? malloc(guess) : NULL;
    vf_arena_t arena;
    vf_renderer_t *r = NULL;
    if (st == VF_OK && !buffer)
        st = VF_ERR_NOMEM;
    if (st == VF_OK) {
        vf_arena_init(&arena, buffer, guess);
        st = vf_renderer_create(&r, &s->params, &s->vol.core, &arena);
    }
    if (st == VF_OK)
        st = vf_renderer_set_window(r, s->window);
    if (st == VF_OK) {
        vf_tf_t tf = {s->points, s->npoints};
        st = vf_renderer_set_tf(r, &tf);
    }
    if (st == VF_OK && s->params.lighting)
        st = vf_renderer_set_lighting(r, &s->lighting);
    if (st == VF_OK) {
        *arena_bytes = vf_renderer_needed_bytes(r);
        if (*arena_bytes < arena.peak)
            *arena_bytes = arena.peak;
        const vf_frame_t frame = {.view = s->view, .width = s->width, .height = s->height};
        st = vf_renderer_begin(r, &frame);
        /* the band height is fixed, so the scratch a band needs does not depend on the view */
        *scratch_bytes = vf_renderer_band_scratch_bytes(r, band_rows);
    }
    free(buffer);
    if (st != VF_OK) {
        snprintf(err, errlen, "measuring the scene: %s", vf_status_text(st));
        return 2;
    }
    return 0;
}

static int write_header(const char *path, const sim_scene_t *s, uint32_t band_rows, size_t arena_bytes,
                        size_t scratch_bytes, int arena_override, const vf_prebuilt_t *pre, size_t runs_bytes,
                        char *err, size_t errlen)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        snprintf(err, errlen, "%s: cannot write", path);
        return 2;
    }
    char about[512];
    sim_scene_describe(s, about, sizeof about);
    const vf_volume_t *v = &s->vol.core;
    const vf_params_t *p = &s->params;
    fprintf(f, "/* scene.h: written by boards/mps2-an386/gen_scene; do not edit.\n * %s */\n", about);
    fprintf(f, "#include \"volfix.h\"\n\n");
    fprintf(f, "#define SCENE_ABOUT \"%s\"\n", about);
    fprintf(f, "#define SCENE_WIDTH %uu\n#define SCENE_HEIGHT %uu\n", s->width, s->height);
    fprintf(f, "#define SCENE_FORMAT %d /* vf_format_t */\n#define SCENE_PIXEL_BYTES %uu\n", (int)s->format,
            vf_format_bytes(s->format));
    fprintf(f, "#define SCENE_BAND_ROWS %uu\n", band_rows);
    fprintf(f, "/* %s on the host with the core's size queries; the firmware checks them on the target */\n",
            arena_override ? "arena given with --arena-bytes, scratch measured" : "measured");
    fprintf(f, "#define SCENE_ARENA_BYTES %zuu\n#define SCENE_SCRATCH_BYTES %zuu\n\n", arena_bytes, scratch_bytes);
    emit_voxels(f, v);
    fprintf(f, "#define SCENE_PREBUILT %d\n", pre != NULL);
    if (pre) {
        blob_t b[MAX_BLOBS];
        const size_t n = prebuilt_blobs(pre, b);
        fprintf(f, "/* what the core would build for this window and transfer function, made on the host and placed in\n"
                   " * read-only memory by scene_data.S; changing the transfer function encodes run lists in the arena,\n"
                   " * this one's %zu bytes on the host */\n#define SCENE_RUNS_BYTES %zuu\n",
                runs_bytes, runs_bytes);
        for (size_t i = 0; i < n; i++)
            fprintf(f, "extern const %s %s[%zu];\n", b[i].ctype, b[i].name, b[i].count);
        fprintf(f, "static const vf_prebuilt_t scene_prebuilt = {\n    .window = {%d, %d},\n", pre->window.lo,
                pre->window.hi);
        fprintf(f, "    .slices = {scene_slices0, scene_slices1, scene_slices2},\n"
                   "    .slice_count = {%zu, %zu, %zu},\n", pre->slice_count[0], pre->slice_count[1],
                pre->slice_count[2]);
        if (pre->unit)
            fprintf(f, "    .codes = {scene_codes0, scene_codes1, scene_codes2},\n"
                       "    .magnitudes = {scene_magnitudes0, scene_magnitudes1, scene_magnitudes2},\n"
                       "    .unit = scene_unit, .unit_count = %zu,\n", pre->unit_count);
        fprintf(f, "    .visible_from = scene_visible_from,\n"
                   "    .row_start = {scene_row_start0, scene_row_start1, scene_row_start2},\n"
                   "    .row_count = {%zu, %zu, %zu},\n"
                   "    .pairs = {scene_pairs0, scene_pairs1, scene_pairs2},\n"
                   "    .pair_count = {%zu, %zu, %zu},\n"
                   "    .intermediate_pixels = %uu,\n};\n",
                pre->row_count[0], pre->row_count[1], pre->row_count[2], pre->pair_count[0], pre->pair_count[1],
                pre->pair_count[2], pre->intermediate_pixels);
    }
    fprintf(f, "static const vf_volume_t scene_volume = {{%u, %u, %u}, {%u, %u, %u}, %d, scene_voxels};\n",
            v->dims[0], v->dims[1], v->dims[2], v->spacing_q16[0], v->spacing_q16[1], v->spacing_q16[2],
            (int)v->type);
    fprintf(f, "static const vf_window_t scene_window = {%d, %d};\n", s->window.lo, s->window.hi);
    fprintf(f, "static const vf_tf_point_t scene_tf_points[%u] = {\n", s->npoints);
    for (uint32_t i = 0; i < s->npoints; i++)
        fprintf(f, "    {%u, %u, %u, %u, %u},\n", s->points[i].scalar_q8, s->points[i].r, s->points[i].g,
                s->points[i].b, s->points[i].a);
    fprintf(f, "};\n");
    fprintf(f, "static const vf_view_t scene_view = {%d, %d, %d, %uu};\n", s->view.azimuth, s->view.elevation,
            s->view.roll, s->view.zoom_q16);
    fprintf(f, "static const vf_params_t scene_params = {\n"
               "    .mode = %d, .table_size = %u, .table_bits = %u, .lookup = %d, .correction = %d,\n"
               "    .buffer = %d, .rays = %u, .partial_slabs = %d, .background = {%u, %u, %u},\n"
               "    .sample_bits = %u, .intermediate_bits = %u, .warp_bits = %u,\n"
               "    .lighting = %d, .normal_bits = %u, .shade_lookup = %d, .table2_size = %u,\n};\n",
            (int)p->mode, p->table_size, p->table_bits, (int)p->lookup, (int)p->correction, (int)p->buffer,
            p->rays, (int)p->partial_slabs, p->background[0], p->background[1], p->background[2], p->sample_bits,
            p->intermediate_bits, p->warp_bits, (int)p->lighting, p->normal_bits, (int)p->shade_lookup,
            p->table2_size);
    /* the lighting vf_renderer_set_lighting takes after the transfer function, as volfix-sim render sets it
     * (host-sim/scene.c, sim_core_lighting); only for a renderer made with params.lighting */
    const vf_lighting_t *l = &s->lighting;
    fprintf(f, "#define SCENE_LIGHTING %d\n", (int)p->lighting);
    if (p->lighting)
        fprintf(f, "static const vf_lighting_t scene_lighting = {\n"
                   "    .shade = %d, .light_count = %uu, .lights = {{%d, %d}, {%d, %d}},\n"
                   "    .ka = %u, .kd = %u, .ks = %u, .shininess = %u, .gradient_lo = %u, .gradient_hi = %u,\n};\n",
                (int)l->shade, l->light_count, l->lights[0].azimuth, l->lights[0].elevation, l->lights[1].azimuth,
                l->lights[1].elevation, l->ka, l->kd, l->ks, l->shininess, l->gradient_lo, l->gradient_hi);
    if (fclose(f) != 0) {
        snprintf(err, errlen, "%s: write failed", path);
        return 2;
    }
    return 0;
}

int main(int argc, char **argv)
{
    /* --band-rows and --arena-bytes are ours; everything else goes to volfix-sim's own parser */
    long band_rows = 8, arena_override = 0;
    int n = 0, prebuilt = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--prebuilt") == 0) {
            prebuilt = 1;
            continue;
        }
        long *value = strcmp(argv[i], "--band-rows") == 0     ? &band_rows
                      : strcmp(argv[i], "--arena-bytes") == 0 ? &arena_override
                                                              : NULL;
        if (!value) {
            argv[++n] = argv[i];
            continue;
        }
        char *end = NULL;
        *value = i + 1 < argc ? strtol(argv[i + 1], &end, 10) : 0;
        if (!end || *end || *value < 1 || *value > (value == &band_rows ? 65535 : 0x7FFFFFFF)) {
            fprintf(stderr, "gen_scene: %s %s: expected a positive number%s\n", argv[i], i + 1 < argc ? argv[i + 1] : "",
                    value == &band_rows ? " up to 65535" : "");
            return 2;
        }
        i++;
    }
    char usage[4096], err[VFP_ERR_LEN];
    snprintf(usage, sizeof usage, "%s%s", usage_head, sim_scene_help);
    sim_opts_t o;
    int status = sim_parse(&o, n, argv + 1, SIM_OPT_SCENE | SIM_OPT_OUT, usage);
    if (status)
        return status == 1 ? 0 : 2;
    if (!o.out) {
        fprintf(stderr, "gen_scene: no output file (-o SCENE.h)\n");
        return 2;
    }
    sim_scene_t scene;
    if (sim_scene_load(&scene, &o, err, sizeof err)) {
        fprintf(stderr, "gen_scene: %s\n", err);
        return 2;
    }
    size_t arena_bytes = 0, scratch_bytes = 0, runs_bytes = 0;
    vf_prebuilt_t pre;
    void *host_arena = NULL; /* the host renderer's, which the prebuilt arrays point into */
    if (prebuilt)
        status = measure_prebuilt(&scene, (uint32_t)band_rows, &pre, &host_arena, &arena_bytes, &scratch_bytes,
                                  &runs_bytes, err, sizeof err);
    else
        status = measure(&scene, (uint32_t)band_rows, &arena_bytes, &scratch_bytes, err, sizeof err);
    if (arena_override)
        arena_bytes = (size_t)arena_override;
    if (status == 0)
        status = write_header(o.out, &scene, (uint32_t)band_rows, arena_bytes, scratch_bytes, arena_override != 0,
                              prebuilt ? &pre : NULL, runs_bytes, err, sizeof err);
    if (status == 0) {
        blob_t b[MAX_BLOBS];
        status = write_blobs(o.out, b, prebuilt ? prebuilt_blobs(&pre, b) : 0, err, sizeof err);
    }
    free(host_arena);
    if (status)
        fprintf(stderr, "gen_scene: %s\n", err);
    sim_scene_free(&scene);
    return status;
}
