/* SPDX-License-Identifier: MIT */
/*
 * ray_study.c: El Hajjar et al. 2008's study of one ray. The signal along the ray (trilinear, or a smooth field)
 * against what shear-warp reconstructs from its samples on the slices: order 0 (each sample held over its own
 * segment, centred, as point sampling composites it), order 1 (linear between samples), order 2 (a quadratic
 * through three samples per slab of two spacings), at spacing 1 and 2 slices; and preint2's own segments (its
 * slab pairing, clamp and last order-1 slab). xi = the integral of |signal - recon|.
 */
#include "truth/truth.h"

#include <math.h>
#include <stdlib.h>

#define EDGE 1e-9        /* slack for a ray that starts or ends on a slice */
#define XI_PER_VOXEL 1024 /* trapezoid points per unit of k for xi (the |.| has kinks; fine steps make them cheap) */

typedef struct ray {
    const ref_volume_t *vol;
    const truth_field_t *field; /* NULL: trilinear */
    double o[3], d[3], t_in, k_in, dk_dt;
} ray_t;

static double signal_at(const ray_t *r, double k);
static double recon(const double *samples, double k_a, int order, int h, int slabs2, double k);
static double preint2_recon(const double *rs, int first, int r_a, int r_b, int tail, double k);
static double slice_recon(const double *rs, int first, int last, int order, double k);

int truth_study_ray(const ref_volume_t *vol, const ref_view_t *view, int out_w, int out_h, double px, double py,
                    int per_voxel, truth_study_t *st)
{
    return truth_study_ray_field(vol, NULL, view, out_w, out_h, px, py, per_voxel, st);
}

int truth_study_ray_field(const ref_volume_t *vol, const truth_field_t *field, const ref_view_t *view, int out_w,
                          int out_h, double px, double py, int per_voxel, truth_study_t *st)
{
    truth_camera_t cam;
    ref_factor_t f;
    if (!st || per_voxel < 1 || per_voxel > 4096 || truth_camera(vol, view, out_w, out_h, &cam) ||
        ref_factor(vol, view, out_w, out_h, &f) || (field && field->vol != vol))
        return -1;
    if (field && field->filter == TRUTH_FILTER_TRILINEAR)
        field = NULL;
    *st = (truth_study_t){0};
    st->k_axis = f.k_axis;
    st->k_flip = f.k_flip;
    st->slab = f.slab;
    ray_t r = {vol, field, {0}, {0}, 0, 0, 0};
    double t_out;
    if (!truth_camera_ray(&cam, px, py, r.o, r.d, &r.t_in, &t_out))
        return 1;
    /* standard slice coordinate k grows along the ray: k = p_k, or n_k - 1 - p_k when the view looks along -k */
    int ka = f.k_axis;
    double p_in = r.o[ka] + r.t_in * r.d[ka], p_out = r.o[ka] + t_out * r.d[ka];
    r.k_in = f.k_flip ? vol->dims[ka] - 1 - p_in : p_in;
    r.dk_dt = fabs(r.d[ka]);
    st->k_in = r.k_in;
    st->k_out = f.k_flip ? vol->dims[ka] - 1 - p_out : p_out;

    /* samples on the slices the ray crosses; every reconstruction is defined on whole spacing-2 order-2 slabs */
    int first = (int)ceil(st->k_in - EDGE), last = (int)floor(st->k_out + EDGE), slabs2 = (last - first) / 4;
    if (slabs2 < 1)
        return 1;
    st->k_a = first;
    st->k_b = first + 4 * slabs2;
    /* preint2's slabs: from even standard slices; a last order-1 slab where the volume's last slice is odd */
    const int nk = vol->dims[ka], tail = (last & 1) && last == nk - 1;
    int r_a = first + (first & 1), r_b = tail ? last : last - (last & 1);
    if (r_b - r_a < 2) /* fewer than one whole slab: compare on the spacing-2 interval, where rs covers k */
        r_a = r_b = first;
    st->r_a = r_a;
    st->r_b = r_b;
    int nsamples = 4 * slabs2 + 1;
    double *samples = malloc(sizeof(double) * nsamples), *rs = malloc(sizeof(double) * (last - first + 1));
    int rows = (int)floor((st->k_out - st->k_in) * per_voxel) + 2;
    st->table = malloc(sizeof(double) * TRUTH_STUDY_COLS * rows);
    if (!samples || !rs || !st->table) {
        free(samples), free(rs);
        truth_study_free(st);
        return -1;
    }
    for (int n = 0; n < nsamples; n++)
        samples[n] = signal_at(&r, first + n);
    for (int n = 0; n <= last - first; n++)
        rs[n] = signal_at(&r, first + n);

    for (int row = 0; row < rows; row++) {
        double k = row + 1 == rows ? st->k_out : st->k_in + (double)row / per_voxel;
        double *out = st->table + TRUTH_STUDY_COLS * row;
        int inside = k >= st->k_a - EDGE && k <= st->k_b + EDGE;
        out[0] = k;
        out[1] = signal_at(&r, k);
        for (int h = 1; h <= 2; h++)
            for (int order = 0; order < 3; order++)
                out[2 + 3 * (h - 1) + order] = inside ? recon(samples, st->k_a, order, h, slabs2, k) : NAN;
        out[8] = r_b > r_a && k >= r_a - EDGE && k <= r_b + EDGE ? preint2_recon(rs, first, r_a, r_b, tail, k) : NAN;
    }
    st->rows = rows;

    /* xi by the trapezoid rule on a fine grid through every sample position */
    int steps = (int)((st->k_b - st->k_a) * XI_PER_VOXEL);
    for (int n = 0; n <= steps; n++) {
        double k = st->k_a + (double)n / XI_PER_VOXEL, w = (n == 0 || n == steps ? 0.5 : 1.0) / XI_PER_VOXEL;
        double s = signal_at(&r, k);
        for (int h = 1; h <= 2; h++)
            for (int order = 0; order < 3; order++)
                st->xi[order][h - 1] += w * fabs(s - recon(samples, st->k_a, order, h, slabs2, k));
    }
    steps = (int)((r_b - r_a) * XI_PER_VOXEL);
    for (int n = 0; n <= steps && r_b > r_a; n++) {
        double k = r_a + (double)n / XI_PER_VOXEL, w = (n == 0 || n == steps ? 0.5 : 1.0) / XI_PER_VOXEL;
        double s = signal_at(&r, k);
        st->xi_r[0] += w * fabs(s - slice_recon(rs, first, last, 0, k));
        st->xi_r[1] += w * fabs(s - slice_recon(rs, first, last, 1, k));
        st->xi_r[2] += w * fabs(s - preint2_recon(rs, first, r_a, r_b, tail, k));
    }
    free(samples), free(rs);
    return 0;
}

