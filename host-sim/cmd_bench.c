/*
 * cmd_bench.c: volfix-sim bench: the protocol of Schulze et al. 2003: rotate 180 degrees about the vertical
 * axis in 2-degree steps (90 frames) and report the mean time per frame, with the time to build the 8-bit
 * slices, the classification and run-length encoding, and per frame the table rebuild, compositing and warp.
 * Timings belong here, never in tests. For instruction counts run it under callgrind (see README).
 */
#include <stdio.h>
#include <stdlib.h>

#include "commands.h"
#include "scene.h"

static const char usage_head[] =
    "usage: volfix-sim bench VOLUME [options] [--frames N] [--json]\n"
    "Time the fixed-point renderer: one warm-up frame, then N frames (default 90) turning 2 degrees each\n"
    "about the vertical axis from the --view azimuth. Reports mean and median milliseconds per frame and\n"
    "where the time goes.\n\n"
    "  --frames N           frames to time (default 90: the 180-degree protocol of Schulze et al.)\n"
    "  --json               print one JSON object\n";

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int sim_cmd_bench(int argc, char **argv)
{
    char usage[4096], err[VFP_ERR_LEN], about[512];
    snprintf(usage, sizeof usage, "%s%s", usage_head, sim_scene_help);
    sim_opts_t o;
    int status = sim_parse(&o, argc, argv, SIM_OPT_SCENE | SIM_OPT_JSON | SIM_OPT_FRAMES, usage);
    if (status)
        return status == 1 ? 0 : 2;
    sim_scene_t s;
    if (sim_scene_load(&s, &o, err, sizeof err)) {
        fprintf(stderr, "volfix-sim: %s\n", err);
        return 2;
    }
    vf_image_t img;
    vfp_render_t r;
    double *ms = malloc(sizeof(double) * (size_t)o.frames);
    if (!ms || sim_image_alloc(&img, s.width, s.height, s.format)) {
        fprintf(stderr, "volfix-sim: out of memory\n");
        free(ms);
        sim_scene_free(&s);
        return 2;
    }
    double window_ms = 0, classify_ms = 0, tables = 0, composite = 0, warp = 0;
    status = vfp_render_open(&r, &s.params, &s.vol.core, s.threads, err, sizeof err);
    if (status == 0) {
        status = vfp_render_set_window(&r, s.window, err, sizeof err);
        window_ms = r.ms_classify;
    }
    if (status == 0) {
        status = vfp_render_set_tf(&r, s.points, s.npoints, err, sizeof err);
        classify_ms = r.ms_classify;
    }
    if (status == 0) { /* warm-up, one step before the first timed view, so that every timed frame is a new view */
        vf_view_t before = sim_view(o.azimuth - 2.0, o.elevation, o.roll, o.zoom);
        status = vfp_render_frame(&r, &before, &img, err, sizeof err);
    }
    for (int f = 0; status == 0 && f < o.frames; f++) {
        vf_view_t v = sim_view(o.azimuth + 2.0 * f, o.elevation, o.roll, o.zoom);
        double t0 = vfp_now_ms();
        status = vfp_render_frame(&r, &v, &img, err, sizeof err);
        ms[f] = vfp_now_ms() - t0;
        tables += r.ms_tables;
        composite += r.ms_composite;
        warp += r.ms_warp;
    }
    vf_memory_t mem = {0};
    if (status == 0)
        vf_renderer_memory(r.core, &mem);
    vfp_render_close(&r);
    if (status) {
        fprintf(stderr, "volfix-sim: %s\n", err);
    } else {
        double sum = 0;
        for (int f = 0; f < o.frames; f++)
            sum += ms[f];
        qsort(ms, (size_t)o.frames, sizeof *ms, by_value);
        double mean = sum / o.frames, median = ms[o.frames / 2];
        double n = o.frames;
        sim_scene_describe(&s, about, sizeof about);
        if (o.json) {
            printf("{\"scene\": \"%s\", \"mode\": \"%s\", \"frames\": %d, \"threads\": %d, \"ms_per_frame\": %.3f, "
                   "\"median_ms\": %.3f, \"tables_ms\": %.3f, \"composite_ms\": %.3f, \"warp_ms\": %.3f, "
                   "\"window_ms\": %.3f, \"classify_rle_ms\": %.3f, \"memory_bytes\": %zu}\n",
                   about, vf_mode_name(s.params.mode), o.frames, s.threads, mean, median, tables / n, composite / n,
                   warp / n, window_ms, classify_ms, mem.total);
        } else {
            printf("%s, %d threads\n", about, s.threads);
            printf("slices (window): %.1f ms; classification and run-length encoding: %.1f ms\n", window_ms,
                   classify_ms);
            printf("%d frames: mean %.2f ms, median %.2f ms (%.1f frames/s)\n", o.frames, mean, median,
                   1000.0 / mean);
            printf("per frame: tables %.2f ms, compositing %.2f ms, warp %.2f ms\n", tables / n, composite / n,
                   warp / n);
            printf("memory: %.1f MB (slices %.1f, run lists %.1f, tables %.2f, intermediate image %.1f)\n",
                   mem.total / 1048576.0, mem.slices / 1048576.0, mem.runs / 1048576.0, mem.tables / 1048576.0,
                   mem.intermediate / 1048576.0);
        }
    }
    free(ms);
    sim_image_free(&img);
    sim_scene_free(&s);
    return status ? 2 : 0;
}
