/* SPDX-License-Identifier: MIT */
/* ref_order2.c: order 2 in double (section 8): the 3D table from the pieces of the 2D table, entry by entry, and its
 * lighting values; its lookup; and preint2's frames (slabs of two slices, the last of an odd count of one), lit or
 * not. */
#include "ref/ref.h"

#include <math.h>
#include <stdlib.h>

#define K REF_ORDER2_PIECES

void ref_order2_ends(int N, int N2, int f, int m, int b, int end[K + 1])
{
    /* P(t_i) = 255 X_i / (256 (N2 - 1)) with the integer X_i = 256 f + 16 i (4m - 3f - b) + i^2 (2f - 4m + 2b)
     * (the entries' scalars are e 255 / (N2 - 1), t_i = i / 16); clamped to the three scalars, X_i to
     * [256 min, 256 max]; and idx(P) = round(P (N - 1) / 255), half up, of that exact value:
     * floor((2 X_i (N - 1) + D) / 2D) with D = 256 (N2 - 1). */
    const long long D = 256LL * (N2 - 1), lin = 16LL * (4 * m - 3 * f - b), quad = 2LL * f - 4LL * m + 2LL * b;
    const int lo3 = f < m ? (f < b ? f : b) : (m < b ? m : b), hi3 = f > m ? (f > b ? f : b) : (m > b ? m : b);
    for (int i = 0; i <= K; i++) {
        long long x = 256LL * f + i * lin + (long long)i * i * quad;
        x = x < 256LL * lo3 ? 256LL * lo3 : x > 256LL * hi3 ? 256LL * hi3 : x;
        end[i] = (int)((2 * x * (N - 1) + D) / (2 * D));
    }
}

int ref_order2_table(const ref_tf_point_t *tf, int npoints, int N, int N2, double d, double *out)
{
    if (!out || N2 < REF_MIN_TABLE2 || N2 > REF_MAX_TABLE2 || !(d > 0) || !isfinite(d) || N < REF_MIN_TABLE ||
        N > REF_MAX_TABLE)
        return -1;
    double *pieces = malloc(sizeof(double) * 4 * (size_t)N * (size_t)N);
    if (!pieces)
        return -1;
    /* the pieces: section 2's table for length 2d / K */
    if (ref_preint_table(tf, npoints, N, 2 * d / K, pieces)) {
        free(pieces);
        return -1;
    }
    for (int f = 0; f < N2; f++)
        for (int m = 0; m < N2; m++)
            for (int b = 0; b < N2; b++) {
                int end[K + 1];
                ref_order2_ends(N, N2, f, m, b, end);
                double A = 0, C[3] = {0, 0, 0};
                for (int i = 0; i < K; i++) { /* front to back */
                    const double *e = pieces + 4 * ((size_t)end[i] * (size_t)N + (size_t)end[i + 1]);
                    for (int c = 0; c < 3; c++)
                        C[c] += (1 - A) * e[1 + c];
                    A += (1 - A) * e[0];
                }
                double *o = out + 4 * (((size_t)f * (size_t)N2 + (size_t)m) * (size_t)N2 + (size_t)b);
                o[0] = A;
                o[1] = C[0];
                o[2] = C[1];
                o[3] = C[2];
            }
    free(pieces);
    return 0;
}

