/* SPDX-License-Identifier: MIT */
/* ref_options.c: the options of section 4b that change a segment's value: bilinear table lookup, 8-bit tables and
 * the lut correction of the slab length. (Mode preclass is compositing: ref_render.c.) */
#include "ref/ref.h"

#include <math.h>

/* Bilinear position of a sample s in a table of N entries: x = s (N - 1) / 255, i = min(floor(x), N - 2),
 * f = x - i (so s = 255 gives i = N - 2, f = 1: the last entry, and nothing beyond it is read). */
static int lookup_position(double s, int N, double *f)
{
    double x = s * (N - 1) / 255.0;
    int i = (int)floor(x);
    i = i > N - 2 ? N - 2 : i < 0 ? 0 : i;
    *f = x - i;
    return i;
}

void ref_lookup_point(const double *table, int N, ref_lookup_t lookup, double s, double out[4])
{
    if (lookup != REF_LOOKUP_BILINEAR) {
        const double *e = table + 4 * (size_t)ref_table_index(s, N);
        for (int c = 0; c < 4; c++)
            out[c] = e[c];
        return;
    }
    double f;
    const double *e = table + 4 * (size_t)lookup_position(s, N, &f);
    for (int c = 0; c < 4; c++)
        out[c] = (1 - f) * e[c] + f * e[4 + c];
}

void ref_lookup_preint(const double *table, int N, ref_lookup_t lookup, double front, double back, double out[4])
{
    size_t n = (size_t)N;
    if (lookup != REF_LOOKUP_BILINEAR) {
        const double *e = table + 4 * ((size_t)ref_table_index(front, N) * n + (size_t)ref_table_index(back, N));
        for (int c = 0; c < 4; c++)
            out[c] = e[c];
        return;
    }
    double f, g;
    size_t i = (size_t)lookup_position(front, N, &f), j = (size_t)lookup_position(back, N, &g);
    const double *t00 = table + 4 * (i * n + j), *t10 = t00 + 4 * n, *t01 = t00 + 4, *t11 = t10 + 4;
    for (int c = 0; c < 4; c++)
        out[c] = (1 - f) * (1 - g) * t00[c] + f * (1 - g) * t10[c] + (1 - f) * g * t01[c] + f * g * t11[c];
}

int ref_table_bits(double *values, size_t count, int bits)
{
    if (bits != 0 && bits != 16 && bits != 8)
        return -1;
    if (bits == 8)
        for (size_t n = 0; n < count; n++)
            values[n] = floor(255.0 * values[n] + 0.5) / 255.0; /* round half up, as everywhere in the spec */
    return 0;
}

int ref_lut_init(ref_lut_t *lut, double rho)
{
    if (!lut || !(rho > 0) || !isfinite(rho))
        return -1;
    lut->rho = rho;
    for (int k = 0; k <= REF_LUT_KNOTS; k++) {
        double a = (double)k / REF_LUT_KNOTS;
        lut->F[k] = 1 - pow(1 - a, rho); /* 1 - a and, for rho = 1, pow are exact: F(a_k) = a_k exactly */
        lut->G[k] = k ? lut->F[k] / a : rho;
    }
    return 0;
}

/* Written as F[k] + w (F[k+1] - F[k]): for rho = 1 (F[k] = a_k, G = 1) every step is exact, so the correction is
 * exactly the identity. */
void ref_lut_correct(const ref_lut_t *lut, double seg[4])
{
    double a = seg[0] < 0 ? 0 : seg[0] > 1 ? 1 : seg[0];
    double t = a * REF_LUT_KNOTS;
    int k = (int)floor(t);
    k = k > REF_LUT_KNOTS - 1 ? REF_LUT_KNOTS - 1 : k;
    double w = t - k;
    double F = lut->F[k] + w * (lut->F[k + 1] - lut->F[k]);
    double G = lut->G[k] + w * (lut->G[k + 1] - lut->G[k]);
    seg[0] = F;
    for (int c = 1; c < 4; c++)
        seg[c] *= G;
}

void ref_lut_correct_lit(const ref_lut_t *lut, double seg[4], double lit[4])
{
    const double a = seg[0] < 0 ? 0 : seg[0] > 1 ? 1 : seg[0], t = a * REF_LUT_KNOTS;
    int k = (int)floor(t);
    k = k > REF_LUT_KNOTS - 1 ? REF_LUT_KNOTS - 1 : k;
    const double G = lut->G[k] + (t - k) * (lut->G[k + 1] - lut->G[k]);
    ref_lut_correct(lut, seg);
    for (int c = 0; c < 4; c++)
        lit[c] *= G; /* S_f and D_f scale as the colour does */
}
