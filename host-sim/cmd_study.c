/* SPDX-License-Identifier: MIT */
/*
 * cmd_study.c: volfix-sim study: what to run. One factor at a time around the default configuration, and the
 * pairs that interact (table size with lookup; mode with smooth and sharp transfer functions; rays per voxel
 * column with the side-face rule and the table size), on Marschner-Lobb 41^3 above all, and the shared volumes
 * when they are there. --quick is the subset make test runs (under two minutes); the full study adds scenes,
 * volumes and views.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "commands.h"
#include "io/numbers.h"
#include "study.h"

static const char usage[] =
    "usage: volfix-sim study [--quick] [--lighting-only | --order2-only] -o DIR [--threads N]\n"
    "The fixed-point precision study. Renders scenes with the core in many configurations and measures each\n"
    "against the double reference of the same algorithm (the fixed-point error alone) and against the ground\n"
    "truth ray caster (the algorithm's own error), with the memory it needs. One factor at a time around the\n"
    "default (preint1, 256 entries, 16-bit tables, nearest, rebuild, exact samples, 16-bit accumulation and\n"
    "warp): bits of the tables, samples, intermediate image and warp; table size with lookup; correction;\n"
    "mode with smooth and sharp transfer functions; rays per voxel column (1 to 16) with whole and partial\n"
    "slabs at 256 and 1024 entries (the full study counts their instructions per frame with valgrind's\n"
    "callgrind when it is installed); lit, the bits of the normal codes (against unquantised normals), of the\n"
    "shade table and of the front-weighted table. Writes to DIR: results.csv, summary.json, plots (PNG,\n"
    "with gnuplot), image strips and report.md with a recommended configuration for a Raspberry Pi class\n"
    "board and for a microcontroller with 256 KB of RAM.\n\n"
    "  --quick              the subset that runs in make test (under two minutes)\n"
    "  --lighting-only      the lighting stages alone (with --quick, their quick subset)\n"
    "  --order2-only        preint2's 3D table alone: resolution 16..128 and entry bits against the reference\n"
    "                       and both truths, memory, the size per board (DIR/order2.md, .csv, .gp, .png)\n"
    "  -o DIR               where to write (created)\n"
    "  --threads N          threads for the ground truth (default 2)\n"
    "The sample volumes (neghip, engine, bucky, ...) come from the folder $VOLFIX_DATA, when it is set.\n";

typedef struct sweep_ctx {
    study_t *st;
    char err[VFP_ERR_LEN];
    int failed;
} sweep_ctx_t;

static void run(sweep_ctx_t *c, int scene, const vf_params_t *p, const char *factor, const char *value)
{
    if (c->failed || scene < 0)
        return;
    int with_truth = strcmp(factor, "fixed_point") != 0; /* the fixed-point check needs only the reference */
    if (!study_run(c->st, scene, p, factor, value, with_truth, c->err, sizeof c->err))
        c->failed = 1;
}

static void run_uint(sweep_ctx_t *c, int scene, const vf_params_t *p, const char *factor, unsigned value)
{
    char text[32];
    snprintf(text, sizeof text, "%u", value);
    run(c, scene, p, factor, text);
}

/* Each precision stage on its own, everything else at the default. */
static void sweep_bits(sweep_ctx_t *c, int scene)
{
    const vf_params_t def = study_default_params();
    const unsigned table_bits[] = {8, 10, 12, 16}, sample_bits[] = {4, 6, 8, 10, 12, 16, 0};
    const unsigned inter_bits[] = {8, 12, 16}, warp_bits[] = {4, 6, 8, 12, 16};
    for (size_t i = 0; i < sizeof table_bits / sizeof *table_bits; i++) {
        vf_params_t p = def;
        p.table_bits = table_bits[i];
        run_uint(c, scene, &p, "table_bits", table_bits[i]);
    }
    for (size_t i = 0; i < sizeof sample_bits / sizeof *sample_bits; i++) {
        vf_params_t p = def;
        p.sample_bits = sample_bits[i];
        run_uint(c, scene, &p, "sample_bits", sample_bits[i] ? sample_bits[i] : 32); /* 32: exact (Q8.32) */
    }
    for (size_t i = 0; i < sizeof inter_bits / sizeof *inter_bits; i++) {
        vf_params_t p = def;
        p.intermediate_bits = inter_bits[i];
        run_uint(c, scene, &p, "intermediate_bits", inter_bits[i]);
    }
    for (size_t i = 0; i < sizeof warp_bits / sizeof *warp_bits; i++) {
        vf_params_t p = def;
        p.warp_bits = warp_bits[i];
        run_uint(c, scene, &p, "warp_bits", warp_bits[i]);
    }
}

