/* SPDX-License-Identifier: MIT */
/* ref_render.c: compositing into the intermediate image, lit or not, the warp, and the whole frame (sections 4, 4b,
 * 4c, 5 and 7). */
#include "ref/ref.h"

#include <math.h>
#include <stdlib.h>

/* The volume's scalars in standard order: std[(k nj + j) ni + i], slice 0 the front one. */
static uint8_t *standard_slices(const ref_volume_t *vol, const ref_factor_t *f)
{
    size_t ni = (size_t)f->ni, nj = (size_t)f->nj, nk = (size_t)f->nk;
    uint8_t *std = malloc(ni * nj * nk);
    if (!std)
        return NULL;
    size_t stride[3] = {1, (size_t)vol->dims[0], (size_t)vol->dims[0] * (size_t)vol->dims[1]};
    for (size_t k = 0; k < nk; k++) {
        size_t kobj = f->k_flip ? nk - 1 - k : k;
        for (size_t j = 0; j < nj; j++)
            for (size_t i = 0; i < ni; i++)
                std[(k * nj + j) * ni + i] =
                    vol->scalars[i * stride[f->i_axis] + j * stride[f->j_axis] + kobj * stride[f->k_axis]];
    }
    return std;
}

/* Bilinear sample of an ni-wide slice at an inside position (x, y); a neighbour beyond the last voxel has weight
 * 0 and is not read. With x, y on the 2^-16 grid every product and sum here is exact in double. */
static double sample(const uint8_t *slice, int ni, double x, double y)
{
    double x0 = floor(x), y0 = floor(y), fx = x - x0, fy = y - y0;
    const uint8_t *p = slice + (size_t)y0 * (size_t)ni + (size_t)x0;
    double row0 = fx > 0 ? (1 - fx) * p[0] + fx * p[1] : p[0];
    if (!(fy > 0))
        return row0;
    p += ni;
    double row1 = fx > 0 ? (1 - fx) * p[0] + fx * p[1] : p[0];
    return (1 - fy) * row0 + fy * row1;
}

/* Preclass: the classified entries (a, C_r, C_g, C_b) of an ni-wide slice, interpolated channel by channel with
 * the bilinear weights of the inside position (x, y) (a neighbour beyond the last voxel has weight 0, not read). */
static void sample_entries(const double *cls, int ni, double x, double y, double out[4])
{
    double x0 = floor(x), y0 = floor(y), fx = x - x0, fy = y - y0;
    const double *p = cls + 4 * ((size_t)y0 * (size_t)ni + (size_t)x0);
    for (int c = 0; c < 4; c++) {
        double row0 = fx > 0 ? (1 - fx) * p[c] + fx * p[4 + c] : p[c];
        if (!(fy > 0)) {
            out[c] = row0;
            continue;
        }
        const double *q = p + 4 * (size_t)ni; /* the next row, only when it has weight */
        double row1 = fx > 0 ? (1 - fx) * q[c] + fx * q[4 + c] : q[c];
        out[c] = (1 - fy) * row0 + fy * row1;
    }
}

/* Preclass: every voxel of a slice to the point-table entry of its own scalar, idx(S). */
static void classify_slice(const uint8_t *slice, size_t count, int N, const double *table, double *cls)
{
    for (size_t n = 0; n < count; n++) {
        const double *e = table + 4 * (size_t)ref_table_index(slice[n], N);
        for (int c = 0; c < 4; c++)
            cls[4 * n + c] = e[c];
    }
}

/* Section 7 for one frame: the lights, every voxel's code (NULL with exact normals) and 8-bit magnitude in
 * object order, the shade of every code, and the shades of the voxels of three slices (the front and back of a
 * slab; order 0 uses the first; order 2's slab, in ref_order2.c, all three). */
typedef struct shading {
    const ref_lighting_t *l;
    ref_lights_t lights;
    int levels;
    int32_t *codes;
    uint8_t *magnitudes;
    double *table;         /* L_d, L_s of each code, L^2 + 1 codes */
    ref_shade_t *slice[3]; /* n_i n_j shades each */
} shading_t;

static void shading_free(shading_t *sh)
{
    free(sh->codes);
    free(sh->magnitudes);
    free(sh->table);
    free(sh->slice[0]);
    free(sh->slice[1]);
    free(sh->slice[2]);
}

