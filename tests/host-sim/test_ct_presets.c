/* SPDX-License-Identifier: MIT */
/*
 * test_ct_presets.c: the CT presets on uncalibrated CT (docs/defaults.md). cthead holds raw 12-bit values with
 * no calibration; an 8-bit export of it (each value scaled by 255 / its largest, as a viewer's export does) is
 * made here. Rendered from the front with the default window and ct-skin-bone, both materials must show: of the
 * head's pixels (those brighter than 24 levels, the three channels averaged), at least 5% must take the skin's
 * colour and at least 5% the bone's. The colours are told apart by blue over red: the preset's skin is
 * (0.9, 0.6, 0.45), 0.5, and its bone (1, 0.95, 0.85), 0.85; lighting scales the channels together, so the ratio
 * survives it: below 0.7 is skin, above is bone. ct-bone, bone alone, must show bone and no skin.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "frame_check.h"
#include "io/pngio.h"
#include "scene.h"

typedef struct shares {
    double skin, bone; /* of the head's pixels */
    long head;
} shares_t;

static int measure(const char *volume, char *const *extra, int nextra, const char *preset, shares_t *sh)
{
    char *argv[16] = {(char *)volume, "--preset", (char *)preset, "--view", "180,90", "--size", "256x256",
                      "--threads", "2"};
    int argc = 9;
    for (int i = 0; i < nextra; i++)
        argv[argc++] = extra[i];
    sim_opts_t o;
    if (sim_parse(&o, argc, argv, SIM_OPT_SCENE, ""))
        return -1;
    sim_scene_t s;
    vf_image_t img;
    vf_factor_t f;
    if (frame_core(&o, &s, &img, &f))
        return -1;
    uint8_t *rgb = malloc((size_t)img.width * img.height * 3);
    vfp_image_to_rgb(&img, rgb);
    long skin = 0, bone = 0, head = 0;
    for (size_t p = 0; p < (size_t)img.width * img.height; p++) {
        const uint8_t *c = rgb + 3 * p;
        if (c[0] + c[1] + c[2] <= 3 * 24)
            continue;
        head++;
        if (c[2] < 0.7 * c[0])
            skin++;
        else
            bone++;
    }
    printf("# %s %s window %d,%d: head %ld pixels, skin %.1f%%, bone %.1f%%\n", strrchr(volume, '/') + 1, preset,
           s.window.lo, s.window.hi, head, 100.0 * skin / (head ? head : 1), 100.0 * bone / (head ? head : 1));
    sh->skin = (double)skin / (head ? head : 1);
    sh->bone = (double)bone / (head ? head : 1);
    sh->head = head;
    free(rgb);
    sim_image_free(&img);
    sim_scene_free(&s);
    return 0;
}

static void check_both(const char *volume, char *const *extra, int nextra)
{
    shares_t sh;
    CHECK(measure(volume, extra, nextra, "ct-skin-bone", &sh) == 0);
    CHECK_MSG(sh.head > 256 * 256 / 10, "the head covers %ld pixels", sh.head);
    CHECK_MSG(sh.skin >= 0.05 && sh.bone >= 0.05, "ct-skin-bone: skin %.1f%%, bone %.1f%% of the head",
              100 * sh.skin, 100 * sh.bone);
    CHECK(measure(volume, extra, nextra, "ct-bone", &sh) == 0);
    CHECK_MSG(sh.bone >= 0.05 && sh.skin < 0.01, "ct-bone: skin %.1f%%, bone %.1f%%", 100 * sh.skin,
              100 * sh.bone);
}

static void cthead_raw_12bit(void)
{
    char path[4096];
    const char *volume = check_data("cthead.nhdr", path, sizeof path);
    CHECK_MSG(volume, "%s", path);
    check_both(volume, NULL, 0);
}

static void cthead_8bit_export(void)
{
    char path[4096], err[VFP_ERR_LEN];
    const char *volume = check_data("cthead.nhdr", path, sizeof path);
    CHECK_MSG(volume, "%s", path);
    vfp_volume_t vol;
    CHECK_MSG(vfp_volume_load(&vol, volume, NULL, err, sizeof err) == VFP_OK, "%s", err);
    size_t n = (size_t)vol.core.dims[0] * vol.core.dims[1] * vol.core.dims[2];
    uint8_t *out = malloc(n);
    const int16_t *in = vol.data;
    for (size_t i = 0; i < n; i++)
        out[i] = (uint8_t)((in[i] < 0 ? 0 : in[i]) * 255 / vol.raw_max);
    char raw[64], dims[64], spacing[128];
    snprintf(raw, sizeof raw, "/tmp/volfix-ct8-%d.raw", (int)getpid());
    snprintf(dims, sizeof dims, "%u,%u,%u", vol.core.dims[0], vol.core.dims[1], vol.core.dims[2]);
    snprintf(spacing, sizeof spacing, "%g,%g,%g", vol.spacing[0], vol.spacing[1], vol.spacing[2]);
    FILE *f = fopen(raw, "wb");
    CHECK(f && fwrite(out, 1, n, f) == n);
    fclose(f);
    free(out);
    vfp_volume_free(&vol);
    char *extra[] = {"--dims", dims, "--type", "uint8", "--spacing", spacing};
    check_both(raw, extra, 6);
    remove(raw);
}

CHECK_CASES({"cthead_raw_12bit", cthead_raw_12bit}, {"cthead_8bit_export", cthead_8bit_export});
CHECK_RUN("ct_presets")
