/* SPDX-License-Identifier: MIT */
/*
 * cmd_bench.c: volfix-sim bench: the protocol of Schulze et al. 2003: rotate 180 degrees about the vertical
 * axis in 2-degree steps (90 frames) and report the mean time per frame, with the time to build the 8-bit
 * slices, the classification and run-length encoding, and per frame the table rebuild, compositing and warp.
 * --matrix runs the variants of their Table 1. Timings belong here, never in tests. For instruction counts run
 * it under callgrind (tools/bench.sh).
 *
 * Rounds: on a shared machine the speed changes by a quarter from one stretch of seconds to the next, so timing
 * the variants one after another lets a slow stretch land on one of them and skew its ratio to point. Every
 * renderer is set up first; then each round renders every variant's rotation once, in an order rotated from
 * round to round, and a variant's ratio to point is taken within each round (the two rotations ran close
 * together) and its median over the rounds reported.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "scene.h"

#define MAX_VARIANTS 20

static const char usage_head[] =
    "usage: volfix-sim bench VOLUME [options] [--frames N] [--rounds N] [--matrix] [--json]\n"
    "Time the fixed-point renderer: one warm-up frame, then N frames (default 90) turning 2 degrees each\n"
    "about the vertical axis from the --view azimuth. Reports mean and median milliseconds per frame and\n"
    "where the time goes.\n\n"
    "  --frames N           frames to time (default 90: the 180-degree protocol of Schulze et al.)\n"
    "  --rounds N           render the rotation N times (default 3 with --matrix, else 1), a warm-up frame\n"
    "                       before each; with --matrix every renderer is set up first and each round times\n"
    "                       every variant once, in an order rotated from round to round. Reports each\n"
    "                       round's mean and their median; ratios to point are taken within a round, their\n"
    "                       median over rounds reported (progress on stderr, one line per round)\n"
    "  --matrix             the variants of Schulze et al.'s Table 1 (point, then preint1 with every lookup x\n"
    "                       correction x buffer, then preclass), then preint2 with 3D tables of 32, 64\n"
    "                       and 128 a side, nearest and trilinear, lut-corrected, and 64 rebuilt per view;\n"
    "                       other scene options apply to all\n"
    "  --json               print one JSON object (a list of them with --matrix)\n";

/* One renderer under test and what its rounds measured. */
typedef struct variant {
    vf_params_t params;
    vfp_render_t r;
    int open;                   /* r is set up (window and transfer function given) */
    int measured_setup;         /* window_ms and classify_ms are from its first setup */
    double window_ms, classify_ms; /* slices, classification and run-length encoding: once */
    vf_memory_t memory;
    size_t arena_estimate;      /* bytes vfp_render_open reserves, for the memory decision */
    /* per round (index = round, not position in the round): mean ms per frame, and its stages */
    double *round_mean, *round_tables, *round_composite, *round_warp;
    double *ratio;              /* per round: the first variant's round mean / this one's (frame-rate ratio) */
    double *frame_ms;           /* every timed frame, rounds x frames */
} variant_t;

/* What a variant's rounds come to. */
typedef struct summary {
    double mean;                    /* median over rounds of the round means: the headline */
    double median;                  /* median frame time over all rounds */
    double tables, composite, warp; /* per frame, of the median round (the two middle ones for an even count) */
    double ratio, ratio_min, ratio_max;
} summary_t;

typedef struct plan {
    int rounds, frames, count;
    int all_at_once;                /* every renderer set up before the first round (else one at a time) */
    size_t total_bytes, available_bytes; /* their arenas together; memory available (0: unknown) */
} plan_t;

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median of n values (the mean of the two middle ones for even n); values is left sorted. */
static double median_sorting(double *values, int n)
{
    qsort(values, (size_t)n, sizeof *values, by_value);
    return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

/* The rounds whose means are the middle ones: lo == hi for an odd count. */
static void middle_rounds(const double *means, int n, int *lo, int *hi)
{
    int order[1000];
    for (int i = 0; i < n; i++)
        order[i] = i;
    for (int i = 1; i < n; i++) /* insertion sort by mean: n is small */
        for (int j = i; j > 0 && means[order[j]] < means[order[j - 1]]; j--) {
            int t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
    *lo = order[(n - 1) / 2];
    *hi = order[n / 2];
}

/* MemAvailable from /proc/meminfo, in bytes; 0 when unknown. */
static size_t memory_available(void)
{
    FILE *f = fopen("/proc/meminfo", "r");
    if (!f)
        return 0;
    char line[256];
    unsigned long long kb = 0;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "MemAvailable: %llu kB", &kb) == 1)
            break;
    fclose(f);
    return (size_t)(kb * 1024);
}

