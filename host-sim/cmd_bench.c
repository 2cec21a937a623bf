/*
 * cmd_bench.c: volfix-sim bench: the protocol of Schulze et al. 2003: rotate 180 degrees about the vertical
 * axis in 2-degree steps (90 frames) and report the mean time per frame, with the time to build the 8-bit
 * slices, the classification and run-length encoding, and per frame the table rebuild, compositing and warp.
 * --matrix runs the variants of their Table 1. Timings belong here, never in tests. For instruction counts run
 * it under callgrind (tools/bench.sh).
 */
#include <stdio.h>
#include <stdlib.h>

#include "commands.h"
#include "scene.h"

static const char usage_head[] =
    "usage: volfix-sim bench VOLUME [options] [--frames N] [--matrix] [--json]\n"
    "Time the fixed-point renderer: one warm-up frame, then N frames (default 90) turning 2 degrees each\n"
    "about the vertical axis from the --view azimuth. Reports mean and median milliseconds per frame and\n"
    "where the time goes.\n\n"
    "  --frames N           frames to time (default 90: the 180-degree protocol of Schulze et al.)\n"
    "  --matrix             the variants of Schulze et al.'s Table 1: point, then preint1 with every lookup x\n"
    "                       correction x buffer, then preclass; other scene options apply to all\n"
    "  --json               print one JSON object (a list of them with --matrix)\n";

typedef struct bench_result {
    int frames;
    double mean, median, tables, composite, warp; /* ms per frame */
    double window_ms, classify_ms;                /* once */
    vf_memory_t memory;
} bench_result_t;

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The protocol for one parameter set. Returns 0, or 2 with err. */
static int run(const sim_scene_t *s, const vf_params_t *params, const sim_opts_t *o, bench_result_t *res, char *err,
               size_t errlen)
{
    vf_image_t img;
    vfp_render_t r;
    double *ms = malloc(sizeof(double) * (size_t)o->frames);
    if (!ms || sim_image_alloc(&img, s->width, s->height, s->format)) {
        free(ms);
        snprintf(err, errlen, "out of memory");
        return 2;
    }
    *res = (bench_result_t){.frames = o->frames};
    int status = vfp_render_open(&r, params, &s->vol.core, s->threads, err, errlen);
    if (status == 0) {
        status = vfp_render_set_window(&r, s->window, err, errlen);
        res->window_ms = r.ms_classify;
    }
    if (status == 0) {
        status = vfp_render_set_tf(&r, s->points, s->npoints, err, errlen);
        res->classify_ms = r.ms_classify;
    }
    if (status == 0) { /* warm-up, one step before the first timed view, so that every timed frame is a new view */
        vf_view_t before = sim_view(o->azimuth - 2.0, o->elevation, o->roll, o->zoom);
        status = vfp_render_frame(&r, &before, &img, err, errlen);
    }
    double sum = 0;
    for (int f = 0; status == 0 && f < o->frames; f++) {
        vf_view_t v = sim_view(o->azimuth + 2.0 * f, o->elevation, o->roll, o->zoom);
        double t0 = vfp_now_ms();
        status = vfp_render_frame(&r, &v, &img, err, errlen);
        ms[f] = vfp_now_ms() - t0;
        sum += ms[f];
        res->tables += r.ms_tables;
        res->composite += r.ms_composite;
        res->warp += r.ms_warp;
    }
    if (status == 0) {
        vf_renderer_memory(r.core, &res->memory);
        qsort(ms, (size_t)o->frames, sizeof *ms, by_value);
        res->mean = sum / o->frames;
        res->median = ms[o->frames / 2];
        res->tables /= o->frames;
        res->composite /= o->frames;
        res->warp /= o->frames;
    }
    vfp_render_close(&r);
    free(ms);
    sim_image_free(&img);
    return status;
}

static void print_one(const sim_scene_t *s, const bench_result_t *b, int json)
{
    char about[512];
    sim_scene_describe(s, about, sizeof about);
    if (json) {
        printf("{\"scene\": \"%s\", \"mode\": \"%s\", \"lookup\": \"%s\", \"correction\": \"%s\", \"buffer\": \"%s\", "
               "\"frames\": %d, \"threads\": %d, \"ms_per_frame\": %.3f, \"median_ms\": %.3f, \"tables_ms\": %.3f, "
               "\"composite_ms\": %.3f, \"warp_ms\": %.3f, \"window_ms\": %.3f, \"classify_rle_ms\": %.3f, "
               "\"memory_bytes\": %zu}\n",
               about, vf_mode_name(s->params.mode), vf_lookup_name(s->params.lookup),
               vf_correction_name(s->params.correction), vf_buffer_name(s->params.buffer), b->frames, s->threads,
               b->mean, b->median, b->tables, b->composite, b->warp, b->window_ms, b->classify_ms, b->memory.total);
        return;
    }
    const vf_memory_t *m = &b->memory;
    printf("%s, %d threads\n", about, s->threads);
    printf("slices (window): %.1f ms; classification and run-length encoding: %.1f ms\n", b->window_ms,
           b->classify_ms);
    printf("%d frames: mean %.2f ms, median %.2f ms (%.1f frames/s)\n", b->frames, b->mean, b->median,
           1000.0 / b->mean);
    printf("per frame: tables %.2f ms, compositing %.2f ms, warp %.2f ms\n", b->tables, b->composite, b->warp);
    printf("memory: %.1f MB (slices %.1f, run lists %.1f, tables %.2f, intermediate image %.1f)\n",
           m->total / 1048576.0, m->slices / 1048576.0, m->runs / 1048576.0, m->tables / 1048576.0,
           m->intermediate / 1048576.0);
}

