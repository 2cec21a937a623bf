/* SPDX-License-Identifier: MIT */
/* fuzz_den.c: a VolPack .den volume, loaded as x.den. */
#include "fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_begin();
    fz_load_volume(fz_write("x.den", data, size), NULL);
    return 0;
}
