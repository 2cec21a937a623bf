/* SPDX-License-Identifier: MIT */
/* truth_smooth.c: the truth's smooth reconstructions (Catmull-Rom, cubic B-spline, a phantom's own function) and
 * the ray walk through them (truth.h, "truth_smooth.c"). */
#include "truth/truth.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CR_NEG 0.477 /* Catmull-Rom: the most its negative weights sum to in 3D, ((1.25)^3 - 1) / 2 = 0.4766 */
#define MAX_DEPTH 10 /* halvings of a sub-step: 1/1024 of max_step, never reached on the shared scenes' peaks */
#define MAX_SUBSTEPS 4096

/* The phantoms as port/io/phantom.c makes them, before rounding (the same constants, written again here: the
 * truth shares no code with what it measures). */
#define ML_FM 6.0
#define ML_ALPHA 0.25
#define SPHERE_RADIUS 0.45

static void cell_smooth(const truth_field_t *f, const truth_tf_t *tf, const truth_opts_t *opts, const int cell[3],
                        const double o[3], const double d[3], double t0, double t1, truth_acc_t *acc);

/* ---- the phantoms ---------------------------------------------------------------------------------------- */

static double unit_coord(double i, int n)
{
    return -1.0 + 2.0 * i / (n - 1);
}

/* Marschner and Lobb 1994 on [-1, 1]^3, times 255. */
static double marschner_lobb(const double p[3], const int dims[3])
{
    const double pi = acos(-1.0);
    double x = unit_coord(p[0], dims[0]), y = unit_coord(p[1], dims[1]), z = unit_coord(p[2], dims[2]);
    double r = sqrt(x * x + y * y), rho_r = cos(2.0 * pi * ML_FM * cos(pi * r / 2.0));
    return 255.0 * (1.0 - sin(pi * z / 2.0) + ML_ALPHA * (1.0 + rho_r)) / (2.0 * (1.0 + ML_ALPHA));
}

/* 255 at the centre, falling linearly to 0 at 0.45 of the side. */
static double sphere(const double p[3], const int dims[3])
{
    double r2 = 0;
    for (int a = 0; a < 3; a++) {
        double c = (dims[a] - 1) / 2.0;
        r2 += (p[a] - c) * (p[a] - c);
    }
    double r = sqrt(r2), radius = SPHERE_RADIUS * dims[0];
    return r < radius ? 255.0 * (1.0 - r / radius) : 0.0;
}

static double cube(const double p[3], const int dims[3])
{
    (void)p, (void)dims;
    return 64.0;
}

truth_phantom_fn_t truth_phantom_fn(const char *spec)
{
    static const struct { const char *name; truth_phantom_fn_t fn; } known[] = {
        {"phantom:marschner-lobb:", marschner_lobb}, {"phantom:sphere:", sphere}, {"phantom:cube:", cube}};
    for (size_t i = 0; spec && i < sizeof known / sizeof known[0]; i++)
        if (strncmp(spec, known[i].name, strlen(known[i].name)) == 0)
            return known[i].fn;
    return NULL;
}

static const char *const filter_names[] = {"trilinear", "catmull-rom", "bspline", "analytic", "smooth"};

int truth_filter_parse(const char *text, truth_filter_t *filter)
{
    for (int i = 0; text && i <= TRUTH_FILTER_SMOOTH; i++)
        if (strcmp(text, filter_names[i]) == 0) {
            *filter = (truth_filter_t)i;
            return 0;
        }
    return -1;
}

const char *truth_filter_name(truth_filter_t filter)
{
    return filter >= TRUTH_FILTER_TRILINEAR && filter <= TRUTH_FILTER_SMOOTH ? filter_names[filter] : "?";
}

/* ---- the field ------------------------------------------------------------------------------------------- */

/* Sample i of axis a's line through the volume, with linearly extrapolated ghosts outside (2 v_0 - v_1). */
static double ghost(const uint8_t *line, ptrdiff_t stride, int n, int i)
{
    if (i < 0)
        return 2.0 * line[0] - line[stride];
    if (i >= n)
        return 2.0 * line[stride * (n - 1)] - line[stride * (n - 2)];
    return line[stride * i];
}

/* The voxel at (i, j, k), each index possibly one outside the volume: ghosts extrapolated one axis at a time
 * (the extrapolation of an extrapolation at a corner, which keeps linear data linear). */
