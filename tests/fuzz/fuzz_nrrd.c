/* SPDX-License-Identifier: MIT */
/* fuzz_nrrd.c: a NRRD file with its data attached (or naming a data file), loaded as volfix-sim loads x.nrrd. */
#include "fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_begin();
    fz_load_volume(fz_write("x.nrrd", data, size), NULL);
    return 0;
}
