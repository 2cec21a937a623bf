/* SPDX-License-Identifier: MIT */
/*
 * test_volume_data.c: the readers on the real volumes in the shared data folder (see its README.md): every header
 * loads with the documented dims, type and spacing, and the same volume in different formats is the same voxels.
 *
 * The folder is $VOLFIX_DATA (make test sets it): a volume that is not there fails its case, naming the variable.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/volume.h"

/* ---------------------------------------------------------------------------------------------------------- */
/* Helpers */

/* Loads the sample volume NAME; on failure why says what went wrong (a missing VOLFIX_DATA or file included). */
static int load(vfp_volume_t *vol, const char *name, char *why, size_t len)
{
    char err[VFP_ERR_LEN];
    if (!check_data(name, why, len))
        return -1;
    if (vfp_volume_load(vol, why, NULL, err, sizeof err) == 0)
        return 0;
    snprintf(why, len, "%s", err);
    return -1;
}

#define LOAD(vol, name) \
    do { \
        char why_[1100]; \
        CHECK_MSG(load(vol, name, why_, sizeof why_) == 0, "%s", why_); \
    } while (0)

static size_t volume_bytes(const vfp_volume_t *vol)
{
    size_t n = (size_t)vol->core.dims[0] * vol->core.dims[1] * vol->core.dims[2];
    return vol->core.type == VF_VOXEL_U16 || vol->core.type == VF_VOXEL_I16 ? 2 * n : n;
}