static vfp_status_t variants_alloc(variant_t *v, int count, const plan_t *p)
{
    for (int c = 0; c < count; c++) {
        size_t n = (size_t)p->rounds * (5 + (size_t)p->frames);
        double *block = calloc(n, sizeof *block);
        if (!block)
            return VFP_ERR;
        v[c].round_mean = block;
        v[c].round_tables = block + p->rounds;
        v[c].round_composite = block + 2 * p->rounds;
        v[c].round_warp = block + 3 * p->rounds;
        v[c].ratio = block + 4 * p->rounds;
        v[c].frame_ms = block + 5 * p->rounds;
    }
    return VFP_OK;
}

static void variants_free(variant_t *v, int count)
{
    for (int c = 0; c < count; c++) {
        if (v[c].open)
            vfp_render_close(&v[c].r);
        free(v[c].round_mean);
    }
}

/* Create a variant's renderer and give it the window and transfer function. Returns VFP_OK, or VFP_ERR with err and the
 * renderer closed (a failed one is never asked for its memory). */
static vfp_status_t setup(const sim_scene_t *s, variant_t *v, char *err, size_t errlen)
{
    vfp_status_t status = vfp_render_open(&v->r, &v->params, &s->vol.core, s->threads, err, errlen);
    double window_ms = 0, classify_ms = 0;
    if (status == VFP_OK) {
        status = vfp_render_set_window(&v->r, s->window, err, errlen);
        window_ms = v->r.ms_classify;
    }
    if (status == VFP_OK) {
        status = vfp_render_set_tf(&v->r, s->points, s->npoints, err, errlen);
        classify_ms = v->r.ms_classify;
    }
    if (status == VFP_OK && v->params.lighting) { /* the scene's lights and material (scene.h) */
        vf_status_t ls = vf_renderer_set_lighting(v->r.core, &s->lighting);
        if (ls != VF_OK) {
            snprintf(err, errlen, "cannot light the frames: %s", vf_status_text(ls));
            status = VFP_ERR;
        }
    }
    if (status) {
        vfp_render_close(&v->r);
        return status;
    }
    v->open = 1;
    if (!v->measured_setup) {
        v->window_ms = window_ms;
        v->classify_ms = classify_ms;
        v->measured_setup = 1;
    }
    return status;
}

static void teardown(variant_t *v)
{
    if (!v->open)
        return;
    vf_renderer_memory(v->r.core, &v->memory);
    vfp_render_close(&v->r);
    v->open = 0;
}

/* One round of one variant: a warm-up frame one step before the first timed view (so that every timed frame
 * is a new view), then the rotation. Returns VFP_OK, or VFP_ERR with err. */
static vfp_status_t time_round(const sim_opts_t *o, variant_t *v, int round, const vf_image_t *img, char *err,
                               size_t errlen)
{
    vf_view_t before = sim_view(o->azimuth - 2.0, o->elevation, o->roll, o->zoom);
    vfp_status_t status = vfp_render_frame(&v->r, &before, img, err, errlen);
    double *ms = v->frame_ms + (size_t)round * o->frames;
    double sum = 0, tables = 0, composite = 0, warp = 0;
    for (int f = 0; status == VFP_OK && f < o->frames; f++) {
        vf_view_t view = sim_view(o->azimuth + 2.0 * f, o->elevation, o->roll, o->zoom);
        double t0 = vfp_now_ms();
        status = vfp_render_frame(&v->r, &view, img, err, errlen);
        ms[f] = vfp_now_ms() - t0;
        sum += ms[f];
        tables += v->r.ms_tables;
        composite += v->r.ms_composite;
        warp += v->r.ms_warp;
    }
    v->round_mean[round] = sum / o->frames;
    v->round_tables[round] = tables / o->frames;
    v->round_composite[round] = composite / o->frames;
    v->round_warp[round] = warp / o->frames;
    return status;
}

