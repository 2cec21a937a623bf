/* SPDX-License-Identifier: MIT */
/*
 * test_order2_accuracy.c: preint2 (docs/algorithm.md, section 8) of the fixed-point core against the double
 * reference on the shared volumes: engine, brainsmall, neghip, cthead and headsq, at 256x256, views 30,20, 45,0 and
 * 135,70, the default 64^3 order-2 table; unlit with the smooth ramp and with a transfer function that suits the
 * volume (sharp ones included), and lit (section 8's lighting: Blinn-Phong, the default headlight) with that one:
 * PSNR >= 50 dB and no channel of any pixel more than 2 of 255 apart. The volumes come from $VOLFIX_DATA (default
 * ../shared/data). (A light from the side is left out: at 45,0 normals exactly side-on to the view, which section
 * 7's two-sided lighting turns on the sign of a zero, light differently in the core and the reference, in preint1
 * as much as here: a light at 40,25 put preint1's cthead 46 levels apart.)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "frame_check.h"

static const struct {
    const char *file, *preset;
} volumes[] = {
    {"engine.nhdr", "ct-bone"},      {"brainsmall.nhdr", "mr-brain"}, {"neghip.nhdr", "sharp"},
    {"cthead.nhdr", "sharp"}, {"headsq.nhdr", "ct-skin-bone"},
};
static const double views[][2] = {{30, 20}, {45, 0}, {135, 70}};

int main(void)
{
    const char *data = getenv("VOLFIX_DATA") ? getenv("VOLFIX_DATA") : "../shared/data";
    struct stat st;
    if (stat(data, &st) != 0) {
        printf("not ok - order2_accuracy/shared volumes: no data at %s: set VOLFIX_DATA to the folder of sample "
               "volumes\n", data);
        return 1;
    }
    int failures = 0;
    double worst_psnr = 1e9;
    int worst_max = 0;
    for (size_t v = 0; v < sizeof volumes / sizeof volumes[0]; v++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", data, volumes[v].file);
        const char *presets[3] = {"ramp", volumes[v].preset, volumes[v].preset};
        for (int p = 0; p < 3; p++)
            for (size_t w = 0; w < sizeof views / sizeof views[0]; w++) {
                char name[256];
                const int lit = p == 2;
                snprintf(name, sizeof name, "order2_accuracy/%s/%s%s/%g,%g", volumes[v].file, presets[p],
                         lit ? "/lit" : "", views[w][0], views[w][1]);
                sim_opts_t o;
                char *argv[] = {path, "--preset", (char *)presets[p], "--threads", "2", "--mode", "preint2",
                                "--size", "256x256", "--shade", lit ? "phong" : "none"};
                if (sim_parse(&o, 11, argv, SIM_OPT_SCENE, "") != VFP_OK) {
                    printf("not ok - %s: options refused\n", name);
                    failures++;
                    continue;
                }
                o.azimuth = views[w][0];
                o.elevation = views[w][1];
                sim_diff_t d;
                const int agree = frame_check(&o, name, &d);
                failures += agree != 1;
                if (agree < 0)
                    continue;
                worst_psnr = d.psnr_db < worst_psnr ? d.psnr_db : worst_psnr;
                worst_max = d.max_abs[3] > worst_max ? d.max_abs[3] : worst_max;
            }
    }
    printf("# preint2 against the reference: lowest PSNR %.1f dB, largest difference %d of 255\n", worst_psnr,
           worst_max);
    return failures ? 1 : 0;
}