int ref_order2_lit_table(const ref_tf_point_t *tf, int npoints, int N, int N2, double d, double *out)
{
    if (!out || N2 < REF_MIN_TABLE2 || N2 > REF_MAX_TABLE2 || !(d > 0) || !isfinite(d) || N < REF_MIN_TABLE ||
        N > REF_MAX_TABLE)
        return -1;
    const size_t entries = (size_t)N * (size_t)N;
    double *pieces = malloc(sizeof(double) * 8 * entries), *lit = pieces + 4 * entries;
    if (!pieces)
        return -1;
    if (ref_preint_table(tf, npoints, N, 2 * d / K, pieces) || ref_lit_table(tf, npoints, N, 2 * d / K, lit)) {
        free(pieces);
        return -1;
    }
    for (int f = 0; f < N2; f++)
        for (int m = 0; m < N2; m++)
            for (int b = 0; b < N2; b++) {
                int end[K + 1];
                ref_order2_ends(N, N2, f, m, b, end);
                double T = 1, W[2][4] = {{0, 0, 0, 0}, {0, 0, 0, 0}};
                for (int i = 0; i < K; i++) {
                    /* piece i: a, C (pieces) and S_f, D_f (lit), lit at its ends by phi_f and phi_b */
                    const size_t at = 4 * ((size_t)end[i] * (size_t)N + (size_t)end[i + 1]);
                    const double *e = pieces + at, *l = lit + at, t0 = (double)i / K, t1 = (double)(i + 1) / K;
                    const double phi[2][2] = {{fmax(0, 1 - 2 * t0), fmax(0, 1 - 2 * t1)},
                                              {fmax(0, 2 * t0 - 1), fmax(0, 2 * t1 - 1)}};
                    for (int h = 0; h < 2; h++)
                        for (int c = 0; c < 4; c++) /* c 0: S_f with a; 1..3: D_f with C */
                            W[h][c] += T * (phi[h][0] * l[c] + phi[h][1] * (e[c] - l[c]));
                    T *= 1 - e[0];
                }
                double *o = out + 8 * (((size_t)f * (size_t)N2 + (size_t)m) * (size_t)N2 + (size_t)b);
                for (int c = 0; c < 4; c++)
                    o[c] = W[0][c], o[4 + c] = W[1][c];
            }
    free(pieces);
    return 0;
}

/* Section 4b's interpolation position in a table of n entries: x = s (n - 1) / 255, i = min(floor(x), n - 2). */
static int position(double s, int n, double *frac)
{
    double x = s * (n - 1) / 255.0;
    int i = (int)floor(x);
    i = i > n - 2 ? n - 2 : i < 0 ? 0 : i;
    *frac = x - i;
    return i;
}

/* The lookup of `values` values an entry (4 for the table, 8 for its lighting values). */
static void lookup_values(const double *table2, int values, int N2, ref_lookup_t lookup, double sf, double sm,
                          double sb, double *out)
{
    const size_t n = (size_t)N2;
    if (lookup != REF_LOOKUP_TRILINEAR) {
        const double *e = table2 + values * (((size_t)ref_table_index(sf, N2) * n + (size_t)ref_table_index(sm, N2)) *
                                                 n +
                                             (size_t)ref_table_index(sb, N2));
        for (int c = 0; c < values; c++)
            out[c] = e[c];
        return;
    }
    double w[3];
    const size_t i = (size_t)position(sf, N2, &w[0]), j = (size_t)position(sm, N2, &w[1]),
                 k = (size_t)position(sb, N2, &w[2]);
    for (int c = 0; c < values; c++)
        out[c] = 0;
    for (int corner = 0; corner < 8; corner++) {
        const int di = corner & 1, dj = (corner >> 1) & 1, dk = corner >> 2;
        const double weight = (di ? w[0] : 1 - w[0]) * (dj ? w[1] : 1 - w[1]) * (dk ? w[2] : 1 - w[2]);
        const double *e = table2 + values * (((i + (size_t)di) * n + j + (size_t)dj) * n + k + (size_t)dk);
        for (int c = 0; c < values; c++)
            out[c] += weight * e[c];
    }
}

void ref_lookup_order2(const double *table2, int N2, ref_lookup_t lookup_kind, double sf, double sm, double sb,
                       double out[4])
{
    lookup_values(table2, 4, N2, lookup_kind, sf, sm, sb, out);
}

/* Section 8's lit slab: seg = (a, C) and w = (S_f', W_f, S_b', W_b) looked up and corrected alike; C' = L_df W_f +
 * L_dm (C - W_f - W_b) + L_db W_b and the same for the specular with a, clamped to [0, a], then a and C' times
 * (g_f + 2 g_m + g_b) / 4. */
static void light_slab2(double seg[4], const double w[8], ref_shade_t f, ref_shade_t m, ref_shade_t b)
{
    const double a = seg[0], g = (f.g + 2 * m.g + b.g) / 4;
    const double specular = f.s * w[0] + m.s * (a - w[0] - w[4]) + b.s * w[4];
    for (int c = 1; c < 4; c++) {
        const double C = f.d * w[c] + m.d * (seg[c] - w[c] - w[4 + c]) + b.d * w[4 + c] + specular;
        seg[c] = fmin(fmax(C, 0.0), a) * g;
    }
    seg[0] = a * g;
}

