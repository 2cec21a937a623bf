/* SPDX-License-Identifier: MIT */
/*
 * ref.h: the double-precision reference renderer, docs/algorithm.md implemented literally.
 *
 * It shares no code and no arithmetic with the core (it does not include volfix.h): the difference between its
 * image and the core's is the core's fixed-point error alone. It skips nothing (no run-length encoding, no skip
 * links), builds the pre-integrated table by brute force, and keeps every intermediate value in double. The
 * only quantisations are the ones the spec imposes on both implementations: the 8-bit window, the table's
 * nearest-entry lookup, the 2^-16 grid of the slice offsets and, when asked for, 8-bit tables (section 4b),
 * partial slabs' side-face crossings and face scalars (section 4c) and lighting's normal codes and 8-bit gradient
 * magnitudes (section 7, computed here from its integer definition).
 * Callers hand the reference the quantised inputs the core sees (spacing q / 65536, zoom q / 65536, TF scalar
 * q / 256, colours q / 65535).
 *
 * One file per stage (VolPack's shape):
 *   ref_window.c   section 1: raw voxels to the 8-bit scalar domain
 *   ref_tables.c   section 2: transfer function, classification, point table, pre-integrated table
 *   ref_factor.c   section 3: rotation, principal axis, shears, slice offsets, slab length, warp map
 *   ref_options.c  section 4b: bilinear table lookup, 8-bit tables, the lut slab-length correction
 *   ref_render.c   sections 4, 4b, 4c and 5: compositing into the intermediate image, the warp, the whole frame
 *   ref_normals.c  section 7: gradients, normal codes and 8-bit magnitudes of the voxels as stored
 *   ref_shade.c    section 7: lights, the shade table, a voxel's shade, lit segments
 *   ref_order2.c   section 8: order 2 (preint2), its table and its frames
 * Every function that returns int (but ref_table_index) returns 0, or -1 on an argument outside the spec's ranges
 * or when out of memory.
 */
#ifndef REF_H
#define REF_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

/* A windowed 8-bit scalar volume S[x][y][z], x fastest in memory. spacing: the quantised spacing the core uses
 * (q / 65536); only ratios matter. Each dimension 2..REF_MAX_DIM, largest spacing <= 64 x smallest. */
typedef struct ref_volume {
    int dims[3];
    double spacing[3];
    const uint8_t *scalars;
} ref_volume_t;

/* Transfer-function control point: s in 0..255, r g b and a (opacity per unit length d_ref) in [0, 1]. */
typedef struct ref_tf_point {
    double s, r, g, b, a;
} ref_tf_point_t;

/* point and preint1: section 4; preclass (voxels classified first, their entries interpolated): section 4b. */
typedef enum ref_mode { REF_MODE_POINT, REF_MODE_PREINT1, REF_MODE_PRECLASS, REF_MODE_PREINT2 } ref_mode_t;

/* Section 4b. Lookup of a sample in a table: the nearest entry (section 2) or bilinear between entries. */
typedef enum ref_lookup { REF_LOOKUP_NEAREST = 0, REF_LOOKUP_BILINEAR, REF_LOOKUP_TRILINEAR } ref_lookup_t;

/* Section 4b. Slab length: tables built for the view's d, or built for d0 = 1 and every segment corrected. */
typedef enum ref_correction { REF_CORRECTION_REBUILD = 0, REF_CORRECTION_LUT } ref_correction_t;

typedef struct ref_lighting ref_lighting_t; /* section 7, below */

