/* SPDX-License-Identifier: MIT */
/* truth_ray.c: the truth's camera (section 3), trilinear reconstruction, and one ray walked cell by cell, lit or
 * not. */
#include "truth/truth.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAX_SUBSTEPS 4096 /* per cell: a bound for absurd tolerances, never reached by the defaults */

static void cell_segment(const ref_volume_t *vol, const truth_tf_t *tf, const truth_opts_t *opts,
                         const truth_lit_t *lit, const int cell[3], const double o[3], const double d[3], double t0,
                         double t1, truth_acc_t *acc);

int truth_camera(const ref_volume_t *vol, const ref_view_t *view, int out_w, int out_h, truth_camera_t *cam)
{
    double spmin, diag2 = 0;
    if (!vol || !vol->scalars || !view || !cam || out_w < 1 || out_h < 1 || !(view->zoom > 0) ||
        !isfinite(view->zoom) || ref_volume_check(vol, &spmin))
        return -1;
    for (int a = 0; a < 3; a++) {
        cam->dims[a] = vol->dims[a];
        cam->Sr[a] = vol->spacing[a] / spmin;
        cam->centre[a] = (vol->dims[a] - 1) / 2.0;
        diag2 += (cam->Sr[a] * (vol->dims[a] - 1)) * (cam->Sr[a] * (vol->dims[a] - 1));
    }
    cam->out_w = out_w;
    cam->out_h = out_h;
    cam->scale = view->zoom * (out_w < out_h ? out_w : out_h) / sqrt(diag2);
    /* R = Rz(roll) Rx(el) Ry(az), multiplied out */
    double sa, ca, se, ce, sr, cr;
    ref_sincos(view->azimuth, &sa, &ca);
    ref_sincos(view->elevation, &se, &ce);
    ref_sincos(view->roll, &sr, &cr);
    double X[3][3] = {{ca, 0, sa}, {se * sa, ce, -se * ca}, {-ce * sa, se, ce * ca}}; /* Rx(el) Ry(az) */
    for (int c = 0; c < 3; c++) {
        cam->R[0][c] = cr * X[0][c] - sr * X[1][c];
        cam->R[1][c] = sr * X[0][c] + cr * X[1][c];
        cam->R[2][c] = X[2][c];
    }
    return 0;
}

int truth_camera_ray(const truth_camera_t *cam, double px, double py, double origin[3], double dir[3],
                     double *t_in, double *t_out)
{
    double ex = (px - (cam->out_w - 1) / 2.0) / cam->scale, ey = (py - (cam->out_h - 1) / 2.0) / cam->scale;
    double lo = -INFINITY, hi = INFINITY;
    for (int a = 0; a < 3; a++) {
        /* p = c + Sr^-1 R^T (e_x, e_y, t) */
        origin[a] = cam->centre[a] + (cam->R[0][a] * ex + cam->R[1][a] * ey) / cam->Sr[a];
        dir[a] = cam->R[2][a] / cam->Sr[a];
    }
    for (int a = 0; a < 3; a++) {
        double top = cam->dims[a] - 1;
        if (dir[a] == 0) {
            if (origin[a] < 0 || origin[a] > top)
                lo = INFINITY; /* parallel to this axis' faces and outside them */
            continue;
        }
        double t0 = (0 - origin[a]) / dir[a], t1 = (top - origin[a]) / dir[a];
        lo = fmax(lo, fmin(t0, t1));
        hi = fmin(hi, fmax(t0, t1));
    }
    *t_in = lo;
    *t_out = hi;
    return lo <= hi && isfinite(lo);
}

double truth_sample(const ref_volume_t *vol, const double p[3])
{
    int base[3];
    double f[3];
    for (int a = 0; a < 3; a++) {
        double x = fmin(fmax(p[a], 0.0), vol->dims[a] - 1.0);
        base[a] = (int)x < vol->dims[a] - 2 ? (int)x : vol->dims[a] - 2;
        f[a] = x - base[a];
    }
    size_t sx = 1, sy = (size_t)vol->dims[0], sz = sy * vol->dims[1];
    const uint8_t *v = vol->scalars + base[0] + sy * base[1] + sz * base[2];
    double c00 = v[0] + f[0] * (v[sx] - v[0]), c10 = v[sy] + f[0] * (v[sy + sx] - v[sy]);
    double c01 = v[sz] + f[0] * (v[sz + sx] - v[sz]), c11 = v[sz + sy] + f[0] * (v[sz + sy + sx] - v[sz + sy]);
    double c0 = c00 + f[1] * (c10 - c00), c1 = c01 + f[1] * (c11 - c01);
    return c0 + f[2] * (c1 - c0);
}

