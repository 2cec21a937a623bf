/* SPDX-License-Identifier: MIT */
/*
 * volume_downsample.c: a volume made smaller by a whole factor in each direction (the box average of each
 * factor^3 block, rounded to nearest), with the spacing multiplied by the factor so that the volume keeps its
 * shape and its opacity per millimetre.
 *
 * The viewer renders this half-resolution copy while a knob turns: an eighth of the voxels to classify and
 * run-length encode again when the transfer function moves, and a quarter of the intermediate image to
 * composite. volfix-sim takes the same --downsample option, so a preview frame can be checked pixel by pixel.
 *
 * A side that does not divide evenly keeps its last, partial block (averaged over the voxels it has), and
 * never falls below the core's smallest side of 2.
 */
#include "volume_internal.h"

#include <stdlib.h>
#include <string.h>

/* One output voxel: the rounded mean of the block starting at (x0, y0, z0), clipped to the volume. */
static int32_t block_mean(const vfp_volume_t *src, uint32_t x0, uint32_t y0, uint32_t z0, uint32_t f)
{
    const uint32_t *d = src->core.dims;
    uint32_t x1 = x0 + f < d[0] ? x0 + f : d[0];
    uint32_t y1 = y0 + f < d[1] ? y0 + f : d[1];
    uint32_t z1 = z0 + f < d[2] ? z0 + f : d[2];
    int64_t sum = 0, n = 0;
    for (uint32_t z = z0; z < z1; z++)
        for (uint32_t y = y0; y < y1; y++) {
            size_t row = ((size_t)z * d[1] + y) * d[0];
            for (uint32_t x = x0; x < x1; x++) {
                size_t i = row + x;
                switch (src->core.type) {
                case VF_VOXEL_U8: sum += ((const uint8_t *)src->data)[i]; break;
                case VF_VOXEL_I8: sum += ((const int8_t *)src->data)[i]; break;
                case VF_VOXEL_U16: sum += ((const uint16_t *)src->data)[i]; break;
                default: sum += ((const int16_t *)src->data)[i]; break;
                }
            }
            n += x1 - x0;
        }
    /* Round half away from zero, so that negative data (int8, int16) is treated as positive data is. */
    return (int32_t)(sum >= 0 ? (sum + n / 2) / n : -((-sum + n / 2) / n));
}

vfp_status_t vfpi_downsample(vfp_volume_t *vol, int factor, char *err, size_t errlen)
{
    if (factor == 1)
        return VFP_OK;
    if (factor < 1 || factor > VFPI_MAX_DOWNSAMPLE)
        return vfpi_fail(err, errlen, vol->name, 0, "downsample factor %d (expected 1 to %d)", factor,
                         VFPI_MAX_DOWNSAMPLE);
    uint32_t f = (uint32_t)factor, dims[3];
    for (int a = 0; a < 3; a++) {
        dims[a] = (vol->core.dims[a] + f - 1) / f;
        if (dims[a] < 2)
            return vfpi_fail(err, errlen, vol->name, 0,
                             "%u voxels along %c are too few to downsample %d times (expected at least %u)",
                             vol->core.dims[a], "xyz"[a], factor, f + 1);
    }
    vfp_volume_t small = *vol;
    small.data = NULL;
    size_t bytes;
    if (vfpi_alloc_voxels(&small, dims, vol->core.type, &bytes, vol->name, err, errlen))
        return VFP_ERR;
    for (uint32_t z = 0; z < dims[2]; z++)
        for (uint32_t y = 0; y < dims[1]; y++)
            for (uint32_t x = 0; x < dims[0]; x++) {
                size_t i = ((size_t)z * dims[1] + y) * dims[0] + x;
                int32_t v = block_mean(vol, x * f, y * f, z * f, f);
                switch (vol->core.type) {
                case VF_VOXEL_U8: ((uint8_t *)small.data)[i] = (uint8_t)v; break;
                case VF_VOXEL_I8: ((int8_t *)small.data)[i] = (int8_t)v; break;
                case VF_VOXEL_U16: ((uint16_t *)small.data)[i] = (uint16_t)v; break;
                default: ((int16_t *)small.data)[i] = (int16_t)v; break;
                }
            }
    for (int a = 0; a < 3; a++)
        small.spacing[a] = vol->spacing[a] * f;
    free(vol->data);
    *vol = small;
    return VFP_OK;
}
