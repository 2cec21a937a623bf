/* SPDX-License-Identifier: MIT */
/* cmd_render.c: volfix-sim render: one image, with the fixed-point core, the double reference or the truth. */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "io/pngio.h"
#include "scene.h"
#include "truth/truth.h"

static const char usage_head[] =
    "usage: volfix-sim render VOLUME [options] -o OUT.png | --hash\n"
    "Render one image of VOLUME with the fixed-point core (or, with --reference, with the double-precision\n"
    "reference of the same algorithm, or with --truth, with the ground-truth ray caster) and write it as PNG.\n\n"
    "  -o FILE              the PNG to write (- for standard output; then the summary goes to standard error)\n"
    "  --hash               print the frame's FNV-1a 64-bit hash over its pixel bytes (port/render/image.h), to\n"
    "                       compare frames across machines; with or without -o\n"
    "  --reference          use the double-precision reference renderer\n"
    "  --truth              use the ground-truth ray caster (trilinear, continuous transfer function, exact\n"
    "                       integration; --mode, --rays, --partial-slabs and the table options do not apply)\n"
    "  --truth-filter F     the truth's reconstruction: trilinear (default), smooth (a phantom's own function\n"
    "                       where it has one, else catmull-rom), catmull-rom, bspline or analytic (unlit only)\n";

int sim_cmd_render(int argc, char **argv)
{
    sim_opts_t o;
    sim_scene_t scene;
    vfp_status_t status =
        sim_scene_command(&o, &scene, argc, argv, SIM_OPT_OUT | SIM_OPT_REF | SIM_OPT_TRUTH | SIM_OPT_HASH, usage_head);
    if (status)
        return vfp_exit_status(status);
    char err[VFP_ERR_LEN], about[512];
    if (o.truth) { /* the truth has no intermediate image: --rays does not apply, nor the spacing's default */
        scene.params.rays = 1;
        scene.sampling.rays_given = 1;
    }
    vf_image_t img;
    status = o.reference ? sim_render_reference(&scene, NULL, &img, err, sizeof err)
             : o.truth   ? sim_render_truth(&scene, &img, err, sizeof err)
                         : sim_render_core(&scene, &img, NULL, err, sizeof err);
    uint64_t hash = 0;
    if (status == VFP_OK) {
        hash = vfp_image_hash(&img);
        if (o.out)
            status = vfp_png_write(o.out, &img, err, sizeof err);
        sim_image_free(&img);
    }
    if (status) {
        fprintf(stderr, "volfix-sim: %s\n", err);
    } else {
        sim_scene_describe(&scene, about, sizeof about);
        char truth[64];
        snprintf(truth, sizeof truth, " (ground truth%s%s)", o.truth_filter ? ", " : "",
                 o.truth_filter ? truth_filter_name((truth_filter_t)o.truth_filter) : "");
        const char *which = o.reference ? " (reference)" : o.truth ? truth : "";
        /* with -o - the PNG is standard output, and the lines go to standard error */
        FILE *lines = o.out && strcmp(o.out, "-") == 0 ? stderr : stdout;
        if (o.hash)
            fprintf(lines, "%016llx %s%s\n", (unsigned long long)hash, about, which);
        if (o.out)
            fprintf(lines, "%s: %s%s\n", o.out, about, which);
    }
    sim_scene_free(&scene);
    return vfp_exit_status(status);
}
