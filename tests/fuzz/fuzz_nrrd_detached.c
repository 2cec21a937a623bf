/* SPDX-License-Identifier: MIT */
/* fuzz_nrrd_detached.c: a detached NRRD header and its data file. The input is the header (x.nhdr), a NUL byte,
 * then the data file's bytes (d.raw, which the seeds' headers name: "data file: d.raw"); a header holds no NUL, so
 * the split is unambiguous. Without a NUL the data file is empty. */
#include "fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_begin();
    const uint8_t *nul = memchr(data, 0, size);
    size_t header = nul ? (size_t)(nul - data) : size;
    fz_write("d.raw", nul ? nul + 1 : data, nul ? size - header - 1 : 0);
    fz_load_volume(fz_write("x.nhdr", data, header), NULL);
    return 0;
}