int truth_lit_init(truth_lit_t *lit, const ref_volume_t *vol, const truth_camera_t *cam, const ref_lighting_t *l)
{
    if (!lit || !vol || !cam || !l || !l->raw || ref_lights_init(&lit->lights, l, cam->R))
        return -1;
    const int64_t most = ref_gradient_most(vol, l->raw, l->raw_type);
    if (most < 0)
        return -1;
    lit->most = (double)most / 16384.0; /* G / 2^14 is dv / dw (section 7) */
    return 0;
}

void truth_trace(const ref_volume_t *vol, const truth_tf_t *tf, const truth_camera_t *cam, const truth_opts_t *opts,
                 double px, double py, truth_acc_t *acc)
{
    truth_trace_lit(vol, tf, cam, opts, NULL, px, py, acc);
}

void truth_trace_lit(const ref_volume_t *vol, const truth_tf_t *tf, const truth_camera_t *cam,
                     const truth_opts_t *opts, const truth_lit_t *lit, double px, double py, truth_acc_t *acc)
{
    if (opts->field && opts->field->filter != TRUTH_FILTER_TRILINEAR) {
        truth_trace_field(tf, cam, opts, px, py, acc); /* unlit: truth_render_lit refuses a field with lighting */
        return;
    }
    truth_walk_t w;
    if (!truth_walk_pixel(&w, cam, vol->dims, px, py, acc))
        return;
    double t0, t1;
    while (acc->T > 1.0 - TRUTH_STOP_OPACITY && truth_walk_next(&w, &t0, &t1))
        cell_segment(vol, tf, opts, lit, w.piece, w.o, w.d, t0, t1, acc);
}

int truth_walk_pixel(truth_walk_t *w, const truth_camera_t *cam, const int dims[3], double px, double py,
                     truth_acc_t *acc)
{
    acc->T = 1;
    acc->C[0] = acc->C[1] = acc->C[2] = 0;
    double o[3], d[3], t_in, t_out;
    if (!truth_camera_ray(cam, px, py, o, d, &t_in, &t_out))
        return 0;
    truth_walk_start(w, dims, o, d, t_in, t_out);
    return 1;
}

void truth_walk_start(truth_walk_t *w, const int dims[3], const double origin[3], const double dir[3], double t_in,
                      double t_out)
{
    w->t = t_in, w->t_out = t_out, w->done = 0;
    for (int a = 0; a < 3; a++) {
        w->o[a] = origin[a], w->d[a] = dir[a];
        const double p = origin[a] + t_in * dir[a];
        w->dims[a] = dims[a];
        w->step[a] = dir[a] > 0 ? 1 : dir[a] < 0 ? -1 : 0;
        const double c = w->step[a] < 0 ? ceil(p) - 1 : floor(p);
        w->cell[a] = c < 0 ? 0 : c > dims[a] - 2 ? dims[a] - 2 : (int)c;
        w->t_next[a] = w->step[a] == 0 ? INFINITY : (w->cell[a] + (w->step[a] > 0) - origin[a]) / dir[a];
    }
}

int truth_walk_next(truth_walk_t *w, double *t0, double *t1)
{
    while (!w->done && w->t < w->t_out) {
        const int a = w->t_next[0] <= w->t_next[1] && w->t_next[0] <= w->t_next[2] ? 0
                      : w->t_next[1] <= w->t_next[2]                                ? 1
                                                                                      : 2;
        const double end = fmin(w->t_next[a], w->t_out), start = w->t;
        for (int b = 0; b < 3; b++)
            w->piece[b] = w->cell[b];
        if (end > start)
            w->t = end;
        if (w->t_next[a] >= w->t_out) {
            w->done = 1;
        } else {
            w->cell[a] += w->step[a];
            if (w->cell[a] < 0 || w->cell[a] > w->dims[a] - 2)
                w->done = 1;
            else
                w->t_next[a] = (w->cell[a] + (w->step[a] > 0) - w->o[a]) / w->d[a];
        }
        if (end > start) {
            *t0 = start, *t1 = end;
            return 1;
        }
    }
    return 0;
}

