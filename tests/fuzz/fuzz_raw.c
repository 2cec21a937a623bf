/* SPDX-License-Identifier: MIT */
/* fuzz_raw.c: raw voxels with the options volfix-sim takes for them. The input's first 7 bytes are the options,
 * the rest is the file:
 *   bytes 0..5  --dims X,Y,Z, three little-endian 16-bit numbers (0..65535: out-of-range sizes are errors too)
 *   byte 6      bits 0-1 --type (uint8, int8, uint16, int16), bit 2 --big-endian, bit 3 the file is x.raw.gz
 *               (gzip'd raw; else x.raw), bits 4-6 --downsample 0..7, bit 7 no options at all
 * A file that is NRRD, NIfTI-1 or .den by its contents goes to that reader, as it does for the programs. */
#include "fuzz.h"

#define OPTION_BYTES 7

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_begin();
    if (size < OPTION_BYTES)
        return 0;
    static const vf_voxel_t types[4] = {VF_VOXEL_U8, VF_VOXEL_I8, VF_VOXEL_U16, VF_VOXEL_I16};
    vfp_load_opts_t opts;
    memset(&opts, 0, sizeof opts);
    opts.have_dims = opts.have_type = 1;
    for (int a = 0; a < 3; a++)
        opts.dims[a] = (uint32_t)data[2 * a] | (uint32_t)data[2 * a + 1] << 8;
    uint8_t flags = data[6];
    opts.type = types[flags & 3];
    opts.big_endian = flags >> 2 & 1;
    opts.downsample = flags >> 4 & 7;
    const char *path = fz_write(flags & 8 ? "x.raw.gz" : "x.raw", data + OPTION_BYTES, size - OPTION_BYTES);
    fz_load_volume(path, flags & 0x80 ? NULL : &opts);
    return 0;
}
