/* SPDX-License-Identifier: MIT */
/*
 * test_window16.c: 16-bit data's default window keeps sparse bright structures (docs/defaults.md). Generated
 * volumes of soft tissue (values 1000..1999, spread through the volume) hold a thin wire of a given share of the
 * voxels at a given multiple of the tissue's mean, lying along x on the face nearest the viewer. The measure:
 * the wire's contrast, in 8-bit levels (the three channels averaged): the mean level of the wire's pixels (those
 * that change when the wire's voxels are given back their tissue values, same window) less the brightest
 * tissue's (the 99th percentile of the tissue-only picture's levels). The wire must be brighter than the
 * brightest tissue by at least 32 levels (an eighth of the range), over at least 8 pixels; and the window must
 * keep the tissue (up to its 99.5 percentile) over at least half of its width. The old default (the 0.5 and 99.5
 * percentiles) is measured too, and must fail: the test tells the two apart.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "frame_check.h"
#include "io/pngio.h"
#include "scene.h"

#define N 96

static char path[256];

static int cmp_int(const void *a, const void *b)
{
    return *(const int *)a - *(const int *)b;
}

static int cmp_u16(const void *a, const void *b)
{
    return (int)*(const uint16_t *)a - (int)*(const uint16_t *)b;
}

/* The volume: tissue everywhere, and a wire of `wire` voxels (or none) at `value`: c voxels by c in y and z (from
 * N/2 and from the face z, inwards; c the smallest that keeps it at most N/2 long), along x from x = N/4 on. */
static void write_volume(uint16_t *v, long wire, int value, int z)
{
    for (int k = 0; k < N; k++)
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++)
                v[((size_t)k * N + j) * N + i] = (uint16_t)(1000 + (i * 7 + j * 13 + k * 5) % 1000);
    int dz = z == 0 ? 1 : -1;
    long c = 1;
    while (c * c * (N / 2) < wire)
        c++;
    for (long w = 0; w < wire; w++)
        v[((size_t)(z + dz * (int)(w % c)) * N + N / 2 + (w / c) % c) * N + N / 4 + w / (c * c)] = (uint16_t)value;
    FILE *f = fopen(path, "wb");
    fwrite(v, sizeof *v, (size_t)N * N * N, f);
    fclose(f);
}

/* Renders path (window: NULL for the default) into rgb; the window used in *used. */
static int render(const char *window, uint8_t *rgb, vf_window_t *used)
{
    char *argv[16] = {path, "--dims", "96,96,96", "--type", "uint16", "--view", "0,0", "--size", "128x128",
                      "--threads", "2"};
    int argc = 11;
    if (window) {
        argv[argc++] = "--window";
        argv[argc++] = (char *)window;
    }
    sim_opts_t o;
    if (sim_parse(&o, argc, argv, SIM_OPT_SCENE, ""))
        return -1;
    sim_scene_t s;
    vf_image_t img;
    vf_factor_t f;
    if (frame_core(&o, &s, &img, &f))
        return -1;
    vfp_image_to_rgb(&img, rgb);
    *used = s.window;
    sim_image_free(&img);
    sim_scene_free(&s);
    return 0;
}

/* The wire's contrast (see the top) with the given window (NULL: the default); its footprint in *pixels. */
static double contrast(uint16_t *v, long wire, int value, int z, const char *window, long *pixels, vf_window_t *w)
{
    static uint8_t a[128 * 128 * 3], b[128 * 128 * 3];
    write_volume(v, wire, value, z);
    if (render(window, a, w))
        return -1;
    char fixed[64];
    snprintf(fixed, sizeof fixed, "%d,%d", w->lo, w->hi);
    write_volume(v, 0, value, z);
    vf_window_t same;
    if (render(fixed, b, &same))
        return -1;
    /* the brightest tissue: the 99th percentile of the tissue-only picture's levels, where it shows */
    static int levels[128 * 128];
    size_t shown = 0;
    for (size_t p = 0; p < 128 * 128; p++)
        if (b[3 * p] | b[3 * p + 1] | b[3 * p + 2])
            levels[shown++] = b[3 * p] + b[3 * p + 1] + b[3 * p + 2];
    qsort(levels, shown, sizeof *levels, cmp_int);
    double brightest = shown ? levels[shown * 99 / 100] / 3.0 : 0;
    double sum = 0;
    *pixels = 0;
    for (size_t p = 0; p < 128 * 128; p++)
        if (a[3 * p] != b[3 * p] || a[3 * p + 1] != b[3 * p + 1] || a[3 * p + 2] != b[3 * p + 2]) {
            sum += (a[3 * p] + a[3 * p + 1] + a[3 * p + 2]) / 3.0;
            (*pixels)++;
        }
    if (getenv("WINDOW16_VERBOSE"))
        printf("#   wire pixels %.1f, brightest tissue %.1f\n", *pixels ? sum / (double)*pixels : 0, brightest);
    return *pixels ? sum / (double)*pixels - brightest : 0;
}

static void wire_stays_distinguishable(void)
{
    snprintf(path, sizeof path, "/tmp/volfix-window16-%d.raw", (int)getpid());
    uint16_t *v = malloc(sizeof *v * N * N * N);
    uint16_t *sorted = malloc(sizeof *v * N * N * N);
    const double shares[] = {0.0002, 0.0005, 0.001};
    const double times[] = {2, 4, 8};
    /* the face nearest the viewer at view 0,0: the one whose wire changes the picture */
    long pixels;
    vf_window_t w;
    contrast(v, 4 * N / 2, 8000, 0, NULL, &pixels, &w);
    int z = pixels > 0 ? 0 : N - 1;
    for (size_t si = 0; si < sizeof shares / sizeof shares[0]; si++)
        for (size_t ti = 0; ti < sizeof times / sizeof times[0]; ti++) {
            long wire = lround(shares[si] * N * N * N);
            int value = (int)(times[ti] * 1500);
            double c = contrast(v, wire, value, z, NULL, &pixels, &w);
            /* the old default window, from the same volume's percentiles */
            write_volume(v, wire, value, z);
            memcpy(sorted, v, sizeof *v * N * N * N);
            qsort(sorted, (size_t)N * N * N, sizeof *sorted, cmp_u16);
            size_t n = (size_t)N * N * N;
            int p005 = sorted[(n - 1) * 5 / 1000], p995 = sorted[((n - 1) * 995 + 999) / 1000];
            char old[64];
            snprintf(old, sizeof old, "%d,%d", p005, p995);
            long old_pixels;
            vf_window_t ow;
            double c_old = contrast(v, wire, value, z, old, &old_pixels, &ow);
            printf("# wire %.2f%% of the voxels at %gx: window %d,%d contrast %.1f levels over %ld pixels; "
                   "old window %s: %.1f over %ld\n",
                   shares[si] * 100, times[ti], w.lo, w.hi, c, pixels, old, c_old, old_pixels);
            CHECK_MSG(c >= 32 && pixels >= 8, "wire %.2f%% at %gx: contrast %.1f over %ld pixels", shares[si] * 100,
                      times[ti], c, pixels);
            CHECK_MSG(p995 - w.lo >= (w.hi - w.lo) / 2, "tissue up to %d in window %d,%d: less than half", p995,
                      w.lo, w.hi);
            if (times[ti] >= 4) /* the old window clipped the wire with the brightest tissue */
                CHECK_MSG(c_old < 8, "old window: contrast %.1f (the measure does not tell the windows apart)",
                          c_old);
        }
    remove(path);
    free(sorted);
    free(v);
}

CHECK_CASES({"wire_stays_distinguishable", wire_stays_distinguishable});
CHECK_RUN("window16")
