/* ref_order2.c: order 2 in double (section 8): the 3D table from the pieces of the 2D table, entry by entry; its
 * lookup; and preint2's frames (slabs of two slices, the last of an odd count of one). */
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

/* Section 4b's interpolation position in a table of n entries: x = s (n - 1) / 255, i = min(floor(x), n - 2). */
static int position(double s, int n, double *frac)
{
    double x = s * (n - 1) / 255.0;
    int i = (int)floor(x);
    i = i > n - 2 ? n - 2 : i < 0 ? 0 : i;
    *frac = x - i;
    return i;
}

void ref_lookup_order2(const double *table2, int N2, ref_lookup_t lookup, double sf, double sm, double sb,
                       double out[4])
{
    const size_t n = (size_t)N2;
    if (lookup != REF_LOOKUP_TRILINEAR) {
        const double *e = table2 + 4 * (((size_t)ref_table_index(sf, N2) * n + (size_t)ref_table_index(sm, N2)) * n +
                                         (size_t)ref_table_index(sb, N2));
        for (int c = 0; c < 4; c++)
            out[c] = e[c];
        return;
    }
    double w[3];
    const size_t i = (size_t)position(sf, N2, &w[0]), j = (size_t)position(sm, N2, &w[1]),
                 k = (size_t)position(sb, N2, &w[2]);
    for (int c = 0; c < 4; c++)
        out[c] = 0;
    for (int corner = 0; corner < 8; corner++) {
        const int di = corner & 1, dj = (corner >> 1) & 1, dk = corner >> 2;
        const double weight = (di ? w[0] : 1 - w[0]) * (dj ? w[1] : 1 - w[1]) * (dk ? w[2] : 1 - w[2]);
        const double *e = table2 + 4 * (((i + (size_t)di) * n + j + (size_t)dj) * n + k + (size_t)dk);
        for (int c = 0; c < 4; c++)
            out[c] += weight * e[c];
    }
}

static int inside(const ref_factor_t *f, double x, double y)
{
    return x >= 0 && x <= f->ni - 1 && y >= 0 && y <= f->nj - 1;
}

int ref_composite_order2(const ref_volume_t *vol, const ref_factor_t *f, ref_lookup_t lookup, int N,
                         const double *table, int N2, const double *table2, const ref_lut_t *lut, int rays,
                         double *inter)
{
    int W, H;
    if (!vol || !vol->scalars || !f || !table || !table2 || !inter || N < REF_MIN_TABLE || N > REF_MAX_TABLE ||
        N2 < REF_MIN_TABLE2 || N2 > REF_MAX_TABLE2 || (lookup != REF_LOOKUP_NEAREST && lookup != REF_LOOKUP_TRILINEAR) ||
        ref_rays_size(f, rays, &W, &H))
        return -1;
    uint8_t *std = ref_standard_slices(vol, f);
    if (!std)
        return -1;
    const size_t slice_size = (size_t)f->ni * (size_t)f->nj;
    for (size_t n = 0; n < 4 * (size_t)W * (size_t)H; n++)
        inter[n] = 0;
    /* slabs k, k + 2 (all three samples inside), then the last slab of one slice when n_k - 1 is odd */
    for (int k = 0; k + 1 < f->nk; k += 2) {
        const int order2 = k + 2 <= f->nk - 1, slices = order2 ? 3 : 2;
        double ou[3], ov[3];
        for (int q = 0; q < slices; q++)
            ref_factor_offset(f, k + q, &ou[q], &ov[q]);
        for (int V = 0; V < H; V++)
            for (int U = 0; U < W; U++) {
                double *pix = inter + 4 * ((size_t)V * (size_t)W + (size_t)U), seg[4], s[3];
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
                if (order2)
                    ref_lookup_order2(table2, N2, lookup, s[0], s[1], s[2], seg);
                else
                    ref_lookup_preint(table, N, lookup == REF_LOOKUP_TRILINEAR ? REF_LOOKUP_BILINEAR
                                                                               : REF_LOOKUP_NEAREST,
                                      s[0], s[1], seg);
                if (lut)
                    ref_lut_correct(lut, seg);
                ref_composite_segment(pix, seg);
            }
    }
    free(std);
    return 0;
}

int ref_render_order2(const ref_volume_t *vol, const ref_tf_point_t *tf, int npoints, const ref_params_t *p,
                      const ref_factor_t *f, double *rgb)
{
    const int rays = p->rays == 0 ? 1 : p->rays, N = p->table_size, N2 = p->table2_size ? p->table2_size : 64;
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
    double *inter = malloc(4 * (size_t)W * (size_t)H * sizeof(double));
    ref_lut_t *lut = lut_on ? malloc(sizeof *lut) : NULL;
    int rc = -1;
    if (table && table2 && inter && (lut || !lut_on)) {
        rc = ref_preint_table(tf, npoints, N, d, table);
        if (rc == 0)
            rc = ref_order2_table(tf, npoints, N, N2, d, table2);
        if (rc == 0)
            rc = ref_table_bits(table, 4 * entries, p->table_bits);
        if (rc == 0)
            rc = ref_table_bits(table2, 4 * entries2, p->table_bits);
        if (rc == 0 && lut)
            rc = ref_lut_init(lut, f->slab / REF_LUT_D0);
        if (rc == 0)
            rc = ref_composite_order2(vol, f, p->lookup, N, table, N2, table2, lut, rays, inter);
        if (rc == 0)
            rc = ref_warp_rays(f, rays, inter, p->background, rgb);
    }
    free(table);
    free(table2);
    free(inter);
    free(lut);
    return rc;
}
