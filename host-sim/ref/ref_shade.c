/* SPDX-License-Identifier: MIT */
/* ref_shade.c: lights, Blinn-Phong shading of a normal, the gradient-opacity factor, and lit segments
 * (section 7), in double with libm. */
#include "ref/ref.h"

#include <math.h>

int ref_lights_init(ref_lights_t *lights, const ref_lighting_t *l, const double R[3][3])
{
    if (!lights || !l || l->light_count < 1 || l->light_count > REF_MAX_LIGHTS || l->shininess < 1 ||
        l->shininess > 255 || !(l->ka >= 0 && l->ka <= 1) || !(l->kd >= 0 && l->kd <= 1) ||
        !(l->ks >= 0 && l->ks <= 1) || l->gradient_lo < 0 || l->gradient_hi > 255 ||
        (l->gradient_hi <= l->gradient_lo && (l->gradient_lo || l->gradient_hi)))
        return -1;
    lights->lighting = l;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            lights->R[r][c] = R[r][c];
    for (int k = 0; k < l->light_count; k++) {
        double sa, ca, se, ce;
        ref_sincos(l->light_azimuth[k], &sa, &ca);
        ref_sincos(l->light_elevation[k], &se, &ce);
        double *L = lights->L[k], *H = lights->H[k];
        L[0] = sa * ce;
        L[1] = -se;
        L[2] = -ca * ce;
        /* H = (L + V) / |L + V| with V = (0, 0, -1) towards the viewer; zero when L = -V */
        H[0] = L[0], H[1] = L[1], H[2] = L[2] - 1;
        const double len = sqrt(H[0] * H[0] + H[1] * H[1] + H[2] * H[2]);
        for (int a = 0; a < 3; a++)
            H[a] = len > 0 ? H[a] / len : 0;
    }
    return 0;
}

static double round_bits(double v, int bits)
{
    const double scale = ldexp(1.0, bits);
    return floor(v * scale + 0.5) / scale;
}

void ref_shade_normal(const ref_lights_t *lights, const double n[3], double *ld, double *ls)
{
    const ref_lighting_t *l = lights->lighting;
    if (!l->shade) {
        *ld = 1, *ls = 0;
        return;
    }
    double d = l->ka, s = 0;
    if (n[0] != 0 || n[1] != 0 || n[2] != 0) {
        double m[3];
        for (int a = 0; a < 3; a++)
            m[a] = lights->R[a][0] * n[0] + lights->R[a][1] * n[1] + lights->R[a][2] * n[2];
        if (m[2] > 0) /* facing away from the viewer: turned round (two-sided lighting) */
            m[0] = -m[0], m[1] = -m[1], m[2] = -m[2];
        double diffuse = 0, specular = 0;
        for (int k = 0; k < l->light_count; k++) {
            const double *L = lights->L[k], *H = lights->H[k];
            diffuse += fmax(0.0, m[0] * L[0] + m[1] * L[1] + m[2] * L[2]);
            specular += pow(fmax(0.0, m[0] * H[0] + m[1] * H[1] + m[2] * H[2]), l->shininess);
        }
        d += l->kd * diffuse;
        s = l->ks * specular;
    }
    if (l->shade_bits) {
        d = round_bits(d, l->shade_bits);
        s = round_bits(s, l->shade_bits);
    }
    *ld = d, *ls = s;
}

double ref_gradient_factor(const ref_lighting_t *l, double gm)
{
    if (l->gradient_hi <= l->gradient_lo)
        return 1;
    const double g = (gm - l->gradient_lo) / (l->gradient_hi - l->gradient_lo);
    return g < 0 ? 0 : g > 1 ? 1 : g;
}

void ref_light_point(double seg[4], ref_shade_t sh)
{
    const double a = seg[0];
    for (int c = 1; c < 4; c++)
        seg[c] = fmin(sh.d * seg[c] + sh.s * a, a) * sh.g;
    seg[0] = a * sh.g;
}

void ref_light_slab(double seg[4], const double lit[4], ref_shade_t f, ref_shade_t b)
{
    const double a = seg[0], g = (f.g + b.g) / 2;
    for (int c = 1; c < 4; c++) {
        const double C = b.d * seg[c] + (f.d - b.d) * lit[c] + b.s * a + (f.s - b.s) * lit[0];
        seg[c] = fmin(fmax(C, 0.0), a) * g;
    }
    seg[0] = a * g;
}
