/* SPDX-License-Identifier: MIT */
/* cmd_compare.c: volfix-sim compare: the core's image against the double reference's (or the ground truth's),
 * pixel by pixel. */
#include <stdio.h>
#include <stdlib.h>

#include "commands.h"
#include "imgcmp.h"
#include "io/pngio.h"
#include "scene.h"

static const char usage_head[] =
    "usage: volfix-sim compare VOLUME [options] [-o CORE.png] [--diff DIFF.png] [--json]\n"
    "Render VOLUME with the fixed-point core and with the double-precision reference of the same algorithm\n"
    "(same inputs, same table size, same lookups) and report how far apart they are, in 8-bit levels per\n"
    "channel: PSNR, largest and mean absolute difference, and the share of pixels off by more than 1.\n"
    "RGB565 images are compared after expanding both to 8 bits.\n\n"
    "  --against W          reference (default: the same algorithm in double, so the difference is the\n"
    "                       fixed-point error) or truth (the ground-truth ray caster: the algorithm's own error\n"
    "                       as well)\n"
    "  --truth-filter F     the truth's reconstruction: trilinear (default), smooth (a phantom's own function\n"
    "                       where it has one, else catmull-rom), catmull-rom, bspline or analytic (unlit only)\n"
    "  -o FILE              also write the core's image as a PNG\n"
    "  --diff FILE          write the difference (largest channel, times 32) as a PNG\n"
    "  --json               print one JSON object: psnr_db, max_abs, mean_abs, over1_pct, and per channel\n";

int sim_cmd_compare(int argc, char **argv)
{
    sim_opts_t o;
    sim_scene_t scene;
    vfp_status_t status = sim_scene_command(&o, &scene, argc, argv,
                                            SIM_OPT_OUT | SIM_OPT_DIFF | SIM_OPT_JSON | SIM_OPT_AGAINST, usage_head);
    if (status)
        return vfp_exit_status(status);
    char err[VFP_ERR_LEN], about[512];
    vf_image_t core, ref;
    vf_factor_t factor;
    if (sim_render_core(&scene, &core, &factor, err, sizeof err)) {
        fprintf(stderr, "volfix-sim: %s\n", err);
        sim_scene_free(&scene);
        return VFP_EXIT_ERR;
    }
    if (o.truth ? sim_render_truth(&scene, &ref, err, sizeof err)
                : sim_render_reference(&scene, &factor, &ref, err, sizeof err)) {
        fprintf(stderr, "volfix-sim: %s\n", err);
        sim_image_free(&core);
        sim_scene_free(&scene);
        return VFP_EXIT_ERR;
    }
    size_t pixels = (size_t)scene.width * scene.height;
    uint8_t *a = malloc(pixels * 3), *b = malloc(pixels * 3);
    if (!a || !b) {
        fprintf(stderr, "volfix-sim: out of memory\n");
        status = VFP_ERR;
        goto done;
    }
    vfp_image_to_rgb(&core, a);
    vfp_image_to_rgb(&ref, b);
    sim_diff_t d;
    sim_diff(a, b, pixels, &d);
    sim_scene_describe(&scene, about, sizeof about);
    if (o.json) {
        printf("{\"scene\": \"%s\", \"against\": \"%s\", \"psnr_db\": %.3f, \"max_abs\": %d, \"mean_abs\": %.5f, "
               "\"over1_pct\": %.5f, \"max_abs_rgb\": [%d, %d, %d], \"mean_abs_rgb\": [%.5f, %.5f, %.5f]}\n",
               about, o.truth ? "truth" : "reference", d.psnr_db, d.max_abs[3], d.mean_abs[3], d.over1_pct,
               d.max_abs[0], d.max_abs[1], d.max_abs[2], d.mean_abs[0], d.mean_abs[1], d.mean_abs[2]);
    } else {
        printf("%s: core against the %s\n", about, o.truth ? "ground truth" : "double reference");
        printf("         red    green   blue    all\n");
        printf("max      %-7d %-7d %-7d %d\n", d.max_abs[0], d.max_abs[1], d.max_abs[2], d.max_abs[3]);
        printf("mean     %-7.4f %-7.4f %-7.4f %.4f\n", d.mean_abs[0], d.mean_abs[1], d.mean_abs[2], d.mean_abs[3]);
        printf("PSNR %.2f dB over all channels; %.4f%% of pixels off by more than 1\n", d.psnr_db, d.over1_pct);
    }
    if (o.out && vfp_png_write(o.out, &core, err, sizeof err)) {
        fprintf(stderr, "volfix-sim: %s\n", err);
        status = VFP_ERR;
    }
    if (o.diff) {
        uint8_t *pic = malloc(pixels * 3);
        if (!pic || (sim_diff_image(a, b, pixels, 32, pic), vfp_png_write_rgb(o.diff, pic, scene.width, scene.height,
                                                                            err, sizeof err))) {
            fprintf(stderr, "volfix-sim: %s\n", pic ? err : "out of memory");
            status = VFP_ERR;
        }
        free(pic);
    }
done:
    free(a);
    free(b);
    sim_image_free(&core);
    sim_image_free(&ref);
    sim_scene_free(&scene);
    return vfp_exit_status(status);
}