static int shading_init(shading_t *sh, const ref_volume_t *vol, const ref_factor_t *f, const ref_lighting_t *l)
{
    *sh = (shading_t){0};
    sh->l = l;
    if (!l->raw || l->normal_bits < 8 || l->normal_bits > 16 || l->normal_bits % 2 ||
        (l->shade_lookup != REF_LOOKUP_NEAREST && l->shade_lookup != REF_LOOKUP_BILINEAR) || l->shade_bits < 0 ||
        l->shade_bits > 30 || (l->lit_table_bits && (l->lit_table_bits < 2 || l->lit_table_bits > 16)) ||
        ref_lights_init(&sh->lights, l, f->R))
        return -1;
    sh->levels = ref_normal_levels(l->normal_bits);
    const size_t voxels = (size_t)vol->dims[0] * (size_t)vol->dims[1] * (size_t)vol->dims[2];
    const size_t codes = (size_t)sh->levels * (size_t)sh->levels + 1, slice = (size_t)f->ni * (size_t)f->nj;
    sh->magnitudes = malloc(voxels);
    sh->codes = l->exact_normals ? NULL : malloc(sizeof(int32_t) * voxels);
    sh->table = l->exact_normals ? NULL : malloc(sizeof(double) * 2 * codes);
    sh->slice[0] = malloc(sizeof(ref_shade_t) * slice);
    sh->slice[1] = malloc(sizeof(ref_shade_t) * slice);
    sh->slice[2] = malloc(sizeof(ref_shade_t) * slice);
    if (!sh->magnitudes || (!l->exact_normals && (!sh->codes || !sh->table)) || !sh->slice[0] || !sh->slice[1] ||
        !sh->slice[2] ||
        ref_normals(vol, l->raw, l->raw_type, l->normal_bits, sh->codes, sh->magnitudes)) {
        shading_free(sh);
        return -1;
    }
    for (size_t c = 0; sh->table && c < codes; c++) {
        double n[3];
        ref_normal_decode((int)c, sh->levels, n);
        ref_shade_normal(&sh->lights, n, &sh->table[2 * c], &sh->table[2 * c + 1]);
    }
    return 0;
}

/* The shades of standard slice k's voxels into sh->slice[which], (j, i) order as standard_slices. */
static void shade_slice(shading_t *sh, const ref_volume_t *vol, const ref_factor_t *f, int k, int which)
{
    const size_t stride[3] = {1, (size_t)vol->dims[0], (size_t)vol->dims[0] * (size_t)vol->dims[1]};
    const int kobj = f->k_flip ? f->nk - 1 - k : k;
    ref_shade_t *out = sh->slice[which];
    for (int j = 0; j < f->nj; j++)
        for (int i = 0; i < f->ni; i++) {
            int p[3];
            p[f->i_axis] = i, p[f->j_axis] = j, p[f->k_axis] = kobj;
            const size_t at = (size_t)p[0] * stride[0] + (size_t)p[1] * stride[1] + (size_t)p[2] * stride[2];
            ref_shade_t *o = &out[(size_t)j * (size_t)f->ni + (size_t)i];
            if (sh->codes) {
                o->d = sh->table[2 * (size_t)sh->codes[at]];
                o->s = sh->table[2 * (size_t)sh->codes[at] + 1];
            } else { /* the study's unquantised normals */
                int64_t G[3];
                double g[3], n[3] = {0, 0, 0};
                ref_gradient(vol, sh->l->raw, sh->l->raw_type, p[0], p[1], p[2], G, g);
                const double len = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
                for (int a = 0; len > 0 && a < 3; a++)
                    n[a] = g[a] / len;
                ref_shade_normal(&sh->lights, n, &o->d, &o->s);
            }
            o->g = ref_gradient_factor(sh->l, sh->magnitudes[at]);
        }
}

/* The shade of a slice sample at the inside position (x, y): its nearest voxel's (floor(x + 1/2), floor(y + 1/2)),
 * or the four voxels' interpolated with the sample's bilinear weights (a neighbour of weight 0 is not read). */