typedef struct ref_params {
    ref_mode_t mode;
    int table_size;       /* N, REF_MIN_TABLE..REF_MAX_TABLE */
    double background[3]; /* RGB in [0, 1] behind the volume */
    /* Optional: the core's snapped slice offsets, (ou_k, ov_k) in Q16.16 for every standard slice k, with the
     * principal axis and flip they belong to. Two renderers whose shears differ by 1e-9 (the core's integer
     * sine) put about one slice a frame on neighbouring grid points, and a narrow transfer-function peak then
     * flips there. Given the core's offsets, the reference first checks each against its own (same axis and
     * flip, within one grid step, else ref_render returns -2) and then samples where the core does. NULL: the
     * reference's own offsets. */
    const int32_t *slice_offsets_q16;
    int slice_k_axis, slice_k_flip;
    /* Section 4b. Zero is each one's default, so initialisers that stop before these keep the section 4 image. */
    ref_lookup_t lookup;         /* nearest (default) or bilinear; ignored by preclass (voxels' nearest entries) */
    int table_bits;              /* 16 (default; 0 means 16) or 8: every table value rounded to a multiple of 1/255 */
    ref_correction_t correction; /* rebuild (default) or lut */
    /* Section 4c. 0, section 4 as written (a slab whose front or back sample is outside the box's side faces is
     * left out; every slice of order 0 stands for one slab); 1, partial slabs: a ray's part of a slab inside the
     * box is composited from the side-face crossing on, with the entry corrected for its length, and order 0's
     * slices stand for the ray's part in the box from halfway to the slice before to halfway to the slice after. */
    int partial_slabs;
    /* Section 4b. Rays R per voxel column along each intermediate axis, 1, 2, 4, 8 or 16 (0 means 1): the
     * intermediate image has R x R pixels per voxel and the warp reads it at (R u, R v). */
    int rays;
    /* Section 7. NULL: unlit (sections 1 to 6). Else every segment is lit as section 7 says; with partial slabs
     * ref_render refuses it (-1), as the core does. */
    const ref_lighting_t *lighting;
    /* Section 8. preint2's 3D table, N2 entries a side (REF_MIN_TABLE2..REF_MAX_TABLE2; 0 means 64); the lookup is
     * nearest or trilinear (the last slab of an odd count then bilinear); partial slabs are not part of preint2. */
    int table2_size;
} ref_params_t;

typedef struct ref_view {
    int32_t azimuth, elevation, roll; /* binary angle units, 65536 per turn */
    double zoom;                      /* > 0; 1 fits the bounding sphere in the smaller image side */
} ref_view_t;

/* The factorisation of a view (section 3). Axes are object axes: 0 x, 1 y, 2 z. */
typedef struct ref_factor {
    int k_axis, i_axis, j_axis; /* principal (slice) axis and the two others in cyclic order */
    int k_flip;                 /* 1: standard slice k is object slice n_k - 1 - k (the view looks along -k) */
    int ni, nj, nk;             /* dimensions along i, j, k */
    double si, sj;              /* shear: intermediate pixels per slice */
    double ti, tj;              /* translation of slice 0 (before snapping) */
    double slab;                /* distance between consecutive slices along a ray, units of d_ref */
    int int_w, int_h;           /* intermediate image for one ray per voxel column (R = 1): covers every pixel
                                 * some slice covers; ref_rays_size gives it for R rays */
    int out_w, out_h;           /* final image */
    double R[3][3];             /* rotation world -> eye, R = Rz(roll) Rx(elevation) Ry(azimuth) */
    double Sr[3];               /* relative spacing sp / min(sp) */
    double dir[3];              /* viewing direction in object space, d_a = R[2][a] / Sr_a */
    double scale;               /* final pixels per world unit: zoom * min(W, H) / D */
    /* Warp map, final pixel (px, py) -> intermediate point: u = u0 + du_dx px + du_dy py, v likewise. For
     * information; ref_warp evaluates the spec's formula per pixel. */
    double u0, v0, du_dx, dv_dx, du_dy, dv_dy;
    const int32_t *given_offsets_q16; /* NULL, or offsets adopted by ref_factor_adopt_offsets */
} ref_factor_t;

