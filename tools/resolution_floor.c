/*
 * resolution_floor.c: how much of shear-warp's distance from the ground truth is the slab integration, and how
 * much the intermediate image's resolution (one ray per voxel column) and the warp. A measurement for issue 4,
 * not part of the build:
 *
 *   make && gcc -std=c11 -D_DEFAULT_SOURCE -O2 -Icore -Iport -Ihost-sim tools/resolution_floor.c \
 *       build/libvolfix-sim.a build/libvolfix-port.a build/libvolfix.a -lpng -lz -lpthread -lm \
 *       -o build/resolution-floor
 *   build/resolution-floor phantom:marschner-lobb:41 --preset sharp --view 30,20 --size 512x512
 *
 * It prints, against the truth's image (final pixels), the truth's own exact ray integrals taken at the
 * intermediate pixels and warped as shear-warp warps them: the best any slab integration can do at this
 * resolution. Then, per mode, the reference's intermediate image against those exact integrals at the same
 * rays (the integration error alone, in 8-bit levels of the premultiplied colour over black), with section 4's
 * side-face rule and with partial slabs (ref.h, ref_params_t.partial_slabs).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "imgcmp.h"
#include "pngio.h"
#include "scene.h"
#include "truth/truth.h"

static double psnr(double se, double values)
{
    return se > 0 ? 10 * log10(255.0 * 255.0 * values / se) : 99;
}

int main(int argc, char **argv)
{
    char err[512];
    sim_opts_t o;
    sim_scene_t s;
    sim_ref_inputs_t in;
    vf_image_t timg;
    if (sim_parse(&o, argc - 1, argv + 1, SIM_OPT_SCENE, "see tools/resolution_floor.c\n") ||
        sim_scene_load(&s, &o, err, sizeof err) || sim_render_truth(&s, &timg, err, sizeof err) ||
        sim_ref_inputs(&s, &in)) {
        fprintf(stderr, "resolution-floor: cannot load or render the scene\n");
        return 2;
    }
    size_t px = (size_t)s.width * s.height;
    uint8_t *t = malloc(px * 3), *r = malloc(px * 3);
    ref_factor_t f;
    truth_camera_t cam;
    truth_tf_t *tf = malloc(sizeof *tf);
    truth_opts_t opts = TRUTH_OPTS_DEFAULT;
    if (!t || !r || !tf || ref_factor(&in.vol, &in.view, (int)s.width, (int)s.height, &f) ||
        truth_camera(&in.vol, &in.view, (int)s.width, (int)s.height, &cam) || truth_tf_init(tf, in.tf, in.npoints))
        return 2;
    vfp_image_to_rgb(&timg, t);

    /* the truth's rays through the intermediate pixels: invert the warp map u = u0 + du_dx px + du_dy py */
    size_t ipx = (size_t)f.int_w * f.int_h;
    double *exact = calloc(4 * ipx, sizeof(double)), *rgb = malloc(sizeof(double) * 3 * px);
    double det = f.du_dx * f.dv_dy - f.du_dy * f.dv_dx;
    for (int v = 0; v < f.int_h; v++)
        for (int u = 0; u < f.int_w; u++) {
            double a = u - f.u0, b = v - f.v0;
            truth_acc_t acc;
            truth_trace(&in.vol, tf, &cam, &opts, (a * f.dv_dy - b * f.du_dy) / det, (f.du_dx * b - f.dv_dx * a) / det,
                        &acc);
            double *p = exact + 4 * ((size_t)v * f.int_w + u);
            p[0] = acc.C[0], p[1] = acc.C[1], p[2] = acc.C[2], p[3] = 1 - acc.T;
        }
    ref_warp(&f, exact, in.background, rgb);
    for (size_t n = 0; n < 3 * px; n++)
        r[n] = (uint8_t)floor(255 * fmin(fmax(rgb[n], 0), 1) + 0.5);
    sim_diff_t d;
    sim_diff(r, t, px, &d);
    printf("exact integrals at the %d x %d intermediate pixels, warped, against the truth: %.2f dB\n", f.int_w,
           f.int_h, d.psnr_db);

    /* the reference's intermediate image against the exact integrals (its own layout: inter is R, G, B, A) */
    static const char *const names[] = {"point", "preint1", "preclass"};
    int N = (int)s.params.table_size;
    double *table = malloc(sizeof(double) * 4 * (size_t)N * N), *inter = malloc(sizeof(double) * 4 * ipx);
    for (int mode = 0; mode < 3; mode++) {
        printf("%-8s intermediate image against the exact integrals:", names[mode]);
        for (int partial = 0; partial < 2; partial++) {
            if (mode == REF_MODE_PREINT1 ? ref_preint_table(in.tf, in.npoints, N, f.slab, table)
                                         : ref_point_table(in.tf, in.npoints, N, f.slab, table))
                return 2;
            ref_composite_sides(&in.vol, &f, (ref_mode_t)mode, REF_LOOKUP_NEAREST, N, table, NULL, partial, inter);
            double se = 0;
            for (size_t n = 0; n < ipx; n++)
                for (int c = 0; c < 3; c++) {
                    double a = floor(255 * fmin(exact[4 * n + c], 1) + 0.5), b = floor(255 * fmin(inter[4 * n + c], 1) + 0.5);
                    se += (a - b) * (a - b);
                }
            printf(" %s %.2f dB", partial ? "partial slabs" : "section 4", psnr(se, 3.0 * ipx));
            printf(partial ? "\n" : ",");
        }
    }
    return 0;
}
