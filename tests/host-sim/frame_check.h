/* SPDX-License-Identifier: MIT */
/*
 * frame_check.h: one frame of the fixed-point core against the double reference, as the accuracy suites
 * (test_accuracy.c, test_order2_accuracy.c) judge it: PSNR >= 50 dB and no channel of any pixel more than 2 of 255
 * apart. Header-only and static inline, as check.h is, so that each test program stays one file.
 */
#ifndef FRAME_CHECK_H
#define FRAME_CHECK_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "imgcmp.h"
#include "io/pngio.h"
#include "scene.h"

/* Renders o's scene with the core into *img (the scene in *s, its factoring in *f); on failure prints "# why" and
 * returns -1, else 0. */
static inline int frame_core(const sim_opts_t *o, sim_scene_t *s, vf_image_t *img, vf_factor_t *f)
{
    char err[VFP_ERR_LEN];
    if (sim_scene_load(s, o, err, sizeof err) || sim_render_core(s, img, f, err, sizeof err)) {
        printf("# %s\n", err);
        return -1;
    }
    return 0;
}

/* Renders o's scene with the core and the reference, compares them into *d and prints the case's line, "ok - NAME:
 * PSNR ..." or "not ok - NAME: ...". Returns 1 when the frames agree, 0 when they do not, -1 when one could not be
 * rendered (d is then untouched). */
static inline int frame_check(const sim_opts_t *o, const char *name, sim_diff_t *d)
{
    char err[VFP_ERR_LEN];
    sim_scene_t s;
    vf_image_t core, ref;
    vf_factor_t factor;
    if (sim_scene_load(&s, o, err, sizeof err) || sim_render_core(&s, &core, &factor, err, sizeof err)) {
        printf("not ok - %s: %s\n", name, err);
        return -1;
    }
    if (sim_render_reference(&s, &factor, &ref, err, sizeof err)) {
        printf("not ok - %s: %s\n", name, err);
        sim_image_free(&core);
        sim_scene_free(&s);
        return -1;
    }
    size_t pixels = (size_t)s.width * s.height;
    uint8_t *a = malloc(pixels * 3), *b = malloc(pixels * 3);
    vfp_image_to_rgb(&core, a);
    vfp_image_to_rgb(&ref, b);
    sim_diff(a, b, pixels, d);
    int ok = d->psnr_db >= 50 && d->max_abs[3] <= 2;
    printf("%s - %s: PSNR %.1f dB, max %d, mean %.4f, over 1: %.4f%%\n", ok ? "ok" : "not ok", name, d->psnr_db,
           d->max_abs[3], d->mean_abs[3], d->over1_pct);
    free(a);
    free(b);
    sim_image_free(&core);
    sim_image_free(&ref);
    sim_scene_free(&s);
    return ok;
}

#endif