static ref_shade_t sample_shade(const shading_t *sh, int which, int ni, double x, double y)
{
    const ref_shade_t *s = sh->slice[which];
    if (sh->l->shade_lookup == REF_LOOKUP_NEAREST)
        return s[(size_t)floor(y + 0.5) * (size_t)ni + (size_t)floor(x + 0.5)];
    const double x0 = floor(x), y0 = floor(y), fx = x - x0, fy = y - y0;
    const ref_shade_t *p = s + (size_t)y0 * (size_t)ni + (size_t)x0;
    ref_shade_t out = {0, 0, 0};
    for (int n = 0; n < 4; n++) {
        const double w = ((n & 1) ? fx : 1 - fx) * ((n >> 1) ? fy : 1 - fy);
        if (w == 0)
            continue;
        const ref_shade_t *v = p + (n & 1) + ((n >> 1) ? (size_t)ni : 0);
        out.d += w * v->d, out.s += w * v->s, out.g += w * v->g;
    }
    return out;
}

/* Preclass, lit: each of the four voxels' classified entries lit with its own shade, then interpolated as
 * sample_entries does. */
static void sample_entries_lit(const double *cls, const shading_t *sh, int ni, double x, double y, double out[4])
{
    const double x0 = floor(x), y0 = floor(y), fx = x - x0, fy = y - y0;
    const size_t at = (size_t)y0 * (size_t)ni + (size_t)x0;
    for (int c = 0; c < 4; c++)
        out[c] = 0;
    for (int n = 0; n < 4; n++) {
        const double w = ((n & 1) ? fx : 1 - fx) * ((n >> 1) ? fy : 1 - fy);
        if (w == 0)
            continue;
        const size_t v = at + (n & 1) + ((n >> 1) ? (size_t)ni : 0);
        double e[4] = {cls[4 * v], cls[4 * v + 1], cls[4 * v + 2], cls[4 * v + 3]};
        ref_light_point(e, sh->slice[0][v]);
        for (int c = 0; c < 4; c++)
            out[c] += w * e[c];
    }
}

/* Front to back: C += (1 - A) C_seg, A += (1 - A) a_seg. pix: R, G, B, A; seg: a, r, g, b. */
static void composite(double *pix, const double *seg)
{
    double t = 1 - pix[3];
    pix[0] += t * seg[1];
    pix[1] += t * seg[2];
    pix[2] += t * seg[3];
    pix[3] += t * seg[0];
}

/* Integer pixels U with 0 <= U / R - ou <= n - 1, clipped to the image (for R = 1 a no-op by construction of
 * int_w/int_h; for R > 1 the image ends at u = int_w - 1, section 3). R ou is exact: R divides 2^16. */
static void covered(double ou, int n, int rays, int size, int *lo, int *hi)
{
    double a = ceil(rays * ou), b = floor(rays * (ou + (n - 1)));
    *lo = a < 0 ? 0 : (int)a;
    *hi = b > size - 1 ? size - 1 : (int)b;
}

static int rays_valid(int rays)
{
    return rays == 1 || rays == 2 || rays == 4 || rays == 8 || rays == 16;
}

int ref_rays_size(const ref_factor_t *f, int rays, int *w, int *h)
{
    if (!f || !rays_valid(rays))
        return -1;
    *w = rays * (f->int_w - 1) + 1;
    *h = rays * (f->int_h - 1) + 1;
    return 0;
}

static int mode_valid(ref_mode_t mode)
{
    return mode == REF_MODE_POINT || mode == REF_MODE_PREINT1 || mode == REF_MODE_PRECLASS;
}

static int lookup_valid(ref_lookup_t lookup)
{
    return lookup == REF_LOOKUP_NEAREST || lookup == REF_LOOKUP_BILINEAR;
}

int ref_composite(const ref_volume_t *vol, const ref_factor_t *f, ref_mode_t mode, int N, const double *table,
                  double *inter)
{
    return ref_composite_ex(vol, f, mode, REF_LOOKUP_NEAREST, N, table, NULL, inter);
}

/* The part of slab k (between slices k and k + 1) that the ray through intermediate point (u, v) (u = U / R) spends
 * inside the box, as fractions phi of the slab: [*lo, *hi], empty when *lo > *hi. Along the slab the ray's slice
 * position is (x0 + phi dx, y0 + phi dy). Each bound is rounded to the 2^-16 grid (half up), which integer code
 * can repeat exactly (the ratio of two Q16.16 values); a sample that is inside gives its end of the slab exactly.
 * In double the quotient is exact enough: its numerator and denominator are below 2^30 in units of 2^-16, so its
 * error is far below the 1 / (2 |dx| 2^16) that separates a non-tie from the nearest half-step, and a tie is
 * representable. */
