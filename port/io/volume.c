/* SPDX-License-Identifier: MIT */
/* volume.c: loading a volume by name (choosing the reader), freeing it, and windows, dims and types from text. */

/*********************
 *      INCLUDES
 *********************/
#include "volume_internal.h"
#include "dicom.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

/*********************
 *      DEFINES
 *********************/
#define PHANTOM_PREFIX "phantom:"
#define SHOWN_TEXT 64 /* characters of a bad option value repeated in its message */

/* The default window of 16-bit data: these percentiles of the raw values, in thousandths. */
#define WINDOW_LO_PERMYRIAD 50      /* 16-bit default window (percentile_window): the 0.5 percentile, */
#define WINDOW_BULK_PERMYRIAD 9950  /* the 99.5 percentile (the bulk of the data), */
#define WINDOW_TAIL_PERMYRIAD 9999  /* and the 99.99 percentile (sparse bright structures) */

/**********************
 *  STATIC PROTOTYPES
 **********************/
static vfp_status_t load(vfp_volume_t *vol, const char *spec, const vfp_load_opts_t *opts, char *err, size_t errlen);
static vfp_status_t finish(vfp_volume_t *vol, const vfp_load_opts_t *opts, char *err, size_t errlen);
static void raw_range(vfp_volume_t *vol);
static int32_t raw_at(const vfp_volume_t *vol, size_t i);
static vf_window_t percentile_window(const vfp_volume_t *vol);
static const char *option_name(char *buf, size_t size, const char *option, const char *text);
static int parse_number(const char **p, double *value);

/**********************
 *   GLOBAL FUNCTIONS
 **********************/

vfp_status_t vfp_volume_load(vfp_volume_t *vol, const char *spec, const vfp_load_opts_t *opts, char *err, size_t errlen)
{
    if (err && errlen)
        err[0] = 0;
    if (!vol)
        return vfpi_fail(err, errlen, spec ? spec : "(null)", 0, "no volume to load into");
    /* Safe construction: everything harmless before anything can fail, so one cleanup serves every path. */
    memset(vol, 0, sizeof *vol);
    vol->slope = 1.0;
    if (!spec || !spec[0])
        return vfpi_fail(err, errlen, "(no file)", 0, "no volume file or phantom spec given");
    snprintf(vol->name, sizeof vol->name, "%s", spec);

    vfp_status_t rc = vfpi_spool_begin(spec, err, errlen);
    if (rc == VFP_OK)
        rc = load(vol, spec, opts, err, errlen);
    vfpi_spool_end();
    if (rc == VFP_OK)
        rc = vfpi_orient(vol, err, errlen);
    if (rc == VFP_OK && opts && opts->downsample > 1)
        rc = vfpi_downsample(vol, opts->downsample, err, errlen);
    if (rc == VFP_OK)
        rc = finish(vol, opts, err, errlen);
    if (rc) {
        vfp_volume_free(vol);
        return VFP_ERR;
    }
    return VFP_OK;
}

void vfp_volume_free(vfp_volume_t *vol)
{
    if (!vol)
        return;
    free(vol->data);
    memset(vol, 0, sizeof *vol);
}

vf_window_t vfp_default_window(const vfp_volume_t *vol)
{
    vf_window_t w = {0, 255};
    if (!vol || !vol->data)
        return w;
    switch (vol->core.type) {
    case VF_VOXEL_U8:
        return w;
    case VF_VOXEL_I8:
        w.lo = -128;
        w.hi = 127;
        return w;
    default:
        return percentile_window(vol);
    }
}

void vfp_window_data(const vfp_volume_t *vol, vf_window_t window, double *lo, double *hi)
{
    double slope = vol && vol->slope != 0.0 ? vol->slope : 1.0, inter = vol ? vol->inter : 0.0;
    *lo = window.lo * slope + inter;
    *hi = window.hi * slope + inter;
}

