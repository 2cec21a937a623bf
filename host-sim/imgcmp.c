/* SPDX-License-Identifier: MIT */
/* imgcmp.c: image differences (see imgcmp.h). */
#include "imgcmp.h"

#include <math.h>
#include <stdlib.h>

void sim_diff(const uint8_t *a, const uint8_t *b, size_t pixels, sim_diff_t *d)
{
    double sum[3] = {0, 0, 0}, sq = 0;
    size_t over1 = 0;
    *d = (sim_diff_t){0};
    d->pixels = pixels;
    for (size_t p = 0; p < pixels; p++) {
        int worst = 0;
        for (int c = 0; c < 3; c++) {
            int e = abs((int)a[p * 3 + c] - (int)b[p * 3 + c]);
            sum[c] += e;
            sq += (double)e * e;
            if (e > d->max_abs[c])
                d->max_abs[c] = e;
            if (e > worst)
                worst = e;
        }
        over1 += worst > 1;
    }
    for (int c = 0; c < 3; c++) {
        d->mean_abs[c] = pixels ? sum[c] / pixels : 0;
        if (d->max_abs[c] > d->max_abs[3])
            d->max_abs[3] = d->max_abs[c];
    }
    d->mean_abs[3] = (d->mean_abs[0] + d->mean_abs[1] + d->mean_abs[2]) / 3;
    double mse = pixels ? sq / (3.0 * pixels) : 0;
    d->psnr_db = mse > 0 ? 10 * log10(255.0 * 255.0 / mse) : 99;
    if (d->psnr_db > 99)
        d->psnr_db = 99;
    d->over1_pct = pixels ? 100.0 * over1 / pixels : 0;
}

void sim_diff_image(const uint8_t *a, const uint8_t *b, size_t pixels, int gain, uint8_t *out)
{
    for (size_t p = 0; p < pixels; p++) {
        int worst = 0;
        for (int c = 0; c < 3; c++) {
            int e = abs((int)a[p * 3 + c] - (int)b[p * 3 + c]);
            worst = e > worst ? e : worst;
        }
        int v = worst * gain > 255 ? 255 : worst * gain;
        out[p * 3] = out[p * 3 + 1] = out[p * 3 + 2] = (uint8_t)v;
    }
}