#define REF_MAX_DIM 4096
#define REF_MIN_TABLE 2
#define REF_MAX_TABLE 1024
#define REF_MAX_TF_POINTS 1024
#define REF_MAX_ANISOTROPY 64.0
#define REF_ERT_THRESHOLD (1.0 - 1.0 / 1024.0) /* early ray termination: A >= 1 - 2^-10 */
#define REF_LUT_KNOTS 1024                       /* lut correction: knots a_k = k / 1024, k = 0..1024 */
#define REF_LUT_D0 1.0                           /* lut correction: the slab length the tables are built for */
#define REF_MAX_RAYS 16                          /* rays per voxel column: 1, 2, 4, 8 or 16 */
#define REF_MIN_TABLE2 16                        /* order 2: entries a side of the 3D table */
#define REF_MAX_TABLE2 128
#define REF_ORDER2_PIECES 16                     /* order 2: pieces K of a slab's curve */

/* ---- ref_window.c -------------------------------------------------------------------------------------- */

enum { REF_VOXEL_U8, REF_VOXEL_I8, REF_VOXEL_U16, REF_VOXEL_I16 };

/* Raw voxel n of an array of the given type, signed where the type is (16-bit voxels in the host's order). */
static inline int32_t ref_raw_voxel(const void *raw, int type, size_t n)
{
    const unsigned char *p = raw;
    switch (type) {
    case REF_VOXEL_U8: return p[n];
    case REF_VOXEL_I8: return (int8_t)p[n];
    case REF_VOXEL_U16: { uint16_t v; memcpy(&v, p + 2 * n, 2); return v; }
    default: { int16_t v; memcpy(&v, p + 2 * n, 2); return v; }
    }
}

/* s = clamp(round((v - lo) * 255 / (hi - lo)), 0, 255) for every voxel (native byte order). lo != hi. */
int ref_window(const void *raw, int type, const int dims[3], int32_t lo, int32_t hi, uint8_t *out);

/* ---- ref_tables.c -------------------------------------------------------------------------------------- */

/* The transfer function (npoints >= 1) at scalar s: rgba = r, g, b, a. Piecewise linear, constant beyond the ends;
 * right-continuous at a step (points sharing a scalar: the last of them holds at that scalar and to its right). */
void ref_tf_eval(const ref_tf_point_t *tf, int npoints, double s, double rgba[4]);

/* Classification of the N entries: tau[i] = -ln(1 - min(a0(s_i), 1 - 2^-16)), rgb[3i..3i+2] = colour. */
int ref_classify(const ref_tf_point_t *tf, int npoints, int N, double *tau, double *rgb);

/* Point table for slab length d: out[4i..4i+3] = a, r, g, b (premultiplied). */
int ref_point_table(const ref_tf_point_t *tf, int npoints, int N, double d, double *out);

/* Pre-integrated table for slab length d, brute force O(N^3): out[4 (front N + back) + 0..3] = a, r, g, b. */
int ref_preint_table(const ref_tf_point_t *tf, int npoints, int N, double d, double *out);

/* Section 7's front-weighted table for slab length d, brute force: out[4 (front N + back) + 0..3] = S_f, D_f r, g,
 * b (the layout of the pre-integrated table, S_f where it has a, so that lookups and corrections treat both
 * alike). */
int ref_lit_table(const ref_tf_point_t *tf, int npoints, int N, double d, double *out);

/* t(x) = 1 / x - exp(-x) / (1 - exp(-x)), t(0) = 1/2: the mean depth, from its front face, of the light a uniform
 * piece of optical depth x sends out (section 7). */
double ref_mean_depth(double x);

/* The nearest entry idx(s) = round(s (N - 1) / 255) of a real-valued scalar s in [0, 255]. */
int ref_table_index(double s, int N);

/* ---- ref_options.c ------------------------------------------------------------------------------------- */

/* One table entry for a sample s in [0, 255] of a point table (N x 4): nearest, T[idx(s)]; bilinear, with
 * x = s (N - 1) / 255, i = min(floor(x), N - 2), f = x - i: (1 - f) T[i] + f T[i + 1]. out: a, r, g, b. */
void ref_lookup_point(const double *table, int N, ref_lookup_t lookup, double s, double out[4]);

/* One entry of a pre-integrated table (N x N x 4, front major) for a front and a back sample: nearest,
 * T[idx(front)][idx(back)]; bilinear, (1-f)(1-g) T[i][j] + f(1-g) T[i+1][j] + (1-f)g T[i][j+1] + fg T[i+1][j+1]
 * with (i, f) from the front sample and (j, g) from the back one as in ref_lookup_point. */