static int inside(const ref_factor_t *f, double x, double y)
{
    return x >= 0 && x <= f->ni - 1 && y >= 0 && y <= f->nj - 1;
}

int ref_composite_order2(const ref_volume_t *vol, const ref_factor_t *f, ref_lookup_t lookup, int N,
                         const double *table, int N2, const double *table2, const ref_lut_t *lut, int rays,
                         const ref_lighting_t *lighting, const double *lit, const double *lit2, double *inter)
{
    int W, H;
    if (!vol || !vol->scalars || !f || !table || !table2 || !inter || N < REF_MIN_TABLE || N > REF_MAX_TABLE ||
        N2 < REF_MIN_TABLE2 || N2 > REF_MAX_TABLE2 || (lookup != REF_LOOKUP_NEAREST && lookup != REF_LOOKUP_TRILINEAR) ||
        ref_rays_size(f, rays, &W, &H) || (lighting && (!lit || !lit2)))
        return -1;
    uint8_t *std = ref_standard_slices(vol, f);
    ref_shading_t *sh = lighting ? ref_shading_new(vol, f, lighting) : NULL;
    if (!std || (lighting && !sh)) {
        free(std);
        ref_shading_free(sh);
        return -1;
    }
    const size_t slice_size = (size_t)f->ni * (size_t)f->nj;
    const ref_lookup_t lookup1 = lookup == REF_LOOKUP_TRILINEAR ? REF_LOOKUP_BILINEAR : REF_LOOKUP_NEAREST;
    for (size_t n = 0; n < 4 * (size_t)W * (size_t)H; n++)
        inter[n] = 0;
    /* slabs k, k + 2 (all three samples inside), then the last slab of one slice when n_k - 1 is odd */
    for (int k = 0; k + 1 < f->nk; k += 2) {
        const int order2 = k + 2 <= f->nk - 1, slices = order2 ? 3 : 2;
        double ou[3], ov[3];
        for (int q = 0; q < slices; q++) {
            ref_factor_offset(f, k + q, &ou[q], &ov[q]);
            if (sh)
                ref_shading_slice(sh, vol, f, k + q, q);
        }
        for (int V = 0; V < H; V++)
            for (int U = 0; U < W; U++) {
                double *pix = inter + 4 * ((size_t)V * (size_t)W + (size_t)U), seg[4], s[3], w[8];
                const double u = (double)U / rays, v = (double)V / rays;
                if (pix[3] >= REF_ERT_THRESHOLD)
                    continue; /* early ray termination */
                int in = 1;
                for (int q = 0; q < slices; q++)
                    in = in && inside(f, u - ou[q], v - ov[q]);
                if (!in)
                    continue;
                for (int q = 0; q < slices; q++)
                    s[q] = ref_slice_sample(std + (size_t)(k + q) * slice_size, f->ni, u - ou[q], v - ov[q]);
                if (order2) {
                    ref_lookup_order2(table2, N2, lookup, s[0], s[1], s[2], seg);
                    if (sh)
                        lookup_values(lit2, 8, N2, lookup, s[0], s[1], s[2], w);
                } else {
                    ref_lookup_preint(table, N, lookup1, s[0], s[1], seg);
                    if (sh)
                        ref_lookup_preint(lit, N, lookup1, s[0], s[1], w);
                }
                if (lut && sh) { /* the lighting values scale as the colour does: G(a) of the entry's a */
                    double copy[4] = {seg[0], seg[1], seg[2], seg[3]};
                    ref_lut_correct_lit(lut, seg, w);
                    if (order2)
                        ref_lut_correct_lit(lut, copy, w + 4);
                } else if (lut) {
                    ref_lut_correct(lut, seg);
                }
                if (sh) {
                    ref_shade_t shade[3];
                    for (int q = 0; q < slices; q++)
                        shade[q] = ref_shading_sample(sh, q, f->ni, u - ou[q], v - ov[q]);
                    if (order2)
                        light_slab2(seg, w, shade[0], shade[1], shade[2]);
                    else
                        ref_light_slab(seg, w, shade[0], shade[1]);
                }
                ref_composite_segment(pix, seg);
            }
    }
    free(std);
    ref_shading_free(sh);
    return 0;
}