int truth_ray_ex(const ref_volume_t *vol, const ref_tf_point_t *tf, int npoints, const ref_view_t *view,
                 int out_w, int out_h, double px, double py, const truth_opts_t *opts, double rgba_out[4])
{
    truth_opts_t defaults = TRUTH_OPTS_DEFAULT;
    truth_camera_t cam;
    truth_tf_t *prepared = malloc(sizeof *prepared);
    if (!rgba_out || !prepared || truth_camera(vol, view, out_w, out_h, &cam) ||
        truth_tf_init(prepared, tf, npoints) ||
        (opts && !(opts->max_step > 0 && opts->scalar_tol > 0 && opts->steep >= 0))) {
        free(prepared);
        return -1;
    }
    truth_acc_t acc;
    truth_trace(vol, prepared, &cam, opts ? opts : &defaults, px, py, &acc);
    free(prepared);
    for (int c = 0; c < 3; c++)
        rgba_out[c] = acc.C[c];
    rgba_out[3] = 1.0 - acc.T;
    return 0;
}

int truth_ray(const ref_volume_t *vol, const ref_tf_point_t *tf, int npoints, const ref_view_t *view, int out_w,
              int out_h, double px, double py, double rgba_out[4])
{
    return truth_ray_ex(vol, tf, npoints, view, out_w, out_h, px, py, NULL, rgba_out);
}

/* ---- static functions ---------------------------------------------------------------------------------- */

/* The shade at cell-local point q (each in [0, 1]) from the raw field's trilinear coefficients k (k0, kx, ky, kz,
 * kxy, kxz, kyz, kxyz): the gradient in index units, then in world units (over Sr), normalised; its magnitude
 * mapped as section 7's 8-bit magnitudes for the ramp. */
static ref_shade_t shade_at(const truth_lit_t *lit, const double k[8], const double Sr[3], const double q[3])
{
    const double x = q[0], y = q[1], z = q[2];
    double g[3] = {k[1] + k[4] * y + k[5] * z + k[7] * y * z, k[2] + k[4] * x + k[6] * z + k[7] * x * z,
                   k[3] + k[5] * x + k[6] * y + k[7] * x * y};
    for (int a = 0; a < 3; a++)
        g[a] /= Sr[a];
    const double len = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    double n[3] = {0, 0, 0};
    for (int a = 0; len > 0 && a < 3; a++)
        n[a] = g[a] / len;
    ref_shade_t out;
    ref_shade_normal(&lit->lights, n, &out.d, &out.s);
    out.g = ref_gradient_factor(lit->lights.lighting, lit->most > 0 ? 255 * len / lit->most : 0);
    return out;
}

/* The ray's piece [t0, t1] inside one cell. Along it the trilinear scalar is a cubic b0 + b1 u + b2 u^2 +
 * b3 u^3 in u in [0, 1]; it is taken as linear across sub-steps of at most max_step voxels (index and world
 * length both) and short enough that the cubic's distance from its chord, at most |f''| / (8 n^2), stays within
 * scalar_tol. */