/* Decide whether every renderer can be set up at once: their arenas together within half the memory available
 * (the machine is shared), or unknown memory. Returns VFP_OK, or VFP_ERR with err. */
static vfp_status_t make_plan(const sim_scene_t *s, variant_t *v, int count, const sim_opts_t *o, plan_t *p, char *err,
                              size_t errlen)
{
    *p = (plan_t){.rounds = o->rounds, .frames = o->frames, .count = count};
    for (int c = 0; c < count; c++) {
        size_t fixed;
        vf_status_t st = vf_renderer_bytes(&v[c].params, &s->vol.core, &fixed);
        if (st != VF_OK) {
            snprintf(err, errlen, "cannot render this volume: %s", vf_status_text(st));
            return VFP_ERR;
        }
        v[c].arena_estimate = fixed + fixed / 4; /* as vfp_render_open reserves */
        p->total_bytes += v[c].arena_estimate;
    }
    p->available_bytes = memory_available();
    p->all_at_once = count == 1 || p->available_bytes == 0 || p->total_bytes <= p->available_bytes / 2;
    return VFP_OK;
}

/* The variant a round starts with: the table order rotated so that each variant takes a different place in
 * each round, the starts spread evenly over the table. */
static int round_start(const plan_t *p, int round)
{
    return (int)((long)round * p->count / p->rounds % p->count);
}

/* Every round, every variant; ratios to the first variant per round. Returns VFP_OK, or VFP_ERR with err. */
static vfp_status_t measure(const sim_scene_t *s, const sim_opts_t *o, variant_t *v, const plan_t *p, int progress,
                            char *err, size_t errlen)
{
    vf_image_t img;
    if (sim_image_alloc(&img, s->width, s->height, s->format)) {
        snprintf(err, errlen, "out of memory for a %ux%u image", s->width, s->height);
        return VFP_ERR;
    }
    vfp_status_t status = VFP_OK;
    for (int c = 0; status == VFP_OK && p->all_at_once && c < p->count; c++)
        status = setup(s, &v[c], err, errlen);
    double start = vfp_now_ms();
    for (int round = 0; status == VFP_OK && round < p->rounds; round++) {
        int first = round_start(p, round);
        double t0 = vfp_now_ms();
        for (int i = 0; status == VFP_OK && i < p->count; i++) {
            variant_t *x = &v[(first + i) % p->count];
            if (!x->open)
                status = setup(s, x, err, errlen);
            if (status == VFP_OK)
                status = time_round(o, x, round, &img, err, errlen);
            if (!p->all_at_once)
                teardown(x);
        }
        if (status == VFP_OK && progress)
            fprintf(stderr, "volfix-sim bench: round %d of %d done in %.1f s (%.0f s so far)\n", round + 1,
                    p->rounds, (vfp_now_ms() - t0) / 1000, (vfp_now_ms() - start) / 1000);
    }
    for (int c = 0; c < p->count; c++) {
        teardown(&v[c]); /* keeps the memory report of the open ones */
        for (int round = 0; status == VFP_OK && round < p->rounds; round++)
            v[c].ratio[round] = v[0].round_mean[round] / v[c].round_mean[round];
    }
    sim_image_free(&img);
    return status;
}