vfp_status_t vfp_parse_window(const vfp_volume_t *vol, const char *text, vf_window_t *window, char *err, size_t errlen)
{
    char name[SHOWN_TEXT + 32];
    option_name(name, sizeof name, "--window", text);
    const char *p = text ? text : "";
    double lo, hi;
    if (!parse_number(&p, &lo) || *p++ != ',' || !parse_number(&p, &hi) || *p)
        return vfpi_fail(err, errlen, name, 0, "expected LO,HI: two numbers in data units, for example 0,1000");
    if (!isfinite(lo) || !isfinite(hi))
        return vfpi_fail(err, errlen, name, 0, "expected two finite numbers");
    if (lo == hi)
        return vfpi_fail(err, errlen, name, 0, "LO and HI are equal (expected two different values)");
    /* data = slope * raw + inter, so raw = (data - inter) / slope; a negative slope turns the window round,
     * which the core handles (hi < lo maps descending). */
    double slope = vol && vol->slope != 0.0 ? vol->slope : 1.0, inter = vol ? vol->inter : 0.0;
    double raw_lo = nearbyint((lo - inter) / slope), raw_hi = nearbyint((hi - inter) / slope);
    if (!(fabs(raw_lo) <= INT32_MAX && fabs(raw_hi) <= INT32_MAX))
        return vfpi_fail(err, errlen, name, 0, "out of range: the raw values (data - %g) / %g must lie within "
                         "+-2147483647", inter, slope);
    if (raw_lo == raw_hi)
        return vfpi_fail(err, errlen, name, 0, "LO and HI both round to the raw value %.0f (slope %g, intercept %g);"
                         " expected a wider window", raw_lo, slope, inter);
    window->lo = (int32_t)raw_lo;
    window->hi = (int32_t)raw_hi;
    return VFP_OK;
}

vfp_status_t vfp_parse_dims(const char *text, uint32_t dims[3], char *err, size_t errlen)
{
    char name[SHOWN_TEXT + 32];
    option_name(name, sizeof name, "--dims", text);
    const char *p = text ? text : "";
    uint64_t d[3];
    for (int a = 0; a < 3; a++) {
        while (*p == ' ')
            p++;
        if (!isdigit((unsigned char)*p))
            return vfpi_fail(err, errlen, name, 0, "expected X,Y,Z: three whole numbers 2..%d, for example "
                             "256,256,113", VF_MAX_DIM);
        errno = 0;
        char *end;
        unsigned long long v = strtoull(p, &end, 10);
        d[a] = errno == ERANGE ? UINT64_MAX : v;
        p = end;
        while (*p == ' ')
            p++;
        if (a < 2 && *p != ',' && *p != 'x' && *p != 'X')
            return vfpi_fail(err, errlen, name, 0, "expected X,Y,Z: three whole numbers 2..%d, for example "
                             "256,256,113", VF_MAX_DIM);
        if (a < 2)
            p++;
    }
    if (*p)
        return vfpi_fail(err, errlen, name, 0, "unexpected '%.16s' after X,Y,Z", p);
    if (vfpi_check_dims(d, name, 0, err, errlen))
        return VFP_ERR;
    for (int a = 0; a < 3; a++)
        dims[a] = (uint32_t)d[a];
    return VFP_OK;
}

vfp_status_t vfp_parse_type(const char *text, vf_voxel_t *type, char *err, size_t errlen)
{
    static const struct {
        const char *name;
        vf_voxel_t type;
    } types[] = {{"uint8", VF_VOXEL_U8}, {"int8", VF_VOXEL_I8}, {"uint16", VF_VOXEL_U16}, {"int16", VF_VOXEL_I16}};
    for (size_t i = 0; text && i < sizeof types / sizeof types[0]; i++) {
        if (strcasecmp(text, types[i].name) == 0) {
            *type = types[i].type;
            return VFP_OK;
        }
    }
    char name[SHOWN_TEXT + 32];
    return vfpi_fail(err, errlen, option_name(name, sizeof name, "--type", text), 0,
                     "unknown type (expected uint8, int8, uint16 or int16)");
}

vfp_status_t vfp_volume_downsampled(vfp_volume_t *dst, const vfp_volume_t *src, int factor, char *err, size_t errlen)
{
    memset(dst, 0, sizeof *dst);
    size_t bytes = (size_t)src->core.dims[0] * src->core.dims[1] * src->core.dims[2] * vfpi_type_bytes(src->core.type);
    *dst = *src;
    dst->data = malloc(bytes);
    if (!dst->data) {
        memset(dst, 0, sizeof *dst);
        return vfpi_fail(err, errlen, src->name, 0, "out of memory for a downsampled copy (%zu bytes)", bytes);
    }
    memcpy(dst->data, src->data, bytes);
    if (vfpi_downsample(dst, factor, err, errlen) || finish(dst, NULL, err, errlen)) {
        vfp_volume_free(dst);
        return VFP_ERR;
    }
    return VFP_OK;
}

/**********************
 *   STATIC FUNCTIONS
 **********************/