static void cell_segment(const ref_volume_t *vol, const truth_tf_t *tf, const truth_opts_t *opts,
                         const truth_lit_t *lit, const int cell[3], const double o[3], const double d[3], double t0,
                         double t1, truth_acc_t *acc)
{
    size_t sy = (size_t)vol->dims[0], sz = sy * vol->dims[1];
    const uint8_t *v = vol->scalars + cell[0] + sy * cell[1] + sz * cell[2];
    double c[8];
    int lo = 255, hi = 0;
    for (int n = 0; n < 8; n++) {
        int s = v[(n & 1) + sy * ((n >> 1) & 1) + sz * (n >> 2)];
        c[n] = s;
        lo = s < lo ? s : lo;
        hi = s > hi ? s : hi;
    }
    if (truth_tf_clear(tf, lo, hi))
        return; /* trilinear values stay within the corners' range */
    double q0[3], dq[3], len2 = 0;
    for (int a = 0; a < 3; a++) {
        q0[a] = fmin(fmax(o[a] + t0 * d[a] - cell[a], 0.0), 1.0);
        dq[a] = fmin(fmax(o[a] + t1 * d[a] - cell[a], 0.0), 1.0) - q0[a];
        len2 += dq[a] * dq[a];
    }
    /* f = k0 + kx x + ky y + kz z + kxy xy + kxz xz + kyz yz + kxyz xyz, corners c[x + 2y + 4z] */
    double k0 = c[0], kx = c[1] - c[0], ky = c[2] - c[0], kz = c[4] - c[0];
    double kxy = c[3] - c[1] - c[2] + c[0], kxz = c[5] - c[1] - c[4] + c[0], kyz = c[6] - c[2] - c[4] + c[0];
    double kxyz = c[7] - c[3] - c[5] - c[6] + c[1] + c[2] + c[4] - c[0];
    double x = q0[0], y = q0[1], z = q0[2], X = dq[0], Y = dq[1], Z = dq[2];
    double b0 = k0 + kx * x + ky * y + kz * z + kxy * x * y + kxz * x * z + kyz * y * z + kxyz * x * y * z;
    double b1 = kx * X + ky * Y + kz * Z + kxy * (x * Y + y * X) + kxz * (x * Z + z * X) + kyz * (y * Z + z * Y) +
                kxyz * (X * y * z + x * Y * z + x * y * Z);
    double b2 = kxy * X * Y + kxz * X * Z + kyz * Y * Z + kxyz * (X * Y * z + X * y * Z + x * Y * Z);
    double b3 = kxyz * X * Y * Z;

    double length = t1 - t0, curve = fmax(fabs(2 * b2), fabs(2 * b2 + 6 * b3));
    double steep = truth_tf_steepness(tf, lo, hi), tol = opts->scalar_tol;
    if (steep < opts->steep) /* a gentle transfer function: a larger scalar error makes the same difference */
        tol = fmax(tol, steep > 0 ? fmin(TRUTH_LOOSEST_TOL, tol * opts->steep / steep) : TRUTH_LOOSEST_TOL);
    double steps = ceil(fmax(length, sqrt(len2)) / opts->max_step);
    steps = fmax(steps, ceil(sqrt(curve / (8 * tol))));
    int n = steps < 1 ? 1 : steps > MAX_SUBSTEPS ? MAX_SUBSTEPS : (int)steps;
    double s_prev = b0, h = length / n;
    /* lit: the raw field's trilinear coefficients in this cell (for its gradient) and the relative spacing */
    double rk[8] = {0}, Sr[3] = {1, 1, 1};
    if (lit) {
        double r[8];
        for (int m = 0; m < 8; m++)
            r[m] = (double)ref_raw_voxel(lit->lights.lighting->raw, lit->lights.lighting->raw_type,
                          (size_t)(cell[0] + (m & 1)) + sy * (size_t)(cell[1] + ((m >> 1) & 1)) +
                              sz * (size_t)(cell[2] + (m >> 2)));
        rk[0] = r[0], rk[1] = r[1] - r[0], rk[2] = r[2] - r[0], rk[3] = r[4] - r[0];
        rk[4] = r[3] - r[1] - r[2] + r[0], rk[5] = r[5] - r[1] - r[4] + r[0], rk[6] = r[6] - r[2] - r[4] + r[0];
        rk[7] = r[7] - r[3] - r[5] - r[6] + r[1] + r[2] + r[4] - r[0];
        const double spmin = fmin(vol->spacing[0], fmin(vol->spacing[1], vol->spacing[2]));
        for (int a = 0; a < 3; a++)
            Sr[a] = vol->spacing[a] / spmin;
    }
    for (int k = 1; k <= n && acc->T > 1.0 - TRUTH_STOP_OPACITY; k++) {
        double u = (double)k / n, s = b0 + u * (b1 + u * (b2 + u * b3));
        /* most sub-steps of a cell near a narrow peak miss it: the integer range check is cheaper than the walk */
        int below = (int)floor(fmax(fmin(s, s_prev), 0.0)), above = (int)ceil(fmin(fmax(s, s_prev), 255.0));
        if (!truth_tf_clear(tf, below, above)) {
            if (lit) { /* the sub-step's shade at its middle */
                const double um = (k - 0.5) / n, q[3] = {x + um * X, y + um * Y, z + um * Z};
                truth_tf_composite_lit(tf, s_prev, s, h, shade_at(lit, rk, Sr, q), acc);
            } else {
                truth_tf_composite(tf, s_prev, s, h, acc);
            }
        }
        s_prev = s;
    }
}