/* Table size with each lookup: they interact (bilinear lookups matter for small tables). */
static void sweep_table_size(sweep_ctx_t *c, int scene, int full)
{
    const unsigned sizes[] = {64, 128, 256, 512, 1024};
    for (int lookup = 0; lookup <= VF_LOOKUP_BILINEAR; lookup++) /* trilinear: preint2's */
        for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++) {
            if (!full && sizes[i] == 1024)
                continue; /* the 1024^2 reference table alone takes longer than the quick study may */
            vf_params_t p = study_default_params();
            p.lookup = (vf_lookup_t)lookup;
            p.table_size = sizes[i];
            run_uint(c, scene, &p, lookup ? "table_size_bilinear" : "table_size_nearest", sizes[i]);
        }
}

/* Every mode the study ranks (STUDY_MODES), and each correction for the pre-integrated one. */
static void sweep_orders(sweep_ctx_t *c, int scene)
{
    for (int mode = 0; mode < STUDY_MODES; mode++) {
        vf_params_t p = study_default_params();
        p.mode = (vf_mode_t)mode;
        run(c, scene, &p, "order", vf_mode_name(p.mode));
    }
    vf_params_t p = study_default_params();
    p.correction = VF_CORRECTION_LUT;
    run(c, scene, &p, "correction", "lut");
    p.correction = VF_CORRECTION_REBUILD;
    run(c, scene, &p, "correction", "rebuild");
}

/* Rays per voxel column (docs/algorithm.md 4b) with each side-face rule (4c) and table size: the options that
 * take away the errors point and preint1 share (the intermediate image's resolution, whole slabs at the box's
 * faces, the table's resolution), each mode at every R. Factor "rays_whole_256" and the like, value R. The quick
 * study runs claim 1's configuration only (16 rays, partial slabs, 1024 entries: every mode, for the strip: about
 * 15 s of its two minutes); the full one all of it, and times frames. */
static void sweep_rays(sweep_ctx_t *c, int scene, int quick)
{
    const unsigned sizes[] = {256, STUDY_CLAIM_TABLE}, rays[] = {1, 2, 4, 8, 16};
    c->st->time_frames = quick ? 0 : 5;
    for (size_t n = 0; n < 2; n++)
        for (int partial = 0; partial < 2; partial++)
            for (size_t k = 0; k < sizeof rays / sizeof *rays; k++)
                for (int mode = 0; mode < STUDY_MODES; mode++) {
                    const int claim = sizes[n] == STUDY_CLAIM_TABLE && partial && rays[k] == STUDY_CLAIM_RAYS;
                    if (quick && !claim)
                        continue;
                    vf_params_t p = study_default_params();
                    p.mode = (vf_mode_t)mode;
                    p.table_size = sizes[n];
                    p.partial_slabs = partial != 0;
                    p.rays = rays[k];
                    char factor[32];
                    snprintf(factor, sizeof factor, "rays_%s_%u", partial ? "partial" : "whole", sizes[n]);
                    c->st->keep_images = claim; /* for the strip of claim 1's configuration */
                    /* instructions per frame for point and preint1 (R = 16 under callgrind: a minute or two each) */
                    c->st->count_instructions = !quick && mode != VF_MODE_PRECLASS &&
                                                (rays[k] <= 4 || (rays[k] == 8 && partial) || claim);
                    run_uint(c, scene, &p, factor, rays[k]);
                    c->st->keep_images = c->st->count_instructions = 0;
                }
    c->st->time_frames = 0;
}