static void slab_inside(const ref_factor_t *f, const double ou[2], const double ov[2], double u, double v,
                        double *lo, double *hi)
{
    double a = 0, b = 1;
    const double p0[2] = {u - ou[0], v - ov[0]}, dp[2] = {ou[0] - ou[1], ov[0] - ov[1]};
    const int n[2] = {f->ni, f->nj};
    for (int c = 0; c < 2; c++) {
        if (dp[c] == 0) {
            if (p0[c] < 0 || p0[c] > n[c] - 1)
                a = 1, b = 0;
            continue;
        }
        double t0 = floor(-p0[c] / dp[c] * 65536 + 0.5) / 65536;
        double t1 = floor((n[c] - 1 - p0[c]) / dp[c] * 65536 + 0.5) / 65536;
        a = fmax(a, fmin(t0, t1));
        b = fmin(b, fmax(t0, t1));
    }
    *lo = a;
    *hi = b;
}

/* (1 - phi) a + phi b rounded half up to the 2^-32 grid, exactly, for a and b on the 2^-32 grid in [0, 255] and
 * phi on the 2^-16 grid in [0, 1]. The exact value lies on the 2^-48 grid and needs up to 56 bits, more than a
 * double holds (computed directly, about 4 in 10^5 random cases round the other way than integer code does,
 * most of them ties). So a and b are split at the 2^-16 grid: the high parts' sum lies on the 2^-32 grid (at most
 * 41 bits a product), the low parts' sum on the 2^-48 grid below 2^-15 (33 bits), both exact, and only the low
 * sum is rounded. */
static double lerp_q32(double a, double b, double phi)
{
    double a_hi = floor(a * 65536) / 65536, b_hi = floor(b * 65536) / 65536;
    double hi = (1 - phi) * a_hi + phi * b_hi, lo = (1 - phi) * (a - a_hi) + phi * (b - b_hi);
    return hi + floor(lo * 4294967296.0 + 0.5) / 4294967296.0;
}

/* The scalar where the ray through (u, v) crosses the box's side at fraction phi of slab k: the trilinear value
 * at slice position (X, Y) = (x0 + phi dx, y0 + phi dy), each rounded to the 2^-16 grid and clamped to the
 * slice, between the two slices: (1 - phi) S_k(X, Y) + phi S_k+1(X, Y), rounded to the 2^-32 grid. x0 + phi dx
 * lies on the 2^-32 grid below 2^14: exact. */
static double face_scalar(const ref_factor_t *f, const uint8_t *front, const uint8_t *back, const double ou[2],
                          const double ov[2], double u, double v, double phi)
{
    double x = (u - ou[0]) + phi * (ou[0] - ou[1]), y = (v - ov[0]) + phi * (ov[0] - ov[1]);
    x = fmin(fmax(floor(x * 65536 + 0.5) / 65536, 0), f->ni - 1);
    y = fmin(fmax(floor(y * 65536 + 0.5) / 65536, 0), f->nj - 1);
    return lerp_q32(sample(front, f->ni, x, y), sample(back, f->ni, x, y), phi);
}

/* A segment of rho slabs' length from an entry made for one slab: a' = 1 - (1 - a)^rho (exact: the optical depth
 * scales with length), C' = C a' / a (exact where extinction and colour are constant), C' = C rho for a = 0. */
static void shorten(double seg[4], double rho)
{
    if (rho == 1)
        return;
    double a = fmin(seg[0], 1.0), a2 = 1 - pow(1 - a, rho), g = a > 0 ? a2 / a : rho;
    seg[0] = a2;
    for (int c = 1; c < 4; c++)
        seg[c] *= g;
}

static int inside(const ref_factor_t *f, double x, double y)
{
    return x >= 0 && x <= f->ni - 1 && y >= 0 && y <= f->nj - 1;
}

/* Order 0 (point, preclass): slice k's sample at (u, v), inside, stands for the part of the ray from halfway to
 * the slice before to halfway to the slice after that lies in the box, plus the rest of a neighbouring slab whose
 * other sample is outside (a ray that enters or leaves through a side face); the front and back slices have no
 * slab beyond them. In slabs: rho = (slab k - 1: 1/2 if slice k - 1's sample is inside, else the part of that
 * slab inside the box) + (slab k: likewise with slice k + 1). */
