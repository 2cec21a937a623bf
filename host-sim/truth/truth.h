/* SPDX-License-Identifier: MIT */
/*
 * truth.h: the ground truth, a double-precision ray caster of the continuous model that shear-warp approximates.
 *
 * It measures what the shear-warp *algorithm* gets wrong (slab sampling, table lookup, order 0/1/2), so its own
 * error must be far below that. Same camera and final-image mapping as docs/algorithm.md section 3, so its
 * images align pixel by pixel with the core's and the reference's; after that nothing is shared:
 *   - reconstruction: trilinear interpolation of the windowed 8-bit scalars on [0, n-1]^3 (nothing outside);
 *   - the transfer function is the continuous piecewise-linear one of the control points, not a table, with the
 *     spec's opacity definition: a0(s) clamped to [0, 1 - 2^-16], tau(s) = -ln(1 - a0(s)) per d_ref, colour c(s);
 *   - emission-absorption integrated along each ray cell by cell (3D DDA), skipping cells whose corner range has
 *     zero opacity, in sub-steps of at most 1/16 voxel and short enough that the trilinear scalar (a cubic
 *     along the ray) is linear to within a small tolerance; each sub-step is split where the scalar crosses a
 *     control point and each piece is integrated exactly in optical depth (closed form) and in emission by
 *     parts, leaving one smooth integral for Gauss-Legendre.
 * A ray stops once its opacity reaches 1 - 1e-9; nothing else is cut short.
 *
 * Files: truth_tf.c (the transfer function and one linear piece), truth_ray.c (camera, DDA, one ray),
 * truth_render.c (an image on threads), ray_study.c (El Hajjar et al.'s reconstruction-error study of one ray).
 * Functions returning int return 0, or -1 on arguments outside the ranges of ref.h or when out of memory.
 */
#ifndef TRUTH_H
#define TRUTH_H

#include <stdint.h>

#include "ref/ref.h"

#define TRUTH_A0_MAX (1.0 - 1.0 / 65536.0) /* the spec's clamp of opacity per d_ref */
#define TRUTH_STOP_OPACITY (1.0 - 1e-9)     /* a ray stops here */
#define TRUTH_MAX_SEGS (3 * REF_MAX_TF_POINTS + 2)

/* ---- truth_tf.c ------------------------------------------------------------------------------------------ */

/* One piece of the transfer function on which opacity (already clamped) and colour are linear in the scalar:
 * values at s0 and s1 are the one-sided limits there. The first and last pieces reach far beyond 0..255. */
typedef struct truth_seg {
    double s0, s1; /* s0 < s1 */
    double a0, a1;
    double c0[3], c1[3];
} truth_seg_t;

/* The transfer function prepared for integration: its pieces (split where the opacity crosses 0 or the clamp,
 * so that the clamped opacity stays linear on each), and what cell skipping and the sub-step tolerance need. */
typedef struct truth_tf {
    int nseg;
    truth_seg_t seg[TRUTH_MAX_SEGS];
    uint8_t visible_at[256]; /* opacity > 0 at the integer scalar s (the value there, right-continuous) */
    int visible_units[257];  /* how many unit intervals [m, m + 1], m < s, have opacity > 0 somewhere */
    /* on [m, m + 1]: how fast the function changes per scalar level, the larger of |da/ds| and max(a) |dc/ds|;
     * INFINITY where it jumps (a step) */
    double steep[255];
} truth_tf_t;

/* Front-to-back accumulation along a ray: transmittance T = 1 - A and premultiplied colour C. */
typedef struct truth_acc {
    double T;
    double C[3];
} truth_acc_t;

/* Prepare a transfer function (ref.h's rules: 1..REF_MAX_TF_POINTS points, s non-decreasing, all finite). */
int truth_tf_init(truth_tf_t *tf, const ref_tf_point_t *points, int npoints);

/* Is the opacity zero everywhere on the integer scalar range [lo, hi] (lo <= hi, both 0..255)? */
int truth_tf_clear(const truth_tf_t *tf, int lo, int hi);