/* Two loads of one volume: same dims, type and every voxel. */
static void same_voxels(const char *a_name, const char *b_name)
{
    vfp_volume_t a, b;
    LOAD(&a, a_name);
    char why[1100];
    if (load(&b, b_name, why, sizeof why) != 0) {
        vfp_volume_free(&a);
        CHECK_MSG(0, "%s", why);
    }
    int same = a.core.type == b.core.type && memcmp(a.core.dims, b.core.dims, sizeof a.core.dims) == 0 &&
               memcmp(a.core.voxels, b.core.voxels, volume_bytes(&a)) == 0;
    vfp_volume_free(&a);
    vfp_volume_free(&b);
    CHECK_MSG(same, "%s and %s differ", a_name, b_name);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Cases */

static void data_nhdr_headers(void)
{
    /* The table of data/README.md. */
    static const struct {
        const char *file;
        uint32_t dims[3];
        vf_voxel_t type;
        double spacing[3];
    } volumes[] = {
        {"bucky.nhdr", {32, 32, 32}, VF_VOXEL_U8, {1, 1, 1}},
        {"neghip.nhdr", {64, 64, 64}, VF_VOXEL_U8, {1, 1, 1}},
        {"headsq.nhdr", {64, 64, 93}, VF_VOXEL_I16, {3.2, 3.2, 1.5}},
        {"brainsmall.nhdr", {128, 128, 84}, VF_VOXEL_U8, {1, 1, 1}},
        {"engine.nhdr", {256, 256, 128}, VF_VOXEL_U8, {1, 1, 1}},
        {"cthead.nhdr", {256, 256, 113}, VF_VOXEL_I16, {1, 1, 2}},
    };
    for (size_t v = 0; v < sizeof volumes / sizeof volumes[0]; v++) {
        vfp_volume_t vol;
        LOAD(&vol, volumes[v].file);
        int ok = strcmp(vol.format, "nrrd") == 0 && vol.core.type == volumes[v].type;
        double smallest = volumes[v].spacing[0];
        for (int a = 1; a < 3; a++)
            smallest = volumes[v].spacing[a] < smallest ? volumes[v].spacing[a] : smallest;
        for (int a = 0; a < 3; a++) {
            ok = ok && vol.core.dims[a] == volumes[v].dims[a] && vol.spacing[a] == volumes[v].spacing[a];
            ok = ok && vol.core.spacing_q16[a] == (uint32_t)(volumes[v].spacing[a] / smallest * 65536.0 + 0.5);
        }
        ok = ok && vol.raw_min < vol.raw_max;
        printf("# %s: %ux%ux%u, raw %d..%d\n", volumes[v].file, vol.core.dims[0], vol.core.dims[1], vol.core.dims[2],
               vol.raw_min, vol.raw_max);
        vfp_volume_free(&vol);
        CHECK_MSG(ok, "%s: dims, type or spacing differ from the README", volumes[v].file);
    }
}

static void data_cthead_is_12_bit(void)
{
    /* Big-endian 12-bit values: a wrong byte order would put values far outside 0..4095. */
    vfp_volume_t vol;
    LOAD(&vol, "cthead.nhdr");
    int32_t lo = vol.raw_min, hi = vol.raw_max;
    vfp_volume_free(&vol);
    CHECK_MSG(lo >= 0 && hi <= 4095 && hi > 1000, "cthead raw range %d..%d is not 12-bit data", lo, hi);
}

static void data_engine_nifti_equals_nrrd(void)
{
    /* engine.nii.gz's sform is the identity in NIfTI's RAS, so in the patient frame (LPS) its x and y run the other
     * way; engine.nhdr names no space and stays as stored. */
    vfp_volume_t nii, nrrd;
    LOAD(&nii, "engine.nii.gz");
    char why[1100];
    if (load(&nrrd, "engine.nhdr", why, sizeof why) != 0) {
        vfp_volume_free(&nii);
        CHECK_MSG(0, "%s", why);
    }
    const uint32_t *d = nrrd.core.dims;
    int same = nii.core.type == nrrd.core.type && memcmp(nii.core.dims, d, sizeof nrrd.core.dims) == 0;
    const uint8_t *a = nii.data, *b = nrrd.data;
    for (uint32_t z = 0; same && z < d[2]; z++)
        for (uint32_t y = 0; same && y < d[1]; y++)
            for (uint32_t x = 0; same && x < d[0]; x++)
                same = a[((size_t)z * d[1] + y) * d[0] + x] == b[((size_t)z * d[1] + (d[1] - 1 - y)) * d[0] + (d[0] - 1 - x)];
    int ok = strcmp(nii.format, "nifti") == 0 && nii.slope == 1.0 && nii.inter == 0.0 && nii.spacing[0] == 1.0 &&
             nii.oriented && strcmp(nii.orient_from, "sform") == 0 && nii.oblique_deg == 0 && nii.stored_flip[0] &&
             nii.stored_flip[1] && !nii.stored_flip[2] && !nrrd.oriented;
    vfp_volume_free(&nii);
    vfp_volume_free(&nrrd);
    CHECK_MSG(same, "engine.nii.gz in LPS is not engine.nhdr with x and y reversed");
    CHECK(ok);
}

static void data_brainsmall_den_equals_nrrd(void)
{
    same_voxels("brainsmall.den", "brainsmall.nhdr");
    vfp_volume_t vol;
    LOAD(&vol, "brainsmall.den");
    int ok = strcmp(vol.format, "den") == 0 && vol.core.dims[0] == 128 && vol.core.dims[1] == 128 &&
             vol.core.dims[2] == 84;
    vfp_volume_free(&vol);
    CHECK(ok);
}

static void data_default_windows(void)
{
    static const char *const files[] = {"headsq.nhdr", "cthead.nhdr"};
    for (size_t f = 0; f < 2; f++) {
        vfp_volume_t vol;
        LOAD(&vol, files[f]);
        vf_window_t w = vfp_default_window(&vol);
        printf("# %s: default window %d..%d of raw %d..%d\n", files[f], w.lo, w.hi, vol.raw_min, vol.raw_max);
        int ok = w.lo < w.hi && w.lo >= vol.raw_min && w.hi <= vol.raw_max;
        vfp_volume_free(&vol);
        CHECK_MSG(ok, "%s: default window %d..%d is not sane", files[f], w.lo, w.hi);
    }
    vfp_volume_t vol;
    LOAD(&vol, "bucky.nhdr");
    vf_window_t w = vfp_default_window(&vol);
    vfp_volume_free(&vol);
    CHECK(w.lo == 0 && w.hi == 255);
}

CHECK_CASES({"data_nhdr_headers", data_nhdr_headers},
            {"data_cthead_is_12_bit", data_cthead_is_12_bit},
            {"data_engine_nifti_equals_nrrd", data_engine_nifti_equals_nrrd},
            {"data_brainsmall_den_equals_nrrd", data_brainsmall_den_equals_nrrd},
            {"data_default_windows", data_default_windows});
CHECK_RUN("volume")