static double voxel(const ref_volume_t *vol, int i, int j, int k)
{
    const int *n = vol->dims;
    if (k < 0)
        return 2.0 * voxel(vol, i, j, 0) - voxel(vol, i, j, 1);
    if (k >= n[2])
        return 2.0 * voxel(vol, i, j, n[2] - 1) - voxel(vol, i, j, n[2] - 2);
    if (j < 0)
        return 2.0 * voxel(vol, i, 0, k) - voxel(vol, i, 1, k);
    if (j >= n[1])
        return 2.0 * voxel(vol, i, n[1] - 1, k) - voxel(vol, i, n[1] - 2, k);
    const uint8_t *line = vol->scalars + (size_t)n[0] * ((size_t)j + (size_t)n[1] * k);
    return ghost(line, 1, n[0], i);
}

static void weights(truth_filter_t filter, double t, double w[4])
{
    double t2 = t * t, t3 = t2 * t;
    if (filter == TRUTH_FILTER_CATMULL_ROM) {
        w[0] = (-t3 + 2 * t2 - t) / 2;
        w[1] = (3 * t3 - 5 * t2 + 2) / 2;
        w[2] = (-3 * t3 + 4 * t2 + t) / 2;
        w[3] = (t3 - t2) / 2;
    } else {
        double u = 1 - t;
        w[0] = u * u * u / 6;
        w[1] = (3 * t3 - 6 * t2 + 4) / 6;
        w[2] = (-3 * t3 + 3 * t2 + 3 * t + 1) / 6;
        w[3] = t3 / 6;
    }
}

double truth_field_sample(const truth_field_t *f, const double p[3])
{
    const ref_volume_t *vol = f->vol;
    double q[3];
    for (int a = 0; a < 3; a++)
        q[a] = fmin(fmax(p[a], 0.0), vol->dims[a] - 1.0);
    double s;
    if (f->filter == TRUTH_FILTER_ANALYTIC) {
        s = (f->analytic(q, vol->dims) - f->win_lo) * 255.0 / (f->win_hi - f->win_lo);
    } else if (f->filter == TRUTH_FILTER_TRILINEAR) {
        s = truth_sample(vol, q);
    } else {
        int base[3];
        double w[3][4];
        for (int a = 0; a < 3; a++) {
            base[a] = (int)q[a] < vol->dims[a] - 2 ? (int)q[a] : vol->dims[a] - 2;
            weights(f->filter, q[a] - base[a], w[a]);
        }
        const int *n = vol->dims;
        const int inside = base[0] >= 1 && base[0] + 2 < n[0] && base[1] >= 1 && base[1] + 2 < n[1] &&
                           base[2] >= 1 && base[2] + 2 < n[2];
        s = 0;
        for (int k = 0; k < 4; k++) {
            double sy = 0;
            for (int j = 0; j < 4; j++) {
                double sx = 0;
                if (inside) {
                    const uint8_t *v = vol->scalars + (size_t)(base[0] - 1) +
                                       (size_t)n[0] * ((size_t)(base[1] - 1 + j) + (size_t)n[1] * (base[2] - 1 + k));
                    sx = w[0][0] * v[0] + w[0][1] * v[1] + w[0][2] * v[2] + w[0][3] * v[3];
                } else {
                    for (int i = 0; i < 4; i++)
                        sx += w[0][i] * voxel(vol, base[0] - 1 + i, base[1] - 1 + j, base[2] - 1 + k);
                }
                sy += w[1][j] * sx;
            }
            s += w[2][k] * sy;
        }
    }
    return fmin(fmax(s, 0.0), 255.0);
}