/* Chooses the reader: by content first (magic numbers), then by extension; raw is what is left. */
static vfp_status_t load(vfp_volume_t *vol, const char *spec, const vfp_load_opts_t *opts, char *err, size_t errlen)
{
    if (strncmp(spec, PHANTOM_PREFIX, strlen(PHANTOM_PREFIX)) == 0) {
        snprintf(vol->format, sizeof vol->format, "phantom");
        return vfpi_load_phantom(vol, spec, err, errlen);
    }
    struct stat st;
    if (vfpi_stat(spec, &st) != 0)
        return vfpi_fail(err, errlen, spec, 0, "cannot open: %s", strerror(errno));
    if (S_ISDIR(st.st_mode)) {
#ifdef VFP_HAVE_GDCM
        snprintf(vol->format, sizeof vol->format, "dicom");
        return vfpi_load_dicom(vol, spec, opts, err, errlen);
#else
        return vfpi_fail(err, errlen, spec, 0, "is a directory (expected a volume file; a folder of DICOM slices needs "
                         "volfix built with GDCM: apt-get install libgdcm-dev, then make)");
#endif
    }
    unsigned char head[VFPI_HEAD_BYTES];
    size_t n;
    if (vfpi_read_head(spec, 0, head, sizeof head, &n, err, errlen))
        return VFP_ERR;
    if (n == 0)
        return vfpi_fail(err, errlen, spec, 0, "empty file (expected a volume: NRRD, NIfTI, MetaImage, DICOM, "
                         "VolPack .den or raw)");
    if (vfpi_is_dicom(head, n) || vfpi_has_suffix(spec, ".dcm")) {
        snprintf(vol->format, sizeof vol->format, "dicom");
        return vfpi_load_dicom(vol, spec, opts, err, errlen);
    }
    if (vfpi_has_suffix(spec, ".mhd") || vfpi_has_suffix(spec, ".mha") || vfpi_is_metaimage(head, n)) {
        snprintf(vol->format, sizeof vol->format, "metaimage");
        return vfpi_load_metaimage(vol, spec, err, errlen);
    }

    if ((n >= 4 && memcmp(head, "NRRD", 4) == 0) || vfpi_has_suffix(spec, ".nrrd") || vfpi_has_suffix(spec, ".nhdr")) {
        snprintf(vol->format, sizeof vol->format, "nrrd");
        return vfpi_load_nrrd(vol, spec, err, errlen);
    }
    int gzip = n >= 2 && head[0] == 0x1f && head[1] == 0x8b;
    int nifti = vfpi_has_suffix(spec, ".nii") || vfpi_has_suffix(spec, ".nii.gz");
    if (gzip && !nifti) {
        unsigned char inner[VFPI_HEAD_BYTES];
        size_t m;
        if (vfpi_read_head(spec, 1, inner, sizeof inner, &m, err, errlen))
            return VFP_ERR;
        nifti = vfpi_is_nifti(inner, m);
    } else if (!gzip) {
        nifti = nifti || vfpi_is_nifti(head, n);
    }
    if (nifti) {
        snprintf(vol->format, sizeof vol->format, "nifti");
        return vfpi_load_nifti(vol, spec, gzip, err, errlen);
    }
    if (vfpi_has_suffix(spec, ".den") || vfpi_is_den(head, n, (uint64_t)st.st_size)) {
        snprintf(vol->format, sizeof vol->format, "den");
        return vfpi_load_den(vol, spec, err, errlen);
    }
    snprintf(vol->format, sizeof vol->format, "raw");
    return vfpi_load_raw(vol, spec, opts, err, errlen);
}

/* What every reader's volume needs after reading: the spacing override, Q16.16 spacing, raw range, voxels. */
static vfp_status_t finish(vfp_volume_t *vol, const vfp_load_opts_t *opts, char *err, size_t errlen)
{
    if (opts && opts->have_spacing) {
        char name[sizeof vol->name + 16];
        snprintf(name, sizeof name, "%s: --spacing", vol->name);
        for (int a = 0; a < 3; a++) {
            if (vfpi_check_spacing(opts->spacing[a], a, name, 0, err, errlen))
                return VFP_ERR;
            vol->spacing[a] = opts->spacing[a] * (opts->downsample > 1 ? opts->downsample : 1);
        }
    }
    /* The core needs only the ratios: relative to the smallest spacing, Q16.16 keeps full precision whatever
     * the unit (a file in metres has spacings near 0.0005). */
    double smallest = vol->spacing[0], largest = vol->spacing[0];
    for (int a = 1; a < 3; a++) {
        smallest = vol->spacing[a] < smallest ? vol->spacing[a] : smallest;
        largest = vol->spacing[a] > largest ? vol->spacing[a] : largest;
    }
    if (largest > smallest * VF_MAX_ANISOTROPY)
        return vfpi_fail(err, errlen, vol->name, 0,
                         "spacings %g, %g, %g differ by more than %dx (expected at most %d times the smallest)",
                         vol->spacing[0], vol->spacing[1], vol->spacing[2], VF_MAX_ANISOTROPY, VF_MAX_ANISOTROPY);
    for (int a = 0; a < 3; a++)
        vol->core.spacing_q16[a] = (uint32_t)lround(vol->spacing[a] / smallest * 65536.0);
    vol->core.voxels = vol->data;
    raw_range(vol);
    return VFP_OK;
}

