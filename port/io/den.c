/* SPDX-License-Identifier: MIT */
/* den.c: the VolPack .den reader (a 62-byte little-endian header of 16-bit fields, then 8-bit voxels, x fastest). */

/*********************
 *      INCLUDES
 *********************/
#include "volume_internal.h"

#include <stdio.h>
#include <string.h>

/*********************
 *      DEFINES
 *********************/
/* The header, as VolPack's and Levoy's tools write it (shorts and a long in VAX, that is little-endian, order):
 * version, orig_min[3], orig_max[3], orig_len[3], extr_min[3], extr_max[3], extr_len[3], map_min[3],
 * map_max[3], map_len[3], map_warps, then the 32-bit map_length = map_len[0] * map_len[1] * map_len[2]. Only
 * the map describes the voxels that follow; the rest records where they were cut from. */
#define DEN_VERSION 1
#define OFF_MAP_LEN 50
#define OFF_MAP_LENGTH 58
#define HDR_BYTES 62

/**********************
 *   GLOBAL FUNCTIONS
 **********************/

int vfpi_is_den(const unsigned char *head, size_t n, uint64_t file_bytes)
{
    if (n < HDR_BYTES || vfpi_load16(head, 0) != DEN_VERSION)
        return 0;
    uint64_t count = 1;
    for (int a = 0; a < 3; a++)
        count *= vfpi_load16(head + OFF_MAP_LEN + 2 * a, 0);
    return count == vfpi_load32(head + OFF_MAP_LENGTH, 0) && file_bytes == HDR_BYTES + count;
}

vfp_status_t vfpi_load_den(vfp_volume_t *vol, const char *path, char *err, size_t errlen)
{
    unsigned char hdr[HDR_BYTES];
    size_t n;
    if (vfpi_read_head(path, 0, hdr, sizeof hdr, &n, err, errlen))
        return VFP_ERR;
    if (n < HDR_BYTES)
        return vfpi_fail(err, errlen, path, 0, "too short for a VolPack .den header: %zu bytes (expected at least %d)",
                         n, HDR_BYTES);
    unsigned version = vfpi_load16(hdr, 0);
    if (version != DEN_VERSION)
        return vfpi_fail(err, errlen, path, 0, "unsupported .den version %u (expected 1%s)", version,
                         version == 0x100 ? "; this header looks byte-swapped, and .den headers are little-endian"
                                          : "");
    uint64_t d[3], count = 1;
    for (int a = 0; a < 3; a++) {
        d[a] = vfpi_load16(hdr + OFF_MAP_LEN + 2 * a, 0);
        count *= d[a];
    }
    uint32_t map_length = vfpi_load32(hdr + OFF_MAP_LENGTH, 0);
    if (map_length != count)
        return vfpi_fail(err, errlen, path, 0, "map_length %u does not match map_len %llu x %llu x %llu = %llu",
                         map_length, (unsigned long long)d[0], (unsigned long long)d[1], (unsigned long long)d[2],
                         (unsigned long long)count);
    if (vfpi_check_dims(d, path, 0, err, errlen))
        return VFP_ERR;
    uint32_t dims[3] = {(uint32_t)d[0], (uint32_t)d[1], (uint32_t)d[2]};
    /* .den files carry no voxel size: unit spacing. */
    for (int a = 0; a < 3; a++)
        vol->spacing[a] = 1.0;
    vfpi_source_t src = {.path = path, .byte_skip = HDR_BYTES};
    size_t bytes;
    return vfpi_read_voxels(vol, dims, VF_VOXEL_U8, &src, &bytes, err, errlen);
}