int truth_field_init(truth_field_t *f, const ref_volume_t *vol, truth_filter_t filter, const char *phantom_spec,
                     double win_lo, double win_hi)
{
    if (!f)
        return -1;
    memset(f, 0, sizeof *f);
    double spmin;
    if (!vol || !vol->scalars || ref_volume_check(vol, &spmin) || filter < TRUTH_FILTER_TRILINEAR ||
        filter > TRUTH_FILTER_SMOOTH || !(win_hi != win_lo))
        return -1;
    truth_phantom_fn_t fn = truth_phantom_fn(phantom_spec);
    if (filter == TRUTH_FILTER_SMOOTH)
        filter = fn ? TRUTH_FILTER_ANALYTIC : TRUTH_FILTER_CATMULL_ROM;
    if (filter == TRUTH_FILTER_ANALYTIC && !fn)
        return -2;
    f->filter = filter;
    f->vol = vol;
    f->analytic = fn;
    f->win_lo = win_lo;
    f->win_hi = win_hi;
    if (filter != TRUTH_FILTER_CATMULL_ROM && filter != TRUTH_FILTER_BSPLINE)
        return 0;
    /* bounds per cell: the range of the 4^3 samples (ghosts included) by three separable passes */
    const int *n = vol->dims;
    const size_t count = (size_t)n[0] * n[1] * n[2];
    double *lo = malloc(sizeof(double) * count), *hi = malloc(sizeof(double) * count);
    size_t cells = (size_t)(n[0] - 1) * (n[1] - 1) * (n[2] - 1);
    f->cell_lo = malloc(cells);
    f->cell_hi = malloc(cells);
    if (!lo || !hi || !f->cell_lo || !f->cell_hi) {
        free(lo), free(hi);
        truth_field_free(f);
        return -1;
    }
    for (size_t i = 0; i < count; i++)
        lo[i] = hi[i] = vol->scalars[i];
    /* axis by axis, each line into a scratch copy: out[i] = extremes over in[i - 1 .. i + 2] with ghosts */
    int len[3] = {n[0], n[1], n[2]};
    size_t stride[3] = {1, (size_t)n[0], (size_t)n[0] * n[1]};
    int maxn = n[0] > n[1] ? n[0] : n[1];
    maxn = maxn > n[2] ? maxn : n[2];
    double *ll = malloc(sizeof(double) * 2 * maxn);
    if (!ll) {
        free(lo), free(hi);
        truth_field_free(f);
        return -1;
    }
    double *lh = ll + maxn;
    for (int a = 0; a < 3; a++) {
        int b = (a + 1) % 3, c = (a + 2) % 3;
        for (int y = 0; y < len[c]; y++)
            for (int x = 0; x < len[b]; x++) {
                size_t start = stride[b] * x + stride[c] * y;
                for (int i = 0; i < len[a]; i++)
                    ll[i] = lo[start + stride[a] * i], lh[i] = hi[start + stride[a] * i];
                for (int i = 0; i + 1 < len[a]; i++) {
                    double l = INFINITY, h = -INFINITY;
                    for (int m = -1; m <= 2; m++) {
                        int v = i + m;
                        double gl, gh;
                        if (v < 0 || v >= len[a]) { /* a ghost 2 v_e - v_next lies within 2 [e] - [next] */
                            int e = v < 0 ? 0 : len[a] - 1, nx = v < 0 ? 1 : len[a] - 2;
                            gl = 2.0 * ll[e] - lh[nx];
                            gh = 2.0 * lh[e] - ll[nx];
                        } else {
                            gl = ll[v], gh = lh[v];
                        }
                        l = fmin(l, gl), h = fmax(h, gh);
                    }
                    lo[start + stride[a] * i] = l, hi[start + stride[a] * i] = h;
                }
                /* the line's last sample is no cell's: its stale value only reaches lines no cell reads */
            }
    }
    free(ll);
    const double widen = filter == TRUTH_FILTER_CATMULL_ROM ? CR_NEG : 0.0;
    size_t cell = 0;
    for (int k = 0; k + 1 < n[2]; k++)
        for (int j = 0; j + 1 < n[1]; j++)
            for (int i = 0; i + 1 < n[0]; i++, cell++) {
                size_t at = (size_t)i + stride[1] * j + stride[2] * k;
                double margin = widen * (hi[at] - lo[at]);
                double l = floor(fmax(lo[at] - margin, 0.0)), h = ceil(fmin(hi[at] + margin, 255.0));
                f->cell_lo[cell] = (uint8_t)(l > 255 ? 255 : l);
                f->cell_hi[cell] = (uint8_t)(h < 0 ? 0 : h);
            }
    free(lo), free(hi);
    return 0;
}

void truth_field_free(truth_field_t *f)
{
    if (!f)
        return;
    free(f->cell_lo), free(f->cell_hi);
    f->cell_lo = f->cell_hi = NULL;
}

/* ---- the walk -------------------------------------------------------------------------------------------- */

void truth_trace_field(const truth_tf_t *tf, const truth_camera_t *cam, const truth_opts_t *opts, double px,
                       double py, truth_acc_t *acc)
{
    const truth_field_t *f = opts->field;
    const ref_volume_t *vol = f->vol;
    /* the trilinear walk's cells: they give the cubic filters their bounds and every filter its pace */
    truth_walk_t w;
    if (!truth_walk_pixel(&w, cam, vol->dims, px, py, acc))
        return;
    double t0, t1;
    while (acc->T > 1.0 - TRUTH_STOP_OPACITY && truth_walk_next(&w, &t0, &t1))
        cell_smooth(f, tf, opts, w.piece, w.o, w.d, t0, t1, acc);
}

