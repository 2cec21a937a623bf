/* SPDX-License-Identifier: MIT */
/*
 * test_accuracy.c: the fixed-point core against the double reference on the shared volumes: for engine,
 * brainsmall, neghip, headsq and cthead, at 512x512, five views, modes point and preint1, and two transfer
 * functions each (the smooth ramp and one that suits the volume, sharp ones included), PSNR >= 50 dB and no
 * channel of any pixel more than 2 of 255 apart. The volumes are in $VOLFIX_DATA: a missing one fails, naming it.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "frame_check.h"

static const struct {
    const char *file, *preset;
} volumes[] = {
    {"engine.nhdr", "ct-bone"},   {"brainsmall.nhdr", "mr-brain"}, {"neghip.nhdr", "sharp"},
    {"headsq.nhdr", "ct-skin-bone"}, {"cthead.nhdr", "sharp"},
};
static const double views[][2] = {{0, 0}, {30, 20}, {45, 0}, {60, -35}, {135, 70}};

int main(void)
{
    int failures = 0;
    for (size_t v = 0; v < sizeof volumes / sizeof volumes[0]; v++) {
        char path[1024];
        if (!check_data(volumes[v].file, path, sizeof path)) {
            printf("not ok - accuracy/%s: %s\n", volumes[v].file, path);
            failures++;
            continue;
        }
        const char *presets[2] = {"ramp", volumes[v].preset};
        for (int p = 0; p < 2; p++)
            for (size_t w = 0; w < sizeof views / sizeof views[0]; w++)
                for (int m = 0; m < 2; m++) {
                    char name[256];
                    snprintf(name, sizeof name, "accuracy/%s/%s/%s/%g,%g", volumes[v].file, presets[p],
                             m ? "preint1" : "point", views[w][0], views[w][1]);
                    sim_opts_t o;
                    /* unlit, as the CT presets are not by default: test_lighting.c has the lit frames */
                    char *argv[] = {path, "--preset", (char *)presets[p], "--threads", "2", "--shade", "none"};
                    sim_parse(&o, 7, argv, SIM_OPT_SCENE, "");
                    o.params.mode = m ? VF_MODE_PREINT1 : VF_MODE_POINT;
                    o.azimuth = views[w][0];
                    o.elevation = views[w][1];
                    sim_diff_t d;
                    failures += frame_check(&o, name, &d) != 1;
                }
    }
    return failures ? 1 : 0;
}