void ref_lookup_preint(const double *table, int N, ref_lookup_t lookup, double front, double back, double out[4]);

/* Table bits: with 8, every one of the count values becomes round(255 x) / 255; with 16 (or 0) nothing changes.
 * Returns -1 for other bits. */
int ref_table_bits(double *values, size_t count, int bits);

/* The lut correction for rho = d / d0 > 0: F(a) = 1 - (1 - a)^rho and G(a) = F(a) / a, G(0) = rho, at the knots
 * a_k = k / REF_LUT_KNOTS. */
typedef struct ref_lut {
    double rho;
    double F[REF_LUT_KNOTS + 1], G[REF_LUT_KNOTS + 1];
} ref_lut_t;

int ref_lut_init(ref_lut_t *lut, double rho);

/* seg = (a, C_r, C_g, C_b) -> (F(a), C G(a)), F and G linear between the knots (a clamped to [0, 1]). */
void ref_lut_correct(const ref_lut_t *lut, double seg[4]);

/* The same for a lit slab: seg as above, and the four front-weighted values lit (S_f, D_f) times G(a) too. */
void ref_lut_correct_lit(const ref_lut_t *lut, double seg[4], double lit[4]);

/* ---- ref_factor.c -------------------------------------------------------------------------------------- */

/* sin and cos of an angle in binary angle units (exact 0 and +-1 at multiples of a quarter turn). */
void ref_sincos(int32_t bau, double *s, double *c);

/* The volume's dimensions and spacings within the spec's ranges (each dimension 2..REF_MAX_DIM, spacings finite
 * and above 0, the largest at most REF_MAX_ANISOTROPY times the smallest): 0 with the smallest spacing in *spmin,
 * or -1. ref_factor and the truth's camera check their volume with it. */
int ref_volume_check(const ref_volume_t *vol, double *spmin);

int ref_factor(const ref_volume_t *vol, const ref_view_t *view, int out_w, int out_h, ref_factor_t *f);

/* Adopt another renderer's snapped offsets (2 n_k values, ou then ov, Q16.16) after checking that they belong to
 * the same principal axis and flip and that each is within one 2^-16 grid step of this factorisation's own.
 * Returns 0, or -2 when they disagree (the factorisations differ). The array must outlive f. */
int ref_factor_adopt_offsets(ref_factor_t *f, const int32_t *offsets_q16, int k_axis, int k_flip);

/* Offset (ou_k, ov_k) of standard slice k in the intermediate image, snapped to the 2^-16 grid (or adopted). */
void ref_factor_offset(const ref_factor_t *f, int k, double *ou, double *ov);

/* The intermediate point (u, v) that final pixel (px, py) sees (section 3, "Warp"). */
void ref_factor_warp(const ref_factor_t *f, double px, double py, double *u, double *v);

/* ---- ref_normals.c (section 7) ----------------------------------------------------------------------- */

#define REF_MAX_LIGHTS 2

/* How frames are lit. The normals come from the volume as stored (raw, before the window): raw and raw_type
 * describe it (x fastest, native byte order, the dims and spacing of the ref_volume_t it goes with). */
struct ref_lighting {
    int shade;                  /* 1: Blinn-Phong; 0: unlit colours (the gradient opacity still applies) */
    int light_count;            /* 1..REF_MAX_LIGHTS white directional lights */
    int32_t light_azimuth[REF_MAX_LIGHTS], light_elevation[REF_MAX_LIGHTS]; /* BAU, relative to the viewer */
    double ka, kd, ks;          /* [0, 1] */
    int shininess;              /* 1..255 */
    int gradient_lo, gradient_hi; /* opacity ramp in 8-bit magnitudes, 0 <= lo < hi <= 255; 0, 0: none */
    int normal_bits;            /* 8, 10, 12, 14 or 16 */
    ref_lookup_t shade_lookup;  /* a sample's shade: its nearest voxel's, or its four voxels' interpolated */
    const void *raw;
    int raw_type;               /* REF_VOXEL_* */
    /* For the precision study, not in section 7 (0: as section 7 says). exact_normals: every voxel's normal is
     * its gradient G / |G| in double (G_a = D_a min(sp) / (c_a sp_a), no q rounding, no code), the codes' error
     * taken away. shade_bits: the shade table's L_d and L_s rounded to that many fraction bits (1..30).
     * lit_table_bits: the front-weighted table's values rounded as the table bits of section 4b do, to 2..16 bits,
     * the plain table left as it is. */
    int exact_normals;
    int shade_bits;
    int lit_table_bits;
};

