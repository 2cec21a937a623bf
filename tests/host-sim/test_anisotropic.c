/* SPDX-License-Identifier: MIT */
/*
 * test_anisotropic.c: rays per voxel column chosen from the spacing (port/render/sampling.h, docs/defaults.md).
 * The rule at its threshold, --rays winning over it, the default frame equal to the one --rays 2 gives on headsq
 * (spacing 3.2, 3.2, 1.5) unlit, to --rays 1 lit and on an isotropic volume, and the reason for the rule: on
 * headsq the default frame is at least 3 dB closer to the ground truth than one ray per voxel column, from two
 * views.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "frame_check.h"
#include "render/sampling.h"

static uint32_t rays_for(double x, double y, double z, uint32_t given, int lit)
{
    vfp_volume_t vol;
    memset(&vol, 0, sizeof vol);
    vol.spacing[0] = x;
    vol.spacing[1] = y;
    vol.spacing[2] = z;
    return vfp_sampling_choose(&vol, given, lit).rays;
}

static void rule(void)
{
    CHECK(rays_for(1, 1, 1, 0, 0) == 1);
    CHECK(rays_for(1, 1, 1.99, 0, 0) == 1);
    CHECK(rays_for(1, 1, 2, 0, 0) == 2);           /* cthead: 1, 1, 2 */
    CHECK(rays_for(3.2, 3.2, 1.5, 0, 0) == 2);     /* headsq: the smallest spacing is the reference */
    CHECK(rays_for(0.4, 1, 1, 0, 0) == 2);
    CHECK(rays_for(3.2, 3.2, 1.5, 0, 1) == 1);     /* lit frames keep one ray */
    CHECK(rays_for(3.2, 3.2, 1.5, 1, 0) == 1);     /* --rays 1 wins */
    CHECK(rays_for(3.2, 3.2, 1.5, 2, 1) == 2);     /* and so does --rays 2 when lit */
    CHECK(rays_for(1, 1, 1, 4, 0) == 4);
    char text[128];
    vfp_volume_t vol;
    memset(&vol, 0, sizeof vol);
    vol.spacing[0] = vol.spacing[1] = 3.2;
    vol.spacing[2] = 1.5;
    vfp_sampling_t s = vfp_sampling_choose(&vol, 0, 0);
    vfp_sampling_text(&s, text, sizeof text);
    CHECK_MSG(strstr(text, "anisotropic spacing 2.13x: rays 2 by default"), "summary: '%s'", text);
    s = vfp_sampling_choose(&vol, 0, 1);
    vfp_sampling_text(&s, text, sizeof text);
    CHECK_MSG(strstr(text, "anisotropic spacing 2.13x: one ray, lit"), "lit summary: '%s'", text);
    s = vfp_sampling_choose(&vol, 1, 0);
    vfp_sampling_text(&s, text, sizeof text);
    CHECK_MSG(text[0] == 0, "summary with --rays given: '%s'", text);
}

/* Render VOLUME at 128x128 from VIEW with the extra options into an 8-bit RGB buffer (the caller frees it);
 * *rays receives the rays the scene took. NULL when it cannot be rendered. */
static uint8_t *render(const char *volume, const char *view, const char *rays_opt, int truth, uint32_t *rays,
                       const char *preset)
{
    char *argv[12] = {(char *)volume, "--size", "128x128", "--view", (char *)view, "--threads", "2", "--preset",
                      (char *)preset};
    int argc = 9;
    if (rays_opt) {
        argv[argc++] = "--rays";
        argv[argc++] = (char *)rays_opt;
    }
    sim_opts_t o;
    if (sim_parse(&o, argc, argv, SIM_OPT_SCENE, ""))
        return NULL;
    char err[VFP_ERR_LEN];
    sim_scene_t s;
    vf_image_t img;
    if (sim_scene_load(&s, &o, err, sizeof err) ||
        (truth ? sim_render_truth(&s, &img, err, sizeof err) : sim_render_core(&s, &img, NULL, err, sizeof err))) {
        printf("# %s\n", err);
        return NULL;
    }
    *rays = s.params.rays;
    uint8_t *rgb = malloc((size_t)img.width * img.height * 3);
    vfp_image_to_rgb(&img, rgb);
    sim_image_free(&img);
    sim_scene_free(&s);
    return rgb;
}

