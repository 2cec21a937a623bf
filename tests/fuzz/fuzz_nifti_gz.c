/* SPDX-License-Identifier: MIT */
/* fuzz_nifti_gz.c: a gzip'd NIfTI-1 volume, loaded as x.nii.gz. An input that starts with gzip's magic (1f 8b)
 * is written as it is, to fuzz the decompression (damaged streams, concatenated members, trailing bytes); any
 * other input is the uncompressed file, gzip'd here, to fuzz the header and the skips on the gzip path. */
#include <zlib.h>

#include "fuzz.h"

/* gzip (not zlib) bytes of data, as gzip(1) writes them; NULL when out of memory. The caller frees. */
static unsigned char *gzip_bytes(const uint8_t *data, size_t size, size_t *out_size)
{
    z_stream z;
    memset(&z, 0, sizeof z);
    if (deflateInit2(&z, 1, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
        return NULL;
    size_t cap = deflateBound(&z, (uLong)size);
    unsigned char *out = malloc(cap);
    z.next_in = (unsigned char *)data;
    z.avail_in = (uInt)size;
    z.next_out = out;
    z.avail_out = (uInt)cap;
    if (!out || deflate(&z, Z_FINISH) != Z_STREAM_END) {
        free(out);
        out = NULL;
    }
    *out_size = cap - z.avail_out;
    deflateEnd(&z);
    return out;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_begin();
    if (size >= 2 && data[0] == 0x1f && data[1] == 0x8b) {
        fz_load_volume(fz_write("x.nii.gz", data, size), NULL);
        return 0;
    }
    size_t gz_size;
    unsigned char *gz = gzip_bytes(data, size, &gz_size);
    if (!gz)
        abort();
    const char *path = fz_write("x.nii.gz", gz, gz_size);
    free(gz);
    fz_load_volume(path, NULL);
    return 0;
}