/* Levels a side of the octahedron, L = 2^(bits / 2) - 1; codes 0 .. L^2 - 1 are normals, L^2 is none. */
int ref_normal_levels(int normal_bits);

/* Section 7's integer gradient of voxel (x, y, z): G_a = D_a q_a(c_a), from the raw voxels. Also, when gd is
 * not NULL, the same gradient in double without q's rounding, D_a min(sp) / (c_a sp_a) (sp the spacings as
 * given), which is G_a / 2^14 exactly up to that rounding. */
void ref_gradient(const ref_volume_t *vol, const void *raw, int raw_type, int x, int y, int z, int64_t G[3],
                  double gd[3]);

/* The code of an integer gradient (the octahedral map, rounded exactly as section 7 says). */
int ref_normal_code(const int64_t G[3], int levels);

/* A code's unit normal in double (world axes); (0, 0, 0) for the code L^2. */
void ref_normal_decode(int code, int levels, double n[3]);

/* M of section 7: the largest floor(|G|) over the volume (0 when it is flat), or -1 on bad arguments. */
int64_t ref_gradient_most(const ref_volume_t *vol, const void *raw, int raw_type);

/* Every voxel's code (levels from normal_bits) and 8-bit gradient magnitude gm, object order (x fastest).
 * codes may be NULL (magnitudes only). Returns 0, or -1 on bad arguments or out of memory. */
int ref_normals(const ref_volume_t *vol, const void *raw, int raw_type, int normal_bits, int32_t *codes,
                uint8_t *magnitudes);

/* ---- ref_shade.c (section 7) -------------------------------------------------------------------------- */

/* A shade: diffuse light L_d, specular light L_s and the gradient-opacity factor g. */
typedef struct ref_shade {
    double d, s, g;
} ref_shade_t;

/* The lights of a frame with rotation R (section 3, world -> eye): towards each light and its half vector in
 * eye axes, and the material. */
typedef struct ref_lights {
    const ref_lighting_t *lighting;
    double R[3][3];
    double L[REF_MAX_LIGHTS][3], H[REF_MAX_LIGHTS][3];
} ref_lights_t;

int ref_lights_init(ref_lights_t *lights, const ref_lighting_t *lighting, const double R[3][3]);

/* L_d and L_s of a world normal n (unit, or (0, 0, 0): no normal, ambient only), two-sided. Rounded to
 * lighting->shade_bits fraction bits when that is set; (1, 0) when lighting->shade is 0. */
void ref_shade_normal(const ref_lights_t *lights, const double n[3], double *ld, double *ls);

/* The gradient-opacity factor of a magnitude in 8-bit units: clamp((gm - lo) / (hi - lo), 0, 1), 1 without a
 * ramp (the truth gives it magnitudes between the levels). */
double ref_gradient_factor(const ref_lighting_t *lighting, double gm);

/* Section 7's lit segment of order 0: seg = (a, C_r, C_g, C_b) -> C' = min(L_d C + L_s a, a), then a and C' times
 * g. */
void ref_light_point(double seg[4], ref_shade_t shade);

/* Section 7's lit slab: seg = (a, C) of the plain table and lit = (S_f, D_f r, g, b) of the front-weighted one,
 * looked up and corrected alike; C' = L_db C + (L_df - L_db) D_f + L_sb a + (L_sf - L_sb) S_f clamped to [0, a],
 * then a and C' times (g_f + g_b) / 2. */