/* The same options on other scenes, at each scene's own output size and table (what they are worth depends on
 * how many output pixels a voxel covers, and on whether the volume is visible up to its box): point and preint1,
 * R = 1 up to most_rays, whole and partial slabs. */
static void sweep_rays_elsewhere(sweep_ctx_t *c, int scene, uint32_t table_size, unsigned most_rays)
{
    c->st->time_frames = c->st->quick ? 0 : 5;
    c->st->count_instructions = !c->st->quick;
    for (int partial = 0; partial < 2; partial++)
        for (unsigned r = 1; r <= most_rays; r *= 2)
            for (int mode = 0; mode < 2; mode++) {
                vf_params_t p = study_default_params();
                p.mode = mode ? VF_MODE_PREINT1 : VF_MODE_POINT;
                p.table_size = table_size;
                p.partial_slabs = partial != 0;
                p.rays = r;
                char factor[32];
                snprintf(factor, sizeof factor, "rays_%s_%u", partial ? "partial" : "whole", table_size);
                run_uint(c, scene, &p, factor, r);
            }
    c->st->time_frames = c->st->count_instructions = 0;
}

/* Point sampling against pre-integration only (the width sweep needs no more). */
static void sweep_two_orders(sweep_ctx_t *c, int scene)
{
    vf_params_t p = study_default_params();
    p.mode = VF_MODE_POINT;
    run(c, scene, &p, "order", "point");
    p.mode = VF_MODE_PREINT1;
    run(c, scene, &p, "order", "preint1");
}

/* The sharp preset's three peaks with another half-width, written into the study's directory. */
static vfp_status_t write_peaks(const char *dir, double half, char *path, size_t len)
{
    snprintf(path, len, "%s/peaks-%.3f.tf", dir, half);
    FILE *f = fopen(path, "w");
    if (!f)
        return VFP_ERR;
    const double centre[3] = {0.30, 0.55, 0.80}, colour[3][4] = {{1, 0.5, 0.1, 0.9}, {0.2, 1, 0.3, 0.9}, {1, 1, 1, 1}};
    fprintf(f, "# the sharp preset's peaks, half-width %.3f of the window\n0 0 0 0 0\n", half);
    for (int k = 0; k < 3; k++) {
        const double *c = colour[k];
        fprintf(f, "%.4f %g %g %g 0\n%.4f %g %g %g %g\n%.4f %g %g %g 0\n", centre[k] - half, c[0], c[1], c[2],
                centre[k], c[0], c[1], c[2], c[3], centre[k] + half, c[0], c[1], c[2]);
    }
    fclose(f);
    return VFP_OK;
}

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

