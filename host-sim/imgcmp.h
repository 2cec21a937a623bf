/* SPDX-License-Identifier: MIT */
/* imgcmp.h: how far apart two 8-bit RGB images are, and a picture of where. */
#ifndef SIM_IMGCMP_H
#define SIM_IMGCMP_H

#include <stddef.h>
#include <stdint.h>

typedef struct sim_diff {
    double psnr_db;        /* over all channels; 99 when the images are identical */
    int max_abs[4];        /* per channel r, g, b, and [3] the largest of them */
    double mean_abs[4];
    double over1_pct;      /* pixels with any channel off by more than 1 */
    size_t pixels;
} sim_diff_t;

void sim_diff(const uint8_t *a, const uint8_t *b, size_t pixels, sim_diff_t *d);

/* A grey image of the largest channel difference per pixel, scaled by `gain` (clamped to 255). */
void sim_diff_image(const uint8_t *a, const uint8_t *b, size_t pixels, int gain, uint8_t *out_rgb);

#endif