static double order0_length(const ref_factor_t *f, int k, double u, double v, const double ou3[3],
                            const double ov3[3])
{
    double rho = 0, lo, hi;
    if (k > 0) {
        slab_inside(f, ou3, ov3, u, v, &lo, &hi);
        rho += inside(f, u - ou3[0], v - ov3[0]) ? 0.5 : hi >= lo ? hi - lo : 0;
    }
    if (k < f->nk - 1) {
        slab_inside(f, ou3 + 1, ov3 + 1, u, v, &lo, &hi);
        rho += inside(f, u - ou3[2], v - ov3[2]) ? 0.5 : hi >= lo ? hi - lo : 0;
    }
    return rho;
}

static void union_range(double ou0, double ou1, int n, int rays, int size, int *lo, int *hi)
{
    int a0, b0, a1, b1;
    covered(ou0, n, rays, size, &a0, &b0);
    covered(ou1, n, rays, size, &a1, &b1);
    *lo = a0 < a1 ? a0 : a1;
    *hi = b0 > b1 ? b0 : b1;
}

int ref_composite_ex(const ref_volume_t *vol, const ref_factor_t *f, ref_mode_t mode, ref_lookup_t lookup, int N,
                     const double *table, const ref_lut_t *lut, double *inter)
{
    return ref_composite_sides(vol, f, mode, lookup, N, table, lut, 0, inter);
}

int ref_composite_sides(const ref_volume_t *vol, const ref_factor_t *f, ref_mode_t mode, ref_lookup_t lookup, int N,
                        const double *table, const ref_lut_t *lut, int partial_slabs, double *inter)
{
    return ref_composite_rays(vol, f, mode, lookup, N, table, lut, partial_slabs, 1, inter);
}

static int composite_all(const ref_volume_t *vol, const ref_factor_t *f, ref_mode_t mode, ref_lookup_t lookup,
                         int N, const double *table, const double *lit_table, const ref_lut_t *lut, int partial_slabs,
                         int rays, const ref_lighting_t *lighting, double *inter);

int ref_composite_rays(const ref_volume_t *vol, const ref_factor_t *f, ref_mode_t mode, ref_lookup_t lookup, int N,
                       const double *table, const ref_lut_t *lut, int partial_slabs, int rays, double *inter)
{
    return composite_all(vol, f, mode, lookup, N, table, NULL, lut, partial_slabs, rays, NULL, inter);
}

int ref_composite_lit(const ref_volume_t *vol, const ref_factor_t *f, ref_mode_t mode, ref_lookup_t lookup, int N,
                      const double *table, const double *lit_table, const ref_lut_t *lut, int rays,
                      const ref_lighting_t *lighting, double *inter)
{
    if (!lighting || (mode == REF_MODE_PREINT1 && !lit_table))
        return -1;
    return composite_all(vol, f, mode, lookup, N, table, lit_table, lut, 0, rays, lighting, inter);
}

/* Pixel (U, V) is the ray through intermediate point (u, v) = (U / R, V / R), exact in double (R divides 2^16, so
 * u - ou_k stays on the 2^-16 grid and every sample stays exact). Lit when lighting is not NULL (then without
 * partial slabs). */