/* The tolerance on the scalar's distance from its chord where the scalar spans [lo, hi] (truth_ray.c's rule). */
static double tolerance(const truth_tf_t *tf, const truth_opts_t *opts, double lo, double hi)
{
    int l = (int)floor(fmax(lo, 0.0)), h = (int)ceil(fmin(hi, 255.0));
    double steep = truth_tf_steepness(tf, l, h > l ? h : l), tol = opts->scalar_tol;
    if (steep < opts->steep)
        tol = fmax(tol, steep > 0 ? fmin(TRUTH_LOOSEST_TOL, tol * opts->steep / steep) : TRUTH_LOOSEST_TOL);
    return tol;
}

static int clear_between(const truth_tf_t *tf, double a, double b)
{
    int lo = (int)floor(fmax(fmin(a, b), 0.0)), hi = (int)ceil(fmin(fmax(a, b), 255.0));
    return truth_tf_clear(tf, lo, hi);
}

/* The piece of the ray from point p0 (scalar s0) to p0 + dp (scalar s1), world length h: halved until the
 * middle's scalar is within 4 tol of the chord (two linear pieces are then within about tol of the curve). */
static void piece(const truth_field_t *f, const truth_tf_t *tf, const truth_opts_t *opts, const double p0[3],
                  const double dp[3], double s0, double s1, double h, int depth, truth_acc_t *acc)
{
    if (acc->T <= 1.0 - TRUTH_STOP_OPACITY)
        return;
    double pm[3] = {p0[0] + dp[0] / 2, p0[1] + dp[1] / 2, p0[2] + dp[2] / 2}, half[3] = {dp[0] / 2, dp[1] / 2,
                                                                                          dp[2] / 2};
    double sm = truth_field_sample(f, pm);
    double lo = fmin(sm, fmin(s0, s1)), hi = fmax(sm, fmax(s0, s1));
    double dev = fabs(sm - (s0 + s1) / 2);
    if (depth < MAX_DEPTH && dev > 4 * tolerance(tf, opts, lo - dev, hi + dev)) {
        piece(f, tf, opts, p0, half, s0, sm, h / 2, depth + 1, acc);
        piece(f, tf, opts, pm, half, sm, s1, h / 2, depth + 1, acc);
        return;
    }
    if (!clear_between(tf, s0, sm))
        truth_tf_composite(tf, s0, sm, h / 2, acc);
    if (!clear_between(tf, sm, s1))
        truth_tf_composite(tf, sm, s1, h / 2, acc);
}

static void cell_smooth(const truth_field_t *f, const truth_tf_t *tf, const truth_opts_t *opts, const int cell[3],
                        const double o[3], const double d[3], double t0, double t1, truth_acc_t *acc)
{
    const int *n = f->vol->dims;
    if (f->cell_lo) {
        size_t at = (size_t)cell[0] + (size_t)(n[0] - 1) * ((size_t)cell[1] + (size_t)(n[1] - 1) * cell[2]);
        if (truth_tf_clear(tf, f->cell_lo[at], f->cell_hi[at]))
            return;
    }
    double p0[3], dp[3], len2 = 0;
    for (int a = 0; a < 3; a++) {
        p0[a] = o[a] + t0 * d[a];
        dp[a] = (t1 - t0) * d[a];
        len2 += dp[a] * dp[a];
    }
    double length = t1 - t0, steps = ceil(fmax(length, sqrt(len2)) / opts->max_step);
    int m = steps < 1 ? 1 : steps > MAX_SUBSTEPS ? MAX_SUBSTEPS : (int)steps;
    double step[3] = {dp[0] / m, dp[1] / m, dp[2] / m}, s_prev = truth_field_sample(f, p0);
    for (int k = 0; k < m && acc->T > 1.0 - TRUTH_STOP_OPACITY; k++) {
        double pa[3] = {p0[0] + k * step[0], p0[1] + k * step[1], p0[2] + k * step[2]};
        double pb[3] = {pa[0] + step[0], pa[1] + step[1], pa[2] + step[2]};
        double s = truth_field_sample(f, pb);
        piece(f, tf, opts, pa, step, s_prev, s, length / m, 0, acc);
        s_prev = s;
    }
}