static void summarise(const variant_t *v, const plan_t *p, summary_t *out)
{
    int lo, hi;
    middle_rounds(v->round_mean, p->rounds, &lo, &hi);
    out->mean = (v->round_mean[lo] + v->round_mean[hi]) / 2;
    out->tables = (v->round_tables[lo] + v->round_tables[hi]) / 2;
    out->composite = (v->round_composite[lo] + v->round_composite[hi]) / 2;
    out->warp = (v->round_warp[lo] + v->round_warp[hi]) / 2;
    size_t n = (size_t)p->rounds * p->frames;
    double *tmp = malloc(sizeof *tmp * (n > (size_t)p->rounds ? n : (size_t)p->rounds));
    if (!tmp) { /* the summary of a benchmark is not worth failing for: fall back to the middle round */
        out->median = out->mean;
        out->ratio = out->ratio_min = out->ratio_max = v->ratio[lo];
        return;
    }
    memcpy(tmp, v->frame_ms, sizeof *tmp * n);
    out->median = median_sorting(tmp, (int)n);
    memcpy(tmp, v->ratio, sizeof *tmp * p->rounds);
    out->ratio = median_sorting(tmp, p->rounds);
    out->ratio_min = tmp[0];
    out->ratio_max = tmp[p->rounds - 1];
    free(tmp);
}

/* A JSON list of numbers with the given decimals. */
static void print_list(const double *values, int n, int decimals)
{
    for (int i = 0; i < n; i++)
        printf("%s%.*f", i ? ", " : "", decimals, values[i]);
}

/* How the matrix was measured: rounds, frames, order, renderers, and what the columns summarise. */
static void print_method(const plan_t *p)
{
    if (p->rounds == 1) {
        printf("measured in 1 round: every variant's %d frame%s once (after a warm-up frame), in table order\n",
               p->frames, p->frames > 1 ? "s" : "");
    } else {
        printf("measured in %d rounds: each times every variant's %d frames once (after a warm-up frame), in table "
               "order rotated: rounds start at row", p->rounds, p->frames);
        for (int r = 0; r < p->rounds && r < 12; r++)
            printf("%s %d", r ? "," : "", round_start(p, r) + 1);
        printf("%s\n", p->rounds > 12 ? ", ..." : "");
    }
    if (p->all_at_once)
        printf("all %d renderers set up first (%.0f MB of arenas)\n", p->count, p->total_bytes / 1048576.0);
    else
        printf("renderers set up again at their turn in each round, one at a time: all %d would need %.0f MB, "
               "%.0f MB available\n", p->count, p->total_bytes / 1048576.0, p->available_bytes / 1048576.0);
    printf("ms/frame: median over rounds of each round's mean; median: of all frames; stages: of the median "
           "round%s\n", p->rounds % 2 ? "" : "s");
    printf("x point: point's ms / the variant's ms in the same round (its frame-rate ratio), median over rounds "
           "(min-max)\n");
}

static void print_one(const sim_scene_t *s, const variant_t *v, const plan_t *p, int json)
{
    char about[512];
    summary_t m;
    summarise(v, p, &m);
    sim_scene_describe(s, about, sizeof about);
    if (json) {
        printf("{\"scene\": \"%s\", \"mode\": \"%s\", \"lookup\": \"%s\", \"correction\": \"%s\", \"buffer\": \"%s\", "
               "\"frames\": %d, \"rounds\": %d, \"threads\": %d, \"ms_per_frame\": %.3f, \"ms_per_frame_rounds\": [",
               about, vf_mode_name(s->params.mode), vf_lookup_name(s->params.lookup),
               vf_correction_name(s->params.correction), vf_buffer_name(s->params.buffer), p->frames, p->rounds,
               s->threads, m.mean);
        print_list(v->round_mean, p->rounds, 3);
        printf("], \"median_ms\": %.3f, \"tables_ms\": %.3f, \"composite_ms\": %.3f, \"warp_ms\": %.3f, "
               "\"window_ms\": %.3f, \"classify_rle_ms\": %.3f, \"memory_bytes\": %zu}\n",
               m.median, m.tables, m.composite, m.warp, v->window_ms, v->classify_ms, v->memory.total);
        return;
    }
    const vf_memory_t *mem = &v->memory;
    printf("%s, %d thread%s\n", about, s->threads, s->threads > 1 ? "s" : "");
    printf("slices (window): %.1f ms; classification and run-length encoding: %.1f ms\n", v->window_ms,
           v->classify_ms);
    if (p->rounds > 1) {
        printf("%d rounds of %d frames, a warm-up frame before each: mean %.2f ms (the median of the rounds' "
               "means:", p->rounds, p->frames, m.mean);
        for (int r = 0; r < p->rounds; r++)
            printf(" %.2f", v->round_mean[r]);
        printf("), median frame %.2f ms (%.1f frames/s)\n", m.median, 1000.0 / m.mean);
    } else {
        printf("%d frames: mean %.2f ms, median %.2f ms (%.1f frames/s)\n", p->frames, m.mean, m.median,
               1000.0 / m.mean);
    }
    printf("per frame%s: tables %.2f ms, compositing %.2f ms, warp %.2f ms\n",
           p->rounds == 1 ? "" : p->rounds % 2 ? " (median round)" : " (median rounds)", m.tables, m.composite, m.warp);
    printf("memory: %.1f MiB (slices %.1f, run lists %.1f, tables %.2f, intermediate image %.1f",
           mem->total / 1048576.0, mem->slices / 1048576.0, mem->runs / 1048576.0, mem->tables / 1048576.0,
           mem->intermediate / 1048576.0);
    if (mem->normals) /* lit: normal codes and gradient magnitudes, a copy per principal axis like the slices */
        printf(", normals %.1f", mem->normals / 1048576.0);
    printf(")\n");
}