/* The table bits of section 4b, and the study's lit table bits (ref_lighting_t), on the lighting values. */
static int lit_bits(double *values, size_t count, int table_bits, const ref_lighting_t *lighting)
{
    int rc = ref_table_bits(values, count, table_bits);
    if (rc == 0 && lighting->lit_table_bits) {
        const double levels = ldexp(1.0, lighting->lit_table_bits) - 1;
        for (size_t n = 0; n < count; n++)
            values[n] = floor(levels * values[n] + 0.5) / levels;
    }
    return rc;
}

int ref_render_order2(const ref_volume_t *vol, const ref_tf_point_t *tf, int npoints, const ref_params_t *p,
                      const ref_factor_t *f, double *rgb)
{
    const int rays = p->rays == 0 ? 1 : p->rays, N = p->table_size, N2 = p->table2_size ? p->table2_size : 64;
    const ref_lighting_t *lighting = p->lighting;
    int W, H;
    if (N < REF_MIN_TABLE || N > REF_MAX_TABLE || N2 < REF_MIN_TABLE2 || N2 > REF_MAX_TABLE2 ||
        (p->lookup != REF_LOOKUP_NEAREST && p->lookup != REF_LOOKUP_TRILINEAR) ||
        (p->table_bits != 0 && p->table_bits != 16 && p->table_bits != 8) ||
        (p->correction != REF_CORRECTION_REBUILD && p->correction != REF_CORRECTION_LUT) || p->partial_slabs ||
        ref_rays_size(f, rays, &W, &H))
        return -1;
    const int lut_on = p->correction == REF_CORRECTION_LUT;
    const double d = lut_on ? REF_LUT_D0 : f->slab; /* lut: tables for d0 (the 3D one for 2 d0), corrected for d */
    const size_t entries = (size_t)N * (size_t)N, entries2 = (size_t)N2 * (size_t)N2 * (size_t)N2;
    double *table = malloc(4 * entries * sizeof(double)), *table2 = malloc(4 * entries2 * sizeof(double));
    double *lit = lighting ? malloc(4 * entries * sizeof(double)) : NULL;
    double *lit2 = lighting ? malloc(8 * entries2 * sizeof(double)) : NULL;
    double *inter = malloc(4 * (size_t)W * (size_t)H * sizeof(double));
    ref_lut_t *lut = lut_on ? malloc(sizeof *lut) : NULL;
    int rc = -1;
    if (table && table2 && inter && (lut || !lut_on) && (!lighting || (lit && lit2))) {
        rc = ref_preint_table(tf, npoints, N, d, table);
        if (rc == 0)
            rc = ref_order2_table(tf, npoints, N, N2, d, table2);
        if (rc == 0)
            rc = ref_table_bits(table, 4 * entries, p->table_bits);
        if (rc == 0)
            rc = ref_table_bits(table2, 4 * entries2, p->table_bits);
        if (rc == 0 && lighting)
            rc = ref_lit_table(tf, npoints, N, d, lit);
        if (rc == 0 && lighting)
            rc = ref_order2_lit_table(tf, npoints, N, N2, d, lit2);
        if (rc == 0 && lighting)
            rc = lit_bits(lit, 4 * entries, p->table_bits, lighting);
        if (rc == 0 && lighting)
            rc = lit_bits(lit2, 8 * entries2, p->table_bits, lighting);
        if (rc == 0 && lut)
            rc = ref_lut_init(lut, f->slab / REF_LUT_D0);
        if (rc == 0)
            rc = ref_composite_order2(vol, f, p->lookup, N, table, N2, table2, lut, rays, lighting, lit, lit2, inter);
        if (rc == 0)
            rc = ref_warp_rays(f, rays, inter, p->background, rgb);
    }
    free(table);
    free(table2);
    free(lit);
    free(lit2);
    free(inter);
    free(lut);
    return rc;
}
