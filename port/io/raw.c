/* SPDX-License-Identifier: MIT */
/* raw.c: the reader for raw voxels (plain, or gzip'd when the name ends in .gz) with dims and type given. */

/*********************
 *      INCLUDES
 *********************/
#include "volume_internal.h"

#include <stdio.h>

/*********************
 *      DEFINES
 *********************/
#define NEEDS "raw data needs --dims X,Y,Z and --type uint8|int8|uint16|int16"

/**********************
 *  STATIC PROTOTYPES
 **********************/
static const char *type_name(vf_voxel_t type);

/**********************
 *   GLOBAL FUNCTIONS
 **********************/

vfp_status_t vfpi_load_raw(vfp_volume_t *vol, const char *path, const vfp_load_opts_t *opts, char *err, size_t errlen)
{
    if (!opts || (!opts->have_dims && !opts->have_type))
        return vfpi_fail(err, errlen, path, 0, NEEDS " (or a file format this program recognises: NRRD, NIfTI-1, "
                         ".den)");
    if (!opts->have_dims || !opts->have_type)
        return vfpi_fail(err, errlen, path, 0, NEEDS " (%s is missing)", opts->have_dims ? "--type" : "--dims");
    uint64_t d[3] = {opts->dims[0], opts->dims[1], opts->dims[2]};
    char name[VFP_ERR_LEN];
    snprintf(name, sizeof name, "%s: --dims", path);
    if (vfpi_check_dims(d, name, 0, err, errlen))
        return VFP_ERR;
    if (opts->type != VF_VOXEL_U8 && opts->type != VF_VOXEL_I8 && opts->type != VF_VOXEL_U16 &&
        opts->type != VF_VOXEL_I16)
        return vfpi_fail(err, errlen, path, 0, "bad --type %d (expected uint8, int8, uint16 or int16)",
                         (int)opts->type);
    for (int a = 0; a < 3; a++)
        vol->spacing[a] = 1.0; /* volume.c applies --spacing */

    /* Size errors say which options the expected size came from, the usual thing to correct. */
    char note[128];
    snprintf(note, sizeof note, "for --dims %u,%u,%u --type %s", opts->dims[0], opts->dims[1], opts->dims[2],
             type_name(opts->type));
    vfpi_source_t src = {.path = path, .note = note, .gzip = vfpi_has_suffix(path, ".gz")};
    size_t bytes;
    if (vfpi_read_voxels(vol, opts->dims, opts->type, &src, &bytes, err, errlen))
        return VFP_ERR;
    if (vfpi_type_bytes(opts->type) == 2)
        vfpi_to_native16(vol->data, bytes / 2, opts->big_endian);
    return VFP_OK;
}

/**********************
 *   STATIC FUNCTIONS
 **********************/

static const char *type_name(vf_voxel_t type)
{
    switch (type) {
    case VF_VOXEL_U8: return "uint8";
    case VF_VOXEL_I8: return "int8";
    case VF_VOXEL_U16: return "uint16";
    default: return "int16";
    }
}
