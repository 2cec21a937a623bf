/* SPDX-License-Identifier: MIT */
/*
 * dicom.h: the DICOM reader's C interface (port/io/dicom.cpp, C++ over GDCM, compiled when the Makefile finds GDCM:
 * VFP_HAVE_GDCM). Without GDCM the loader is the inline below, which says how to get it, and the rest of the port
 * layer is the same either way.
 *
 * vfpi_load_dicom reads a series: PATH is a folder of slices (one series, or several: the largest is loaded and the
 * others are listed on stderr, one line each, unless opts->series names one) or a single file (a multi-frame image,
 * or one slice of the series in its folder). Slices are sorted by Image Position (Patient) along the normal of
 * Image Orientation (Patient); the spacing comes from Pixel Spacing and the positions' step; Rescale Slope and
 * Intercept become vol->slope and inter (Hounsfield units for CT); GDCM decodes compressed transfer syntaxes. A
 * missing slice (uneven positions), a gantry tilt (positions not along the normal) and slices that disagree (size,
 * orientation, type, rescale) are errors naming the file and the tag. Hundreds of files show progress on stderr.
 * Like the other readers: fills vol->data, core.dims, core.type, spacing, slope, inter and the orientation, or fails
 * with err filled and everything freed.
 */
#ifndef VFP_DICOM_H
#define VFP_DICOM_H

#include <stddef.h>
#include <string.h>

#include "volume.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The DICOM Part 10 file's "DICM" after its 128-byte preamble. */
static inline int vfpi_is_dicom(const unsigned char *head, size_t n)
{
    return n >= 132 && memcmp(head + 128, "DICM", 4) == 0;
}

#ifdef VFP_HAVE_GDCM
vfp_status_t vfpi_load_dicom(vfp_volume_t *vol, const char *path, const vfp_load_opts_t *opts, char *err,
                             size_t errlen);
#else
vfp_status_t vfpi_fail(char *err, size_t errlen, const char *name, unsigned line, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));

static inline vfp_status_t vfpi_load_dicom(vfp_volume_t *vol, const char *path, const vfp_load_opts_t *opts,
                                           char *err, size_t errlen)
{
    (void)vol;
    (void)opts;
    return vfpi_fail(err, errlen, path, 0, "DICOM (a folder of slices or a .dcm file) needs volfix built with GDCM: "
                     "apt-get install libgdcm-dev, then make");
}
#endif

#ifdef __cplusplus
}
#endif

#endif /* VFP_DICOM_H */
