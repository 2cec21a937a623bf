/* SPDX-License-Identifier: MIT */
/*
 * test_order2_frames.c: preint2 frames of the fixed-point core against the double reference (docs/algorithm.md,
 * section 8) on phantoms and made-up volumes, every option preint2 takes: no channel more than 1 of 255 apart.
 *   - slab counts even and odd (the last slab of one slice), nearest and trilinear lookups, both corrections, 16-
 *     and 8-bit tables, both buffers, 1 and 2 rays, N2 16 and 40, several views;
 *   - empty space: a volume whose voxels only an order-2 entry's scalar makes visible (N2 = 16 rounds scalar 9 to
 *     17, inside a narrow peak that no voxel reaches): the run-length encoding must not skip it.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "fixtures.h"
#include "imgcmp.h"
#include "io/pngio.h"
#include "scene.h"

/* Render argv's scene with the core and the reference and compare them; *lit_pixels: pixels the core drew. */
static int compare(int argc, char **argv, sim_diff_t *d, size_t *lit_pixels, char *err, size_t errlen)
{
    sim_opts_t o;
    sim_scene_t s;
    vf_image_t core, ref;
    vf_factor_t factor;
    if (sim_parse(&o, argc, argv, SIM_OPT_SCENE, "") != VFP_OK) {
        snprintf(err, errlen, "bad options");
        return -1;
    }
    if (sim_scene_load(&s, &o, err, errlen) || sim_render_core(&s, &core, &factor, err, errlen))
        return -1;
    if (sim_render_reference(&s, &factor, &ref, err, errlen)) {
        sim_image_free(&core);
        sim_scene_free(&s);
        return -1;
    }
    const size_t pixels = (size_t)s.width * s.height;
    uint8_t *a = malloc(pixels * 3), *b = malloc(pixels * 3);
    vfp_image_to_rgb(&core, a);
    vfp_image_to_rgb(&ref, b);
    sim_diff(a, b, pixels, d);
    *lit_pixels = 0;
    for (size_t k = 0; k < pixels * 3; k++)
        *lit_pixels += a[k] != 0;
    free(a);
    free(b);
    sim_image_free(&core);
    sim_image_free(&ref);
    sim_scene_free(&s);
    return 0;
}

static void options_against_reference(void)
{
    static const char *const volumes[] = {"phantom:marschner-lobb:25", "phantom:shepp-logan:26"};
    static const char *const views[] = {"30,20", "135,70", "0,0", "-80,10"};
    static const char *const opts[][8] = {
        {"--preset", "sharp"},
        {"--preset", "sharp", "--lookup", "trilinear"},
        {"--preset", "ramp", "--correction", "lut"},
        {"--preset", "sharp", "--table-bits", "8"},
        {"--preset", "sharp", "--buffer", "image", "--rays", "2"},
        {"--preset", "ct-bone", "--table2-size", "16", "--table-size", "100"},
        {"--preset", "sharp", "--lookup", "trilinear", "--correction", "lut", "--table-bits", "8"},
        {"--preset", "mr-brain", "--table2-size", "40", "--rays", "2", "--buffer", "image"},
    };
    int cases = 0;
    for (size_t v = 0; v < sizeof volumes / sizeof volumes[0]; v++)
        for (size_t o = 0; o < sizeof opts / sizeof opts[0]; o++) {
            char *argv[16] = {(char *)volumes[v], "--mode", "preint2", "--size", "72x64", "--view",
                              (char *)views[(v + o) % 4]};
            int argc = 7;
            for (int k = 0; k < 8 && opts[o][k]; k++)
                argv[argc++] = (char *)opts[o][k];
            sim_diff_t d;
            size_t drawn;
            char err[VFP_ERR_LEN];
            CHECK_MSG(compare(argc, argv, &d, &drawn, err, sizeof err) == 0, "%s", err);
            CHECK_MSG(d.max_abs[3] <= 1 && drawn > 100, "%s %s %s %s: max %d, PSNR %.1f dB, %zu values drawn",
                      volumes[v], opts[o][1], opts[o][2] ? opts[o][2] : "", opts[o][3] ? opts[o][3] : "",
                      d.max_abs[3], d.psnr_db, drawn);
            cases++;
        }
    CHECK_EQ(cases, 16);
}

/* Scalar 9 everywhere in a block, 0 around it; opacity only in a narrow peak at 14..20 of 255. No voxel and no
 * sample reaches the peak, but N2 = 16 puts scalar 9 on entry 1, whose scalar is 17: every segment inside the
 * block is the peak's. The core's run-length encoding counts what an order-2 entry can reach; the reference
 * skips nothing. Both slab counts. */
static void entry_scalars_are_visible(void)
{
    const char *tf = fx_path("peak.tf");
    FILE *f = fopen(tf, "w");
    CHECK(f != NULL);
    fprintf(f, "0 0 0 0 0\n%.6f 1 0.5 0.2 0\n%.6f 1 0.5 0.2 0.8\n%.6f 1 0.5 0.2 0\n1 0 0 0 0\n", 14 / 255.0,
            17 / 255.0, 20 / 255.0);
    fclose(f);
    for (int nz = 11; nz <= 12; nz++) {
        char raw[64], dims[32];
        snprintf(raw, sizeof raw, "block%d.raw", nz);
        snprintf(dims, sizeof dims, "12,12,%d", nz);
        const char *path = fx_path(raw);
        f = fopen(path, "wb");
        CHECK(f != NULL);
        for (int z = 0; z < nz; z++)
            for (int y = 0; y < 12; y++)
                for (int x = 0; x < 12; x++)
                    fputc(x > 2 && x < 9 && y > 2 && y < 9 && z > 2 && z < nz - 2 ? 9 : 0, f);
        fclose(f);
        char *argv[] = {(char *)path, "--dims", dims, "--type", "uint8", "--tf", (char *)tf, "--mode", "preint2",
                        "--table2-size", "16", "--size", "48x48", "--view", "20,15", "--window", "0,255"};
        sim_diff_t d;
        size_t drawn;
        char err[VFP_ERR_LEN];
        CHECK_MSG(compare((int)(sizeof argv / sizeof argv[0]), argv, &d, &drawn, err, sizeof err) == 0, "%s", err);
        CHECK_MSG(drawn > 300, "n_z %d: only %zu values drawn", nz, drawn);
        CHECK_MSG(d.max_abs[3] <= 1, "n_z %d: max %d", nz, d.max_abs[3]);
    }
}

CHECK_CASES({"options_against_reference", options_against_reference},
            {"entry_scalars_are_visible", entry_scalars_are_visible});
CHECK_RUN("order2_frames")
