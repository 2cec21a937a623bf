/* SPDX-License-Identifier: MIT */
/* status.c: a text for every status, and the names of modes and formats. */
#include "volfix.h"

static const char *const status_texts[VF_STATUS_COUNT] = {
    [VF_OK] = "ok",
    [VF_ERR_NULL] = "a required pointer is NULL",
    [VF_ERR_ARG] = "an argument is out of range",
    [VF_ERR_DIMS] = "volume dimensions must each be 2..VF_MAX_DIM",
    [VF_ERR_SPACING] = "voxel spacings must be positive and within VF_MAX_ANISOTROPY of each other",
    [VF_ERR_WINDOW] = "the window is empty (lo == hi)",
    [VF_ERR_TF] = "the transfer function has no points, too many, or decreasing scalars",
    [VF_ERR_NOMEM] = "the arena or scratch buffer is too small",
    [VF_ERR_STATE] = "called out of order (set a window and a transfer function, then begin a frame)",
    [VF_ERR_IMAGE] = "the output image is empty, has an unknown format, a short stride or the wrong size",
    [VF_ERR_UNSUPPORTED] = "not supported by this build",
    [VF_ERR_INTERMEDIATE] = "too many rays: the intermediate image would exceed VF_MAX_INTERMEDIATE pixels a side",
};

const char *vf_status_text(vf_status_t status)
{
    if ((unsigned)status >= VF_STATUS_COUNT)
        return "unknown status";
    return status_texts[status];
}

const char *vf_mode_name(vf_mode_t mode)
{
    switch (mode) {
    case VF_MODE_POINT: return "point";
    case VF_MODE_PREINT1: return "preint1";
    case VF_MODE_PRECLASS: return "preclass";
    case VF_MODE_PREINT2: return "preint2";
    default: return "unknown";
    }
}

const char *vf_lookup_name(vf_lookup_t lookup)
{
    return lookup == VF_LOOKUP_NEAREST    ? "nearest"
           : lookup == VF_LOOKUP_BILINEAR  ? "bilinear"
           : lookup == VF_LOOKUP_TRILINEAR ? "trilinear"
                                           : "unknown";
}

const char *vf_correction_name(vf_correction_t correction)
{
    return correction == VF_CORRECTION_REBUILD ? "rebuild" : correction == VF_CORRECTION_LUT ? "lut" : "unknown";
}

const char *vf_buffer_name(vf_buffer_t buffer)
{
    return buffer == VF_BUFFER_SLICE ? "slice" : buffer == VF_BUFFER_IMAGE ? "image" : "unknown";
}

uint32_t vf_format_bytes(vf_format_t format)
{
    switch (format) {
    case VF_FORMAT_RGB888: return 3;
    case VF_FORMAT_RGB565: return 2;
    case VF_FORMAT_XRGB8888: return 4;
    default: return 0;
    }
}
