/* SPDX-License-Identifier: MIT */
/* fuzz_nifti.c: a single-file NIfTI-1 volume, loaded as x.nii. */
#include "fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_begin();
    fz_load_volume(fz_write("x.nii", data, size), NULL);
    return 0;
}