void ref_light_slab(double seg[4], const double lit[4], ref_shade_t front, ref_shade_t back);

/* ---- ref_render.c -------------------------------------------------------------------------------------- */

/* Composite every slice (point and preclass: table is the N x 4 point table) or slab (preint1: the N x N x 4
 * table) into the intermediate image inter[4 (v int_w + u) + 0..3] = premultiplied R, G, B and opacity A, with
 * nearest lookup and no correction (section 4, and preclass of section 4b). */
int ref_composite(const ref_volume_t *vol, const ref_factor_t *f, ref_mode_t mode, int N, const double *table,
                  double *inter);

/* The same with the options of section 4b: the lookup, and when lut is not NULL every segment corrected by it
 * (after the lookup, or after the interpolation of the classified voxels for preclass). The table is used as
 * given: build it for the slab length wanted (d, or d0 with a lut) and apply the table bits first. */
int ref_composite_ex(const ref_volume_t *vol, const ref_factor_t *f, ref_mode_t mode, ref_lookup_t lookup, int N,
                     const double *table, const ref_lut_t *lut, double *inter);

/* The same with a choice of the side-face rule: section 4's, or partial slabs (section 4c; as in ref_params_t). */
int ref_composite_sides(const ref_volume_t *vol, const ref_factor_t *f, ref_mode_t mode, ref_lookup_t lookup, int N,
                        const double *table, const ref_lut_t *lut, int partial_slabs, double *inter);

/* The intermediate image of R rays per voxel column (section 3): *w = R (int_w - 1) + 1, *h = R (int_h - 1) + 1
 * pixels; pixel (U, V) is the ray through intermediate point (U / R, V / R). Returns 0, or -1 when R is not 1, 2,
 * 4, 8 or 16 (0 is not accepted here: callers say what they mean). */
int ref_rays_size(const ref_factor_t *f, int rays, int *w, int *h);

/* The same with R rays per voxel column: inter[4 (V w + U) + 0..3] for the w x h pixels of ref_rays_size. R = 1 is
 * ref_composite_sides. */
int ref_composite_rays(const ref_volume_t *vol, const ref_factor_t *f, ref_mode_t mode, ref_lookup_t lookup, int N,
                       const double *table, const ref_lut_t *lut, int partial_slabs, int rays, double *inter);

/* The same, lit (section 7): lighting says how, with the frame's rotation f->R; lit_table is preint1's
 * front-weighted table (N x N x 4 as ref_lit_table, built for the length and rounded to the bits of table), NULL
 * for the other modes. Partial slabs are not lit: -1. */
int ref_composite_lit(const ref_volume_t *vol, const ref_factor_t *f, ref_mode_t mode, ref_lookup_t lookup, int N,
                      const double *table, const double *lit_table, const ref_lut_t *lut, int rays,
                      const ref_lighting_t *lighting, double *inter);

/* Resample the intermediate image bilinearly (outside: transparent) onto the final image:
 * rgb[3 (py out_w + px) + c] = C + (1 - A) background[c]. */
void ref_warp(const ref_factor_t *f, const double *inter, const double background[3], double *rgb);

/* The same for an intermediate image of R rays per voxel column (ref_rays_size): final pixel (px, py), which sees
 * intermediate point (u, v), reads it at (R u, R v). Returns 0, or -1 for a bad R. */
int ref_warp_rays(const ref_factor_t *f, int rays, const double *inter, const double background[3], double *rgb);

/* The whole frame: factor, tables (for the slab length d, or for d0 = 1 with the lut correction for rho = d),
 * table bits, composite, warp. rgb: out_w * out_h * 3 in [0, 1]. factor_out may be NULL. */
int ref_render(const ref_volume_t *vol, const ref_tf_point_t *tf, int npoints, const ref_params_t *p,
               const ref_view_t *view, int out_w, int out_h, double *rgb, ref_factor_t *factor_out);

/* ---- ref_order2.c ------------------------------------------------------------------------------------- */