static int composite_all(const ref_volume_t *vol, const ref_factor_t *f, ref_mode_t mode, ref_lookup_t lookup,
                         int N, const double *table, const double *lit_table, const ref_lut_t *lut, int partial_slabs,
                         int rays, const ref_lighting_t *lighting, double *inter)
{
    int W, H;
    if (!vol || !vol->scalars || !f || !table || !inter || N < REF_MIN_TABLE || N > REF_MAX_TABLE ||
        !mode_valid(mode) || !lookup_valid(lookup) || ref_rays_size(f, rays, &W, &H) || (lighting && partial_slabs))
        return -1;
    shading_t sh = {0};
    if (lighting && shading_init(&sh, vol, f, lighting))
        return -1;
    uint8_t *std = standard_slices(vol, f);
    size_t slice_size = (size_t)f->ni * (size_t)f->nj;
    double *cls = mode == REF_MODE_PRECLASS ? malloc(4 * slice_size * sizeof(double)) : NULL;
    if (!std || (mode == REF_MODE_PRECLASS && !cls)) {
        free(std);
        free(cls);
        shading_free(&sh);
        return -1;
    }
    for (size_t n = 0; n < 4 * (size_t)W * (size_t)H; n++)
        inter[n] = 0;

    if (mode != REF_MODE_PREINT1) {
        /* point, preclass: segment k is slice k, for the pixels whose sample is inside (with partial slabs, for the
         * length order0_length; else for one slab) */
        for (int k = 0; k < f->nk; k++) {
            double ou3[3] = {0, 0, 0}, ov3[3] = {0, 0, 0}; /* slices k - 1, k, k + 1 where they exist */
            for (int q = -1; q <= 1; q++)
                if (k + q >= 0 && k + q < f->nk)
                    ref_factor_offset(f, k + q, &ou3[q + 1], &ov3[q + 1]);
            int u_lo, u_hi, v_lo, v_hi;
            covered(ou3[1], f->ni, rays, W, &u_lo, &u_hi);
            covered(ov3[1], f->nj, rays, H, &v_lo, &v_hi);
            const uint8_t *slice = std + (size_t)k * slice_size;
            if (cls)
                classify_slice(slice, slice_size, N, table, cls);
            if (lighting)
                shade_slice(&sh, vol, f, k, 0);
            for (int V = v_lo; V <= v_hi; V++) {
                for (int U = u_lo; U <= u_hi; U++) {
                    double *pix = inter + 4 * ((size_t)V * (size_t)W + (size_t)U), seg[4];
                    const double u = (double)U / rays, v = (double)V / rays;
                    if (pix[3] >= REF_ERT_THRESHOLD)
                        continue; /* early ray termination: no further segments */
                    double rho = partial_slabs ? order0_length(f, k, u, v, ou3, ov3) : 1;
                    if (!(rho > 0))
                        continue;
                    const double x = u - ou3[1], y = v - ov3[1];
                    if (cls && lighting)
                        sample_entries_lit(cls, &sh, f->ni, x, y, seg); /* each voxel lit, then interpolated */
                    else if (cls)
                        sample_entries(cls, f->ni, x, y, seg);
                    else
                        ref_lookup_point(table, N, lookup, sample(slice, f->ni, x, y), seg);
                    if (lut)
                        ref_lut_correct(lut, seg); /* after the lookup (and the table bits, applied to the table) */
                    if (lighting && !cls)
                        ref_light_point(seg, sample_shade(&sh, 0, f->ni, x, y));
                    shorten(seg, rho);
                    composite(pix, seg);
                }
            }
        }
    } else {
        /* preint1: segment k is the slab between slices k and k + 1 when both samples are inside; with partial
         * slabs also the part of it inside the box when one or neither is, from or to the side-face crossing */
        for (int k = 0; k + 1 < f->nk; k++) {
            double ou[2], ov[2];
            ref_factor_offset(f, k, &ou[0], &ov[0]);
            ref_factor_offset(f, k + 1, &ou[1], &ov[1]);
            int u_lo, u_hi, v_lo, v_hi;
            union_range(ou[0], ou[1], f->ni, rays, W, &u_lo, &u_hi);
            union_range(ov[0], ov[1], f->nj, rays, H, &v_lo, &v_hi);
            const uint8_t *front = std + (size_t)k * slice_size, *back = front + slice_size;
            if (lighting) { /* the front's shades are the last slab's back's */
                if (k == 0)
                    shade_slice(&sh, vol, f, 0, 0);
                else {
                    ref_shade_t *t = sh.slice[0];
                    sh.slice[0] = sh.slice[1], sh.slice[1] = t;
                }
                shade_slice(&sh, vol, f, k + 1, 1);
            }
            for (int V = v_lo; V <= v_hi; V++) {
                for (int U = u_lo; U <= u_hi; U++) {
                    double *pix = inter + 4 * ((size_t)V * (size_t)W + (size_t)U), seg[4], lo = 0, hi = 1;
                    const double u = (double)U / rays, v = (double)V / rays;
                    if (pix[3] >= REF_ERT_THRESHOLD)
                        continue; /* early ray termination: no further segments */
                    int in_f = inside(f, u - ou[0], v - ov[0]), in_b = inside(f, u - ou[1], v - ov[1]);
                    double rho = 1;
                    if (!in_f || !in_b) {
                        if (!partial_slabs)
                            continue; /* section 4: both samples inside, or nothing */
                        slab_inside(f, ou, ov, u, v, &lo, &hi);
                        if (!(hi > lo))
                            continue;
                        rho = hi - lo;
                    }
                    double sf = in_f ? sample(front, f->ni, u - ou[0], v - ov[0])
                                     : face_scalar(f, front, back, ou, ov, u, v, lo);
                    double sb = in_b ? sample(back, f->ni, u - ou[1], v - ov[1])
                                     : face_scalar(f, front, back, ou, ov, u, v, hi);
                    ref_lookup_preint(table, N, lookup, sf, sb, seg);
                    if (lighting) {
                        double lit[4];
                        ref_lookup_preint(lit_table, N, lookup, sf, sb, lit);
                        if (lut)
                            ref_lut_correct_lit(lut, seg, lit);
                        ref_light_slab(seg, lit, sample_shade(&sh, 0, f->ni, u - ou[0], v - ov[0]),
                                       sample_shade(&sh, 1, f->ni, u - ou[1], v - ov[1]));
                    } else if (lut) {
                        ref_lut_correct(lut, seg);
                    }
                    shorten(seg, rho);
                    composite(pix, seg);
                }
            }
        }
    }
    free(std);
    free(cls);
    shading_free(&sh);
    return 0;
}

