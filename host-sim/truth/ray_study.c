/*
 * ray_study.c: El Hajjar et al. 2008's study of one ray. The trilinear signal along the ray against what
 * shear-warp reconstructs from its samples on the slices: order 0 (each sample held over its own segment,
 * centred, as point sampling composites it), order 1 (linear between samples), order 2 (a quadratic through
 * three samples per slab of two spacings), at spacing 1 and 2 slices. xi = the integral of |signal - recon|.
 */
#include "truth/truth.h"

#include <math.h>
#include <stdlib.h>

#define EDGE 1e-9        /* slack for a ray that starts or ends on a slice */
#define XI_PER_VOXEL 1024 /* trapezoid points per unit of k for xi (the |.| has kinks; fine steps make them cheap) */

typedef struct ray {
    const ref_volume_t *vol;
    double o[3], d[3], t_in, k_in, dk_dt;
} ray_t;

static double signal_at(const ray_t *r, double k);
static double recon(const double *samples, double k_a, int order, int h, int slabs2, double k);

int truth_study_ray(const ref_volume_t *vol, const ref_view_t *view, int out_w, int out_h, double px, double py,
                    int per_voxel, truth_study_t *st)
{
    truth_camera_t cam;
    ref_factor_t f;
    if (!st || per_voxel < 1 || per_voxel > 4096 || truth_camera(vol, view, out_w, out_h, &cam) ||
        ref_factor(vol, view, out_w, out_h, &f))
        return -1;
    *st = (truth_study_t){0};
    st->k_axis = f.k_axis;
    st->k_flip = f.k_flip;
    st->slab = f.slab;
    ray_t r = {vol, {0}, {0}, 0, 0, 0};
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
    int nsamples = 4 * slabs2 + 1;
    double *samples = malloc(sizeof(double) * nsamples);
    int rows = (int)floor((st->k_out - st->k_in) * per_voxel) + 2;
    st->table = malloc(sizeof(double) * 8 * rows);
    if (!samples || !st->table) {
        free(samples);
        truth_study_free(st);
        return -1;
    }
    for (int n = 0; n < nsamples; n++)
        samples[n] = signal_at(&r, first + n);

    for (int row = 0; row < rows; row++) {
        double k = row + 1 == rows ? st->k_out : st->k_in + (double)row / per_voxel, *out = st->table + 8 * row;
        int inside = k >= st->k_a - EDGE && k <= st->k_b + EDGE;
        out[0] = k;
        out[1] = signal_at(&r, k);
        for (int h = 1; h <= 2; h++)
            for (int order = 0; order < 3; order++)
                out[2 + 3 * (h - 1) + order] = inside ? recon(samples, st->k_a, order, h, slabs2, k) : NAN;
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
    free(samples);
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
    return truth_sample(r->vol, p);
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