static int32_t raw_at(const vfp_volume_t *vol, size_t i)
{
    switch (vol->core.type) {
    case VF_VOXEL_U8:
        return ((const uint8_t *)vol->data)[i];
    case VF_VOXEL_I8:
        return ((const int8_t *)vol->data)[i];
    case VF_VOXEL_U16:
        return ((const uint16_t *)vol->data)[i];
    default:
        return ((const int16_t *)vol->data)[i];
    }
}

static void raw_range(vfp_volume_t *vol)
{
    size_t count = (size_t)vol->core.dims[0] * vol->core.dims[1] * vol->core.dims[2];
    int32_t lo = INT32_MAX, hi = INT32_MIN;
    for (size_t i = 0; i < count; i++) {
        int32_t v = raw_at(vol, i);
        lo = v < lo ? v : lo;
        hi = v > hi ? v : hi;
    }
    vol->raw_min = lo;
    vol->raw_max = hi;
}

/* 16-bit data's default window, by a histogram of all 65536 raw values (docs/defaults.md has the measurements):
 * lo is the 0.5 percentile; hi is the 99.99 percentile, but at most twice as far from lo as the 99.5 percentile.
 * The 99.5 percentile alone clipped sparse bright structures (a stent, a wire, contrast: well under 0.5% of the
 * voxels) to the top of the window together with the brightest soft tissue, so they could not be told apart;
 * the 99.99 percentile keeps anything above a hundredth of a percent of the voxels, and the cap keeps the bulk
 * of the data (up to the 99.5 percentile) spread over at least half the window. Widened so that lo < hi. */
static vf_window_t percentile_window(const vfp_volume_t *vol)
{
    vf_window_t w = {vol->raw_min, vol->raw_max};
    int32_t base = vol->core.type == VF_VOXEL_I16 ? -32768 : 0;
    uint64_t *hist = calloc(65536, sizeof *hist);
    uint64_t count = (uint64_t)vol->core.dims[0] * vol->core.dims[1] * vol->core.dims[2];
    if (hist) {
        for (size_t i = 0; i < count; i++)
            hist[raw_at(vol, i) - base]++;
        /* Ranks into the sorted values: lo rounds down and the upper ones round up, so the window never shrinks
         * to less than the data between the percentiles. */
        const uint64_t rank[3] = {(count - 1) * WINDOW_LO_PERMYRIAD / 10000,
                                  ((count - 1) * WINDOW_BULK_PERMYRIAD + 9999) / 10000,
                                  ((count - 1) * WINDOW_TAIL_PERMYRIAD + 9999) / 10000};
        int32_t at[3] = {w.lo, w.hi, w.hi};
        uint64_t seen = 0;
        int found = 0;
        for (int32_t v = 0; v < 65536 && found < 3; v++) {
            seen += hist[v];
            while (found < 3 && seen > rank[found])
                at[found++] = v + base;
        }
        free(hist);
        int64_t cap = (int64_t)at[0] + 2 * ((int64_t)at[1] - at[0]);
        w.lo = at[0];
        w.hi = at[2] < cap ? at[2] : (int32_t)cap;
        if (w.hi < at[1])
            w.hi = at[1];
    }
    /* Mostly constant data (a small object in empty space) puts both percentiles on one value: widen to the
     * whole range, and to one raw step for constant data. */
    if (w.lo >= w.hi) {
        w.lo = vol->raw_min;
        w.hi = vol->raw_max;
    }
    if (w.lo >= w.hi) {
        int32_t top = vol->core.type == VF_VOXEL_I16 ? 32767 : 65535;
        if (w.lo < top)
            w.hi = w.lo + 1;
        else
            w.lo = w.hi - 1;
    }
    return w;
}

/* "--dims '1,2'" for messages, with long or missing text cut short. */
static const char *option_name(char *buf, size_t size, const char *option, const char *text)
{
    if (!text)
        snprintf(buf, size, "%s (missing)", option);
    else if (strlen(text) > SHOWN_TEXT)
        snprintf(buf, size, "%s '%.*s...'", option, SHOWN_TEXT, text);
    else
        snprintf(buf, size, "%s '%s'", option, text);
    return buf;
}

/* strtod with surrounding spaces; returns 0 if there is no number at *p. */
static int parse_number(const char **p, double *value)
{
    char *end;
    while (**p == ' ')
        (*p)++;
    *value = strtod(*p, &end);
    if (end == *p)
        return 0;
    *p = end;
    while (**p == ' ')
        (*p)++;
    return 1;
}
