/* SPDX-License-Identifier: MIT */
/* cmd_diff.c: volfix-sim diff: two PNG images compared pixel by pixel (a viewer's frame against volfix-sim
 * render, a board's screenshot against a reference), with the same measures as compare. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "imgcmp.h"
#include "io/numbers.h"
#include "io/pngio.h"
#include "io/volume.h"

static const char usage[] =
    "usage: volfix-sim diff A.png B.png [--max N] [--diff DIFF.png] [--json]\n"
    "Compare two images of one size pixel by pixel, in 8-bit levels per channel: PSNR, largest and mean\n"
    "absolute difference, and the share of pixels off by more than 1.\n\n"
    "  --max N      exit with status 1 when any channel differs by more than N levels (default: report only)\n"
    "  --diff FILE  write the difference (largest channel, times 32) as a PNG\n"
    "  --json       print one JSON object: psnr_db, max_abs, mean_abs, over1_pct\n";

int sim_cmd_diff(int argc, char **argv)
{
    const char *files[2] = {NULL, NULL}, *diff_png = NULL;
    int json = 0, max = -1, nfiles = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        long long n;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(usage, stdout);
            return VFP_EXIT_OK;
        } else if (strcmp(a, "--json") == 0) {
            json = 1;
        } else if ((strcmp(a, "--diff") == 0 || strcmp(a, "--max") == 0) && !v) {
            fprintf(stderr, "volfix-sim: diff: %s: missing value (see volfix-sim diff --help)\n", a);
            return VFP_EXIT_ERR;
        } else if ((strcmp(a, "--diff") == 0 || strcmp(a, "--max") == 0) && vfp_is_empty(v)) {
            fprintf(stderr, "volfix-sim: diff: %s '': an empty value (see volfix-sim diff --help)\n", a);
            return VFP_EXIT_ERR;
        } else if (strcmp(a, "--diff") == 0) {
            diff_png = argv[++i];
        } else if (strcmp(a, "--max") == 0) {
            if (!vfp_parse_integer(v, 0, 255, &n)) {
                fprintf(stderr, "volfix-sim: diff: --max %s: expected levels, an integer 0..255\n", v);
                return VFP_EXIT_ERR;
            }
            max = (int)n;
            i++;
        } else if (a[0] != '-' && a[0] && nfiles < 2) {
            files[nfiles++] = a;
        } else {
            fprintf(stderr, "volfix-sim: diff: unexpected '%s' (see volfix-sim diff --help)\n", a);
            return VFP_EXIT_ERR;
        }
    }
    if (nfiles != 2) {
        fprintf(stderr, "volfix-sim: diff: expected two PNG files (see volfix-sim diff --help)\n");
        return VFP_EXIT_ERR;
    }
    char err[VFP_ERR_LEN];
    if (diff_png && (strcmp(diff_png, "-") == 0 || vfp_png_check_output(diff_png, err, sizeof err))) {
        fprintf(stderr, "volfix-sim: diff: --diff %s\n", strcmp(diff_png, "-") == 0 ? "-: expected a file name (the "
                        "report is on standard output)" : err);
        return VFP_EXIT_ERR;
    }
    uint8_t *img[2] = {NULL, NULL};
    uint32_t w[2], h[2];
    int exit_status = VFP_EXIT_OK;
    for (int k = 0; k < 2 && !exit_status; k++)
        if (vfp_png_read_rgb(files[k], &img[k], &w[k], &h[k], err, sizeof err)) {
            fprintf(stderr, "volfix-sim: %s\n", err);
            exit_status = VFP_EXIT_ERR;
        }
    if (!exit_status && (w[0] != w[1] || h[0] != h[1])) {
        fprintf(stderr, "volfix-sim: %s is %ux%u but %s is %ux%u (expected one size)\n", files[0], w[0], h[0],
                files[1], w[1], h[1]);
        exit_status = VFP_EXIT_ERR;
    }
    if (!exit_status) {
        size_t pixels = (size_t)w[0] * h[0];
        sim_diff_t d;
        sim_diff(img[0], img[1], pixels, &d);
        if (json)
            printf("{\"a\": \"%s\", \"b\": \"%s\", \"psnr_db\": %.3f, \"max_abs\": %d, \"mean_abs\": %.5f, "
                   "\"over1_pct\": %.5f}\n",
                   files[0], files[1], d.psnr_db, d.max_abs[3], d.mean_abs[3], d.over1_pct);
        else
            printf("%s against %s: max %d, mean %.4f, PSNR %.2f dB, %.4f%% of pixels off by more than 1\n",
                   files[0], files[1], d.max_abs[3], d.mean_abs[3], d.psnr_db, d.over1_pct);
        if (diff_png) {
            uint8_t *pic = malloc(pixels * 3);
            if (!pic || (sim_diff_image(img[0], img[1], pixels, 32, pic),
                         vfp_png_write_rgb(diff_png, pic, w[0], h[0], err, sizeof err))) {
                fprintf(stderr, "volfix-sim: %s\n", pic ? err : "out of memory");
                exit_status = VFP_EXIT_ERR;
            }
            free(pic);
        }
        if (!exit_status && max >= 0 && d.max_abs[3] > max)
            exit_status = SIM_EXIT_DIFFERENT;
    }
    free(img[0]);
    free(img[1]);
    return exit_status;
}