/* The largest steepness on the integer scalar range [lo, hi] (0 when lo == hi). */
double truth_tf_steepness(const truth_tf_t *tf, int lo, int hi);

/* Optical depth of a length L (units of d_ref) over which the clamped opacity per d_ref goes linearly from a0
 * to a1: L times the mean of -ln(1 - a), in closed form (with g = 1 - a, -L (g1 ln g1 - g1 - g0 ln g0 + g0) /
 * (g1 - g0)) written so that it does not cancel when g1 is close to g0. */
double truth_depth(double a0, double a1, double L);

/* Composite a length L along which the scalar goes linearly from sa to sb into acc: split at every
 * control point crossed, each piece exact in optical depth, emission by Gauss-Legendre. */
void truth_tf_composite(const truth_tf_t *tf, double sa, double sb, double L, truth_acc_t *acc);

/* The same lit by a shade constant over the length (docs/algorithm.md, "Lit truth"): colour c(s) L_d + L_s,
 * clamped to 1 per channel, and the extinction times the gradient-opacity factor g. */
void truth_tf_composite_lit(const truth_tf_t *tf, double sa, double sb, double L, ref_shade_t shade,
                            truth_acc_t *acc);

/* ---- truth_ray.c ----------------------------------------------------------------------------------------- */

/* Section 3's camera for the truth: the ray through final pixel (px, py) is p(t) = origin + t dir in object
 * index coordinates, t in world units (d_ref), dir_a = R[2][a] / Sr_a. */
typedef struct truth_camera {
    int dims[3];
    double R[3][3];   /* world -> eye, Rz(roll) Rx(elevation) Ry(azimuth) */
    double Sr[3];     /* relative spacing sp / min(sp) */
    double centre[3]; /* (n - 1) / 2 */
    double scale;     /* final pixels per world unit, zoom min(W, H) / |Sr (n - 1)| */
    int out_w, out_h;
} truth_camera_t;

int truth_camera(const ref_volume_t *vol, const ref_view_t *view, int out_w, int out_h, truth_camera_t *cam);

/* The ray through final pixel (px, py) and the part of it inside [0, n-1]^3, t_in <= t <= t_out.
 * Returns 1 when the ray meets the volume, else 0. */
int truth_camera_ray(const truth_camera_t *cam, double px, double py, double origin[3], double dir[3],
                     double *t_in, double *t_out);

/* A ray's walk through the cells [c, c + 1]^3, c_a in 0..n_a - 2 (3D DDA, Amanatides and Woo), from t_in to t_out
 * along origin + t dir. A ray on a cell face may be given either cell: the fields are continuous there. */
typedef struct truth_walk {
    int piece[3];        /* the cell of the piece truth_walk_next returned last */
    int cell[3], step[3], dims[3], done;
    double t_next[3], t, t_out;
    double o[3], d[3]; /* the ray: origin + t dir */
} truth_walk_t;

void truth_walk_start(truth_walk_t *w, const int dims[3], const double origin[3], const double dir[3], double t_in,
                      double t_out);
/* The walk of the ray through final pixel (px, py), with *acc emptied; 0 when the ray misses the volume. */
int truth_walk_pixel(truth_walk_t *w, const truth_camera_t *cam, const int dims[3], double px, double py,
                     truth_acc_t *acc);
/* The next piece [*t0, *t1] of the ray, in cell w->piece; 0 once the ray has left the volume. */
int truth_walk_next(truth_walk_t *w, double *t0, double *t1);

/* The trilinear scalar at object point p (clamped to the volume). */
double truth_sample(const ref_volume_t *vol, const double p[3]);

