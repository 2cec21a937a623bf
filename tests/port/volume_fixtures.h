/* SPDX-License-Identifier: MIT */
/*
 * volume_fixtures.h: small volume files written at test time into the tests' temporary directory (fixtures.h),
 * and the checks the volume tests share. Header-only so that each test program stays one file; every function is
 * static inline so a test that does not use one gets no warning.
 */
#ifndef VOLUME_FIXTURES_H
#define VOLUME_FIXTURES_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include "check.h"
#include "fixtures.h"
#include "io/volume.h"

/* The fixture volume: 3 x 4 x 5 voxels, distinct values in every byte, so a swapped or shifted byte shows. */
#define FX_X 3
#define FX_Y 4
#define FX_Z 5
#define FX_COUNT (FX_X * FX_Y * FX_Z)

/* gzip (not zlib) bytes of data, as gzip(1) and NRRD writers make them; caller frees. */
static inline unsigned char *fx_gzip_bytes(const void *data, size_t n, size_t *out_n)
{
    z_stream z;
    memset(&z, 0, sizeof z);
    if (deflateInit2(&z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
        exit(1);
    size_t cap = deflateBound(&z, (uLong)n) + 64;
    unsigned char *out = malloc(cap);
    z.next_in = (unsigned char *)data;
    z.avail_in = (uInt)n;
    z.next_out = out;
    z.avail_out = (uInt)cap;
    if (deflate(&z, Z_FINISH) != Z_STREAM_END)
        exit(1);
    *out_n = cap - z.avail_out;
    deflateEnd(&z);
    return out;
}

/* A .gz file written through zlib's own gzopen/gzwrite. */
static inline const char *fx_write_gz(const char *name, const void *data, size_t n)
{
    const char *p = fx_path(name);
    gzFile g = gzopen(p, "wb");
    if (!g || (n && gzwrite(g, data, (unsigned)n) != (int)n) || gzclose(g) != Z_OK) {
        fprintf(stderr, "gzwrite %s failed\n", p);
        exit(1);
    }
    return p;
}

/* The fixture's value i for each type. */
static inline int32_t fx_value(vf_voxel_t type, int i)
{
    switch (type) {
    case VF_VOXEL_U8: return 3 + 4 * i;           /* 3..239 */
    case VF_VOXEL_I8: return -120 + 4 * i;        /* -120..116 */
    case VF_VOXEL_U16: return 17 + 1031 * i;      /* 17..60846, both bytes vary */
    default: return -30000 + 1013 * i;            /* -30000..29767 */
    }
}

/* The fixture's bytes as a file stores them. */
static inline size_t fx_bytes(vf_voxel_t type, int big_endian, unsigned char *out)
{
    size_t k = 0;
    for (int i = 0; i < FX_COUNT; i++) {
        uint32_t v = (uint32_t)fx_value(type, i);
        if (type == VF_VOXEL_U8 || type == VF_VOXEL_I8) {
            out[k++] = (unsigned char)v;
        } else if (big_endian) {
            out[k++] = (unsigned char)(v >> 8);
            out[k++] = (unsigned char)v;
        } else {
            out[k++] = (unsigned char)v;
            out[k++] = (unsigned char)(v >> 8);
        }
    }
    return k;
}

static inline int32_t fx_voxel(const vfp_volume_t *vol, size_t i)
{
    switch (vol->core.type) {
    case VF_VOXEL_U8: return ((const uint8_t *)vol->core.voxels)[i];
    case VF_VOXEL_I8: return ((const int8_t *)vol->core.voxels)[i];
    case VF_VOXEL_U16: return ((const uint16_t *)vol->core.voxels)[i];
    default: return ((const int16_t *)vol->core.voxels)[i];
    }
}

/* A loaded fixture: dims, type, every voxel, raw range, the core view. Frees the volume. */
static inline void fx_check_fixture(vfp_volume_t *vol, vf_voxel_t type)
{
    CHECK(vol->data != NULL);
    CHECK(vol->core.voxels == vol->data);
    CHECK_EQ(vol->core.dims[0], FX_X);
    CHECK_EQ(vol->core.dims[1], FX_Y);
    CHECK_EQ(vol->core.dims[2], FX_Z);
    CHECK_EQ(vol->core.type, type);
    for (int i = 0; i < FX_COUNT; i++)
        CHECK_MSG(fx_voxel(vol, (size_t)i) == fx_value(type, i), "voxel %d is %d, expected %d", i,
                  fx_voxel(vol, (size_t)i), fx_value(type, i));
    CHECK_EQ(vol->raw_min, fx_value(type, 0));
    CHECK_EQ(vol->raw_max, fx_value(type, FX_COUNT - 1));
    vfp_volume_free(vol);
    CHECK(vol->data == NULL);
}

static inline int fx_load(vfp_volume_t *vol, const char *spec, const vfp_load_opts_t *opts)
{
    char err[VFP_ERR_LEN];
    int rc = vfp_volume_load(vol, spec, opts, err, sizeof err);
    if (rc)
        fprintf(stderr, "# unexpected failure: %s\n", err);
    return rc;
}

/* A load that must fail: status 2, one line naming `name` and containing `phrase`, the volume zeroed. Set
 * VOLFIX_SHOW_ERRORS=1 to see the messages. */
static inline void fx_expect_error(const char *spec, const vfp_load_opts_t *opts, const char *name,
                                   const char *phrase)
{
    vfp_volume_t vol;
    char err[VFP_ERR_LEN];
    memset(&vol, 0x5a, sizeof vol);
    vfp_status_t rc = vfp_volume_load(&vol, spec, opts, err, sizeof err);
    if (getenv("VOLFIX_SHOW_ERRORS"))
        printf("# %s\n", err);
    CHECK_MSG(rc == VFP_ERR, "load of %s returned %d, expected VFP_ERR", spec, rc);
    CHECK_MSG(strstr(err, name) != NULL, "error '%s' does not name '%s'", err, name);
    CHECK_MSG(strstr(err, phrase) != NULL, "error '%s' lacks '%s'", err, phrase);
    CHECK_MSG(strchr(err, '\n') == NULL, "error '%s' is more than one line", err);
    CHECK(vol.data == NULL && vol.core.voxels == NULL && vol.core.dims[0] == 0 && vol.name[0] == 0);
}

/* Same for the parsers, which name the option instead of a file. */
static inline void fx_expect_text(vfp_status_t rc, const char *err, const char *phrase1, const char *phrase2)
{
    if (getenv("VOLFIX_SHOW_ERRORS"))
        printf("# %s\n", err);
    CHECK_EQ(rc, VFP_ERR);
    CHECK_MSG(strstr(err, phrase1) != NULL, "error '%s' lacks '%s'", err, phrase1);
    CHECK_MSG(strstr(err, phrase2) != NULL, "error '%s' lacks '%s'", err, phrase2);
}

/* The message for a claimed 4096^3 int16 volume (128 GiB) over a few bytes: "truncated", except where size_t cannot
 * count the bytes (32-bit machines, make test-cross), which refuse the size before they look for the data. */
#define FX_HUGE(truncated) \
    (SIZE_MAX < UINT64_C(137438953472) ? ": volume of 137438953472 bytes is too large for this machine" : (truncated))

#endif /* VOLUME_FIXTURES_H */
