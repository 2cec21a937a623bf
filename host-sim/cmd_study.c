/*
 * cmd_study.c: volfix-sim study: what to run. One factor at a time around the default configuration, and the
 * pairs that interact (table size with lookup; mode with smooth and sharp transfer functions), on Marschner-Lobb
 * 41^3 above all, and the shared volumes when they are there. --quick is the subset make test runs (under two
 * minutes); the full study adds scenes, volumes and views.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "commands.h"
#include "study.h"

static const char usage[] =
    "usage: volfix-sim study [--quick] -o DIR [--threads N]\n"
    "The fixed-point precision study. Renders scenes with the core in many configurations and measures each\n"
    "against the double reference of the same algorithm (the fixed-point error alone) and against the ground\n"
    "truth ray caster (the algorithm's own error), with the memory it needs. One factor at a time around the\n"
    "default (preint1, 256 entries, 16-bit tables, nearest, rebuild, exact samples, 16-bit accumulation and\n"
    "warp): bits of the tables, samples, intermediate image and warp; table size with lookup; correction;\n"
    "mode with smooth and sharp transfer functions. Writes to DIR: results.csv, summary.json, plots (PNG,\n"
    "with gnuplot), image strips and report.md with a recommended configuration for a Raspberry Pi class\n"
    "board and for a microcontroller with 256 KB of RAM.\n\n"
    "  --quick              the subset that runs in make test (under two minutes)\n"
    "  -o DIR               where to write (created)\n"
    "  --threads N          threads for the ground truth (default 2)\n";

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
    for (int lookup = 0; lookup < VF_LOOKUP_COUNT; lookup++)
        for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++) {
            if (!full && sizes[i] == 1024)
                continue; /* the 1024^2 reference table alone takes longer than the quick study may */
            vf_params_t p = study_default_params();
            p.lookup = (vf_lookup_t)lookup;
            p.table_size = sizes[i];
            run_uint(c, scene, &p, lookup ? "table_size_bilinear" : "table_size_nearest", sizes[i]);
        }
}

/* Every mode (the study picks up new ones without a change), and each correction for the pre-integrated one. */
static void sweep_orders(sweep_ctx_t *c, int scene)
{
    for (int mode = 0; mode < VF_MODE_COUNT; mode++) {
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
static int write_peaks(const char *dir, double half, char *path, size_t len)
{
    snprintf(path, len, "%s/peaks-%.3f.tf", dir, half);
    FILE *f = fopen(path, "w");
    if (!f)
        return 2;
    const double centre[3] = {0.30, 0.55, 0.80}, colour[3][4] = {{1, 0.5, 0.1, 0.9}, {0.2, 1, 0.3, 0.9}, {1, 1, 1, 1}};
    fprintf(f, "# the sharp preset's peaks, half-width %.3f of the window\n0 0 0 0 0\n", half);
    for (int k = 0; k < 3; k++) {
        const double *c = colour[k];
        fprintf(f, "%.4f %g %g %g 0\n%.4f %g %g %g %g\n%.4f %g %g %g 0\n", centre[k] - half, c[0], c[1], c[2],
                centre[k], c[0], c[1], c[2], c[3], centre[k] + half, c[0], c[1], c[2]);
    }
    fclose(f);
    return 0;
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
        return 2;
    }
    st->threads = 2;
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            fputs(usage, stdout);
            free(st);
            return 0;
        } else if (strcmp(argv[i], "--quick") == 0) {
            st->quick = 1;
        } else if (strcmp(argv[i], "-o") == 0 && i + 1 < argc) {
            st->dir = argv[++i];
        } else if (strcmp(argv[i], "--threads") == 0 && i + 1 < argc) {
            st->threads = atoi(argv[++i]);
            if (st->threads < 1 || st->threads > 16) {
                fprintf(stderr, "volfix-sim study: --threads %s: expected 1..16\n", argv[i]);
                free(st);
                return 2;
            }
        } else {
            fprintf(stderr, "volfix-sim study: %s: unknown option or missing value (see --help)\n", argv[i]);
            free(st);
            return 2;
        }
    }
    if (!st->dir) {
        fprintf(stderr, "volfix-sim study: no output directory (-o DIR)\n");
        free(st);
        return 2;
    }
    if (mkdir(st->dir, 0755) != 0 && !exists(st->dir)) {
        fprintf(stderr, "volfix-sim study: %s: cannot create the directory\n", st->dir);
        free(st);
        return 2;
    }
    st->started_ms = vfp_now_ms();
    st->progress_tty = isatty(2);
    const char *data = getenv("VOLFIX_DATA") ? getenv("VOLFIX_DATA") : "../shared/data";
    char path[1024];
    sweep_ctx_t c = {.st = st};
    const uint32_t small = 256;

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
    } shared[] = {
        {"neghip.nhdr", "neghip-sharp", "sharp", 30, 20, 1},    {"neghip.nhdr", "neghip-mr-brain", "mr-brain", 30, 20, 0},
        {"brainsmall.nhdr", "brain-mr-brain", "mr-brain", 0, -90, 0}, {"engine.nhdr", "engine-ct-bone", "ct-bone", 30, 20, 0},
        {"engine.nhdr", "engine-ramp", "ramp", 30, 20, 0},      {"cthead.nhdr", "cthead-ct-skin-bone", "ct-skin-bone", 180, 90, 0},
        {"headsq.nhdr", "headsq-ct-bone", "ct-bone", 30, 20, 0}, {"bucky.nhdr", "bucky-sharp", "sharp", 30, 20, 0},
    };
    for (size_t i = 0; i < sizeof shared / sizeof shared[0] && !c.failed; i++) {
        if (st->quick && !shared[i].quick)
            continue;
        snprintf(path, sizeof path, "%s/%s", data, shared[i].file);
        if (!exists(path))
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
        snprintf(path, sizeof path, "%s/%s", data, fixed_volumes[v]);
        if (!exists(path))
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

    if (st->progress_tty)
        fprintf(stderr, "\n");
    int status = 0;
    if (c.failed) {
        fprintf(stderr, "volfix-sim study: %s\n", c.err);
        status = 2;
    } else if (study_write_report(st, c.err, sizeof c.err)) {
        fprintf(stderr, "volfix-sim study: %s\n", c.err);
        status = 2;
    } else {
        printf("study: %d runs on %d scenes in %.0f s; report in %s/report.md\n", st->run_count, st->scene_count,
               (vfp_now_ms() - st->started_ms) / 1000, st->dir);
    }
    study_free(st);
    free(st);
    return status;
}