/* Integration settings.
 * max_step: the longest sub-step, in voxels of the index grid and in world units alike (world units keep the
 *   optical depth of a piece small for Gauss-Legendre in anisotropic volumes).
 * scalar_tol: the most the trilinear scalar may differ from its linear interpolation across a sub-step, in
 *   scalar levels; it shortens sub-steps where the signal curves.
 * steep: a scalar error changes opacity and colour in proportion to how fast the transfer function changes
 *   (truth_tf_steepness); where that is below `steep` per level the tolerance grows in proportion, up to
 *   TRUTH_LOOSEST_TOL, for the same error in less time. 0: scalar_tol everywhere.
 * The defaults' own error, against 1/64-voxel steps, a 1e-6 tolerance and steep 0: at most 4e-4 per channel
 * (0.1 of an 8-bit level) and 2e-6 on average on marschner-lobb 41^3 with the sharp preset, 512x512 at 30,20. */
typedef struct truth_field truth_field_t;
typedef struct truth_opts {
    double max_step;
    double scalar_tol;
    double steep;
    const truth_field_t *field; /* the reconstruction (truth_smooth.c); NULL: trilinear */
} truth_opts_t;

#define TRUTH_MAX_STEP (1.0 / 16.0)
#define TRUTH_SCALAR_TOL (1.0 / 4096.0)
#define TRUTH_STEEP 0.2 /* opacity 0 to 1 within 5 levels (the sharp preset's peaks, 2% of the range wide) */
#define TRUTH_LOOSEST_TOL (1.0 / 16.0)
#define TRUTH_OPTS_DEFAULT {TRUTH_MAX_STEP, TRUTH_SCALAR_TOL, TRUTH_STEEP, NULL}

/* Integrate the ray through final pixel (px, py): rgba_out = premultiplied r, g, b and opacity A (no
 * background). opts NULL: the defaults above. */
int truth_ray_ex(const ref_volume_t *vol, const ref_tf_point_t *tf, int npoints, const ref_view_t *view,
                 int out_w, int out_h, double px, double py, const truth_opts_t *opts, double rgba_out[4]);
int truth_ray(const ref_volume_t *vol, const ref_tf_point_t *tf, int npoints, const ref_view_t *view, int out_w,
              int out_h, double px, double py, double rgba_out[4]);

/* The same for a prepared transfer function and camera (what truth_render runs per pixel). */
void truth_trace(const ref_volume_t *vol, const truth_tf_t *tf, const truth_camera_t *cam, const truth_opts_t *opts,
                 double px, double py, truth_acc_t *acc);

/* Lighting for the truth (docs/algorithm.md, "Lit truth"): at every sub-step the gradient of the trilinear field
 * of the raw voxels in world units, shaded as section 7 shades a normal, and its magnitude mapped to 8-bit
 * magnitudes by 255 |g| / M, M the volume's largest central-difference magnitude (section 7's, in world
 * units), for the gradient-opacity ramp. */
typedef struct truth_lit {
    ref_lights_t lights; /* section 7's lights with the camera's rotation, and the lighting */
    double most;         /* M in raw units per world unit (section 7's largest m over 2^14); 0: a flat volume */
} truth_lit_t;

/* Prepare lit tracing for a camera (the lighting's raw voxels go with vol). Returns 0, or -1. */
int truth_lit_init(truth_lit_t *lit, const ref_volume_t *vol, const truth_camera_t *cam, const ref_lighting_t *l);

/* truth_trace, lit (lit NULL: unlit, truth_trace itself). */
void truth_trace_lit(const ref_volume_t *vol, const truth_tf_t *tf, const truth_camera_t *cam,
                     const truth_opts_t *opts, const truth_lit_t *lit, double px, double py, truth_acc_t *acc);

/* ---- truth_smooth.c -------------------------------------------------------------------------------------- */