int sim_cmd_study(int argc, char **argv)
{
    study_t *st = calloc(1, sizeof *st);
    if (!st) {
        fprintf(stderr, "volfix-sim: out of memory\n");
        return VFP_EXIT_ERR;
    }
    st->threads = 2;
    st->have_valgrind = -1;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        long long n;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(usage, stdout);
            free(st);
            return VFP_EXIT_OK;
        } else if (strcmp(a, "--quick") == 0) {
            st->quick = 1;
            continue;
        } else if (strcmp(a, "--lighting-only") == 0) {
            st->lighting_only = 1;
            continue;
        } else if (strcmp(a, "--order2-only") == 0) {
            st->order2_only = 1;
            continue;
        } else if ((strcmp(a, "-o") == 0 || strcmp(a, "--threads") == 0) && vfp_is_empty(v)) {
            fprintf(stderr, "volfix-sim study: %s '': an empty value (see --help)\n", a);
        } else if (strcmp(a, "-o") == 0 && v) {
            st->dir = v;
            i++;
            continue;
        } else if (strcmp(a, "--threads") == 0 && v) {
            if (vfp_parse_integer(v, 1, 16, &n)) {
                st->threads = (int)n;
                i++;
                continue;
            }
            fprintf(stderr, "volfix-sim study: --threads %s: expected an integer 1..16\n", v);
        } else {
            fprintf(stderr, "volfix-sim study: %s: unknown option or missing value (see --help)\n", a);
        }
        free(st);
        return VFP_EXIT_ERR;
    }
    if (!st->dir) {
        fprintf(stderr, "volfix-sim study: no output directory (-o DIR)\n");
        free(st);
        return VFP_EXIT_ERR;
    }
    /* everything the study writes goes into DIR: made now, and known writable before the first minute of work */
    struct stat dir_st;
    if (mkdir(st->dir, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "volfix-sim study: -o %s: cannot make the directory: %s\n", st->dir, strerror(errno));
        free(st);
        return VFP_EXIT_ERR;
    }
    if (stat(st->dir, &dir_st) != 0 || !S_ISDIR(dir_st.st_mode) || access(st->dir, W_OK) != 0) {
        fprintf(stderr, "volfix-sim study: -o %s: expected a directory the study can write into%s\n", st->dir,
                stat(st->dir, &dir_st) == 0 && !S_ISDIR(dir_st.st_mode) ? " (it is a file)" : "");
        free(st);
        return VFP_EXIT_ERR;
    }
    st->started_ms = vfp_now_ms();
    st->progress_tty = isatty(2);
    /* The sample volumes' folder comes from the environment only (make sets it): without it the study says so
     * and measures the phantoms alone. */
    const char *data = getenv("VOLFIX_DATA");
    if (!data || !data[0]) {
        fprintf(stderr, "volfix-sim study: VOLFIX_DATA is not set: the sample volumes are left out (set it to "
                        "their folder)\n");
        data = NULL;
    }
    char path[1024];
    sweep_ctx_t c = {.st = st};
    const uint32_t small = 256;
    if (st->order2_only) {
        vfp_status_t o2 = study_order2(st, data, c.err, sizeof c.err);
        if (o2)
            fprintf(stderr, "volfix-sim study: %s\n", c.err);
        else
            printf("study: preint2's 3D table in %.0f s; report in %s/order2.md\n",
                   (vfp_now_ms() - st->started_ms) / 1000, st->dir);
        study_free(st);
        free(st);
        return vfp_exit_status(o2);
    }
    if (st->lighting_only)
        goto lighting;

    /* Marschner-Lobb 41^3, the test signal made to show reconstruction error: sharp and smooth. The sharp scene
     * is rendered at 512x512, the size of the claim that pre-integration is at least 6 dB closer to the truth. */
    int ml_sharp = study_add_scene(st, "ml41-sharp", "phantom:marschner-lobb:41", "sharp", 30, 20, 1, 512, c.err,
                                   sizeof c.err);
    int ml_ramp = ml_sharp < 0 ? -1
                               : study_add_scene(st, "ml41-ramp", "phantom:marschner-lobb:41", "ramp", 30, 20, 1, small,
                                                 c.err, sizeof c.err);
    /* The same volume and view, zoomed to its interior: Marschner-Lobb is visible up to its box, whose side faces
     * shear-warp samples a slab at a time (a staircase the truth does not have); inside, the rays' integration
     * is all that differs. */
    int ml_inside = ml_ramp < 0 ? -1
                                : study_add_scene(st, "ml41-sharp-interior", "phantom:marschner-lobb:41", "sharp", 30,
                                                  20, 3, small, c.err, sizeof c.err);
    if (ml_sharp < 0 || ml_ramp < 0 || ml_inside < 0)
        c.failed = 1;
    sweep_orders(&c, ml_sharp);
    if (!c.failed && study_floor(st, ml_sharp, 1, 0, &st->floor, c.err, sizeof c.err))
        c.failed = 1;
    st->floor.scene = ml_sharp;
    /* Claim 1 again without the errors both orders share; in the full study the floor at each R too (at 1024
     * entries, claim 1's), which says how much of what is left is the slab integration. */
    sweep_rays(&c, ml_sharp, st->quick);
    for (int k = 0; k < STUDY_RAYS_STEPS && !c.failed && !st->quick; k++) {
        if (study_floor(st, ml_sharp, 1 << k, STUDY_CLAIM_TABLE, &st->rays_floor[k], c.err, sizeof c.err))
            c.failed = 1;
        st->rays_floor[k].scene = ml_sharp;
        if (!c.failed)
            fprintf(stderr, "%sstudy: %.0f s: ml41-sharp floor with %d rays per voxel column: %.1f dB%s",
                    st->progress_tty ? "\r" : "", (vfp_now_ms() - st->started_ms) / 1000, 1 << k,
                    st->rays_floor[k].exact_db, st->progress_tty ? "" : "\n");
    }
    sweep_orders(&c, ml_ramp);
    sweep_orders(&c, ml_inside);
    sweep_bits(&c, ml_sharp);
    sweep_bits(&c, ml_ramp);
    sweep_table_size(&c, ml_sharp, !st->quick);

    /* Where pre-integration matters: the peaks' width, in the whole view and inside the volume. */
    const double halves[] = {0.005, 0.01, 0.015, 0.02, 0.03, 0.05};
    for (size_t i = 0; i < sizeof halves / sizeof halves[0] && !c.failed; i++) {
        char tf[400], spec[410], label[64];
        if (write_peaks(st->dir, halves[i], tf, sizeof tf)) {
            snprintf(c.err, sizeof c.err, "%s: cannot write", tf);
            c.failed = 1;
            break;
        }
        snprintf(spec, sizeof spec, "file:%s", tf);
        for (int inside = 0; inside < 2 && !c.failed; inside++) {
            snprintf(label, sizeof label, "ml41-peaks-%.3f%s", halves[i], inside ? "-interior" : "");
            int s = study_add_scene(st, label, "phantom:marschner-lobb:41", spec, 30, 20, inside ? 3 : 1, small,
                                    c.err, sizeof c.err);
            if (s < 0)
                c.failed = 1;
            sweep_two_orders(&c, s);
        }
    }

    /* A uniform cube: nothing but the box's faces, which shear-warp adds a slab at a time. */
    int cube = c.failed ? -1 : study_add_scene(st, "cube24", "phantom:cube:24", "ramp", 30, 20, 1, small, c.err,
                                               sizeof c.err);
    if (cube < 0)
        c.failed = 1;
    sweep_two_orders(&c, cube);

    /* Shared volumes: neghip (the second-order paper's), and in the full study the others with a transfer
     * function that suits each, smooth and sharp. */
    struct {
        const char *file, *label, *preset;
        double az, el;
        int quick;
        unsigned most_rays; /* the full study's rays sweep on the scene: R = 1 up to this (0: none) */
    } shared[] = {
        {"neghip.nhdr", "neghip-sharp", "sharp", 30, 20, 1, 4},
        {"neghip.nhdr", "neghip-mr-brain", "mr-brain", 30, 20, 0, 0},
        {"brainsmall.nhdr", "brain-mr-brain", "mr-brain", 0, -90, 0, 0},
        {"engine.nhdr", "engine-ct-bone", "ct-bone", 30, 20, 0, 2},
        {"engine.nhdr", "engine-ramp", "ramp", 30, 20, 0, 0},
        {"cthead.nhdr", "cthead-ct-skin-bone", "ct-skin-bone", 180, 90, 0, 0},
        {"headsq.nhdr", "headsq-ct-bone", "ct-bone", 30, 20, 0, 0},
        {"bucky.nhdr", "bucky-sharp", "sharp", 30, 20, 0, 4},
    };
    for (size_t i = 0; i < sizeof shared / sizeof shared[0] && !c.failed; i++) {
        if (st->quick && !shared[i].quick)
            continue;
        snprintf(path, sizeof path, "%s/%s", data ? data : "", shared[i].file);
        if (!data || !exists(path))
            continue;
        int s = study_add_scene(st, shared[i].label, path, shared[i].preset, shared[i].az, shared[i].el, 1, small,
                                c.err, sizeof c.err);
        if (s < 0) {
            c.failed = 1;
            break;
        }
        sweep_orders(&c, s);
        if (!st->quick)
            sweep_bits(&c, s);
        if (!st->quick && shared[i].most_rays)
            sweep_rays_elsewhere(&c, s, 256, shared[i].most_rays);
    }
    /* The microcontroller's scene (boards/mps2-an386: bucky at 64x64) with the table it can hold, one and two
     * rays, whole and partial slabs (what the options are worth where a voxel covers about one output pixel), and
     * each candidate configuration for such a board. */
    snprintf(path, sizeof path, "%s/bucky.nhdr", data ? data : "");
    if (!c.failed && data && exists(path)) {
        int s = study_add_scene(st, "bucky-sharp-64", path, "sharp", 30, 20, 1, 64, c.err, sizeof c.err);
        if (s < 0)
            c.failed = 1;
        sweep_rays_elsewhere(&c, s, 64, 2);
        st->time_frames = st->quick ? 0 : 5;
        st->count_instructions = !st->quick;
        for (int k = 0; k < STUDY_MCU_CANDIDATES; k++) { /* the report's candidates for such a board */
            vf_params_t p = study_mcu_params(k);
            run_uint(&c, s, &p, "mcu", (unsigned)k);
        }
        st->time_frames = st->count_instructions = 0;
    }
    if (!st->quick && !c.failed) { /* the other phantoms */
        int sl = study_add_scene(st, "shepp-logan-ramp", "phantom:shepp-logan:96", "ramp", 0, -60, 1, small, c.err,
                                 sizeof c.err);
        sweep_orders(&c, sl);
        sweep_table_size(&c, ml_ramp, 1);
    }

    /* The default configuration's fixed-point error on the shared volumes at the five views of the foundation
     * issue (the full study at 512x512; the quick one at 256x256 on two of them). */
    const double views[5][2] = {{0, 0}, {30, 20}, {45, 0}, {60, -35}, {135, 70}};
    const char *fixed_volumes[] = {"engine.nhdr", "brainsmall.nhdr", "neghip.nhdr", "headsq.nhdr", "cthead.nhdr"};
    for (size_t v = 0; v < 5 && !c.failed; v++) {
        if (st->quick && v != 1 && v != 2)
            continue;
        snprintf(path, sizeof path, "%s/%s", data ? data : "", fixed_volumes[v]);
        if (!data || !exists(path))
            continue;
        for (int w = 0; w < 5 && !c.failed; w++) {
            char label[64];
            snprintf(label, sizeof label, "fixed-%.*s-%g,%g", (int)(strchr(fixed_volumes[v], '.') - fixed_volumes[v]),
                     fixed_volumes[v], views[w][0], views[w][1]);
            int s = study_add_scene(st, label, path, "ramp", views[w][0], views[w][1], 1, st->quick ? 256 : 512,
                                    c.err, sizeof c.err);
            vf_params_t p = study_default_params();
            run(&c, s, &p, "fixed_point", label);
        }
    }

lighting: /* the lighting stages (study_lit.c) */
    if (!c.failed && study_lit(st, data, c.err, sizeof c.err))
        c.failed = 1;

    if (st->progress_tty)
        fprintf(stderr, "\n");
    vfp_status_t status = VFP_OK;
    if (c.failed) {
        fprintf(stderr, "volfix-sim study: %s\n", c.err);
        status = VFP_ERR;
    } else if (study_write_report(st, c.err, sizeof c.err)) {
        fprintf(stderr, "volfix-sim study: %s\n", c.err);
        status = VFP_ERR;
    } else {
        printf("study: %d runs on %d scenes in %.0f s; report in %s/report.md\n", st->run_count, st->scene_count,
               (vfp_now_ms() - st->started_ms) / 1000, st->dir);
    }
    study_free(st);
    free(st);
    return vfp_exit_status(status);
}