static void print_matrix(sim_scene_t *s, const variant_t *v, const plan_t *p, int json)
{
    char about[512];
    if (json)
        printf("[\n");
    else {
        s->params = v[0].params;
        sim_scene_describe(s, about, sizeof about);
        printf("%s: %d thread%s (the layout of Schulze et al. 2003, Table 1)\n", about, s->threads,
               s->threads > 1 ? "s" : "");
        print_method(p);
        printf("%-11s %-9s %-11s %-7s %9s %9s %8s %11s %8s   %-34s %s\n", "mode", "lookup", "correction", "buffer",
               "ms/frame", "frames/s", "x point", "(min-max)", "median", "(tables + compositing + warp, ms)",
               "ms/frame per round");
    }
    for (int c = 0; c < p->count; c++) {
        const vf_params_t *q = &v[c].params;
        summary_t m;
        summarise(&v[c], p, &m);
        if (json) {
            s->params = *q;
            sim_scene_describe(s, about, sizeof about);
            printf("  {\"mode\": \"%s\", \"table2_size\": %u, \"lookup\": \"%s\", \"correction\": \"%s\", "
                   "\"buffer\": \"%s\", \"ms_per_frame\": %.3f, \"median_ms\": %.3f, \"frames\": %d, \"rounds\": %d, "
                   "\"ms_per_frame_rounds\": [",
                   vf_mode_name(q->mode), q->mode == VF_MODE_PREINT2 ? (unsigned)q->table2_size : 0u,
                   vf_lookup_name(q->lookup), vf_correction_name(q->correction),
                   vf_buffer_name(q->buffer), m.mean, m.median, p->frames, p->rounds);
            print_list(v[c].round_mean, p->rounds, 3);
            printf("], \"x_point\": %.4f, \"x_point_min\": %.4f, \"x_point_max\": %.4f, \"x_point_rounds\": [",
                   m.ratio, m.ratio_min, m.ratio_max);
            print_list(v[c].ratio, p->rounds, 4);
            printf("], \"tables_ms\": %.3f, \"composite_ms\": %.3f, \"warp_ms\": %.3f, \"memory_bytes\": %zu, "
                   "\"scene\": \"%s\"}%s\n",
                   m.tables, m.composite, m.warp, v[c].memory.total, about, c + 1 < p->count ? "," : "");
        } else {
            char range[32], split[64];
            snprintf(range, sizeof range, "(%.2f-%.2f)", m.ratio_min, m.ratio_max);
            snprintf(split, sizeof split, "(%.2f + %.2f + %.2f)", m.tables, m.composite, m.warp);
            char mode[24];
            snprintf(mode, sizeof mode, q->mode == VF_MODE_PREINT2 ? "%s/%u" : "%s", vf_mode_name(q->mode),
                     (unsigned)q->table2_size);
            printf("%-11s %-9s %-11s %-7s %9.2f %9.1f %8.2f %11s %8.2f   %-34s", mode,
                   vf_lookup_name(q->lookup), vf_correction_name(q->correction),
                   q->mode == VF_MODE_PREINT1 ? vf_buffer_name(q->buffer) : "-", m.mean, 1000.0 / m.mean, m.ratio,
                   range, m.median, split);
            for (int r = 0; r < p->rounds; r++)
                printf(" %.2f", v[c].round_mean[r]);
            printf("\n");
        }
    }
    if (json)
        printf("]\n");
}