/* Smoother reconstructions than trilinear, for ranking the orders of integration: along an oblique ray a
 * trilinear field bends only at cell faces and is linear along an axis, which favours order 1; the signal
 * order 2 is meant to follow is the smooth one the samples came from (docs/algorithm.md, section 8b).
 *   - TRUTH_FILTER_CATMULL_ROM: the tensor-product Catmull-Rom cubic of the windowed scalars; it interpolates
 *     (equals every voxel at its grid point) and reproduces quadratics. Outside the volume the ghost samples
 *     are extrapolated linearly (2 v_0 - v_1), so linear data stays linear up to the faces.
 *   - TRUTH_FILTER_BSPLINE: the cubic B-spline of the same samples (approximates: at a grid point it is the
 *     1-4-1 / 6 blend in each axis; reproduces linear data; never leaves the range of its 4^3 samples).
 *   - TRUTH_FILTER_ANALYTIC: a phantom's own function (truth_phantom_fn) before it was rounded to 8 bits,
 *     windowed like the voxels and clamped to [0, 255].
 * The cubic filters' values are clamped to [0, 255] like every scalar. The ray is walked cell by cell as the
 * trilinear truth walks it; a cell is skipped when the transfer function is clear on a bound of the scalar
 * there (the range of its 4^3 samples, widened by 0.477 of it for Catmull-Rom, whose negative weights sum to
 * 0.477 at most in 3D); each sub-step of at most max_step is halved until the scalar at its middle is within
 * 4 scalar_tol of its chord (relaxed by `steep` as for trilinear), and integrated as two linear pieces.
 * Lighting is trilinear only (truth_render_lit refuses a field with lighting). */
typedef enum truth_filter {
    TRUTH_FILTER_TRILINEAR = 0,
    TRUTH_FILTER_CATMULL_ROM,
    TRUTH_FILTER_BSPLINE,
    TRUTH_FILTER_ANALYTIC,
    TRUTH_FILTER_SMOOTH, /* only as a request: ANALYTIC for a phantom that has one, else CATMULL_ROM */
} truth_filter_t;

/* A phantom's raw value (0..255, unrounded) at object index point p of a volume of dims. */
typedef double (*truth_phantom_fn_t)(const double p[3], const int dims[3]);

struct truth_field {
    truth_filter_t filter;         /* CATMULL_ROM, BSPLINE or ANALYTIC */
    const ref_volume_t *vol;
    truth_phantom_fn_t analytic;   /* ANALYTIC */
    double win_lo, win_hi;         /* ANALYTIC: the window that maps raw values to scalars */
    uint8_t *cell_lo, *cell_hi;    /* cubic filters: bounds on the scalar in cell c, (n_a - 1) per axis */
};

/* The analytic function of phantom:NAME:N (marschner-lobb, sphere, cube), or NULL when NAME has none
 * (shepp-logan: a sum of ellipsoids with jumps, no smooth signal) or spec is not a phantom. */
truth_phantom_fn_t truth_phantom_fn(const char *spec);

/* "trilinear", "catmull-rom", "bspline", "analytic", "smooth": 0 and *filter, or -1. */
int truth_filter_parse(const char *text, truth_filter_t *filter);
const char *truth_filter_name(truth_filter_t filter);

/* Prepare a field for vol (which must outlive it). phantom_spec: the volume's phantom spec or NULL; win_lo,
 * win_hi: the window of the raw values (ref_window's). filter SMOOTH resolves as above; TRILINEAR gives a field
 * with filter TRILINEAR that the truth treats as NULL. Returns 0, -1 on bad arguments or out of memory, -2 for
 * ANALYTIC on a volume without an analytic function. */
int truth_field_init(truth_field_t *field, const ref_volume_t *vol, truth_filter_t filter, const char *phantom_spec,
                     double win_lo, double win_hi);
void truth_field_free(truth_field_t *field);

/* The field's scalar at object index point p (clamped to the volume), in [0, 255]. */
double truth_field_sample(const truth_field_t *field, const double p[3]);

/* The field's part of truth_trace: the ray through (px, py) walked through the field. */
void truth_trace_field(const truth_tf_t *tf, const truth_camera_t *cam, const truth_opts_t *opts, double px,
                       double py, truth_acc_t *acc);

/* ---- truth_render.c -------------------------------------------------------------------------------------- */

/* Rows 0 .. rows - 1 of any grid of rays on threads (1..64), interleaved so that the expensive middle of an image
 * is shared evenly: row(ctx, y) for every y, each exactly once; rows of a thread that could not start are run
 * on the caller's. */
