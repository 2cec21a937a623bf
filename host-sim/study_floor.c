/* SPDX-License-Identifier: MIT */
/*
 * study_floor.c: how much of shear-warp's distance from the ground truth is the slab integration, and how much
 * the intermediate image's resolution (one ray per voxel column, or R x R: docs/algorithm.md section 4b) and the
 * warp. For one scene, at the R and table size asked for:
 *
 *   - the floor: the truth's own exact ray integrals taken at the intermediate pixels and warped as shear-warp
 *     warps them, against the truth's image: the best any slab integration can do at this resolution;
 *   - per mode, the double reference's intermediate image against those exact integrals at the same rays (the
 *     integration error alone, in 8-bit levels of the premultiplied colour over black), and the reference's
 *     final image against the truth, each with section 4's side-face rule and with partial slabs
 *     (ref_params_t.partial_slabs).
 */
#include <math.h>
#include <stdlib.h>

#include "study.h"
#include "truth/truth.h"

static double psnr(double squared_error, double values)
{
    return squared_error > 0 ? 10 * log10(255.0 * 255.0 * values / squared_error) : 99;
}

static uint8_t level(double x)
{
    return (uint8_t)floor(255 * fmin(fmax(x, 0), 1) + 0.5);
}

/* Exact integrals at the intermediate pixels, a row at a time (truth_rows). */
typedef struct exact_job {
    const ref_volume_t *vol;
    const truth_tf_t *tf;
    const truth_camera_t *cam;
    const truth_opts_t *opts;
    const ref_factor_t *f;
    int rays, w;
    double *exact; /* R, G, B, A per pixel */
} exact_job_t;

/* The truth's rays through intermediate pixels (U, V), at intermediate points (u, v) = (U / R, V / R): invert the
 * warp's map u = u0 + du_dx x + du_dy y to find the final-image point each one passes through. */
static void exact_row(const void *ctx, int V)
{
    const exact_job_t *j = ctx;
    const ref_factor_t *f = j->f;
    const double det = f->du_dx * f->dv_dy - f->du_dy * f->dv_dx;
    for (int U = 0; U < j->w; U++) {
        double a = (double)U / j->rays - f->u0, b = (double)V / j->rays - f->v0;
        truth_acc_t acc;
        truth_trace(j->vol, j->tf, j->cam, j->opts, (a * f->dv_dy - b * f->du_dy) / det,
                    (f->du_dx * b - f->dv_dx * a) / det, &acc);
        double *p = j->exact + 4 * ((size_t)V * j->w + U);
        p[0] = acc.C[0], p[1] = acc.C[1], p[2] = acc.C[2], p[3] = 1 - acc.T;
    }
}

/* Warp an intermediate image of R rays per voxel column (R, G, B, A doubles) and compare the result with the
 * truth's image. */
static double warped_against_truth(const ref_factor_t *f, int rays, const double *inter, const double background[3],
                                   const uint8_t *truth, size_t pixels, double *rgb, uint8_t *bytes)
{
    ref_warp_rays(f, rays, inter, background, rgb);
    for (size_t n = 0; n < 3 * pixels; n++)
        bytes[n] = level(rgb[n]);
    sim_diff_t d;
    sim_diff(bytes, truth, pixels, &d);
    return d.psnr_db;
}

vfp_status_t study_floor(study_t *st, int scene, int rays, int table_size, study_floor_t *out, char *err, size_t errlen)
{
    const uint8_t *truth = study_truth(st, scene, err, errlen);
    if (!truth)
        return VFP_ERR;
    const sim_scene_t *s = &st->scenes[scene].scene;
    sim_ref_inputs_t in;
    if (sim_ref_inputs(s, &in)) {
        snprintf(err, errlen, "%s: out of memory for the reference's inputs", st->scenes[scene].label);
        return VFP_ERR;
    }
    ref_factor_t f;
    truth_camera_t cam;
    truth_tf_t *tf = malloc(sizeof *tf);
    const truth_opts_t opts = TRUTH_OPTS_DEFAULT;
    const size_t pixels = (size_t)s->width * s->height;
    const int N = table_size > 0 ? table_size : (int)s->params.table_size, R = rays > 0 ? rays : (int)s->params.rays;
    vfp_status_t status = VFP_ERR;
    int W = 0, H = 0;
    double *exact = NULL, *inter = NULL, *table = NULL, *rgb = malloc(sizeof(double) * 3 * pixels);
    uint8_t *bytes = malloc(3 * pixels);
    if (!tf || !rgb || !bytes || ref_factor(&in.vol, &in.view, (int)s->width, (int)s->height, &f) ||
        ref_rays_size(&f, R, &W, &H) || truth_camera(&in.vol, &in.view, (int)s->width, (int)s->height, &cam) ||
        truth_tf_init(tf, in.tf, in.npoints)) {
        snprintf(err, errlen, "%s: cannot set up the floor's rays", st->scenes[scene].label);
        goto done;
    }
    const size_t ipx = (size_t)W * H;
    exact = calloc(4 * ipx, sizeof(double));
    inter = malloc(sizeof(double) * 4 * ipx);
    table = malloc(sizeof(double) * 4 * (size_t)N * N);
    if (!exact || !inter || !table) {
        snprintf(err, errlen, "%s: out of memory for the floor", st->scenes[scene].label);
        goto done;
    }

    /* The truth's rays through the intermediate pixels (U, V), on the study's threads (at R = 16 there are 900,000
     * of them, three and a half times the final image's pixels). */
    const exact_job_t job = {&in.vol, tf, &cam, &opts, &f, R, W, exact};
    truth_rows(H, st->threads, exact_row, &job);
    out->rays = R;
    out->table_size = N;
    out->int_w = W;
    out->int_h = H;
    out->exact_db = warped_against_truth(&f, R, exact, in.background, truth, pixels, rgb, bytes);

    for (int mode = 0; mode < STUDY_FLOOR_MODES; mode++) {
        int fail = mode == REF_MODE_PREINT1 ? ref_preint_table(in.tf, in.npoints, N, f.slab, table)
                                            : ref_point_table(in.tf, in.npoints, N, f.slab, table);
        for (int partial = 0; partial < 2 && !fail; partial++) {
            fail = ref_composite_rays(&in.vol, &f, (ref_mode_t)mode, REF_LOOKUP_NEAREST, N, table, NULL, partial, R,
                                      inter);
            if (fail)
                break;
            double se = 0;
            for (size_t n = 0; n < ipx; n++)
                for (int c = 0; c < 3; c++) {
                    double d = (double)level(exact[4 * n + c]) - (double)level(inter[4 * n + c]);
                    se += d * d;
                }
            out->integration_db[mode][partial] = psnr(se, 3.0 * ipx);
            out->truth_db[mode][partial] = warped_against_truth(&f, R, inter, in.background, truth, pixels, rgb,
                                                                bytes);
        }
        if (fail) {
            snprintf(err, errlen, "%s: the reference failed (mode %d)", st->scenes[scene].label, mode);
            goto done;
        }
    }
    out->done = 1;
    status = VFP_OK;
done:
    free(tf);
    free(rgb);
    free(bytes);
    free(exact);
    free(inter);
    free(table);
    sim_ref_inputs_free(&in);
    return status;
}