/* Section 8: the order-2 table for slabs of length 2d, N2 entries a side, built from the pieces of the N-entry
 * pre-integrated table for length 2d / K (ref_preint_table, brute force): out[4 ((f N2 + m) N2 + b) + 0..3] = a, r,
 * g, b, entry (f, m, b) the K pieces along its quadratic, composited front to back in double. */
int ref_order2_table(const ref_tf_point_t *tf, int npoints, int N, int N2, double d, double *out);

/* The K + 1 ends of entry (f, m, b)'s pieces, entries of the N-entry table (section 8's integers). */
void ref_order2_ends(int N, int N2, int f, int m, int b, int end[REF_ORDER2_PIECES + 1]);

/* One entry of the order-2 table (N2^3 x 4) for a front, middle and back sample: nearest, T2[idx2(sf)][idx2(sm)]
 * [idx2(sb)]; trilinear, the eight entries around them weighted as section 4b weights four. out: a, r, g, b. */
void ref_lookup_order2(const double *table2, int N2, ref_lookup_t lookup, double sf, double sm, double sb,
                       double out[4]);

/* Section 8's lighting values of the order-2 table for slabs of 2d, from the pieces of section 7's front-weighted
 * table (ref_lit_table) for 2d / K: out[8 ((f N2 + m) N2 + b) + 0..7] = S_f', W_f r, g, b, S_b', W_b r, g, b (the
 * layout of two entries of the plain table, the specular weight where it has a). */
int ref_order2_lit_table(const ref_tf_point_t *tf, int npoints, int N, int N2, double d, double *out);

/* Composite preint2's slabs (section 8) into the R-ray intermediate image (as ref_composite_rays): table2 the order-2
 * table (N2), table the 2D table (N) for the last slab of an odd count, both as given (built for the slab length,
 * table bits applied); lut NULL or the correction of every segment. Lit when lighting is not NULL: lit2 the
 * order-2 table's lighting values (ref_order2_lit_table) and lit the 2D table's front-weighted ones (ref_lit_table),
 * both as given. */
int ref_composite_order2(const ref_volume_t *vol, const ref_factor_t *f, ref_lookup_t lookup, int N,
                         const double *table, int N2, const double *table2, const ref_lut_t *lut, int rays,
                         const ref_lighting_t *lighting, const double *lit, const double *lit2, double *inter);

/* What ref_render does for preint2: the tables for d (rebuild: the 2D table for d, the 3D one for slabs of 2d) or
 * d0 (lut, corrected for rho = d / d0), table bits, composite, warp. */
int ref_render_order2(const ref_volume_t *vol, const ref_tf_point_t *tf, int npoints, const ref_params_t *p,
                      const ref_factor_t *f, double *rgb);

/* ---- ref_render.c's helpers, for ref_order2.c -------------------------------------------------------------- */

/* The volume's scalars in standard order (malloc'd; NULL when out of memory): std[(k nj + j) ni + i]. */
uint8_t *ref_standard_slices(const ref_volume_t *vol, const ref_factor_t *f);
/* The bilinear sample of an ni-wide slice at an inside position (x, y), exact on the 2^-16 grid. */
double ref_slice_sample(const uint8_t *slice, int ni, double x, double y);
/* Front to back: pix R, G, B, A; seg a, r, g, b. */
void ref_composite_segment(double *pix, const double *seg);
/* A frame's shading (section 7, as the lit modes have it): its lights, the voxels' codes and magnitudes, the shade
 * of every code; the shades of standard slice k's voxels into slot which (0..2); a sample's shade in a slot's slice
 * at the inside position (x, y). ref_shading_new returns NULL on bad lighting or when out of memory. */
typedef struct ref_shading ref_shading_t;
ref_shading_t *ref_shading_new(const ref_volume_t *vol, const ref_factor_t *f, const ref_lighting_t *lighting);
void ref_shading_free(ref_shading_t *shading);
void ref_shading_slice(ref_shading_t *shading, const ref_volume_t *vol, const ref_factor_t *f, int k, int which);
ref_shade_t ref_shading_sample(const ref_shading_t *shading, int which, int ni, double x, double y);

#endif /* REF_H */