void ref_warp(const ref_factor_t *f, const double *inter, const double background[3], double *rgb)
{
    ref_warp_rays(f, 1, inter, background, rgb);
}

int ref_warp_rays(const ref_factor_t *f, int rays, const double *inter, const double background[3], double *rgb)
{
    int W, H;
    if (ref_rays_size(f, rays, &W, &H))
        return -1;
    for (int py = 0; py < f->out_h; py++) {
        for (int px = 0; px < f->out_w; px++) {
            double u, v, acc[4] = {0, 0, 0, 0};
            ref_factor_warp(f, px, py, &u, &v);
            u *= rays; /* the R-scaled image's pixel coordinates: exact */
            v *= rays;
            if (u > -1 && v > -1 && u < W && v < H) {
                double u0 = floor(u), v0 = floor(v), fu = u - u0, fv = v - v0;
                for (int n = 0; n < 4; n++) {
                    int x = (int)u0 + (n & 1), y = (int)v0 + (n >> 1);
                    double w = ((n & 1) ? fu : 1 - fu) * ((n >> 1) ? fv : 1 - fv);
                    if (x < 0 || y < 0 || x >= W || y >= H || w == 0)
                        continue; /* outside the intermediate image: transparent black */
                    const double *pix = inter + 4 * ((size_t)y * (size_t)W + (size_t)x);
                    for (int c = 0; c < 4; c++)
                        acc[c] += w * pix[c];
                }
            }
            double *out = rgb + 3 * ((size_t)py * (size_t)f->out_w + (size_t)px);
            for (int c = 0; c < 3; c++)
                out[c] = acc[c] + (1 - acc[3]) * background[c];
        }
    }
    return 0;
}