static int same(const uint8_t *a, const uint8_t *b)
{
    return a && b && memcmp(a, b, 128 * 128 * 3) == 0;
}

static void default_is_rays2_on_headsq(void)
{
    char path[4096];
    const char *volume = check_data("headsq.nhdr", path, sizeof path);
    CHECK_MSG(volume, "%s", path);
    uint32_t r_default = 0, r2 = 0, r1 = 0;
    uint8_t *d = render(volume, "30,20", NULL, 0, &r_default, "ramp");
    uint8_t *two = render(volume, "30,20", "2", 0, &r2, "ramp"), *one = render(volume, "30,20", "1", 0, &r1, "ramp");
    CHECK_MSG(r_default == 2 && r2 == 2 && r1 == 1, "rays: default %u, --rays 2 %u, --rays 1 %u", r_default, r2, r1);
    CHECK_MSG(same(d, two), "headsq's default frame equals --rays 2's");
    CHECK_MSG(d && one && !same(d, one), "and differs from --rays 1's");
    free(d);
    free(two);
    free(one);
    uint8_t *lit = render(volume, "30,20", NULL, 0, &r_default, "ct-skin-bone");
    CHECK_MSG(lit && r_default == 1, "a lit preset (ct-skin-bone) keeps one ray: %u", r_default);
    free(lit);
}

static void default_is_one_ray_on_isotropic(void)
{
    char path[4096];
    const char *volume = check_data("bucky.nhdr", path, sizeof path);
    CHECK_MSG(volume, "%s", path);
    uint32_t r_default = 0, r1 = 0;
    uint8_t *d = render(volume, "30,20", NULL, 0, &r_default, "ramp");
    uint8_t *one = render(volume, "30,20", "1", 0, &r1, "ramp");
    CHECK_MSG(r_default == 1, "bucky (spacing 1, 1, 1) took %u rays", r_default);
    CHECK_MSG(same(d, one), "bucky's default frame equals --rays 1's");
    free(d);
    free(one);
}

static double psnr(const uint8_t *a, const uint8_t *b)
{
    sim_diff_t diff;
    sim_diff(a, b, 128 * 128, &diff);
    return diff.psnr_db;
}

static void closer_to_the_truth(void)
{
    char path[4096];
    const char *volume = check_data("headsq.nhdr", path, sizeof path);
    CHECK_MSG(volume, "%s", path);
    const char *views[] = {"30,20", "90,0"};
    for (int v = 0; v < 2; v++) {
        uint32_t r;
        uint8_t *truth = render(volume, views[v], NULL, 1, &r, "ramp");
        uint8_t *d = render(volume, views[v], NULL, 0, &r, "ramp"), *one = render(volume, views[v], "1", 0, &r, "ramp");
        CHECK(truth && d && one);
        double p_default = psnr(truth, d), p_one = psnr(truth, one);
        printf("# headsq view %s, 128x128, against the truth: default %.2f dB, --rays 1 %.2f dB\n", views[v],
               p_default, p_one);
        CHECK_MSG(p_default >= p_one + 3, "view %s: default %.2f dB, --rays 1 %.2f dB", views[v], p_default, p_one);
        free(truth);
        free(d);
        free(one);
    }
}

CHECK_CASES({"rule", rule}, {"default_is_rays2_on_headsq", default_is_rays2_on_headsq},
            {"default_is_one_ray_on_isotropic", default_is_one_ray_on_isotropic},
            {"closer_to_the_truth", closer_to_the_truth});
CHECK_RUN("anisotropic")
