/* SPDX-License-Identifier: MIT */
/* fuzz_metaimage.c: a MetaImage header and its data. The whole input is loaded as x.mha (a header whose
 * "ElementDataFile = LOCAL" data follows it in the same file); when the input holds a NUL byte, the part before it
 * is also loaded as x.mhd and the part after it is d.raw, the data file the seeds' detached headers name
 * ("ElementDataFile = d.raw"); a header holds no NUL, so the split is unambiguous. */
#include "fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_begin();
    fz_load_volume(fz_write("x.mha", data, size), NULL);
    const uint8_t *nul = memchr(data, 0, size);
    if (nul) {
        size_t header = (size_t)(nul - data);
        fz_write("d.raw", nul + 1, size - header - 1);
        fz_load_volume(fz_write("x.mhd", data, header), NULL);
    }
    return 0;
}