void truth_study_free(truth_study_t *st)
{
    free(st->table);
    st->table = NULL;
    st->rows = 0;
}

/* ---- static functions ---------------------------------------------------------------------------------- */

static double signal_at(const ray_t *r, double k)
{
    double t = r->t_in + (k - r->k_in) / r->dk_dt, p[3];
    for (int a = 0; a < 3; a++)
        p[a] = r->o[a] + t * r->d[a];
    return r->field ? truth_field_sample(r->field, p) : truth_sample(r->vol, p);
}

/* Point sampling (order 0, each slice's sample held over its own slab-length segment, centred) or preint1
 * (order 1) at k from the samples rs[n] of slices first + n .. last. */
static double slice_recon(const double *rs, int first, int last, int order, double k)
{
    double x = k - first;
    if (order == 0) {
        int n = (int)floor(x + 0.5);
        return rs[n < 0 ? 0 : n > last - first ? last - first : n];
    }
    int n = (int)floor(x);
    n = n < 0 ? 0 : n > last - first - 1 ? last - first - 1 : n;
    return rs[n] + (x - n) * (rs[n + 1] - rs[n]);
}

/* preint2's segment at k in [r_a, r_b] (docs/algorithm.md section 8): the quadratic of the slab from the even
 * slice at or below k, clamped to its three samples; the last slab of an odd count (tail) linear. */
static double preint2_recon(const double *rs, int first, int r_a, int r_b, int tail, double k)
{
    if (tail && k >= r_b - 1)
        return slice_recon(rs, first, r_b, 1, k);
    int whole_end = tail ? r_b - 1 : r_b, slab = (int)floor((k - r_a) / 2);
    slab = slab < 0 ? 0 : slab > (whole_end - r_a) / 2 - 1 ? (whole_end - r_a) / 2 - 1 : slab;
    int k0 = r_a + 2 * slab;
    double sf = rs[k0 - first], sm = rs[k0 + 1 - first], sb = rs[k0 + 2 - first];
    double t = (k - k0) / 2, A = 2 * sf - 4 * sm + 2 * sb, B = -3 * sf + 4 * sm - sb, p = (A * t + B) * t + sf;
    double lo = fmin(sf, fmin(sm, sb)), hi = fmax(sf, fmax(sm, sb));
    return fmin(fmax(p, lo), hi);
}

/* The reconstruction of the given order from the samples at spacing h (samples[n] is slice k_a + n) at k in
 * [k_a, k_a + 4 slabs2]. */
static double recon(const double *samples, double k_a, int order, int h, int slabs2, double k)
{
    double x = (k - k_a) / h; /* in spacings from the first sample */
    int last = 4 * slabs2 / h; /* the last sample's number, in spacings */
    if (order == 0) {
        int n = (int)floor(x + 0.5);
        return samples[h * (n < 0 ? 0 : n > last ? last : n)];
    }
    if (order == 1) {
        int n = (int)floor(x);
        n = n < 0 ? 0 : n > last - 1 ? last - 1 : n;
        double w = x - n;
        return (1 - w) * samples[h * n] + w * samples[h * (n + 1)];
    }
    /* El Hajjar et al.: P(t) = A t^2 + B t + C through sf, sm, sb over a slab of two spacings, t in [0, 1] */
    int slab = (int)floor(x / 2);
    slab = slab < 0 ? 0 : slab > last / 2 - 1 ? last / 2 - 1 : slab;
    double sf = samples[h * 2 * slab], sm = samples[h * (2 * slab + 1)], sb = samples[h * (2 * slab + 2)];
    double t = (x - 2 * slab) / 2, A = 2 * sf - 4 * sm + 2 * sb, B = -3 * sf + 4 * sm - sb;
    return (A * t + B) * t + sf;
}