int ref_render(const ref_volume_t *vol, const ref_tf_point_t *tf, int npoints, const ref_params_t *p,
               const ref_view_t *view, int out_w, int out_h, double *rgb, ref_factor_t *factor_out)
{
    ref_factor_t f;
    if (p && p->mode == REF_MODE_PREINT2) { /* section 8: ref_order2.c */
        if (!vol || !vol->scalars || !rgb || ref_factor(vol, view, out_w, out_h, &f))
            return -1;
        if (p->slice_offsets_q16 && ref_factor_adopt_offsets(&f, p->slice_offsets_q16, p->slice_k_axis,
                                                             p->slice_k_flip))
            return -2;
        int rc = ref_render_order2(vol, tf, npoints, p, &f, rgb);
        if (rc == 0 && factor_out)
            *factor_out = f;
        return rc;
    }
    int rays = p && p->rays == 0 ? 1 : p ? p->rays : 0, W, H;
    if (!vol || !vol->scalars || !p || !rgb || p->table_size < REF_MIN_TABLE || p->table_size > REF_MAX_TABLE ||
        !mode_valid(p->mode) || !lookup_valid(p->lookup) ||
        (p->table_bits != 0 && p->table_bits != 16 && p->table_bits != 8) ||
        (p->correction != REF_CORRECTION_REBUILD && p->correction != REF_CORRECTION_LUT) || !rays_valid(rays) ||
        ref_factor(vol, view, out_w, out_h, &f))
        return -1;
    if (p->slice_offsets_q16 && ref_factor_adopt_offsets(&f, p->slice_offsets_q16, p->slice_k_axis, p->slice_k_flip))
        return -2;
    size_t N = (size_t)p->table_size;
    size_t entries = p->mode == REF_MODE_PREINT1 ? N * N : N; /* preclass classifies with the point table */
    int lut_on = p->correction == REF_CORRECTION_LUT;
    const ref_lighting_t *lighting = p->lighting;
    if (lighting && p->partial_slabs)
        return -1; /* section 7: lighting with partial slabs is not supported */
    int lit_on = lighting && p->mode == REF_MODE_PREINT1; /* the front-weighted table */
    double d = lut_on ? REF_LUT_D0 : f.slab; /* lut: tables for d0, every segment corrected for rho = d / d0 */
    double *table = malloc(4 * entries * sizeof(double));
    double *lit_table = lit_on ? malloc(4 * entries * sizeof(double)) : NULL;
    ref_rays_size(&f, rays, &W, &H);
    double *inter = malloc(4 * (size_t)W * (size_t)H * sizeof(double));
    ref_lut_t *lut = lut_on ? malloc(sizeof *lut) : NULL;
    int rc = -1;
    if (table && inter && (lut || !lut_on) && (lit_table || !lit_on)) {
        rc = p->mode == REF_MODE_PREINT1 ? ref_preint_table(tf, npoints, p->table_size, d, table)
                                         : ref_point_table(tf, npoints, p->table_size, d, table);
        if (rc == 0)
            rc = ref_table_bits(table, 4 * entries, p->table_bits);
        if (rc == 0 && lit_on)
            rc = ref_lit_table(tf, npoints, p->table_size, d, lit_table);
        if (rc == 0 && lit_on) /* in the plain table's format (section 7), and for the study maybe fewer bits */
            rc = ref_table_bits(lit_table, 4 * entries, p->table_bits);
        if (rc == 0 && lit_on && lighting->lit_table_bits) {
            const double levels = ldexp(1.0, lighting->lit_table_bits) - 1;
            for (size_t n = 0; n < 4 * entries; n++)
                lit_table[n] = floor(levels * lit_table[n] + 0.5) / levels;
        }
        if (rc == 0 && lut)
            rc = ref_lut_init(lut, f.slab / REF_LUT_D0);
        if (rc == 0)
            rc = lighting ? ref_composite_lit(vol, &f, p->mode, p->lookup, p->table_size, table, lit_table, lut, rays,
                                              lighting, inter)
                          : ref_composite_rays(vol, &f, p->mode, p->lookup, p->table_size, table, lut,
                                               p->partial_slabs, rays, inter);
        if (rc == 0)
            rc = ref_warp_rays(&f, rays, inter, p->background, rgb);
    }
    free(lit_table);
    free(table);
    free(inter);
    free(lut);
    if (rc == 0 && factor_out)
        *factor_out = f;
    return rc;
}

/* ---- For ref_order2.c (ref.h): the helpers above by name. ---- */

uint8_t *ref_standard_slices(const ref_volume_t *vol, const ref_factor_t *f)
{
    return standard_slices(vol, f);
}

double ref_slice_sample(const uint8_t *slice, int ni, double x, double y)
{
    return sample(slice, ni, x, y);
}

void ref_composite_segment(double *pix, const double *seg)
{
    composite(pix, seg);
}

/* ---- For ref_order2.c (ref.h): a frame's shading, as the lit modes above have it. ---- */

struct ref_shading {
    shading_t sh;
};

ref_shading_t *ref_shading_new(const ref_volume_t *vol, const ref_factor_t *f, const ref_lighting_t *lighting)
{
    ref_shading_t *s = malloc(sizeof *s);
    if (s && shading_init(&s->sh, vol, f, lighting)) {
        free(s);
        s = NULL;
    }
    return s;
}

void ref_shading_free(ref_shading_t *s)
{
    if (s)
        shading_free(&s->sh);
    free(s);
}

void ref_shading_slice(ref_shading_t *s, const ref_volume_t *vol, const ref_factor_t *f, int k, int which)
{
    shade_slice(&s->sh, vol, f, k, which);
}

ref_shade_t ref_shading_sample(const ref_shading_t *s, int which, int ni, double x, double y)
{
    return sample_shade(&s->sh, which, ni, x, y);
}