/* Schulze et al. 2003, Table 1: standard shear-warp, then pre-integrated with each combination of lookup,
 * opacity correction and buffer slices; the VolPack baseline (preclass) last. Point first: ratios are to it. */
static int matrix_variants(const vf_params_t *scene_params, variant_t *v)
{
    int count = 0;
    vf_params_t base = *scene_params;
    base.mode = VF_MODE_POINT;
    base.lookup = VF_LOOKUP_NEAREST;
    base.correction = VF_CORRECTION_REBUILD;
    base.buffer = VF_BUFFER_SLICE;
    v[count++].params = base;
    for (int lookup = 0; lookup <= VF_LOOKUP_BILINEAR; lookup++) /* preint1's lookups (trilinear: preint2's) */
        for (int correction = 0; correction < VF_CORRECTION_COUNT; correction++)
            for (int buffer = 0; buffer < VF_BUFFER_COUNT; buffer++) {
                vf_params_t q = base;
                q.mode = VF_MODE_PREINT1;
                q.lookup = (vf_lookup_t)lookup;
                q.correction = (vf_correction_t)correction;
                q.buffer = (vf_buffer_t)buffer;
                v[count++].params = q;
            }
    base.mode = VF_MODE_PRECLASS;
    v[count++].params = base;
    /* order 2 (not in Table 1): the 3D table at 32, 64 and 128 a side, looked up nearest and trilinearly, built
     * once and corrected by lookup (a rotation changes the slab length every frame, and a rebuilt 128^3 table
     * takes seconds); one row rebuilds the default 64^3 table for every view, for the cost of that */
    base.mode = VF_MODE_PREINT2;
    base.correction = VF_CORRECTION_LUT;
    for (uint32_t n2 = 32; n2 <= 128; n2 *= 2)
        for (int lookup = 0; lookup < 2; lookup++) {
            vf_params_t q = base;
            q.table2_size = n2;
            q.lookup = lookup ? VF_LOOKUP_TRILINEAR : VF_LOOKUP_NEAREST;
            v[count++].params = q;
        }
    base.table2_size = 64;
    base.correction = VF_CORRECTION_REBUILD;
    v[count++].params = base;
    return count;
}

int sim_cmd_bench(int argc, char **argv)
{
    sim_opts_t o;
    sim_scene_t s;
    unsigned groups = SIM_OPT_JSON | SIM_OPT_FRAMES | SIM_OPT_MATRIX | SIM_OPT_ROUNDS;
    vfp_status_t status = sim_scene_command(&o, &s, argc, argv, groups, usage_head);
    if (status)
        return vfp_exit_status(status);
    if (o.rounds == 0)
        o.rounds = o.matrix ? 3 : 1;
    char err[VFP_ERR_LEN];
    variant_t v[MAX_VARIANTS];
    memset(v, 0, sizeof v);
    int count = 1;
    if (o.matrix)
        count = matrix_variants(&s.params, v);
    else
        v[0].params = s.params;
    plan_t p;
    status = make_plan(&s, v, count, &o, &p, err, sizeof err);
    if (status == VFP_OK && variants_alloc(v, count, &p)) {
        snprintf(err, sizeof err, "out of memory");
        status = VFP_ERR;
    }
    if (status == VFP_OK)
        status = measure(&s, &o, v, &p, o.matrix || p.rounds > 1, err, sizeof err);
    if (status)
        fprintf(stderr, "volfix-sim: %s\n", err);
    else if (o.matrix)
        print_matrix(&s, v, &p, o.json);
    else
        print_one(&s, &v[0], &p, o.json);
    variants_free(v, count);
    sim_scene_free(&s);
    return vfp_exit_status(status);
}