/* Schulze et al. 2003, Table 1: standard shear-warp, then pre-integrated with each combination of lookup,
 * opacity correction and buffer slices; the VolPack baseline (preclass) last. */
static int matrix(sim_scene_t *s, const sim_opts_t *o)
{
    vf_params_t configs[10];
    int count = 0;
    vf_params_t base = s->params;
    base.mode = VF_MODE_POINT;
    base.lookup = VF_LOOKUP_NEAREST;
    base.correction = VF_CORRECTION_REBUILD;
    base.buffer = VF_BUFFER_SLICE;
    configs[count++] = base;
    for (int lookup = 0; lookup < VF_LOOKUP_COUNT; lookup++)
        for (int correction = 0; correction < VF_CORRECTION_COUNT; correction++)
            for (int buffer = 0; buffer < VF_BUFFER_COUNT; buffer++) {
                vf_params_t p = base;
                p.mode = VF_MODE_PREINT1;
                p.lookup = (vf_lookup_t)lookup;
                p.correction = (vf_correction_t)correction;
                p.buffer = (vf_buffer_t)buffer;
                configs[count++] = p;
            }
    base.mode = VF_MODE_PRECLASS;
    configs[count++] = base;

    char err[VFP_ERR_LEN], about[512];
    bench_result_t res[10];
    double point_mean = 0;
    if (o->json)
        printf("[\n");
    else {
        s->params = configs[0];
        sim_scene_describe(s, about, sizeof about);
        printf("%s: %d frames each, %d thread%s (the layout of Schulze et al. 2003, Table 1)\n", about, o->frames,
               s->threads, s->threads > 1 ? "s" : "");
        printf("%-9s %-9s %-11s %-7s %9s %9s %8s   %s\n", "mode", "lookup", "correction", "buffer", "ms/frame",
               "frames/s", "x point", "(tables + compositing + warp, ms)");
    }
    for (int c = 0; c < count; c++) {
        s->params = configs[c];
        if (run(s, &configs[c], o, &res[c], err, sizeof err)) {
            fprintf(stderr, "volfix-sim: %s\n", err);
            return 2;
        }
        if (c == 0)
            point_mean = res[c].mean;
        const vf_params_t *p = &configs[c];
        if (o->json) {
            sim_scene_describe(s, about, sizeof about);
            printf("  {\"mode\": \"%s\", \"lookup\": \"%s\", \"correction\": \"%s\", \"buffer\": \"%s\", "
                   "\"ms_per_frame\": %.3f, \"median_ms\": %.3f, \"frames\": %d, \"frame_rate_vs_point\": %.3f, "
                   "\"tables_ms\": %.3f, \"composite_ms\": %.3f, \"warp_ms\": %.3f, \"scene\": \"%s\"}%s\n",
                   vf_mode_name(p->mode), vf_lookup_name(p->lookup), vf_correction_name(p->correction),
                   vf_buffer_name(p->buffer), res[c].mean, res[c].median, res[c].frames, point_mean / res[c].mean,
                   res[c].tables, res[c].composite, res[c].warp, about, c + 1 < count ? "," : "");
        } else {
            printf("%-9s %-9s %-11s %-7s %9.2f %9.1f %8.2f   (%.2f + %.2f + %.2f)\n", vf_mode_name(p->mode),
                   vf_lookup_name(p->lookup), vf_correction_name(p->correction),
                   p->mode == VF_MODE_PREINT1 ? vf_buffer_name(p->buffer) : "-", res[c].mean, 1000.0 / res[c].mean,
                   point_mean / res[c].mean, res[c].tables, res[c].composite, res[c].warp);
        }
        fflush(stdout);
    }
    if (o->json)
        printf("]\n");
    return 0;
}

int sim_cmd_bench(int argc, char **argv)
{
    char usage[4096], err[VFP_ERR_LEN];
    snprintf(usage, sizeof usage, "%s%s", usage_head, sim_scene_help);
    sim_opts_t o;
    int status = sim_parse(&o, argc, argv, SIM_OPT_SCENE | SIM_OPT_JSON | SIM_OPT_FRAMES | SIM_OPT_MATRIX, usage);
    if (status)
        return status == 1 ? 0 : 2;
    sim_scene_t s;
    if (sim_scene_load(&s, &o, err, sizeof err)) {
        fprintf(stderr, "volfix-sim: %s\n", err);
        return 2;
    }
    if (o.matrix) {
        status = matrix(&s, &o);
    } else {
        bench_result_t res;
        status = run(&s, &s.params, &o, &res, err, sizeof err);
        if (status)
            fprintf(stderr, "volfix-sim: %s\n", err);
        else
            print_one(&s, &res, o.json);
    }
    sim_scene_free(&s);
    return status ? 2 : 0;
}