#define TRUTH_MAX_THREADS 64
void truth_rows(int rows, int threads, void (*row)(const void *ctx, int y), const void *ctx);

/* The whole image: rgb[3 (py out_w + px) + c] = C + (1 - A) background[c], rows split over threads (1..64). */
int truth_render_ex(const ref_volume_t *vol, const ref_tf_point_t *tf, int npoints, const double background[3],
                    const ref_view_t *view, int out_w, int out_h, int threads, const truth_opts_t *opts,
                    double *rgb);
int truth_render(const ref_volume_t *vol, const ref_tf_point_t *tf, int npoints, const double background[3],
                 const ref_view_t *view, int out_w, int out_h, int threads, double *rgb);

/* The whole image lit (lighting NULL: truth_render_ex); its study knobs (exact_normals, shade_bits,
 * lit_table_bits) and normal_bits and shade_lookup do not apply: the truth has no codes and no tables. */
int truth_render_lit(const ref_volume_t *vol, const ref_tf_point_t *tf, int npoints, const double background[3],
                     const ref_view_t *view, int out_w, int out_h, int threads, const truth_opts_t *opts,
                     const ref_lighting_t *lighting, double *rgb);

/* ---- ray_study.c ----------------------------------------------------------------------------------------- */

/* El Hajjar et al. 2008's study of one ray: the trilinear signal along the ray and its reconstructions from
 * shear-warp's samples (on the slices of the principal axis) of order 0, 1, 2 at spacing 1 and 2 slices.
 * Positions are in standard slice coordinates k (0 at the front slice; one unit = one slab, the spacing of
 * shear-warp's samples). */
typedef struct truth_study {
    double k_in, k_out; /* the ray's part inside the volume */
    double k_a, k_b;    /* where every reconstruction is defined (whole order-2 slabs at spacing 2) */
    int k_axis, k_flip; /* the principal axis as ref_factor chooses it */
    double slab;        /* world length of one unit of k (ref_factor's slab length d) */
    double xi[3][2];    /* xi[order][spacing - 1] = integral over [k_a, k_b] of |signal - reconstruction| dk */
    /* The renderers' own segments (docs/algorithm.md sections 4 and 8): point and preint1 as order 0 and 1 at
     * spacing 1; preint2's slabs start on even standard slices (k = 0, 2, ...), each the quadratic through its
     * three samples clamped to their range, and a volume with n_k - 1 odd ends in one order-1 slab. Compared on
     * [r_a, r_b], the whole slabs of preint2 inside the ray's slices (also its last order-1 slab, when the ray
     * reaches the last slice). xi_r[0..2] = point, preint1, preint2 there. */
    double r_a, r_b;
    double xi_r[3];
    /* the signal and the reconstructions on a grid of `per_voxel` points per unit of k over [k_in, k_out]:
     * rows of TRUTH_STUDY_COLS values t, signal, order0_1, order1_1, order2_1, order0_2, order1_2, order2_2,
     * preint2 (NaN where a reconstruction is not defined) */
    int rows;
    double *table;
} truth_study_t;
#define TRUTH_STUDY_COLS 9

/* Returns 0, 1 when the ray misses the volume or crosses too few slices for a spacing-2 order-2 slab, or -1.
 * field: the signal's reconstruction (truth_smooth.c), NULL or trilinear: trilinear; the samples on the slices
 * are the field's too (a renderer samples the data bilinearly in a slice: against a smooth field the samples
 * are where the smooth signal is, which isolates the error along the ray). */
int truth_study_ray(const ref_volume_t *vol, const ref_view_t *view, int out_w, int out_h, double px, double py,
                    int per_voxel, truth_study_t *study);
int truth_study_ray_field(const ref_volume_t *vol, const truth_field_t *field, const ref_view_t *view, int out_w,
                          int out_h, double px, double py, int per_voxel, truth_study_t *study);
void truth_study_free(truth_study_t *study);

#endif /* TRUTH_H */
